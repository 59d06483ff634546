//! Each WGSL force function against its Rust twin, on random inputs, at f32 and f64
//! (the functions of a step's element and node passes: `step_functions`).
//!
//! A test kernel (below) calls one prelude function per invocation; the Rust twin runs
//! in f64 on the very same inputs (the values the GPU received, converted back), so
//! only the GPU's arithmetic is measured. Contract: every output within
//! `16 eps_R * scale`, where `eps_R` is the machine epsilon of the shader precision
//! and `scale` the sum of the magnitudes of the terms that make the output (so
//! cancellation is allowed for, and a missing or wrong term is not: it is of the size
//! of `scale`).

use super::common::*;
use cablesim::gpu::layout::*;
use cablesim::gpu::solver::{rebased_route, route_samples};
use cablesim::gpu::{shaders, GpuContext, Precision};
use cablesim::math::{Sym3, V3};
use cablesim::model::{Current, Route};
use cablesim::physics::{
    glmf_element, seabed_damping, seabed_force, tabulated_max_slope, tabulated_tension, Coefs,
    ElementInput, SeabedCoefs,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod axial;
mod bending;
mod free_body;
mod routes;
use axial::*;
use bending::*;
use routes::*;
mod seabed_grid;
use seabed_grid::*;
mod visco;
use visco::*;
mod screen;
use screen::*;

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

fn line_in(b: u32) -> LineParams {
    return LineParams(tin[b], tin[b + 1u], tin[b + 2u], tin[b + 3u], tin[b + 4u],
        tin[b + 5u], tin[b + 6u], tin[b + 7u], tin[b + 8u], tin[b + 9u], tin[b + 10u], R(0.0),
        R(0.0), R(0.0), R(0.0), R(0.0));
}

// The water-acceleration load of case i: line constants, tangent, acceleration, l0 wet.
@compute @workgroup_size(64)
fn t_froude_krylov(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 18u {
        return;
    }
    let b = i * 18u;
    v3out(i * 3u, froude_krylov(line_in(b), v3in(b + 11u), v3in(b + 14u), tin[b + 17u]));
}

@compute @workgroup_size(64)
fn t_element(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 27u {
        return;
    }
    let b = i * 27u;
    let c = line_in(b);
    let d = v3in(b + 11u);
    let el = glmf_element(c, d, norm3(d) - tin[b + 20u], v3in(b + 14u), v3in(b + 17u),
        tin[b + 20u], v3in(b + 21u), v3in(b + 24u));
    let o = i * 9u;
    v3out(o, el.t);
    tout[o + 3u] = el.tension;
    v3out(o + 4u, el.f_half);
    tout[o + 7u] = el.half_mass;
    tout[o + 8u] = el.half_added;
}

@compute @workgroup_size(64)
fn t_stretch(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 8u {
        return;
    }
    let b = i * 8u;
    tout[i] = element_stretch(v3in(b), v3in(b + 3u), tin[b + 6u], tin[b + 7u]);
}

@compute @workgroup_size(64)
fn t_seabed(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 5u {
        return;
    }
    let b = i * 5u;
    v3out(i * 3u, seabed_force(tin[b], tin[b + 1u], v3in(b + 2u)));
}

@compute @workgroup_size(64)
fn t_seabed_damping(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 5u {
        return;
    }
    let b = i * 5u;
    v3out(i * 3u, seabed_damping(tin[b], tin[b + 1u], v3in(b + 2u)));
}

// The seabed grid (bound as current range 0, params.seabed = 2) at (x, y) of case i.
@compute @workgroup_size(64)
fn t_seabed_height(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 2u {
        return;
    }
    v3out(i * 3u, seabed_height(tin[2u * i], tin[2u * i + 1u]));
}

// Sloped contact of case i: gap, lt, v, g (seabed_height's output); out: the force,
// the damping slopes (c_n, c_t) and the normal.
@compute @workgroup_size(64)
fn t_seabed_slope(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 8u {
        return;
    }
    let b = i * 8u;
    let g = v3in(b + 5u);
    v3out(b, seabed_slope_force(tin[b], tin[b + 1u], v3in(b + 2u), g));
    let d = seabed_slope_damping(tin[b], tin[b + 1u], v3in(b + 2u), g);
    tout[b + 3u] = d.x;
    tout[b + 4u] = d.y;
    v3out(b + 5u, seabed_slope_normal(g));
}

// The friction's axial split of case i: fnorm, n, v, t; out: (q, d).
@compute @workgroup_size(64)
fn t_seabed_friction_axis(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 10u {
        return;
    }
    let b = i * 10u;
    let o = seabed_friction_axis(tin[b], v3in(b + 1u), v3in(b + 4u), v3in(b + 7u));
    v3out(i * 4u, o.xyz);
    tout[i * 4u + 3u] = o.w;
}

@compute @workgroup_size(64)
fn t_mass(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 14u {
        return;
    }
    let b = i * 14u;
    var m = sym3_scalar(tin[b]);
    m = sym3_add_element(m, tin[b + 1u], tin[b + 2u], v3in(b + 3u));
    m = sym3_add_element(m, tin[b + 6u], tin[b + 7u], v3in(b + 8u));
    let x = sym3_solve(m, v3in(b + 11u));
    let o = i * 12u;
    tout[o] = m.xx;
    tout[o + 1u] = m.yy;
    tout[o + 2u] = m.zz;
    tout[o + 3u] = m.xy;
    tout[o + 4u] = m.xz;
    tout[o + 5u] = m.yz;
    v3out(o + 6u, x);
    v3out(o + 9u, sym3_mul(m, v3in(b + 11u)));
}

@compute @workgroup_size(64)
fn t_sincos(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) {
        return;
    }
    let sc = sin_cos(tin[i]);
    tout[2u * i] = sc.x;
    tout[2u * i + 1u] = sc.y;
}

