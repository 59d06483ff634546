//! The kinematics cache's WGSL functions against their Rust twins, run by `waves`'s
//! `check_all` (moved from `waves.rs`): the decay cut's prefix length, the Hermite
//! weights, the midpoint values and the refresh band of a node.

use super::*;

/// The decay cut's prefix length against the Rust twin on the components the GPU
/// received: equal, but where the bound at the boundary is within the precision's
/// rounding of 1 (then one more or less).
pub(super) fn check_decay_prefix<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let s = sea(300.0, Stretching::Wheeler, 30.0);
    let field = WaveField::new(&s);
    let (bytes, comps) = gpu_comps::<R>(&field);
    let n = 1000;
    let mut x = vec![comps.len() as f64];
    for _ in 0..n {
        x.push(-rng.gen_range(0.0..300.0f64).powf(rng.gen_range(0.5..1.0)));
        x.push(rng.gen_range(0.0..4.0));
        x.push(rng.gen_range(0.0..0.05));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_prefix", &[(17, bytes)], &xr, n, n);
    let (mut inner, mut near) = (0, 0);
    for i in 0..n {
        let (zs, sp, rr) = (x[1 + 3 * i], x[2 + 3 * i], x[3 + 3 * i]);
        let m = wave_decay_prefix(&comps, zs, sp, rr);
        let g = out[i].f64() as usize;
        inner += usize::from(m > 0 && m < comps.len());
        if g != m {
            let j = g.min(m);
            let c = &comps[j];
            let bound = (c.k * zs).exp() * (c.cut0 + c.cut1 * sp + c.cut2 * rr);
            let tol = 64.0 * R::epsilon().f64() * (1.0 + (c.k * zs).abs());
            assert!(
                g.abs_diff(m) == 1 && (bound - 1.0).abs() <= tol,
                "{p:?} case {i}: zs {zs}: GPU {g}, Rust {m} (bound {bound})"
            );
            near += 1;
        }
    }
    // The cut is active in most cases; rounding-edge cases are rare.
    assert!(inner > n / 4, "{inner} of {n} cut");
    assert!(near <= n / 100, "{near} of {n} off by one");
}

pub(super) fn check_hermite<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let mut x = Vec::new();
    for i in 0..n {
        for _ in 0..28 {
            x.push(rng.gen_range(-5.0..5.0));
        }
        // Ends included: s = 0 and s = 1 give [1, 0, 0, 0] and [0, 0, 1, 0].
        let s = match i % 10 {
            0 => 0.0,
            1 => 1.0,
            _ => rng.gen_range(0.0..1.0),
        };
        x.extend(hermite_weights(s, rng.gen_range(0.01..3.0)));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_hermite", &[], &xr, n, 7 * n);
    let mut w = Worst::new::<R>("wave_cache_hermite");
    for i in 0..n {
        let b = &x[32 * i..32 * i + 32];
        let wt = [b[28], b[29], b[30], b[31]];
        let mut o = [0.0; 7];
        wave_cache_hermite(&b[0..7], &b[7..14], &b[14..21], &b[21..28], wt, &mut o);
        for d in 0..7 {
            let scale: f64 = (0..4).map(|q| (wt[q] * b[7 * q + d]).abs()).sum();
            w.check("value", i, out[7 * i + d].f64(), o[d], scale);
        }
        if i % 10 < 2 {
            // Exactly the values at an end.
            for d in 0..7 {
                assert_eq!(out[7 * i + d].f64(), b[14 * (i % 10) + d], "case {i}");
            }
        }
    }
    w.report(p);
}

