//! GPU f64 against the CPU f64 reference path, run for run.
//!
//! Contract (the round-off bound of `compare`): the same physics in the same order of passes; the arithmetic differs only
//! in round-off (positions relative to a block origin and kept as compensated pairs,
//! routes rebased to each submission's start, the shaders' own sine and cosine, the
//! strain formed as `(l - l0) / l0`, fused or reordered operations in the driver).
//! Each of these perturbs a step by a few ulps of the quantity involved: positions by
//! about `eps L` (`eps = 2^-52`, `L` the largest coordinate relative to the origin),
//! velocities by `eps V` (`V` the largest speed). A stable, damped model does not
//! amplify such perturbations exponentially, so after `N` steps the two runs differ by
//! at most about `N eps L` in position, times a constant for the number of operations
//! per step that round differently, taken as 10 below. (A damped line forgets old
//! perturbations, so the measured differences stay far below this bound, flat in `N`:
//! about 2e-12 m after 1000 to 16000 steps of the line below, where the CPU's own two
//! f64 paths, chain kernel and general, differ by about 5e-13 m. The bound does not
//! hold for a model that amplifies round-off exponentially, such as the violently
//! released line of tests/cpu/chain_kernel.rs past 3000 steps, where the two CPU paths
//! part just as fast.) A position difference `dr` in the fastest mode (the
//! axial mode of the shortest element, `omega_max = 2 / dt_stable` from
//! `stability::stable_step`) comes with a velocity difference `omega_max dr`, plus the
//! velocity's own `N eps V`; it changes a strain by `dr / l0_min`, so a tension by
//! `EA dr / l0_min`, plus the strain's own round-off `eps EA` and `eps T_max`.
//! Reactions (`F - M a` at driven nodes) get the tension tolerance.

use super::common::*;
use super::compare::{dist, RoundOff, Snapshot};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::model::{
    CableDef, Current, Environment, Layout, ModelDef, NodeDef, PointMass, Route,
};
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use std::path::Path;

const CATENARY: &str = include_str!("../../examples/catenary.toml");

const EPS: f64 = f64::EPSILON;

