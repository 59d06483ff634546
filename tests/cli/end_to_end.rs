//! The command line end to end: a real run writes what the README promises, a step
//! above the stable bound warns, and a blow-up stops the run naming cable, node and
//! time while keeping the output written so far.

use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

#[test]
fn catenary_run_writes_summary_and_time_series() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(BIN)
        .args([
            "run",
            "examples/catenary.toml",
            "--duration",
            "5",
            "-q",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    for key in [
        "backend",
        "precision",
        "scheme",
        "steps",
        "dt",
        "simulated_time",
        "wall_seconds",
        "node_steps_per_second",
    ] {
        assert!(s.get(key).is_some(), "summary.json lacks {key}");
    }
    assert_eq!(s["simulated_time"].as_f64().unwrap(), 5.0);
    assert!(s["node_steps_per_second"].as_f64().unwrap() > 0.0);
    let c = &s["cables"][0];
    assert_eq!(c["name"], "line1");
    // The summary holds a handful of numbers per cable; the nodes' final state is in
    // final_state.csv.
    assert!(c.get("final_positions").is_none());
    let max = c["max_tension"].as_array().unwrap();
    let min = &c["min_tension"];
    assert!(max[0].as_f64().unwrap() >= min.as_f64().unwrap());
    assert!(max[2].as_u64().unwrap() < 50);
    let fin = super::common::final_state(dir.path());
    assert_eq!(fin.len(), 1);
    assert_eq!(fin[0].0, "line1");
    assert_eq!(fin[0].1.len(), 51);
    // The fairlead force points down and towards the anchor (at -x).
    let end = c["end_forces"]["end"].as_array().unwrap();
    assert!(
        end[0].as_f64().unwrap() < -1000.0 && end[2].as_f64().unwrap() < -1000.0,
        "{end:?}"
    );
    // end_forces.csv: header, one row per cable end per output time, exact times.
    let csv = std::fs::read_to_string(dir.path().join("end_forces.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "time,cable,end,fx,fy,fz");
    assert_eq!(lines.len(), 1 + 2 * 6);
    let times: Vec<&str> = lines[1..]
        .iter()
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(
        times,
        ["0", "0", "1", "1", "2", "2", "3", "3", "4", "4", "5", "5"]
    );
    // The relaxed line holds still: the fairlead force at 5 s equals the one at 0 s.
    let f = |l: &str| {
        l.split(',')
            .skip(3)
            .map(|x| x.parse::<f64>().unwrap())
            .collect::<Vec<_>>()
    };
    let (f0, f5) = (f(lines[2]), f(lines[12]));
    for k in 0..3 {
        assert!((f0[k] - f5[k]).abs() < 1e-6 * 7000.0, "{f0:?} vs {f5:?}");
    }
    assert!(dir.path().join("tensions.csv").exists() && dir.path().join("positions.csv").exists());
}

#[test]
fn step_above_the_bound_warns_and_blow_up_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(BIN)
        .args([
            "run",
            "examples/catenary.toml",
            "--dt",
            "0.01",
            "--duration",
            "20",
            "-q",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("above the stable step") && err.contains("set by axial waves"),
        "{err}"
    );
    assert!(
        err.contains("diverged at t =") && err.contains("cable 'line1', node"),
        "{err}"
    );
    // What was written before the blow-up is kept, and the summary says what happened.
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(s["status"], "diverged");
    assert!(s["error"].as_str().unwrap().contains("line1"));
    let csv = std::fs::read_to_string(dir.path().join("end_forces.csv")).unwrap();
    assert!(csv.lines().count() >= 3, "the t = 0 rows at least");
}

/// Runs each `(scenario, duration, threads)` with the environment variable `var` at 4
/// and at 8 lanes and asserts that the output files `files` are the same bytes.
fn lanes_give_the_same_bytes(var: &str, runs: &[(&str, &str, &str)], files: &[&str]) {
    if !cablesim::lanes::avx512_present() {
        eprintln!("no AVX-512 here: both runs take 4 lanes");
    }
    for &(scenario, duration, threads) in runs {
        let run = |lanes: &str| {
            let dir = tempfile::tempdir().unwrap();
            let out = Command::new(BIN)
                .args(["run", scenario, "--backend", "cpu", "--duration", duration])
                .args(["-q", "--out"])
                .arg(dir.path())
                .env(var, lanes)
                .env("RAYON_NUM_THREADS", threads)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{scenario}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            files
                .iter()
                .map(|f| std::fs::read(dir.path().join(f)).unwrap())
                .collect::<Vec<_>>()
        };
        let (four, eight) = (run("4"), run("8"));
        for (k, f) in files.iter().enumerate() {
            assert!(!four[k].is_empty(), "{scenario}: {f} is empty");
            assert!(
                four[k] == eight[k],
                "{scenario}, {threads} threads: {f} differs between 4 and 8 lanes ({var})"
            );
        }
    }
}

/// The chain fast path runs whole chunks of 8 lanes where the CPU has AVX-512 and of 4
/// with `CABLESIM_CHAIN_LANES=4` (AVX2); every lane does a scalar loop's arithmetic, so
/// the output files are the same bytes: a winch cable with an end mass towed along a
/// route (Case 2), a line on the seabed (the catenary), and lines with seabed friction
/// in waves.
#[test]
fn chain_lanes_4_and_8_give_the_same_bytes() {
    lanes_give_the_same_bytes(
        "CABLESIM_CHAIN_LANES",
        &[
            ("examples/case2_straight.toml", "20", "2"),
            ("examples/catenary.toml", "5", "2"),
            ("examples/spread_mooring_waves.toml", "2", "2"),
        ],
        &["positions.csv", "tensions.csv", "end_forces.csv"],
    );
}

/// The network path with 8 lanes (AVX-512, `CABLESIM_NET_LANES=8`) and with 4 (AVX2, the
/// default) writes the same output bytes: a net cage in still water on one thread and
/// on two (its loops in whole chunks of lanes, the last chunk of a piece overlapping),
/// and a net cage in waves (surface-piercing twines: the loop over elements).
#[test]
fn net_lanes_4_and_8_give_the_same_bytes() {
    lanes_give_the_same_bytes(
        "CABLESIM_NET_LANES",
        &[
            ("examples/net_cage.toml", "0.5", "1"),
            ("examples/net_cage.toml", "0.5", "2"),
            ("examples/net_cage_waves.toml", "0.5", "1"),
        ],
        &["tensions.csv", "end_forces.csv"],
    );
}
