//! `src/scenario/wave_inputs.rs`: `"components"` and `"record"` wave trains read into the
//! sea state, and every bad input refused with the scenario, the key, and for a file
//! its line and column.

use cablesim::error::Error;
use cablesim::scenario::{collect_warnings, Scenario};
use cablesim::sea::dispersion::wave_number;
use cablesim::sea::kinematics::WaveField;
use std::f64::consts::TAU;
use std::path::PathBuf;

const BASE: &str = r#"
[simulation]
duration = 10.0
output_interval = 1.0

[environment]
depth = 120.0

[[line_types]]
name = "chain"
diameter = 0.1
mass_per_length = 100.0
ea = 1e9

[[cables]]
name = "a"
line_type = "chain"
length = 150.0
segments = 10
start = { fixed = [0.0, 0.0, -120.0] }
end = { fixed = [140.0, 0.0, 0.0] }
"#;

/// A folder with `files` written in it and the scenario `case.toml` (BASE plus `waves`).
struct Case {
    _dir: tempfile::TempDir,
    path: PathBuf,
}

fn case(waves: &str, files: &[(&str, &str)]) -> Case {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let path = dir.path().join("case.toml");
    std::fs::write(&path, format!("{BASE}\n{waves}")).unwrap();
    Case { _dir: dir, path }
}

fn load(c: &Case) -> Result<Scenario, Error> {
    Scenario::load(&c.path)
}

/// Loading fails with an error on `case.toml` whose field contains `field` and whose
/// message contains each of `says`.
fn refused(waves: &str, files: &[(&str, &str)], field: &str, says: &[&str]) {
    let c = case(waves, files);
    match load(&c) {
        Ok(_) => panic!("accepted; expected {field}: {says:?}"),
        Err(Error::Scenario {
            path,
            field: f,
            message,
        }) => {
            assert_eq!(path, c.path);
            assert!(
                f.contains(field),
                "field `{f}` should name `{field}` ({message})"
            );
            for s in says {
                assert!(message.contains(s), "`{message}` should say `{s}`");
            }
        }
        Err(e) => panic!("wrong error kind: {e}"),
    }
}

const TABLE_TRAIN: &str = r#"
[[environment.waves.trains]]
type = "components"
file = "waves.csv"
"#;

const RECORD_TRAIN: &str = r#"
[[environment.waves.trains]]
type = "record"
file = "basin.csv"
"#;

#[test]
fn a_component_table_becomes_the_seas_components_in_hz_or_rad_per_s() {
    let hz = "frequency,amplitude,phase,direction\n0.1,1.5,30,0\n0.125,0.5,-90,45\n0.2,0,0,0\n";
    let c = case(TABLE_TRAIN, &[("waves.csv", hz)]);
    let sea = load(&c).unwrap().sea;
    assert_eq!(sea.components.len(), 3);
    let want = [
        (0.1, 1.5, 30.0, 0.0),
        (0.125, 0.5, -90.0, 45.0),
        (0.2, 0.0, 0.0, 0.0),
    ];
    for (comp, (f, a, ph, dir)) in sea.components.iter().zip(want) {
        assert!((comp.omega - TAU * f).abs() < 1e-15);
        assert_eq!(comp.amplitude, a);
        assert!((comp.phase - f64::to_radians(ph)).abs() < 1e-15);
        assert!((comp.direction - f64::to_radians(dir)).abs() < 1e-15);
        assert_eq!(comp.k, wave_number(comp.omega, 120.0, 9.81));
    }
    // The same table in rad/s, without the direction column (the train's key instead),
    // and as `rows` in the scenario: the same components.
    let rad = format!(
        "omega,amplitude,phase\n{},1.5,30\n{},0.5,-90\n{},0,0\n",
        TAU * 0.1,
        TAU * 0.125,
        TAU * 0.2
    );
    let c = case(
        &format!("{TABLE_TRAIN}direction = 45.0\n"),
        &[("waves.csv", rad.as_str())],
    );
    let s2 = load(&c).unwrap().sea;
    for (a, b) in s2.components.iter().zip(&sea.components) {
        assert_eq!(a.omega, b.omega);
        assert_eq!(a.amplitude, b.amplitude);
        assert_eq!(a.phase, b.phase);
        assert!((a.direction - f64::to_radians(45.0)).abs() < 1e-15);
    }
    let rows = format!(
        "[[environment.waves.trains]]\ntype = \"components\"\nrows = [[{}, 1.5, 30.0, 0.0], [{}, 0.5, -90.0, 45.0], [{}, 0.0, 0.0, 0.0]]\n",
        TAU * 0.1,
        TAU * 0.125,
        TAU * 0.2
    );
    let s3 = load(&case(&rows, &[])).unwrap().sea;
    assert_eq!(s3.components, sea.components);
    // A table train adds to a spectrum's.
    let both = format!(
        "{TABLE_TRAIN}\n[[environment.waves.trains]]\ntype = \"regular\"\nheight = 1.0\nperiod = 9.0\n"
    );
    let s4 = load(&case(&both, &[("waves.csv", hz)])).unwrap().sea;
    assert_eq!(s4.components.len(), 4);
    assert_eq!(s4.components[..3], sea.components[..]);
}

