//! Screen-model net loads (docs/src/model/screen.md) on the CPU path: a plane panel of
//! known solidity in a uniform current, head on and at 45 degrees, for each
//! coefficient set, against the coefficients the models give (values computed from
//! the published formulas as Cheng et al. 2020's code states them); the wake rule on
//! a cage in current from an oblique direction; the network fast path against the
//! general passes; the scenario keys and their errors.

use super::common::wire;
use cablesim::cpu::CpuSolver;
use cablesim::math::V3;
use cablesim::model::{
    add_net, Current, Environment, Layout, ModelDef, NetShape, NetSpec, PointMass, ScreenModel,
    ScreenNet, WakeModel,
};
use cablesim::options::{Baumgarte, Scheme, SolverOptions};
use cablesim::physics::screen::{WAKE_CHENG, WAKE_NONE};
use cablesim::physics::{screen_panel_force, ScreenCoefs};
use cablesim::scenario::Scenario;
use cablesim::sea::dispersion::wave_number;
use cablesim::sea::{SeaState, Stretching, WaveComponent};
use cablesim::stability::stable_step;

const RHO: f64 = 1025.0;
/// Sn, twine diameter (m) and viscosity of the Moe-Føre et al. (2016) net as Cheng et
/// al.'s benchmark input gives them (water 1025 kg/m^3, mu 1.002e-3 Pa s).
const SN: f64 = 0.347;
const DW: f64 = 1.41e-3;
const NU: f64 = 1.002e-3 / RHO;

/// A neutrally buoyant twine (no weight less buoyancy), so that a net at rest in its
/// generated shape carries the screen loads alone.
fn neutral_twine() -> cablesim::model::LineType {
    let mut lt = wire();
    lt.diameter = 0.004;
    lt.mass_per_length = RHO * std::f64::consts::PI * 0.25 * lt.diameter * lt.diameter;
    lt.ea = 2.0e4;
    lt.damping = 1e-3;
    lt
}

fn screen(model: ScreenModel, wake: WakeModel) -> ScreenNet {
    ScreenNet {
        model,
        solidity: SN,
        twine_diameter: DW,
        viscosity: NU,
        wake,
        axis: [0.0, 0.0],
    }
}

/// A net in a uniform current `u`.
fn model_with(shape: NetShape, u: [f64; 3], scr: Option<ScreenNet>) -> ModelDef {
    let mut def = ModelDef {
        env: Environment {
            depth: 200.0,
            ..Environment::default()
        },
        line_types: vec![neutral_twine()],
        currents: vec![Current {
            table: vec![(0.0, u)],
        }],
        ..Default::default()
    };
    add_net(
        &mut def,
        &NetSpec {
            name: "net".into(),
            line_type: 0,
            current: 0,
            shape,
            segments: 1,
            sinker: PointMass::default(),
            output_positions: false,
            screen: scr,
        },
    )
    .unwrap();
    def
}

/// A 2 m x 1.5 m panel (5 x 4 knots) in the x-z plane, its normal along y.
fn panel() -> NetShape {
    NetShape::Panel {
        columns: 5,
        rows: 4,
        width: 2.0,
        depth: 1.5,
        top: [0.0, 0.0, -2.0],
    }
}

/// The per-node forces of `def` at rest in its generated shape (evaluated, not stepped).
fn forces_at_rest(def: &ModelDef) -> Vec<[f64; 3]> {
    let (lay, pos) = Layout::build(def).unwrap();
    let opts = SolverOptions {
        dt: 1e-4,
        ..Default::default()
    };
    let mut s = CpuSolver::new(lay, &pos, opts);
    s.evaluate().unwrap().force
}

fn total(f: &[[f64; 3]]) -> V3<f64> {
    f.iter().fold(V3::zero(), |a, x| a + V3::from_f64(*x))
}

