//! The cut of a refresh's decay pass: at a node whose evaluation depth is `zs`, a
//! component of wave number `k` reaches it decayed by `e^{k zs}` (its `ch, sh` are at
//! most `2 e^{k zs}`), so a deep node needs only the longest waves. The packed
//! components are sorted by `k`, ascending ([`super::kinematics::WaveField`], so
//! that the CPU and the GPU sum in the same order), and each carries bounds on
//! everything from it to the end ([`decay_cut_bounds`]); the decay pass then sums a
//! prefix, whose length [`wave_decay_prefix`] finds by bisection (WGSL twin of the
//! same name in `shaders/shared/waves.wgsl`). The elevation pass stays whole: an
//! error in `eta` would move `zs`, and with it the decay of the waves that are kept.
//!
//! The bound. With `s = |v_h| + |zs'|` (the node's horizontal speed and the rate of
//! its evaluation depth) and `r'` the ramp's rate, the components `i >= j` dropped
//! together change, at most (norms of the vectors; `r <= 1`):
//! - `u` by `2 e^{k_j zs} sum A_u`, `a` by `2 e^{k_j zs} sum A_a`;
//! - the rate of `u` by `2 e^{k_j zs} (s sum A_u k + sum A_u w + |r'| sum A_u)`,
//!   of `a` the same with `A_a` (each term's rate is `k zs' (sh, ch)` and
//!   `theta' (ch, sh)` times its amplitude, `|theta'| <= k |v_h| + w`);
//!
//! since `e^{k_i zs} <= e^{k_j zs}` for `i >= j` and `zs <= 0`. Each is held under
//! [`CUT_FRACTION`] times the cache tolerance times the sea's scale of that quantity
//! (`sigma_u`, `sigma_a`, `sigma_a` for the rate of `u` and `sigma_j` for the rate of
//! `a`, `sigma_x = sqrt(sum x^2 / 2)` over the components with `x = A w, A w^2,
//! A w^3`): the cut's error is a hundredth of what the cache's interpolation may err.

use super::kinematics::PackedComponent;
use super::poly;

/// The cut's share of the cache tolerance.
pub const CUT_FRACTION: f64 = 1e-2;

/// Fills each component's `cut0, cut1, cut2` (the bounds of everything from it to the
/// end, over their limits; see the module) for cache tolerance `tolerance`. `comps`
/// must be sorted by `k`, ascending. With a zero tolerance (or a still sea) the
/// bounds are infinite or NaN, which cut nothing.
pub fn decay_cut_bounds(comps: &mut [PackedComponent], tolerance: f64) {
    let sigma = |p: i32| {
        (comps
            .iter()
            .map(|c| (c.amp * c.omega.powi(p)).powi(2))
            .sum::<f64>()
            / 2.0)
            .sqrt()
    };
    let lim = |p: i32| CUT_FRACTION * tolerance * sigma(p);
    let (l_u, l_a, l_du, l_da) = (lim(1), lim(2), lim(2), lim(3));
    // Suffix sums of A_u, A_u k, A_u w and the same with A_a.
    let mut s = [0.0f64; 6];
    for c in comps.iter_mut().rev() {
        s[0] += c.amp_u;
        s[1] += c.amp_u * c.k;
        s[2] += c.amp_u * c.omega;
        s[3] += c.amp_a;
        s[4] += c.amp_a * c.k;
        s[5] += c.amp_a * c.omega;
        c.cut0 = 2.0
            * (s[0] / l_u)
                .max(s[3] / l_a)
                .max(s[2] / l_du)
                .max(s[5] / l_da);
        c.cut1 = 2.0 * (s[1] / l_du).max(s[4] / l_da);
        c.cut2 = 2.0 * (s[0] / l_du).max(s[3] / l_da);
    }
}

/// The number of leading components (sorted by `k`) that the decay pass needs at
/// evaluation depth `zs` (`<= 0`), for a node of speed `s = |v_h| + |zs'|` (m/s)
/// under a ramp changing at `r_rate` (1/s): the smallest `m` such that the bound of
/// [`decay_cut_bounds`] on the components from `m` on is at most 1 (`n` when none
/// is; a NaN depth keeps all).
pub fn wave_decay_prefix(comps: &[PackedComponent], zs: f64, s: f64, r_rate: f64) -> usize {
    decay_prefix(comps.len(), zs, s, r_rate, |j| {
        let c = &comps[j];
        (c.k, c.cut0, c.cut1, c.cut2)
    })
}

