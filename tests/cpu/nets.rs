//! `[[nets]]`: net panels and cylindrical cages from a few numbers. The example cage is
//! built as stated; a panel hanging in still water carries its wet weight on its top
//! row; bad tables name the field.

use cablesim::cpu::CpuSolver;
use cablesim::error::Error;
use cablesim::model::Layout;
use cablesim::options::{Baumgarte, Scheme, SolverOptions};
use cablesim::scenario::Scenario;
use cablesim::stability::stable_step;
use std::path::Path;

#[test]
fn example_cage_is_built_as_stated() {
    let sc = Scenario::load(Path::new("examples/net_cage.toml")).unwrap();
    let m = &sc.model;
    assert_eq!(m.cables.len(), 128 * 32 + 128 * 31);
    assert_eq!(m.nodes.len(), 128 * 32);
    let held: Vec<_> = m.nodes.iter().filter(|n| n.route.is_some()).collect();
    assert_eq!(held.len(), 128);
    assert!(held.iter().all(|n| (n.position[2] + 0.5).abs() < 1e-12));
    let sinkers = m.nodes.iter().filter(|n| n.point.mass == 20.0).count();
    assert_eq!(sinkers, 128);
    for n in &m.nodes {
        let r = n.position[0].hypot(n.position[1]);
        assert!((r - 10.0).abs() < 1e-9 && n.position[2] <= -0.5 && n.position[2] >= -8.5);
    }
    let (lay, _) = Layout::build(m).unwrap();
    assert_eq!(lay.blocks.len(), 1, "one connected net");
    assert!(!lay.blocks[0].is_chain);
}

const PANEL: &str = r#"
[simulation]
duration = 1.0
output_interval = 1.0

[environment]

[[line_types]]
name = "twine"
diameter = 0.01
mass_per_length = 0.2
ea = 5.0e3
damping = 0.05
cn = 1.2
ct = 0.01
cm = 1.0

[[nets]]
name = "panel"
line_type = "twine"
shape = "panel"
knots = [9, 7]
size = [8.0, 6.0]
top = [0.0, 0.0, -1.0]
segments = 2
sinker = { mass = 3.0, volume = 1.0e-3 }
"#;

fn load(text: &str) -> Result<Scenario, Error> {
    // A directory of its own per call: the tests of this binary run in parallel threads
    // of one process, so a name made from the process id alone would be shared.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nets.toml");
    std::fs::write(&path, text).unwrap();
    Scenario::load(&path)
}

/// A panel of 9 x 7 knots in still water settles; its top row then carries the wet
/// weight of the twines and the sinkers (drag and damping dissipate the start).
#[test]
fn hanging_panel_carries_its_wet_weight_on_the_top_row() {
    let sc = load(PANEL).unwrap();
    let (lay, pos) = Layout::build(&sc.model).unwrap();
    let dt = 0.8 * stable_step(&lay, Scheme::Symplectic, Baumgarte::default()).dt;
    let mut s = CpuSolver::new(
        lay.clone(),
        &pos,
        SolverOptions {
            dt,
            ..Default::default()
        },
    );
    s.advance((40.0 / dt) as u64).unwrap();
    let ev = s.evaluate().unwrap();
    let down: f64 = ev.reaction.iter().map(|f| f[2]).sum();
    let (g, rho) = (9.81, 1025.0);
    let lt = &lay.line_types[0];
    let twine: f64 = sc
        .model
        .cables
        .iter()
        .map(|c| c.l0.iter().sum::<f64>())
        .sum();
    let wet = twine * lt.wet_weight_per_length(g, rho) + 9.0 * (3.0 - rho * 1.0e-3) * g;
    let speed = s.v.iter().map(|v| v.norm()).fold(0.0, f64::max);
    eprintln!(
        "panel: top row carries {:.3} N down, wet weight {wet:.3} N, fastest node {speed:.2e} m/s",
        -down
    );
    assert!(speed < 2e-2, "not settled: {speed} m/s");
    assert!((-down - wet).abs() < 1e-3 * wet, "{} vs {wet}", -down);
    // Sideways the reactions balance (no current).
    let side: f64 = ev.reaction.iter().map(|f| f[0]).sum();
    assert!(side.abs() < 1e-3 * wet);
}

#[test]
fn bad_net_tables_name_the_field() {
    for (from, to, field, msg) in [
        (
            "shape = \"panel\"",
            "shape = \"sphere\"",
            "nets[0] (\"panel\").shape",
            "\"panel\" or \"cylinder\"",
        ),
        (
            "knots = [9, 7]",
            "knots = [9, 1]",
            "nets[0] (\"panel\").knots",
            "at least 2 across and 2 down",
        ),
        (
            "size = [8.0, 6.0]",
            "size = [8.0, -6.0]",
            "nets[0] (\"panel\").size[1]",
            "must be positive",
        ),
        (
            "line_type = \"twine\"\nshape",
            "line_type = \"rope\"\nshape",
            "nets[0] (\"panel\").line_type",
            "unknown line type",
        ),
        (
            "segments = 2",
            "segments = 0",
            "nets[0] (\"panel\").segments",
            "from 1 to 1000",
        ),
        (
            "sinker = { mass = 3.0, volume = 1.0e-3 }",
            "sinker = { mass = -3.0 }",
            "nets[0] (\"panel\").sinker.mass",
            "must not be negative",
        ),
    ] {
        assert!(PANEL.contains(from), "{from}");
        match load(&PANEL.replace(from, to)) {
            Err(Error::Scenario {
                field: f, message, ..
            }) => {
                assert!(
                    f.contains(field),
                    "field `{f}` should name `{field}` ({message})"
                );
                assert!(message.contains(msg), "`{message}` should say `{msg}`");
            }
            other => panic!("{to}: expected a scenario error, got {other:?}"),
        }
    }
    // Unknown keys are errors too (serde names the key).
    let e = load(&PANEL.replace("segments = 2", "segments = 2\ncolour = 1")).unwrap_err();
    assert!(e.to_string().contains("colour"), "{e}");
}
