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
//! common grid of refresh times). The rule does not see the nodes' motion: the error
//! of the predicted path adds to it (third order in the interval with the
//! acceleration estimate; the tests below measure both).
//!
//! Layout: four arrays of [`CACHE_STRIDE`] values per node, `eta, u_x, u_y, u_z, a_x,
//! a_y, a_z` (m, m/s, m/s^2) at `t0`, their rates at `t0` (m/s, m/s^2, m/s^3), values
//! at `t1`, rates at `t1`; nodes one after another; positions and velocities three per
//! node.

use super::kinematics::{Kinematics, KinematicsScratch, WaveField};
use super::schedule::RefreshClock;
use super::{SeaState, WaveComponent};
use rayon::prelude::*;

/// Values per node in the cache: `eta, u (3), a (3)`.
pub const CACHE_STRIDE: usize = 7;

/// The fraction of the interval of the interpolation rule that the cache uses (see
/// [`refresh_interval`]). Empirical: at the rule's own interval the fairlead force of
/// the moored rope in `tests/cpu/waves_steppers.rs` (200-component JONSWAP, nodes up
/// to 1 m under the mean level) was out by 1e-2 of its largest value at tolerance
/// 1e-3, ten times the kinematics' tolerance, and by 1e-3 at 0.32 of it; the error
/// falls as the interval squared, not to the fourth power, and its cause is not found
/// (not the path prediction: predicting with or without the nodes' velocity gave the
/// same force). Until it is, the cache refreshes at this fraction of the rule when its
/// nodes may come near the surface (`super::schedule::SUBMERGED_FACTOR` otherwise).
pub const HERMITE_INTERVAL_FACTOR: f64 = 0.3;

/// The refresh interval, s: [`HERMITE_INTERVAL_FACTOR`] times the interval that keeps
/// the root-mean-square cubic Hermite interpolation error of the water acceleration
/// within `tolerance` of its root-mean-square value at a fixed point (see the module
/// doc), `(384^2 eps^2 m4 / m12)^(1/8)` with `m_n = sum A^2 w^n / 2`; for one
/// component the rule's `w dt_r = (384 eps)^(1/4)`. Infinite for still water.
pub fn refresh_interval(components: &[WaveComponent], tolerance: f64) -> f64 {
    HERMITE_INTERVAL_FACTOR * hermite_rule_interval(components, tolerance)
}

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
/// `t1`, rates at `t1`), so that interpolation reads four aligned streams. Its two
/// times and when it refreshes are its [`RefreshClock`] (`sea::schedule`), which the
/// GPU path's schedules share.
#[derive(Clone, Debug)]
pub struct WaveCache {
    /// The sea, packed for evaluation.
    pub field: WaveField,
    /// The cache's times `t0, t1` and refresh interval.
    pub clock: RefreshClock,
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
    /// The nodes' velocities at the previous refresh: the acceleration of the path
    /// prediction is the velocity change since then.
    last_vel: Vec<f64>,
}

impl WaveCache {
    /// A cache for `n_nodes` nodes in `sea`, refreshed at the interval of
    /// [`refresh_interval`] for the sea's `cache_tolerance`, from wherever it starts
    /// (the solvers use [`Self::with_clock`] and a [`crate::sea::schedule::refresh_plan`]).
    pub fn new(sea: &SeaState, n_nodes: usize) -> Self {
        let interval = refresh_interval(&sea.components, sea.cache_tolerance);
        Self::with_interval(sea, n_nodes, interval)
    }

    /// A cache with a given refresh interval, s, from wherever it starts.
    pub fn with_interval(sea: &SeaState, n_nodes: usize, interval: f64) -> Self {
        Self::with_clock(sea, n_nodes, RefreshClock::free(interval))
    }

    /// A cache refreshed as `clock` says.
    pub fn with_clock(sea: &SeaState, n_nodes: usize, clock: RefreshClock) -> Self {
        let zeros = || vec![0.0; n_nodes * CACHE_STRIDE];
        Self {
            field: WaveField::new(sea),
            clock,
            v0: zeros(),
            d0: zeros(),
            v1: zeros(),
            d1: zeros(),
            predicted: vec![0.0; n_nodes * 3],
            predicted_vel: vec![0.0; n_nodes * 3],
            last_vel: vec![0.0; n_nodes * 3],
        }
    }

    /// Time of the older values, s.
    pub fn t0(&self) -> f64 {
        self.clock.t0
    }

    /// Time of the newer values, s.
    pub fn t1(&self) -> f64 {
        self.clock.t1
    }