/// `(C_D, C_L)` of each model at `theta` for the Moe-Føre net, from the published
/// polynomials (Aarsnes, Løland), and at 0.5 m/s for Kristiansen and Faltinsen the
/// values the research notes computed with Cheng et al.'s form (see docs).
fn cases() -> Vec<(ScreenModel, f64, [f64; 2], [f64; 2])> {
    // (model, speed, (C_D, C_L) at 0 deg, (C_D, C_L) at 45 deg)
    vec![
        (ScreenModel::Aarsnes, 0.5, [0.7701, 0.0], [0.5563, 0.1935]),
        (ScreenModel::Loland, 0.5, [0.6981, 0.0], [0.5053, 0.1861]),
        (
            ScreenModel::KristiansenFaltinsen,
            0.5,
            [0.665, 0.0],
            [0.376, 0.129],
        ),
    ]
}

#[test]
fn screen_panel_normal_to_the_current_has_the_models_drag() {
    let area = 2.0 * 1.5;
    for (model, u, [cd, _], _) in cases() {
        let def = model_with(panel(), [0.0, u, 0.0], Some(screen(model, WakeModel::None)));
        let f = total(&forces_at_rest(&def));
        let drag = 0.5 * RHO * cd * area * u * u;
        println!("{model:?}: F = {f:?}, expected drag {drag:.4} N");
        assert!(
            (f.y - drag).abs() <= 5e-3 * drag,
            "{model:?}: drag {} N, the model's {drag} N",
            f.y
        );
        assert!(
            f.x.abs() < 1e-9 * drag && f.z.abs() < 1e-9 * drag,
            "{model:?}: {f:?}"
        );
    }
}

#[test]
fn screen_panel_at_45_degrees_has_the_models_drag_and_lift() {
    let area = 2.0 * 1.5;
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (model, u, _, [cd, cl]) in cases() {
        // The flow at 45 degrees to the panel's normal (+y), in the x-y plane.
        let dir = V3::new(h, h, 0.0);
        let def = model_with(
            panel(),
            [u * h, u * h, 0.0],
            Some(screen(model, WakeModel::None)),
        );
        let f = total(&forces_at_rest(&def));
        let q = 0.5 * RHO * area * u * u;
        let drag = f.dot(dir);
        let side = f - dir * drag;
        // Lift across the flow towards the side the panel faces: (-1, 1, 0) / sqrt 2.
        let lift = side.dot(V3::new(-h, h, 0.0));
        println!(
            "{model:?}: drag {drag:.4} N ({:.4}), lift {lift:.4} N ({:.4})",
            cd * q,
            cl * q
        );
        assert!(
            (drag - cd * q).abs() <= 5e-3 * cd * q,
            "{model:?}: drag {drag}, expected {}",
            cd * q
        );
        assert!(
            (lift - cl * q).abs() <= 5e-3 * cl * q,
            "{model:?}: lift {lift}, expected {}",
            cl * q
        );
        assert!(
            (side - V3::new(-h, h, 0.0) * lift).norm() < 1e-9 * q,
            "{model:?}: {side:?}"
        );
    }
}

#[test]
fn screen_loads_replace_the_twines_drag() {
    // Morison twines of the same line type load the panel differently; with the
    // screen model the twines' drag is gone (the force is the screen model's alone,
    // the test above), here: the Morison net's force is the twines' drag.
    let u = 0.5;
    let morison = total(&forces_at_rest(&model_with(panel(), [0.0, u, 0.0], None)));
    let scr = total(&forces_at_rest(&model_with(
        panel(),
        [0.0, u, 0.0],
        Some(screen(ScreenModel::Aarsnes, WakeModel::None)),
    )));
    println!("Morison {morison:?}, screen {scr:?}");
    assert!(morison.y > 0.0 && scr.y > 0.0);
    assert!((morison.y - scr.y).abs() > 0.05 * scr.y);
}

/// A cylinder of 16 knots around and 3 rows, radius 2 m, in a current at 45 degrees.
fn cage(wake: WakeModel) -> (ModelDef, f64) {
    let u = 0.4;
    let b = std::f64::consts::FRAC_PI_4;
    let def = model_with(
        NetShape::Cylinder {
            around: 16,
            rows: 3,
            radius: 2.0,
            depth: 2.0,
            top: [1.0, -3.0, -1.0],
        },
        [u * b.cos(), u * b.sin(), 0.0],
        Some(screen(ScreenModel::Aarsnes, wake)),
    );
    (def, u)
}

