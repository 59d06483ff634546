//! When the kinematics cache refreshes: the refresh interval of a sea for the nodes
//! it acts on (how deep they stay), and the common grid of refresh times that the CPU
//! path's caches ([`super::cache::WaveCache`]) and the GPU path's schedules
//! (`gpu::wave_schedule::WaveSchedule`) both follow, through one [`RefreshClock`].
//!
//! The interval ([`refresh_plan`]): the interpolation rule
//! ([`hermite_rule_interval`]) is written for a point at the mean level.
//! A node at depth sees component `j` decayed by `cosh(k_j (z + h)) / cosh(k_j h)`
//! (`e^{k_j z}` in deep water), so the short waves that set the rule's `m12` are gone
//! a few metres down. The plan takes the rule with every amplitude times its decay at
//! the highest *evaluation* depth the sea's nodes reach: from the highest height they
//! reach, `reach` (see `sim::reach`: route ends over the run, free nodes' starting
//! heights, plus a margin), stretched under the lowest trough ([`lowest_trough`]: with
//! Wheeler stretching a node under a trough is evaluated nearer the mean level). With
//! `reach` unknown (infinite) that is the rule at the mean level, as before.
//!
//! The factor on the rule: [`HERMITE_INTERVAL_FACTOR`] (0.3) when a node
//! may come near the surface (the path prediction of nodes that move with the short
//! waves there: see that constant); [`SUBMERGED_FACTOR`] when every node stays [`SURFACE_MARGIN`] under the
//! lowest trough (measured: `tests/cpu/waves_steppers.rs`,
//! `submerged_line_keeps_the_end_force_at_the_planned_interval`).
//!
//! The grid ([`grid_steps`]): the interval is rounded down to `p dt` with `p` a power of
//! two or three times one (`1, 2, 3, 4, 6, 8, 12, 16, 24, ...`), and refresh times are
//! the multiples of it from `t = 0` (the run's start), formed as the solver forms its
//! step times (`(steps as f64) * dt`). Two seas whose `p` are both powers of two (or
//! both three times one) refresh at nested steps: every refresh step of the longer is
//! one of the shorter, so the GPU path's fused dispatch of a packed study is cut only at
//! the shortest interval's refreshes (`gpu::wave_schedule::fused_segments`); seas of the two
//! families cut it at both of theirs, all at multiples of the smaller power of two.
//! Why not powers of two alone: rounding down to them loses up to half the interval
//! (a third of it on average), and the refresh is a third of a wave step's cost on
//! the CPU; with the threes the loss is at most a third, about a sixth on average. Why
//! a fixed ladder and not one fitted to what is packed: a member's results must not
//! depend on the other members of its batch.

use super::kinematics::wave_depth_decay;
use super::{SeaState, Stretching, WaveComponent};

/// The fraction of the interval of the interpolation rule that the cache uses (see
/// [`super::cache::refresh_interval`]). Empirical: at the rule's own interval the fairlead force of
/// the moored rope in `tests/cpu/waves_steppers.rs` (200-component JONSWAP, nodes up
/// to 1 m under the mean level) was out by 1e-2 of its largest value at tolerance
/// 1e-3, ten times the kinematics' tolerance, and by 1e-3 at 0.3 of it. The cause
/// (BENCHMARKS.md, "Why the surface needs 0.3 of the rule"; `examples/surface_kink.rs`):
/// the path prediction of nodes that move with the short waves near the surface. The
/// values at `t1` are evaluated where a node is predicted to be; for the rope's top
/// nodes that misses by 0.1 to 0.27 m at the rule's interval (third order in it), and
/// their acceleration errs 10-25 times what the rule allows, while a node at rest, or
/// the same nodes interpolated from their actual states, err as the rule says. Not the
/// kink of Wheeler stretching's clamp where the surface crosses a node: that is there,
/// but the force errs as much with the profile held at `z = 0`. Until the prediction
/// is better, the cache refreshes at this fraction of the rule when its nodes may come
/// near the surface ([`SUBMERGED_FACTOR`] otherwise;
/// [`surface_factor`] reads it, with an experiment knob).
pub const HERMITE_INTERVAL_FACTOR: f64 = 0.3;

