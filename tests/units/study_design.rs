//! `src/study/design.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::study::design::*;

#[test]
fn design_tension_and_utilisation_against_hand_values() {
    // T_mean 2.0 MN, T_MPM 3.5 MN, factors 1.1 and 1.5:
    // T_d = 2.2 + 1.5 * 1.5 = 4.45 MN; on S_C = 8.9 MN, utilisation 0.5.
    let c = DesignCheck::new(8.9e6, 1.1, 1.5, 2.0e6, 3.5e6);
    assert!((c.design_tension - 4.45e6).abs() < 1e-6);
    assert!((c.utilisation - 0.5).abs() < 1e-15);
    // Unit factors give back the MPM itself.
    assert_eq!(design_tension(1.0, 1.0, 2.0e6, 3.5e6), 3.5e6);
    // A consequence class 2 set (1.4, 2.1): 2.8 + 3.15 = 5.95 MN.
    assert!((design_tension(1.4, 2.1, 2.0e6, 3.5e6) - 5.95e6).abs() < 1e-6);
}