@compute @workgroup_size(64)
fn t_route(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) {
        return;
    }
    let s = route_eval(routes[i], tin[i]);
    let o = i * 12u;
    v3out(o, s.r_hi);
    v3out(o + 3u, s.r_lo);
    v3out(o + 6u, s.v);
    v3out(o + 9u, s.a);
}

@compute @workgroup_size(64)
fn t_current(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 2u {
        return;
    }
    v3out(i * 3u, current_at(u32(tin[2u * i]), tin[2u * i + 1u]));
}
"#;

/// Runs `entry` of [`KERNELS`] over `input` with `group0` bound at group 0 and returns
/// `n_out` values.
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

/// Runs `entry` of the test kernels `kernels` (WGSL appended to the prelude, reading
/// `tin` and writing `tout` at group 1) over `input` with `group0` (binding, bytes) bound
/// at group 0, on `n_threads` invocations, and returns the first `n_out` values of
/// `tout`.
#[allow(clippy::too_many_arguments)]
pub fn run_kernels<R: GpuReal>(
    ctx: &GpuContext,
    p: Precision,
    kernels: &str,
    entry: &str,
    group0: &[(u32, Vec<u8>)],
    input: &[R],
    n_threads: usize,
    n_out: usize,
) -> Vec<R> {
    use wgpu::util::DeviceExt;
    let dev = &ctx.device;
    let src = format!("{}\n{kernels}", shaders::prelude(p));
    let scope = dev.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("function parity"),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let pipe = dev.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry),
        layout: None,
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
    let buf = |label: &str, bytes: &[u8]| {
        dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage,
        })
    };
    let g0: Vec<wgpu::Buffer> = group0.iter().map(|(_, b)| buf("group0", b)).collect();
    let tin = buf("tin", bytemuck::cast_slice(input));
    let out_bytes = (n_out * std::mem::size_of::<R>()) as u64;
    let tout = buf("tout", &vec![0u8; out_bytes as usize]);
    let staging = dev.create_buffer(&wgpu::BufferDescriptor {
        label: Some("staging"),
        size: out_bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bg0 = dev.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipe.get_bind_group_layout(0),
        entries: &group0
            .iter()
            .zip(&g0)
            .map(|((binding, _), b)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: b.as_entire_binding(),
            })
            .collect::<Vec<_>>(),
    });
    let bg1 = dev.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipe.get_bind_group_layout(1),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: tin.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: tout.as_entire_binding(),
            },
        ],
    });
    let mut enc = dev.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipe);
        pass.set_bind_group(0, &bg0, &[]);
        pass.set_bind_group(1, &bg1, &[]);
        pass.dispatch_workgroups((n_threads as u32).div_ceil(64), 1, 1);
    }
    enc.copy_buffer_to_buffer(&tout, 0, &staging, 0, out_bytes);
    ctx.queue.submit([enc.finish()]);
    if let Some(e) = pollster::block_on(scope.pop()) {
        panic!("{entry} ({}): {e}", p.name());
    }
    staging
        .slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.unwrap());
    dev.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let view = staging.slice(..).get_mapped_range().unwrap();
    view.chunks_exact(std::mem::size_of::<R>())
        .map(bytemuck::pod_read_unaligned)
        .collect()
}

