//! The fused GPU kernel (one workgroup steps one cable through a whole submission)
//! against the two-pass kernel (two dispatches a step over the packed layout), run for
//! run on the same adapter, and when each is used.
//!
//! Contract: both evaluate the same WGSL functions per element and per node
//! (`element_step`, `gather_*`, `node_advance`) in the same order, from the same
//! values; only where they keep the state differs (workgroup memory and registers, or
//! storage). So they may differ only where the compiler contracts or reorders
//! operations differently in the two shaders, by a few ulps per step, and the
//! round-off bound of `compare` (as in `parity`) applies: after `N` steps positions within `10 N eps L`
//! (`eps` of the precision, `L` the largest coordinate relative to a block origin),
//! velocities within `omega_max` times that plus `10 N eps V`, tensions within
//! `EA dr / l0_min + 100 eps (EA + T_max)`. In f64 on lavapipe they agree to the last
//! bit (the tests print how many values differ). In f32 the f32 contract of
//! `f32_vs_f64` is asserted (nodes within `1e-4` of the cable's length, tensions
//! within 1% plus 0.1% of the cable's largest), and the f64 bound with f32's `eps` as
//! well.

use super::common::*;
use super::compare::{dist, nodes_within_length, Check, Place, RoundOff, Snapshot};
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::model::{
    CableDef, Current, Environment, Layout, LineType, ModelDef, NodeDef, PointMass, Route, Seabed,
};
use cablesim::options::SolverOptions;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const DEPTH: f64 = 60.0;