#[test]
fn wake_slows_the_flow_on_the_downstream_side_of_a_cage() {
    // Knot j of the middle row sits at angle 22.5 j degrees; the flow comes from 45
    // degrees. Knot 2 (45 degrees) and its panels are downstream of the axis; its
    // mirror across the axis's line normal to the flow is knot 12 - 2 = 10, upstream,
    // whose panels meet the flow at the same angles. Løland's factor r slows the flow on
    // the downstream side: force r^2 times the mirror's. Without a wake both are equal.
    let cd0: f64 = 0.04 + (-0.04 + SN - 1.24 * SN * SN + 13.7 * SN.powi(3));
    let r = 1.0 - 0.46 * cd0;
    let knot = |f: &[[f64; 3]], j: usize| V3::<f64>::from_f64(f[16 + j]).norm();
    let (def, _) = cage(WakeModel::Loland);
    let f = forces_at_rest(&def);
    let (down, up) = (knot(&f, 2), knot(&f, 10));
    println!(
        "r = {r:.4}: downstream {down:.5} N, upstream {up:.5} N, ratio {:.5}",
        down / up
    );
    assert!(
        (down / up - r * r).abs() < 1e-9,
        "ratio {} against r^2 {}",
        down / up,
        r * r
    );
    let (def, _) = cage(WakeModel::None);
    let f = forces_at_rest(&def);
    assert!((knot(&f, 2) / knot(&f, 10) - 1.0).abs() < 1e-9);
    // Upstream knots are untouched by the wake.
    let g = forces_at_rest(&cage(WakeModel::Loland).0);
    assert!((knot(&g, 10) - knot(&f, 10)).abs() < 1e-12 * knot(&f, 10));
}

#[test]
fn nets_csv_drag_holds_the_screen_panels_loads() {
    // A cylindrical screen cage at rest in its generated shape (neutral twines, no
    // Morison drag on them) in a current at 45 degrees with Cheng's wake: the water's
    // horizontal force on it is the screen loads alone, so `nets.csv`'s force (the
    // output's sum of whole panels) equals the sum of the knots' forces the solver
    // evaluates (each knot a quarter of its panels), and is not small.
    use cablesim::model::cage::{add_cage, CageSpec};
    let u = 0.4;
    let b = std::f64::consts::FRAC_PI_4;
    let mut def = ModelDef {
        env: Environment {
            depth: 200.0,
            ..Environment::default()
        },
        line_types: vec![neutral_twine()],
        currents: vec![Current {
            table: vec![(0.0, [u * b.cos(), u * b.sin(), 0.0])],
        }],
        ..Default::default()
    };
    let spec = NetSpec {
        name: "cage".into(),
        line_type: 0,
        current: 0,
        shape: NetShape::Cylinder {
            around: 16,
            rows: 4,
            radius: 2.0,
            depth: 3.0,
            top: [1.0, -3.0, -1.0],
        },
        segments: 1,
        sinker: PointMass::default(),
        output_positions: false,
        screen: Some(screen(ScreenModel::Aarsnes, WakeModel::Cheng)),
    };
    let info = add_cage(&mut def, &spec, &CageSpec::default()).unwrap();
    let (lay, pos) = Layout::build(&def).unwrap();
    let opts = SolverOptions {
        dt: 1e-4,
        ..Default::default()
    };
    let mut s = CpuSolver::new(lay.clone(), &pos, opts);
    let ev = s.evaluate().unwrap();
    let f = total(&ev.force);
    let r: Vec<[f64; 3]> = s.r.iter().map(|x| x.to_f64()).collect();
    let v: Vec<[f64; 3]> = s.v.iter().map(|x| x.to_f64()).collect();
    let st = cablesim::output::net_states(&lay, &ev, &r, &v, &[info]);
    let out = st[0].force;
    println!(
        "knots' sum ({:.6}, {:.6}) N, nets.csv ({:.6}, {:.6}) N",
        f.x, f.y, out[0], out[1]
    );
    // The Aarsnes drag of the whole cage's projected area is some tens of N.
    assert!(
        f.x > 1.0 && f.y > 1.0,
        "the cage must feel the current: {f:?}"
    );
    let tol = 1e-9 * (f.x * f.x + f.y * f.y).sqrt();
    assert!((out[0] - f.x).abs() < tol && (out[1] - f.y).abs() < tol);
}