/// Records the worst `|gpu - rust| / (eps scale)` of a function.
pub struct Worst {
    name: &'static str,
    eps: f64,
    worst: f64,
}

impl Worst {
    pub fn new<R: GpuReal>(name: &'static str) -> Self {
        Self {
            name,
            eps: R::epsilon().f64(),
            worst: 0.0,
        }
    }
    pub fn check(&mut self, what: &str, case: usize, gpu: f64, rust: f64, scale: f64) {
        let e = (gpu - rust).abs() / (self.eps * scale.max(f64::MIN_POSITIVE));
        self.worst = self.worst.max(e);
        assert!(
            e <= 16.0,
            "{} case {case} {what}: GPU {gpu:e}, Rust {rust:e}: {e:.1} eps x scale {scale:e}",
            self.name
        );
    }
    pub fn v(&mut self, what: &str, case: usize, gpu: &[f64], rust: V3<f64>, scale: f64) {
        for (k, r) in [rust.x, rust.y, rust.z].into_iter().enumerate() {
            self.check(what, case, gpu[k], r, scale);
        }
    }
    pub fn report(&self, p: Precision) {
        eprintln!(
            "{} ({}): worst difference {:.2} eps x scale (limit 16)",
            self.name,
            p.name(),
            self.worst
        );
    }
}

/// The line constants of a case as the test kernels read them (`line_in`: `tin[b..b +
/// 11]`, in `LineParams`' order).
pub fn line_case(a: &[f64]) -> Coefs<f64> {
    Coefs::<f64> {
        ea: a[0],
        ea_c: a[1],
        drag_n: a[2],
        drag_t: a[3],
        froude_krylov: a[4],
        froude_krylov_t: a[5],
        mass: a[6],
        added_mass: a[7],
        added_mass_t: a[8],
        wet_weight_z: a[9],
        compression: a[10],
    }
}

/// Random line constants in `LineParams`' order (case `i`: slack or a rod by its
/// parity), the water-acceleration and added-mass constants folded from random `Cm`,
/// `Cat` (below and above each other) on a random `rho A`.
pub fn random_line(rng: &mut ChaCha8Rng, i: usize) -> [f64; 11] {
    let ea = 10f64.powf(rng.gen_range(5.0..9.0));
    let rho_a = rng.gen_range(0.0..3.0);
    let (cm, cat) = (rng.gen_range(0.0..2.0), rng.gen_range(0.0..2.0));
    [
        ea,
        ea * rng.gen_range(0.0..1e-2),
        rng.gen_range(0.0..30.0),
        rng.gen_range(0.0..3.0),
        (1.0 + cm) * rho_a,
        (1.0 + cat) * rho_a,
        rng.gen_range(0.1..100.0),
        cm * rho_a,
        cat * rho_a,
        rng.gen_range(-500.0..50.0),
        (i % 2) as f64,
    ]
}

