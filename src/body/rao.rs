//! Body motion from response amplitude operators (RAOs), driven by wave components.
//!
//! An RAO table gives, over wave frequency and heading, the amplitude and phase of each
//! degree of freedom per metre of wave amplitude: surge, sway, heave in m/m, roll,
//! pitch, yaw in deg/m (radians per metre inside the library), phases in degrees.
//!
//! Heading: the direction the waves travel towards, relative to the body's x axis,
//! from x towards y (0: waves from astern travelling towards the bow; 180: head seas).
//! A component travelling towards `b` meets a body of mean heading `h` at `b - h`.
//!
//! Phase: a lead, in time, on the wave elevation at the reference point. For a
//! component `eta = A cos(theta)`, `theta = k (x cos b + y sin b) - w t + phi`, taken
//! at the body's mean reference point,
//!
//! ```text
//! xi_i(t) = sum_j A_j |H_i(w_j, b_j - h)| cos(theta_j - arg H_i)
//! ```
//!
//! so a motion of phase `p` reaches its maximum `p / w` seconds before the crest
//! passes the reference point (`theta` decreases with time, hence the minus sign).
//!
//! Interpolation, linear in frequency and in heading: amplitudes linearly, phases
//! linearly along the shorter arc (interpolating the complex value instead would
//! shrink the amplitude between rows whose phases differ). Headings are periodic: a
//! heading between the last row and the first plus 360 degrees interpolates across
//! that gap, so give the whole circle (a half-circle table of a symmetric vessel is
//! not mirrored). Below the lowest and above the highest frequency the nearest
//! frequency's values are held: extend the table to where the response has died out.
//!
//! Evaluation ([`RaoMotion::eval`]): the exact sum over the components (a sine and a
//! cosine each) only at knots `t_k = k dt_b` on a grid fixed from `t = 0`, values and
//! their first three derivatives, and cubic Hermite interpolation in time between two
//! knots: the displacements with the rates as slopes, the rates with the
//! accelerations, the accelerations with the jerks (`w^3`, analytic). So the motion is
//! a function of `t` alone (not of the order in which times are asked for, nor of the
//! thread or shard that asks), the same on the CPU path and in the GPU path's host
//! rows. The knot spacing `dt_b` ([`RaoMotion::knot_interval`]) is the wave cache's
//! interpolation rule (`sea::cache::hermite_rule_interval`) applied to the body's own
//! response spectrum, each degree of freedom's components `A_j |H_i(w_j)|`, at the
//! relative tolerance [`RAO_KNOT_TOLERANCE`], the smallest over the six degrees of
//! freedom. The ramp is applied exactly to the interpolated motion.

use super::kinematics::Dofs;
use crate::sea::cache::{hermite_rule_interval, hermite_weights};
use crate::sea::poly::sin_cos;
use crate::sea::WaveComponent;
use std::f64::consts::{PI, TAU};
use std::sync::Mutex;

/// The relative tolerance of the knot spacing of [`RaoMotion`]: for each degree of
/// freedom, the root-mean-square cubic Hermite error of the acceleration within this
/// fraction of its root-mean-square value (the rule of
/// `sea::cache::hermite_rule_interval`, which weights each component by its largest
/// error). The displacements and rates are closer still: the rule for them weights the
/// spectrum's lower moments (`m8 / m0` and `m10 / m2` instead of `m12 / m4`), and the
/// moments of a spectrum are log-convex, so their intervals are longer.
/// `tests/cpu/bodies.rs` measures the errors on a real RAO table in a JONSWAP sea.
pub const RAO_KNOT_TOLERANCE: f64 = 1e-6;

/// How many knots [`RaoMotion`] keeps: two for the interval in use and a few for
/// threads that ask for times a little apart.
const KNOT_CACHE_LEN: usize = 8;

/// Amplitude (m/m or rad/m) and phase (rad) of one degree of freedom.
pub type Response = (f64, f64);

/// An RAO table on a full grid of frequencies and headings.
#[derive(Clone, Debug, PartialEq)]
pub struct RaoTable {
    /// Angular frequencies, rad/s, strictly increasing.
    omega: Vec<f64>,
    /// Headings, rad, strictly increasing, spanning less than a full turn.
    heading: Vec<f64>,
    /// `values[i * heading.len() + j]`: the six responses at `omega[i]`, `heading[j]`.
    values: Vec<[Response; 6]>,
}

