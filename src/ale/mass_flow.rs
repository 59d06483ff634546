//! The mass-flow forces of the variable element and the material velocity in it.

use crate::math::V3;

/// The mass-flow forces of Eq. 39 on the variable element's material node `m` and
/// winch node `w` (see the module doc): `(-mbar l0 g / 6, -mbar l0 g / 3)` with
/// `g = -2 (Ldot / l0) (v_w - v_m) + (2 Ldot^2 / l0^2 - Lddot / l0) (r_w - r_m)`.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn mass_flow_forces(
    mbar: f64,
    l0: f64,
    rate: f64,
    accel: f64,
    rm: V3<f64>,
    rw: V3<f64>,
    vm: V3<f64>,
    vw: V3<f64>,
) -> (V3<f64>, V3<f64>) {
    let il0 = 1.0 / l0;
    let g = (vw - vm) * (-2.0 * rate * il0) + (rw - rm) * ((2.0 * rate * rate * il0 - accel) * il0);
    let s = -mbar * l0;
    (g * (s / 6.0), g * (s / 3.0))
}

/// The material velocity of the point at `xi` (from `m`, 0, to the winch, 1) of the
/// variable element: `(1 - xi) v_m + xi v_w - xi (Ldot / l0) (r_w - r_m)`.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn material_velocity(
    xi: f64,
    l0: f64,
    rate: f64,
    rm: V3<f64>,
    rw: V3<f64>,
    vm: V3<f64>,
    vw: V3<f64>,
) -> V3<f64> {
    vm * (1.0 - xi) + vw * xi - (rw - rm) * (xi * rate / l0)
}
