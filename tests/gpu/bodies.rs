//! Cable ends on bodies with prescribed motion, on the GPU.
//!
//! 1. The WGSL attachment kinematics (`body_point`, from a route rebased to `t0` and
//!    the body's row of a step) against its Rust twin `body::attachment` on the exact
//!    body state, on random bodies, points and times, at f32 and f64. Contract: every
//!    output within `16 eps_R * scale` (as tests/gpu_functions.rs), where the scale of
//!    the position is the size of the motion since `t0` (`|dX| + sum |dR_ij at_j|`)
//!    plus `eps_R` times the position: the rebasing is what keeps an f32 attachment
//!    point 50 m from the reference point accurate to the motion's round-off, and a
//!    shader that formed `R at` whole in f32 fails this contract.
//! 2. Whole runs: a vessel moving on RAOs in three wave components, with four lines to
//!    the seabed, and a barge moving on a 6-DOF table with one; GPU against CPU, both
//!    kernels. f64: the round-off bound of tests/gpu_parity.rs (`10 N eps L` in
//!    position after `N` steps, and what follows for tensions and reactions). f32: the
//!    f32 contract of tests/gpu_f32.rs (nodes within `1e-4` of the cable's length,
//!    tensions within 1% plus 0.1% of the largest).

use super::common::*;
use cablesim::body::{attachment, Body, MeanPose, Motion, MotionTable, RaoMotion, RaoTable};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::layout::*;
use cablesim::gpu::solver::{body_rows, rebased_route};
use cablesim::gpu::{shaders, GpuContext, GpuKernel, GpuSolver, Precision};
use cablesim::model::{
    CableDef, Current, Environment, Layout, LineType, ModelDef, NodeDef, PointMass, Route, Seabed,
};
use cablesim::options::SolverOptions;
use cablesim::sea::WaveComponent;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;
use std::sync::Arc;

const KERNEL: &str = r#"
@group(1) @binding(0) var<storage, read_write> tout: array<R>;

@compute @workgroup_size(64)
fn t_body(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tout) / 12u {
        return;
    }
    let s = body_point(routes[i], body_row_at(i * 24u));
    let o = i * 12u;
    tout[o] = s.r_hi.x;
    tout[o + 1u] = s.r_hi.y;
    tout[o + 2u] = s.r_hi.z;
    tout[o + 3u] = s.r_lo.x;
    tout[o + 4u] = s.r_lo.y;
    tout[o + 5u] = s.r_lo.z;
    tout[o + 6u] = s.v.x;
    tout[o + 7u] = s.v.y;
    tout[o + 8u] = s.v.z;
    tout[o + 9u] = s.a.x;
    tout[o + 10u] = s.a.y;
    tout[o + 11u] = s.a.z;
}
"#;

/// Runs `t_body` over the given routes and rows and returns 12 values per case.
fn run_kernel<R: GpuReal>(
    ctx: &GpuContext,
    p: Precision,
    routes: &[RouteParams<R>],
    rows: &[BodyRow<R>],
) -> Vec<f64> {
    use wgpu::util::DeviceExt;
    let dev = &ctx.device;
    let src = format!("{}\n{KERNEL}", shaders::prelude(p));
    let scope = dev.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("body_point"),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let pipe = dev.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("t_body"),
        layout: None,
        module: &module,
        entry_point: Some("t_body"),
        compilation_options: Default::default(),
        cache: None,
    });
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
    let buf = |bytes: &[u8]| {
        dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytes,
            usage,
        })
    };
    let rb = buf(bytemuck::cast_slice(routes));
    let bb = buf(bytemuck::cast_slice(rows));
    let n_out = routes.len() * 12;
    let out_bytes = (n_out * std::mem::size_of::<R>()) as u64;
    let tout = buf(&vec![0u8; out_bytes as usize]);
    let staging = dev.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: out_bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bg0 = dev.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipe.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 6,
                resource: rb.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 18,
                resource: bb.as_entire_binding(),
            },
        ],
    });
    let bg1 = dev.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipe.get_bind_group_layout(1),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: tout.as_entire_binding(),
        }],
    });
    let mut enc = dev.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipe);
        pass.set_bind_group(0, &bg0, &[]);
        pass.set_bind_group(1, &bg1, &[]);
        pass.dispatch_workgroups((routes.len() as u32).div_ceil(64), 1, 1);
    }
    enc.copy_buffer_to_buffer(&tout, 0, &staging, 0, out_bytes);
    ctx.queue.submit([enc.finish()]);
    if let Some(e) = pollster::block_on(scope.pop()) {
        panic!("t_body ({}): {e}", p.name());
    }
    staging
        .slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.unwrap());
    dev.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let view = staging.slice(..).get_mapped_range().unwrap();
    view.chunks_exact(std::mem::size_of::<R>())
        .map(|b| bytemuck::pod_read_unaligned::<R>(b).f64())
        .collect()
}