/// The line constants and element kinematics of one random element case as the test
/// kernels read it (`tin[b..b + 27]`: 11 coefficients, then r_b, v_a, v_b, l0, current,
/// water acceleration; r_a at the origin).
pub fn element_case(a: &[f64]) -> (Coefs<f64>, ElementInput<f64>) {
    let c = line_case(a);
    let v = |k: usize| V3::new(a[k], a[k + 1], a[k + 2]);
    let inp = ElementInput {
        ra: V3::zero(),
        rb: v(11),
        va: v(14),
        vb: v(17),
        l0: a[20],
        current: v(21),
        water_accel: v(24),
    };
    (c, inp)
}

pub fn rv(rng: &mut ChaCha8Rng, a: f64) -> [f64; 3] {
    [0, 1, 2].map(|_| rng.gen_range(-a..a))
}

/// Inputs as `R`, and back as f64 (what the GPU actually got).
pub fn to_r<R: GpuReal>(x: &[f64]) -> (Vec<R>, Vec<f64>) {
    let r: Vec<R> = x.iter().map(|&v| R::c(v)).collect();
    let back = r.iter().map(|v| v.f64()).collect();
    (r, back)
}

fn norm(v: V3<f64>) -> f64 {
    v.norm()
}

fn check_element<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 500;
    let mut x = Vec::new();
    for i in 0..n {
        let l0 = rng.gen_range(0.5..50.0);
        let l = l0 * (1.0 + rng.gen_range(-0.01..0.01));
        let dir = V3::<f64>::from_f64(rv(rng, 1.0));
        let d = dir / dir.norm() * l;
        x.extend(random_line(rng, i));
        x.extend(d.to_f64());
        x.extend(rv(rng, 2.0));
        x.extend(rv(rng, 2.0));
        x.push(l0);
        x.extend(rv(rng, 1.5));
        x.extend(rv(rng, 1.0));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_element", &[], &xr, n, 9 * n);
    let mut w = Worst::new::<R>("glmf_element");
    for i in 0..n {
        let a = &x[27 * i..27 * (i + 1)];
        let (c, inp) = element_case(a);
        let el = glmf_element(&c, &inp);
        let ext = cablesim::physics::glmf_external(&c, &inp, el.t, inp.rb.norm());
        let o = &out[9 * i..9 * (i + 1)];
        let o: Vec<f64> = o.iter().map(|v| v.f64()).collect();
        w.v("t", i, &o[0..3], el.t, 1.0);
        let l = inp.rb.norm();
        let t_scale = c.ea * l / inp.l0 + c.ea_c * (norm(inp.vb - inp.va) / inp.l0);
        w.check("tension", i, o[3], el.tension, t_scale);
        let f_scale = 0.5
            * (norm(ext.drag_n)
                + norm(ext.drag_t)
                + norm(ext.froude_krylov)
                + norm(ext.wet_weight));
        w.v("f_half", i, &o[4..7], el.f_half, f_scale);
        w.check("half_mass", i, o[7], el.half_mass, el.half_mass);
        let added = 0.5 * (c.added_mass + c.added_mass_t) * inp.l0;
        w.check("half_added", i, o[8], el.half_added, added);
    }
    w.report(p);
}

