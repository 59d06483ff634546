//! Refresh per depth band: the kinematics cache refreshes a node at an interval set by
//! how high that node can be, not by the highest node of its sea.
//!
//! Why: a mooring chain's fairlead may come near the surface, where the short waves
//! set a short refresh interval ([`super::schedule::refresh_plan`]), while most of the
//! chain lies tens to hundreds of metres down, where only the long swell reaches
//! (decay `e^{k z}`) and the rule's interval is many times longer. With one interval
//! for all the nodes of a sea, every node pays the surface's.
//!
//! The bands ([`band_plan`]): band 0 is the sea's plan for its nodes' reach, as
//! before (`steps_0` steps per refresh on the common grid). Band `m` refreshes every
//! `steps_0 2^m` steps (nested rungs of the grid: a band's refresh times are refresh
//! times of every shallower band, and all bands refresh together at the coarsest
//! band's times); its top `tops[m]` is the highest node height at which the band
//! interval ([`band_interval`]: the rule on the sea's scale, below, at that height's
//! evaluation depth, times the factor of
//! [`super::schedule`]: 0.3 near the surface, 0.8 five metres under the lowest
//! trough) is still at least `steps_0 2^m dt`. At most [`MAX_BANDS`] bands; a band
//! exists only if its interval is reached above the seabed.
//!
//! The deeper bands' interval is the rule held on the sea's scale
//! ([`super::schedule::sea_scale_rule_interval`]): the node's interpolation error,
//! `sqrt(m12(zs)) dt^4 / 384` with the amplitudes decayed to its evaluation depth `zs`,
//! within the tolerance of the root-mean-square acceleration at the mean level,
//! `sqrt(m4(0))`, not of its own decayed one. Why: the cache's error matters through
//! the loads, and a deep node's wave loads are themselves decayed, a thousandth of a
//! surface node's 300 m down; held to 1e-3 of its own (the relative rule,
//! [`super::schedule::decayed_rule_interval`], which is scale-free in the decay), its
//! error is a millionth of the loads at the line's top, far below what any other node
//! may err. Held on the sea's scale, every node errs by at most what a node at the
//! mean level may (one absolute bound on the error of the loads for the whole line),
//! the measure the decay cut ([`super::cut`]) already uses (the sea's `sigma`). At the
//! mean level the two rules agree, and the sea-scale one is never the shorter (its
//! `m4` is not decayed). Band 0 keeps the relative rule at the nodes' reach
//! ([`refresh_plan`]), as before.
//!
//! Which band a node is in ([`wave_band`]): decided at each refresh of its band,
//! among the bands that refresh then. At a time `t` where bands `0..=M` refresh (`M`
//! the coarsest band refreshing at `t`, `M > 0`; the rungs are nested, so every band
//! up to `M` refreshes at `t` and no deeper one does), each node of a band `j <= M` is
//! decided anew among bands `0..=M`; a node of a deeper band is left alone (its
//! band's interval runs on). Why a node can change band there: `t` is a refresh time
//! of both its old band `j` and its new band `m`, so its `t0` values and rates become
//! its values at `t` (the old band's `t1` ones, as at any refresh of `j`) and its new
//! `t1` is band `m`'s next rung, `t + I_m` (`I_m = steps_0 2^m dt`, band `m`'s own
//! interval): the interpolant and its derivative stay continuous, no jump in the
//! loads, as at a refresh that keeps the band; and the node's acceleration estimate at
//! `m`'s next refresh is its velocity change since `t`, `m`'s previous rung. The node
//! goes to the deepest band `m <= M` whose top is not under `z + |v_z| L_m + |a_z|
//! L_m^2 / 2 + BAND_MARGIN`, from its height `z`, vertical velocity `v_z` and
//! acceleration estimate `a_z` (its velocity change since its previous refresh) at
//! `t`, with the look-ahead `L_m` [`BAND_LOOK_AHEAD`] (2) of band `m`'s own intervals
//! `I_m`: the node stays in `m` until `t + I_m`, where `m` refreshes and the node is
//! decided again, so one interval is as far as its height must be bounded; the second
//! is an empirical margin for what the rule at a fixed point does not see (a moving
//! node's path prediction over a long interval; the constant says how it was found).
//! The bound grows with `m` and the tops fall, so the bands that pass are `0..=m`.
//! Why not decide
//! only when every band refreshes, looking one coarsest interval `H` ahead (as
//! before): the bound over `H` (5.12 s on the design check) of a heaving fairlead
//! reaches far above it, so every moving node near the top stayed in band 0; looking
//! only as far as the band it is tried for, a node is kept out of a band only by its
//! motion over that band's look-ahead, and after a restart it leaves band 0 at band 1's
//! first refresh, not the coarsest band's. `|v_z|`, not `max(v_z, 0)`: a node moving
//! down in an oscillation comes back up within the interval (for `z = A sin(w t)` the
//! bound's rise over `I` is at least `A min(w I, w^2 I^2 / 2)`, over `2 A` once
//! `w I >= 2`, i.e. every period under `pi I`), which `max(v_z, 0)` missed by up to
//! 3.2 m on the design check (deciding every 5.12 s). Why this and not a per-node
//! bound over the run: a node's motion is known only as the run goes (a chain's
//! fairlead region follows its vessel, its bottom lies still), and the decision is
//! cheap (a few comparisons per node and refresh). After a restart (the first
//! refresh, a remesh) the acceleration is not known: every node starts in band 0
//! until band 1's first refresh.
//!
//! A node that rises above its band's top anyway (a motion the bound did not foresee)
//! is noticed at every refresh of band 0: the cache counts it (and, apart, one more
//! than [`BAND_MARGIN`] above its band's top, of which it warns once per process:
//! [`warn_beyond_margin`]), and its band's next refresh puts the node in the band its
//! height then allows.
//!
//! The plan option ([`super::SeaSet::banded`]): banding is on unless the scenario
//! sets `environment.waves.depth_bands = false`, on both paths: the GPU path
//! (`gpu::wave_schedule`, `shaders/shared/waves.wgsl`) keeps the same clocks per band,
//! one `WaveStep` row per band and step, each node's band in its cache, decided by the
//! WGSL twin of [`wave_band`] at the same steps, and counts breaches per node (those
//! beyond the margin apart, with the first one's height and step, from which the host
//! gives the same warning: [`BandCensus`]).
//!
//! How the CPU path reads a banded cache: the general path interpolates each node
//! with its band's Hermite weights (`WaveCache::interpolate`, runs of nodes of one
//! band); the chain kernel reads each node's interpolant as a cubic in the power
//! basis of `t - t_ref`, `t_ref` the coarsest band's `t0`
//! (`WaveCache::power_node`), so that a stage interpolates every node, whatever its
//! band, with the one set of weights `1, tau, tau^2, tau^3`.