#[test]
fn cheng_wake_factor_depends_on_the_panels_angle() {
    // One panel downstream of the axis, normal at angle a to the flow; the same panel
    // with the wake off: the force ratio is r(a)^2, r = (cos a + 0.05 - 0.38 Sn) /
    // (cos a + 0.05) (Cheng et al. 2020).
    for deg in [0.0f64, 30.0, 60.0] {
        let a = deg.to_radians();
        let u = V3::new(0.6, 0.0, 0.0);
        // A unit square whose normal is (cos a, sin a, 0), centred at x = 5.
        let n = V3::new(a.cos(), a.sin(), 0.0);
        let t = V3::new(-a.sin(), a.cos(), 0.0);
        let z = V3::new(0.0, 0.0, 1.0);
        let c = V3::new(5.0, 0.0, -3.0);
        let p = [
            c - t * 0.5 + z * 0.5,
            c + t * 0.5 + z * 0.5,
            c + t * 0.5 - z * 0.5,
            c - t * 0.5 - z * 0.5,
        ];
        assert!(((p[2] - p[0]).cross(p[3] - p[1]).dot(n)).abs() > 0.99);
        let mut co = ScreenCoefs {
            model: ScreenModel::Loland.code(),
            wake: WAKE_CHENG,
            sn: SN,
            re_scale: DW / (NU * (1.0 - SN)),
            half_rho: 0.5 * RHO,
            axis_x: 0.0,
            axis_y: 0.0,
        };
        let v = [V3::zero(); 4];
        let fw = screen_panel_force(&co, p, v, u).norm();
        co.wake = WAKE_NONE;
        let f0 = screen_panel_force(&co, p, v, u).norm();
        let r = (a.cos() + 0.05 - 0.38 * SN) / (a.cos() + 0.05);
        println!("{deg} deg: r = {r:.4}, force ratio {:.4}", fw / f0);
        assert!((fw / f0 - r * r).abs() < 1e-12);
    }
}

#[test]
fn screen_net_fast_path_matches_the_general_path() {
    // A screen panel in a current and waves, moving: the network fast path against
    // the general passes, both with the screen loads from the step's start.
    let mut def = model_with(
        NetShape::Panel {
            columns: 8,
            rows: 8,
            width: 7.0,
            depth: 7.0,
            top: [0.0, 0.0, -1.0],
        },
        [0.2, 0.6, 0.0],
        Some(screen(ScreenModel::KristiansenFaltinsen, WakeModel::None)),
    );
    def.line_types[0].mass_per_length *= 1.5;
    let (lay, pos) = Layout::build(&def).unwrap();
    let omega = 2.0 * std::f64::consts::PI / 5.0;
    let sea = SeaState {
        components: vec![WaveComponent {
            amplitude: 0.5,
            omega,
            k: wave_number(omega, 200.0, 9.81),
            direction: 0.3,
            phase: 0.1,
        }],
        depth: 200.0,
        stretching: Stretching::Wheeler,
        ramp_duration: 1.0,
        cache_tolerance: 1e-3,
    };
    let dt = 0.8 * stable_step(&lay, Scheme::Symplectic, Baumgarte::default()).dt;
    let opts = SolverOptions {
        dt,
        ..Default::default()
    };
    let mut fast = CpuSolver::new(lay.clone(), &pos, opts);
    let mut slow = CpuSolver::new(lay, &pos, opts);
    slow.use_net_kernel = false;
    fast.set_sea(&sea, false);
    slow.set_sea(&sea, false);
    let steps = (2.0 / dt) as u64;
    fast.advance(steps).unwrap();
    slow.advance(steps).unwrap();
    let dr = fast
        .r
        .iter()
        .zip(&slow.r)
        .map(|(a, b)| (*a - *b).norm())
        .fold(0.0, f64::max);
    let moved = fast
        .r
        .iter()
        .zip(&pos)
        .map(|(a, p)| (*a - V3::from_f64(*p)).norm())
        .fold(0.0, f64::max);
    println!("{steps} steps: |dr| {dr:.2e} m, moved {moved:.3} m");
    assert!(moved > 0.05, "the net must move: {moved} m");
    assert!(dr < 1e-10, "fast and general paths differ by {dr:e} m");
}

