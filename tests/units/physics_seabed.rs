//! `src/physics/seabed.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::math::V3;
use cablesim::physics::seabed::*;

#[test]
fn contact_force_pushes_up_and_friction_opposes_sliding() {
    let s = SeabedCoefs::<f64> {
        z: -100.0,
        k: 3e6,
        c: 3e4,
        mu: 0.5,
        v_eps: 0.01,
    };
    let up = seabed_force(&s, 2.0, V3::new(0.0, 0.0, -100.01), V3::zero());
    assert!((up.z - 3e6 * 2.0 * 0.01).abs() < 1e-6);
    assert_eq!((up.x, up.y), (0.0, 0.0));
    let sliding = seabed_force(&s, 2.0, V3::new(0.0, 0.0, -100.01), V3::new(1.0, 0.0, 0.0));
    assert!((sliding.x + 0.5 * up.z).abs() < 1e-6);
    // The damping slopes reproduce the force's damping part.
    let v = V3::new(0.3, -0.4, 0.2);
    let c = seabed_damping(&s, 2.0, V3::new(0.0, 0.0, -100.01), v);
    let f = seabed_force(&s, 2.0, V3::new(0.0, 0.0, -100.01), v);
    assert!((f.x + c.x * v.x).abs() < 1e-9 && (f.y + c.y * v.y).abs() < 1e-9);
    assert!((f.z - up.z + c.z * v.z).abs() < 1e-9);
    let above = seabed_force(&s, 2.0, V3::new(0.0, 0.0, -99.0), V3::new(1.0, 0.0, -1.0));
    assert_eq!(above, V3::zero());
}