/// Wraps an angle into `(-pi, pi]`.
#[doc(hidden)]
pub fn wrap_pi(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

fn blend(a: &[Response; 6], b: &[Response; 6], s: f64) -> [Response; 6] {
    std::array::from_fn(|k| {
        let (a0, p0) = a[k];
        let (a1, p1) = b[k];
        (a0 + s * (a1 - a0), p0 + s * wrap_pi(p1 - p0))
    })
}

impl RaoTable {
    /// A table from its grid: `omega` (rad/s) and `heading` (rad) strictly increasing,
    /// headings within one turn, and per grid point (frequency-major) the amplitude
    /// (m/m, rad/m) and phase (rad) of each degree of freedom. The scenario reader
    /// checks all of this with messages naming the row; here it is asserted.
    pub fn new(omega: Vec<f64>, heading: Vec<f64>, values: Vec<[Response; 6]>) -> Self {
        assert!(!omega.is_empty() && !heading.is_empty());
        assert_eq!(values.len(), omega.len() * heading.len());
        assert!(omega.windows(2).all(|w| w[0] < w[1]));
        assert!(heading.windows(2).all(|w| w[0] < w[1]));
        assert!(heading[heading.len() - 1] - heading[0] < TAU);
        Self {
            omega,
            heading,
            values,
        }
    }

    /// The six responses at frequency `w` (rad/s) and relative heading `beta` (rad).
    pub fn at(&self, w: f64, beta: f64) -> [Response; 6] {
        let nw = self.omega.len();
        let (i0, i1, s) = if w <= self.omega[0] {
            (0, 0, 0.0)
        } else if w >= self.omega[nw - 1] {
            (nw - 1, nw - 1, 0.0)
        } else {
            let i = self.omega.partition_point(|&x| x <= w) - 1;
            (
                i,
                i + 1,
                (w - self.omega[i]) / (self.omega[i + 1] - self.omega[i]),
            )
        };
        let a = self.at_heading(i0, beta);
        if i1 == i0 {
            return a;
        }
        blend(&a, &self.at_heading(i1, beta), s)
    }

    /// Responses of frequency row `i` at heading `beta`, periodic in heading.
    fn at_heading(&self, i: usize, beta: f64) -> [Response; 6] {
        let nh = self.heading.len();
        let row = &self.values[i * nh..(i + 1) * nh];
        if nh == 1 {
            return row[0];
        }
        let h0 = self.heading[0];
        let b = h0 + (beta - h0).rem_euclid(TAU);
        let j = self.heading.partition_point(|&x| x <= b) - 1;
        let (hj, hn, next) = if j + 1 < nh {
            (self.heading[j], self.heading[j + 1], j + 1)
        } else {
            (self.heading[nh - 1], h0 + TAU, 0)
        };
        blend(&row[j], &row[next], (b - hj) / (hn - hj))
    }
}

/// One wave component's contribution to the six degrees of freedom:
/// `xi = c cos(w t) + s sin(w t)` per degree of freedom.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Term {
    w: f64,
    c: [f64; 6],
    s: [f64; 6],
}

/// The exact motion at a knot: the six degrees of freedom and their first three time
/// derivatives (the jerk is the slope of the acceleration's interpolant).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Knot {
    q: [f64; 6],
    qd: [f64; 6],
    qdd: [f64; 6],
    qddd: [f64; 6],
}

/// The last knots evaluated, by index: every value a pure function of its index, so a
/// hit returns exactly what evaluating again would.
#[derive(Default)]
struct KnotCache {
    slots: Mutex<Vec<(i64, Knot)>>,
}

impl Clone for KnotCache {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for KnotCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("KnotCache")
    }
}

/// The motion of a body in given wave components (see the module doc), with an
/// optional start-up ramp.
#[derive(Clone, Debug)]
pub struct RaoMotion {
    terms: Vec<Term>,
    /// Ramp duration, s (0: none): the motion is multiplied by
    /// `0.5 (1 - cos(pi t / ramp))` for `t < ramp`.
    ramp: f64,
    /// Knot spacing `dt_b`, s (infinite: no motion, evaluated exactly).
    interval: f64,
    knots: KnotCache,
}

impl PartialEq for RaoMotion {
    fn eq(&self, o: &Self) -> bool {
        self.terms == o.terms && self.ramp == o.ramp && self.interval == o.interval
    }
}

impl RaoMotion {
    /// The motion of a body whose mean reference point is at `(x, y)` (m) with mean
    /// heading `heading` (rad), under `waves`, with RAOs `rao`, ramped in over `ramp`
    /// seconds (0: none).
    pub fn new(
        rao: &RaoTable,
        waves: &[WaveComponent],
        x: f64,
        y: f64,
        heading: f64,
        ramp: f64,
    ) -> Self {
        let terms: Vec<Term> = waves
            .iter()
            .map(|wc| {
                let h = rao.at(wc.omega, wc.direction - heading);
                // theta_j - arg H = (theta_j at t = 0 - arg H) - w t.
                let th0 = wc.theta(x, y, 0.0);
                let mut t = Term {
                    w: wc.omega,
                    c: [0.0; 6],
                    s: [0.0; 6],
                };
                for (k, (amp, ph)) in h.iter().enumerate() {
                    let (s, c) = (th0 - ph).sin_cos();
                    t.c[k] = wc.amplitude * amp * c;
                    t.s[k] = wc.amplitude * amp * s;
                }
                t
            })
            .collect();
        let interval = knot_interval(&terms, RAO_KNOT_TOLERANCE);
        Self {
            terms,
            ramp,
            interval,
            knots: KnotCache::default(),
        }
    }

    /// The knot spacing `dt_b`, s (see the module doc; infinite without motion).
    pub fn knot_interval(&self) -> f64 {
        self.interval
    }

