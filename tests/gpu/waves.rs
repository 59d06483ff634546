//! Each WGSL wave function (`shaders/shared/waves.wgsl`) against its Rust twin
//! (`cablesim::sea`), on random inputs, at f32 and f64.
//!
//! As in tests/gpu_functions.rs: a test kernel calls one function per invocation, the
//! Rust twin runs in f64 on the values the GPU received (converted back), and every
//! output must be within `16 eps_R * scale`, `scale` the sum of the magnitudes of the
//! terms that make the output times the size of the rounding each term inherits from
//! its arguments (a phase `theta` carries `eps |theta|`, an exponent `eps |x|`), so a
//! missing or wrong term, of the size of `scale`, is caught.

use super::common::*;
use super::functions::{run_kernels, to_r, Worst};
use cablesim::gpu::layout::{GpuReal, WaveComp};
use cablesim::gpu::{GpuContext, Precision};
use cablesim::math::V3;
use cablesim::sea::bands::{wave_band, MAX_BANDS};
use cablesim::sea::cache::{hermite_weights, wave_cache_hermite, wave_cache_midpoint};
use cablesim::sea::cut::wave_decay_prefix;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::kinematics::{
    wave_depth_decay, wave_eval_depth, wave_eval_depth_rate, wave_kinematics_at,
    wave_kinematics_rates_tau, wave_ramp, wave_ramp_rate, PackedComponent, WaveField,
};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaState, Stretching, WaveComponent, GPU_DEEP};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};

mod cache;
mod exact;
use cache::*;

const KERNELS: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

@compute @workgroup_size(64)
fn t_exp(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) {
        return;
    }
    tout[i] = wave_exp(tin[i]);
}

@compute @workgroup_size(64)
fn t_ramp(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 2u {
        return;
    }
    tout[i] = wave_ramp(tin[2u * i], tin[2u * i + 1u]);
}

@compute @workgroup_size(64)
fn t_ramp_rate(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 2u {
        return;
    }
    tout[i] = wave_ramp_rate(tin[2u * i], tin[2u * i + 1u]);
}

@compute @workgroup_size(64)
fn t_decay(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 3u {
        return;
    }
    let d = wave_depth_decay(tin[3u * i], tin[3u * i + 1u], tin[3u * i + 2u]);
    tout[2u * i] = d.x;
    tout[2u * i + 1u] = d.y;
}

@compute @workgroup_size(64)
fn t_eval_depth(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 4u {
        return;
    }
    let b = 4u * i;
    tout[i] = wave_eval_depth(tin[b], tin[b + 1u], tin[b + 2u], u32(tin[b + 3u]));
}

// tin: z, eta, depth, stretching, vz, eta_rate per case.
@compute @workgroup_size(64)
fn t_eval_depth_rate(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 6u {
        return;
    }
    let b = 6u * i;
    tout[i] = wave_eval_depth_rate(tin[b], tin[b + 1u], tin[b + 2u], u32(tin[b + 3u]), tin[b + 4u], tin[b + 5u]);
}

fn kin_out(o: u32, k: WaveKin) {
    tout[o] = k.eta;
    tout[o + 1u] = k.u.x;
    tout[o + 2u] = k.u.y;
    tout[o + 3u] = k.u.z;
    tout[o + 4u] = k.a.x;
    tout[o + 5u] = k.a.y;
    tout[o + 6u] = k.a.z;
}

fn kin_in(b: u32) -> WaveKin {
    return WaveKin(tin[b], vec3<R>(tin[b + 1u], tin[b + 2u], tin[b + 3u]),
        vec3<R>(tin[b + 4u], tin[b + 5u], tin[b + 6u]));
}

// tin: n, depth, stretching, ramp duration, t_ref, then x, y, z, t per point.
@compute @workgroup_size(64)
fn t_kin(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= (arrayLength(&tin) - 5u) / 4u {
        return;
    }
    let b = 5u + 4u * i;
    let k = wave_kinematics_at(u32(tin[0]), tin[1], u32(tin[2]), tin[3],
        vec3<R>(tin[b], tin[b + 1u], tin[b + 2u]), tin[b + 3u], tin[4]);
    kin_out(7u * i, k);
}