use super::schedule::{
    eval_depth_of_reach, lowest_trough, refresh_plan, sea_scale_rule_interval, surface_factor,
    RefreshPlan, SUBMERGED_FACTOR,
};
use super::SeaState;

/// The most bands of a sea (the coarsest refreshes `2^(MAX_BANDS - 1)` times less
/// often than band 0). Why a cap: a deep band's decision looks one of its intervals
/// ahead, and the bound on how far a node may rise grows with it. The GPU's step rows carry
/// the tops of bands 1 to 6 (`gpu::layout::WaveStep`): at most 7.
pub const MAX_BANDS: usize = 7;

/// Added to a node's bound on how high it may rise before the next decision, m.
pub const BAND_MARGIN: f64 = 2.0;

/// How many of band `m`'s own intervals a decision into band `m` looks ahead
/// ([`wave_band`]): a power of two, so that the look-ahead doubles exactly from band
/// to band in any precision. Why 2 and not 1 (the node is decided again after one):
/// empirical. With 1, moving nodes near a line's top went into deep bands whose long
/// intervals the path prediction (constant acceleration) follows less well, an error
/// the rule at a fixed point does not see: the deep line of
/// `tests/cpu/waves_steppers.rs` (fairlead on a 2 m circle, 6 to 10 m down) erred by
/// 1.6e-3 of its largest fairlead force against 1e-3 allowed (1.3e-4 when every node
/// looked one coarsest interval ahead); with 2, 4.0e-4 (4: 8.7e-4, 8: 3.8e-4; the
/// error is not monotone in it). BENCHMARKS.md, "A node's band decided at its own
/// band's refreshes".
pub const BAND_LOOK_AHEAD: f64 = 2.0;