/// `froude_krylov`: the water-acceleration load across and along a line (random
/// tangents, accelerations, coefficients with `Cat` below and above `Cm`), within
/// `16 eps` of the sum of the two parts' magnitudes.
fn check_froude_krylov<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 500;
    let mut x = Vec::new();
    for i in 0..n {
        x.extend(random_line(rng, i));
        let dir = V3::<f64>::from_f64(rv(rng, 1.0));
        x.extend((dir / dir.norm()).to_f64());
        x.extend(rv(rng, 3.0));
        x.push(rng.gen_range(0.0..50.0));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_froude_krylov", &[], &xr, n, 3 * n);
    let mut w = Worst::new::<R>("froude_krylov");
    for i in 0..n {
        let a = &x[18 * i..18 * (i + 1)];
        let c = line_case(a);
        let v = |k: usize| V3::new(a[k], a[k + 1], a[k + 2]);
        // The tangent as the GPU got it: a unit vector to its precision's round-off.
        let (t, aw, vol) = (v(11), v(14), a[17]);
        let f = cablesim::physics::froude_krylov(&c, t, aw, vol);
        let scale = (c.froude_krylov + c.froude_krylov_t) * vol * aw.norm();
        let o: Vec<f64> = out[3 * i..3 * (i + 1)].iter().map(|v| v.f64()).collect();
        w.v("F_a", i, &o, f, scale);
    }
    w.report(p);
}

/// `element_stretch`: the stretch `|d| - l0` of an element given as compensated pairs,
/// against f64 on the same inputs (the pairs' sums are exact in f64). Contract in f32:
/// within `16 eps (|stretch| + eps l0)`, accurate relative to the stretch itself
/// (plain `|d| - l0` rounds to `eps l0`, a thousand to a million times more at strains
/// of 1e-3 to 1e-6). In f64 the twin is no better than `eps l0`, so that is the scale.
fn check_stretch<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let mut x = Vec::new();
    let mut exact = Vec::new();
    let pair = |v: f64| {
        let hi = R::c(v);
        let lo = R::c(v - hi.f64());
        (hi, lo)
    };
    for i in 0..n {
        let l0 = rng.gen_range(0.5..50.0);
        let strain = match i % 4 {
            0 => rng.gen_range(-1e-2..1e-2),
            1 => rng.gen_range(-1e-4..1e-4),
            2 => rng.gen_range(-1e-6..1e-6),
            _ => rng.gen_range(-1e-7..1e-7),
        };
        let dir = V3::<f64>::from_f64(rv(rng, 1.0));
        let d = dir / dir.norm() * (l0 * (1.0 + strain));
        let (lh, ll) = pair(l0);
        let mut row: Vec<R> = Vec::new();
        let (mut dh, mut dl) = ([R::c(0.0); 3], [R::c(0.0); 3]);
        for (k, v) in d.to_f64().into_iter().enumerate() {
            (dh[k], dl[k]) = pair(v);
        }
        row.extend(dh);
        row.extend(dl);
        row.push(lh);
        row.push(ll);
        // What the GPU got, in f64 (exact sums of the pairs).
        let dd: Vec<f64> = (0..3).map(|k| dh[k].f64() + dl[k].f64()).collect();
        let l = (dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]).sqrt();
        exact.push((l - (lh.f64() + ll.f64()), l0));
        x.extend(row);
    }
    let out = run::<R>(
        ctx,
        p,
        "t_stretch",
        &[(0, params::<R>(0.0, 0.0, 0.0, 0.01))],
        &x,
        n,
        n,
    );
    let mut w = Worst::new::<R>("element_stretch (compensated)");
    let eps = R::epsilon().f64();
    for (i, &(s, l0)) in exact.iter().enumerate() {
        let scale = if p == Precision::F32 {
            s.abs() + eps * l0
        } else {
            s.abs() + l0
        };
        w.check("stretch", i, out[i].f64(), s, scale);
    }
    w.report(p);
}

pub(crate) fn params<R: GpuReal>(k: f64, c: f64, mu: f64, v_eps: f64) -> Vec<u8> {
    bytemuck::bytes_of(&params_struct::<R>(k, c, mu, v_eps)).to_vec()
}