/// An RAO table with responses in every degree of freedom, varying with frequency and
/// heading (amplitudes m/m and rad/m, phases rad).
fn rao_table(rng: &mut ChaCha8Rng) -> RaoTable {
    let omega = vec![0.3, 0.6, 0.9, 1.4];
    let heading: Vec<f64> = (0..8).map(|j| j as f64 * TAU / 8.0).collect();
    let mut values = Vec::new();
    for _ in 0..omega.len() * heading.len() {
        values.push(std::array::from_fn(|k| {
            let amp = if k < 3 {
                rng.gen_range(0.05..1.2)
            } else {
                rng.gen_range(0.2..3.0f64).to_radians()
            };
            (amp, rng.gen_range(-3.0..3.0))
        }));
    }
    RaoTable::new(omega, heading, values)
}

fn waves(rng: &mut ChaCha8Rng, n: usize, amplitude: f64) -> Vec<WaveComponent> {
    (0..n)
        .map(|_| {
            let omega: f64 = rng.gen_range(0.35..1.3);
            WaveComponent {
                amplitude: amplitude * rng.gen_range(0.3..1.0),
                omega,
                k: omega * omega / 9.81,
                direction: rng.gen_range(0.0..TAU),
                phase: rng.gen_range(0.0..TAU),
            }
        })
        .collect()
}

fn rao_body(rng: &mut ChaCha8Rng, name: &str, reference: [f64; 3], amplitude: f64) -> Body {
    let pose = MeanPose {
        reference,
        offset: [rng.gen_range(-5.0..5.0), rng.gen_range(-5.0..5.0), 0.0],
        heading: rng.gen_range(0.0..TAU),
    };
    let m = pose.position();
    let w = waves(rng, 3, amplitude);
    let motion = RaoMotion::new(&rao_table(rng), &w, m[0], m[1], pose.heading, 5.0);
    Body::new(name.into(), pose, Motion::Rao(motion))
}

/// A barge on a 6-DOF table sampled every 0.25 s from smooth motions.
fn table_body(name: &str, reference: [f64; 3]) -> Body {
    let t: Vec<f64> = (0..400).map(|k| k as f64 * 0.25).collect();
    let rows: Vec<[f64; 6]> = t
        .iter()
        .map(|&t| {
            [
                0.8 * (0.5 * t).sin(),
                0.5 * (0.4 * t + 1.0).sin(),
                0.6 * (0.7 * t).sin(),
                2.0 * (0.6 * t).sin(),
                1.5 * (0.5 * t + 0.3).sin(),
                3.0 * (0.2 * t).sin(),
            ]
        })
        .collect();
    Body::new(
        name.into(),
        MeanPose {
            reference,
            offset: [0.0; 3],
            heading: 0.3,
        },
        Motion::Table(MotionTable::new(t, &rows)),
    )
}

