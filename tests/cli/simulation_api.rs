//! The library API (`cablesim::Simulation`) and the command line's options: a run into
//! memory sees what the files hold, a run advanced in pieces ends where one run ends,
//! an end driven from outside follows as a scenario route does, overrides apply,
//! option values are enums listed in `--help`, and a good run prints no error lines.

use cablesim::options::{Backend, Overrides, Scheme};
use cablesim::sim::{self, CableEnd, RunOptions};
use cablesim::{Error, MemorySink, Simulation};
use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

fn cpu(duration: f64) -> Overrides {
    Overrides {
        backend: Some(Backend::Cpu),
        duration: Some(duration),
        ..Overrides::default()
    }
}

/// The rows of a CSV file below its header, split at commas.
fn rows(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// A winch paying out (remeshing as it goes): the memory sink's snapshots hold exactly
/// the numbers the file sink writes, at the same times, and the same summary.
#[test]
fn memory_and_files_hold_the_same_run() {
    let scenario = "examples/winch_deploy.toml";
    let dir = tempfile::tempdir().unwrap();
    let sc = cablesim::scenario::Scenario::load(scenario).unwrap();
    let from_files = sim::run(
        &sc,
        &RunOptions {
            out_dir: dir.path().to_path_buf(),
            overrides: cpu(12.5),
            progress: false,
        },
    )
    .unwrap();
    let mut mem = MemorySink::new();
    let mut calls = 0;
    let summary = Simulation::from_file(scenario, &cpu(12.5))
        .unwrap()
        .run(&mut mem, |_| calls += 1)
        .unwrap();
    assert!(calls >= 13, "progress reported {calls} times");
    assert_eq!(mem.summary.as_ref().unwrap().steps, summary.steps);
    assert_eq!(summary.steps, from_files.steps);
    assert_eq!(summary.cables, from_files.cables);
    // Whole output intervals exactly, then the end of the partial last one (`steps dt`).
    let times: Vec<f64> = mem.frames.iter().map(|f| f.time).collect();
    let want: Vec<f64> = (0..=12).map(|k| k as f64).collect();
    assert_eq!(times[..13], want);
    assert_eq!(times.len(), 14);
    assert!((times[13] - 12.5).abs() < 1e-9, "{times:?}");

    let tensions = rows(&dir.path().join("tensions.csv"));
    let ends = rows(&dir.path().join("end_forces.csv"));
    let winches = rows(&dir.path().join("winches.csv"));
    let positions = rows(&dir.path().join("positions.csv"));
    let (mut kt, mut ke, mut kp) = (0, 0, 0);
    for (k, f) in mem.frames.iter().enumerate() {
        let c = &f.cables[0];
        assert_eq!(c.name, "tether");
        for (e, t) in c.tensions.iter().enumerate() {
            let r = &tensions[kt];
            assert_eq!(r[0].parse::<f64>().unwrap(), f.time);
            assert_eq!(r[2], e.to_string());
            assert_eq!(r[3].parse::<f64>().unwrap(), *t);
            kt += 1;
        }
        for (which, v) in [("start", c.end_forces.start), ("end", c.end_forces.end)] {
            let r = &ends[ke];
            assert_eq!(r[2], which);
            let got: Vec<f64> = r[3..6].iter().map(|x| x.parse().unwrap()).collect();
            assert_eq!(got, v);
            ke += 1;
        }
        for p in &c.positions {
            let got: Vec<f64> = positions[kp][3..6]
                .iter()
                .map(|x| x.parse().unwrap())
                .collect();
            assert_eq!(got, p);
            kp += 1;
        }
        let w = c.winch.as_ref().unwrap();
        assert_eq!(winches[k][2].parse::<f64>().unwrap(), w.deployed_length);
        assert_eq!(winches[k][4], w.elements.to_string());
        assert_eq!(c.positions.len(), w.elements + 1);
        assert_eq!(c.velocities.len(), c.positions.len());
    }
    assert_eq!((kt, ke, kp), (tensions.len(), ends.len(), positions.len()));
    // Paying out 0.5 m/s from t = 10 s: it grew, and remeshed to keep up.
    let last = mem.frames.last().unwrap().cables[0].winch.clone().unwrap();
    assert!(last.deployed_length > 20.5, "{last:?}");
}

/// Advancing by uneven numbers of steps, then to a time, ends bitwise where one run to
/// that time ends; the getters agree with the snapshot.
#[test]
fn advancing_in_pieces_ends_where_one_run_ends() {
    let text = std::fs::read_to_string("examples/winch_deploy.toml").unwrap();
    let path = Path::new("examples/winch_deploy.toml");
    let mut whole = MemorySink::new();
    Simulation::from_toml(&text, path, &cpu(11.0))
        .unwrap()
        .run(&mut whole, |_| {})
        .unwrap();
    let mut pieces = Simulation::from_toml(&text, path, &cpu(11.0)).unwrap();
    let dt = pieces.dt();
    let (mut n, six) = (1, (6.0 / dt).round() as u64);
    while pieces.steps() < six {
        pieces.advance(n.min(six - pieces.steps())).unwrap();
        n = n * 3 + 1;
    }
    assert_eq!(pieces.time(), 6.0);
    pieces.advance_to(11.0).unwrap();
    assert_eq!(pieces.steps(), (11.0 / dt).round() as u64);
    let a = pieces.snapshot().unwrap();
    let b = whole.frames.last().unwrap();
    assert_eq!(a.time, 11.0);
    assert_eq!(a.steps, pieces.steps());
    assert_eq!(&a, b);
    // A time already passed does nothing.
    pieces.advance_to(3.0).unwrap();
    assert_eq!(pieces.snapshot().unwrap(), a);
}

/// Overrides reach the run, and the summary names what ran.
#[test]
fn overrides_choose_scheme_and_step() {
    let text = std::fs::read_to_string("examples/catenary.toml").unwrap();
    let ov = Overrides {
        scheme: Some(Scheme::Rk4),
        dt: Some(1e-4),
        ..cpu(0.5)
    };
    let mut sim = Simulation::from_toml(&text, "catenary.toml", &ov).unwrap();
    assert_eq!(sim.dt(), 1e-4);
    let s = sim.run(&mut MemorySink::new(), |_| {}).unwrap();
    assert_eq!((s.scheme.as_str(), s.backend.as_str()), ("rk4", "cpu"));
    assert_eq!(s.steps, 5000);
    assert_eq!(s.scenario, "catenary.toml");
}

/// An unknown option value in a scenario is an error naming the field and the values
/// allowed; on the command line too, and `--help` lists them.
#[test]
fn option_values_are_checked_and_listed() {
    let text = std::fs::read_to_string("examples/catenary.toml")
        .unwrap()
        .replace("[simulation]", "[simulation]\nscheme = \"rk3\"");
    match Simulation::from_toml(&text, "x.toml", &Overrides::default()) {
        Err(Error::Scenario { field, message, .. }) => {
            assert_eq!(field, "simulation.scheme");
            assert!(
                message.contains("rk4") && message.contains("symplectic"),
                "{message}"
            );
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("rk3 accepted"),
    }
    let help = Command::new(BIN).args(["run", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&help.stdout);
    for v in ["auto", "gpu", "f64", "rk2", "rk4", "frenet", "ancf"] {
        assert!(help.contains(v), "--help does not list {v}: {help}");
    }
    let bad = Command::new(BIN)
        .args(["run", "examples/catenary.toml", "--scheme", "rk3"])
        .output()
        .unwrap();
    assert!(!bad.status.success());
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("rk3") && err.contains("rk4"), "{err}");
}

/// A good run with the default backend prints no error line (adapters are probed
/// quietly, also without a desktop session), and says in one line what it chose.
#[test]
fn a_good_run_prints_no_error_lines() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(BIN)
        .args(["run", "examples/catenary.toml", "--duration", "1", "--out"])
        .arg(dir.path())
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("RUST_LOG")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let errors: Vec<&str> = err
        .lines()
        .filter(|l| l.to_lowercase().contains("error"))
        .collect();
    assert!(errors.is_empty(), "{err}");
    assert_eq!(
        err.lines().filter(|l| l.contains("backend auto:")).count(),
        1,
        "{err}"
    );
}

/// A coupling loop (set the fairlead's target, step, read the force back) moving the
/// fairlead of the catenary at 0.5 m/s along x gives the end forces of the same motion
/// written as a line route in the scenario; the fixed fairlead's differ.
#[test]
fn an_end_driven_from_outside_follows_like_a_route() {
    let fixed = std::fs::read_to_string("examples/catenary.toml").unwrap();
    let v = [0.5, 0.0, 0.0];
    let routed = fixed.replace(
        "end = { fixed = [0.0, 0.0, -10.0] }",
        "end = { route = \"line\", start = [0.0, 0.0, -10.0], velocity = [0.5, 0.0, 0.0] }",
    );
    assert_ne!(routed, fixed);
    let mut route = Simulation::from_toml(&routed, "routed.toml", &cpu(3.0)).unwrap();
    let mut coupled = Simulation::from_toml(&fixed, "coupled.toml", &cpu(3.0)).unwrap();
    let mut still = Simulation::from_toml(&fixed, "still.toml", &cpu(3.0)).unwrap();
    assert_eq!(coupled.dt(), route.dt());
    let mut forces = Vec::new();
    for k in 1..=30 {
        let t = coupled.time();
        let p = [v[0] * t, 0.0, -10.0];
        coupled.set_end_motion(0, CableEnd::End, p, v).unwrap();
        let to = k as f64 * 0.1;
        coupled.advance_to(to).unwrap();
        route.advance_to(to).unwrap();
        let (a, b) = (coupled.snapshot().unwrap(), route.snapshot().unwrap());
        let (fa, fb) = (a.cables[0].end_forces.end, b.cables[0].end_forces.end);
        let scale = fb.iter().map(|x| x * x).sum::<f64>().sqrt();
        let diff = (0..3).map(|i| (fa[i] - fb[i]).powi(2)).sum::<f64>().sqrt();
        assert!(
            diff <= 1e-6 * scale,
            "t = {to}: {fa:?} vs the route's {fb:?}"
        );
        let (pa, pb) = (
            a.cables[0].positions.last().unwrap(),
            b.cables[0].positions.last().unwrap(),
        );
        assert!(
            (0..3).all(|i| (pa[i] - pb[i]).abs() < 1e-9),
            "t = {to}: {pa:?} vs {pb:?}"
        );
        forces.push(fb);
    }
    let end = *coupled.snapshot().unwrap().cables[0]
        .positions
        .last()
        .unwrap();
    assert!(
        (end[0] - 1.5).abs() < 1e-3 && (end[2] + 10.0).abs() < 1e-3,
        "{end:?}"
    );
    still.advance_to(3.0).unwrap();
    let f = still.snapshot().unwrap().cables[0].end_forces.end;
    let last = forces.last().unwrap();
    assert!(
        (f[0] - last[0]).abs() > 0.01 * f[0].abs(),
        "{f:?} vs {last:?}"
    );
    // Only a held end can be driven.
    assert!(coupled
        .set_end_motion(0, CableEnd::End, [0.0; 3], v)
        .is_ok());
    assert!(matches!(
        coupled.set_end_motion(3, CableEnd::Start, [0.0; 3], v),
        Err(Error::Model(_))
    ));
}
