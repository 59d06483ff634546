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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mass_flow_vanishes_in_steady_payout() {
        let (l0, eps, rate) = (3.0, 0.01, 0.7);
        let t = V3::new(0.0, 0.0, 1.0);
        let rw = V3::new(0.0, 0.0, 0.0);
        let rm = rw - t * (l0 * (1.0 + eps));
        let vw = V3::zero();
        let vm = t * (-rate * (1.0 + eps));
        let (fm, fw) = mass_flow_forces(5.0, l0, rate, 0.0, rm, rw, vm, vw);
        assert!(fm.norm() < 1e-12 && fw.norm() < 1e-12, "{fm:?} {fw:?}");
        // Material velocity is uniform along the element.
        for xi in [0.0, 0.3, 1.0] {
            let v = material_velocity(xi, l0, rate, rm, rw, vm, vw);
            assert!((v - vm).norm() < 1e-12);
        }
        // A stopping payout pushes the material node away from the winch.
        let (fm, _) = mass_flow_forces(5.0, l0, rate, -1.0, rm, rw, vm, vw);
        assert!(fm.z < 0.0);
    }
}