const PANEL: &str = r#"
[simulation]
duration = 0.2
dt = 1e-4
output_interval = 0.1

[environment]
current = [0.0, 0.5, 0.0]

[[line_types]]
name = "twine"
diameter = 0.004
mass_per_length = 0.02
ea = 2.0e4
damping = 1.0e-3
cn = 1.2
ct = 0.01
cm = 1.0

[[nets]]
name = "panel"
line_type = "twine"
shape = "panel"
knots = [5, 4]
size = [2.0, 1.5]
top = [0.0, 0.0, -2.0]
loads = "screen"
screen_model = "aarsnes"
solidity = 0.347
"#;

#[test]
fn screen_keys_are_read_and_bad_ones_named() {
    let path = std::path::Path::new("panel.toml");
    let sc = Scenario::parse(PANEL, path).unwrap();
    let s = &sc.model.screens;
    assert_eq!(s.nets.len(), 1);
    assert_eq!(s.knots.len(), 20);
    assert_eq!(s.nets[0].model, ScreenModel::Aarsnes);
    assert_eq!(s.nets[0].twine_diameter, 0.004);
    // The twines lose their drag coefficients, not their mass.
    let lt = sc
        .model
        .cables
        .iter()
        .map(|c| &sc.model.line_types[c.line_type])
        .next()
        .unwrap();
    assert_eq!((lt.cn, lt.ct, lt.mass_per_length), (0.0, 0.0, 0.02));
    // Solidity from the mesh: 2 d / l - (d / l)^2.
    let m = Scenario::parse(&PANEL.replace("solidity = 0.347", "mesh = 0.02"), path).unwrap();
    let x: f64 = 0.004 / 0.02;
    assert!((m.model.screens.nets[0].solidity - (2.0 * x - x * x)).abs() < 1e-15);
    let cases = [
        (
            "solidity = 0.347",
            "solidity = 1.2",
            "solidity: must be between 0 and 1",
        ),
        (
            "solidity = 0.347",
            "solidity = 0.0",
            "solidity: must be between 0 and 1",
        ),
        (
            "solidity = 0.347",
            "mesh = 0.003",
            "mesh: 0.003 m is not coarser than the twine",
        ),
        (
            "solidity = 0.347",
            "solidity = 0.3\nmesh = 0.02",
            "mesh: give the netting by solidity or by mesh",
        ),
        (
            "solidity = 0.347",
            "",
            "solidity: loads = \"screen\" needs the netting's solidity",
        ),
        (
            "screen_model = \"aarsnes\"",
            "screen_model = \"fridman\"",
            "screen_model: must be \"aarsnes\"",
        ),
        (
            "screen_model = \"aarsnes\"",
            "",
            "screen_model: is required",
        ),
        (
            "loads = \"screen\"",
            "loads = \"porous\"",
            "loads: must be \"morison\" or \"screen\"",
        ),
        (
            "loads = \"screen\"",
            "",
            "screen_model: is a key of the screen model",
        ),
        (
            "solidity = 0.347",
            "solidity = 0.347\nwake = \"loland\"",
            "wake: wake shielding needs a closed net",
        ),
        (
            "solidity = 0.347",
            "solidity = 0.347\nwake = \"behind\"",
            "wake: must be \"none\"",
        ),
    ];
    for (from, to, says) in cases {
        assert!(PANEL.contains(from), "{from}");
        let e = Scenario::parse(&PANEL.replace(from, to), path)
            .unwrap_err()
            .to_string();
        assert!(e.contains(says), "{to}: {e}");
    }
}