fn check_body_point<R: GpuReal>(ctx: &GpuContext, p: Precision) {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let eps = R::epsilon().f64();
    let bodies: Vec<Arc<Body>> = (0..6)
        .map(|i| {
            let r = [
                rng.gen_range(-500.0..500.0),
                rng.gen_range(-500.0..500.0),
                0.0,
            ];
            Arc::new(if i % 3 == 2 {
                table_body("barge", r)
            } else {
                rao_body(&mut rng, "ship", r, 2.0)
            })
        })
        .collect();
    let (mut routes, mut rows, mut want) = (Vec::new(), Vec::new(), Vec::new());
    for case in 0..600 {
        let body = &bodies[case % bodies.len()];
        let at = [
            rng.gen_range(-60.0..60.0),
            rng.gen_range(-20.0..20.0),
            rng.gen_range(-15.0..10.0),
        ];
        let t0 = rng.gen_range(0.0..80.0);
        // Up to a submission after the rebase, at an odd step.
        let t = t0 + rng.gen_range(0.0..2.0);
        // A block origin: whole metres near the point.
        let o = attachment(&body.state(t0), at)
            .r
            .map(|x| (x + rng.gen_range(-30.0..30.0)).round());
        let route = Route::Body {
            body: body.clone(),
            at,
        };
        routes.push(rebased_route::<R>(&route, 0, t0, o, 0));
        let row = body_rows::<R>(body, t0, std::iter::once(t))[0];
        rows.push(row);
        want.push((
            attachment(&body.state(t), at),
            o,
            body.state(t),
            body.state(t0),
            at,
        ));
    }
    let got = run_kernel(ctx, p, &routes, &rows);
    let mut worst = [0.0f64; 3];
    for (i, (w, o, s, s0, at)) in want.iter().enumerate() {
        let g = &got[12 * i..12 * i + 12];
        // Sizes of the terms each output is made of.
        let dx = (s.x - s0.x).norm();
        let mut dq = 0.0;
        for r in 0..3 {
            for (c, a) in at.iter().enumerate() {
                dq += ((s.rot[r][c] - s0.rot[r][c]) * a).abs();
            }
        }
        let q = (0..3).map(|k| at[k] * at[k]).sum::<f64>().sqrt();
        let pos = (0..3).map(|k| (w.r[k] - o[k]).abs()).fold(0.0, f64::max);
        let scale_r = dx + dq + eps * pos + eps * q;
        let (wn, an) = (s.omega.norm(), s.alpha.norm());
        let scale_v = s.v.norm() + wn * q;
        let scale_a = s.a.norm() + an * q + wn * wn * q;
        // The f64 reference forms absolute positions (hundreds of metres), and so does
        // the host's rebased point: their own round-off, 8 eps_64 |r|, is allowed for
        // (negligible against f32's eps, a few eps_64 of the motion in f64).
        let abs = s.x.norm() + q;
        let scale_r = scale_r + 8.0 * f64::EPSILON * abs / eps;
        for k in 0..3 {
            let r = g[k] + g[3 + k];
            let checks = [
                (r, w.r[k] - o[k], scale_r, "position"),
                (g[6 + k], w.v[k], scale_v, "velocity"),
                (g[9 + k], w.a[k], scale_a, "acceleration"),
            ];
            for (j, (gpu, rust, scale, what)) in checks.into_iter().enumerate() {
                let e = (gpu - rust).abs() / (eps * scale);
                worst[j] = worst[j].max(e);
                assert!(
                    e <= 16.0,
                    "body_point ({}) case {i} {what}[{k}]: GPU {gpu:e}, Rust {rust:e}: {e:.1} eps x scale {scale:e}",
                    p.name()
                );
            }
        }
    }
    eprintln!(
        "body_point ({}): worst position / velocity / acceleration {:.2} / {:.2} / {:.2} eps x scale (limit 16)",
        p.name(),
        worst[0],
        worst[1],
        worst[2]
    );
}

#[test]
fn wgsl_body_point_matches_attachment_in_f32() {
    let Some(ctx) = gpu_context("wgsl_body_point_matches_attachment_in_f32", false) else {
        return;
    };
    check_body_point::<f32>(&ctx, Precision::F32);
}

