//! Measured and tabulated seas from the command line: a scenario whose waves are a
//! component table runs, and a bad table or record is refused before anything is
//! written, the message naming the file, its line and its column.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

const SCENARIO: &str = r#"
[simulation]
duration = 20.0
output_interval = 0.5

[environment]
depth = 40.0

[[environment.waves.trains]]
type = "TYPE"
file = "FILE"

[[line_types]]
name = "rope"
diameter = 0.05
mass_per_length = 3.0
ea = 5.0e6
cn = 1.2
ct = 0.01
cm = 1.0

[[cables]]
name = "riser"
line_type = "rope"
length = 62.0
segments = 20
start = { fixed = [-50.0, 0.0, -40.0] }
end = { fixed = [0.0, 0.0, -3.0] }
"#;

/// Writes the scenario (a `kind` train reading `file`, holding `body`) in `dir` and
/// runs `cablesim run` on it with the output in `dir/out`: success, stderr.
fn run(dir: &Path, kind: &str, file: &str, body: &str) -> (bool, String) {
    std::fs::write(dir.join(file), body).unwrap();
    let text = SCENARIO.replace("TYPE", kind).replace("FILE", file);
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    let r = Command::new(BIN)
        .args(["run", "-q"])
        .arg(&path)
        .arg("--out")
        .arg(dir.join("out"))
        .output()
        .unwrap();
    (
        r.status.success(),
        String::from_utf8_lossy(&r.stderr).into_owned(),
    )
}

#[test]
fn a_component_table_runs_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let table = "omega,amplitude,phase,direction\n0.6,0.5,0,0\n0.8,0.3,45,20\n1.1,0.1,90,-20\n";
    let (ok, err) = run(dir.path(), "components", "waves.csv", table);
    assert!(ok, "{err}");
    let summary = std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap();
    assert!(summary.contains("\"riser\""), "{summary}");
}

#[test]
fn bad_wave_files_are_refused_and_nothing_is_written() {
    let good_record: String = (0..40).fold("t,eta\n".into(), |s, i| {
        s + &format!("{},{}\n", 0.25 * i as f64, (0.7 * 0.25 * i as f64).sin())
    });
    let uneven = good_record.replacen("\n2.5,", "\n2.6,", 1);
    for (kind, file, body, says) in [
        (
            "components",
            "waves.csv",
            "frequency,amplitude,phase\n0.1,1,0\n0,1,0\n",
            "waves.csv line 3, column frequency: frequency must be positive, got 0",
        ),
        (
            "components",
            "waves.csv",
            "frequency,amplitude,phase\n0.1,-1,0\n",
            "waves.csv line 2, column amplitude: amplitude must not be negative",
        ),
        (
            "components",
            "waves.csv",
            "omega,amplitude,phase\n0.5,inf,0\n",
            "waves.csv line 2, column amplitude: `inf` is not a finite number",
        ),
        (
            "record",
            "basin.csv",
            "t,eta\n0,0\n1,1\n2,0\n",
            "basin.csv: 3 samples; an elevation record needs at least 8",
        ),
        (
            "record",
            "basin.csv",
            uneven.as_str(),
            "basin.csv line 12, column t: the record is not evenly sampled",
        ),
        (
            "record",
            "basin.csv",
            "t,eta\n0,0\n1,1\n2,NaN\n3,0\n4,1\n5,0\n6,1\n7,0\n",
            "basin.csv line 4, column eta: `NaN` is not a finite number",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let (ok, err) = run(dir.path(), kind, file, body);
        assert!(!ok, "accepted: {says}");
        assert!(
            err.contains("case.toml")
                && err.contains("environment.waves.trains[0].file")
                && err.contains(says),
            "expected \"{says}\" in: {err}"
        );
        assert!(!dir.path().join("out").exists(), "{says}: output written");
    }
}
