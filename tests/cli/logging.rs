//! What the command line prints, and how a person controls it: `-q` warnings and
//! errors only, `-v` more detail, RUST_LOG when neither is given, no progress bar when
//! standard error is not a terminal.

use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

/// `cablesim run examples/catenary.toml --backend cpu --duration 2` with `args` and
/// the environment variable `env` (name, value), standard error captured (a pipe).
fn run(args: &[&str], env: Option<(&str, &str)>) -> (Output, String) {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Command::new(BIN);
    c.args([
        "run",
        "examples/catenary.toml",
        "--backend",
        "cpu",
        "--duration",
        "2",
    ])
    .args(args)
    .arg("--out")
    .arg(dir.path())
    .env_remove("RUST_LOG");
    if let Some((k, v)) = env {
        c.env(k, v);
    }
    let out = c.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{err}");
    (out, err)
}

#[test]
fn quiet_prints_warnings_and_errors_only() {
    // By default: the information lines (mesh and step, the estimate, the backend) and
    // the closing line.
    let (_, err) = run(&[], None);
    assert!(err.contains("INFO") && err.contains("work: "), "{err}");
    assert!(
        err.contains("backend cpu") && err.contains("done: "),
        "{err}"
    );
    // -q, before or after the subcommand: nothing of that.
    for q in [&["-q"][..], &["--quiet"][..]] {
        let (_, err) = run(q, None);
        assert!(err.trim().is_empty(), "{q:?}: {err}");
    }
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(BIN)
        .args([
            "-q",
            "run",
            "examples/catenary.toml",
            "--backend",
            "cpu",
            "--duration",
            "1",
        ])
        .arg("--out")
        .arg(dir.path())
        .env_remove("RUST_LOG")
        .output()
        .unwrap();
    assert!(out.status.success() && out.stderr.is_empty(), "{out:?}");
    // A warning still shows with -q (f32 asked of the CPU path, which is f64).
    let (_, err) = run(&["-q", "--precision", "f32"], None);
    assert!(
        err.contains("WARN") && err.contains("always f64") && !err.contains("INFO"),
        "{err}"
    );
    // And RUST_LOG does not bring the information lines back under -q.
    let (_, err) = run(&["-q"], Some(("RUST_LOG", "info,cablesim=debug")));
    assert!(err.trim().is_empty(), "{err}");
}

#[test]
fn verbose_adds_detail_and_rust_log_still_works() {
    let (_, plain) = run(&[], None);
    assert!(!plain.contains("DEBUG"), "{plain}");
    // -v: cablesim's debug lines (the step plan in detail, the static relaxation).
    let (_, v) = run(&["-v"], None);
    assert!(v.contains("DEBUG") && v.contains("INFO"), "{v}");
    assert!(v.lines().count() > plain.lines().count(), "{v}");
    // -q and -v together are refused.
    let out = Command::new(BIN)
        .args(["run", "examples/catenary.toml", "-q", "-v"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    // Without flags RUST_LOG sets the levels: warnings only, or debug.
    let (_, w) = run(&[], Some(("RUST_LOG", "warn")));
    assert!(!w.contains("INFO") && w.contains("done: "), "{w}");
    let (_, d) = run(&[], Some(("RUST_LOG", "cablesim=debug")));
    assert!(d.contains("DEBUG"), "{d}");
}

#[test]
fn no_progress_bar_when_stderr_is_not_a_terminal() {
    // Standard error is a pipe here: no bar, none of its redraws, even without -q.
    let (_, err) = run(&[], None);
    assert!(
        !err.contains('\r') && !err.contains("eta") && !err.contains("[="),
        "{err}"
    );
    // The same for a study.
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    let text = std::fs::read_to_string("examples/study_spread_mooring.toml")
        .unwrap()
        .replace("duration = 40.0          # s per member", "duration = 3.0")
        .replace("transient = 10.0", "transient = 1.0")
        .replace("ramp = 8.0 ", "ramp = 1.0 ");
    std::fs::write(&study, text).unwrap();
    let out = Command::new(BIN)
        .args(["study", "run"])
        .arg(&study)
        .arg("--out")
        .arg(dir.path().join("o"))
        .env_remove("RUST_LOG")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("work: ") && err.contains("done: "), "{err}");
    assert!(!err.contains('\r') && !err.contains("eta"), "{err}");
    // -q: nothing at all on success.
    let out = Command::new(BIN)
        .args(["study", "run", "-q"])
        .arg(&study)
        .arg("--out")
        .arg(dir.path().join("q"))
        .env_remove("RUST_LOG")
        .output()
        .unwrap();
    assert!(out.status.success() && out.stderr.is_empty(), "{out:?}");
}
