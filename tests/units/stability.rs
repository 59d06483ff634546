//! `src/stability.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::options::Scheme;
use cablesim::stability::*;

#[test]
fn symplectic_bound_matches_model_md() {
    // Undamped: omega dt < 2.
    assert!((mode_step(Scheme::Symplectic, 100.0, 0.0) - 0.2).abs() < 1e-12);
    let (w2, g) = (1.0e6, 300.0);
    let dt = mode_step(Scheme::Symplectic, w2, g);
    assert!((w2 * dt * dt + 2.0 * g * dt - 4.0).abs() < 1e-9);
}

#[test]
fn rk4_reaches_its_imaginary_axis_limit() {
    // RK4 is stable on the imaginary axis up to 2 sqrt(2).
    let dt = mode_step(Scheme::Rk4, 1.0, 0.0);
    assert!((dt - 2.0 * 2f64.sqrt()).abs() < 1e-3, "{dt}");
    // RK2 needs damping; with some it allows a finite step.
    let undamped = mode_step(Scheme::Rk2, 1.0, 0.0);
    let damped = mode_step(Scheme::Rk2, 1.0, 0.1);
    assert!(undamped < 0.05 && damped > 0.5, "{undamped} {damped}");
}