#[test]
fn bad_component_tables_are_refused_naming_the_file_line_and_column() {
    let head = "frequency,amplitude,phase,direction\n0.1,1.0,0,0\n";
    let file = "trains[0].file";
    for (row, col, says) in [
        ("0,1.0,0,0", "column frequency", "must be positive, got 0"),
        (
            "-0.2,1.0,0,0",
            "column frequency",
            "must be positive, got -0.2",
        ),
        (
            "0.2,-1.0,0,0",
            "column amplitude",
            "must not be negative, got -1",
        ),
        ("0.2,nan,0,0", "column amplitude", "is not a finite number"),
        ("0.2,1.0,inf,0", "column phase", "is not a finite number"),
        ("0.2,1.0,0,x", "column direction", "is not a finite number"),
        ("0.2,1.0,0", "line 3", "expected 4 values"),
    ] {
        let text = format!("{head}{row}\n");
        refused(
            TABLE_TRAIN,
            &[("waves.csv", &text)],
            file,
            &["waves.csv line 3", col, says],
        );
    }
    // Units the checks of every train apply, per row: a frequency far out of range.
    refused(
        TABLE_TRAIN,
        &[("waves.csv", &format!("{head}1e200,1.0,0,0\n"))],
        file,
        &["waves.csv line 3", "check the value"],
    );
    refused(
        TABLE_TRAIN,
        &[("waves.csv", "f,amplitude,phase\n0.1,1,0\n")],
        file,
        &["the header must be", "`omega,amplitude,phase`"],
    );
    refused(
        TABLE_TRAIN,
        &[("waves.csv", "frequency,amplitude,phase\n0.1,0,0\n0.2,0,0\n")],
        file,
        &["every amplitude is zero"],
    );
    refused(
        TABLE_TRAIN,
        &[("waves.csv", "frequency,amplitude,phase\n")],
        file,
        &["no rows after the header"],
    );
    refused(TABLE_TRAIN, &[], file, &["cannot read wave component file"]);
    refused(
        &format!("{TABLE_TRAIN}direction = 10.0\n"),
        &[("waves.csv", head)],
        "trains[0].direction",
        &["gives each component's direction"],
    );
    refused(
        "[[environment.waves.trains]]\ntype = \"components\"\n",
        &[],
        file,
        &["needs `file`"],
    );
    refused(
        &format!("{TABLE_TRAIN}rows = [[1.0, 1.0, 0.0, 0.0]]\n"),
        &[("waves.csv", head)],
        "trains[0].rows",
        &["not both"],
    );
    refused(
        &format!("{TABLE_TRAIN}hs = 2.0\n"),
        &[("waves.csv", head)],
        "trains[0].hs",
        &["not a key of a \"components\" train"],
    );
    // `rows` in the scenario: the row and column in the field.
    for (row, field, says) in [
        (
            "[0.0, 1.0, 0.0, 0.0]",
            "trains[0].rows[1][0]",
            "must be positive",
        ),
        (
            "[1.0, -1.0, 0.0, 0.0]",
            "trains[0].rows[1][1]",
            "must not be negative",
        ),
        ("[1.0, nan, 0.0, 0.0]", "trains[0].rows[1][1]", "finite"),
        ("[1.0, 1.0, inf, 0.0]", "trains[0].rows[1][2]", "finite"),
    ] {
        let w = format!(
            "[[environment.waves.trains]]\ntype = \"components\"\nrows = [[0.5, 1.0, 0.0, 0.0], {row}]\n"
        );
        refused(&w, &[], field, &[says]);
    }
    refused(
        "[[environment.waves.trains]]\ntype = \"components\"\nrows = []\n",
        &[],
        "trains[0].rows",
        &["no rows"],
    );
}

/// An evenly sampled record of `n` samples every `dt` s from `t0`: two waves.
fn record_csv(n: usize, dt: f64, t0: f64) -> String {
    let mut s = String::from("t,eta\n");
    for i in 0..n {
        let t = t0 + i as f64 * dt;
        s += &format!(
            "{t},{}\n",
            0.9 * (0.5 * t).cos() + 0.4 * (1.1 * t + 1.0).sin()
        );
    }
    s
}

