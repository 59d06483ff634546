//! Statics that do not give up (issue 11, point 7): near-inextensible lines partly on
//! the seabed converge and match the inextensible catenary; slack near-vertical lines
//! converge; a block with a free point that is not brought to equilibrium is an error
//! that says what to change.

use cablesim::cpu::CpuSolver;
use cablesim::initial::apply_with;
use cablesim::model::Layout;
use cablesim::options::SolverOptions;
use cablesim::physics::catenary::catenary;
use cablesim::scenario::Scenario;
use cablesim::statics::{relax, RelaxOptions};
use std::path::Path;

/// A 500 m chain (100 kg/m, 0.1 m) from an anchor on the seabed at 100 m depth,
/// `span` m away horizontally, to a fairlead 10 m below the surface, `segments`
/// elements, axial stiffness `ea`, `initial = "catenary"`.
fn line(ea: f64, segments: usize, span: f64, length: f64) -> Scenario {
    let text = format!(
        r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0
backend = "cpu"

[environment]
gravity = 9.81
water_density = 1025.0
depth = 100.0

[environment.seabed]
stiffness = 3.0e6
damping = 3.0e4

[[line_types]]
name = "chain"
diameter = 0.1
mass_per_length = 100.0
ea = {ea:e}
damping = 1.0e-4
cn = 2.4
ct = 0.4
cm = 1.0

[[cables]]
name = "line1"
line_type = "chain"
length = {length:e}
segments = {segments}
start = {{ fixed = [{x:e}, 0.0, -100.0] }}
end = {{ fixed = [0.0, 0.0, -10.0] }}
initial = "catenary"
"#,
        x = -span
    );
    Scenario::parse(&text, Path::new("stiff.toml")).unwrap()
}

/// EA 7.5e11 and 1e13 N on a 500 m line with 200 segments, partly on the seabed: the
/// initial equilibrium (the library's own stage, `initial::apply_with`, default
/// options) converges to its tolerance (it stopped at 2.8 N and 154 N against 0.24 N
/// and 3.2 N before the axial stiffness was written out), and the fairlead force is
/// the inextensible catenary's within the discretisation error.
#[test]
fn near_inextensible_lines_partly_on_the_seabed_converge() {
    let w = (100.0 - 1025.0 * std::f64::consts::PI * 0.05 * 0.05) * 9.81;
    let c = catenary(450.0, 90.0, 500.0, f64::INFINITY, w, true).unwrap();
    assert!(c.grounded_length > 100.0, "{c:?}");
    for ea in [7.5e11, 1e13] {
        let sc = line(ea, 200, 450.0, 500.0);
        let (lay, mut pos) = Layout::build(&sc.model).unwrap();
        let residual = apply_with(&sc, &lay, &mut pos, &RelaxOptions::default()).unwrap();
        // Relaxing again from there must find it converged at once: `relax` errs
        // when a block misses its tolerance.
        let rep = relax(&lay, &mut pos.clone(), &RelaxOptions::default()).unwrap();
        let tol = rep.blocks[0].tolerance;
        let f = CpuSolver::new(lay.clone(), &pos, SolverOptions::default())
            .evaluate()
            .unwrap()
            .reaction[1];
        let eh = (-f[0] - c.hf).abs() / c.hf;
        let ev = (-f[2] - c.vf).abs() / c.vf;
        println!(
            "EA {ea:e}: residual {residual:.3e} N (tolerance {tol:.3e} N), HF {:.1} N vs {:.1} N ({eh:.2e}), VF {:.1} N vs {:.1} N ({ev:.2e})",
            -f[0], c.hf, -f[2], c.vf
        );
        assert!(
            residual <= tol,
            "EA {ea:e}: residual {residual} N, tolerance {tol} N"
        );
        assert!(eh < 5e-3 && ev < 5e-3, "EA {ea:e}: HF {eh:e}, VF {ev:e}");
    }
}

/// Slack, near-vertical lines: 120 m of chain from an anchor 1 m (and 0.5 m for a
/// 91 m line with EA 1e13 N) off the vertical below a fairlead 90 m above it: the
/// excess lies on the seabed. They converge.
#[test]
fn slack_near_vertical_lines_converge() {
    for (ea, span, length) in [(7.5e8, 1.0, 120.0), (1e13, 1.0, 120.0), (1e13, 0.5, 91.0)] {
        let sc = line(ea, 50, span, length);
        let (lay, mut pos) = Layout::build(&sc.model).unwrap();
        let residual = apply_with(&sc, &lay, &mut pos, &RelaxOptions::default()).unwrap();
        let rep = relax(&lay, &mut pos.clone(), &RelaxOptions::default()).unwrap();
        println!(
            "EA {ea:e}, span {span} m, length {length} m: residual {residual:.3e} N (tolerance {:.3e} N)",
            rep.blocks[0].tolerance
        );
        assert!(residual <= rep.blocks[0].tolerance);
    }
}

/// A line exactly vertical with slack on the seabed (the grounded part has nowhere to
/// go: any heap is an equilibrium) is not an error: the run starts from the better of
/// the best state found and the analytic catenary, and says so (a warning); the
/// residual it reports is that state's.
#[test]
fn an_exactly_vertical_slack_line_starts_anyway() {
    let sc = line(7.5e8, 50, 0.0, 120.0);
    let (lay, mut pos) = Layout::build(&sc.model).unwrap();
    let residual = apply_with(&sc, &lay, &mut pos, &RelaxOptions::default()).unwrap();
    let forces = cablesim::statics::static_forces(&lay, &pos);
    let worst = (1..pos.len() - 1)
        .map(|i| forces[i].iter().map(|x| x * x).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    println!("vertical slack line: residual {residual:.3e} N");
    assert!(residual.is_finite() && residual > 0.0);
    assert!(
        (worst - residual).abs() <= 1e-9 * residual,
        "{worst} vs {residual}"
    );
}

/// The issue's buoy: net lift 15 kN, three chains of 147 kN wet weight each. With the
/// seabed under them an equilibrium exists (the chains lie on it, the buoy floats one
/// element above) and is found; when the solver is cut short, the error names the
/// buoy's net lift against the weight it carries and what to change.
#[test]
fn a_buoy_too_small_for_its_chains() {
    let text = std::fs::read_to_string("tests/data/buoy_three_chains.toml")
        .unwrap()
        .replace("mass_per_length = 20.0 ", "mass_per_length = 236.0 ")
        .replace("mass = 2000.0 ", "mass = 8716.0 ");
    assert!(
        text.contains("236.0") && text.contains("8716.0"),
        "the data changed"
    );
    let sc = Scenario::parse(&text, Path::new("buoy.toml")).unwrap();
    let (lay, pos) = Layout::build(&sc.model).unwrap();
    let mut p = pos.clone();
    let residual = apply_with(&sc, &lay, &mut p, &RelaxOptions::default()).unwrap();
    assert!(residual < 1e-3, "{residual}");
    let cut = RelaxOptions {
        max_iterations: 1,
        newton_first_pass: 1,
        dr_max_iterations: 0,
        ..RelaxOptions::default()
    };
    let err = apply_with(&sc, &lay, &mut pos.clone(), &cut)
        .unwrap_err()
        .to_string();
    println!("{err}");
    for what in [
        "The free point 'buoy'",
        "net lift (buoyancy less weight) of 15.0 kN",
        "'chain1', 'chain2', 'chain3'",
        "440.7 kN wet weight",
        "cannot hold them all up",
        "initial = \"straight\"",
    ] {
        assert!(err.contains(what), "{what} not in: {err}");
    }
}