/// [`wave_decay_prefix`] over components read by `comp(j) = (k, cut0, cut1, cut2)`
/// (the CPU's columns read it this way).
#[inline]
pub fn decay_prefix(
    n: usize,
    zs: f64,
    s: f64,
    r_rate: f64,
    comp: impl Fn(usize) -> (f64, f64, f64, f64),
) -> usize {
    let (mut lo, mut hi) = (0usize, n);
    // The bound is non-increasing in j (k ascending, zs <= 0, suffix sums), so the
    // components it allows to drop are a suffix: bisect for its start.
    while lo < hi {
        let mid = (lo + hi) / 2;
        let (k, c0, c1, c2) = comp(mid);
        let bound = poly::exp_neg(k * zs) * (c0 + c1 * s + c2 * r_rate.abs());
        if bound <= 1.0 {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sea::irregular::{discretise, Discretisation};
    use crate::sea::kinematics::{wave_kinematics_rates_tau, wave_ramp_rate, WaveField};
    use crate::sea::spectrum::Spectrum;
    use crate::sea::{SeaState, Stretching};

    /// A 200-component JONSWAP sea (Hs 9 m, Tp 13 s, spread) in 320 m: the design
    /// check's design sea.
    fn field(tolerance: f64) -> WaveField {
        let depth = 320.0;
        let comps = discretise(
            &Spectrum::Jonswap {
                hs: 9.0,
                tp: 13.0,
                gamma: 2.5,
            },
            &Discretisation {
                components: 200,
                direction: 0.5,
                spreading: Some(4.0),
                seed: 3,
                stream: 0,
            },
            depth,
            9.81,
        );
        WaveField::new(&SeaState {
            components: comps,
            cache_tolerance: tolerance,
            ramp_duration: 60.0,
            ..SeaState::still(depth)
        })
    }

    /// The cut's error against the full sum, at nodes from the surface to the seabed,
    /// moving and inside the ramp, is within the stated bound of each quantity; the
    /// cut drops components at the deep nodes (so the test could fail). The tolerance
    /// here is 0.1, a hundred times the default, so that the cut is aggressive and its
    /// errors large enough to see against round-off.
    #[test]
    fn the_cuts_error_is_within_its_bound() {
        let tol = 0.1;
        let f = field(tol);
        assert!(f.comps.windows(2).all(|w| w[0].k <= w[1].k), "sorted by k");
        let whole: Vec<PackedComponent> = f
            .comps
            .iter()
            .map(|c| PackedComponent {
                cut0: f64::INFINITY,
                cut1: f64::INFINITY,
                cut2: f64::INFINITY,
                ..*c
            })
            .collect();
        let sigma = |p: i32| {
            (f.comps
                .iter()
                .map(|c| (c.amp * c.omega.powi(p)).powi(2))
                .sum::<f64>()
                / 2.0)
                .sqrt()
        };
        let lim = |p: i32| CUT_FRACTION * tol * sigma(p);
        let (l_u, l_a, l_du, l_da) = (lim(1), lim(2), lim(2), lim(3));
        let norm = |a: [f64; 3], b: [f64; 3]| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        };
        let (mut cut_somewhere, mut worst) = (0, 0.0f64);
        for (i, z) in [-1.0, -5.0, -18.0, -40.0, -80.0, -150.0, -250.0, -319.0]
            .into_iter()
            .enumerate()
        {
            for (t, v) in [
                (200.0, [0.0, 0.0, 0.0]),
                (30.0, [1.5, -0.7, 0.4]),
                (611.3, [-0.3, 2.0, -1.1]),
            ] {
                let p = [10.0 * i as f64, -4.0, z];
                let r = crate::sea::kinematics::wave_ramp(t, f.ramp_duration);
                let rr = wave_ramp_rate(t, f.ramp_duration);
                let tau = t - f.t_ref;
                let args = (f.depth, Stretching::Wheeler, r, rr, p, v, tau);
                let (kc, dc) = wave_kinematics_rates_tau(
                    &f.comps, args.0, args.1, args.2, args.3, args.4, args.5, args.6,
                );
                let (kw, dw) = wave_kinematics_rates_tau(
                    &whole, args.0, args.1, args.2, args.3, args.4, args.5, args.6,
                );
                assert_eq!(kc.eta, kw.eta, "the elevation pass is whole");
                let errs = [
                    norm(kc.u, kw.u) / l_u,
                    norm(kc.a, kw.a) / l_a,
                    norm(dc.u, dw.u) / l_du,
                    norm(dc.a, dw.a) / l_da,
                ];
                for (q, e) in errs.iter().enumerate() {
                    assert!(*e <= 1.0, "z {z} t {t} quantity {q}: {e} of its bound");
                    worst = worst.max(*e);
                }
                if kc != kw {
                    cut_somewhere += 1;
                }
            }
        }
        // Deep nodes lose components (and errors are seen), the bound is not vacuous.
        assert!(cut_somewhere >= 9, "cut at {cut_somewhere} nodes");
        assert!(worst > 1e-4, "worst error {worst} of the bound");
    }

    /// The prefix: all at the surface (and at a NaN depth), fewer and fewer with
    /// depth, and each the smallest whose bound is at most 1.
    #[test]
    fn the_prefix_shrinks_with_depth() {
        let f = field(1e-3);
        let n = f.comps.len();
        let bound = |m: usize, zs: f64, s: f64| {
            let c = &f.comps[m];
            poly::exp_neg(c.k * zs) * (c.cut0 + c.cut1 * s + c.cut2 * 0.01)
        };
        assert_eq!(wave_decay_prefix(&f.comps, 0.0, 1.0, 0.01), n);
        assert_eq!(wave_decay_prefix(&f.comps, f64::NAN, 1.0, 0.01), n);
        let mut last = n;
        for zs in [-10.0, -30.0, -60.0, -120.0, -200.0, -320.0] {
            let m = wave_decay_prefix(&f.comps, zs, 1.0, 0.01);
            assert!(m <= last, "{zs}: {m} after {last}");
            assert!(m == n || bound(m, zs, 1.0) <= 1.0);
            assert!(m == 0 || bound(m - 1, zs, 1.0) > 1.0);
            last = m;
        }
        assert!(last < n / 3, "{last} of {n} at the seabed");
    }
}
