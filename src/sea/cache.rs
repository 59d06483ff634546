//! The per-node wave kinematics cache: the sum over every component evaluated at each
//! node only at refresh times `t0, t1 = t0 + dt_r, ...`, values and their rates along
//! the node's path, and cubic Hermite interpolation in time between them at every step.
//!
//! Why: a 200-component sea summed at every node at every step costs some 200 sines,
//! cosines and pairs of exponentials per node-step, about twenty times a still-water
//! step. The cache spends that once per refresh interval `dt_r` (tens to hundreds of
//! steps) and four multiply-adds per value per step. The rates come from the same
//! sines, cosines and exponentials as the values (`wave_kinematics_rates_tau`).
//!
//! Where: the values and rates at `t1` are evaluated at each node's predicted position
//! `x + v (t1 - t) + a (t1 - t)^2 / 2` with velocity `v + a (t1 - t)`, where `a` is the
//! node's velocity change since the previous refresh over the time since then (0 on a
//! restart); the values and rates at `t0` are those computed at the previous refresh
//! (so the interpolant and its derivative are continuous in time: no jump at a
//! refresh).
//!
//! How often ([`refresh_interval`]): cubic Hermite interpolation of `cos(w t + c)` over
//! an interval `dt_r` is out by at most `(w dt_r)^4 / 384` of its amplitude. Weighting
//! each component by its share of the water acceleration (the most demanding value,
//! `A w^2`) in the root-mean-square sense, the interval for a relative tolerance `eps`
//! at a fixed point is `(384^2 eps^2 m4 / m12)^(1/8)` with the discrete moments
//! `m_n = sum A^2 w^n / 2` ([`hermite_rule_interval`]). At the mean level the cache
//! uses [`HERMITE_INTERVAL_FACTOR`] of it (see there why); the solvers refresh by the
//! plan of [`super::schedule`] (the rule with the amplitudes decayed to the depth the
//! nodes stay at, a larger factor for lines well under the troughs, rounded down to a
//! common grid of refresh times), per depth band of nodes on the CPU path
//! ([`super::bands`]: each node refreshes at the interval of the band its height
//! allows). The rule does not see the nodes' motion: the error
//! of the predicted path adds to it (third order in the interval with the
//! acceleration estimate; the tests below measure both).
//!
//! Layout: four arrays of [`CACHE_STRIDE`] values per node, `eta, u_x, u_y, u_z, a_x,
//! a_y, a_z` (m, m/s, m/s^2) at `t0`, their rates at `t0` (m/s, m/s^2, m/s^3), values
//! at `t1`, rates at `t1`; nodes one after another; positions and velocities three per
//! node.

use super::bands::{warn_beyond_margin, wave_band, BandPlan, BAND_LOOK_AHEAD, BAND_MARGIN};
use super::kinematics::{Kinematics, KinematicsScratch, WaveField};
// The rule's interval and its factor live with the refresh plan (`schedule.rs`, which
// this file uses): re-exported here, where they were.
pub use super::schedule::{hermite_rule_interval, HERMITE_INTERVAL_FACTOR};
use super::schedule::{RefreshClock, Tick};
use super::{SeaState, WaveComponent};
use rayon::prelude::*;
use std::sync::Arc;

/// Values per node in the cache: `eta, u (3), a (3)`.
pub const CACHE_STRIDE: usize = 7;

/// The refresh interval, s: [`HERMITE_INTERVAL_FACTOR`] times the interval that keeps
/// the root-mean-square cubic Hermite interpolation error of the water acceleration
/// within `tolerance` of its root-mean-square value at a fixed point (see the module
/// doc), `(384^2 eps^2 m4 / m12)^(1/8)` with `m_n = sum A^2 w^n / 2`; for one
/// component the rule's `w dt_r = (384 eps)^(1/4)`. Infinite for still water.
pub fn refresh_interval(components: &[WaveComponent], tolerance: f64) -> f64 {
    HERMITE_INTERVAL_FACTOR * hermite_rule_interval(components, tolerance)
}

