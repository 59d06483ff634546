//! Rigid-body kinematics of a body with prescribed motion, and of a point fixed on it.
//!
//! Conventions (stated once; the docs, the table and RAO readers and the WGSL twin use
//! them): the rotation from body to global coordinates is
//! `R = Rz(yaw) Ry(pitch) Rx(roll)` (roll about x first, then pitch about y, then yaw
//! about z, each about the fixed global axes; equivalently yaw, pitch, roll about the
//! body's own axes). With all angles zero the body axes are the global ones. A point
//! fixed at body coordinates `p` (relative to the reference point) is at
//! `r = X + q`, `q = R p`, and moves with
//!
//! ```text
//! v = V + w x q
//! a = A + alpha x q + w x (w x q)
//! ```
//!
//! where `X`, `V`, `A` are the reference point's position, velocity and acceleration
//! and `w`, `alpha` the angular velocity and acceleration, both in global axes. For
//! this rotation order, with `a2 = Rz(yaw) e_y` and `a3 = Rz(yaw) Ry(pitch) e_x` (the
//! axes the pitch and roll rates turn about),
//!
//! ```text
//! w     = yaw' e_z + pitch' a2 + roll' a3
//! alpha = yaw'' e_z + pitch'' a2 + roll'' a3
//!         + yaw' pitch' (e_z x a2) + (yaw' e_z + pitch' a2) x (roll' a3)
//! ```
//!
//! (`a2` turns at `yaw' e_z`, `a3` at `yaw' e_z + pitch' a2`).

use crate::math::V3;
use crate::model::RouteState;

type V = V3<f64>;

/// Six degrees of freedom and their first two time derivatives: surge, sway, heave
/// (m, m/s, m/s^2) and roll, pitch, yaw (rad, rad/s, rad/s^2).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dofs {
    /// Values.
    pub q: [f64; 6],
    /// First time derivatives.
    pub qd: [f64; 6],
    /// Second time derivatives.
    pub qdd: [f64; 6],
}

/// Where a body sits when it does not move: its reference point and mean offset
/// (global, m) and its mean heading (rad, from +x towards +y).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeanPose {
    /// The reference point at rest, m.
    pub reference: [f64; 3],
    /// Mean displacement added to the reference point, m.
    pub offset: [f64; 3],
    /// Mean heading (a yaw added to the motion's), rad.
    pub heading: f64,
}

impl MeanPose {
    /// The mean position of the reference point (`reference + offset`), m.
    pub fn position(&self) -> [f64; 3] {
        [0, 1, 2].map(|d| self.reference[d] + self.offset[d])
    }
}

/// The motion state of a body at one time, global axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyState {
    /// Reference point position `X`, m.
    pub x: V,
    /// Reference point velocity `V`, m/s.
    pub v: V,
    /// Reference point acceleration `A`, m/s^2.
    pub a: V,
    /// Rotation body -> global, rows of `R`.
    pub rot: [[f64; 3]; 3],
    /// Angular velocity `w`, rad/s.
    pub omega: V,
    /// Angular acceleration `alpha`, rad/s^2.
    pub alpha: V,
}