// tin: n, depth, stretching, then x, y, z, vx, vy, vz, tau, r, r_rate per point;
// tout: the values, then the rates (14 per point).
@compute @workgroup_size(64)
fn t_kin_rates(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= (arrayLength(&tin) - 3u) / 9u {
        return;
    }
    let b = 3u + 9u * i;
    let k = wave_kinematics_rates_tau(0u, u32(tin[0]), tin[1], u32(tin[2]), tin[b + 7u], tin[b + 8u],
        vec3<R>(tin[b], tin[b + 1u], tin[b + 2u]), vec3<R>(tin[b + 3u], tin[b + 4u], tin[b + 5u]), tin[b + 6u]);
    kin_out(14u * i, k.val);
    kin_out(14u * i + 7u, k.rate);
}

// tin: n, then zs, s, r_rate per case; tout: the prefix length.
@compute @workgroup_size(64)
fn t_prefix(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= (arrayLength(&tin) - 1u) / 3u {
        return;
    }
    let b = 1u + 3u * i;
    tout[i] = R(wave_decay_prefix(0u, u32(tin[0]), tin[b], tin[b + 1u], tin[b + 2u]));
}

// tin: v0, d0, v1, d1 (7 each), then the four weights, per case.
@compute @workgroup_size(64)
fn t_hermite(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 32u {
        return;
    }
    let b = 32u * i;
    let w = vec4<R>(tin[b + 28u], tin[b + 29u], tin[b + 30u], tin[b + 31u]);
    kin_out(7u * i, wave_cache_hermite(kin_in(b), kin_in(b + 7u), kin_in(b + 14u), kin_in(b + 21u), w));
}

fn mid_out(o: u32, m: WaveMid) {
    tout[o] = m.eta_a;
    tout[o + 1u] = m.eta_b;
    tout[o + 2u] = m.u.x;
    tout[o + 3u] = m.u.y;
    tout[o + 4u] = m.u.z;
    tout[o + 5u] = m.a.x;
    tout[o + 6u] = m.a.y;
    tout[o + 7u] = m.a.z;
}

// tin: per side (values at t0, rates at t0, values at t1, rates at t1) node a's and
// node b's 7, then the four weights, per case; tout: the four sides' midpoints
// (wave_cache_midpoint), then their interpolation (wave_mid_hermite): 40 per case.
@compute @workgroup_size(64)
fn t_midpoint(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 60u {
        return;
    }
    let b = 60u * i;
    var m: array<WaveMid, 4>;
    for (var q = 0u; q < 4u; q++) {
        m[q] = wave_cache_midpoint(kin_in(b + 14u * q), kin_in(b + 14u * q + 7u));
        mid_out(40u * i + 8u * q, m[q]);
    }
    let w = vec4<R>(tin[b + 56u], tin[b + 57u], tin[b + 58u], tin[b + 59u]);
    mid_out(40u * i + 32u, wave_mid_hermite(m[0], m[1], m[2], m[3], w));
}

// tin: z, vz, az, band 0's look-ahead, margin, tops[1..7], n_bands per case; tout: the band.
@compute @workgroup_size(64)
fn t_band(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 12u {
        return;
    }
    let b = 12u * i;
    let tops = array<R, 6>(tin[b + 5u], tin[b + 6u], tin[b + 7u], tin[b + 8u], tin[b + 9u], tin[b + 10u]);
    tout[i] = R(wave_band(tin[b], tin[b + 1u], tin[b + 2u], tin[b + 3u], tin[b + 4u], tops, u32(tin[b + 11u])));
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

fn check_exp<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    // Down to where f32 results are still normal numbers.
    let low = if R::epsilon().f64() > 1e-10 {
        -85.0
    } else {
        -740.0
    };
    let n = 2000;
    let x: Vec<f64> = (0..n)
        .map(|i| match i % 3 {
            0 => rng.gen_range(-1.0..0.0),
            1 => rng.gen_range(-30.0..0.0),
            _ => rng.gen_range(low..0.0),
        })
        .collect();
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_exp", &[], &xr, n, n);
    let mut w = Worst::new::<R>("wave_exp");
    for i in 0..n {
        // Relative accuracy: the argument's own rounding is not counted.
        w.check("exp", i, out[i].f64(), x[i].exp(), x[i].exp());
    }
    w.report(p);
}

fn check_ramp<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let mut x = Vec::new();
    for i in 0..n {
        x.push(rng.gen_range(-5.0..30.0));
        x.push([0.0, 20.0, 7.3][i % 3]);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_ramp", &[], &xr, n, n);
    let mut w = Worst::new::<R>("wave_ramp");
    for i in 0..n {
        let (t, tr) = (x[2 * i], x[2 * i + 1]);
        let scale = 1.0 + if tr > 0.0 { PI * t.abs() / tr } else { 0.0 };
        w.check("ramp", i, out[i].f64(), wave_ramp(t, tr), scale);
    }
    w.report(p);
}

