//! Runs that end early keep honest output: Ctrl-C and SIGTERM stop a run cleanly, a
//! blow-up leaves every cable's state at the failure, output directories belong to one
//! run.

use std::path::Path;
use std::process::{Child, Command};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

/// `examples/catenary.toml` made long (`duration` s) with a dense output interval.
fn long_catenary(dir: &Path, duration: f64) -> std::path::PathBuf {
    let text = std::fs::read_to_string("examples/catenary.toml").unwrap();
    let text = text
        .replace("duration = 60.0 ", &format!("duration = {duration:e} "))
        .replace("output_interval = 1.0 ", "output_interval = 0.05 ");
    assert!(
        text.contains("output_interval = 0.05"),
        "the example changed"
    );
    let path = dir.join("long.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// Waits for `child` at most `limit`; kills it and fails if it runs on.
fn wait_at_most(child: &mut Child, limit: Duration) -> std::process::ExitStatus {
    let t0 = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        if t0.elapsed() > limit {
            child.kill().ok();
            panic!("the run did not stop within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Every line of a CSV file has the header's number of fields and the file ends with
/// a newline (no row cut in half).
fn assert_whole_rows(path: &Path) -> Vec<csv::StringRecord> {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.ends_with('\n'), "{} ends mid-row", path.display());
    let mut r = csv::ReaderBuilder::new()
        .flexible(true)
        .from_path(path)
        .unwrap();
    let width = r.headers().unwrap().len();
    let rows: Vec<_> = r.records().map(|x| x.unwrap()).collect();
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(
            row.len(),
            width,
            "{} row {}: {:?}",
            path.display(),
            i + 2,
            row
        );
    }
    rows
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn sigint_and_sigterm_stop_a_run_with_whole_rows_and_a_summary() {
    for signal in ["-INT", "-TERM"] {
        let dir = tempfile::tempdir().unwrap();
        let duration = 1e5; // s: hours of stepping; only a signal ends it
        let scenario = long_catenary(dir.path(), duration);
        let out = dir.path().join("out");
        let mut child = Command::new(BIN)
            .args(["run", "-q", "--out"])
            .arg(&out)
            .arg(&scenario)
            .spawn()
            .unwrap();
        // Signal once the run has written past the first buffer of rows.
        let t0 = Instant::now();
        let forces = out.join("end_forces.csv");
        while std::fs::metadata(&forces).map_or(0, |m| m.len()) < 20_000 {
            assert!(t0.elapsed() < Duration::from_secs(120), "no output written");
            assert!(
                child.try_wait().unwrap().is_none(),
                "the run ended by itself"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        let killed = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .unwrap();
        assert!(killed.success());
        let status = wait_at_most(&mut child, Duration::from_secs(30));
        assert_eq!(status.code(), Some(130), "{signal}: {status:?}");

        let s = summary(&out);
        assert_eq!(s["status"], "interrupted", "{signal}");
        let t = s["simulated_time"].as_f64().unwrap();
        let dt = s["dt"].as_f64().unwrap();
        let steps = s["steps"].as_u64().unwrap();
        assert!(t > 0.0 && t < duration, "{signal}: t = {t}");
        assert!(
            (t - steps as f64 * dt).abs() < 1e-6 * t,
            "{signal}: {t} vs {steps} steps"
        );
        // The final state is that of the time reached: finite, not the start's.
        let fin = super::common::final_state(&out);
        assert!(fin[0]
            .1
            .iter()
            .all(|(x, v)| x.iter().chain(v).all(|c| c.is_finite())));
        let ef = &s["cables"][0]["end_forces"]["end"];
        assert!(ef
            .as_array()
            .unwrap()
            .iter()
            .all(|x| x.as_f64().unwrap().is_finite()));

        for name in ["end_forces.csv", "tensions.csv", "positions.csv"] {
            let path = out.join(name);
            if !path.exists() {
                continue;
            }
            let rows = assert_whole_rows(&path);
            // The last frame is at the time reached.
            let last: f64 = rows.last().unwrap()[0].parse().unwrap();
            assert!(
                (last - t).abs() <= 1e-9 * t,
                "{name}: last row at {last}, summary {t}"
            );
        }
        // Two rows per cable and time: the last time's rows are all there.
        let rows = assert_whole_rows(&forces);
        let last = &rows[rows.len() - 1][0];
        assert_eq!(rows.iter().filter(|r| &r[0] == last).count(), 2);
    }
}

#[test]
fn a_stop_request_ends_a_library_run_with_its_last_frame() {
    use cablesim::{MemorySink, Overrides, Simulation};
    let mut sim = Simulation::from_file("examples/catenary.toml", &Overrides::default()).unwrap();
    let total = sim.plan().unwrap().total_steps;
    let mut sink = MemorySink::new();
    let mut asked = 0;
    let s = sim
        .run_until(
            &mut sink,
            |_| {},
            || {
                asked += 1;
                asked > 3
            },
        )
        .unwrap();
    assert_eq!(s.status, "interrupted");
    assert!(s.steps > 0 && s.steps < total, "{} of {total}", s.steps);
    let last = sink.frames.last().unwrap();
    assert_eq!((last.steps, last.time), (s.steps, s.simulated_time));
    assert_eq!(sink.summary.unwrap().status, "interrupted");
    // Not stopped: the same run completes.
    let mut sim = Simulation::from_file("examples/catenary.toml", &Overrides::default()).unwrap();
    let s = sim
        .run_until(&mut MemorySink::new(), |_| {}, || false)
        .unwrap();
    assert_eq!((s.status.as_str(), s.steps), ("completed", total));
}

/// `examples/catenary.toml` at a step that blows up its seabed contact, with a second,
/// mid-water cable that the step keeps stable and that sags from its straight start.
fn catenary_and_midwater(dir: &Path) -> std::path::PathBuf {
    let mut text = std::fs::read_to_string("examples/catenary.toml").unwrap();
    text = text.replace("dt = \"auto\" ", "dt = 0.01 ");
    assert!(text.contains("dt = 0.01"), "the example changed");
    text.push_str(
        r#"
[[line_types]]
name = "soft"
diameter = 0.02
mass_per_length = 2.0
ea = 1.0e5
damping = 0.0
cn = 1.0
ct = 0.01
cm = 0.2

[[cables]]
name = "midwater"
line_type = "soft"
length = 100.0
segments = 10
start = { fixed = [0.0, 50.0, -30.0] }
end = { fixed = [99.0, 50.0, -30.0] }
initial = "straight"
output_positions = true
"#,
    );
    let path = dir.join("two.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_blow_up_leaves_every_cable_at_the_failure_and_says_the_step_was_too_big() {
    blow_up_case("cpu");
}

/// The same on the GPU path (lavapipe here): it reads a checkpoint back once per output
/// interval and replays from it to the step before the failure.
#[test]
fn a_blow_up_on_the_gpu_leaves_every_cable_at_the_failure() {
    blow_up_case("gpu");
}

fn blow_up_case(backend: &str) {
    let dir = tempfile::tempdir().unwrap();
    let scenario = catenary_and_midwater(dir.path());
    let check = Command::new(BIN)
        .arg("check")
        .arg(&scenario)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&check.stdout);
    assert!(said.contains("dt is above the stable step"), "{said}");

    let out = dir.path().join("out");
    let run = Command::new(BIN)
        .args([
            "run",
            "-q",
            "--duration",
            "20",
            "--backend",
            backend,
            "--out",
        ])
        .arg(&out)
        .arg(&scenario)
        .output()
        .unwrap();
    assert!(!run.status.success());
    let s = summary(&out);
    assert_eq!(s["status"], "diverged");
    assert_eq!(s["backend"], backend);
    assert_eq!(s["dt_above_stable"], true);
    let (t, dt, steps) = (
        s["simulated_time"].as_f64().unwrap(),
        s["dt"].as_f64().unwrap(),
        s["steps"].as_u64().unwrap(),
    );
    // The time and steps are the failure's: the step before the time in the error.
    let err = s["error"].as_str().unwrap();
    let t_fail: f64 = err
        .split("diverged at t = ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no failure time in {err}"));
    assert!(
        t < 20.0 && (t - steps as f64 * dt).abs() < 1e-9,
        "t = {t}, {steps} steps"
    );
    assert!(
        (t_fail - t - dt).abs() < 1e-6,
        "failure at {t_fail}, state at {t}"
    );
    // Every cable's final state is that of the failure: finite, and the mid-water
    // cable has moved from its straight start.
    let fin = super::common::final_state(&out);
    for (_, nodes) in &fin {
        for (x, _) in nodes {
            assert!(x.iter().all(|v| v.is_finite()));
        }
    }
    assert_eq!(fin[1].0, "midwater");
    let mid = fin[1].1[5].0;
    let sag = -30.0 - mid[2];
    // It has sagged since t = 0, no faster than a free fall over the time reached.
    assert!(
        sag > 1e-6 && sag < 0.5 * 9.81 * t * t,
        "the mid-water cable's middle at t = {t}: {mid:?}"
    );
    // A frame was written at the failure, and matches the summary.
    let rows = assert_whole_rows(&out.join("positions.csv"));
    let last: Vec<_> = rows
        .iter()
        .filter(|r| &r[1] == "midwater" && &r[2] == "5")
        .collect();
    let last = last.last().unwrap();
    let tl: f64 = last[0].parse().unwrap();
    assert!((tl - t).abs() < 1e-9, "last frame at {tl}, summary at {t}");
    assert_eq!(last[5].parse::<f64>().unwrap(), mid[2]);
}

/// A winch cable (its mesh changes as it pays out) that blows up: the summary's time
/// and steps are the step before the failure, and the last frame and `winches.csv`
/// stand there too (the CPU path checkpoints the whole solver, mesh and payout).
#[test]
fn a_blow_up_of_a_winch_cable_leaves_it_at_the_failure() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/winch_deploy.toml"),
    )
    .unwrap()
    .replace(
        "output_interval = 1.0",
        "output_interval = 10.0\nmax_speed = 0.3",
    );
    let scenario = dir.path().join("winch_blow.toml");
    std::fs::write(&scenario, text).unwrap();
    let out = dir.path().join("out");
    let run = Command::new(BIN)
        .args(["run", "-q", "--backend", "cpu", "--out"])
        .arg(&out)
        .arg(&scenario)
        .output()
        .unwrap();
    assert!(!run.status.success());
    let s = summary(&out);
    assert_eq!(s["status"], "diverged");
    let (t, dt, steps) = (
        s["simulated_time"].as_f64().unwrap(),
        s["dt"].as_f64().unwrap(),
        s["steps"].as_u64().unwrap(),
    );
    let err = s["error"].as_str().unwrap();
    let t_fail: f64 = err
        .split("diverged at t = ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no failure time in {err}"));
    // The failure falls inside the first output interval (10 s), so a summary at the
    // interval's end would be caught here.
    assert!(t_fail < 10.0, "{err}");
    assert!(
        (t - steps as f64 * dt).abs() < 1e-9,
        "t = {t}, {steps} steps"
    );
    assert!(
        (t_fail - t - dt).abs() < 1e-6,
        "failure at {t_fail}, state at {t}"
    );
    for file in ["positions.csv", "winches.csv"] {
        let rows = assert_whole_rows(&out.join(file));
        let tl: f64 = rows.last().unwrap()[0].parse().unwrap();
        assert!(
            (tl - t).abs() < 1e-9,
            "{file}: last frame at {tl}, summary at {t}"
        );
    }
}

#[test]
fn an_output_directory_belongs_to_one_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    // An earlier run's files, a stale `completed` summary among them, are cleared even
    // when the new run fails before its first step (the ANCF model has no GPU path);
    // that run writes its own `failed` summary.
    std::fs::create_dir(&out).unwrap();
    for f in ["winches.csv", "summary.json", "end_forces.csv"] {
        std::fs::write(out.join(f), "stale").unwrap();
    }
    let r = Command::new(BIN)
        .args([
            "run",
            "-q",
            "examples/catenary.toml",
            "--formulation",
            "ancf",
        ])
        .args(["--backend", "gpu", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(!r.status.success());
    for f in ["winches.csv", "end_forces.csv"] {
        assert!(!out.join(f).exists(), "{f} of the earlier run is left");
    }
    // The summary is the failed start's, not the stale one.
    assert_eq!(summary(&out)["status"], "failed");
    assert!(out.join(cablesim::output::MARKER_FILE).exists());

    // A folder holding anything else is refused, and nothing in it is touched.
    let foreign = dir.path().join("foreign");
    std::fs::create_dir(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    std::fs::write(foreign.join("tensions.csv"), "stale").unwrap();
    let r = Command::new(BIN)
        .args(["run", "-q", "examples/catenary.toml", "--out"])
        .arg(&foreign)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(!r.status.success() && err.contains("notes.txt"), "{err}");
    assert_eq!(
        std::fs::read_to_string(foreign.join("tensions.csv")).unwrap(),
        "stale"
    );
    assert_eq!(
        std::fs::read_to_string(foreign.join("notes.txt")).unwrap(),
        "mine"
    );

    // `--out` naming a file: one clear error.
    let file = dir.path().join("a_file");
    std::fs::write(&file, "x").unwrap();
    let r = Command::new(BIN)
        .args(["run", "-q", "examples/catenary.toml", "--out"])
        .arg(&file)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(!r.status.success(), "{err}");
    assert_eq!(err.matches("not a directory").count(), 1, "{err}");

    // While a run holds the folder, a second one is refused with a clear error.
    let held = cablesim::output::FileSink::claim(&out).unwrap();
    let r = Command::new(BIN)
        .args([
            "run",
            "-q",
            "examples/catenary.toml",
            "--duration",
            "1",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(
        !r.status.success() && err.contains("another cablesim run"),
        "{err}"
    );
    assert!(!out.join("summary.json").exists());
    drop(held);
    let r = Command::new(BIN)
        .args([
            "run",
            "-q",
            "examples/catenary.toml",
            "--duration",
            "1",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
}

#[test]
fn cable_names_with_commas_quotes_and_newlines_are_quoted() {
    use cablesim::output::{CableState, EndForces, FileSink, OutputSink, PointState, Snapshot};
    let dir = tempfile::tempdir().unwrap();
    let names = ["plain", "a,b", "say \"hi\"", "two\nlines"];
    let mut snap = Snapshot {
        time: 0.5,
        steps: 2,
        points: names
            .iter()
            .map(|n| PointState {
                name: n.to_string(),
                position: [1.0, 2.0, 3.0],
                force: [0.0, 0.0, -9.0],
            })
            .collect(),
        cables: names
            .iter()
            .map(|n| CableState {
                name: n.to_string(),
                output_positions: true,
                positions: vec![[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]],
                velocities: vec![[0.0; 3]; 2],
                tensions: vec![7.0],
                end_forces: EndForces {
                    start: [1.0, 2.0, 3.0],
                    end: [4.0, 5.0, 6.0],
                },
                winch: None,
            })
            .collect(),
        bodies: Vec::new(),
        nets: Vec::new(),
    };
    // Two output times: the second writes the names the sink quoted at the first.
    let mut sink = FileSink::new(dir.path());
    sink.frame(&snap).unwrap();
    snap.time = 1.0;
    sink.frame(&snap).unwrap();
    let mut sim =
        cablesim::Simulation::from_file("examples/catenary.toml", &cablesim::Overrides::default())
            .unwrap();
    sink.finish(&sim.summary(None).unwrap()).unwrap();
    for (file, per_cable) in [
        ("end_forces.csv", 2),
        ("tensions.csv", 1),
        ("positions.csv", 2),
        ("points.csv", 1),
    ] {
        let rows = assert_whole_rows(&dir.path().join(file));
        let got: Vec<&str> = rows.iter().map(|r| &r[1]).collect();
        let want: Vec<&str> = [names, names]
            .iter()
            .flatten()
            .flat_map(|n| std::iter::repeat_n(*n, per_cable))
            .collect();
        assert_eq!(got, want, "{file}");
    }
}

#[test]
fn a_zero_stable_step_or_absurd_work_is_refused_by_check_and_run() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string("examples/catenary.toml").unwrap();
    let cases = [
        // Internal damping so strong the stable step is 1e-12 s (it was computed as
        // zero before, and the run looped for ever).
        (
            "damping = 1.0e-5 ",
            "damping = 1.0e6 ",
            "simulation.duration",
            "internal damping",
        ),
        // Far more node-steps than any machine runs.
        (
            "duration = 60.0 ",
            "duration = 1e20 ",
            "simulation.duration",
            "node-steps",
        ),
    ];
    for (from, to, field, what) in cases {
        assert!(text.contains(from), "the example changed");
        let path = dir.path().join("absurd.toml");
        std::fs::write(&path, text.replace(from, to)).unwrap();
        for cmd in ["check", "run"] {
            let mut c = Command::new(BIN);
            c.arg(cmd).arg(&path);
            if cmd == "run" {
                c.args(["-q", "--out"]).arg(dir.path().join("out"));
            }
            let r = c.output().unwrap();
            let err = String::from_utf8_lossy(&r.stderr);
            assert!(!r.status.success(), "{cmd} {to}: {err}");
            assert!(
                err.contains(field) && err.contains(what),
                "{cmd} {to}: {err}"
            );
            if cmd == "run" && field == "simulation.duration" {
                // Refused after the output directory was claimed (the plan needs the
                // initial state): a failed start still writes its summary.
                let s = summary(&dir.path().join("out"));
                assert_eq!(s["status"], "failed");
                assert_eq!(s["steps"], 0);
                assert_eq!(s["simulated_time"], 0.0);
                let e = s["error"].as_str().unwrap();
                assert!(e.contains(field) && e.contains(what), "{e}");
            }
        }
    }
}