/// `R = Rz(yaw) Ry(pitch) Rx(roll)`, rows; angles in rad.
pub fn rotation(roll: f64, pitch: f64, yaw: f64) -> [[f64; 3]; 3] {
    let (sr, cr) = roll.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let (sy, cy) = yaw.sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// `m p` for a matrix given by rows.
pub fn mat_vec(m: &[[f64; 3]; 3], p: [f64; 3]) -> V {
    let row = |r: [f64; 3]| r[0] * p[0] + r[1] * p[1] + r[2] * p[2];
    V::new(row(m[0]), row(m[1]), row(m[2]))
}

/// Angular velocity and acceleration (global axes) of `R = Rz(yaw) Ry(pitch) Rx(roll)`
/// from the angles (`d.q[3..6]`) and their rates (see the module doc).
pub fn angular(d: &Dofs) -> (V, V) {
    let [_, pitch, yaw] = [d.q[3], d.q[4], d.q[5]];
    let [rd, pd, yd] = [d.qd[3], d.qd[4], d.qd[5]];
    let [rdd, pdd, ydd] = [d.qdd[3], d.qdd[4], d.qdd[5]];
    let (sy, cy) = yaw.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let ez = V::new(0.0, 0.0, 1.0);
    let a2 = V::new(-sy, cy, 0.0);
    let a3 = V::new(cy * cp, sy * cp, -sp);
    let omega = ez * yd + a2 * pd + a3 * rd;
    let turn = ez * yd + a2 * pd;
    let alpha = ez * ydd + a2 * pdd + a3 * rdd + ez.cross(a2) * (yd * pd) + turn.cross(a3 * rd);
    (omega, alpha)
}

/// The body's state from its mean pose and its motion about it: the translations
/// `d.q[0..3]` are along the mean-heading axes (surge, sway, heave; with a zero heading
/// the global ones), the angles are roll, pitch and yaw, the heading added to the yaw.
pub fn body_state(pose: &MeanPose, d: &Dofs) -> BodyState {
    let (sh, ch) = pose.heading.sin_cos();
    let turn = |x: f64, y: f64, z: f64| V::new(ch * x - sh * y, sh * x + ch * y, z);
    let m = pose.position();
    let dx = turn(d.q[0], d.q[1], d.q[2]);
    let mut e = *d;
    e.q[5] += pose.heading;
    let (omega, alpha) = angular(&e);
    BodyState {
        x: V::new(m[0], m[1], m[2]) + dx,
        v: turn(d.qd[0], d.qd[1], d.qd[2]),
        a: turn(d.qdd[0], d.qdd[1], d.qdd[2]),
        rot: rotation(e.q[3], e.q[4], e.q[5]),
        omega,
        alpha,
    }
}

/// Position, velocity and acceleration of the point at body coordinates `at` (m,
/// relative to the reference point): the rigid-body formulas of the module doc.
/// WGSL twin: `body_point` (in rebased form; see `gpu::solver::body_rows`).
pub fn attachment(s: &BodyState, at: [f64; 3]) -> RouteState {
    let q = mat_vec(&s.rot, at);
    let v = s.v + s.omega.cross(q);
    let a = s.a + s.alpha.cross(q) + s.omega.cross(s.omega.cross(q));
    RouteState {
        r: (s.x + q).to_f64(),
        v: v.to_f64(),
        a: a.to_f64(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(t: f64) -> Dofs {
        // Smooth, large, unrelated motions in every degree of freedom.
        let f = |a: f64, w: f64, p: f64| {
            (
                a * (w * t + p).cos(),
                -a * w * (w * t + p).sin(),
                -a * w * w * (w * t + p).cos(),
            )
        };
        let mut d = Dofs::default();
        for (i, (a, w, p)) in [
            (2.0, 0.7, 0.1),
            (-1.5, 0.9, 1.0),
            (3.0, 0.5, 2.0),
            (0.4, 1.1, 0.3),
            (0.3, 0.8, -0.5),
            (0.9, 0.6, 1.7),
        ]
        .into_iter()
        .enumerate()
        {
            (d.q[i], d.qd[i], d.qdd[i]) = f(a, w, p);
        }
        d
    }

    #[test]
    fn rotation_is_yaw_after_pitch_after_roll() {
        // Roll alone turns +y towards +z; pitch alone turns +z towards +x; yaw alone
        // turns +x towards +y.
        let r = rotation(0.5, 0.0, 0.0);
        assert!((r[2][1] - 0.5f64.sin()).abs() < 1e-15);
        let p = rotation(0.0, 0.5, 0.0);
        assert!((p[0][2] - 0.5f64.sin()).abs() < 1e-15);
        let y = rotation(0.0, 0.0, 0.5);
        assert!((y[1][0] - 0.5f64.sin()).abs() < 1e-15);
        // The product, composed by hand in that order.
        let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| {
            let mut c = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
                }
            }
            c
        };
        let full = rotation(0.3, -0.4, 1.2);
        let composed = mul(
            rotation(0.0, 0.0, 1.2),
            mul(rotation(0.0, -0.4, 0.0), rotation(0.3, 0.0, 0.0)),
        );
        for i in 0..3 {
            for j in 0..3 {
                assert!((full[i][j] - composed[i][j]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn attachment_velocity_and_acceleration_are_derivatives_of_its_position() {
        let pose = MeanPose {
            reference: [10.0, -5.0, 2.0],
            offset: [1.0, 2.0, -0.5],
            heading: 0.7,
        };
        let at = [40.0, -12.0, 8.0];
        let pos = |t: f64| attachment(&body_state(&pose, &motion(t)), at).r;
        let h = 1e-4;
        for &t in &[0.0, 1.3, 7.9] {
            let s = attachment(&body_state(&pose, &motion(t)), at);
            let (m, p) = (pos(t - h), pos(t + h));
            for k in 0..3 {
                let v = (p[k] - m[k]) / (2.0 * h);
                let a = (p[k] - 2.0 * s.r[k] + m[k]) / (h * h);
                // Central differences: error h^2 |r'''| / 6 (v) and rounding
                // 4 eps |r| / h^2 (a), with |r| ~ 50 m and rates ~ 1 s^-1.
                assert!((v - s.v[k]).abs() < 1e-6, "t {t} v{k}: {v} vs {}", s.v[k]);
                assert!((a - s.a[k]).abs() < 5e-4, "t {t} a{k}: {a} vs {}", s.a[k]);
            }
        }
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // matrix products written out
    fn angular_velocity_is_the_rotation_rate() {
        // dR/dt R^T = [w]x, and its derivative gives alpha.
        let h = 1e-5;
        let pose = MeanPose::default();
        for &t in &[0.4, 3.0] {
            let s = body_state(&pose, &motion(t));
            let (m, p) = (
                body_state(&pose, &motion(t - h)),
                body_state(&pose, &motion(t + h)),
            );
            let mut w = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    w[i][j] = (0..3)
                        .map(|k| (p.rot[i][k] - m.rot[i][k]) / (2.0 * h) * s.rot[j][k])
                        .sum();
                }
            }
            let fd = [w[2][1], w[0][2], w[1][0]];
            let om = s.omega.to_f64();
            let al = s.alpha.to_f64();
            let fd_alpha =
                [0, 1, 2].map(|k| (p.omega.to_f64()[k] - m.omega.to_f64()[k]) / (2.0 * h));
            for k in 0..3 {
                assert!((fd[k] - om[k]).abs() < 1e-8, "w{k}: {} vs {}", fd[k], om[k]);
                assert!(
                    (fd_alpha[k] - al[k]).abs() < 1e-7,
                    "alpha{k}: {} vs {}",
                    fd_alpha[k],
                    al[k]
                );
            }
        }
    }
}