fn check_ramp_rate<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let mut x = Vec::new();
    for i in 0..n {
        x.push(rng.gen_range(-5.0..30.0));
        x.push([0.0, 20.0, 7.3][i % 3]);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_ramp_rate", &[], &xr, n, n);
    let mut w = Worst::new::<R>("wave_ramp_rate");
    for i in 0..n {
        let (t, tr) = (x[2 * i], x[2 * i + 1]);
        // The rate's size pi / (2 T_r), times the rounding of its phase pi t / T_r.
        let scale = if tr > 0.0 {
            PI / (2.0 * tr) * (1.0 + PI * t.abs() / tr)
        } else {
            1.0
        };
        w.check("ramp rate", i, out[i].f64(), wave_ramp_rate(t, tr), scale);
    }
    w.report(p);
}

fn check_decay<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1500;
    let mut x = Vec::new();
    for i in 0..n {
        let h = [5.0, 80.0, GPU_DEEP][i % 3];
        x.push(10f64.powf(rng.gen_range(-4.0..0.5)));
        x.push(-rng.gen_range(0.0..h.min(300.0)));
        x.push(h);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_decay", &[], &xr, n, 2 * n);
    let mut w = Worst::new::<R>("wave_depth_decay");
    let floor = R::min_positive_value().f64() / R::epsilon().f64();
    for i in 0..n {
        let (k, zs, h) = (x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        let (c, s) = wave_depth_decay(k, zs, h);
        let e1 = (k * zs).exp();
        let e2 = (-k * (zs + 2.0 * h)).exp();
        // Plus the underflow floor: below the smallest normal number the GPU may flush
        // to zero (f32 reaches it at e^-87).
        let scale = e1 * (1.0 + (k * zs).abs()) + e2 * (1.0 + (k * (zs + 2.0 * h)).abs()) + floor;
        w.check("cosh part", i, out[2 * i].f64(), c, scale);
        w.check("sinh part", i, out[2 * i + 1].f64(), s, scale);
    }
    w.report(p);
}

fn check_eval_depth<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let mut x = Vec::new();
    for i in 0..n {
        let h = [6.0, 80.0, GPU_DEEP][i % 3];
        x.push(rng.gen_range(-h.min(300.0)..5.0));
        x.push(rng.gen_range(-3.0..3.0));
        x.push(h);
        x.push((i / 3 % 2) as f64);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_eval_depth", &[], &xr, n, n);
    let mut w = Worst::new::<R>("wave_eval_depth");
    for i in 0..n {
        let (z, eta, h) = (x[4 * i], x[4 * i + 1], x[4 * i + 2]);
        let s = [Stretching::Wheeler, Stretching::Constant][x[4 * i + 3] as usize];
        let scale = (z.abs() + eta.abs()) / (1.0 + eta / h);
        w.check("zs", i, out[i].f64(), wave_eval_depth(z, eta, h, s), scale);
    }
    w.report(p);
}

fn check_eval_depth_rate<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let mut x = Vec::new();
    for i in 0..n {
        let h = [6.0, 80.0, GPU_DEEP][i % 3];
        x.push(rng.gen_range(-h.min(300.0)..5.0));
        x.push(rng.gen_range(-3.0..3.0));
        x.push(h);
        x.push((i / 3 % 2) as f64);
        x.push(rng.gen_range(-4.0..4.0));
        x.push(rng.gen_range(-6.0..6.0));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_eval_depth_rate", &[], &xr, n, n);
    let mut w = Worst::new::<R>("wave_eval_depth_rate");
    let mut clamped = 0;
    for i in 0..n {
        let b = &x[6 * i..6 * i + 6];
        let (z, eta, h, vz, er) = (b[0], b[1], b[2], b[4], b[5]);
        let s = [Stretching::Wheeler, Stretching::Constant][b[3] as usize];
        let rust = wave_eval_depth_rate(z, eta, h, s, vz, er);
        clamped += usize::from(rust == 0.0);
        let d = 1.0 + eta / h;
        let zs = (z.abs() + eta.abs()) / d;
        let scale = (vz.abs() + er.abs() * (1.0 + zs / h)) / d * (1.0 + eta.abs() / h / d);
        w.check("zs rate", i, out[i].f64(), rust, scale);
    }
    // Both sides of the clamp are exercised.
    assert!(
        clamped > n / 20 && clamped < n / 2,
        "{clamped} clamped of {n}"
    );
    w.report(p);
}

/// Components at precision `R` (as bytes for binding 17) and back as f64.
fn gpu_comps<R: GpuReal>(field: &WaveField) -> (Vec<u8>, Vec<PackedComponent>) {
    let comps: Vec<WaveComp<R>> = field.comps.iter().map(WaveComp::from_packed).collect();
    let back = comps
        .iter()
        .map(|c| {
            let [kx, ky, phase_ref, omega] = c.phase.map(|x| x.f64());
            let [amp, amp_u, amp_a, k] = c.amps.map(|x| x.f64());
            let [cos_b, sin_b, _, _] = c.dir.map(|x| x.f64());
            let [k_cut, cut0, cut1, cut2] = c.cut.map(|x| x.f64());
            assert_eq!(k, k_cut, "k is stored twice, the same");
            PackedComponent {
                kx,
                ky,
                k,
                omega,
                phase_ref,
                amp,
                amp_u,
                amp_a,
                cos_b,
                sin_b,
                cut0,
                cut1,
                cut2,
            }
        })
        .collect();
    (bytemuck::cast_slice(&comps).to_vec(), back)
}

/// A JONSWAP train of 40 components spread `cos^4` about 20 degrees plus a regular
/// wave across it.
fn sea(depth: f64, stretching: Stretching, ramp: f64) -> SeaState {
    let g = 9.81;
    let mut comps = discretise(
        &Spectrum::Jonswap {
            hs: 4.0,
            tp: 9.0,
            gamma: 3.3,
        },
        &Discretisation {
            components: 40,
            direction: 20f64.to_radians(),
            spreading: Some(4.0),
            seed: 11,
            stream: 0,
        },
        depth,
        g,
    );
    let w = TAU / 12.0;
    comps.push(WaveComponent {
        amplitude: 0.8,
        omega: w,
        k: cablesim::sea::dispersion::wave_number(w, depth, g),
        direction: -1.2,
        phase: 0.4,
    });
    SeaState {
        components: comps,
        stretching,
        ramp_duration: ramp,
        ..SeaState::still(depth)
    }
}

fn check_kinematics<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    for (case, (depth, stretching, ramp, t_ref, t_range)) in [
        (60.0, Stretching::Wheeler, 20.0, 100.0, (95.0, 125.0)),
        (f64::INFINITY, Stretching::Constant, 20.0, 0.0, (0.0, 30.0)),
        (15.0, Stretching::Wheeler, 0.0, 3.0, (0.0, 10.0)),
    ]
    .into_iter()
    .enumerate()
    {
        let s = sea(depth, stretching, ramp);
        let mut field = WaveField::new(&s);
        field.rebase(t_ref);
        let (bytes, comps) = gpu_comps::<R>(&field);
        let gpu_depth = depth.min(GPU_DEEP);
        let code = match stretching {
            Stretching::Wheeler => 0.0,
            Stretching::Constant => 1.0,
        };
        let n = 500;
        let mut x = vec![comps.len() as f64, gpu_depth, code, ramp, t_ref];
        for _ in 0..n {
            x.push(rng.gen_range(-150.0..150.0));
            x.push(rng.gen_range(-150.0..150.0));
            x.push(rng.gen_range(-depth.min(200.0)..3.0));
            x.push(rng.gen_range(t_range.0..t_range.1));
        }
        let (xr, x) = to_r::<R>(&x);
        let out = run::<R>(ctx, p, "t_kin", &[(17, bytes)], &xr, n, 7 * n);
        let (h, ramp, t_ref) = (x[1], x[3], x[4]);
        let mut w = Worst::new::<R>("wave_kinematics_at");
        for i in 0..n {
            let q = &x[5 + 4 * i..9 + 4 * i];
            let (pt, t) = ([q[0], q[1], q[2]], q[3]);
            let k = wave_kinematics_at(&comps, h, stretching, ramp, pt, t, t_ref);
            let r = wave_ramp(t, ramp);
            let tau = t - t_ref;
            let ramp_err = if ramp > 0.0 && t < ramp {
                PI * t / ramp
            } else {
                0.0
            };
            // The phase of each term carries the rounding of its pieces.
            let theta = |c: &PackedComponent| {
                1.0 + ramp_err
                    + (c.kx * pt[0]).abs()
                    + (c.ky * pt[1]).abs()
                    + c.phase_ref.abs()
                    + (c.omega * tau).abs()
            };
            let s_eta: f64 = comps.iter().map(|c| c.amp * theta(c)).sum();
            let zs = wave_eval_depth(pt[2], k.eta, h, stretching);
            let depth_term = |c: &PackedComponent| {
                let e1 = (c.k * zs).exp();
                let e2 = (-c.k * (zs + 2.0 * h)).exp();
                let shift = c.k * (s_eta + pt[2].abs() + zs.abs());
                e1 * (theta(c) + shift) + e2 * (theta(c) + shift + (c.k * (zs + 2.0 * h)).abs())
            };
            let s_u: f64 = comps.iter().map(|c| c.amp_u * depth_term(c)).sum();
            let s_a: f64 = comps.iter().map(|c| c.amp_a * depth_term(c)).sum();
            let o: Vec<f64> = out[7 * i..7 * i + 7].iter().map(|v| v.f64()).collect();
            let what = format!("case {case} eta");
            w.check(&what, i, o[0], k.eta, r * s_eta);
            let v = |a: [f64; 3]| V3::new(a[0], a[1], a[2]);
            w.v("u", i, &o[1..4], v(k.u), r * s_u);
            w.v("a", i, &o[4..7], v(k.a), r * s_a);
        }
        w.report(p);
    }
}

