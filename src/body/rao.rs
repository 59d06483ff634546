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

use super::kinematics::Dofs;
use crate::sea::WaveComponent;
use std::f64::consts::{PI, TAU};

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
fn wrap_pi(a: f64) -> f64 {
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

/// The motion of a body in given wave components (see the module doc), with an
/// optional start-up ramp.
#[derive(Clone, Debug, PartialEq)]
pub struct RaoMotion {
    terms: Vec<Term>,
    /// Ramp duration, s (0: none): the motion is multiplied by
    /// `0.5 (1 - cos(pi t / ramp))` for `t < ramp`.
    ramp: f64,
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
        let terms = waves
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
        Self { terms, ramp }
    }

    /// The six degrees of freedom and their rates at time `t`, s.
    pub fn eval(&self, t: f64) -> Dofs {
        let mut d = Dofs::default();
        for term in &self.terms {
            let (sn, cs) = (term.w * t).sin_cos();
            let w = term.w;
            for k in 0..6 {
                // cos(th0 - p - w t) = c cos(w t) + s sin(w t) with (c, s) from th0 - p.
                let x = term.c[k] * cs + term.s[k] * sn;
                d.q[k] += x;
                d.qd[k] += w * (term.s[k] * cs - term.c[k] * sn);
                d.qdd[k] -= w * w * x;
            }
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> RaoTable {
        // Two frequencies, four headings; heave amplitude and phase vary with both.
        let omega = vec![0.5, 1.0];
        let heading: Vec<f64> = [0.0f64, 90.0, 180.0, 270.0]
            .iter()
            .map(|d| d.to_radians())
            .collect();
        let mut values = Vec::new();
        for i in 0..2 {
            for j in 0..4 {
                let mut r = [(0.0, 0.0); 6];
                r[2] = (
                    1.0 - 0.4 * i as f64 + 0.1 * j as f64,
                    (10.0 * j as f64 + 170.0 * i as f64).to_radians(),
                );
                values.push(r);
            }
        }
        RaoTable::new(omega, heading, values)
    }

    #[test]
    fn grid_points_are_exact_and_between_them_linear() {
        let t = table();
        let (a, p) = t.at(1.0, 90f64.to_radians())[2];
        assert!((a - 0.7).abs() < 1e-15 && (p - 180f64.to_radians()).abs() < 1e-12);
        // Halfway in frequency at heading 0: amplitude 0.8, phase 85 deg.
        let (a, p) = t.at(0.75, 0.0)[2];
        assert!((a - 0.8).abs() < 1e-15 && (p - 85f64.to_radians()).abs() < 1e-12);
        // Across the wrap: 315 deg is halfway between 270 (0.3 + 1) and 360 (= 0).
        let (a, _) = t.at(0.5, 315f64.to_radians())[2];
        assert!((a - 1.15).abs() < 1e-12);
        // -45 deg is the same heading.
        assert_eq!(
            t.at(0.5, -45f64.to_radians()),
            t.at(0.5, 315f64.to_radians())
        );
        // Held outside the frequency range.
        assert_eq!(t.at(0.1, 0.3), t.at(0.5, 0.3));
        assert_eq!(t.at(9.0, 0.3), t.at(1.0, 0.3));
    }

    #[test]
    fn phases_take_the_shorter_arc() {
        let r = |p: f64| {
            let mut x = [(1.0, 0.0); 6];
            x[0].1 = p.to_radians();
            x
        };
        let t = RaoTable::new(vec![1.0, 2.0], vec![0.0], vec![r(170.0), r(-170.0)]);
        let p = t.at(1.5, 0.0)[0].1;
        assert!((wrap_pi(p) - PI).abs() < 1e-12, "{p}");
    }

    #[test]
    fn motion_leads_the_elevation_by_its_phase() {
        // One component, heave RAO 0.8 m/m with a 30 deg lead: heave peaks 30 deg of
        // the period before the crest passes the reference point.
        let mut v = [(0.0, 0.0); 6];
        v[2] = (0.8, 30f64.to_radians());
        let rao = RaoTable::new(vec![0.6], vec![0.0], vec![v]);
        let wc = WaveComponent {
            amplitude: 1.5,
            omega: 0.6,
            k: 0.6 * 0.6 / 9.81,
            direction: 0.4,
            phase: 1.1,
        };
        let (x, y) = (30.0, -20.0);
        let m = RaoMotion::new(&rao, &[wc], x, y, 0.0, 0.0);
        // The crest passes (x, y) when theta = 0 (mod 2 pi).
        let t_crest = wc.theta(x, y, 0.0) / wc.omega;
        let t_peak = t_crest - 30f64.to_radians() / wc.omega;
        let d = m.eval(t_peak);
        assert!((d.q[2] - 1.2).abs() < 1e-12, "{}", d.q[2]);
        assert!(d.qd[2].abs() < 1e-12);
        assert!((d.qdd[2] + 1.2 * 0.36).abs() < 1e-12);
    }

    #[test]
    fn ramp_derivatives_are_consistent() {
        let mut v = [(0.0, 0.0); 6];
        v[4] = (0.02, 0.5);
        let rao = RaoTable::new(vec![0.8], vec![0.0], vec![v]);
        let wc = WaveComponent {
            amplitude: 2.0,
            omega: 0.8,
            k: 0.8 * 0.8 / 9.81,
            direction: 0.0,
            phase: 0.2,
        };
        let m = RaoMotion::new(&rao, &[wc], 0.0, 0.0, 0.0, 10.0);
        assert_eq!(m.eval(0.0).q[4], 0.0);
        let h = 1e-4;
        for &t in &[2.0, 7.5, 12.0] {
            let (a, b, c) = (m.eval(t - h), m.eval(t), m.eval(t + h));
            assert!(((c.q[4] - a.q[4]) / (2.0 * h) - b.qd[4]).abs() < 1e-9);
            assert!(((c.qd[4] - a.qd[4]) / (2.0 * h) - b.qdd[4]).abs() < 1e-9);
        }
    }
}