/// Where the waves' caches of a run stand (`CpuSolver::wave_band_census`, and
/// `GpuSolver`'s from the device): per band how many nodes refresh in it now, how
/// many times a node was found above its band's top at a refresh of band 0, and how
/// many of those were more than [`BAND_MARGIN`] above it (the ones warned of).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BandCensus {
    /// Per band, its nodes now (empty in still water).
    pub nodes: Vec<usize>,
    /// Nodes found above their band's top, counted at each refresh of band 0.
    pub breaches: u64,
    /// Of [`Self::breaches`], those more than [`BAND_MARGIN`] above the top.
    pub beyond_margin: u64,
    /// The first of those, `[t, z, top]` (s, m, m): what [`warn_beyond_margin`] warns
    /// of (the lowest node at the earliest time).
    pub first_beyond_margin: Option<[f64; 3]>,
}

/// Whether [`warn_beyond_margin`] has warned in this process.
static BEYOND_MARGIN_WARNED: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// Warns, once per process (a study's members share one log; the CPU and the GPU
/// path the same warning), that a node was at height `z` (m) at time `t` (s), more
/// than [`BAND_MARGIN`] above the top `top` (m) of the band it refreshes in. Returns
/// whether it warned (false: warned before). Why only beyond the margin: a node a
/// little above its band's top refreshes at an interval a little longer than the rule
/// allows at its height; the rule's interval changes with height through the decay of
/// the components that set it, which over a metre or two is a few percent at the
/// depths of the deeper bands (the error grows as the fourth power of the interval).
/// The full study of the design check (30 members of 3 hours) saw breaches of 0.02 to
/// 0.4 m, at 100 and 250 m down.
pub fn warn_beyond_margin(t: f64, z: f64, top: f64) -> bool {
    if BEYOND_MARGIN_WARNED.swap(true, std::sync::atomic::Ordering::Relaxed) {
        return false;
    }
    log::warn!(
        "waves: a node is at z = {z:.2} m at t = {t:.2} s, {:.2} m above the \
         top {top:.2} m of the depth band it refreshes in (decided from its \
         height, velocity and acceleration plus {BAND_MARGIN} m): its wave \
         loads may be less accurate than the cache tolerance until the next \
         band decision (docs/src/sea_states.md, \"Refresh per depth band\"); \
         warned once",
        z - top
    );
    true
}

/// A sea's bands: band 0 its [`RefreshPlan`], band `m` every `steps_0 2^m` steps for
/// nodes that stay under `tops[m]`.
#[derive(Clone, Debug, PartialEq)]
pub struct BandPlan {
    /// Band 0: the sea's plan for its nodes' reach.
    pub base: RefreshPlan,
    /// Per band: the highest height, m, a node of it may reach (`tops[0]` infinite);
    /// decreasing.
    pub tops: Vec<f64>,
    /// Per band: steps per refresh, `steps_0 2^m`.
    pub steps: Vec<u64>,
}

impl BandPlan {
    /// One band: the sea's plan alone.
    pub fn single(base: RefreshPlan) -> Self {
        Self {
            base,
            tops: vec![f64::INFINITY],
            steps: vec![base.steps],
        }
    }

    /// The number of bands.
    pub fn len(&self) -> usize {
        self.tops.len()
    }

    /// Whether there are no bands (never: band 0 always is).
    pub fn is_empty(&self) -> bool {
        self.tops.is_empty()
    }

