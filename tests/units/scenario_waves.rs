//! `src/scenario/waves.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::error::Error;
use cablesim::scenario::waves::*;
use cablesim::scenario::Scenario;
use cablesim::sea::dispersion::wave_number;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::{dnv_peak_factor, Spectrum};
use cablesim::sea::Stretching;
use std::f64::consts::TAU;
use std::path::Path;

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

fn parse(waves: &str) -> Result<Scenario, Error> {
    Scenario::parse(&format!("{BASE}\n{waves}"), Path::new("/tmp/sea.toml"))
}

fn fails(waves: &str, field: &str, msg: &str) {
    match parse(waves) {
        Ok(_) => panic!("expected an error naming {field}"),
        Err(Error::Scenario {
            path,
            field: f,
            message,
        }) => {
            assert_eq!(path, Path::new("/tmp/sea.toml"));
            assert!(
                f.contains(field),
                "field `{f}` should name `{field}` ({message})"
            );
            assert!(
                message.contains(msg),
                "message `{message}` should say `{msg}`"
            );
        }
        Err(e) => panic!("wrong error kind: {e}"),
    }
}

#[test]
fn no_waves_is_still_water() {
    let s = parse("").unwrap();
    assert!(s.sea.is_still());
    assert_eq!(s.sea.depth, 120.0);
}

/// Several trains combine: a regular wave (height, degrees) and a JONSWAP sea with
/// the DNV peak factor; options reach the sea state.
#[test]
fn trains_combine() {
    let s = parse(
        r#"
[environment.waves]
stretching = "constant"
ramp = 15.0
seed = 4
[[environment.waves.trains]]
type = "regular"
height = 2.0
period = 9.0
direction = 90.0
phase = 180.0
[[environment.waves.trains]]
type = "jonswap"
hs = 4.0
tp = 10.0
components = 50
"#,
    )
    .unwrap();
    let sea = &s.sea;
    assert_eq!(sea.components.len(), 51);
    assert_eq!(sea.stretching, Stretching::Constant);
    assert_eq!(sea.ramp_duration, 15.0);
    let r = sea.components[0];
    assert_eq!(r.amplitude, 1.0);
    assert!((r.direction - TAU / 4.0).abs() < 1e-15);
    assert!((r.phase - TAU / 2.0).abs() < 1e-15);
    assert_eq!(r.k, wave_number(TAU / 9.0, 120.0, 9.81));
    let expected = discretise(
        &Spectrum::Jonswap {
            hs: 4.0,
            tp: 10.0,
            gamma: dnv_peak_factor(4.0, 10.0),
        },
        &Discretisation {
            components: 50,
            direction: 0.0,
            spreading: None,
            seed: 4,
            stream: 1,
        },
        120.0,
        9.81,
    );
    assert_eq!(&sea.components[1..], &expected[..]);
}

#[test]
fn bad_values_are_named() {
    let t = "[[environment.waves.trains]]\n";
    fails(
        &format!("{t}type = \"jonswap\"\nhs = 0.0\ntp = 10.0"),
        "trains[0].hs",
        "positive",
    );
    fails(
        &format!("{t}type = \"jonswap\"\nhs = -2.0\ntp = 10.0"),
        "trains[0].hs",
        "positive",
    );
    fails(
        &format!("{t}type = \"pierson_moskowitz\"\nhs = 2.0\ntp = 0.0"),
        "trains[0].tp",
        "positive",
    );
    fails(
        &format!("{t}type = \"regular\"\namplitude = 1.0\nperiod = -3.0"),
        "trains[0].period",
        "positive",
    );
    fails(
        &format!("{t}type = \"regular\"\namplitude = 1.0"),
        "trains[0].period",
        "required",
    );
    fails(
        &format!("{t}type = \"regular\"\namplitude = 1.0\nheight = 2.0\nperiod = 8.0"),
        "height",
        "not both",
    );
    fails(
        &format!("{t}type = \"jonswap\"\nhs = 2.0\ntp = 8.0\ncomponents = 3"),
        "trains[0].components",
        "at least 10",
    );
    fails(
        &format!("{t}type = \"regular\"\namplitude = 1.0\nperiod = 8.0\ndirection = nan"),
        "trains[0].direction",
        "finite",
    );
    fails(
        &format!("{t}type = \"regular\"\namplitude = 1.0\nperiod = 8.0\nphase = inf"),
        "trains[0].phase",
        "finite",
    );
    fails(
        &format!("{t}type = \"jonswp\"\nhs = 2.0\ntp = 8.0"),
        "trains[0].type",
        "unknown wave train type",
    );
    fails(
        &format!("{t}type = \"regular\"\namplitude = 1.0\nperiod = 8.0\nhs = 2.0"),
        "trains[0].hs",
        "not a key",
    );
    fails(
        &format!("{t}type = \"jonswap\"\nhs = 2.0\ntp = 8.0\ngamma = 0.5"),
        "trains[0].gamma",
        "at least 1",
    );
    fails(
        "[environment.waves]\nstretching = \"linear\"",
        "environment.waves.stretching",
        "wheeler",
    );
    fails(
        "[environment.waves]\nramp = -1.0",
        "environment.waves.ramp",
        "negative",
    );
    fails(
        "[environment.waves]\nswell = 1.0",
        "environment.waves",
        "swell",
    );
}