fn line_types() -> Vec<LineType> {
    let chain = LineType {
        name: "chain".into(),
        diameter: 0.1,
        mass_per_length: 40.0,
        ea: 1.0e8,
        damping: 1e-4,
        cn: 2.4,
        ct: 0.4,
        cm: 1.0,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    let rope = LineType {
        name: "rope".into(),
        diameter: 0.06,
        mass_per_length: 2.5,
        ea: 2.0e6,
        damping: 1e-3,
        cn: 1.2,
        ct: 0.008,
        cm: 1.0,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    let wire = LineType {
        damping: 1e-4,
        ..wire()
    };
    vec![wire, chain, rope]
}

/// `n` moorings drawn from a seeded generator: each from an anchor on the seabed (a
/// fixed route) to a fairlead 5 to 15 m below the surface, longer than the chord so
/// that a stretch of it lies on the seabed (contact with friction), with its own line
/// type, 20 to 100 nodes, its own current (uniform, or a profile for one in three) and
/// a fairlead route cycling through fixed, line, circle and table; one in three has a
/// clump (mass, buoyancy, drag) a third of the way up. Relaxed to static equilibrium
/// before the run.
fn fleet(n: usize, seed: u64) -> (Layout, Vec<[f64; 3]>) {
    fleet_with_profiles(n, seed, 3)
}

/// [`fleet`] with current profiles of `points` points (3: the fleet's own, three
/// depths with random speeds; more: evenly from the seabed to the surface, the same
/// for every profiled cable).
fn fleet_with_profiles(n: usize, seed: u64, points: usize) -> (Layout, Vec<[f64; 3]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut def = ModelDef {
        env: Environment {
            depth: DEPTH,
            seabed: Seabed {
                friction: 0.5,
                ..Seabed::default()
            },
            ..Environment::default()
        },
        line_types: line_types(),
        ..Default::default()
    };
    for c in 0..n {
        let nodes = rng.gen_range(20..=100usize);
        let segments = nodes - 1;
        let x0 = (c % 10) as f64 * 500.0;
        let y0 = (c / 10) as f64 * 500.0;
        let anchor = [x0, y0, -DEPTH];
        let depth_f = rng.gen_range(5.0..15.0);
        let span = rng.gen_range(60.0..160.0);
        let ang = rng.gen_range(0.0..std::f64::consts::TAU);
        let fair = [x0 + span * ang.cos(), y0 + span * ang.sin(), -depth_f];
        let chord = ((span * span) + (DEPTH - depth_f).powi(2)).sqrt();
        let length = chord * rng.gen_range(1.1..1.3);
        let speed = rng.gen_range(0.1..0.4);
        let route = match c % 4 {
            0 => Route::Fixed { position: fair },
            1 => Route::Line {
                start: fair,
                velocity: [speed * ang.cos(), speed * ang.sin(), 0.0],
            },
            2 => {
                let radius = rng.gen_range(1.0..4.0);
                let period = std::f64::consts::TAU * radius / speed;
                let phase: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
                let (e1, e2) = cablesim::model::circle_basis([0.0, 0.0, 1.0]);
                let center = [0, 1, 2]
                    .map(|d| fair[d] - radius * (phase.cos() * e1[d] + phase.sin() * e2[d]));
                Route::Circle {
                    center,
                    radius,
                    period,
                    axis: [0.0, 0.0, 1.0],
                    phase,
                    advance: 0.0,
                }
            }
            _ => {
                let t: Vec<f64> = (0..40).map(|k| k as f64 * 0.1).collect();
                let p = t
                    .iter()
                    .map(|&tk| {
                        [
                            fair[0] + 0.5 * (speed * tk).sin(),
                            fair[1] + 0.3 * (1.0 - (speed * tk).cos()),
                            fair[2] + 0.2 * (2.0 * speed * tk).sin(),
                        ]
                    })
                    .collect();
                Route::Table { t, p }
            }
        };
        let current = if c % 3 == 2 && points > 3 {
            Current {
                table: (0..points)
                    .map(|i| {
                        let z = -DEPTH + DEPTH * i as f64 / (points - 1) as f64;
                        (z, [0.05 + 0.5 * (i as f64 / points as f64), 0.1, 0.0])
                    })
                    .collect(),
            }
        } else if c % 3 == 2 {
            Current {
                table: vec![
                    (-DEPTH, [0.05, 0.0, 0.0]),
                    (-30.0, [0.2, rng.gen_range(-0.2..0.2), 0.0]),
                    (
                        0.0,
                        [rng.gen_range(0.2..0.8), rng.gen_range(-0.5..0.5), 0.0],
                    ),
                ],
            }
        } else {
            Current::uniform([rng.gen_range(-0.5..0.5), rng.gen_range(-0.5..0.5), 0.0])
        };
        def.currents.push(current);
        let clump = (c % 3 == 1).then_some(segments / 3);
        let first = def.nodes.len();
        for k in 0..=segments {
            // A catenary-like start: along the chord, sagged down to the seabed.
            let s = k as f64 / segments as f64;
            let mut p = [0, 1, 2].map(|d| anchor[d] + s * (fair[d] - anchor[d]));
            p[2] = (p[2] - 0.3 * (DEPTH - depth_f) * (std::f64::consts::PI * s).sin()).max(-DEPTH);
            def.nodes.push(NodeDef {
                position: p,
                point: if Some(k) == clump {
                    PointMass {
                        mass: rng.gen_range(100.0..1000.0),
                        volume: 0.05,
                        drag_area: 0.5,
                        added_mass_coef: 1.0,
                    }
                } else {
                    PointMass::default()
                },
                route: if k == 0 {
                    Some(Route::Fixed { position: anchor })
                } else if k == segments {
                    Some(route.clone())
                } else {
                    None
                },
                label: None,
            });
        }
        def.cables.push(CableDef {
            name: format!("m{c}"),
            line_type: c % 3,
            nodes: (first..=first + segments).collect(),
            l0: vec![length / segments as f64; segments],
            current: c,
            output_positions: false,
            elem_lines: Vec::new(),
        });
    }
    let (lay, mut pos) = Layout::build(&def).unwrap();
    let opts = cablesim::statics::RelaxOptions {
        require_convergence: false,
        ..Default::default()
    };
    cablesim::statics::relax(&lay, &mut pos, &opts).unwrap();
    (lay, pos)
}

/// A kernel's state and evaluation after the same uneven `advance` calls.
fn run(
    ctx: &cablesim::gpu::GpuContext,
    lay: &Layout,
    pos: &[[f64; 3]],
    opts: SolverOptions,
    p: Precision,
    kernel: GpuKernel,
    steps: u64,
) -> Snapshot {
    let mut gpu = GpuSolver::new(ctx, lay.clone(), pos, opts, p).unwrap();
    if kernel == GpuKernel::Fused {
        // The fused kernel is the default where it applies.
        assert_eq!(
            gpu.kernel(),
            GpuKernel::Fused,
            "{:?}",
            gpu.fused_unavailable()
        );
    }
    gpu.set_kernel(kernel).unwrap();
    // Uneven advance calls: submissions of odd lengths, routes rebased at odd steps.
    let mut done = 0;
    for n in [1u64, 700, 299, 1000].iter().cycle() {
        let n = (*n).min(steps - done);
        if n == 0 {
            break;
        }
        gpu.advance(n).unwrap();
        done += n;
    }
    let t = gpu.timings();
    match kernel {
        // One dispatch per submission, against two per step.
        GpuKernel::Fused => assert_eq!(t.dispatches, t.submissions),
        GpuKernel::TwoPass => assert_eq!(t.dispatches, 2 * steps),
    }
    Snapshot::gpu(format!("GPU {} {}", p.name(), kernel.name()), &mut gpu)
}

fn compare_kernels(p: Precision) {
    let name = format!("fused_matches_two_pass_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let (lay, pos) = fleet(50, 7);
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = 3000;
    let fused = run(&ctx, &lay, &pos, opts, p, GpuKernel::Fused, steps);
    let two = run(&ctx, &lay, &pos, opts, p, GpuKernel::TwoPass, steps);

    // The scenario does what it is meant to: it moves, and lies on the seabed.
    let moved = fused
        .r
        .iter()
        .zip(&pos)
        .map(|(a, b)| dist(*a, *b))
        .fold(0.0, f64::max);
    let on_bed = fused.r.iter().filter(|r| r[2] < -DEPTH + 1e-3).count();
    assert!(
        moved > 0.05,
        "{name}: the fleet should move: {moved} m (dt {} s)",
        opts.dt
    );
    assert!(on_bed > 100, "{name}: only {on_bed} nodes touch the seabed");
    assert!(lay.cables.iter().any(|c| c.nodes.len() > 64));

    let eps = match p {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    };
    let differ = fused.r.iter().zip(&two.r).filter(|(a, b)| a != b).count()
        + fused.v.iter().zip(&two.v).filter(|(a, b)| a != b).count();

    // The round-off bound of `compare`, with this precision's eps.
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    let ea = lay.line_coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
    let bounds = RoundOff::new(&lay, &two, steps, eps, ea, l0_min, 2.0 / bound.dt);
    let d = bounds.check(&name, &lay, &fused, &two);
    eprintln!(
        "{name}: {} cables, {} nodes, {steps} steps, largest displacement {moved:.3} m, {on_bed} nodes on the seabed; \
         fused vs two-pass: {differ} of {} position and velocity vectors differ at all; {} (max T {:.3e} N)",
        lay.cables.len(),
        lay.n_nodes(),
        2 * lay.n_nodes(),
        d.report(&lay),
        bounds.scale_t,
    );
    if p == Precision::F32 {
        // The f32 contract of tests/gpu/f32_vs_f64.rs, per cable: nodes within 1e-4 of
        // the length, tensions within 1% plus 0.1% of the cable's largest.
        let check = Check::new(&name, &lay, &fused, &two);
        nodes_within_length(&check, &fused.r, &two.r, 1e-4);
        let tmax: Vec<f64> = lay
            .cables
            .iter()
            .map(|c| {
                c.elements
                    .iter()
                    .map(|&e| two.eval.tension[e as usize].abs())
                    .fold(0.0, f64::max)
            })
            .collect();
        check.within(
            "tensions",
            "N",
            Place::Element,
            &fused.eval.tension,
            &two.eval.tension,
            |e| 0.01 * two.eval.tension[e].abs() + 1e-3 * tmax[lay.elem_cable[e] as usize],
        );
    }
}

#[test]
fn fused_matches_two_pass_in_f64() {
    compare_kernels(Precision::F64);
}

#[test]
fn fused_matches_two_pass_in_f32() {
    compare_kernels(Precision::F32);
}

/// Where the fused kernel does not apply, the two-pass one runs, and asking for the
/// fused one says why: a cable longer than the largest workgroup. A small network
/// (shared nodes) within one workgroup is stepped fused.
#[test]
fn fused_kernel_applies_only_where_it_can() {
    let Some(ctx) = gpu_context("fused_kernel_applies_only_where_it_can", false) else {
        return;
    };
    let long = straight_cable(
        vacuum(),
        wire(),
        [0.0; 3],
        [300.0, 0.0, 0.0],
        300.0,
        300,
        Some(Route::Fixed { position: [0.0; 3] }),
        None,
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, pos) = Layout::build(&long).unwrap();
    let mut gpu =
        GpuSolver::new(&ctx, lay, &pos, SolverOptions::default(), Precision::F32).unwrap();
    assert_eq!(gpu.kernel(), GpuKernel::TwoPass);
    let why = gpu.fused_unavailable().expect("a reason").to_string();
    assert!(why.contains("301 nodes"), "{why}");
    assert!(gpu.set_kernel(GpuKernel::Fused).is_err());
    gpu.advance(10).unwrap();
    assert_eq!(gpu.timings().dispatches, 20);

    let short = straight_cable(
        vacuum(),
        wire(),
        [0.0; 3],
        [100.0, 0.0, 0.0],
        100.0,
        100,
        Some(Route::Fixed { position: [0.0; 3] }),
        None,
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, pos) = Layout::build(&short).unwrap();
    let gpu = GpuSolver::new(&ctx, lay, &pos, SolverOptions::default(), Precision::F32).unwrap();
    assert_eq!(gpu.kernel(), GpuKernel::Fused);
}

/// A blow-up in the second of two cables (a stiff, finely meshed chain whose stable
/// step is far below the run's; the first cable is stable at it) is reported alike by
/// both kernels: the same cable and time, a node of that cable; the stable cable
/// stays sane.
#[test]
fn fused_blow_up_names_the_cable_node_and_time() {
    let Some(ctx) = gpu_context("fused_blow_up_names_the_cable_node_and_time", false) else {
        return;
    };
    let mut def = straight_cable(
        Environment::default(),
        wire(),
        [0.0, 0.0, -5.0],
        [0.0, 0.0, -55.0],
        50.0,
        10,
        Some(Route::Fixed {
            position: [0.0, 0.0, -5.0],
        }),
        None,
        PointMass::default(),
        [0.2, 0.0, 0.0],
    );
    let mut chain = line_types()[1].clone();
    chain.ea = 4.0e10;
    def.line_types.push(chain);
    let first = def.nodes.len();
    for k in 0..=40 {
        def.nodes.push(NodeDef {
            position: [100.0, 0.0, -5.0 - 0.5 * k as f64],
            point: PointMass::default(),
            route: (k == 0).then_some(Route::Circle {
                center: [100.0, 2.0, -5.0],
                radius: 2.0,
                period: 5.0,
                axis: [0.0, 0.0, 1.0],
                phase: -std::f64::consts::FRAC_PI_2,
                advance: 0.0,
            }),
            label: None,
        });
    }
    def.cables.push(CableDef {
        name: "stiff".into(),
        line_type: 1,
        nodes: (first..=first + 40).collect(),
        l0: vec![0.5; 40],
        current: 0,
        output_positions: false,
        elem_lines: Vec::new(),
    });
    let (lay, pos) = Layout::build(&def).unwrap();
    let opts = SolverOptions {
        dt: 1e-3,
        ..Default::default()
    };
    let mut errs = Vec::new();
    for p in [Precision::F32, Precision::F64] {
        if !ctx.supports(p) {
            continue;
        }
        for kernel in [GpuKernel::Fused, GpuKernel::TwoPass] {
            let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
            gpu.set_kernel(kernel).unwrap();
            let e = gpu.advance(20_000).unwrap_err();
            eprintln!("{} {}: {e}", p.name(), kernel.name());
            let cablesim::Error::Diverged {
                cable, node, time, ..
            } = e
            else {
                panic!("expected Diverged: {e}");
            };
            assert_eq!(cable, "stiff");
            assert!(node <= 40);
            assert!(time > 0.0);
            if kernel == GpuKernel::Fused {
                // The stable cable stays where it was, give or take its swing.
                let (r, _) = gpu.state().unwrap();
                assert!(r[..first].iter().all(|x| x.iter().all(|c| c.abs() < 100.0)));
            }
            errs.push((p, kernel, time));
        }
    }
    for p in [Precision::F32, Precision::F64] {
        let t: Vec<f64> = errs.iter().filter(|e| e.0 == p).map(|e| e.2).collect();
        if t.len() == 2 {
            // Same step in f64; within a few steps in f32.
            let slack = if p == Precision::F64 { 0.5 } else { 5.0 } * opts.dt;
            assert!((t[0] - t[1]).abs() <= slack, "{}: {t:?}", p.name());
        }
    }
}

/// A current profile of 300 points: each element's linear search of it is up to 300
/// loop iterations a step, so a whole submission in one fused dispatch would pass
/// llvmpipe's budget of 65535 loop iterations per shader invocation, after which every
/// loop silently ends after one iteration (with whole submissions in one dispatch the
/// fused kernel parted from the two-pass kernel by 0.28 m on this fleet and these
/// `advance` calls, at cable m41). The host cuts the fused dispatches short
/// (`fused_max_steps`): more dispatches than submissions, and agreement to round-off.
#[test]
fn fused_with_a_long_current_profile_matches_two_pass() {
    let name = "fused_with_a_long_current_profile_matches_two_pass";
    let Some(ctx) = gpu_context(name, true) else {
        return;
    };
    let (lay, pos) = fleet_with_profiles(50, 7, 300);
    assert!(lay.currents.iter().any(|c| c.table.len() == 300));
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = 3000;
    let run = |kernel| {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, Precision::F64).unwrap();
        gpu.set_kernel(kernel).unwrap();
        // The uneven advance calls of `run`.
        for n in [1u64, 700, 299, 1000, 1, 700, 299] {
            gpu.advance(n).unwrap();
        }
        let t = gpu.timings();
        (
            Snapshot::gpu(format!("GPU f64 {}", kernel.name()), &mut gpu),
            t,
        )
    };
    let (fused, tf) = run(GpuKernel::Fused);
    let (two, _) = run(GpuKernel::TwoPass);
    assert!(
        tf.dispatches > tf.submissions,
        "{name}: {} dispatches in {} submissions",
        tf.dispatches,
        tf.submissions
    );
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    let ea = lay.line_coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
    let bounds = RoundOff::new(&lay, &two, steps, f64::EPSILON, ea, l0_min, 2.0 / bound.dt);
    let d = bounds.check(name, &lay, &fused, &two);
    eprintln!(
        "{name}: {} dispatches in {} submissions; {}",
        tf.dispatches,
        tf.submissions,
        d.report(&lay)
    );
}
