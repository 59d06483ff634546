//! Seabed contact (docs/src/model/seabed.md, paper Eq. 48 with `zdot` for `z` and a
//! regularised friction law).

use crate::math::{Real, V3};

/// Seabed constants in the precision of the computation.
#[derive(Clone, Copy, Debug, Default)]
pub struct SeabedCoefs<T> {
    /// Seabed height `z_b = -depth`, m.
    pub z: T,
    /// Stiffness per metre of cable, N/m^2.
    pub k: T,
    /// Damping per metre of cable, N s/m^2.
    pub c: T,
    /// Friction coefficient.
    pub mu: T,
    /// Friction regularisation velocity, m/s.
    pub v_eps: T,
}

/// Contact force on a node at `r` moving at `v`, with tributary length `lt`
/// (half the sum of its elements' unstretched lengths). Zero above the seabed.
#[inline(always)]
pub fn seabed_force<T: Real>(s: &SeabedCoefs<T>, lt: T, r: V3<T>, v: V3<T>) -> V3<T> {
    let pen = s.z - r.z;
    if pen <= T::zero() {
        return V3::zero();
    }
    let fz = s.k * lt * pen - s.c * lt * v.z;
    let mut f = V3::new(T::zero(), T::zero(), fz);
    if s.mu > T::zero() {
        // |F_N| is the elastic normal force (paper Eq. 48); friction opposes the
        // sliding velocity and is linear below v_eps, so a node at rest feels none.
        let fnorm = s.k * lt * pen;
        let vh = V3::new(v.x, v.y, T::zero());
        let speed = vh.norm().max(s.v_eps);
        f += vh * (-s.mu * fnorm / speed);
    }
    f
}

/// The contact's damping slopes on a node at `r` moving at `v` (tributary length
/// `lt`): `(c_h, c_h, c_z)`, N s/m, with `c_z = C lt` (normal damping) and
/// `c_h = mu F_N / max(|v_h|, v_eps)` (the regularised friction as a damper, its slope
/// at the node's current speed), so that the damping part of [`seabed_force`] is
/// `-(c_h v_x, c_h v_y, c_z v_z)`. Zero above the seabed.
///
/// The symplectic stepper treats these terms implicitly: it solves
/// `(M + dt diag(c)) a = F` instead of `M a = F` (docs/src/model/seabed.md), so the
/// contact's damping does not bound the explicit step.
#[inline(always)]
pub fn seabed_damping<T: Real>(s: &SeabedCoefs<T>, lt: T, r: V3<T>, v: V3<T>) -> V3<T> {
    let pen = s.z - r.z;
    if pen <= T::zero() {
        return V3::zero();
    }
    let cz = s.c * lt;
    let mut ch = T::zero();
    if s.mu > T::zero() {
        let fnorm = s.k * lt * pen;
        let speed = V3::new(v.x, v.y, T::zero()).norm().max(s.v_eps);
        ch = s.mu * fnorm / speed;
    }
    V3::new(ch, ch, cz)
}
