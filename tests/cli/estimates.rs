//! Estimates before work and the default budget: `check` prints the node-steps and the
//! estimated wall time and what sets the step; a run beyond the default budget (1e12
//! node-steps) is refused by `check` and `run` with the estimate, the cause and the key
//! or `--limit` to go on. The two runs of issue 35: a 1 micrometre cable stretched over
//! 238 m, and a 20 m wire with an internal damping of 1e6 s.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

fn catenary() -> String {
    std::fs::read_to_string("examples/catenary.toml").unwrap()
}

/// `text` with `from` (which must be there) replaced by `to`.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

/// Runs `cablesim ARGS FILE` on `text` written to `d/case.toml`: (success, stdout,
/// stderr).
fn cli(d: &Path, text: &str, args: &[&str]) -> (bool, String, String) {
    let f = d.join("case.toml");
    std::fs::write(&f, text).unwrap();
    let out = Command::new(BIN)
        .args(args)
        .arg(&f)
        .env_remove("RUST_LOG")
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The 1 micrometre cable of the issue: the catenary example's line with `length =
/// 1e-6` between its anchor and fairlead, 238 m apart, for 1 s.
fn micrometre() -> String {
    let c = edit(&catenary(), "length = 250.0", "length = 1e-6");
    edit(&c, "duration = 60.0", "duration = 1.0")
}

/// The damped wire of the issue: 20 m in 4 elements, internal damping 1e6 s, 1 s.
fn damped() -> String {
    let c = edit(&catenary(), "damping = 1.0e-5 ", "damping = 1.0e6 ");
    let c = edit(&c, "length = 250.0", "length = 20.0");
    let c = edit(&c, "segments = 50", "segments = 4");
    let c = edit(
        &c,
        "start = { fixed = [-220.0, 0.0, -100.0] }",
        "start = { fixed = [0.0, 0.0, -50.0] }",
    );
    let c = edit(
        &c,
        "end = { fixed = [0.0, 0.0, -10.0] }",
        "end = { fixed = [0.0, 0.0, -30.5] }",
    );
    let c = edit(&c, "initial = \"catenary\"", "initial = \"straight\"");
    edit(&c, "duration = 60.0", "duration = 1.0")
}

#[test]
fn check_prints_the_work_and_its_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let (ok, out, err) = cli(dir.path(), &catenary(), &["check"]);
    assert!(ok, "{err}");
    // The plan as before, then the work: node-steps, a time, the path and its rate.
    assert!(out.contains("set by axial waves"), "{out}");
    let work = out
        .lines()
        .find(|l| l.contains("work: "))
        .unwrap_or_else(|| panic!("no work line: {out}"));
    assert!(
        work.contains("node-steps, about ")
            && work.contains("on the CPU path (chain path")
            && work.contains("node-steps/s")
            && work.contains("budget 1e12 node-steps"),
        "{work}"
    );
    // 60 s of 51 nodes at about 1e-3 s: 3.1e6 node-steps, well under a second.
    let n: f64 = work
        .split("work: ")
        .nth(1)
        .and_then(|w| w.split(' ').next())
        .and_then(|x| x.parse().ok())
        .unwrap();
    assert!((2.5e6..4e6).contains(&n), "{work}");
    assert!(work.contains(" s on the CPU path"), "{work}");
}

/// Both runs of the issue: refused by `check` and `run` (exit status non-zero), with
/// the node-steps, an estimated time, what sets the step with its key, and `--limit`.
#[test]
fn the_issues_runs_are_refused_with_why_how_long_and_what_to_change() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("out");
    let out = out.to_str().unwrap();
    for (case, text, cause) in [
        // Its 2e-8 m elements: the line type's internal damping (1e-5 s) sets a step
        // of 1.6e-18 s (the axial waves alone, 4.5e-12 s).
        (
            "micrometre",
            micrometre(),
            &[
                "internal damping of line type 'wire'",
                "an element of 2.000e-8 m",
                "cable 'line1' fewer `segments`",
            ][..],
        ),
        (
            "damped",
            damped(),
            &[
                "internal damping of line type 'wire'",
                "`damping` = 1.000e6 s",
                "lower that `damping`",
            ][..],
        ),
    ] {
        for args in [
            &["check"][..],
            &["run", "--backend", "cpu", "--out", out][..],
        ] {
            let (ok, _, err) = cli(d, &text, args);
            assert!(!ok, "{case} {args:?} accepted: {err}");
            assert!(
                err.contains("node-steps, about ")
                    && err.contains("on the CPU path")
                    && err.contains("over the budget of 1e12 node-steps"),
                "{case} {args:?}: {err}"
            );
            for c in cause {
                assert!(err.contains(c), "{case} {args:?}: no \"{c}\": {err}");
            }
            assert!(
                err.contains("--limit node_steps=") && err.contains("[limits] node_steps"),
                "{case} {args:?}: {err}"
            );
        }
    }
    // Their sizes: 4e19 node-steps (thousands of years), and 6.25e12 as the issue counts.
    let (_, _, err) = cli(d, &micrometre(), &["check"]);
    assert!(
        err.contains("is 3.98") && err.contains("e19 node-steps") && err.contains(" years "),
        "{err}"
    );
    let (_, _, err) = cli(d, &damped(), &["check"]);
    assert!(
        err.contains("is 6.2") && err.contains("e12 node-steps"),
        "{err}"
    );
    // `--limit` goes on: check accepts the damped wire and prints its estimate.
    let (ok, out, err) = cli(d, &damped(), &["check", "--limit", "node_steps=1e13"]);
    assert!(ok, "{err}");
    assert!(
        out.contains("set by internal damping") && out.contains("budget 1e13"),
        "{out}"
    );
}

#[test]
fn the_default_budget_is_1e12_node_steps() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // The catenary example simulates about 5.2e4 node-steps a second (51 nodes at
    // about 9.9e-4 s): 1.5e7 s is 7.8e11 node-steps, 2.5e7 s 1.3e12.
    let c = edit(
        &catenary(),
        "output_interval = 1.0 ",
        "output_interval = 1000.0 ",
    );
    let (ok, out, err) = cli(
        d,
        &edit(&c, "duration = 60.0", "duration = 1.5e7"),
        &["check"],
    );
    assert!(ok, "{err}");
    assert!(out.contains("e11 node-steps"), "{out}");
    let (ok, _, err) = cli(
        d,
        &edit(&c, "duration = 60.0", "duration = 2.5e7"),
        &["check"],
    );
    assert!(
        !ok && err.contains("over the budget of 1e12 node-steps"),
        "{err}"
    );
    // What sets this step is the wire's axial wave: the message says so, and how long.
    assert!(
        err.contains("set by axial waves") && err.contains(" h on the CPU path"),
        "{err}"
    );
}