#[test]
fn bad_tables_are_named() {
    let t = "[[environment.waves.trains]]\ntype = \"table\"\n";
    fails(
        &format!("{t}spectrum = [[0.3, 0.0], [0.5, 1.0], [0.4, 0.5]]"),
        "spectrum[2][0]",
        "must increase",
    );
    fails(
        &format!("{t}spectrum = [[0.3, 0.0], [0.5, 1.0], [0.5, 0.5]]"),
        "spectrum[2][0]",
        "must increase",
    );
    fails(
        &format!("{t}spectrum = [[0.3, 0.0], [0.35, 1.0], [0.4, 2.0], [0.45, 1.0], [1.5, 0.2], [1.55, 0.0]]"),
        "spectrum[4]",
        "gap",
    );
    fails(
        &format!("{t}spectrum = [[0.3, 0.0], [0.5, -1.0], [0.6, 0.0]]"),
        "spectrum[1][1]",
        "negative",
    );
    fails(
        &format!("{t}spectrum = [[0.3, 0.0], [0.5, 1.0]]"),
        "spectrum",
        "at least 3",
    );
    fails(&format!("{t}components = 50"), "spectrum", "needs spectrum");
    // A good table parses, and its components hold the table's m0 (less the 0.7%
    // left in the tails).
    let (mut w, mut d) = (Vec::new(), Vec::new());
    let js = Spectrum::Jonswap {
        hs: 3.0,
        tp: 9.0,
        gamma: 2.0,
    };
    for j in 0..40 {
        w.push(0.3 + 0.03 * j as f64);
        d.push(js.density(w[j]));
    }
    let rows: Vec<String> = w
        .iter()
        .zip(&d)
        .map(|(a, b)| format!("[{a}, {b}]"))
        .collect();
    let s = parse(&format!("{t}spectrum = [{}]", rows.join(", "))).unwrap();
    let m0: f64 = s
        .sea
        .components
        .iter()
        .map(|c| c.amplitude.powi(2) / 2.0)
        .sum();
    let table = Spectrum::Table {
        omega: w,
        density: d,
    }
    .moment(0);
    assert!((m0 / table - 0.993).abs() < 0.01, "m0 {m0}, table {table}");
}

/// The example in docs/src/sea_states.md parses into the sea it describes.
#[test]
fn documented_example_parses() {
    let doc = include_str!("../../docs/src/sea_states.md");
    let start = doc.find("```toml\n").expect("a toml block") + 8;
    let block = &doc[start..start + doc[start..].find("```").unwrap()];
    let base = BASE.replace("[environment]\ndepth = 120.0\n", "");
    let s = Scenario::parse(&format!("{base}\n{block}"), Path::new("/tmp/doc.toml"))
        .unwrap_or_else(|e| panic!("docs/src/sea_states.md example: {e}"));
    assert_eq!(s.sea.components.len(), 201);
    assert_eq!(s.sea.depth, 150.0);
    assert_eq!(s.sea.ramp_duration, 30.0);
    assert_eq!(s.sea.components[0].amplitude, 0.75);
    assert!((s.sea.components[0].direction - 45f64.to_radians()).abs() < 1e-15);
    assert!(s.sea.components[1..].iter().any(|c| c.direction != 0.0));
}

/// A wave steeper than H/L = 1/7 parses with a warning naming the field; a gentle
/// one without.
#[test]
fn steep_waves_warn() {
    let raw = |h: f64| RawWaves {
        trains: vec![RawTrain {
            kind: "regular".into(),
            height: Some(h),
            period: Some(6.0),
            hs: None,
            tp: None,
            gamma: None,
            spectrum: None,
            components: None,
            spreading: None,
            amplitude: None,
            phase: None,
            direction: None,
            file: None,
            rows: None,
            reference: None,
            max_frequency: None,
        }],
        ..Default::default()
    };
    // L = 56.2 m at 6 s in deep water: the limit is H = 8.0 m.
    let p = Path::new("/tmp/sea.toml");
    let (_, w) = sea_state(p, Some(&raw(9.0)), f64::INFINITY, 9.81).unwrap();
    assert_eq!(w.len(), 1);
    assert!(
        w[0].contains("trains[0].height") && w[0].contains("breaking"),
        "{}",
        w[0]
    );
    let (_, w) = sea_state(p, Some(&raw(7.0)), f64::INFINITY, 9.81).unwrap();
    assert!(w.is_empty());
}