/// The catenary example (examples/catenary.toml, relaxed to its static equilibrium)
/// made dynamic: the fairlead driven round a 5 m circle, a current profile, seabed
/// friction, and a clump weight with drag half way along.
fn line_model() -> (Layout, Vec<[f64; 3]>) {
    let sc = Scenario::parse(CATENARY, Path::new("examples/catenary.toml")).unwrap();
    let (mut lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let fair = lay.cables[0].nodes[50] as usize;
    let c = lay.node_constraint[fair] as usize;
    let p = pos[fair];
    lay.routes[c] = Route::Circle {
        center: [p[0], p[1] + 5.0, p[2]],
        radius: 5.0,
        period: 20.0,
        axis: [0.0, 0.0, 1.0],
        phase: -std::f64::consts::FRAC_PI_2,
        advance: 0.0,
    };
    lay.env.seabed.friction = 0.5;
    lay.currents[0] = Current {
        table: vec![
            (-100.0, [0.1, 0.0, 0.0]),
            (-50.0, [0.4, 0.2, 0.0]),
            (0.0, [0.8, 0.3, 0.0]),
        ],
    };
    let clump = lay.cables[0].nodes[30] as usize;
    let rho = lay.env.water_density;
    let (m, vol, cd_a, ca) = (200.0, 0.02, 0.5, 1.0);
    lay.node_point_mass[clump] = m + ca * rho * vol;
    lay.node_point_weight_z[clump] = -(m - rho * vol) * lay.env.gravity;
    lay.node_point_drag[clump] = 0.5 * rho * cd_a;
    (lay, pos)
}

/// A square net of `k x k` knots, `spacing` apart, joined by cables of `seg` elements
/// along rows and columns (the knots are shared nodes); three corners fixed, the
/// fourth towed along a line, a buoy with drag at the centre knot, a uniform current,
/// and a second, separate line in the same run (two blocks).
fn net_model() -> (Layout, Vec<[f64; 3]>) {
    let (k, seg, spacing, z0) = (4usize, 4usize, 20.0, -40.0);
    let env = Environment {
        depth: 60.0,
        ..Environment::default()
    };
    let mut lt = wire();
    lt.ea = 2.0e6;
    lt.damping = 2e-3;
    lt.cm = 1.0;
    let mut nodes = Vec::new();
    let knot = |i: usize, j: usize| i * k + j;
    for i in 0..k {
        for j in 0..k {
            nodes.push(NodeDef {
                position: [j as f64 * spacing, i as f64 * spacing, z0],
                point: PointMass::default(),
                route: None,
                label: None,
            });
        }
    }
    let corner = |i: usize, j: usize| [j as f64 * spacing, i as f64 * spacing, z0];
    nodes[knot(0, 0)].route = Some(Route::Fixed {
        position: corner(0, 0),
    });
    nodes[knot(0, k - 1)].route = Some(Route::Fixed {
        position: corner(0, k - 1),
    });
    nodes[knot(k - 1, 0)].route = Some(Route::Fixed {
        position: corner(k - 1, 0),
    });
    nodes[knot(k - 1, k - 1)].route = Some(Route::Line {
        start: corner(k - 1, k - 1),
        velocity: [0.5, 0.3, 0.2],
    });
    nodes[knot(1, 1)].point = PointMass {
        mass: 50.0,
        volume: 0.3,
        drag_area: 0.5,
        added_mass_coef: 0.5,
    };
    let mut cables = Vec::new();
    let mut add_cable = |nodes: &mut Vec<NodeDef>, a: usize, b: usize, name: String| {
        let (pa, pb) = (nodes[a].position, nodes[b].position);
        let mut chain = vec![a];
        for s in 1..seg {
            let f = s as f64 / seg as f64;
            // A little sag so the elements start slack-free but not straight.
            let mut p = [0, 1, 2].map(|d| pa[d] + f * (pb[d] - pa[d]));
            p[2] -= 2.0 * (std::f64::consts::PI * f).sin();
            nodes.push(NodeDef {
                position: p,
                point: PointMass::default(),
                route: None,
                label: None,
            });
            chain.push(nodes.len() - 1);
        }
        chain.push(b);
        cables.push(CableDef {
            name,
            line_type: 0,
            nodes: chain,
            l0: vec![spacing / seg as f64 * 1.02; seg],
            current: 0,
            output_positions: true,
            elem_lines: Vec::new(),
        });
    };
    for i in 0..k {
        for j in 0..k - 1 {
            add_cable(
                &mut nodes,
                knot(i, j),
                knot(i, j + 1),
                format!("row{i}_{j}"),
            );
            add_cable(
                &mut nodes,
                knot(j, i),
                knot(j + 1, i),
                format!("col{i}_{j}"),
            );
        }
    }
    // A separate hanging line: a second block, on its own origin.
    let top = nodes.len();
    for s in 0..=10 {
        nodes.push(NodeDef {
            position: [300.0 + 3.0 * s as f64, -50.0, -5.0 - 4.0 * s as f64],
            point: PointMass::default(),
            route: (s == 0).then_some(Route::Fixed {
                position: [300.0, -50.0, -5.0],
            }),
            label: None,
        });
    }
    cables.push(CableDef {
        name: "hanging".into(),
        line_type: 0,
        nodes: (top..=top + 10).collect(),
        l0: vec![5.0; 10],
        current: 0,
        output_positions: true,
        elem_lines: Vec::new(),
    });
    let def = ModelDef {
        env,
        line_types: vec![lt],
        currents: vec![Current::uniform([0.3, -0.2, 0.0])],
        nodes,
        cables,
        clamps: Vec::new(),
        joints: Vec::new(),
        screens: Default::default(),
    };
    Layout::build(&def).unwrap()
}

/// Runs the CPU path and the GPU path on each kernel (the fused one, asserted to be
/// what `GpuSolver` picks for these models, and the two-pass one) for `steps` steps
/// and asserts the round-off contract of the module doc on each (`ea` the line's
/// axial stiffness, N).
fn compare(
    ctx: &cablesim::gpu::GpuContext,
    name: &str,
    lay: Layout,
    pos: &[[f64; 3]],
    opts: SolverOptions,
    steps: u64,
    ea: f64,
) {
    for kernel in [GpuKernel::Fused, GpuKernel::TwoPass] {
        compare_on(ctx, name, lay.clone(), pos, opts, steps, ea, kernel);
    }
}

#[allow(clippy::too_many_arguments)]
fn compare_on(
    ctx: &cablesim::gpu::GpuContext,
    name: &str,
    lay: Layout,
    pos: &[[f64; 3]],
    opts: SolverOptions,
    steps: u64,
    ea: f64,
    kernel: GpuKernel,
) {
    let omega = 2.0 / cablesim::stability::stable_step(&lay, opts.scheme, opts.baumgarte).dt;
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut cpu = CpuSolver::new(lay.clone(), pos, opts);
    cpu.use_chain_kernel = false;
    let mut gpu = GpuSolver::new(ctx, lay.clone(), pos, opts, Precision::F64).unwrap();
    if kernel == GpuKernel::Fused {
        assert_eq!(gpu.kernel(), kernel, "{:?}", gpu.fused_unavailable());
    }
    gpu.set_kernel(kernel).unwrap();
    // Several advance calls of uneven length: submissions and rebasing at odd steps.
    let mut done = 0;
    for n in [1u64, 700, 299, 1000].iter().cycle() {
        let n = (*n).min(steps - done);
        if n == 0 {
            break;
        }
        cpu.advance(n).unwrap();
        gpu.advance(n).unwrap();
        done += n;
    }
    assert_eq!(gpu.steps(), cpu.steps());
    let c = Snapshot::cpu("CPU f64", &mut cpu);
    let g = Snapshot::gpu(format!("GPU f64 {}", kernel.name()), &mut gpu);
    let moved =
        c.r.iter()
            .zip(pos)
            .map(|(a, b)| dist(*a, *b))
            .fold(0.0f64, f64::max);
    assert!(moved > 0.01, "the model should move: {moved} m");
    let bounds = RoundOff::new(&lay, &c, steps, EPS, ea, l0_min, omega);
    let name = format!("{name} ({})", kernel.name());
    let d = bounds.check(&name, &lay, &g, &c);
    eprintln!(
        "{name}: {steps} steps, largest displacement {moved:.3} m, omega_max {omega:.0} rad/s, max T {:.3e} N: {}",
        bounds.scale_t,
        d.report(&lay)
    );
}

#[test]
fn gpu_f64_matches_cpu_f64_on_a_line() {
    let Some(ctx) = gpu_context("gpu_f64_matches_cpu_f64_on_a_line", true) else {
        return;
    };
    let (lay, pos) = line_model();
    // The example's automatic step.
    let opts = SolverOptions {
        dt: 2.5e-4,
        ..Default::default()
    };
    let steps = 4000;
    compare(&ctx, "line", lay, &pos, opts, steps, wire().ea);
}

/// The same line at its automatic step (0.8 of the axial waves' bound, 4x the step the
/// seabed's damping allowed when it was explicit): the grounded nodes, sliding and
/// creeping under friction, take the contact's damping implicitly on both paths.
#[test]
fn gpu_f64_matches_cpu_f64_on_a_line_at_its_auto_step() {
    let Some(ctx) = gpu_context("gpu_f64_matches_cpu_f64_on_a_line_at_its_auto_step", true) else {
        return;
    };
    let (lay, pos) = line_model();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    assert!(bound.term.starts_with("axial waves"), "{}", bound.term);
    let opts = SolverOptions {
        dt: cablesim::stability::AUTO_SAFETY * bound.dt,
        ..Default::default()
    };
    let zb = -lay.env.depth;
    let grounded = pos.iter().filter(|p| p[2] < zb).count();
    assert!(grounded >= 3, "{grounded} nodes on the seabed");
    compare(&ctx, "line, auto step", lay, &pos, opts, 2000, wire().ea);
}

#[test]
fn gpu_f64_matches_cpu_f64_on_a_net() {
    let Some(ctx) = gpu_context("gpu_f64_matches_cpu_f64_on_a_net", true) else {
        return;
    };
    let (lay, pos) = net_model();
    assert!(lay.blocks.len() == 2 && !lay.blocks[0].is_chain);
    let opts = SolverOptions {
        dt: 2e-4,
        ..Default::default()
    };
    let steps = 3000;
    compare(&ctx, "net", lay, &pos, opts, steps, 2.0e6);
}

/// The line of [`gpu_f64_matches_cpu_f64_on_a_line`] with its fairlead on a table
/// route instead of the circle: samples at uneven times that no step lands on (so both
/// paths take the same segment at every step; at a sample time itself they could
/// differ by one ulp of `t` and pick the two sides of a velocity jump), crossed many
/// times per submission and at odd rebase steps, then held after the last sample.
#[test]
fn gpu_f64_matches_cpu_f64_with_a_table_route() {
    let Some(ctx) = gpu_context("gpu_f64_matches_cpu_f64_with_a_table_route", true) else {
        return;
    };
    let (mut lay, pos) = line_model();
    let fair = lay.cables[0].nodes[50] as usize;
    let c = lay.node_constraint[fair] as usize;
    let p = pos[fair];
    let (mut t, mut pts) = (Vec::new(), Vec::new());
    let mut tk = 0.0137;
    while tk < 0.8 {
        // From rest to rest along (0.8, 0.6, 0.2) at up to 1.5 m/s: x = A (t - sin(w t) / w).
        let w = 2.0 * std::f64::consts::PI / 0.8;
        let x = 0.75 * (tk - (w * tk).sin() / w);
        t.push(tk);
        pts.push([p[0] + 0.8 * x, p[1] + 0.6 * x, p[2] + 0.2 * x]);
        tk += 0.0131 + 0.007 * std::f64::consts::SQRT_2 * (t.len() % 3) as f64;
    }
    let opts = SolverOptions {
        dt: 2.5e-4,
        ..Default::default()
    };
    for &tk in &t {
        let steps = tk / opts.dt;
        assert!(
            (steps - steps.round()).abs() > 1e-3,
            "sample at {tk} s is a step time"
        );
    }
    lay.routes[c] = Route::Table { t, p: pts };
    let steps = 4000;
    compare(&ctx, "table route", lay, &pos, opts, steps, wire().ea);
}

/// A step far above the stable one blows up on the GPU as on the CPU: the error names
/// the cable, the node and the time, and the times agree.
#[test]
fn gpu_blow_up_is_reported_like_the_cpu() {
    let Some(ctx) = gpu_context("gpu_blow_up_is_reported_like_the_cpu", false) else {
        return;
    };
    let (lay, pos) = line_model();
    let opts = SolverOptions {
        dt: 2e-2,
        ..Default::default()
    };
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.use_chain_kernel = false;
    let ce = cpu.advance(10_000).unwrap_err();
    for p in [Precision::F32, Precision::F64] {
        if !ctx.supports(p) {
            continue;
        }
        for kernel in [GpuKernel::Fused, GpuKernel::TwoPass] {
            let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
            gpu.set_kernel(kernel).unwrap();
            let ge = gpu.advance(10_000).unwrap_err();
            eprintln!("CPU: {ce}\nGPU {} {}: {ge}", p.name(), kernel.name());
            match (&ce, &ge) {
                (
                    cablesim::Error::Diverged {
                        cable: cc,
                        time: tc,
                        ..
                    },
                    cablesim::Error::Diverged {
                        cable: cg,
                        node,
                        time: tg,
                        ..
                    },
                ) => {
                    assert_eq!(cc, cg);
                    assert!(*node <= 50);
                    // Same step in f64; within a few steps in f32.
                    let slack = if p == Precision::F64 { 0.5 } else { 5.0 } * opts.dt;
                    assert!((tc - tg).abs() <= slack, "CPU at {tc} s, GPU at {tg} s");
                }
                _ => panic!("expected Diverged from both: {ce} / {ge}"),
            }
            let msg = ge.to_string();
            assert!(
                msg.contains("cable 'line1'") && msg.contains("node"),
                "{msg}"
            );
        }
    }
}