    /// The six degrees of freedom and their rates at time `t`, s: interpolated between
    /// knots (see the module doc), the ramp applied exactly.
    pub fn eval(&self, t: f64) -> Dofs {
        let d = if self.interval.is_finite() {
            self.interpolated(t)
        } else {
            let k = self.exact(t);
            Dofs {
                q: k.q,
                qd: k.qd,
                qdd: k.qdd,
            }
        };
        self.ramped(t, d)
    }

    /// The six degrees of freedom and their rates at time `t`, s, from the sum over
    /// every component at `t` itself (what the knots hold), the ramp applied: the
    /// reference that [`RaoMotion::eval`] is tested against.
    pub fn eval_exact(&self, t: f64) -> Dofs {
        let k = self.exact(t);
        self.ramped(
            t,
            Dofs {
                q: k.q,
                qd: k.qd,
                qdd: k.qdd,
            },
        )
    }

    /// The unramped sum over the components at `t` and its first three derivatives.
    /// The sine and cosine of `w t` are the inlined polynomials of `sea::poly` (within
    /// a few units in the last place of the library's, and of `w t`'s own rounding:
    /// the library call was two thirds of a knot's cost).
    fn exact(&self, t: f64) -> Knot {
        let mut d = Knot::default();
        for term in &self.terms {
            let (sn, cs) = sin_cos(term.w * t);
            let w = term.w;
            let w2 = w * w;
            for k in 0..6 {
                // cos(th0 - p - w t) = c cos(w t) + s sin(w t) with (c, s) from th0 - p.
                let x = term.c[k] * cs + term.s[k] * sn;
                let v = w * (term.s[k] * cs - term.c[k] * sn);
                d.q[k] += x;
                d.qd[k] += v;
                d.qdd[k] -= w2 * x;
                d.qddd[k] -= w2 * v;
            }
        }
        d
    }

    /// Knot `k` (at `k dt_b`), from the cache or evaluated.
    fn knot(&self, k: i64) -> Knot {
        let lock = || self.knots.slots.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, v)) = lock().iter().find(|(i, _)| *i == k) {
            return *v;
        }
        // Evaluated outside the lock: other threads go on meanwhile.
        let v = self.exact(k as f64 * self.interval);
        let mut slots = lock();
        if slots.len() >= KNOT_CACHE_LEN {
            // The knot furthest from this one goes.
            let far = (0..slots.len())
                .max_by_key(|&i| (slots[i].0 - k).unsigned_abs())
                .unwrap_or(0);
            slots.swap_remove(far);
        }
        slots.push((k, v));
        v
    }

    /// The unramped motion at `t` by cubic Hermite interpolation between the knots
    /// around it.
    fn interpolated(&self, t: f64) -> Dofs {
        let dt = self.interval;
        let k = (t / dt).floor() as i64;
        let (a, b) = (self.knot(k), self.knot(k + 1));
        let w = hermite_weights(t / dt - k as f64, dt);
        let h = |v0: &[f64; 6], d0: &[f64; 6], v1: &[f64; 6], d1: &[f64; 6]| {
            std::array::from_fn(|i| w[0] * v0[i] + w[1] * d0[i] + w[2] * v1[i] + w[3] * d1[i])
        };
        Dofs {
            q: h(&a.q, &a.qd, &b.q, &b.qd),
            qd: h(&a.qd, &a.qdd, &b.qd, &b.qdd),
            qdd: h(&a.qdd, &a.qddd, &b.qdd, &b.qddd),
        }
    }

    /// `d` with the ramp applied at `t` (unchanged past the ramp).
    fn ramped(&self, t: f64, mut d: Dofs) -> Dofs {
        if self.ramp > 0.0 && t < self.ramp {
            // r = (1 - cos(pi t / T)) / 2 and its derivatives, applied by the product rule.
            let wr = PI / self.ramp;
            let tt = t.max(0.0);
            let (s, c) = (wr * tt).sin_cos();
            let (r, r1, r2) = (0.5 * (1.0 - c), 0.5 * wr * s, 0.5 * wr * wr * c);
            for k in 0..6 {
                let (x, v, a) = (d.q[k], d.qd[k], d.qdd[k]);
                d.q[k] = r * x;
                d.qd[k] = r1 * x + r * v;
                d.qdd[k] = r2 * x + 2.0 * r1 * v + r * a;
            }
        }
        d
    }
}

/// The knot spacing for `tolerance`: the interpolation rule of the wave cache on each
/// degree of freedom's response spectrum (components of amplitude `A_j |H_i(w_j)|`),
/// the smallest over the six; infinite when nothing moves.
fn knot_interval(terms: &[Term], tolerance: f64) -> f64 {
    (0..6)
        .map(|i| {
            let spectrum: Vec<WaveComponent> = terms
                .iter()
                .map(|t| WaveComponent {
                    amplitude: t.c[i].hypot(t.s[i]),
                    omega: t.w,
                    k: 0.0,
                    direction: 0.0,
                    phase: 0.0,
                })
                .collect();
            hermite_rule_interval(&spectrum, tolerance)
        })
        .fold(f64::INFINITY, f64::min)
}
