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
