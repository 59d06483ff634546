//! Static equilibrium of the discrete model: relaxed lines stay still under the dynamic
//! solver, and the relaxed mooring line converges to the analytic catenary.

use super::common::dist;
use cablesim::cpu::CpuSolver;
use cablesim::model::{
    CableDef, Current, Environment, Layout, LineType, ModelDef, NodeDef, PointMass, Route, Seabed,
};
use cablesim::options::{Scheme, SolverOptions};
use cablesim::physics::catenary::{catenary, catenary_positions, straight_positions};
use cablesim::statics::{relax, static_forces, Method, RelaxOptions, RelaxReport};

const ANCHOR: [f64; 3] = [-220.0, 0.0, -100.0];
const FAIRLEAD: [f64; 3] = [0.0, 0.0, -10.0];
const LENGTH: f64 = 250.0;

/// The catenary example's line type.
fn chain() -> LineType {
    LineType {
        name: "chain".into(),
        diameter: 0.04,
        mass_per_length: 5.0265,
        ea: 6.2832e7,
        damping: 1e-5,
        cn: 1.0,
        ct: 0.01,
        cm: 0.2,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    }
}

fn env(depth: f64) -> Environment {
    Environment {
        gravity: 9.81,
        water_density: 1025.0,
        depth,
        seabed: Seabed {
            stiffness: 3e6,
            damping: 3e4,
            friction: 0.0,
            friction_velocity: 0.01,
            ..Seabed::default()
        },
    }
}

fn wet_weight(lt: &LineType) -> f64 {
    lt.wet_weight_per_length(9.81, 1025.0)
}

fn node(position: [f64; 3], fixed: bool) -> NodeDef {
    NodeDef {
        position,
        point: PointMass::default(),
        route: fixed.then_some(Route::Fixed { position }),
        label: None,
    }
}

/// One cable through `pts`, ends fixed, `length / n` per element.
fn single_line(pts: &[[f64; 3]], length: f64, depth: f64, current: [f64; 3]) -> ModelDef {
    let n = pts.len() - 1;
    ModelDef {
        env: env(depth),
        line_types: vec![chain()],
        currents: vec![Current::uniform(current)],
        nodes: pts
            .iter()
            .enumerate()
            .map(|(k, &p)| node(p, k == 0 || k == n))
            .collect(),
        cables: vec![CableDef {
            name: "line".into(),
            line_type: 0,
            nodes: (0..=n).collect(),
            l0: vec![length / n as f64; n],
            current: 0,
            output_positions: true,
            elem_lines: Vec::new(),
        }],
        clamps: Vec::new(),
        joints: Vec::new(),
        screens: Default::default(),
    }
}

/// The catenary example's mooring line, first guess from the analytic catenary.
fn mooring(n: usize, current: [f64; 3]) -> (Layout, Vec<[f64; 3]>) {
    let lt = chain();
    let pts = catenary_positions(ANCHOR, FAIRLEAD, LENGTH, n, lt.ea, wet_weight(&lt), -100.0);
    Layout::build(&single_line(&pts, LENGTH, 100.0, current)).unwrap()
}

fn relaxed(lay: &Layout, pos: &mut [[f64; 3]]) -> RelaxReport {
    let rep = relax(lay, pos, &RelaxOptions::default()).unwrap();
    assert!(rep.converged, "{rep:?}");
    rep
}

/// Time step of the dynamic checks. The symplectic scheme is stable for
/// `(omega dt)^2 + 2 gamma dt < 4` (docs/src/model/time_stepping.md); on a grounded node
/// of the 5 m chain the seabed damping alone has `gamma = C lt / m = 3e4 * 5 / 25.1
/// = 6e3 /s`, so with the contact explicit 1e-3 s was unstable there (a grounded node's
/// velocity grew 4.7-fold per step) and the limit with the axial and seabed stiffness was
/// about 3.1e-4 s. The symplectic scheme now takes the seabed's damping implicitly
/// (docs/src/model/seabed.md); the checks keep the small step they were written with.
const DT: f64 = 2e-4;