    /// The plan of band `m`: the base plan with `steps_0 2^m` steps per refresh.
    pub fn band(&self, m: usize) -> RefreshPlan {
        let steps = self.steps[m];
        RefreshPlan {
            steps,
            interval: if steps == u64::MAX {
                f64::INFINITY
            } else {
                steps as f64 * self.base.dt
            },
            ..self.base
        }
    }

    /// The coarsest band's interval, s: the longest a node stays in one band between
    /// two decisions (a node of the coarsest band).
    pub fn horizon(&self) -> f64 {
        self.band(self.len() - 1).interval
    }
}

/// The unrounded interval of a deeper band at node height `z` (m): the factor of
/// [`super::schedule`] (0.3, or 0.8 when `z` is five metres under the lowest trough)
/// times the rule on the sea's scale at `z`'s evaluation depth (see the module doc).
/// Not increasing in `z`; not shorter than [`refresh_plan`]'s `unrounded` at `z`.
pub fn band_interval(sea: &SeaState, z: f64) -> f64 {
    let trough = lowest_trough(&sea.components);
    let (zs, submerged) = eval_depth_of_reach(sea, z, trough);
    let factor = if submerged {
        SUBMERGED_FACTOR
    } else {
        surface_factor()
    };
    factor * sea_scale_rule_interval(&sea.components, sea.cache_tolerance, zs, sea.depth)
}

/// The bands of `sea` for nodes reaching no higher than `reach` (m; infinite when
/// unknown), stepping by `dt` (see the module doc); one band in still water.
pub fn band_plan(sea: &SeaState, reach: f64, dt: f64) -> BandPlan {
    let base = refresh_plan(sea, reach, dt);
    let mut plan = BandPlan::single(base);
    if base.steps == u64::MAX {
        return plan;
    }
    // A band's unrounded interval for nodes reaching no higher than `z`: not
    // increasing in `z`.
    let interval_at = |z: f64| band_interval(sea, z);
    let floor = if sea.depth.is_finite() {
        -sea.depth
    } else {
        -2000.0
    };
    let ceiling = if reach.is_finite() {
        reach.min(0.0)
    } else {
        0.0
    };
    for m in 1..MAX_BANDS {
        let steps = base.steps << m;
        let need = steps as f64 * dt;
        let (mut lo, mut hi) = (floor, *plan.tops.last().unwrap());
        hi = hi.min(ceiling);
        if lo >= hi || interval_at(lo) < need {
            break;
        }
        // Bisection for the highest height at which the interval reaches `need`:
        // `lo` always does, `hi` (a shallower band's top or the reach) does not.
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if interval_at(mid) >= need {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        plan.tops.push(lo);
        plan.steps.push(steps);
    }
    plan
}

/// The band of a node at height `z` (m) with vertical velocity `vz` (m/s) and
/// acceleration estimate `az` (m/s^2), among the bands of `tops` (decreasing,
/// `tops[0]` infinite: the bands `0..=M` that refresh at the decision, see the module
/// doc): the deepest band `m` whose top is not under `z + |vz| L_m + |az| L_m^2 / 2 +
/// margin`, with `L_m = look0 2^m` (s) the look-ahead of band `m`, `look0` band 0's:
/// [`BAND_LOOK_AHEAD`] times band `m`'s own interval (the node stays in `m` until `m`'s
/// next refresh, where it is decided again). The
/// bound grows with `m` and the tops fall, so the bands that pass are `0..=m`: the
/// search stops at the first that does not. WGSL twin: `wave_band` in
/// `shaders/shared/waves.wgsl`.
pub fn wave_band(z: f64, vz: f64, az: f64, look0: f64, margin: f64, tops: &[f64]) -> usize {
    let mut b = 0;
    let mut h = look0;
    while b + 1 < tops.len() {
        // Band b + 1's look-ahead: a doubling, exact in any precision.
        h += h;
        let bound = z + vz.abs() * h + 0.5 * az.abs() * h * h + margin;
        if !(bound <= tops[b + 1]) {
            break;
        }
        b += 1;
    }
    b
}