#[test]
fn wgsl_body_point_matches_attachment_in_f64() {
    let Some(ctx) = gpu_context("wgsl_body_point_matches_attachment_in_f64", true) else {
        return;
    };
    check_body_point::<f64>(&ctx, Precision::F64);
}

const DEPTH: f64 = 50.0;

fn chain() -> LineType {
    LineType {
        name: "chain".into(),
        diameter: 0.08,
        mass_per_length: 30.0,
        ea: 5.0e7,
        damping: 1e-3,
        cn: 2.4,
        ct: 0.4,
        cm: 1.0,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    }
}

/// A vessel on RAOs with four lines to the seabed and a barge on a table with one,
/// relaxed to static equilibrium at `t = 0`.
fn moored_bodies() -> (Layout, Vec<[f64; 3]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let ship = Arc::new(rao_body(&mut rng, "ship", [0.0, 0.0, 0.0], 1.5));
    let barge = Arc::new(table_body("barge", [300.0, 40.0, 0.0]));
    let mut def = ModelDef {
        env: Environment {
            depth: DEPTH,
            seabed: Seabed {
                friction: 0.3,
                ..Seabed::default()
            },
            ..water()
        },
        line_types: vec![chain()],
        currents: vec![Current::uniform([0.3, 0.1, 0.0])],
        ..Default::default()
    };
    let ends: [(&Arc<Body>, [f64; 3], f64); 5] = [
        (&ship, [40.0, 12.0, -6.0], 0.4),
        (&ship, [40.0, -12.0, -6.0], -0.4),
        (&ship, [-40.0, 12.0, -6.0], 2.7),
        (&ship, [-40.0, -12.0, -6.0], -2.7),
        (&barge, [10.0, 0.0, -2.0], 0.0),
    ];
    for (c, (body, at, dir)) in ends.into_iter().enumerate() {
        let route = Route::Body {
            body: body.clone(),
            at,
        };
        let fair = route.eval(0.0).r;
        let anchor = [
            fair[0] + 120.0 * dir.cos(),
            fair[1] + 120.0 * dir.sin(),
            -DEPTH,
        ];
        let segments = 40;
        let chord = (0..3)
            .map(|d| (fair[d] - anchor[d]).powi(2))
            .sum::<f64>()
            .sqrt();
        let first = def.nodes.len();
        for k in 0..=segments {
            let s = k as f64 / segments as f64;
            let mut p = [0, 1, 2].map(|d| anchor[d] + s * (fair[d] - anchor[d]));
            p[2] = (p[2] - 0.2 * DEPTH * (std::f64::consts::PI * s).sin()).max(-DEPTH);
            def.nodes.push(NodeDef {
                position: p,
                point: PointMass::default(),
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
            name: format!("line{c}"),
            line_type: 0,
            nodes: (first..=first + segments).collect(),
            l0: vec![1.1 * chord / segments as f64; segments],
            current: 0,
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

struct Run {
    r: Vec<[f64; 3]>,
    tension: Vec<f64>,
    reaction: Vec<[f64; 3]>,
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|d| (a[d] - b[d]).powi(2)).sum::<f64>().sqrt()
}

/// Advance calls of uneven length: submissions and rebasing at odd steps.
fn advance_unevenly(steps: u64, mut f: impl FnMut(u64)) {
    let mut done = 0;
    for n in [1u64, 700, 299, 1000].iter().cycle() {
        let n = (*n).min(steps - done);
        if n == 0 {
            break;
        }
        f(n);
        done += n;
    }
}

fn gpu_run(
    ctx: &GpuContext,
    lay: &Layout,
    pos: &[[f64; 3]],
    opts: SolverOptions,
    p: Precision,
    kernel: GpuKernel,
    steps: u64,
) -> Run {
    let mut gpu = GpuSolver::new(ctx, lay.clone(), pos, opts, p).unwrap();
    if kernel == GpuKernel::Fused {
        assert_eq!(gpu.kernel(), kernel, "{:?}", gpu.fused_unavailable());
    }
    gpu.set_kernel(kernel).unwrap();
    advance_unevenly(steps, |n| gpu.advance(n).unwrap());
    let (r, _) = gpu.state().unwrap();
    let e = gpu.evaluate().unwrap();
    Run {
        r,
        tension: e.tension,
        reaction: e.reaction,
    }
}

fn parity(p: Precision) {
    let name = format!("gpu_runs_bodies_like_cpu_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let (lay, pos) = moored_bodies();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = 3000;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.use_chain_kernel = false;
    advance_unevenly(steps, |n| cpu.advance(n).unwrap());
    let ec = cpu.evaluate().unwrap();
    let cr: Vec<[f64; 3]> = cpu.r.iter().map(|x| x.to_f64()).collect();

    // The fairleads went where the bodies took them (the CPU's own check), and moved.
    let t = steps as f64 * opts.dt;
    let mut moved = 0.0f64;
    for (c, r) in lay.routes.iter().enumerate() {
        if let Route::Body { .. } = r {
            let i = lay.constraint_node[c] as usize;
            assert!(
                dist(cr[i], r.eval(t).r) < 1e-3,
                "{name}: fairlead {c} off its body"
            );
            moved = moved.max(dist(cr[i], pos[i]));
        }
    }
    assert!(
        moved > 0.1,
        "{name}: the fairleads should move: {moved} m in {t} s"
    );

    let max = |it: &mut dyn Iterator<Item = f64>| it.fold(0.0f64, f64::max);
    let scale_t = max(&mut ec.tension.iter().map(|x| x.abs()));
    let ea = chain().ea;
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let g = gpu_run(&ctx, &lay, &pos, opts, p, kernel, steps);
        let dr = max(&mut g.r.iter().zip(&cr).map(|(a, b)| dist(*a, *b)));
        // f32: what each element's tension exceeds 1% of its own by (tolerance 0.1% of
        // the largest); f64: the difference.
        let rel = if p == Precision::F32 { 0.01 } else { 0.0 };
        let dt_ = max(&mut g
            .tension
            .iter()
            .zip(&ec.tension)
            .map(|(a, b)| (a - b).abs() - rel * b.abs()));
        let dt_raw = max(&mut g
            .tension
            .iter()
            .zip(&ec.tension)
            .map(|(a, b)| (a - b).abs()));
        let dre = max(&mut g
            .reaction
            .iter()
            .zip(&ec.reaction)
            .map(|(a, b)| dist(*a, *b)));
        let (tol_r, tol_t) = match p {
            Precision::F64 => {
                // tests/gpu_parity.rs: 10 N eps L, L the largest coordinate relative to a
                // block's mean (here under 100 m: the lines are about 130 m long).
                let tol_r = 10.0 * steps as f64 * f64::EPSILON * 100.0;
                (
                    tol_r,
                    ea * (tol_r / l0_min + 100.0 * f64::EPSILON) + 100.0 * f64::EPSILON * scale_t,
                )
            }
            Precision::F32 => {
                let length = lay.elem_l0.iter().sum::<f64>() / lay.cables.len() as f64;
                (1e-4 * length, 0.001 * scale_t)
            }
        };
        eprintln!(
            "{name} ({}): {steps} steps, fairleads moved {moved:.3} m: |dr| {dr:.3e} m (tol {tol_r:.1e}), |dT| {dt_raw:.3e} N (less 1% of T in f32: {dt_:.3e} N), |dReaction| {dre:.3e} N (tol {tol_t:.1e}, max T {scale_t:.3e} N)",
            kernel.name()
        );
        assert!(
            dr <= tol_r,
            "{name} ({}): positions differ by {dr:e} m > {tol_r:e}",
            kernel.name()
        );
        assert!(
            dt_ <= tol_t,
            "{name} ({}): tensions differ by {dt_:e} N > {tol_t:e}",
            kernel.name()
        );
        assert!(
            dre <= tol_t + rel * scale_t,
            "{name} ({}): reactions differ by {dre:e} N > {tol_t:e}",
            kernel.name()
        );
    }
}

#[test]
fn gpu_runs_bodies_like_cpu_in_f64() {
    parity(Precision::F64);
}

#[test]
fn gpu_runs_bodies_like_cpu_in_f32() {
    parity(Precision::F32);
}

/// `bodies.csv` of a scenario run on `backend` (f64 on the GPU).
fn bodies_csv(dir: &std::path::Path, backend: cablesim::scenario::Backend) -> Vec<Vec<f64>> {
    let sc = cablesim::scenario::Scenario::load(dir.join("s.toml")).unwrap();
    let out = dir.join(format!("out_{backend:?}"));
    cablesim::sim::run(
        &sc,
        &cablesim::sim::RunOptions {
            out_dir: out.clone(),
            overrides: cablesim::sim::Overrides {
                backend: Some(backend),
                precision: Some(Precision::F64),
                ..Default::default()
            },
            progress: false,
        },
    )
    .unwrap();
    std::fs::read_to_string(out.join("bodies.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect()
}

#[test]
fn a_scenario_with_bodies_writes_the_same_bodies_csv_on_the_gpu() {
    let Some(_ctx) = gpu_context(
        "a_scenario_with_bodies_writes_the_same_bodies_csv_on_the_gpu",
        true,
    ) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("t,x,y,z,roll,pitch,yaw\n");
    for k in 0..=40 {
        let t = 0.25 * k as f64;
        csv += &format!(
            "{t},{},{},{},{},{},{}\n",
            0.5 * (0.6 * t).sin(),
            0.3 * (0.5 * t).sin(),
            0.8 * (0.7 * t).cos(),
            3.0 * (0.6 * t).sin(),
            2.0 * (0.4 * t).sin(),
            4.0 * (0.3 * t).sin()
        );
    }
    std::fs::write(dir.path().join("m.csv"), csv).unwrap();
    let text = r#"
[simulation]
duration = 10.0
output_interval = 0.5

[[line_types]]
name = "rope"
diameter = 0.02
mass_per_length = 1.0
ea = 2.0e6
damping = 1.0e-4
cn = 1.2
ct = 0.01
cm = 1.0

[[bodies]]
name = "ship"
reference = [5.0, 2.0, 0.0]
heading = 30.0
motion_file = "m.csv"

[[cables]]
name = "a"
line_type = "rope"
length = 10.0
segments = 10
start = { body = "ship", at = [8.0, -3.0, -2.0] }
end = { free = [14.0, -1.0, -12.0], mass = 20.0, volume = 0.005 }

[[cables]]
name = "b"
line_type = "rope"
length = 12.0
segments = 12
start = { body = "ship", at = [-8.0, 3.0, -2.0] }
end = { fixed = [-12.0, 4.0, -12.0] }
"#;
    std::fs::write(dir.path().join("s.toml"), text).unwrap();
    let cpu = bodies_csv(dir.path(), cablesim::scenario::Backend::Cpu);
    let gpu = bodies_csv(dir.path(), cablesim::scenario::Backend::Gpu);
    assert_eq!(cpu.len(), 21);
    assert_eq!(cpu.len(), gpu.len());
    let fmax = cpu
        .iter()
        .map(|r| (r[8].powi(2) + r[9].powi(2) + r[10].powi(2)).sqrt())
        .fold(0.0, f64::max);
    assert!(fmax > 50.0, "the lines load the body: {fmax} N");
    for (c, g) in cpu.iter().zip(&gpu) {
        // The pose is the host's on both paths; the loads agree to f64 round-off
        // (amplified by the run's stiffness: 1e-9 of the largest force).
        for k in 0..8 {
            if k != 1 {
                assert_eq!(c[k], g[k], "column {k} at t = {}", c[0]);
            }
        }
        for k in 8..14 {
            let scale = if k < 11 { fmax } else { 20.0 * fmax };
            assert!(
                (c[k] - g[k]).abs() < 1e-9 * scale,
                "column {k} at t = {}: CPU {} GPU {}",
                c[0],
                c[k],
                g[k]
            );
        }
    }
}
