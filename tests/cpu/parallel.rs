//! A big network (a net cage: one block of thousands of nodes) has its symplectic GLMF
//! steps split across threads. The split changes nothing: the result equals the
//! single-thread one bit for bit, and a blow-up names the same node and time.

use super::common::wire;
use cablesim::cpu::CpuSolver;
use cablesim::model::{
    add_net, Current, Environment, Layout, ModelDef, NetShape, NetSpec, PointMass, Route,
};
use cablesim::options::{Baumgarte, Scheme, SolverOptions};
use cablesim::stability::stable_step;

/// A vertical panel of `k x k` knots 2 m apart (`model::add_net`), twines of `seg`
/// elements, the top row held with one corner towed, sinkers on the bottom row, a
/// seabed the lowest rows reach, a current.
fn net(k: usize, seg: usize) -> ModelDef {
    let mut lt = wire();
    lt.diameter = 0.003;
    lt.mass_per_length = 0.01;
    lt.ea = 2.0e4;
    lt.damping = 1e-3;
    let size = 2.0 * (k - 1) as f64;
    let mut def = ModelDef {
        env: Environment {
            depth: size - 1.0,
            ..Environment::default()
        },
        line_types: vec![lt],
        currents: vec![Current::uniform([0.4, 0.1, 0.0])],
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
                top: [0.0, 0.0, 0.0],
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
    // Tow the top-right knot.
    let corner = &mut def.nodes[k - 1];
    corner.route = Some(Route::Line {
        start: corner.position,
        velocity: [0.3, 0.2, 0.0],
    });
    def
}

fn run(
    threads: usize,
    lay: &Layout,
    pos: &[[f64; 3]],
    opts: SolverOptions,
    steps: u64,
) -> (Vec<[f64; 3]>, Vec<[f64; 3]>, Option<String>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut s = CpuSolver::new(lay.clone(), pos, opts);
        let err = s.advance(steps).err().map(|e| e.to_string());
        (
            s.r.iter().map(|x| x.to_f64()).collect(),
            s.v.iter().map(|x| x.to_f64()).collect(),
            err,
        )
    })
}

#[test]
fn big_net_steps_the_same_on_one_and_two_threads() {
    let (lay, pos) = Layout::build(&net(26, 4)).unwrap();
    let big = lay
        .blocks
        .iter()
        .map(|b| (b.node_end - b.node_start) as usize)
        .max()
        .unwrap();
    assert!(
        big >= 4096 && !lay.blocks[0].is_chain,
        "one block of {big} nodes"
    );
    let dt = 0.8 * stable_step(&lay, Scheme::Symplectic, Baumgarte::default()).dt;
    let opts = SolverOptions {
        dt,
        ..Default::default()
    };
    let (r1, v1, e1) = run(1, &lay, &pos, opts, 400);
    let (r2, v2, e2) = run(2, &lay, &pos, opts, 400);
    assert!(e1.is_none() && e2.is_none(), "{e1:?} {e2:?}");
    let moved = r1
        .iter()
        .zip(&pos)
        .map(|(a, b)| (0..3).map(|d| (a[d] - b[d]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "the net must move: {moved} m");
    assert!(
        r1 == r2 && v1 == v2,
        "positions or velocities differ between 1 and 2 threads"
    );

    // A step far too large blows up: both name the same node and time.
    let fast = SolverOptions {
        dt: 20.0 * dt,
        ..Default::default()
    };
    let (_, _, e1) = run(1, &lay, &pos, fast, 400);
    let (_, _, e2) = run(2, &lay, &pos, fast, 400);
    assert!(e1.is_some(), "a step 20x the stable one must blow up");
    assert_eq!(e1, e2);
}