#[test]
fn a_record_becomes_components_that_reproduce_it_at_the_reference_point() {
    let (n, dt, t0) = (300usize, 0.2, 4.0);
    let text = record_csv(n, dt, t0);
    let w = format!("{RECORD_TRAIN}reference = [25.0, -5.0]\ndirection = 30.0\n");
    let c = case(&w, &[("basin.csv", &text)]);
    let sea = load(&c).unwrap().sea;
    assert_eq!(sea.components.len(), n / 2);
    let eta: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    let mean = eta.iter().sum::<f64>() / n as f64;
    let field = WaveField::new(&sea);
    for (i, e) in eta.iter().enumerate() {
        let t = t0 + i as f64 * dt;
        let got = field.elevation(25.0, -5.0, t);
        assert!(
            (got - (e - mean)).abs() < 1e-12,
            "sample {i}: {got} against {}",
            e - mean
        );
    }
    for c in &sea.components {
        assert!((c.direction - f64::to_radians(30.0)).abs() < 1e-15);
    }
    // `max_frequency` (Hz) keeps the bins at or below it.
    let w = format!("{RECORD_TRAIN}max_frequency = 0.5\n");
    let sea = load(&case(&w, &[("basin.csv", &text)])).unwrap().sea;
    let period = n as f64 * dt;
    assert_eq!(sea.components.len(), (0.5 * period).floor() as usize);
    assert!(sea.components.iter().all(|c| c.omega <= TAU * 0.5));
    // A run longer than the record is warned of (it repeats the record).
    let long = case(RECORD_TRAIN, &[("basin.csv", &record_csv(20, 0.2, 0.0))]);
    let (s, warnings) = collect_warnings(|| load(&long));
    s.unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("repeat the record") && w.contains("trains[0].file")),
        "{warnings:?}"
    );
}

#[test]
fn bad_records_are_refused_naming_the_file_line_and_column() {
    let file = "trains[0].file";
    refused(
        RECORD_TRAIN,
        &[("basin.csv", &record_csv(7, 0.1, 0.0))],
        file,
        &["basin.csv", "7 samples", "at least 8"],
    );
    // One sample 2% of the step off the even grid: refused; 0.5%: accepted.
    let mut rows: Vec<String> = record_csv(50, 0.1, 0.0).lines().map(String::from).collect();
    let shifted = |off: f64| {
        let mut r = rows.clone();
        r[21] = format!("{},0.3", 2.0 + off);
        r.join("\n") + "\n"
    };
    refused(
        RECORD_TRAIN,
        &[("basin.csv", &shifted(0.002))],
        file,
        &[
            "basin.csv line 22, column t",
            "not evenly sampled",
            "2.0%",
            "1% allowed",
        ],
    );
    load(&case(RECORD_TRAIN, &[("basin.csv", &shifted(0.0005))])).unwrap();
    rows[30] = "3.0,nan".into();
    refused(
        RECORD_TRAIN,
        &[("basin.csv", &(rows.join("\n") + "\n"))],
        file,
        &["basin.csv line 31, column eta", "not a finite number"],
    );
    refused(
        RECORD_TRAIN,
        &[(
            "basin.csv",
            "t,eta\n0,0\n0.1,1\n0.1,2\n0.3,0\n0.4,1\n0.5,0\n0.6,1\n0.7,0\n",
        )],
        file,
        &["basin.csv line 4, column t", "does not increase"],
    );
    refused(
        RECORD_TRAIN,
        &[(
            "basin.csv",
            &(0..10).fold("t,eta\n".to_string(), |s, i| s + &format!("{i},0.25\n")),
        )],
        file,
        &["elevation is constant"],
    );
    refused(
        RECORD_TRAIN,
        &[("basin.csv", "time,elevation\n0,0\n")],
        file,
        &["the header must be `t,eta`"],
    );
    refused(
        &format!("{RECORD_TRAIN}max_frequency = 0.01\n"),
        &[("basin.csv", &record_csv(50, 0.1, 0.0))],
        "trains[0].max_frequency",
        &["keeps no component", "1 / T = 0.2 Hz"],
    );
    refused(
        &format!("{RECORD_TRAIN}max_frequency = -1.0\n"),
        &[("basin.csv", &record_csv(50, 0.1, 0.0))],
        "trains[0].max_frequency",
        &["must be positive"],
    );
    refused(
        &format!("{RECORD_TRAIN}reference = [nan, 0.0]\n"),
        &[("basin.csv", &record_csv(50, 0.1, 0.0))],
        "trains[0].reference[0]",
        &["finite"],
    );
    refused(
        "[[environment.waves.trains]]\ntype = \"record\"\n",
        &[],
        file,
        &["needs `file`", "`t,eta`"],
    );
    refused(
        &format!("{RECORD_TRAIN}rows = [[1.0, 1.0, 0.0, 0.0]]\n"),
        &[("basin.csv", &record_csv(50, 0.1, 0.0))],
        "trains[0].rows",
        &["not a key of a \"record\" train"],
    );
}

#[test]
fn the_wave_input_keys_of_other_trains_are_refused() {
    refused(
        "[[environment.waves.trains]]\ntype = \"regular\"\nheight = 1.0\nperiod = 8.0\nfile = \"x.csv\"\n",
        &[],
        "trains[0].file",
        &["not a key of a \"regular\" train"],
    );
}