/// Runs the symplectic solver (step [`DT`]) for `seconds` from rest at `pos`; returns
/// the largest node displacement seen and the largest relative change of any reaction
/// (checked once per simulated 0.1 s).
fn run_still(lay: &Layout, pos: &[[f64; 3]], seconds: f64) -> (f64, f64) {
    let opts = SolverOptions {
        scheme: Scheme::Symplectic,
        dt: DT,
        ..SolverOptions::default()
    };
    let mut s = CpuSolver::new(lay.clone(), pos, opts);
    let r0 = s.evaluate().unwrap().reaction;
    let (mut max_disp, mut max_react) = (0.0f64, 0.0f64);
    let chunks = (seconds / 0.1).round() as usize;
    for _ in 0..chunks {
        s.advance((0.1 / DT).round() as u64).unwrap();
        for (i, p) in pos.iter().enumerate() {
            max_disp = max_disp.max(dist(s.r[i].to_f64(), *p));
        }
        let r = s.evaluate().unwrap().reaction;
        for (a, b) in r.iter().zip(&r0) {
            max_react = max_react.max(dist(*a, *b) / dist(*b, [0.0; 3]));
        }
    }
    (max_disp, max_react)
}

/// (a) The relaxed catenary mooring line stays still under the dynamic solver; the
/// analytic first guess alone does not.
#[test]
fn relaxed_mooring_line_stays_still() {
    let (lay, guess) = mooring(50, [0.0; 3]);
    let mut pos = guess.clone();
    let rep = relaxed(&lay, &mut pos);
    assert_eq!(rep.blocks[0].method, Method::Chain);
    println!(
        "mooring line, 50 segments: {} Newton iterations, residual {:.3e} N (tolerance {:.3e} N)",
        rep.iterations, rep.max_residual, rep.blocks[0].tolerance
    );
    let (disp, react) = run_still(&lay, &pos, 10.0);
    println!("relaxed: max displacement {disp:.3e} m, max reaction change {react:.3e} over 10 s");
    assert!(disp < 1e-4, "relaxed line moved {disp} m");
    assert!(react < 1e-3, "reactions changed by {react}");
    // Control: the unrelaxed analytic shape rings.
    let (disp0, react0) = run_still(&lay, &guess, 1.0);
    println!(
        "unrelaxed: max displacement {disp0:.3e} m, max reaction change {react0:.3e} over 1 s"
    );
    assert!(disp0 > 1e-2 && react0 > 1e-2);
}

/// Touchdown estimates of a relaxed line (horizontal distance from the anchor):
/// * by node: the last grounded node (error up to one element length);
/// * interpolated: node `k`, the last grounded one, stands for the tributary stretch
///   `[s_k - l0/2, s_k + l0/2]` of line, and the seabed carries the fraction `R_k / W_k`
///   of its weight, so the grounded part ends `(R_k / W_k - 1/2)` of an element past
///   node `k` (`R_k` its contact force, `W_k` its wet weight).
fn touchdown(lay: &Layout, pos: &[[f64; 3]], w: f64) -> (f64, f64) {
    let zb = -100.0;
    let k = pos
        .iter()
        .rposition(|p| p[2] < zb)
        .expect("a grounded node");
    let by_node = pos[k][0] - ANCHOR[0];
    let lt = lay.node_tributary[k];
    let contact = lay.env.seabed.stiffness * lt * (zb - pos[k][2]);
    let frac = contact / (w * lt);
    let dx = pos[k][0] - pos[k - 1][0];
    (by_node, by_node + (frac - 0.5) * dx)
}

/// (b) The relaxed discrete line's fairlead force and touchdown point converge to the
/// analytic catenary as segments increase.
#[test]
fn relaxed_line_converges_to_the_analytic_catenary() {
    let lt = chain();
    let w = wet_weight(&lt);
    let c = catenary(220.0, 90.0, LENGTH, lt.ea, w, true).unwrap();
    println!(
        "analytic: HF {:.3} N, VF {:.3} N, touchdown {:.4} m from the anchor",
        c.hf, c.vf, c.touchdown
    );
    println!(
        "segments |  HF error  |  VF error  | touchdown error: by node, interpolated | Newton its"
    );
    let mut errs = Vec::new();
    for n in [10, 20, 50, 100] {
        let (lay, mut pos) = mooring(n, [0.0; 3]);
        let rep = relaxed(&lay, &mut pos);
        let mut s = CpuSolver::new(lay.clone(), &pos, SolverOptions::default());
        let ev = s.evaluate().unwrap();
        // Constraint 1 holds the fairlead (node n): the cable pulls it towards the
        // anchor (-x) and down.
        let f = ev.reaction[1];
        assert!(f[0] < 0.0 && f[2] < 0.0 && f[1].abs() < 1e-9 * c.hf);
        let eh = (-f[0] - c.hf).abs() / c.hf;
        let ev_ = (-f[2] - c.vf).abs() / c.vf;
        let (td_node, td) = touchdown(&lay, &pos, w);
        let (et_node, et) = ((td_node - c.touchdown).abs(), (td - c.touchdown).abs());
        println!(
            "{n:8} | {eh:10.3e} | {ev_:10.3e} | {et_node:9.4} m  {et:10.3e} m | {}",
            rep.iterations
        );
        // No seabed friction: the anchor feels the same horizontal pull.
        let ha = ev.reaction[0][0];
        assert!((ha + f[0]).abs() < 1e-8 * c.hf, "{ha} vs {}", f[0]);
        // The last grounded node is within an element of the analytic touchdown.
        assert!(et_node < LENGTH / n as f64, "{n}: {et_node}");
        errs.push((n, eh, ev_, et));
    }
    for w2 in errs.windows(2) {
        let ((n0, h0, v0, t0), (n1, h1, v1, t1)) = (w2[0], w2[1]);
        assert!(
            h1 < h0 && v1 < v0,
            "force error grew from {n0} to {n1} segments"
        );
        assert!(t1 < t0, "touchdown error grew from {n0} to {n1} segments");
    }
    let (_, h50, v50, t50) = errs[2];
    assert!(h50 < 5e-3 && v50 < 5e-3, "50 segments: {h50} {v50}");
    assert!(t50 < 0.05, "touchdown error at 50 segments: {t50} m");
}