/// The element cache (`wave_cache_midpoint`, `wave_mid_hermite`) against
/// `sea::cache::wave_cache_midpoint` and `wave_cache_hermite` over its eight scalars:
/// the surfaces are copied exactly, the means and the interpolation within the
/// rounding of their terms.
pub(super) fn check_midpoint<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let mut x = Vec::new();
    for i in 0..n {
        for _ in 0..56 {
            x.push(rng.gen_range(-5.0..5.0));
        }
        let s = match i % 10 {
            0 => 0.0,
            1 => 1.0,
            _ => rng.gen_range(0.0..1.0),
        };
        x.extend(hermite_weights(s, rng.gen_range(0.01..3.0)));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_midpoint", &[], &xr, n, 40 * n);
    let mut w = Worst::new::<R>("wave_cache_midpoint, wave_mid_hermite");
    for i in 0..n {
        let b = &x[60 * i..60 * i + 60];
        let o = &out[40 * i..40 * i + 40];
        let mids: Vec<[f64; 8]> = (0..4)
            .map(|q| wave_cache_midpoint(&b[14 * q..14 * q + 7], &b[14 * q + 7..14 * q + 14]))
            .collect();
        for (q, m) in mids.iter().enumerate() {
            let (na, nb) = (&b[14 * q..14 * q + 7], &b[14 * q + 7..14 * q + 14]);
            assert_eq!(o[8 * q].f64(), na[0], "{p:?} case {i}: eta_a");
            assert_eq!(o[8 * q + 1].f64(), nb[0], "{p:?} case {i}: eta_b");
            for d in 2..8 {
                let scale = 0.5 * (na[d - 1].abs() + nb[d - 1].abs());
                w.check("mean", i, o[8 * q + d].f64(), m[d], scale);
            }
        }
        let wt = [b[56], b[57], b[58], b[59]];
        let mut h = [0.0; 8];
        wave_cache_hermite(&mids[0], &mids[1], &mids[2], &mids[3], wt, &mut h);
        for d in 0..8 {
            // The means' own rounding, carried by each weight, plus the sum's.
            let scale: f64 = (0..4)
                .map(|q| 2.0 * (wt[q] * mids[q][d]).abs())
                .sum::<f64>()
                + (0..4)
                    .map(|q| (wt[q] * 0.5 * (b[14 * q + d].abs() + b[14 * q + 7 + d].abs())).abs())
                    .sum::<f64>();
            w.check("interpolated", i, o[32 + d].f64(), h[d], scale);
        }
        if i % 10 < 2 {
            // Exactly the side at an end (the values at t0 or at t1).
            let q = 2 * (i % 10);
            for d in 0..8 {
                assert_eq!(o[32 + d].f64(), o[8 * q + d].f64(), "{p:?} case {i}");
            }
        }
    }
    w.report(p);
}

/// The band decision (`sea::bands::wave_band`): random nodes against random
/// decreasing tops for one to `MAX_BANDS` (7) bands decided among, each band's bound
/// over its own interval (band 0's, random, doubled per band), and nodes at rest whose
/// bound lands exactly on a top (all terms whole numbers: exact in f32 too), where
/// the node stays in the deeper band. The bands must be equal, except where a band's
/// bound is within the precision's rounding of its top (the f64 twin then may round
/// the other way).
pub(super) fn check_band<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 2000;
    let mut x = Vec::new();
    for i in 0..n {
        let n_bands = 1 + i % MAX_BANDS;
        // The shader's six tops (bands 1 to 6), those past the node's bands unused.
        let mut tops = [f64::NEG_INFINITY; 6];
        let mut top = 0.0;
        for t in tops.iter_mut().take(n_bands - 1) {
            top -= rng.gen_range(5.0..80.0_f64).round();
            *t = top;
        }
        let (z, vz, az, h) = if i % 4 == 0 {
            // On a top: bound = z + 2 exactly.
            let m = rng.gen_range(0..n_bands.max(2) - 1);
            (tops[m].max(-400.0) - 2.0, 0.0, 0.0, 4.0)
        } else {
            (
                rng.gen_range(-400.0..5.0),
                rng.gen_range(-3.0..3.0),
                rng.gen_range(-2.0..2.0),
                rng.gen_range(0.1..2.0),
            )
        };
        x.extend([z, vz, az, h, 2.0]);
        x.extend(tops.map(|t| if t.is_finite() { t } else { -1e30 }));
        x.push(n_bands as f64);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(ctx, p, "t_band", &[], &xr, n, n);
    let (mut ties, mut deep) = (0, 0);
    for i in 0..n {
        let b = &x[12 * i..12 * i + 12];
        let nb = b[11] as usize;
        let mut tops = vec![f64::INFINITY];
        tops.extend(&b[5..5 + nb - 1]);
        let want = wave_band(b[0], b[1], b[2], b[3], b[4], &tops);
        let (mut near, mut tie) = (false, false);
        for (m, &top) in tops.iter().enumerate().skip(1) {
            let h = b[3] * (1u64 << m) as f64;
            let bound = b[0] + b[1].abs() * h + 0.5 * b[2].abs() * h * h + b[4];
            let scale = b[0].abs() + (b[1] * h).abs() + (b[2] * h * h).abs() + b[4];
            near |= (bound - top).abs() <= 16.0 * R::epsilon().f64() * scale && bound != top;
            tie |= bound == top;
        }
        ties += tie as usize;
        deep += (want > 0) as usize;
        if !near {
            assert_eq!(out[i].f64() as usize, want, "{p:?} case {i}: {b:?}");
        }
    }
    println!("wave_band {p:?}: {n} cases, {ties} on a top, {deep} in a deeper band");
    assert!(ties > n / 8 && deep > n / 4, "{ties} ties, {deep} deeper");
}