    /// Makes the cache cover time `t`, given the nodes' positions and velocities at
    /// `t` (three per node). Returns whether it refreshed. The first call (or a `t`
    /// before `t0`, or more than one interval past `t1`) evaluates values and rates at
    /// `t` and at `t1` ([`RefreshClock::tick`]); otherwise, once `t` passes `t1`, the
    /// `t1` values and rates become the `t0` ones (the interpolant stays continuous
    /// with a continuous derivative: no jump in the loads at a refresh) and new `t1`
    /// ones are evaluated at the predicted positions `x + v (t1 - t) + a (t1 - t)^2 /
    /// 2`, with velocity `v + a (t1 - t)`.
    pub fn refresh_if_due(&mut self, t: f64, positions: &[f64], velocities: &[f64]) -> bool {
        let Some(tick) = self.clock.tick(t) else {
            return false;
        };
        if tick.restart {
            evaluate_nodes_rates(
                &self.field,
                positions,
                velocities,
                t,
                &mut self.v0,
                &mut self.d0,
            );
        } else {
            std::mem::swap(&mut self.v0, &mut self.v1);
            std::mem::swap(&mut self.d0, &mut self.d1);
        }
        let ahead = tick.ahead;
        // The acceleration since the previous refresh (none on a restart).
        let rate = tick.acc_rate;
        for i in 0..positions.len() {
            let (x, v) = (positions[i], velocities[i]);
            let acc = (v - self.last_vel[i]) * rate;
            self.predicted[i] = x + v * ahead + 0.5 * acc * ahead * ahead;
            self.predicted_vel[i] = v + acc * ahead;
        }
        self.last_vel.copy_from_slice(velocities);
        evaluate_nodes_rates(
            &self.field,
            &self.predicted,
            &self.predicted_vel,
            self.clock.t1,
            &mut self.v1,
            &mut self.d1,
        );
        true
    }

    /// The Hermite weights of time `t` ([`hermite_weights`]; `t` clamped to
    /// `[t0, t1]`).
    pub fn weights(&self, t: f64) -> [f64; 4] {
        let (t0, t1) = (self.clock.t0, self.clock.t1);
        let delta = t1 - t0;
        hermite_weights(((t - t0) / delta).clamp(0.0, 1.0), delta)
    }

    /// Every node's values at `t` (within `[t0, t1]`) into `out`.
    pub fn interpolate(&self, t: f64, out: &mut [f64]) {
        wave_cache_hermite(&self.v0, &self.d0, &self.v1, &self.d1, self.weights(t), out);
    }

