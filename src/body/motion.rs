//! Body motion from a 6-DOF time series (`t,x,y,z,roll,pitch,yaw`), interpolated by a
//! natural cubic spline per degree of freedom.
//!
//! Why cubic, not linear: a cable end on a body follows the body's acceleration (the
//! end constraint takes the target acceleration as it is), so the motion must have a
//! continuous velocity and acceleration. Linear interpolation has neither: its
//! velocity jumps at every sample, which puts an impulse on the end node and a spike
//! in its force at every sample time. The natural cubic spline through the samples is
//! twice continuously differentiable and is the interpolant of least curvature; its
//! error on a smooth motion sampled every `h` is of order `h^4`. Outside the table's
//! span the motion is held at the first or last row (zero velocity and acceleration),
//! as route tables are. Angles are unwrapped before the spline (a step of more than
//! 180 degrees between rows is taken as the short way round), so a yaw record that
//! crosses +-180 degrees does not spin the body.

use super::kinematics::Dofs;

/// A natural cubic spline through `(t_i, y_i)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Spline {
    /// Second derivatives at the samples (zero at both ends).
    m: Vec<f64>,
    /// Sample values.
    y: Vec<f64>,
}

impl Spline {
    /// The spline through `y` at the strictly increasing times `t` (same length).
    pub fn new(t: &[f64], y: &[f64]) -> Self {
        let n = y.len();
        let mut m = vec![0.0; n];
        if n > 2 {
            // Tridiagonal system for the interior second derivatives (Thomas algorithm):
            // h_{i-1} m_{i-1} + 2 (h_{i-1} + h_i) m_i + h_i m_{i+1}
            //   = 6 ((y_{i+1} - y_i) / h_i - (y_i - y_{i-1}) / h_{i-1}).
            let mut diag = vec![0.0; n];
            let mut rhs = vec![0.0; n];
            for i in 1..n - 1 {
                let (h0, h1) = (t[i] - t[i - 1], t[i + 1] - t[i]);
                diag[i] = 2.0 * (h0 + h1);
                rhs[i] = 6.0 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
            }
            for i in 2..n - 1 {
                let w = (t[i] - t[i - 1]) / diag[i - 1];
                diag[i] -= w * (t[i] - t[i - 1]);
                rhs[i] -= w * rhs[i - 1];
            }
            for i in (1..n - 1).rev() {
                m[i] = (rhs[i] - (t[i + 1] - t[i]) * m[i + 1]) / diag[i];
            }
        }
        Self { m, y: y.to_vec() }
    }

    /// Value, first and second derivative on segment `i` (between `t[i]` and
    /// `t[i + 1]`) at time `x`.
    #[doc(hidden)]
    pub fn eval_segment(&self, t: &[f64], i: usize, x: f64) -> (f64, f64, f64) {
        let h = t[i + 1] - t[i];
        let (a, b) = (t[i + 1] - x, x - t[i]);
        let (m0, m1) = (self.m[i], self.m[i + 1]);
        let (c0, c1) = (
            self.y[i] / h - m0 * h / 6.0,
            self.y[i + 1] / h - m1 * h / 6.0,
        );
        (
            (m0 * a * a * a + m1 * b * b * b) / (6.0 * h) + c0 * a + c1 * b,
            (m1 * b * b - m0 * a * a) / (2.0 * h) + c1 - c0,
            (m0 * a + m1 * b) / h,
        )
    }
}

/// A 6-DOF motion table: times, s, and per degree of freedom a spline of surge, sway,
/// heave (m) and roll, pitch, yaw (rad).
#[derive(Clone, Debug, PartialEq)]
pub struct MotionTable {
    t: Vec<f64>,
    dof: [Spline; 6],
}

/// Adds multiples of 360 degrees so that no step between rows exceeds 180 degrees.
pub fn unwrap_degrees(a: &mut [f64]) {
    for i in 1..a.len() {
        let d = a[i] - a[i - 1];
        a[i] -= 360.0 * (d / 360.0).round();
    }
}

impl MotionTable {
    /// The table of rows `[x, y, z, roll, pitch, yaw]` (m and degrees) at the strictly
    /// increasing times `t` (s); the caller has checked both (finite, increasing).
    pub fn new(t: Vec<f64>, rows: &[[f64; 6]]) -> Self {
        assert_eq!(t.len(), rows.len());
        assert!(!t.is_empty());
        let dof = std::array::from_fn(|k| {
            let mut col: Vec<f64> = rows.iter().map(|r| r[k]).collect();
            if k >= 3 {
                unwrap_degrees(&mut col);
                col.iter_mut().for_each(|a| *a = a.to_radians());
            }
            Spline::new(&t, &col)
        });
        Self { t, dof }
    }

    /// Whether the roll, pitch and yaw columns are all zero (a pinned body's file).
    pub fn translation_only(&self) -> bool {
        self.dof[3..].iter().all(|s| s.y.iter().all(|&a| a == 0.0))
    }

    /// Time span covered, s.
    pub fn span(&self) -> (f64, f64) {
        (self.t[0], self.t[self.t.len() - 1])
    }

    /// The motion at time `t`, s (held outside the table's span).
    pub fn eval(&self, t: f64) -> Dofs {
        let n = self.t.len();
        let mut d = Dofs::default();
        if n == 1 || t <= self.t[0] || t >= self.t[n - 1] {
            let i = if n == 1 || t <= self.t[0] { 0 } else { n - 1 };
            for k in 0..6 {
                d.q[k] = self.dof[k].y[i];
            }
            return d;
        }
        let i = self.t.partition_point(|&x| x <= t).clamp(1, n - 1) - 1;
        for k in 0..6 {
            (d.q[k], d.qd[k], d.qdd[k]) = self.dof[k].eval_segment(&self.t, i, t);
        }
        d
    }
}
