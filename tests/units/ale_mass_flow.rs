//! `src/ale/mass_flow.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::math::V3;
use cablesim::testing::ale_mass_flow::*;

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
