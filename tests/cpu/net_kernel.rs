//! The vectorised network fast path of the CPU stepper agrees with the general path.
//!
//! Contract: same physics, different arithmetic order (the chain path's element loop
//! over gathered ends; a node's point loads summed before they join its force; the
//! seabed's load as on the chain path), so trajectories agree to round-off amplified
//! by the dynamics over the run. Checked on a net panel with every extra the fast path
//! takes: sinkers with drag and volume at the bottom knots, a towed corner, a seabed
//! with friction that the lowest rows reach, a current profile, twines of two elements
//! (nodes of 2, 3 and 4 elements); in still water, through the water surface, and in
//! waves. On one thread and, for a block big enough to be split, on two.

use super::common::wire;
use cablesim::cpu::CpuSolver;
use cablesim::model::{
    add_net, Current, Environment, Layout, ModelDef, NetShape, NetSpec, PointMass, Route, Seabed,
};
use cablesim::options::{Baumgarte, Scheme, SolverOptions};
use cablesim::sea::dispersion::wave_number;
use cablesim::sea::{SeaState, Stretching, WaveComponent};
use cablesim::stability::stable_step;

/// A vertical panel of `k x k` knots 2 m apart, its top row at height `top`, twines of
/// `seg` elements, the top row held with one corner towed, sinkers on the bottom row,
/// a seabed with friction that the lowest rows reach, a current profile.
fn net(k: usize, seg: usize, top: f64) -> ModelDef {
    let mut lt = wire();
    lt.diameter = 0.003;
    lt.mass_per_length = 0.01;
    lt.ea = 2.0e4;
    lt.damping = 1e-3;
    let size = 2.0 * (k - 1) as f64;
    let mut def = ModelDef {
        env: Environment {
            depth: size - 1.0 - top,
            seabed: Seabed {
                friction: 0.4,
                ..Seabed::default()
            },
            ..Environment::default()
        },
        line_types: vec![lt],
        currents: vec![Current {
            table: vec![(-40.0, [0.1, 0.0, 0.0]), (0.0, [0.5, 0.2, 0.0])],
        }],
        ..Default::default()
    };
    add_net(
        &mut def,
        &NetSpec {
            name: "net".into(),
            line_type: 0,
            current: 0,
            shape: NetShape::Panel {
                columns: k,
                rows: k,
                width: size,
                depth: size,
                top: [0.0, 0.0, top],
            },
            segments: seg,
            sinker: PointMass {
                mass: 2.0,
                volume: 2.0e-4,
                drag_area: 0.01,
                added_mass_coef: 1.0,
            },
            output_positions: false,
            screen: None,
        },
    )
    .unwrap();
    let corner = &mut def.nodes[k - 1];
    corner.route = Some(Route::Line {
        start: corner.position,
        velocity: [0.3, 0.2, 0.0],
    });
    def
}

/// A regular wave 1.5 m high, 6 s, in the net's water.
fn wave(depth: f64) -> SeaState {
    let omega = 2.0 * std::f64::consts::PI / 6.0;
    SeaState {
        components: vec![WaveComponent {
            amplitude: 0.75,
            omega,
            k: wave_number(omega, depth, 9.81),
            direction: 0.2,
            phase: 0.3,
        }],
        depth,
        stretching: Stretching::Wheeler,
        ramp_duration: 1.0,
        cache_tolerance: 1e-3,
    }
}

/// Runs `steps` on the fast path and on the general path in `threads` threads; the
/// largest position and velocity differences, and how far the net moved.
fn compare(
    lay: &Layout,
    pos: &[[f64; 3]],
    sea: Option<&SeaState>,
    steps: u64,
    threads: usize,
) -> (f64, f64, f64) {
    let dt = 0.8 * stable_step(lay, Scheme::Symplectic, Baumgarte::default()).dt;
    let opts = SolverOptions {
        dt,
        ..Default::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut fast = CpuSolver::new(lay.clone(), pos, opts);
        let mut slow = CpuSolver::new(lay.clone(), pos, opts);
        slow.use_net_kernel = false;
        if let Some(sea) = sea {
            fast.set_sea(sea, false);
            slow.set_sea(sea, false);
        }
        fast.advance(steps).unwrap();
        slow.advance(steps).unwrap();
        let worst = |a: &[cablesim::math::V3<f64>], b: &[cablesim::math::V3<f64>]| {
            a.iter()
                .zip(b)
                .map(|(a, b)| (*a - *b).norm())
                .fold(0.0, f64::max)
        };
        let moved = fast
            .r
            .iter()
            .zip(pos)
            .map(|(r, p)| {
                (0..3)
                    .map(|d| (r.to_f64()[d] - p[d]).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        (worst(&fast.r, &slow.r), worst(&fast.v, &slow.v), moved)
    })
}

#[test]
fn net_fast_path_matches_the_general_path() {
    // Top row 1 m under water; 0.2 m over it (the top elements partly dry); in waves.
    // 8 x 8 knots, twines of 2 elements: runs of consecutive ends too short to be read
    // in place, every element's ends gathered; 20 x 20 knots, twines of one element:
    // the rows (19 elements) and the twines between rows read in place.
    for (k, seg, steps) in [(8, 2, 3000), (20, 1, 1000)] {
        for (top, waves) in [(-1.0, false), (0.2, false), (-1.0, true)] {
            let def = net(k, seg, top);
            let depth = def.env.depth;
            let (lay, pos) = Layout::build(&def).unwrap();
            assert!(!lay.blocks[0].is_chain && lay.blocks.len() == 1);
            let sea = waves.then(|| wave(depth));
            let (dr, dv, moved) = compare(&lay, &pos, sea.as_ref(), steps, 1);
            println!(
                "{k} x {k} knots, {seg} elements a twine, top {top}, waves {waves}: \
                 |dr| {dr:.2e} m, |dv| {dv:.2e} m/s, moved {moved:.3} m"
            );
            assert!(moved > 0.1, "the net must move: {moved} m");
            assert!(
                dr < 1e-10 && dv < 1e-8,
                "{k} x {k}, top {top}, waves {waves}: fast and general paths differ by \
                 {dr:e} m, {dv:e} m/s"
            );
        }
    }
}

#[test]
fn big_net_fast_path_on_two_threads_matches_the_general_path() {
    // 4160 nodes: split across the threads on both paths.
    let (lay, pos) = Layout::build(&net(26, 4, 0.0)).unwrap();
    assert!(lay.n_nodes() >= 4096);
    let (dr, dv, moved) = compare(&lay, &pos, None, 300, 2);
    println!("|dr| {dr:.2e} m, |dv| {dv:.2e} m/s, moved {moved:.3} m");
    assert!(moved > 1e-3, "the net must move: {moved} m");
    assert!(
        dr < 1e-10 && dv < 1e-8,
        "paths differ by {dr:e} m, {dv:e} m/s"
    );
}

#[test]
fn net_fast_path_reports_blow_up_like_the_general_path() {
    let (lay, pos) = Layout::build(&net(8, 2, -1.0)).unwrap();
    let dt = 20.0 * stable_step(&lay, Scheme::Symplectic, Baumgarte::default()).dt;
    let opts = SolverOptions {
        dt,
        ..Default::default()
    };
    let mut fast = CpuSolver::new(lay.clone(), &pos, opts);
    let mut slow = CpuSolver::new(lay, &pos, opts);
    slow.use_net_kernel = false;
    let e1 = fast.advance(2000).unwrap_err().to_string();
    let e2 = slow.advance(2000).unwrap_err().to_string();
    assert!(e1.contains("diverged") && e1.contains("node"), "{e1}");
    assert_eq!(e1, e2);
}