/// The seabed's run constants (the plane, isotropic friction `mu`).
pub(crate) fn params_struct<R: GpuReal>(k: f64, c: f64, mu: f64, v_eps: f64) -> Params<R> {
    Params::<R> {
        seabed: 1,
        seabed_k: R::c(k),
        seabed_c: R::c(c),
        seabed_mu: R::c(mu),
        seabed_v_eps: R::c(v_eps),
        seabed_mu_axial: R::c(mu),
        one: R::c(1.0),
        ..Default::default()
    }
}

fn check_seabed<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 500;
    let (k, c, mu, v_eps) = (3e6, 3e4, 0.6, 0.01);
    let sc = {
        let r = |x: f64| R::c(x).f64();
        SeabedCoefs {
            z: 0.0,
            k: r(k),
            c: r(c),
            mu: r(mu),
            mu_axial: r(mu),
            v_eps: r(v_eps),
        }
    };
    let mut x = Vec::new();
    for i in 0..n {
        x.push(rng.gen_range(-0.05..0.1));
        x.push(rng.gen_range(0.5..50.0));
        // Some at rest or creeping below v_eps, most sliding.
        let vs = if i % 5 == 0 { 0.005 } else { 1.0 };
        x.extend(rv(rng, vs));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(
        ctx,
        p,
        "t_seabed",
        &[(0, params::<R>(k, c, mu, v_eps))],
        &xr,
        n,
        3 * n,
    );
    let mut w = Worst::new::<R>("seabed_force");
    for i in 0..n {
        let a = &x[5 * i..5 * (i + 1)];
        let (pen, lt, v) = (a[0], a[1], V3::new(a[2], a[3], a[4]));
        // The twin takes the node's position: seabed at z = 0, node at z = -pen.
        let f = seabed_force(&sc, lt, V3::new(0.0, 0.0, -pen), v);
        let scale = sc.k * lt * pen.abs() * (1.0 + sc.mu) + sc.c * lt * v.z.abs();
        let o: Vec<f64> = out[3 * i..3 * i + 3].iter().map(|v| v.f64()).collect();
        w.v("force", i, &o, f, scale);
    }
    w.report(p);
    // The damping slopes node_advance takes implicitly, on the same inputs.
    let out = run::<R>(
        ctx,
        p,
        "t_seabed_damping",
        &[(0, params::<R>(k, c, mu, v_eps))],
        &xr,
        n,
        3 * n,
    );
    let mut w = Worst::new::<R>("seabed_damping");
    let mut sliding = 0;
    for i in 0..n {
        let a = &x[5 * i..5 * (i + 1)];
        let (pen, lt, v) = (a[0], a[1], V3::new(a[2], a[3], a[4]));
        let d = seabed_damping(&sc, lt, V3::new(0.0, 0.0, -pen), v);
        if d.x > 0.0 {
            sliding += 1;
        }
        let scale = sc.c * lt + sc.mu * sc.k * lt * pen.abs() / sc.v_eps;
        let o: Vec<f64> = out[3 * i..3 * i + 3].iter().map(|v| v.f64()).collect();
        w.v("slopes", i, &o, d, scale);
    }
    assert!(
        sliding > n / 2,
        "{sliding} of {n} nodes in contact with friction"
    );
    w.report(p);
}

