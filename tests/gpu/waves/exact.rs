//! `wave_exp` and `wave_depth_decay` against the forms they replaced (branch `hgpuref`),
//! bit for bit on the same device: `wave_exp`'s factor 2^n by `ldexp` where it was
//! built by repeated squaring of 1/2, and `wave_depth_decay` without the seabed's term
//! where `2 k (zs + h) > 39`. The old forms are kept here, as test kernels only; the
//! new must give the same bits (the comments in shaders/shared/waves.wgsl say why),
//! including where the results leave the normal numbers.

use super::*;

const OLD_FORMS: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

// wave_exp before branch hgpuref: the factor 2^n by repeated squaring of 1/2.
fn wave_exp_squaring(x: R) -> R {
    if x < R(-745.0) {
        return R(0.0);
    }
    let n = floor(x * R(1.4426950408889634) + R(0.5));
    let r = (x - n * WAVE_LN2_HI) - n * WAVE_LN2_LO;
    let p = R(1.0) + r * (R(1.0) + r * (R(1.0 / 2.0) + r * (R(1.0 / 6.0) + r * (R(1.0 / 24.0)
        + r * (R(1.0 / 120.0) + r * (R(1.0 / 720.0) + r * (R(1.0 / 5040.0) + r * (R(1.0 / 40320.0)
        + r * (R(1.0 / 362880.0) + r * (R(1.0 / 3628800.0) + r * (R(1.0 / 39916800.0)
        + r * (R(1.0 / 479001600.0) + r * R(1.0 / 6227020800.0)))))))))))));
    var m = u32(-n);
    var s = R(1.0);
    var b = R(0.5);
    loop {
        if m == 0u {
            break;
        }
        if (m & 1u) == 1u {
            s = s * b;
        }
        b = b * b;
        m = m >> 1u;
    }
    return p * s;
}

// wave_depth_decay before branch hgpuref: both exponentials always.
fn wave_depth_decay_both(k: R, zs: R, depth: R) -> vec2<R> {
    let e1 = wave_exp_squaring(k * zs);
    let e2 = wave_exp_squaring(-k * (zs + R(2.0) * depth));
    return vec2<R>(e1 + e2, e1 - e2);
}

@compute @workgroup_size(64)
fn t_exp_pair(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) {
        return;
    }
    tout[2u * i] = wave_exp(tin[i]);
    tout[2u * i + 1u] = wave_exp_squaring(tin[i]);
}

@compute @workgroup_size(64)
fn t_decay_pair(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 3u {
        return;
    }
    let d = wave_depth_decay(tin[3u * i], tin[3u * i + 1u], tin[3u * i + 2u]);
    let o = wave_depth_decay_both(tin[3u * i], tin[3u * i + 1u], tin[3u * i + 2u]);
    tout[4u * i] = d.x;
    tout[4u * i + 1u] = d.y;
    tout[4u * i + 2u] = o.x;
    tout[4u * i + 3u] = o.y;
}
"#;

/// The first index where `new` and `old` differ in their bits, with both values.
fn first_difference<R: GpuReal>(new: &[R], old: &[R]) -> Option<(usize, f64, f64)> {
    new.iter()
        .zip(old)
        .enumerate()
        .find(|(_, (a, b))| a.f64().to_bits() != b.f64().to_bits())
        .map(|(i, (a, b))| (i, a.f64(), b.f64()))
}