/// (c) A vertical cable with an end mass: the top reaction is the wet weight of cable
/// and mass, and the stretch is the analytic one.
#[test]
fn vertical_cable_with_end_mass() {
    let lt = chain();
    let w = wet_weight(&lt);
    let (n, l) = (20, 100.0);
    let top = [3.0, -2.0, -10.0];
    let bottom = [3.0, -2.0, -10.0 - l];
    let mut def = single_line(&straight_positions(top, bottom, n), l, 1000.0, [0.0; 3]);
    let (mass, volume) = (1000.0, 0.05);
    def.nodes[n].route = None;
    def.nodes[n].point = PointMass {
        mass,
        volume,
        drag_area: 0.0,
        added_mass_coef: 1.0,
    };
    let (lay, mut pos) = Layout::build(&def).unwrap();
    let rep = relaxed(&lay, &mut pos);
    let p = (mass - 1025.0 * volume) * 9.81;
    let weight = w * l + p;
    let mut s = CpuSolver::new(lay.clone(), &pos, SolverOptions::default());
    let top_force = s.evaluate().unwrap().reaction[0];
    println!(
        "top reaction {top_force:?}, wet weight {weight:.6} N, residual {:.3e} N",
        rep.max_residual
    );
    assert!((top_force[2] + weight).abs() < 1e-8 * weight);
    assert!(top_force[0].abs() < 1e-8 * weight && top_force[1].abs() < 1e-8 * weight);
    // The discrete chain's stretch equals the continuous (P L + w L^2 / 2) / EA.
    let stretch = (p * l + 0.5 * w * l * l) / lt.ea;
    let end = pos[lay.cables[0].nodes[n] as usize];
    assert!(
        (end[2] - (bottom[2] - stretch)).abs() < 1e-8,
        "bottom at {end:?}, stretch {stretch}"
    );
    assert!((end[0] - 3.0).abs() < 1e-9 && (end[1] + 2.0).abs() < 1e-9);
    let (disp, _) = run_still(&lay, &pos, 2.0);
    assert!(disp < 1e-5, "moved {disp} m");
}

/// A 3x3 net of knots 10 m apart at z = -50, each side a 12 m cable of 4 elements,
/// corners held; the cables start straight (and slack) in the horizontal plane.
fn net() -> ModelDef {
    let mut def = ModelDef {
        env: env(100.0),
        line_types: vec![chain()],
        currents: vec![Current::uniform([0.0; 3])],
        ..ModelDef::default()
    };
    let knot = |i: usize, j: usize| 3 * i + j;
    for i in 0..3 {
        for j in 0..3 {
            let corner = (i == 0 || i == 2) && (j == 0 || j == 2);
            def.nodes
                .push(node([10.0 * i as f64, 10.0 * j as f64, -50.0], corner));
        }
    }
    let mut links = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            if i < 2 {
                links.push((knot(i, j), knot(i + 1, j)));
            }
            if j < 2 {
                links.push((knot(i, j), knot(i, j + 1)));
            }
        }
    }
    for (c, (a, b)) in links.into_iter().enumerate() {
        let pts = straight_positions(def.nodes[a].position, def.nodes[b].position, 4);
        let mut nodes = vec![a];
        for p in &pts[1..4] {
            def.nodes.push(node(*p, false));
            nodes.push(def.nodes.len() - 1);
        }
        nodes.push(b);
        def.cables.push(CableDef {
            name: format!("side{c}"),
            line_type: 0,
            nodes,
            l0: vec![3.0; 4],
            current: 0,
            output_positions: true,
            elem_lines: Vec::new(),
        });
    }
    def
}

