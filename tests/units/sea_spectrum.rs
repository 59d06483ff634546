//! `src/sea/spectrum.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::spectrum::*;
use std::f64::consts::TAU;

/// `m0 = Hs^2 / 16` within 1% for Pierson-Moskowitz and JONSWAP over the DNV
/// range of the peak factor; the PM zero-crossing period against its closed form.
#[test]
fn zeroth_moment_is_hs_squared_over_16() {
    for &(hs, tp) in &[(2.0, 6.0), (6.0, 11.0), (14.0, 16.0)] {
        let m0 = hs * hs / 16.0;
        let pm = Spectrum::PiersonMoskowitz { hs, tp };
        assert!((pm.moment(0) / m0 - 1.0).abs() < 1e-4, "PM m0");
        for &gamma in &[1.0, 2.0, 3.3, 5.0] {
            let j = Spectrum::Jonswap { hs, tp, gamma };
            let r = j.moment(0) / m0;
            assert!(
                (r - 1.0).abs() < 0.01,
                "JONSWAP Hs {hs} Tp {tp} g {gamma}: {r}"
            );
        }
        // PM in closed form: m_n = Hs^2 / 16 w_p^n (5/4)^(n/4) Gamma(1 - n/4), so
        // Tz = 2 pi sqrt(m0 / m2) = Tp / (5 pi / 4)^(1/4) = Tp / 1.4077 (the
        // support's cut at 20 w_p lowers m2 by 0.3%).
        let tz = TAU * (pm.moment(0) / pm.moment(2)).sqrt();
        let ratio = (5.0 * std::f64::consts::PI / 4.0).powf(0.25);
        assert!((tp / tz / ratio - 1.0).abs() < 3e-3, "Tp/Tz = {}", tp / tz);
    }
}

/// The DNV peak factor in its three regimes, and continuous at the borders.
#[test]
fn dnv_peak_factor_regimes() {
    assert_eq!(dnv_peak_factor(4.0, 6.0), 5.0); // Tp / sqrt(Hs) = 3
    assert_eq!(dnv_peak_factor(4.0, 12.0), 1.0); // 6
    let g = dnv_peak_factor(4.0, 8.6); // 4.3
    assert!((g - (5.75 - 1.15 * 4.3f64).exp()).abs() < 1e-12);
    assert!((dnv_peak_factor(1.0, 3.6 + 1e-12) - 5.0).abs() < 0.01);
    assert!((dnv_peak_factor(1.0, 5.0 - 1e-12) - 1.0).abs() < 1e-9);
}

/// JONSWAP with `g = 1` is Pierson-Moskowitz; the peak is at `w_p` and raised by
/// `g (1 - 0.287 ln g)` relative to PM.
#[test]
fn jonswap_shape() {
    let (hs, tp) = (5.0, 10.0);
    let pm = Spectrum::PiersonMoskowitz { hs, tp };
    let j1 = Spectrum::Jonswap { hs, tp, gamma: 1.0 };
    let j = Spectrum::Jonswap { hs, tp, gamma: 3.3 };
    let wp = TAU / tp;
    for &w in &[0.3, 0.5, wp, 0.9, 1.5] {
        assert!((j1.density(w) - pm.density(w)).abs() < 1e-15 * pm.density(wp));
    }
    let ratio = j.density(wp) / pm.density(wp);
    assert!((ratio - 3.3 * (1.0 - 0.287 * 3.3f64.ln())).abs() < 1e-12);
    assert!(j.density(wp) > j.density(wp * 0.98) && j.density(wp) > j.density(wp * 1.02));
}

/// A table is linear between its points and zero outside.
#[test]
fn table_interpolates() {
    let t = Spectrum::Table {
        omega: vec![0.3, 0.5, 0.8],
        density: vec![0.0, 2.0, 1.0],
    };
    assert_eq!(t.density(0.2), 0.0);
    assert!((t.density(0.4) - 1.0).abs() < 1e-15);
    assert!((t.density(0.65) - 1.5).abs() < 1e-15);
    assert_eq!(t.density(0.9), 0.0);
    // m0: two trapezoids, 0.2 * 1 + 0.3 * 1.5.
    assert!((t.moment(0) - 0.65).abs() < 1e-9);
}
