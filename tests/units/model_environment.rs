//! `src/model/environment.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::model_environment::*;

#[test]
fn current_profile_interpolates_and_holds_beyond_its_ends() {
    let c = Current {
        table: vec![
            (-100.0, [0.0, 0.0, 0.0]),
            (-20.0, [0.8, 0.4, 0.0]),
            (0.0, [1.0, 0.4, 0.0]),
        ],
    };
    let u = |z: f64| c.at::<f64>(z).to_f64();
    assert_eq!(u(-60.0), [0.4, 0.2, 0.0]);
    assert_eq!(u(-10.0), [0.9, 0.4, 0.0]);
    assert_eq!(u(-500.0), [0.0, 0.0, 0.0]);
    assert_eq!(u(5.0), [1.0, 0.4, 0.0]);
    assert_eq!(
        Current::uniform([0.3, 0.0, 0.0]).at::<f64>(-1e4).to_f64(),
        [0.3, 0.0, 0.0]
    );
}