/// (d) A small net (a non-chain block) relaxes by dense Newton and by dynamic
/// relaxation to the same shape, which then stays still.
#[test]
fn net_relaxes_and_stays_still() {
    let (lay, start) = Layout::build(&net()).unwrap();
    assert_eq!(lay.blocks.len(), 1);
    assert!(!lay.blocks[0].is_chain);
    let mut pos = start.clone();
    let rep = relaxed(&lay, &mut pos);
    assert_eq!(rep.blocks[0].method, Method::Dense);
    println!(
        "net, dense Newton: {} iterations, residual {:.3e} N (tolerance {:.3e} N)",
        rep.iterations, rep.max_residual, rep.blocks[0].tolerance
    );
    // It sagged, and the corners carry the whole wet weight (12 cables of 12 m).
    let w = wet_weight(&chain());
    let f = static_forces(&lay, &pos);
    let total: f64 = lay.constraint_node.iter().map(|&k| f[k as usize][2]).sum();
    assert!((total + w * 144.0).abs() < 1e-6 * w * 144.0, "{total}");
    // Symmetric shape: the centre knot stays above the centre of the square.
    let centre = pos[start
        .iter()
        .position(|p| *p == [10.0, 10.0, -50.0])
        .unwrap()];
    assert!((centre[0] - 10.0).abs() < 1e-6 && (centre[1] - 10.0).abs() < 1e-6);
    assert!(centre[2] < -55.0, "centre knot at {centre:?}");
    let (disp, react) = run_still(&lay, &pos, 10.0);
    println!("net: max displacement {disp:.3e} m, reaction change {react:.3e} over 10 s");
    assert!(disp < 1e-4 && react < 1e-3, "{disp} {react}");

    // Dynamic relaxation (forced by a zero dense limit) finds the same equilibrium.
    let mut pos_dr = start.clone();
    let opts = RelaxOptions {
        max_dense_dof: 0,
        ..RelaxOptions::default()
    };
    let rep_dr = relax(&lay, &mut pos_dr, &opts).unwrap();
    assert_eq!(rep_dr.blocks[0].method, Method::DynamicRelaxation);
    println!(
        "net, dynamic relaxation: {} iterations, residual {:.3e} N",
        rep_dr.blocks[0].dr_iterations, rep_dr.max_residual
    );
    let gap = pos
        .iter()
        .zip(&pos_dr)
        .map(|(a, b)| dist(*a, *b))
        .fold(0.0, f64::max);
    assert!(gap < 1e-5, "dense and DR equilibria differ by {gap} m");
}

/// (e) Newton (through its stiffness continuation) and dynamic relaxation reach the
/// same equilibrium from a straight first guess, where every element is slack.
#[test]
fn mooring_line_relaxes_from_a_straight_guess() {
    let n = 50;
    let (lay, mut pos_cat) = mooring(n, [0.0; 3]);
    relaxed(&lay, &mut pos_cat);
    let mut pos = straight_positions(ANCHOR, FAIRLEAD, n);
    let rep = relaxed(&lay, &mut pos);
    println!(
        "from a straight guess: {} Newton iterations, residual {:.3e} N",
        rep.iterations, rep.max_residual
    );
    let gap = pos
        .iter()
        .zip(&pos_cat)
        .map(|(a, b)| dist(*a, *b))
        .fold(0.0, f64::max);
    assert!(gap < 1e-6, "equilibria differ by {gap} m");
    // Dynamic relaxation alone gets there too.
    let mut pos_dr = straight_positions(ANCHOR, FAIRLEAD, n);
    let opts = RelaxOptions {
        force_dynamic_relaxation: true,
        ..RelaxOptions::default()
    };
    let rep = relax(&lay, &mut pos_dr, &opts).unwrap();
    assert_eq!(rep.blocks[0].method, Method::DynamicRelaxation);
    let gap = pos_dr
        .iter()
        .zip(&pos_cat)
        .map(|(a, b)| dist(*a, *b))
        .fold(0.0, f64::max);
    println!(
        "dynamic relaxation from a straight guess: {} iterations, residual {:.3e} N, {gap:.2e} m from Newton's",
        rep.dr_iterations, rep.max_residual
    );
    assert!(gap < 1e-5, "equilibria differ by {gap} m");
}