    /// One node's values at `t` (within `[t0, t1]`).
    pub fn node(&self, i: usize, t: f64) -> Kinematics {
        let r = i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE;
        let mut o = [0.0; CACHE_STRIDE];
        wave_cache_hermite(
            &self.v0[r.clone()],
            &self.d0[r.clone()],
            &self.v1[r.clone()],
            &self.d1[r],
            self.weights(t),
            &mut o,
        );
        read_node(&o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sea::dispersion::wave_number;
    use crate::sea::Stretching;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::TAU;

    /// A broad sea: 60 components from 3 s to 20 s, Pierson-Moskowitz-like amplitudes
    /// for Hs ~ 4 m, random directions and phases, in 80 m of water.
    fn broad_sea() -> SeaState {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let h = 80.0;
        let wp: f64 = TAU / 10.0;
        let mut comps = Vec::new();
        for j in 0..60 {
            let w = 0.3 + (2.1 - 0.3) * (j as f64 + rng.gen::<f64>()) / 60.0;
            let s = 5.0 / 16.0 * 16.0 * wp.powi(4) * w.powi(-5) * (-1.25 * (wp / w).powi(4)).exp();
            comps.push(WaveComponent {
                amplitude: (2.0 * s * 0.03).sqrt(),
                omega: w,
                k: wave_number(w, h, 9.81),
                direction: rng.gen_range(-0.5..0.5),
                phase: rng.gen_range(0.0..TAU),
            });
        }
        SeaState {
            components: comps,
            ..SeaState::still(h)
        }
    }

    /// Nodes on a line from the seabed to just under the troughs, moving on circles
    /// of 2 m radius with a 7 s period (a line heaving and surging with the waves).
    fn node_path(i: usize, t: f64, radius: f64) -> ([f64; 3], [f64; 3]) {
        let n = i as f64;
        let om = TAU / 7.0;
        let (s, c) = (om * t + 0.3 * n).sin_cos();
        (
            [
                -30.0 + 4.0 * n + radius * c,
                1.5 * n,
                -75.0 + 3.5 * n + radius * s,
            ],
            [-radius * om * s, 0.0, radius * om * c],
        )
    }

    /// Root-mean-square interpolation error of `u` and `a` over nodes and steps,
    /// relative to the root-mean-square of the exact values.
    fn cache_error(sea: &SeaState, interval: f64, duration: f64, radius: f64) -> (f64, f64) {
        let n = 20;
        let mut cache = WaveCache::with_interval(sea, n, interval);
        let exact = WaveField::new(sea);
        let dt = 0.002;
        let (mut eu, mut nu, mut ea, mut na) = (0.0, 0.0, 0.0, 0.0);
        let mut pos = vec![0.0; 3 * n];
        let mut vel = vec![0.0; 3 * n];
        let steps = (duration / dt) as usize;
        for step in 0..steps {
            let t = 10.0 + step as f64 * dt;
            for i in 0..n {
                let (p, v) = node_path(i, t, radius);
                pos[3 * i..3 * i + 3].copy_from_slice(&p);
                vel[3 * i..3 * i + 3].copy_from_slice(&v);
            }
            cache.refresh_if_due(t, &pos, &vel);
            for i in 0..n {
                let c = cache.node(i, t);
                let e = exact.kinematics([pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]], t);
                for d in 0..3 {
                    eu += (c.u[d] - e.u[d]).powi(2);
                    nu += e.u[d].powi(2);
                    ea += (c.a[d] - e.a[d]).powi(2);
                    na += e.a[d].powi(2);
                }
            }
        }
        ((eu / nu).sqrt(), (ea / na).sqrt())
    }

    /// Nodes at rest: the rule's interval keeps the acceleration's interpolation error
    /// within the tolerance, and not far inside it (the rule is not vacuous); halving
    /// the interval divides the error by about sixteen (fourth order).
    #[test]
    fn interpolation_error_is_within_the_tolerance() {
        let sea = broad_sea();
        for &tol in &[1e-3, 1e-2] {
            let dt_r = hermite_rule_interval(&sea.components, tol);
            let (eu, ea) = cache_error(&sea, dt_r, 40.0, 0.0);
            let (_, ea2) = cache_error(&sea, dt_r / 2.0, 40.0, 0.0);
            let order = (ea / ea2).log2();
            eprintln!(
                "at rest, tolerance {tol:e}: interval {dt_r:.4} s, rms error u {eu:.3e}, \
                 a {ea:.3e}; half the interval: a {ea2:.3e}, order {order:.2}"
            );
            assert!(
                ea <= tol,
                "acceleration error {ea:e} over tolerance {tol:e}"
            );
            assert!(eu <= tol, "velocity error {eu:e} over tolerance {tol:e}");
            assert!(
                ea >= 0.1 * tol,
                "acceleration error {ea:e}: the rule is far too strict"
            );
            assert!((3.5..4.5).contains(&order), "observed order {order}");
        }
    }

    /// Nodes moving on circles: the error of predicting each node's path over the
    /// interval adds to the interpolation's and, at the rule's interval, dominates it
    /// (the rule does not see the nodes' motion; see the module doc). Measured and
    /// held to what it is: with the acceleration estimated from the velocity change
    /// since the previous refresh, the path error is third order in the interval
    /// (halving it divides the error by about seven), on circles of 0.5 m within twice
    /// the tolerance, on circles of 2 m within ten times.
    #[test]
    fn moving_nodes_add_the_path_prediction_error() {
        let sea = broad_sea();
        for (radius, factor) in [(0.5, 2.0), (2.0, 10.0)] {
            for &tol in &[1e-3, 1e-2] {
                let dt_r = hermite_rule_interval(&sea.components, tol);
                let (eu, ea) = cache_error(&sea, dt_r, 40.0, radius);
                let (_, ea2) = cache_error(&sea, dt_r / 2.0, 40.0, radius);
                let order = (ea / ea2).log2();
                eprintln!(
                    "circles of {radius} m, tolerance {tol:e}: interval {dt_r:.4} s, rms error \
                     u {eu:.3e}, a {ea:.3e}; half the interval: a {ea2:.3e}, order {order:.2}"
                );
                assert!(
                    ea <= factor * tol && eu <= factor * tol,
                    "error {ea:e} {eu:e}"
                );
                assert!(
                    ea > 0.5 * tol,
                    "the path error was expected to show: {ea:e}"
                );
                assert!((2.5..3.5).contains(&order), "observed order {order}");
            }
        }
    }

    /// A regular wave: the interval is `(384 eps)^(1/4) / w`, and the cache is exact at the
    /// refresh times themselves.
    #[test]
    fn single_component_interval_and_exact_ends() {
        let w = TAU / 9.0;
        let c = WaveComponent {
            amplitude: 1.0,
            omega: w,
            k: wave_number(w, 50.0, 9.81),
            direction: 0.0,
            phase: 0.0,
        };
        let dt_r = hermite_rule_interval(&[c], 1e-3);
        assert!((w * dt_r - (0.384f64).powf(0.25)).abs() < 1e-14);
        let sea = SeaState {
            components: vec![c],
            stretching: Stretching::Wheeler,
            ..SeaState::still(50.0)
        };
        let mut cache = WaveCache::new(&sea, 1);
        let p = [3.0, 0.0, -10.0];
        cache.refresh_if_due(1.0, &p, &[0.0; 3]);
        cache.refresh_if_due(1.0 + 1.5 * dt_r, &p, &[0.0; 3]);
        let exact = WaveField::new(&sea);
        for &t in &[cache.t0(), cache.t1()] {
            assert_eq!(cache.node(0, t), exact.kinematics(p, t));
        }
        assert!(hermite_rule_interval(&[], 1e-3).is_infinite());
    }

    /// The Hermite weights are exact at both ends, sum to one (a constant is kept) and
    /// reproduce a cubic exactly.
    #[test]
    fn hermite_weights_are_exact_at_the_ends_and_on_cubics() {
        assert_eq!(hermite_weights(0.0, 0.37), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(hermite_weights(1.0, 0.37), [0.0, 0.0, 1.0, 0.0]);
        let f = |t: f64| 0.3 - 1.2 * t + 0.7 * t * t - 2.1 * t * t * t;
        let df = |t: f64| -1.2 + 1.4 * t - 6.3 * t * t;
        let (t0, t1) = (0.4, 0.95);
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            let w = hermite_weights(s, t1 - t0);
            assert!((w[0] + w[2] - 1.0).abs() < 1e-15);
            let mut o = [0.0];
            wave_cache_hermite(&[f(t0)], &[df(t0)], &[f(t1)], &[df(t1)], w, &mut o);
            let t = t0 + s * (t1 - t0);
            assert!((o[0] - f(t)).abs() < 1e-14, "s = {s}: {} {}", o[0], f(t));
        }
    }

    /// A single cosine interpolated over the interval of the rule: within the bound
    /// `(w dt_r)^4 / 384` of its amplitude, and the bound is nearly reached (it is the
    /// error, not a loose bound); the rule's single-component interval is
    /// `(384 eps)^(1/4) / w`.
    #[test]
    fn hermite_interpolation_of_a_cosine_is_within_the_bound() {
        let w = TAU / 6.0;
        let c = WaveComponent {
            amplitude: 1.0,
            omega: w,
            k: wave_number(w, 50.0, 9.81),
            direction: 0.0,
            phase: 0.0,
        };
        let dt_r = hermite_rule_interval(&[c], 1e-3);
        assert!((w * dt_r - (0.384f64).powf(0.25)).abs() < 1e-14);
        let bound = (w * dt_r).powi(4) / 384.0;
        let mut worst = 0.0f64;
        for start in 0..20 {
            let t0 = 0.173 * start as f64;
            let t1 = t0 + dt_r;
            let (f0, f1) = ((w * t0).cos(), (w * t1).cos());
            let (d0, d1) = (-w * (w * t0).sin(), -w * (w * t1).sin());
            for i in 0..=100 {
                let s = i as f64 / 100.0;
                let mut o = [0.0];
                wave_cache_hermite(&[f0], &[d0], &[f1], &[d1], hermite_weights(s, dt_r), &mut o);
                worst = worst.max((o[0] - (w * (t0 + s * dt_r)).cos()).abs());
            }
        }
        eprintln!("worst {worst:.3e}, bound {bound:.3e}");
        assert!(worst <= bound, "error {worst:e} over the bound {bound:e}");
        assert!(
            worst >= 0.5 * bound,
            "error {worst:e} far under the bound {bound:e}"
        );
        assert!(hermite_rule_interval(&[], 1e-3).is_infinite());
        assert_eq!(refresh_interval(&[c], 1e-3), HERMITE_INTERVAL_FACTOR * dt_r);
    }
}