/// The interval of the interpolation rule alone, `(384^2 eps^2 m4 / m12)^(1/8)`.
pub fn hermite_rule_interval(components: &[WaveComponent], tolerance: f64) -> f64 {
    let (m4, m12) = components.iter().fold((0.0, 0.0), |(m4, m12), c| {
        let a2w4 = 0.5 * c.amplitude * c.amplitude * c.omega.powi(4);
        (m4 + a2w4, m12 + a2w4 * c.omega.powi(8))
    });
    if m12 <= 0.0 {
        return f64::INFINITY;
    }
    (384.0 * 384.0 * tolerance * tolerance * m4 / m12).powf(0.125)
}

/// The factor on the rule's interval when no node comes within [`SURFACE_MARGIN`] of
/// the lowest trough. Measured on a rope whose highest node stays 5 m or more under the
/// surface (`tests/cpu/waves_steppers.rs`): its fairlead force within 1e-3 of exact
/// evaluation at this factor with the decayed rule, rounded down to the grid.
pub const SUBMERGED_FACTOR: f64 = 0.8;

/// The environment variable of the experiment knob of [`surface_factor`].
pub const SURFACE_FACTOR_VAR: &str = "CABLESIM_EXPERIMENT_SURFACE_FACTOR";

/// The factor on the rule for nodes that may come near the surface:
/// [`HERMITE_INTERVAL_FACTOR`], unless the environment variable [`SURFACE_FACTOR_VAR`]
/// gives another (read once per process). An experiment knob, not a setting: it
/// exists so that the measurements of BENCHMARKS.md, "Why the surface needs 0.3 of
/// the rule", can run the solvers and the command line at other factors (0.8, 1.0)
/// against exact evaluation; results at any factor but 0.3 are not what the tests
/// hold. Panics on a value that is not a number in `(0, 2]`.
pub fn surface_factor() -> f64 {
    static FACTOR: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
    *FACTOR.get_or_init(|| match std::env::var(SURFACE_FACTOR_VAR) {
        Err(_) => HERMITE_INTERVAL_FACTOR,
        Ok(v) => match v.trim().parse::<f64>() {
            Ok(f) if f > 0.0 && f <= 2.0 => {
                log::warn!("waves: the surface factor is {f} ({SURFACE_FACTOR_VAR}), not {HERMITE_INTERVAL_FACTOR}: an experiment");
                f
            }
            _ => panic!("{SURFACE_FACTOR_VAR} = {v:?}: not a factor in (0, 2]"),
        },
    })
}

/// How far under the lowest trough, m, a sea's nodes must stay for
/// [`SUBMERGED_FACTOR`] (the submerged rope of the test stays 4.9 m or more under the
/// surface).
pub const SURFACE_MARGIN: f64 = 5.0;

/// The lowest trough the plan assumes, in standard deviations of the elevation:
/// `4.8 sqrt(m0) = 1.2 Hs`. Over a three-hour sea of about a thousand waves the
/// deepest trough of a Gaussian sea is about `3.7 sqrt(m0)` (`sqrt(2 ln 1000)`), and
/// one deeper than 4.8 comes in about one sea in a hundred; the run warns when a node
/// rises above its sea's `reach` (the plan's other assumption).
pub const TROUGH_SIGMAS: f64 = 4.8;

/// The lowest trough the plan assumes, m (negative): [`TROUGH_SIGMAS`] standard
/// deviations of the elevation, `m0 = sum A^2 / 2`.
pub fn lowest_trough(components: &[WaveComponent]) -> f64 {
    let m0: f64 = components
        .iter()
        .map(|c| 0.5 * c.amplitude * c.amplitude)
        .sum();
    -TROUGH_SIGMAS * m0.sqrt()
}

/// A component's amplitude factor at evaluation depth `zs` (`<= 0`) relative to the
/// mean level: the horizontal (the larger) profile `cosh(k (zs + h)) / cosh(k h)`.
pub fn depth_decay(k: f64, zs: f64, depth: f64) -> f64 {
    let zs = zs.min(0.0).max(-depth);
    wave_depth_decay(k, zs, depth).0 / wave_depth_decay(k, 0.0, depth).0
}

/// The interpolation rule ([`hermite_rule_interval`]) with every component's amplitude
/// times its decay at evaluation depth `zs`.
pub fn decayed_rule_interval(
    components: &[WaveComponent],
    tolerance: f64,
    zs: f64,
    depth: f64,
) -> f64 {
    let decayed: Vec<WaveComponent> = components
        .iter()
        .map(|c| WaveComponent {
            amplitude: c.amplitude * depth_decay(c.k, zs, depth),
            ..*c
        })
        .collect();
    hermite_rule_interval(&decayed, tolerance)
}