/// The cubic Hermite weights at `s = (t - t0) / delta` in `[0, 1]`, `delta = t1 - t0`:
/// `[h00, delta h10, h01, delta h11]`, so that `f(t) = w0 f0 + w1 f0' + w2 f1 + w3 f1'`.
/// Factored so that they are exactly `[1, 0, 0, 0]` at `s = 0` and `[0, 0, 1, 0]` at
/// `s = 1`. Formed once per step on the host (f64) for every node.
pub fn hermite_weights(s: f64, delta: f64) -> [f64; 4] {
    let s2 = s * s;
    let m = s - 1.0;
    [
        s2 * (2.0 * s - 3.0) + 1.0,
        delta * (s * m * m),
        s2 * (3.0 - 2.0 * s),
        delta * (s2 * m),
    ]
}

/// An element's share of its nodes' cache entries `a` and `b` (each `eta, u, a`:
/// [`CACHE_STRIDE`] values, or their rates): the surface over each node and the mean
/// of the two nodes' wave velocity and acceleration, `[eta_a, eta_b, u (3), a (3)]`.
/// The CPU's chain columns and the GPU's element cache hold these per element and
/// refresh, so that a step interpolates them instead of both nodes' entries
/// (interpolation is linear: the same up to round-off). WGSL twin:
/// `wave_cache_midpoint` in `shaders/shared/waves.wgsl`.
#[inline(always)]
pub fn wave_cache_midpoint(a: &[f64], b: &[f64]) -> [f64; 8] {
    let mut m = [a[0], b[0], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for q in 0..6 {
        m[2 + q] = 0.5 * (a[1 + q] + b[1 + q]);
    }
    m
}

/// Cubic Hermite interpolation of cached values `v0, v1` with rates `d0, d1`,
/// elementwise, with the weights `w` of [`hermite_weights`]: four multiply-adds a value.
pub fn wave_cache_hermite(
    v0: &[f64],
    d0: &[f64],
    v1: &[f64],
    d1: &[f64],
    w: [f64; 4],
    out: &mut [f64],
) {
    let n = out.len();
    let (v0, d0, v1, d1) = (&v0[..n], &d0[..n], &v1[..n], &d1[..n]);
    for i in 0..n {
        out[i] = w[0] * v0[i] + w[1] * d0[i] + w[2] * v1[i] + w[3] * d1[i];
    }
}

/// The exact kinematics at every node (positions `x, y, z` per node) at time `t`,
/// written to `out` ([`CACHE_STRIDE`] per node). Nodes in parallel.
pub fn evaluate_nodes(field: &WaveField, positions: &[f64], t: f64, out: &mut [f64]) {
    assert_eq!(positions.len() % 3, 0);
    assert_eq!(out.len(), positions.len() / 3 * CACHE_STRIDE);
    out.par_chunks_mut(CACHE_STRIDE)
        .zip(positions.par_chunks(3))
        .with_min_len(16)
        .for_each_init(KinematicsScratch::default, |scratch, (o, p)| {
            write_node(o, &field.kinematics_with([p[0], p[1], p[2]], t, scratch))
        });
}

fn write_node(o: &mut [f64], k: &Kinematics) {
    o[0] = k.eta;
    o[1..4].copy_from_slice(&k.u);
    o[4..7].copy_from_slice(&k.a);
}

/// Reads one node's values back as [`Kinematics`].
pub fn read_node(v: &[f64]) -> Kinematics {
    Kinematics {
        eta: v[0],
        u: [v[1], v[2], v[3]],
        a: [v[4], v[5], v[6]],
    }
}

/// The values and their rates along each node's path at every node (positions and
/// velocities `x, y, z` per node) at time `t`, written to `values` and `rates`
/// ([`CACHE_STRIDE`] per node each). Nodes in parallel.
pub fn evaluate_nodes_rates(
    field: &WaveField,
    positions: &[f64],
    velocities: &[f64],
    t: f64,
    values: &mut [f64],
    rates: &mut [f64],
) {
    assert_eq!(positions.len() % 3, 0);
    assert_eq!(velocities.len(), positions.len());
    assert_eq!(values.len(), positions.len() / 3 * CACHE_STRIDE);
    assert_eq!(rates.len(), values.len());
    values
        .par_chunks_mut(CACHE_STRIDE)
        .zip(rates.par_chunks_mut(CACHE_STRIDE))
        .zip(positions.par_chunks(3).zip(velocities.par_chunks(3)))
        .with_min_len(16)
        .for_each_init(KinematicsScratch::default, |scratch, ((o, d), (p, v))| {
            let (k, dk) =
                field.kinematics_rates_with([p[0], p[1], p[2]], [v[0], v[1], v[2]], t, scratch);
            write_node(o, &k);
            write_node(d, &dk);
        });
}

/// The rolling cache of one run: values and rates at `t0` and `t1` for every node.
///
/// Four arrays of [`CACHE_STRIDE`] per node (values at `t0`, rates at `t0`, values at
/// `t1`, rates at `t1`), so that interpolation reads four aligned streams. Each node
/// is in a depth band (`super::bands`; one band unless built with
/// [`Self::with_bands`]) whose two times and refresh steps are its band's
/// [`RefreshClock`] (`sea::schedule`), which the GPU path's schedules share.
#[derive(Clone, Debug)]
pub struct WaveCache {
    /// The sea, packed for evaluation; shared, not copied, by a clone of the cache
    /// (it does not change during a run, and the CPU solver is copied whole for a
    /// checkpoint at each output time).
    pub field: Arc<WaveField>,
    /// Per band: the band's times `t0, t1` and refresh interval (nested rungs of one
    /// grid: band `m` every `2^m` refreshes of band 0).
    pub clocks: Vec<RefreshClock>,
    /// Per band: the highest height, m, its nodes may reach (`tops[0]` infinite).
    tops: Vec<f64>,
    /// How far ahead a decision into band 0 looks, s ([`BAND_LOOK_AHEAD`] band 0
    /// intervals): into band `m`, `2^m` times it (`super::bands::wave_band`).
    look0: f64,
    /// Per node: its band.
    band: Vec<u8>,
    /// Runs of consecutive nodes of one band: `(first, end, band)`.
    runs: Vec<(usize, usize, usize)>,
    /// Counts the refreshes (any band): what the values were formed by.
    pub generation: u64,
    /// How many times a node was found above its band's top at a refresh of band 0.
    pub breaches: u64,
    /// Of those, how many were more than [`BAND_MARGIN`] above it.
    pub beyond_margin: u64,
    /// The first of those, `[t, z, top]` (s, m, m).
    pub first_beyond_margin: Option<[f64; 3]>,
    /// Values at `t0`, [`CACHE_STRIDE`] per node.
    pub v0: Vec<f64>,
    /// Rates at `t0` along the node's path, [`CACHE_STRIDE`] per node.
    pub d0: Vec<f64>,
    /// Values at `t1`, [`CACHE_STRIDE`] per node.
    pub v1: Vec<f64>,
    /// Rates at `t1` along the node's predicted path, [`CACHE_STRIDE`] per node.
    pub d1: Vec<f64>,
    predicted: Vec<f64>,
    predicted_vel: Vec<f64>,
    /// Per node: the time its new values are for at this refresh (NaN: not due).
    due: Vec<f64>,
    /// The nodes' velocities at their previous refresh: the acceleration of the path
    /// prediction is the velocity change since then.
    last_vel: Vec<f64>,
    /// For the refresh of a few nodes, one after another.
    scratch: KinematicsScratch,
}

impl WaveCache {
    /// A cache for `n_nodes` nodes in `sea`, refreshed at the interval of
    /// [`refresh_interval`] for the sea's `cache_tolerance`, from wherever it starts
    /// (the solvers use [`Self::with_bands`] and a [`crate::sea::bands::band_plan`]).
    pub fn new(sea: &SeaState, n_nodes: usize) -> Self {
        let interval = refresh_interval(&sea.components, sea.cache_tolerance);
        Self::with_interval(sea, n_nodes, interval)
    }

    /// A cache with a given refresh interval, s, from wherever it starts.
    pub fn with_interval(sea: &SeaState, n_nodes: usize, interval: f64) -> Self {
        Self::with_clock(sea, n_nodes, RefreshClock::free(interval))
    }

    /// A cache of one band refreshed as `clock` says.
    pub fn with_clock(sea: &SeaState, n_nodes: usize, clock: RefreshClock) -> Self {
        let zeros = || vec![0.0; n_nodes * CACHE_STRIDE];
        Self {
            field: Arc::new(WaveField::new(sea)),
            look0: BAND_LOOK_AHEAD * clock.interval,
            clocks: vec![clock],
            tops: vec![f64::INFINITY],
            band: vec![0; n_nodes],
            runs: vec![(0, n_nodes, 0)],
            generation: 0,
            breaches: 0,
            beyond_margin: 0,
            first_beyond_margin: None,
            v0: zeros(),
            d0: zeros(),
            v1: zeros(),
            d1: zeros(),
            predicted: vec![0.0; n_nodes * 3],
            predicted_vel: vec![0.0; n_nodes * 3],
            due: vec![f64::NAN; n_nodes],
            last_vel: vec![0.0; n_nodes * 3],
            scratch: KinematicsScratch::default(),
        }
    }

    /// A cache refreshed per depth band as `plan` says (`super::bands`), on the
    /// common grid.
    pub fn with_bands(sea: &SeaState, n_nodes: usize, plan: &BandPlan) -> Self {
        let mut c = Self::with_clock(sea, n_nodes, RefreshClock::on_grid(&plan.base));
        c.clocks = (0..plan.len())
            .map(|m| RefreshClock::on_grid(&plan.band(m)))
            .collect();
        c.tops = plan.tops.clone();
        c.look0 = BAND_LOOK_AHEAD * plan.band(0).interval;
        c
    }

    /// Time of the older values of band 0, s.
    pub fn t0(&self) -> f64 {
        self.clocks[0].t0
    }

    /// Time of the newer values of band 0, s.
    pub fn t1(&self) -> f64 {
        self.clocks[0].t1
    }

    /// Whether every band covers `t` (no refresh due): band 0's interval is within
    /// every deeper band's.
    pub fn covers(&self, t: f64) -> bool {
        self.clocks[0].covers(t)
    }

    /// Node `i`'s band.
    pub fn band_of(&self, i: usize) -> usize {
        self.band[i] as usize
    }

    /// Runs of consecutive nodes of one band, `(first, end, band)`, in node order.
    pub fn runs(&self) -> &[(usize, usize, usize)] {
        &self.runs
    }

    /// Makes the cache cover time `t`, given the nodes' positions and velocities at
    /// `t` (three per node). Returns whether it refreshed. The first call (or a `t`
    /// before `t0`, or more than one interval past band 0's `t1`) restarts every band
    /// ([`RefreshClock::tick`]): values and rates at `t`, every node in band 0.
    /// Otherwise each band whose `t1` `t` passed refreshes its nodes: the `t1` values
    /// and rates become the `t0` ones (the interpolant stays continuous with a
    /// continuous derivative: no jump in the loads at a refresh) and new `t1` ones are
    /// evaluated at the predicted positions `x + v (t1 - t) + a (t1 - t)^2 / 2`, with
    /// velocity `v + a (t1 - t)`. When bands `0..=M` refresh (`M > 0` the coarsest
    /// that does; the rungs are nested), each node of those bands is decided anew
    /// among them (`super::bands::wave_band`); the nodes of deeper bands keep theirs.
    pub fn refresh_if_due(&mut self, t: f64, positions: &[f64], velocities: &[f64]) -> bool {
        if self.covers(t) {
            return false;
        }
        if self.clocks[0].would_restart(t) {
            self.clocks.iter_mut().for_each(RefreshClock::reset);
        }
        let ticks: Vec<Option<Tick>> = self.clocks.iter_mut().map(|c| c.tick(t)).collect();
        let restart = ticks[0].is_some_and(|k| k.restart);
        let nb = self.clocks.len();
        // The coarsest band refreshing now, when a decision is due: every band up to
        // it refreshes too (nested rungs), so a node of one of them may move to
        // another with its values at `t` as its new `t0` ones (no jump).
        let decide = ticks
            .iter()
            .rposition(Option::is_some)
            .filter(|&m| m > 0 && !restart);
        if restart {
            evaluate_nodes_rates(
                &self.field,
                positions,
                velocities,
                t,
                &mut self.v0,
                &mut self.d0,
            );
            self.band.iter_mut().for_each(|b| *b = 0);
        } else if nb > 1 {
            // A node above its band's top: noticed here, re-banded at its band's
            // next refresh (now, when its band refreshes now).
            self.watch(t, positions);
        }
        let mut all_due = true;
        for i in 0..self.band.len() {
            let old = self.band[i] as usize;
            let (p, v) = (&positions[3 * i..3 * i + 3], &velocities[3 * i..3 * i + 3]);
            let lv = &self.last_vel[3 * i..3 * i + 3];
            // The acceleration since the node's previous refresh (a band that ticks
            // now: the node's old band ticks whenever its new one does).
            let rate = ticks[old].map_or(0.0, |k| k.acc_rate);
            let acc = [
                (v[0] - lv[0]) * rate,
                (v[1] - lv[1]) * rate,
                (v[2] - lv[2]) * rate,
            ];
            let new = match decide {
                Some(m) if old <= m => {
                    let tops = &self.tops[..=m];
                    wave_band(p[2], v[2], acc[2], self.look0, BAND_MARGIN, tops)
                }
                _ => old,
            };
            self.band[i] = new as u8;
            let Some(tick) = ticks[new] else {
                self.due[i] = f64::NAN;
                all_due = false;
                continue;
            };
            self.due[i] = self.clocks[new].t1;
            if !restart {
                for j in i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE {
                    self.v0[j] = self.v1[j];
                    self.d0[j] = self.d1[j];
                }
            }
            let ahead = tick.ahead;
            for d in 0..3 {
                let k = 3 * i + d;
                self.predicted[k] = p[d] + v[d] * ahead + 0.5 * acc[d] * ahead * ahead;
                self.predicted_vel[k] = v[d] + acc[d] * ahead;
                self.last_vel[k] = v[d];
            }
        }
        if decide.is_some() || restart {
            self.form_runs();
        }
        if all_due && nb == 1 {
            evaluate_nodes_rates(
                &self.field,
                &self.predicted,
                &self.predicted_vel,
                self.clocks[0].t1,
                &mut self.v1,
                &mut self.d1,
            );
        } else if rayon::current_num_threads() == 1
            || self.due.iter().filter(|t| !t.is_nan()).count() < 32
        {
            // Few nodes due (a rung of the shallow bands alone), or one thread: one
            // after another with the cache's own scratch, no parallel split (each
            // split allocates and zeroes a scratch of its own).
            let s = &mut self.scratch;
            for (i, &t1) in self.due.iter().enumerate() {
                if t1.is_nan() {
                    continue;
                }
                let (p, v) = (
                    &self.predicted[3 * i..3 * i + 3],
                    &self.predicted_vel[3 * i..3 * i + 3],
                );
                let (k, dk) =
                    self.field
                        .kinematics_rates_with([p[0], p[1], p[2]], [v[0], v[1], v[2]], t1, s);
                let r = i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE;
                write_node(&mut self.v1[r.clone()], &k);
                write_node(&mut self.d1[r], &dk);
            }
        } else {
            evaluate_due_nodes(
                &self.field,
                &self.predicted,
                &self.predicted_vel,
                &self.due,
                &mut self.v1,
                &mut self.d1,
            );
        }
        self.generation += 1;
        true
    }

    /// Counts nodes above their band's top at `t`, apart those more than
    /// [`BAND_MARGIN`] above it, and warns of the first of these (once per process:
    /// [`warn_beyond_margin`], which says why not of every breach).
    fn watch(&mut self, t: f64, positions: &[f64]) {
        for (i, &b) in self.band.iter().enumerate() {
            let z = positions[3 * i + 2];
            let top = self.tops[b as usize];
            if z > top {
                self.breaches += 1;
                let beyond = z - top > BAND_MARGIN;
                self.beyond_margin += beyond as u64;
                if beyond && self.first_beyond_margin.is_none() {
                    self.first_beyond_margin = Some([t, z, top]);
                }
                if !(beyond && warn_beyond_margin(t, z, top)) {
                    log::debug!(
                        "waves: a node at z = {z:.2} m at t = {t:.2} s is above the top \
                         {top:.2} m of its depth band"
                    );
                }
            }
        }
    }

    /// The runs of consecutive nodes of one band.
    fn form_runs(&mut self) {
        self.runs.clear();
        let mut a = 0;
        for i in 1..=self.band.len() {
            if i == self.band.len() || self.band[i] != self.band[a] {
                self.runs.push((a, i, self.band[a] as usize));
                a = i;
            }
        }
    }

    /// The Hermite weights of time `t` in band `b` ([`hermite_weights`]; `t` clamped
    /// to the band's `[t0, t1]`).
    pub fn band_weights(&self, b: usize, t: f64) -> [f64; 4] {
        let (t0, t1) = (self.clocks[b].t0, self.clocks[b].t1);
        let delta = t1 - t0;
        hermite_weights(((t - t0) / delta).clamp(0.0, 1.0), delta)
    }

    /// The Hermite weights of time `t` in band 0.
    pub fn weights(&self, t: f64) -> [f64; 4] {
        self.band_weights(0, t)
    }

    /// Every node's values at `t` (within its band's `[t0, t1]`) into `out`.
    pub fn interpolate(&self, t: f64, out: &mut [f64]) {
        let n = out.len() / CACHE_STRIDE;
        for &(a, e, b) in &self.runs {
            if a >= n {
                break;
            }
            let r = a * CACHE_STRIDE..e.min(n) * CACHE_STRIDE;
            wave_cache_hermite(
                &self.v0[r.clone()],
                &self.d0[r.clone()],
                &self.v1[r.clone()],
                &self.d1[r.clone()],
                self.band_weights(b, t),
                &mut out[r],
            );
        }
    }

    /// One node's values at `t` (within its band's `[t0, t1]`).
    pub fn node(&self, i: usize, t: f64) -> Kinematics {
        let r = i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE;
        let mut o = [0.0; CACHE_STRIDE];
        wave_cache_hermite(
            &self.v0[r.clone()],
            &self.d0[r.clone()],
            &self.v1[r.clone()],
            &self.d1[r],
            self.band_weights(self.band[i] as usize, t),
            &mut o,
        );
        read_node(&o)
    }
}

impl WaveCache {
    /// The time the power-basis cubics are referred to ([`Self::power_coefficients`]):
    /// the coarsest band's `t0`, which moves only when every band refreshes.
    pub fn power_ref(&self) -> f64 {
        self.clocks[self.clocks.len() - 1].t0
    }

    /// Per node: the time its values were refreshed for at the last refresh (NaN:
    /// not refreshed then).
    pub fn due(&self) -> &[f64] {
        &self.due
    }

    /// Every node's interpolant as a cubic in `tau = t - t_ref` (power basis,
    /// `p[0] + p[1] tau + p[2] tau^2 + p[3] tau^3`, [`CACHE_STRIDE`] per node in each
    /// of `p`; [`Self::power_node`] per node).
    pub fn power_coefficients(&self, t_ref: f64, p: &mut [Vec<f64>; 4]) {
        let len = self.v0.len();
        for q in p.iter_mut() {
            q.resize(len, 0.0);
        }
        for i in 0..self.band.len() {
            self.power_node(i, t_ref, p);
        }
    }

    /// Node `i`'s interpolant as a cubic in `tau = t - t_ref` into `p` (sized), from
    /// its band's Hermite data over `[t0, t1]`: in `sigma = t - t0`, `a0 = v0`, `a1 =
    /// d0`, `a2 = (3 (v1 - v0) / delta - 2 d0 - d1) / delta`, `a3 = (2 (v0 - v1) /
    /// delta + d0 + d1) / delta^2`, then shifted by `e = t_ref - t0`. Why: every node,
    /// whatever its band, then interpolates with the weights `1, tau, tau^2, tau^3`,
    /// and an element's midpoint is the mean of its nodes' cubics: one set of weights
    /// per stage, as with one band. With `t_ref` the coarsest band's `t0` only the
    /// nodes a refresh touched change until every band refreshes (a node changes band
    /// only at a refresh of its old and its new band); `tau` stays within the
    /// coarsest interval (a second or two), and the coefficients are bounded by the
    /// values' time derivatives, so the power basis loses nothing that matters.
    #[inline]
    pub fn power_node(&self, i: usize, t_ref: f64, p: &mut [Vec<f64>; 4]) {
        let clock = &self.clocks[self.band[i] as usize];
        let delta = clock.t1 - clock.t0;
        let (inv, inv2) = (1.0 / delta, 1.0 / (delta * delta));
        let e = t_ref - clock.t0;
        let [p0, p1, p2, p3] = p;
        let r = i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE;
        let (v0, d0, v1, d1) = (
            &self.v0[r.clone()],
            &self.d0[r.clone()],
            &self.v1[r.clone()],
            &self.d1[r.clone()],
        );
        let (p0, p1, p2, p3) = (
            &mut p0[r.clone()],
            &mut p1[r.clone()],
            &mut p2[r.clone()],
            &mut p3[r],
        );
        for j in 0..CACHE_STRIDE {
            let (v0, d0, v1, d1) = (v0[j], d0[j], v1[j], d1[j]);
            let a2 = (3.0 * (v1 - v0) * inv - 2.0 * d0 - d1) * inv;
            let a3 = (2.0 * (v0 - v1) * inv + d0 + d1) * inv2;
            p0[j] = v0 + e * (d0 + e * (a2 + e * a3));
            p1[j] = d0 + e * (2.0 * a2 + 3.0 * a3 * e);
            p2[j] = a2 + 3.0 * a3 * e;
            p3[j] = a3;
        }
    }
}

/// [`evaluate_nodes_rates`] at the nodes that are due (`due[i]`: the time of node
/// `i`'s new values; NaN: leave it), each at its own time. Nodes in parallel.
fn evaluate_due_nodes(
    field: &WaveField,
    positions: &[f64],
    velocities: &[f64],
    due: &[f64],
    values: &mut [f64],
    rates: &mut [f64],
) {
    values
        .par_chunks_mut(CACHE_STRIDE)
        .zip(rates.par_chunks_mut(CACHE_STRIDE))
        .zip(positions.par_chunks(3).zip(velocities.par_chunks(3)))
        .zip(due.par_iter())
        .with_min_len(16)
        .for_each_init(
            KinematicsScratch::default,
            |scratch, (((o, d), (p, v)), &t)| {
                if t.is_nan() {
                    return;
                }
                let (k, dk) =
                    field.kinematics_rates_with([p[0], p[1], p[2]], [v[0], v[1], v[2]], t, scratch);
                write_node(o, &k);
                write_node(d, &dk);
            },
        );
}