fn check_kinematics_rates<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    for (case, (depth, stretching, t_ref)) in [
        (60.0, Stretching::Wheeler, 100.0),
        (f64::INFINITY, Stretching::Constant, 0.0),
        (15.0, Stretching::Wheeler, 3.0),
    ]
    .into_iter()
    .enumerate()
    {
        let s = sea(depth, stretching, 0.0);
        let mut field = WaveField::new(&s);
        field.rebase(t_ref);
        let (bytes, comps) = gpu_comps::<R>(&field);
        let code = match stretching {
            Stretching::Wheeler => 0.0,
            Stretching::Constant => 1.0,
        };
        let n = 500;
        let mut x = vec![comps.len() as f64, depth.min(GPU_DEEP), code];
        for i in 0..n {
            x.push(rng.gen_range(-150.0..150.0));
            x.push(rng.gen_range(-150.0..150.0));
            x.push(rng.gen_range(-depth.min(200.0)..3.0));
            for _ in 0..3 {
                x.push(rng.gen_range(-3.0..3.0));
            }
            x.push(rng.gen_range(-5.0..25.0));
            // Ramp factor and rate: full, or within a ramp.
            let (r, r_rate) = if i % 3 == 0 {
                (1.0, 0.0)
            } else {
                (rng.gen_range(0.0..1.0), rng.gen_range(0.0..0.08))
            };
            x.push(r);
            x.push(r_rate);
        }
        let (xr, x) = to_r::<R>(&x);
        let out = run::<R>(ctx, p, "t_kin_rates", &[(17, bytes)], &xr, n, 14 * n);
        let h = x[1];
        let mut w = Worst::new::<R>("wave_kinematics_rates_tau");
        for i in 0..n {
            let q = &x[3 + 9 * i..12 + 9 * i];
            let (pt, v, tau, r, r_rate) =
                ([q[0], q[1], q[2]], [q[3], q[4], q[5]], q[6], q[7], q[8]);
            let (kv, kr) = wave_kinematics_rates_tau(&comps, h, stretching, r, r_rate, pt, v, tau);
            // Sizes as in check_kinematics: the phase of each term carries the rounding
            // of its pieces, the depth decay that of the evaluation depth.
            let theta = |c: &PackedComponent| {
                1.0 + (c.kx * pt[0]).abs()
                    + (c.ky * pt[1]).abs()
                    + c.phase_ref.abs()
                    + (c.omega * tau).abs()
            };
            // The size of a phase's rate.
            let theta_rate =
                |c: &PackedComponent| (c.kx * v[0]).abs() + (c.ky * v[1]).abs() + c.omega;
            let s_eta: f64 = comps.iter().map(|c| c.amp * theta(c)).sum();
            let s_eta_rate: f64 = r * comps
                .iter()
                .map(|c| c.amp * theta(c) * theta_rate(c))
                .sum::<f64>()
                + r_rate.abs() * s_eta;
            let zs = wave_eval_depth(pt[2], kv.eta, h, stretching);
            let zs_rate = wave_eval_depth_rate(pt[2], kv.eta, h, stretching, v[2], kr.eta);
            let d = 1.0 + kv.eta / h;
            let zs_rate_size = match stretching {
                Stretching::Wheeler => {
                    (v[2].abs() + s_eta_rate * (1.0 + zs.abs() / h) + zs_rate.abs() * r * s_eta / h)
                        / d
                }
                Stretching::Constant => v[2].abs(),
            };
            let exps = |c: &PackedComponent| ((c.k * zs).exp(), (-c.k * (zs + 2.0 * h)).exp());
            let depth_term = |c: &PackedComponent| {
                let (e1, e2) = exps(c);
                let shift = c.k * (s_eta + pt[2].abs() + zs.abs());
                e1 * (theta(c) + shift) + e2 * (theta(c) + shift + (c.k * (zs + 2.0 * h)).abs())
            };
            // A rate term: the value's size times the phase's and the depth's rates,
            // plus the rounding of the depth's rate.
            let rate_term = |c: &PackedComponent| {
                let (e1, e2) = exps(c);
                depth_term(c) * (theta_rate(c) + c.k * zs_rate.abs())
                    + (e1 + e2) * c.k * zs_rate_size
            };
            let s_u: f64 = comps.iter().map(|c| c.amp_u * depth_term(c)).sum();
            let s_a: f64 = comps.iter().map(|c| c.amp_a * depth_term(c)).sum();
            let s_du =
                r * comps.iter().map(|c| c.amp_u * rate_term(c)).sum::<f64>() + r_rate.abs() * s_u;
            let s_da =
                r * comps.iter().map(|c| c.amp_a * rate_term(c)).sum::<f64>() + r_rate.abs() * s_a;
            let o: Vec<f64> = out[14 * i..14 * i + 14].iter().map(|v| v.f64()).collect();
            let vv = |a: [f64; 3]| V3::new(a[0], a[1], a[2]);
            let what = format!("case {case} eta");
            w.check(&what, i, o[0], kv.eta, r * s_eta);
            w.v("u", i, &o[1..4], vv(kv.u), r * s_u);
            w.v("a", i, &o[4..7], vv(kv.a), r * s_a);
            w.check("eta rate", i, o[7], kr.eta, s_eta_rate);
            w.v("u rate", i, &o[8..11], vv(kr.u), s_du);
            w.v("a rate", i, &o[11..14], vv(kr.a), s_da);
        }
        w.report(p);
    }
}