/// The interpolation rule held on the sea's scale: the interval that keeps the
/// root-mean-square Hermite error of the water acceleration at evaluation depth `zs`,
/// `sqrt(m12(zs)) dt^4 / 384` with `m12(zs)` of the decayed amplitudes, within
/// `tolerance` of the root-mean-square acceleration at the mean level, `sqrt(m4)` of
/// the undecayed ones: `(384^2 eps^2 m4(0) / m12(zs))^(1/8)`. Never shorter than the
/// relative rule ([`decayed_rule_interval`], whose `m4` is decayed too) and the same
/// at the mean level. Why the sea's scale: see [`super::bands`].
pub fn sea_scale_rule_interval(
    components: &[WaveComponent],
    tolerance: f64,
    zs: f64,
    depth: f64,
) -> f64 {
    let (m4, m12) = components.iter().fold((0.0, 0.0), |(m4, m12), c| {
        let w4 = c.omega.powi(4);
        let ad = c.amplitude * depth_decay(c.k, zs, depth);
        (
            m4 + 0.5 * c.amplitude * c.amplitude * w4,
            m12 + 0.5 * ad * ad * w4 * c.omega.powi(8),
        )
    });
    if m12 <= 0.0 {
        return f64::INFINITY;
    }
    (384.0 * 384.0 * tolerance * tolerance * m4 / m12).powf(0.125)
}

/// The highest evaluation depth of nodes reaching no higher than `reach` (m; infinite
/// when unknown: the mean level) under the lowest trough `trough`, and whether they
/// all stay [`SURFACE_MARGIN`] under it (see [`refresh_plan`]).
pub fn eval_depth_of_reach(sea: &SeaState, reach: f64, trough: f64) -> (f64, bool) {
    let eval_depth = if reach.is_finite() {
        match sea.stretching {
            Stretching::Wheeler => (reach - trough) / (1.0 + trough / sea.depth),
            Stretching::Constant => reach,
        }
        .min(0.0)
    } else {
        0.0
    };
    (eval_depth, reach <= trough - SURFACE_MARGIN)
}

/// A sea's refresh interval for nodes that reach no higher than `reach`, and how it was
/// found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefreshPlan {
    /// The highest height the nodes reach, m (infinite: unknown, taken at the surface).
    pub reach: f64,
    /// The lowest trough assumed, m ([`lowest_trough`]).
    pub trough: f64,
    /// The highest evaluation depth, m (`reach` stretched under the trough, `<= 0`).
    pub eval_depth: f64,
    /// Whether every node stays [`SURFACE_MARGIN`] under the trough.
    pub submerged: bool,
    /// The factor on the rule.
    pub factor: f64,
    /// The factor times the decayed rule, s, before rounding to the grid.
    pub unrounded: f64,
    /// Steps per refresh ([`grid_steps`]: the largest power of two, or three times
    /// one, with `steps dt <= unrounded`; at least 1; `u64::MAX` in still water).
    pub steps: u64,
    /// The refresh interval, `steps dt`, s (infinite in still water).
    pub interval: f64,
    /// The step, s.
    pub dt: f64,
}

/// The refresh plan of `sea` for nodes reaching no higher than `reach` (m; infinite
/// when unknown), stepping by `dt` (see the module doc).
pub fn refresh_plan(sea: &SeaState, reach: f64, dt: f64) -> RefreshPlan {
    assert!(dt > 0.0, "the step must be positive");
    let trough = lowest_trough(&sea.components);
    let (eval_depth, submerged) = eval_depth_of_reach(sea, reach, trough);
    let factor = if submerged {
        SUBMERGED_FACTOR
    } else {
        surface_factor()
    };
    let unrounded =
        factor * decayed_rule_interval(&sea.components, sea.cache_tolerance, eval_depth, sea.depth);
    let steps = grid_steps(unrounded, dt);
    RefreshPlan {
        reach,
        trough,
        eval_depth,
        submerged,
        factor,
        unrounded,
        steps,
        interval: if steps == u64::MAX {
            f64::INFINITY
        } else {
            steps as f64 * dt
        },
        dt,
    }
}

/// The largest `p` of the ladder `2^m, 3 2^m` (`1, 2, 3, 4, 6, 8, ...`) with `p dt <=
/// interval` (at least 1, at most `2^40`; `u64::MAX` for an infinite interval).
pub fn grid_steps(interval: f64, dt: f64) -> u64 {
    if !interval.is_finite() {
        return u64::MAX;
    }
    let mut p = 1u64;
    while p < (1 << 40) && (2 * p) as f64 * dt <= interval {
        p *= 2;
    }
    // Between p and 2p: 3p / 2 when it fits.
    if p >= 2 && (3 * p / 2) as f64 * dt <= interval {
        3 * p / 2
    } else {
        p
    }
}

