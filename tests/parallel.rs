//! A big network (a net cage: one block of thousands of nodes) has its symplectic GLMF
//! steps split across threads. The split changes nothing: the result equals the
//! single-thread one bit for bit, and a blow-up names the same node and time.

mod common;

use cablesim::cpu::CpuSolver;
use cablesim::model::{
    CableDef, Current, Environment, Layout, ModelDef, NodeDef, PointMass, Route,
};
use cablesim::options::{Baumgarte, Scheme, SolverOptions};
use cablesim::stability::stable_step;
use common::wire;

/// A square net of `k x k` knots 2 m apart, twines of `seg` elements between
/// neighbouring knots, the top row held (one corner towed), sinkers on the bottom row,
/// a seabed the lower part reaches, a current.
fn net(k: usize, seg: usize) -> ModelDef {
    let spacing = 2.0;
    let mut lt = wire();
    lt.diameter = 0.003;
    lt.mass_per_length = 0.01;
    lt.ea = 2.0e4;
    lt.damping = 1e-3;
    let mut nodes: Vec<NodeDef> = Vec::new();
    let knot = |i: usize, j: usize| i * k + j;
    for i in 0..k {
        for j in 0..k {
            let p = [j as f64 * spacing, 0.3 * i as f64, -(i as f64) * spacing];
            nodes.push(NodeDef {
                position: p,
                point: if i == k - 1 {
                    PointMass {
                        mass: 2.0,
                        volume: 2.0e-4,
                        drag_area: 0.01,
                        added_mass_coef: 1.0,
                    }
                } else {
                    PointMass::default()
                },
                route: (i == 0).then_some(Route::Fixed { position: p }),
                label: None,
            });
        }
    }
    nodes[knot(0, k - 1)].route = Some(Route::Line {
        start: nodes[knot(0, k - 1)].position,
        velocity: [0.3, 0.2, 0.0],
    });
    let mut cables = Vec::new();
    let mut twine = |nodes: &mut Vec<NodeDef>, a: usize, b: usize| {
        let (pa, pb) = (nodes[a].position, nodes[b].position);
        let mut chain = vec![a];
        for s in 1..seg {
            let f = s as f64 / seg as f64;
            nodes.push(NodeDef {
                position: [0, 1, 2].map(|d| pa[d] + f * (pb[d] - pa[d])),
                point: PointMass::default(),
                route: None,
                label: None,
            });
            chain.push(nodes.len() - 1);
        }
        chain.push(b);
        cables.push(CableDef {
            name: format!("t{}", cables.len()),
            line_type: 0,
            nodes: chain,
            l0: vec![spacing / seg as f64; seg],
            current: 0,
            output_positions: false,
        });
    };
    for i in 0..k {
        for j in 0..k - 1 {
            twine(&mut nodes, knot(i, j), knot(i, j + 1));
            twine(&mut nodes, knot(j, i), knot(j + 1, i));
        }
    }
    ModelDef {
        env: Environment {
            depth: 2.0 * (k as f64 - 1.5),
            ..Environment::default()
        },
        line_types: vec![lt],
        currents: vec![Current::uniform([0.4, 0.1, 0.0])],
        nodes,
        cables,
    }
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
