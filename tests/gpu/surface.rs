//! The water surface on the GPU path (docs/src/water_surface.md).
//!
//! Per function: `wetted_fraction`, `point_wetted_fraction` and `glmf_element_wet`
//! against their Rust twins on random inputs at f32 and f64, by the contract of
//! tests/gpu_functions.rs (whose harness is repeated here): every output within
//! `16 eps_R * scale`, `scale` the sum of the magnitudes of the terms that make it.
//!
//! Per run: a mooring line whose fairlead circles through the surface, carrying a buoy
//! that floats across it, stepped on the CPU (f64) and on the GPU with both kernels.
//! In f64 the GPU equals the CPU to round-off (positions within `1e-9` of the line's
//! length after 4000 steps, where one element switching between wet and dry a step
//! early or late would move nodes by millimetres); in f32 the contract of
//! tests/gpu_f32.rs: nodes within `1e-4` of the line's length, tensions within 1%
//! plus 0.1% of the largest.

use super::common::*;
use super::functions::{element_case, run_kernels, rv, to_r, Worst};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::layout::*;
use cablesim::gpu::{GpuContext, GpuKernel, GpuSolver, Precision};
use cablesim::math::V3;
use cablesim::model::{Layout, PointMass, Route};
use cablesim::options::SolverOptions;
use cablesim::physics::{
    glmf_element_wet, glmf_external_wet, point_wetted_fraction, wetted_fraction,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const KERNELS: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

fn v3in(k: u32) -> vec3<R> {
    return vec3<R>(tin[k], tin[k + 1u], tin[k + 2u]);
}

fn v3out(k: u32, v: vec3<R>) {
    tout[k] = v.x;
    tout[k + 1u] = v.y;
    tout[k + 2u] = v.z;
}

@compute @workgroup_size(64)
fn t_fractions(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 5u {
        return;
    }
    let b = i * 5u;
    tout[2u * i] = wetted_fraction(tin[b], tin[b + 1u], tin[b + 2u]);
    tout[2u * i + 1u] = point_wetted_fraction(tin[b + 3u], tin[b + 4u]);
}

@compute @workgroup_size(64)
fn t_element_wet(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 29u {
        return;
    }
    let b = i * 29u;
    let c = LineParams(tin[b], tin[b + 1u], tin[b + 2u], tin[b + 3u], tin[b + 4u],
        tin[b + 5u], tin[b + 6u], tin[b + 7u], tin[b + 8u], tin[b + 9u], tin[b + 10u], R(0.0),
        R(0.0), R(0.0), R(0.0), R(0.0));
    let d = v3in(b + 11u);
    let el = glmf_element_wet(c, d, norm3(d) - tin[b + 20u], v3in(b + 14u), v3in(b + 17u),
        tin[b + 20u], v3in(b + 21u), v3in(b + 24u), tin[b + 27u], tin[b + 28u]);
    let o = i * 9u;
    v3out(o, el.t);
    tout[o + 3u] = el.tension;
    v3out(o + 4u, el.f_half);
    tout[o + 7u] = el.half_mass;
    tout[o + 8u] = el.half_added;
}
"#;

/// Runs `entry` of this file's test kernels over `input` (the shared harness of
/// `functions.rs`) and returns `n_out` values.
fn run<R: GpuReal>(
    ctx: &GpuContext,
    p: Precision,
    entry: &str,
    group0: &[(u32, Vec<u8>)],
    input: &[R],
    n_threads: usize,
    n_out: usize,
) -> Vec<R> {
    run_kernels(ctx, p, KERNELS, entry, group0, input, n_threads, n_out)
}

/// The two fractions on submergences of both signs, zero, and near the surface.
fn check_fractions<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 2000;
    let mut x = Vec::new();
    for i in 0..n {
        let s = |rng: &mut ChaCha8Rng| match i % 4 {
            0 => rng.gen_range(-5.0..5.0),
            1 => rng.gen_range(-1e-3..1e-3),
            2 => 0.0,
            _ => rng.gen_range(-0.5..0.5),
        };
        let (sa, sb, sp) = (s(rng), s(rng), s(rng));
        let d = if i % 5 == 0 {
            0.0
        } else {
            rng.gen_range(0.01..0.2)
        };
        let radius = if i % 7 == 0 {
            0.0
        } else {
            rng.gen_range(0.05..2.0)
        };
        x.extend([sa, sb, d, sp, radius]);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_fractions", &[], &xr, n, 2 * n);
    let mut w = Worst::new::<R>("wetted_fraction, point_wetted_fraction");
    for i in 0..n {
        let a = &x[5 * i..5 * i + 5];
        let f = wetted_fraction(a[0], a[1], a[2]);
        // Quotients of sums and differences of the inputs, formed without
        // cancellation: relative rounding of a few eps.
        w.check("element", i, out[2 * i].f64(), f, 1.0);
        let fp = point_wetted_fraction(a[3], a[4]);
        w.check("point", i, out[2 * i + 1].f64(), fp, 1.0);
    }
    w.report(p);
}

/// `glmf_element_wet` on random lines, kinematics, wetted fractions (a third wholly
/// wet, a third dry, a third in between) and gravity.
fn check_element_wet<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 500;
    let mut x = Vec::new();
    for i in 0..n {
        let ea = 10f64.powf(rng.gen_range(5.0..9.0));
        let l0 = rng.gen_range(0.5..50.0);
        let l = l0 * (1.0 + rng.gen_range(-0.01..0.01));
        let dir = V3::<f64>::from_f64(rv(rng, 1.0));
        let d = dir / dir.norm() * l;
        let mass = rng.gen_range(0.1..100.0);
        let g = rng.gen_range(9.0..10.0);
        // Weight less buoyancy per length: `-(m - rho A) g` with rho A below or above m.
        let rho_a = rng.gen_range(0.0..2.0) * mass;
        let wz = -(mass - rho_a) * g;
        // Added-mass coefficients with `Cat` below and above `Cm`.
        let (cm, cat) = (rng.gen_range(0.0..2.0), rng.gen_range(0.0..2.0));
        x.extend([
            ea,
            ea * rng.gen_range(0.0..1e-2),
            rng.gen_range(0.0..30.0),
            rng.gen_range(0.0..3.0),
            (1.0 + cm) * rho_a,
            (1.0 + cat) * rho_a,
            mass,
            cm * rho_a,
            cat * rho_a,
            wz,
            (i % 2) as f64,
        ]);
        x.extend(d.to_f64());
        x.extend(rv(rng, 2.0));
        x.extend(rv(rng, 2.0));
        x.push(l0);
        x.extend(rv(rng, 1.5));
        x.extend(rv(rng, 1.0));
        x.push(match i % 3 {
            0 => 1.0,
            1 => 0.0,
            _ => rng.gen_range(0.0..1.0),
        });
        x.push(g);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_element_wet", &[], &xr, n, 9 * n);
    let mut w = Worst::new::<R>("glmf_element_wet");
    for i in 0..n {
        let a = &x[29 * i..29 * (i + 1)];
        let (c, inp) = element_case(a);
        let (wet, g) = (a[27], a[28]);
        let el = glmf_element_wet(&c, &inp, wet, g);
        let l = inp.rb.norm();
        let ext = glmf_external_wet(&c, &inp, el.t, l, 1.0, g);
        let o: Vec<f64> = out[9 * i..9 * (i + 1)].iter().map(|v| v.f64()).collect();
        w.v("t", i, &o[0..3], el.t, 1.0);
        let t_scale = c.ea * l / inp.l0 + c.ea_c * ((inp.vb - inp.va).norm() / inp.l0);
        w.check("tension", i, o[3], el.tension, t_scale);
        // The wholly wet terms bound every term of the partly wet sum; the weight's
        // parts are the wet weight and the buoyancy.
        let f_scale = 0.5
            * (ext.drag_n.norm()
                + ext.drag_t.norm()
                + ext.froude_krylov.norm()
                + (c.wet_weight_z.abs() + 2.0 * c.mass * g) * inp.l0);
        w.v("f_half", i, &o[4..7], el.f_half, f_scale);
        w.check("half_mass", i, o[7], el.half_mass, el.half_mass);
        let added = (c.added_mass + c.added_mass_t) * inp.l0;
        w.check("half_added", i, o[8], el.half_added, added);
    }
    w.report(p);
}

fn check_functions<R: GpuReal>(ctx: &GpuContext, p: Precision) {
    let mut rng = ChaCha8Rng::seed_from_u64(20261201);
    check_fractions::<R>(ctx, p, &mut rng);
    check_element_wet::<R>(ctx, p, &mut rng);
}

#[test]
fn surface_functions_match_their_rust_twins_in_f32() {
    let Some(ctx) = gpu_context("surface_functions_match_their_rust_twins_in_f32", false) else {
        return;
    };
    check_functions::<f32>(&ctx, Precision::F32);
}

#[test]
fn surface_functions_match_their_rust_twins_in_f64() {
    let Some(ctx) = gpu_context("surface_functions_match_their_rust_twins_in_f64", true) else {
        return;
    };
    check_functions::<f64>(&ctx, Precision::F64);
}

/// A rope moored 30 m deep whose fairlead circles through the surface (radius 3 m,
/// period 8 s), with a buoy (sphere of 0.2 m^3) at node 12 that floats across the
/// surface; current 0.3 m/s.
pub(crate) fn crossing_line() -> (Layout, Vec<[f64; 3]>) {
    let mut def = straight_cable(
        water(),
        rope(),
        [-30.0, 0.0, -30.0],
        [0.0, 0.0, -3.0],
        45.0,
        15,
        Some(Route::Fixed {
            position: [-30.0, 0.0, -30.0],
        }),
        Some(Route::Circle {
            center: [0.0, 0.0, 0.0],
            radius: 3.0,
            period: 8.0,
            axis: [0.0, 1.0, 0.0],
            phase: -std::f64::consts::FRAC_PI_2,
            advance: 0.0,
        }),
        PointMass::default(),
        [0.3, 0.0, 0.0],
    );
    def.nodes[12].point = PointMass {
        mass: 60.0,
        volume: 0.2,
        drag_area: 0.4,
        added_mass_coef: 0.5,
    };
    def.nodes[12].position[2] = 0.0;
    Layout::build(&def).unwrap()
}

struct Run {
    r: Vec<[f64; 3]>,
    tension: Vec<f64>,
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn parity(p: Precision) {
    let name = format!("gpu_matches_cpu_across_the_surface_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let (lay, pos) = crossing_line();
    let opts = SolverOptions {
        dt: 2e-4,
        ..SolverOptions::default()
    };
    let steps = 4000u64;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.advance(steps).unwrap();
    let cpu_run = Run {
        r: cpu.r.iter().map(|v| v.to_f64()).collect(),
        tension: cpu.evaluate().unwrap().tension,
    };
    let above = cpu_run.r.iter().filter(|r| r[2] > 0.0).count();
    let buoy = lay.cables[0].nodes[12] as usize;
    println!(
        "{name}: {above} nodes above the surface, buoy centre at z = {:.4} m",
        cpu_run.r[buoy][2]
    );
    assert!(above >= 1, "the line crosses the surface");
    let length = 45.0;
    let tmax = cpu_run.tension.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
        gpu.set_kernel(kernel).unwrap();
        for n in [1u64, 999, 1000, 2000] {
            gpu.advance(n).unwrap();
        }
        let (r, _) = gpu.state().unwrap();
        let tension = gpu.evaluate().unwrap().tension;
        let dr = r
            .iter()
            .zip(&cpu_run.r)
            .map(|(a, b)| dist(*a, *b))
            .fold(0.0f64, f64::max);
        let dt = tension
            .iter()
            .zip(&cpu_run.tension)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        println!("{name} {kernel:?}: |dr| {dr:.3e} m, |dT| {dt:.3e} N (largest {tmax:.1} N)");
        match p {
            Precision::F64 => {
                assert!(dr < 1e-9 * length, "{kernel:?}: |dr| {dr} m");
                assert!(dt < 1e-6 * tmax, "{kernel:?}: |dT| {dt} N");
            }
            Precision::F32 => {
                assert!(dr < 1e-4 * length, "{kernel:?}: |dr| {dr} m");
                for (a, b) in tension.iter().zip(&cpu_run.tension) {
                    assert!(
                        (a - b).abs() < 0.01 * b.abs() + 1e-3 * tmax,
                        "{kernel:?}: tension {a} N against {b} N"
                    );
                }
            }
        }
    }
}

#[test]
fn gpu_matches_cpu_across_the_surface_in_f64() {
    parity(Precision::F64);
}

#[test]
fn gpu_matches_cpu_across_the_surface_in_f32() {
    parity(Precision::F32);
}