/// What a refresh does ([`RefreshClock::tick`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tick {
    /// A fresh start: values at `t0 = t` too, and no acceleration estimate.
    pub restart: bool,
    /// `t1 - t`, s: how far ahead the nodes' paths are predicted.
    pub ahead: f64,
    /// `1 / (t - t_last)` for the nodes' acceleration estimate from their velocity
    /// change since the previous refresh (0 on a restart).
    pub acc_rate: f64,
}

/// The cache's two times and when it refreshes, the same on both paths.
///
/// With a grid (`steps dt`, [`RefreshClock::on_grid`]) `t1` is always a multiple of
/// the interval, `(j steps) as f64 * dt` for an integer `j`; a restart at `t` sets
/// `t0 = t` and `t1` to the first grid time after it. Without one
/// ([`RefreshClock::free`]) `t1 = t0 + interval` (tests of the cache at arbitrary
/// times).
#[derive(Clone, Debug, PartialEq)]
pub struct RefreshClock {
    /// Refresh interval, s.
    pub interval: f64,
    /// `(dt, steps)` of the grid.
    grid: Option<(f64, u64)>,
    started: bool,
    /// Time of the older values, s.
    pub t0: f64,
    /// Time of the newer values, s.
    pub t1: f64,
    /// The grid index of `t1`.
    j1: u64,
    /// Time of the last refresh, s (NaN before the first).
    last_t: f64,
}

impl RefreshClock {
    /// A clock refreshing every `interval` s from wherever it starts.
    pub fn free(interval: f64) -> Self {
        assert!(interval > 0.0);
        Self {
            interval,
            grid: None,
            started: false,
            t0: 0.0,
            t1: 0.0,
            j1: 0,
            last_t: f64::NAN,
        }
    }

    /// A clock on the grid of `plan` (refresh times `j plan.steps dt`).
    pub fn on_grid(plan: &RefreshPlan) -> Self {
        let mut c = Self::free(plan.interval);
        if plan.steps != u64::MAX {
            c.grid = Some((plan.dt, plan.steps));
        }
        c
    }

    /// Whether `t` is within `[t0, t1]` (no refresh due).
    #[inline]
    pub fn covers(&self, t: f64) -> bool {
        self.started && self.t1 > self.t0 && t >= self.t0 && t <= self.t1
    }

    /// Forgets the cache's times: the next [`Self::tick`] restarts.
    pub fn reset(&mut self) {
        self.started = false;
        self.t0 = 0.0;
        self.t1 = 0.0;
    }

    fn grid_time(&self, j: u64) -> f64 {
        let (dt, p) = self.grid.expect("grid");
        (j * p) as f64 * dt
    }

    /// Whether [`Self::tick`] at `t` would restart: not started, `t` before `t0`, or
    /// more than an interval past `t1`.
    pub fn would_restart(&self, t: f64) -> bool {
        !self.started || t < self.t0 || t > self.t1 + self.interval
    }

    /// Makes the clock cover `t`: `None` when it does; otherwise moves `t0, t1` on
    /// (the old `t1` becomes `t0`; a restart when not started, when `t` is before `t0`
    /// or more than an interval past `t1`) and says what the refresh does.
    pub fn tick(&mut self, t: f64) -> Option<Tick> {
        if self.covers(t) {
            return None;
        }
        let restart = self.would_restart(t);
        let span = t - self.last_t;
        let acc_rate = if !restart && span > 0.0 {
            1.0 / span
        } else {
            0.0
        };
        self.last_t = t;
        if restart {
            self.t0 = t;
            self.started = true;
            if let Some((dt, p)) = self.grid {
                let mut j = (t / (p as f64 * dt)).floor().max(0.0) as u64 + 1;
                while self.grid_time(j) <= t {
                    j += 1;
                }
                self.j1 = j;
            }
        } else {
            self.t0 = self.t1;
            self.j1 += 1;
        }
        self.t1 = match self.grid {
            Some(_) => self.grid_time(self.j1),
            None => self.t0 + self.interval,
        };
        Some(Tick {
            restart,
            ahead: self.t1 - t,
            acc_rate,
        })
    }
}
