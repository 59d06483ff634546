//! The cut of a refresh's decay pass: at a node whose evaluation depth is `zs`, a
//! component of wave number `k` reaches it decayed by `e^{k zs}` (its `ch, sh` are at
//! most `2 e^{k zs}`), so a deep node needs only the longest waves. The packed
//! components are sorted by `k`, ascending ([`super::kinematics::WaveField`], so
//! that the CPU and the GPU sum in the same order), and each carries bounds on
//! everything from it to the end ([`decay_cut_bounds`]); the decay pass then sums a
//! prefix, whose length [`wave_decay_prefix`] finds by bisection (WGSL twin of the
//! same name in `shaders/shared/waves.wgsl`). The elevation pass stays whole: an
//! error in `eta` would move `zs`, and with it the decay of the waves that are kept;
//! a bound in this style allows too little of it to pay (on the design member, not
//! one component above 250 m: `scripts/elevation_cut_bound.py`, and
//! docs/src/sea_states.md, "Why the elevation pass is not cut").
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
