//! `src/scenario/materials.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::scenario::materials::*;
use std::f64::consts::PI;

#[test]
fn studless_chain_76mm_against_hand_values() {
    let l = Material::ChainStudless.line(0.076);
    let d2 = 0.076f64 * 0.076;
    assert!((l.mass_per_length - 20.0e3 * d2).abs() < 1e-9);
    assert!((l.diameter - 0.1368).abs() < 1e-12);
    assert!((l.ea - (85.6e9 * d2 - 3.93e7 * d2 * 0.076)).abs() < 1e-3);
    // The volume-equivalent diameter of 7850 kg/m^3 steel: within 1% of 1.8 d_n.
    let dvol_steel = (4.0 * l.mass_per_length / (PI * 7850.0)).sqrt();
    assert!((dvol_steel / l.diameter - 1.0).abs() < 0.01, "{dvol_steel}");
    assert_eq!((l.cn, l.ct, l.cm), (1.333, Some(0.639), 1.0));
}

#[test]
fn fibre_rope_stiffness_follows_its_breaking_load() {
    let l = Material::Polyester.line(0.2);
    let mbl = 308e6 * 0.04;
    assert!((l.mbl - mbl).abs() < 1e-6);
    assert!((l.ea - 14.0 * mbl).abs() < 1e-3);
    // From its density: mass = rho A, so the rope is barely heavier than water.
    let area = PI * l.diameter * l.diameter / 4.0;
    assert!((area * 1380.0 - l.mass_per_length).abs() < 1e-9);
    assert_eq!(l.ct, None);
}