fn check_mass<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 500;
    let mut x = Vec::new();
    for _ in 0..n {
        x.push(if rng.gen_bool(0.2) {
            rng.gen_range(0.0..1000.0)
        } else {
            0.0
        });
        for _ in 0..2 {
            // The normal plane's extra mass is negative where the tangential added mass
            // exceeds the normal one (`Cat > Cm`), and then smaller than the half mass.
            let s = rng.gen_range(1.0..100.0);
            x.push(s);
            x.push(if rng.gen_bool(0.3) {
                -rng.gen_range(0.0..0.9) * s
            } else {
                rng.gen_range(0.0..50.0)
            });
            let t = V3::<f64>::from_f64(rv(rng, 1.0));
            x.extend((t / t.norm()).to_f64());
        }
        x.extend(rv(rng, 1e4));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_mass", &[], &xr, n, 12 * n);
    let mut w = Worst::new::<R>("mass block (sym3_add_element, sym3_solve, sym3_mul)");
    for i in 0..n {
        let a = &x[14 * i..14 * (i + 1)];
        let mut m = Sym3::scalar(a[0]);
        let mut s_tot = a[0];
        let (mut a_pos, mut a_neg) = (0.0, 0.0);
        for k in [1usize, 6] {
            m.xx += a[k];
            m.yy += a[k];
            m.zz += a[k];
            m.add_normal_projection(a[k + 1], V3::new(a[k + 2], a[k + 3], a[k + 4]));
            s_tot += a[k];
            if a[k + 1] > 0.0 {
                a_pos += a[k + 1];
            } else {
                a_neg -= a[k + 1];
            }
        }
        let b = V3::new(a[11], a[12], a[13]);
        let xs = m.solve(b);
        let o: Vec<f64> = out[12 * i..12 * (i + 1)].iter().map(|v| v.f64()).collect();
        let mscale = s_tot + a_pos + a_neg;
        for (k, r) in [m.xx, m.yy, m.zz, m.xy, m.xz, m.yz].into_iter().enumerate() {
            w.check("m", i, o[k], r, mscale);
        }
        // Eigenvalues lie in [s_tot - a_neg, s_tot + a_pos]: the solve's error is the
        // condition number times eps times |x|'s scale |b| / (s_tot - a_neg).
        let lo = s_tot - a_neg;
        let cond = (s_tot + a_pos) / lo;
        w.v("solve", i, &o[6..9], xs, cond * cond * b.norm() / lo);
        w.v("mul", i, &o[9..12], m.mul_vec(b), mscale * b.norm());
    }
    w.report(p);
}

fn check_sincos<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let x: Vec<f64> = (0..n).map(|_| rng.gen_range(-2.0..9.0)).collect();
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_sincos", &[], &xr, n, 2 * n);
    let mut w = Worst::new::<R>("sin_cos");
    for i in 0..n {
        // The argument's own rounding does not count: scale 1 + |x|.
        w.check("sin", i, out[2 * i].f64(), x[i].sin(), 1.0 + x[i].abs());
        w.check("cos", i, out[2 * i + 1].f64(), x[i].cos(), 1.0 + x[i].abs());
    }
    w.report(p);
}

fn check_all<R: GpuReal>(ctx: &GpuContext, p: Precision) {
    let mut rng = ChaCha8Rng::seed_from_u64(20240611);
    check_element::<R>(ctx, p, &mut rng);
    check_froude_krylov::<R>(ctx, p, &mut rng);
    check_stretch::<R>(ctx, p, &mut rng);
    check_seabed::<R>(ctx, p, &mut rng);
    check_seabed_grid::<R>(ctx, p, &mut rng);
    check_seabed_slope::<R>(ctx, p, &mut rng);
    check_seabed_friction_axis::<R>(ctx, p, &mut rng);
    check_mass::<R>(ctx, p, &mut rng);
    check_sincos::<R>(ctx, p, &mut rng);
    check_route::<R>(ctx, p, &mut rng);
    check_current::<R>(ctx, p, &mut rng);
    check_tabulated::<R>(ctx, p, &mut rng);
    check_bending::<R>(ctx, p, &mut rng);
    check_visco::<R>(ctx, p, &mut rng);
    check_screen::<R>(ctx, p, &mut rng);
}

#[test]
fn wgsl_functions_match_their_rust_twins_in_f32() {
    let Some(ctx) = gpu_context("wgsl_functions_match_their_rust_twins_in_f32", false) else {
        return;
    };
    check_all::<f32>(&ctx, Precision::F32);
}

#[test]
fn wgsl_functions_match_their_rust_twins_in_f64() {
    let Some(ctx) = gpu_context("wgsl_functions_match_their_rust_twins_in_f64", true) else {
        return;
    };
    check_all::<f64>(&ctx, Precision::F64);
}
