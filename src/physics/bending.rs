//! Bending stiffness `EI` of a lumped-mass cable (docs/src/model/bending.md).
//!
//! A cable bends at hinges: an interior node joins its cable's element before it
//! (unit tangent `q1`, current length `l1`) and after it (`q2`, `l2`); a clamped end
//! joins the held direction and its first (or last) element. The hinge stores the
//! energy `E = EI phi^2 / (2 lbar)`, `phi` the angle between `q1` and `q2` and `lbar`
//! the unstretched length the hinge stands for (half of each element beside it; half
//! of the one element at a clamp), so that its curvature is `phi / lbar`. The forces
//! are `-dE/dr` exactly: the model is conservative and the static solver's energy
//! holds them.

use crate::math::{Real, V3};

/// The hinge's stiffness `EI / lbar`, N m, of bending stiffness `ei` over the
/// unstretched length `lbar`.
#[inline(always)]
pub fn hinge_stiffness(ei: f64, lbar: f64) -> f64 {
    ei / lbar
}

/// The angle `phi` between unit tangents `q1`, `q2` and the factor `phi / sin(phi)`
/// (1 at `phi = 0`, by its series below `sin(phi) = 1e-4`).
#[inline(always)]
pub fn bending_angle<T: Real>(q1: V3<T>, q2: V3<T>) -> (T, T) {
    let c = q1.dot(q2);
    let s = q1.cross(q2).norm();
    let phi = s.atan2(c);
    let g = if s < T::c(1e-4) {
        T::one() + phi * phi / T::c(6.0)
    } else {
        phi / s
    };
    (phi, g)
}

/// The bending forces of a hinge of stiffness `k = EI / lbar` between the element
/// before it (unit tangent `q1`, length `l1`) and the one after it (`q2`, `l2`): the
/// force on the far node of the element before (`f1`) and on the far node of the
/// element after (`f2`); the hinge's own node receives `-(f1 + f2)`. With
/// `phi / sin(phi) = g`:
/// `f1 = -(k g / l1) (q2 - (q1 . q2) q1)`, `f2 = (k g / l2) (q1 - (q1 . q2) q2)`,
/// each across its element, so that the pair makes the moment `EI phi / lbar` about
/// the hinge and no net force or moment.
#[inline(always)]
pub fn bending_hinge<T: Real>(q1: V3<T>, l1: T, q2: V3<T>, l2: T, k: T) -> (V3<T>, V3<T>) {
    let c = q1.dot(q2);
    let (_, g) = bending_angle(q1, q2);
    let kg = k * g;
    let f1 = (q2 - q1 * c) * (-kg / l1);
    let f2 = (q1 - q2 * c) * (kg / l2);
    (f1, f2)
}

/// The energy `k phi^2 / 2` of a hinge of stiffness `k = EI / lbar`, J.
#[inline(always)]
pub fn bending_energy<T: Real>(q1: V3<T>, q2: V3<T>, k: T) -> T {
    let (phi, _) = bending_angle(q1, q2);
    T::c(0.5) * k * phi * phi
}