/// (f) With a current across the line's plane the relaxed shape includes the drag,
/// and stays still too.
#[test]
fn mooring_line_in_a_cross_current_stays_still() {
    let (lay, mut pos) = mooring(40, [0.3, 0.5, 0.0]);
    let rep = relaxed(&lay, &mut pos);
    // Pushed sideways (+y) by the current.
    let mid = pos[30];
    assert!(mid[1] > 0.1, "{mid:?}");
    println!(
        "cross current: {} Newton iterations, residual {:.3e} N, node 30 at {mid:?}",
        rep.iterations, rep.max_residual
    );
    let (disp, react) = run_still(&lay, &pos, 5.0);
    assert!(disp < 1e-4 && react < 1e-3, "{disp} {react}");
}

/// Many independent blocks are relaxed together, each to its own tolerance, and a
/// block with every node held is left alone.
#[test]
fn independent_blocks_and_errors() {
    let lt = chain();
    let w = wet_weight(&lt);
    let mut def = ModelDef {
        env: env(100.0),
        line_types: vec![lt.clone()],
        currents: vec![Current::uniform([0.0; 3])],
        ..ModelDef::default()
    };
    for k in 0..6 {
        let y = 50.0 * k as f64;
        let a = [-220.0, y, -100.0];
        let b = [0.0 - 5.0 * k as f64, y, -10.0];
        let pts = catenary_positions(a, b, LENGTH, 25, lt.ea, w, -100.0);
        let base = def.nodes.len();
        for (j, p) in pts.iter().enumerate() {
            def.nodes.push(node(*p, j == 0 || j == 25));
        }
        def.cables.push(CableDef {
            name: format!("line{k}"),
            line_type: 0,
            nodes: (base..base + 26).collect(),
            l0: vec![LENGTH / 25.0; 25],
            current: 0,
            output_positions: true,
            elem_lines: Vec::new(),
        });
    }
    // A taut two-node cable: both ends held.
    let base = def.nodes.len();
    def.nodes.push(node([0.0, -50.0, -20.0], true));
    def.nodes.push(node([10.0, -50.0, -20.0], true));
    def.cables.push(CableDef {
        name: "held".into(),
        line_type: 0,
        nodes: vec![base, base + 1],
        l0: vec![10.0],
        current: 0,
        output_positions: true,
        elem_lines: Vec::new(),
    });
    let (lay, mut pos) = Layout::build(&def).unwrap();
    let rep = relaxed(&lay, &mut pos);
    assert_eq!(rep.blocks.len(), 7);
    assert_eq!(rep.blocks[6].method, Method::Fixed);
    assert!(rep.blocks[..6].iter().all(|b| b.method == Method::Chain));
    let f = static_forces(&lay, &pos);
    for (i, fi) in f.iter().enumerate() {
        if lay.node_constraint[i] == cablesim::model::NO_CONSTRAINT {
            assert!(dist(*fi, [0.0; 3]) <= rep.max_residual);
        }
    }
    // Too few iterations: an error naming the cable.
    let mut pos2 = straight_positions(ANCHOR, FAIRLEAD, 25);
    pos2.extend(pos[26..].iter().copied());
    let opts = RelaxOptions {
        max_iterations: 2,
        ..RelaxOptions::default()
    };
    let err = relax(&lay, &mut pos2, &opts).unwrap_err().to_string();
    assert!(
        err.contains("line0") && err.contains("did not converge"),
        "{err}"
    );
    // Wrong length.
    assert!(relax(&lay, &mut pos[..3].to_vec(), &RelaxOptions::default()).is_err());
}

/// A model built without the scenario's checks (which refuse such inputs by name):
/// a free middle node carrying a point mass whose weight, 9.81e200 N, has a square
/// that overflows f64. The statics' error says so, at that node, with the value,
/// rather than guessing at a zero-length element.
#[test]
fn a_static_force_that_overflows_says_which_load() {
    let mid = [-110.0, 0.0, -80.0];
    let mut def = single_line(&[ANCHOR, mid, FAIRLEAD], LENGTH, 100.0, [0.0; 3]);
    def.nodes[1].point = PointMass {
        mass: 1e200,
        ..PointMass::default()
    };
    let (lay, mut pos) = Layout::build(&def).unwrap();
    let e = relax(&lay, &mut pos, &RelaxOptions::default())
        .unwrap_err()
        .to_string();
    println!("{e}");
    assert!(
        e.contains("non-finite static force at cable 'line', node 1")
            && e.contains("point load")
            && e.contains("e200")
            && !e.contains("zero-length"),
        "{e}"
    );
}
