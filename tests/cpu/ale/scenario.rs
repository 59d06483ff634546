//! Winch cables as a scenario describes them (moved from `ale.rs`): bad `winch` keys and
//! schedule files named in the error, impossible schedules refused before the run, and the
//! example `examples/winch_deploy.toml` run through the binary.

use super::*;

pub(super) const EXAMPLE: &str = include_str!("../../../examples/winch_deploy.toml");
pub(super) const WINCH_LINE: &str = r#"winch = { end = "start", schedule = "rates", rates = [[0.0, 0.0], [10.0, 0.5], [110.0, 0.5], [120.0, 0.0]], drum_length = 300.0 }"#;

/// The example with its winch line replaced, parsed as `dir/case.toml`.
fn with_winch(dir: &Path, winch: &str) -> Result<Scenario, Error> {
    assert!(EXAMPLE.contains(WINCH_LINE));
    let text = EXAMPLE.replace(WINCH_LINE, winch);
    let path = dir.join("case.toml");
    std::fs::write(&path, &text).unwrap();
    Scenario::load(&path)
}

/// Asserts a scenario error whose field contains `field` and message contains `msg`.
fn scenario_fails(r: Result<Scenario, Error>, field: &str, msg: &str) {
    match r {
        Err(Error::Scenario {
            field: f, message, ..
        }) => {
            assert!(
                f.contains(field),
                "field `{f}` should name `{field}` ({message})"
            );
            assert!(
                message.contains(msg),
                "message `{message}` should say `{msg}`"
            );
        }
        Ok(_) => panic!("expected an error naming {field}"),
        Err(e) => panic!("wrong error kind: {e}"),
    }
}

