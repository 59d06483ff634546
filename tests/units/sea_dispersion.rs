//! `src/sea/dispersion.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::dispersion::*;
use std::f64::consts::PI;

const G: f64 = 9.80665;

/// The relation holds to round-off: `|g k tanh(k h) - w^2| <= 1e-14 w^2` from very
/// shallow (`k h` ~ 1e-3) to deep (`k h` ~ 100) water.
#[test]
fn satisfies_the_relation_to_round_off() {
    let mut worst: f64 = 0.0;
    for &h in &[0.5, 2.0, 10.0, 50.0, 200.0, 1000.0, 4000.0] {
        for i in 0..400 {
            let omega = 10f64.powf(-2.5 + 3.5 * i as f64 / 399.0);
            let k = wave_number(omega, h, G);
            let r = (G * k * (k * h).tanh() - omega * omega).abs() / (omega * omega);
            worst = worst.max(r);
            assert!(
                r <= 1e-14,
                "h = {h}, w = {omega}: k = {k}, relative residual {r:e}"
            );
        }
    }
    eprintln!("worst relative residual {worst:e}");
}

/// DNV-RP-C205 (sec. 3.2.2, after Hunt 1979) gives the wavelength in finite depth as
/// `L = T sqrt(g d) sqrt(f / (1 + w f))`, with `w = 4 pi^2 d / (g T^2)` and
/// `f = 1 + 0.666 w + 0.445 w^2 - 0.105 w^3 + 0.272 w^4`, an approximation it states to
/// be good to a fraction of a percent. Our exact solution must agree to within 0.2% over the
/// whole range of depth to wavelength (the approximation's own worst error there is
/// 0.15%), and a wrong solution (e.g. the deep-water wavelength in shallow water,
/// off by up to a factor of ten) would not.
#[test]
fn agrees_with_the_dnv_wavelength_formula() {
    for &d in &[1.0, 10.0, 100.0] {
        for i in 0..200 {
            let w = 0.01 + 9.99 * i as f64 / 199.0;
            let period = (4.0 * PI * PI * d / (G * w)).sqrt();
            let f = 1.0 + 0.666 * w + 0.445 * w * w - 0.105 * w.powi(3) + 0.272 * w.powi(4);
            let l_dnv = period * (G * d).sqrt() * (f / (1.0 + w * f)).sqrt();
            let l = 2.0 * PI / wave_number_of_period(period, d, G);
            assert!(
                (l / l_dnv - 1.0).abs() < 2e-3,
                "d = {d} m, T = {period} s: L = {l}, DNV {l_dnv}"
            );
        }
    }
}

/// The limits: deep water `k = w^2 / g` (also for infinite depth), shallow water
/// `k -> w / sqrt(g h)` with the first correction `k h = a^(1/2) (1 + a / 6)`.
#[test]
fn deep_and_shallow_limits() {
    let omega = 2.0 * PI / 8.0;
    assert_eq!(wave_number(omega, f64::INFINITY, G), omega * omega / G);
    let k = wave_number(omega, 1000.0, G);
    assert!((k / (omega * omega / G) - 1.0).abs() < 1e-15);
    for &h in &[1e-4, 1e-3, 1e-2] {
        let a = omega * omega * h / G;
        let k = wave_number(omega, h, G);
        let long = omega / (G * h).sqrt();
        let series = a.sqrt() * (1.0 + a / 6.0) / h;
        assert!(
            (k / series - 1.0).abs() < a * a,
            "h = {h}: k = {k}, series {series}"
        );
        assert!(
            k > long,
            "finite depth makes the wave shorter than the long wave"
        );
    }
}