fn check_all<R: GpuReal>(ctx: &GpuContext, p: Precision) {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    check_exp::<R>(ctx, p, &mut rng);
    check_ramp::<R>(ctx, p, &mut rng);
    check_decay::<R>(ctx, p, &mut rng);
    check_eval_depth::<R>(ctx, p, &mut rng);
    check_kinematics::<R>(ctx, p, &mut rng);
    check_ramp_rate::<R>(ctx, p, &mut rng);
    check_eval_depth_rate::<R>(ctx, p, &mut rng);
    check_kinematics_rates::<R>(ctx, p, &mut rng);
    check_decay_prefix::<R>(ctx, p, &mut rng);
    check_hermite::<R>(ctx, p, &mut rng);
    check_midpoint::<R>(ctx, p, &mut rng);
    check_band::<R>(ctx, p, &mut rng);
}

#[test]
fn wgsl_wave_functions_match_their_rust_twins_in_f32() {
    let Some(ctx) = gpu_context("wgsl_wave_functions_match_their_rust_twins_in_f32", false) else {
        return;
    };
    check_all::<f32>(&ctx, Precision::F32);
}

#[test]
fn wgsl_wave_functions_match_their_rust_twins_in_f64() {
    let Some(ctx) = gpu_context("wgsl_wave_functions_match_their_rust_twins_in_f64", true) else {
        return;
    };
    check_all::<f64>(&ctx, Precision::F64);
}

/// The WGSL band decision's margin is the Rust one (`sea::bands::BAND_MARGIN`): the
/// shader holds it as a literal constant, which would otherwise drift unseen.
#[test]
fn wgsl_band_margin_is_the_rust_one() {
    let line = cablesim::gpu::shaders::WAVES
        .lines()
        .find(|l| l.trim_start().starts_with("const WAVE_BAND_MARGIN"))
        .expect("const WAVE_BAND_MARGIN in shaders/shared/waves.wgsl");
    let value: f64 = line
        .split('=')
        .nth(1)
        .expect("a value")
        .trim()
        .trim_end_matches(';')
        .parse()
        .expect("a number");
    assert_eq!(value, cablesim::sea::bands::BAND_MARGIN);
}
