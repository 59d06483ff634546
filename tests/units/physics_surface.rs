//! `src/physics/surface.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::physics::surface::*;

#[test]
fn element_fraction_is_the_submerged_share_and_continuous() {
    // Sharp (no diameter).
    assert_eq!(wetted_fraction(1.0, 2.0, 0.0), 1.0);
    assert_eq!(wetted_fraction(0.0, 2.0, 0.0), 1.0);
    assert_eq!(wetted_fraction(-1.0, -2.0, 0.0), 0.0);
    assert_eq!(wetted_fraction(0.0, -2.0, 0.0), 0.0);
    // Node a 1 m under, node b 3 m above: a quarter of the segment is wet.
    assert_eq!(wetted_fraction(1.0, -3.0, 0.0), 0.25);
    assert_eq!(wetted_fraction(-3.0, 1.0, 0.0), 0.25);
    // With a diameter: half a diameter more wet length, crossing.
    let d: f64 = 0.1;
    assert!((wetted_fraction(1.0, -3.0, d) - (1.0 + 0.5 * d) / 4.0).abs() < 1e-15);
    assert_eq!(wetted_fraction(0.0, 0.0, d), 1.0);
    assert_eq!(wetted_fraction(-d, -2.0, d), 0.0);
    // Level and floating: the band share of the section.
    assert!((wetted_fraction(-0.25 * d, -0.25 * d, d) - 0.75).abs() < 1e-15);
    // Nearly level, also across a kink of the section's share: no cancellation.
    let f = |sa: f64| wetted_fraction(sa, -0.3 * d, d);
    // u runs from 0.7 + 1e-11 to 0.7: the mean is its midpoint.
    assert!((f(-0.3 * d + 1e-12) - (0.7f64 + 5e-12)).abs() < 1e-14);
    // Across u = 1 over 2e-9: 1.5e-9 of it above the kink (share 1), 0.5e-9 below
    // (mean share 1 - 0.25e-9): the mean is 1 - 6.25e-11.
    let g: f64 = wetted_fraction(-0.5e-9 * d, 1.5e-9 * d, d);
    assert!((g - (1.0 - 6.25e-11)).abs() < 1e-15, "{g}");
    assert!(wetted_fraction(1e-12, -1.0, d) < 1.0);
    assert!((wetted_fraction(-1e-12, 1.0, d) - 1.0).abs() < 1e-11);
}

#[test]
fn sphere_fraction_is_the_cap_volume() {
    let r = 0.5;
    assert_eq!(point_wetted_fraction(1.0, r), 1.0);
    assert_eq!(point_wetted_fraction(-1.0, r), 0.0);
    assert_eq!(point_wetted_fraction(0.0, r), 0.5);
    // Cap of height h = 0.25 (a quarter of the diameter): pi h^2 (3 r - h) / 3 over
    // 4/3 pi r^3.
    let h: f64 = 0.25;
    let cap = h * h * (3.0 * r - h) / (4.0 * r * r * r);
    assert!((point_wetted_fraction(h - r, r) - cap).abs() < 1e-15);
    assert!((sphere_radius(4.0 / 3.0 * std::f64::consts::PI * 8.0) - 2.0).abs() < 1e-14);
    assert_eq!(point_wetted_fraction(0.0, 0.0), 1.0);
    assert_eq!(point_wetted_fraction(-1e-9, 0.0), 0.0);
}