/// Bad winch keys and payout files give errors naming the file, the field and the
/// problem (and the file's line).
#[test]
fn bad_winch_keys_and_schedule_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let f = "cables[0] (\"tether\").winch";
    let sc = with_winch(d, WINCH_LINE).unwrap();
    assert_eq!(sc.winches.len(), 1);
    assert_eq!(sc.winches[0].element_length, 5.0);
    for (winch, field, msg) in [
        (
            r#"winch = { schedule = "spline" }"#,
            "winch.schedule",
            "unknown schedule \"spline\"",
        ),
        (r#"winch = { rate = 1.0 }"#, "winch.schedule", "missing"),
        (
            r#"winch = { schedule = "constant" }"#,
            "winch.rate",
            "missing",
        ),
        (
            r#"winch = { schedule = "constant", rate = "fast" }"#,
            "winch.rate",
            "must be a number",
        ),
        (
            r#"winch = { schedule = "constant", rate = nan }"#,
            "winch.rate",
            "finite",
        ),
        (
            r#"winch = { schedule = "constant", rate = 1.0, speed = 2 }"#,
            "winch.speed",
            "unknown key",
        ),
        (
            r#"winch = { end = "end", schedule = "constant", rate = 1.0 }"#,
            "winch.end",
            "free",
        ),
        (
            r#"winch = { end = "top", schedule = "constant", rate = 1.0 }"#,
            "winch.end",
            "\"start\" or \"end\"",
        ),
        (
            r#"winch = { schedule = "constant", rate = 1.0, drum_length = 10.0 }"#,
            "winch.drum_length",
            "less than the 20 m deployed",
        ),
        (
            r#"winch = { schedule = "constant", rate = 1.0, drum_length = -1.0 }"#,
            "winch.drum_length",
            "must be positive",
        ),
        (
            r#"winch = { schedule = "rates", rates = [] }"#,
            "winch.rates",
            "at least one row",
        ),
        (
            r#"winch = { schedule = "rates", rates = [[0, 0], [10, 1], [5, 1]] }"#,
            "winch.rates",
            "row 2: time 5 s comes before",
        ),
        (
            r#"winch = { schedule = "rates", rates = [[0, 0, 1]] }"#,
            "winch.rates[0]",
            "[t, rate]",
        ),
        (r#"winch = { schedule = "table" }"#, "winch.file", "missing"),
    ] {
        scenario_fails(with_winch(d, winch), &format!("{f}{}", &field[5..]), msg);
    }
    // Payout tables.
    let table = r#"winch = { schedule = "table", file = "payout.csv", drum_length = 300.0 }"#;
    std::fs::write(d.join("payout.csv"), "t,length\n0,20\n60,50\n100,50\n").unwrap();
    let sc = with_winch(d, table).unwrap();
    let p = sc.winches[0].schedule.eval(30.0);
    assert_eq!((p.dl, p.rate), (15.0, 0.5));
    for (rows, msg) in [
        ("t,x\n0,20\n", "the header must be `t,length`, found `t,x`"),
        ("t,length\n", "no rows after the header"),
        (
            "t,length\n0,20\n10,abc\n",
            "line 3, column length: `abc` is not a finite number",
        ),
        (
            "t,length\n0,20\n10,30\n10,40\n",
            "line 4: time 10 s does not increase",
        ),
        (
            "t,length\n0,20\n10,-3\n",
            "line 3: deployed length -3 m is negative",
        ),
        (
            "t,length\n0,20,1\n",
            "line 2: expected 2 values t,length, found 3",
        ),
        (
            "t,length\n0,25\n10,30\n",
            "deployed length at t = 0 is 25 m, but the cable's `length`",
        ),
    ] {
        std::fs::write(d.join("payout.csv"), rows).unwrap();
        scenario_fails(with_winch(d, table), &format!("{f}.file"), msg);
    }
    std::fs::remove_file(d.join("payout.csv")).unwrap();
    scenario_fails(
        with_winch(d, table),
        &format!("{f}.file"),
        "cannot read payout file",
    );
    // A winch needs the cable's own held end, not a shared point.
    let text = EXAMPLE
        .replace(
            "start = { fixed = [0.0, 0.0, -5.0] }",
            "start = { point = \"ship\" }",
        )
        .replace(
            "[[cables]]",
            "[[points]]\nname = \"ship\"\nfixed = [0.0, 0.0, -5.0]\n\n[[cables]]",
        );
    scenario_fails(
        Scenario::parse(&text, Path::new("/tmp/case.toml")),
        &format!("{f}.end"),
        "shared [[points]] node",
    );
}

/// A schedule that hauls in past the last node, or pays out past the drum, is refused
/// before anything runs (the plan follows the schedule over the step times), by the
/// library and by `cablesim check`, naming the cable and the time.
#[test]
fn impossible_schedules_are_refused_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (winch, time, msg) in [
        // 20 m hauled in at 1 m/s: the last element may not go below 2.5 m: t = 17.5 s.
        (
            r#"winch = { schedule = "constant", rate = -1.0 }"#,
            17.5,
            "past the cable's last node",
        ),
        // 20 m on a 50 m drum paid out at 0.5 m/s: empty at t = 60 s.
        (
            r#"winch = { schedule = "constant", rate = 0.5, drum_length = 50.0 }"#,
            60.0,
            "drum_length = 50",
        ),
    ] {
        let sc = with_winch(d, winch).unwrap();
        let (lay, _) = Layout::build(&sc.model).unwrap();
        let r = cablesim::sim::plan_steps(&sc, &lay, &SolverOptions::default(), 150.0, sc.sim.dt);
        match r {
            Err(Error::Winch {
                cable,
                time: t,
                message,
            }) => {
                assert_eq!(cable, "tether");
                assert!((t - time).abs() < 1e-3, "{t} vs {time}");
                assert!(message.contains(msg), "{message}");
            }
            other => panic!("expected a winch error, got {other:?}"),
        }
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_cablesim"))
            .arg("check")
            .arg(d.join("case.toml"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success());
        assert!(
            err.contains("winch of cable 'tether' at t = ") && err.contains(msg),
            "{err}"
        );
    }
}

/// The example runs through `cablesim run`: the CSV files have one row per existing
/// element and node at each output time, winches.csv follows the deployed length, and
/// summary.json reports the winch.
#[test]
fn winch_example_runs_and_outputs_follow_the_node_count() {
    let dir = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cablesim"))
        .args([
            "run",
            "examples/winch_deploy.toml",
            "--duration",
            "30",
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
    let read = |f: &str| std::fs::read_to_string(dir.path().join(f)).unwrap();
    let s: serde_json::Value = serde_json::from_str(&read("summary.json")).unwrap();
    let c = &s["cables"][0];
    let wz = &c["winch"];
    // 2.5 m during the ramp, then 0.5 m/s for 20 s: 32.5 m deployed, 6 elements.
    assert!(
        (wz["deployed_length"].as_f64().unwrap() - 32.5).abs() < 1e-9,
        "{wz}"
    );
    assert_eq!(wz["elements"], 6);
    assert_eq!(wz["nodes_inserted"], 2);
    assert_eq!(super::super::common::final_state(dir.path())[0].1.len(), 7);
    let p = wz["physical_coordinates"].as_array().unwrap();
    assert_eq!(p.len(), 7);
    assert!((p[0].as_f64().unwrap() - 32.5).abs() < 1e-9 && p[6].as_f64().unwrap() == 0.0);
    let count = |f: &str, t: &str| {
        read(f)
            .lines()
            .filter(|l| l.starts_with(&format!("{t},")))
            .count()
    };
    assert_eq!(
        (count("tensions.csv", "0"), count("positions.csv", "0")),
        (4, 5)
    );
    assert_eq!(
        (count("tensions.csv", "30"), count("positions.csv", "30")),
        (6, 7)
    );
    let w = read("winches.csv");
    assert_eq!(
        w.lines().next().unwrap(),
        "time,cable,deployed_length,variable_l0,elements"
    );
    assert_eq!(w.lines().count(), 1 + 31);
    assert!(
        w.lines().last().unwrap().starts_with("30,tether,32.5"),
        "{w}"
    );
}