fn check_exp_bits<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    // Every scale of the domain x <= 0, beyond the old cut-off -745, and dense where
    // the results become subnormal and then 0: f32 below -87.3 (2^-126) with the
    // least subnormal 2^-149 at -103.3, f64 below -708.4 with 2^-1074 at -744.4.
    let mut x: Vec<f64> = vec![0.0, -0.0, -745.0, -744.5, -708.4, -103.5, -103.3, -87.3];
    for i in 0..6000 {
        x.push(match i % 6 {
            0 => rng.gen_range(-1.0..0.0),
            1 => rng.gen_range(-30.0..0.0),
            2 => rng.gen_range(-800.0..0.0),
            3 => rng.gen_range(-106.0..-86.0),
            4 => rng.gen_range(-746.0..-706.0),
            _ => -(10f64.powf(rng.gen_range(-8.0..2.9))),
        });
    }
    let (xr, x) = to_r::<R>(&x);
    let n = x.len();
    let out = run_kernels::<R>(ctx, p, OLD_FORMS, "t_exp_pair", &[], &xr, n, 2 * n);
    let new: Vec<R> = out.iter().step_by(2).copied().collect();
    let old: Vec<R> = out.iter().skip(1).step_by(2).copied().collect();
    if let Some((i, a, b)) = first_difference(&new, &old) {
        panic!(
            "{p:?}: wave_exp({}) = {a:e} by ldexp, {b:e} by squaring",
            x[i]
        );
    }
    // Not vacuous: some results are 0, some are in (0, 1), and some subnormal or not.
    let zeros = old.iter().filter(|v| v.f64() == 0.0).count();
    let inner = old
        .iter()
        .filter(|v| v.f64() > 0.0 && v.f64() < 1.0)
        .count();
    assert!(
        zeros > 50 && inner > 2000,
        "{p:?}: {zeros} zeros, {inner} in (0, 1)"
    );
    eprintln!("{p:?}: wave_exp the same bits at {n} arguments ({zeros} results 0)");
}

fn check_decay_bits<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let mut x = Vec::new();
    let mut skipped = 0;
    for i in 0..6000 {
        let h = [5.0, 80.0, 320.0, 1000.0, GPU_DEEP][i % 5];
        let k = 10f64.powf(rng.gen_range(-4.0..0.7));
        // Half anywhere in the column, half where 2 k (zs + h) is near 39.
        let zs = if i % 2 == 0 {
            -rng.gen_range(0.0..h.min(400.0))
        } else {
            (39.0 * rng.gen_range(0.95..1.05) / (2.0 * k) - h).clamp(-h, 0.0)
        };
        skipped += usize::from(2.0 * k * (zs + h) > 39.0);
        x.extend([k, zs, h]);
    }
    let (xr, _) = to_r::<R>(&x);
    let n = x.len() / 3;
    let out = run_kernels::<R>(ctx, p, OLD_FORMS, "t_decay_pair", &[], &xr, n, 4 * n);
    let new: Vec<R> = out.chunks(4).flat_map(|c| [c[0], c[1]]).collect();
    let old: Vec<R> = out.chunks(4).flat_map(|c| [c[2], c[3]]).collect();
    if let Some((i, a, b)) = first_difference(&new, &old) {
        let j = i / 2;
        panic!(
            "{p:?}: wave_depth_decay(k {}, zs {}, h {}) component {}: {a:e} without the \
             seabed's term, {b:e} with it",
            x[3 * j],
            x[3 * j + 1],
            x[3 * j + 2],
            i % 2
        );
    }
    assert!(
        skipped > 1000 && skipped < n - 1000,
        "{p:?}: {skipped} of {n} skip the seabed"
    );
    eprintln!("{p:?}: wave_depth_decay the same bits at {n} points ({skipped} skip the seabed)");
}

#[test]
fn wave_exp_and_depth_decay_keep_their_bits_in_f32() {
    let Some(ctx) = gpu_context("wave_exp_and_depth_decay_keep_their_bits_in_f32", false) else {
        return;
    };
    let mut rng = ChaCha8Rng::seed_from_u64(85);
    check_exp_bits::<f32>(&ctx, Precision::F32, &mut rng);
    check_decay_bits::<f32>(&ctx, Precision::F32, &mut rng);
}

#[test]
fn wave_exp_and_depth_decay_keep_their_bits_in_f64() {
    let Some(ctx) = gpu_context("wave_exp_and_depth_decay_keep_their_bits_in_f64", true) else {
        return;
    };
    let mut rng = ChaCha8Rng::seed_from_u64(86);
    check_exp_bits::<f64>(&ctx, Precision::F64, &mut rng);
    check_decay_bits::<f64>(&ctx, Precision::F64, &mut rng);
}
