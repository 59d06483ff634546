//! The water surface: how much of an element, or of a point mass, is under water.
//!
//! A submergence `s = eta - z` is the depth of a point below the instantaneous surface
//! elevation `eta` above it (`eta = 0` in still water): positive under water, negative
//! in air. The rules below are continuous in the node positions, so a cable crossing
//! the surface sees no jump in any load (docs/water_surface.md states them in words).

use crate::math::Real;

/// Fraction of a straight element under water, from the submergences `sa`, `sb` of its
/// two nodes: 1 when neither node is in air, 0 when neither is under water, else the
/// submerged share of the straight segment between them, `s+ / (|sa| + |sb|)` with
/// `s+` the positive one. It tends to 0 as the submerged node reaches the surface and
/// to 1 as the node in air does, so it is continuous except when both nodes reach the
/// surface at once (an element lying on it).
#[inline(always)]
pub fn wetted_fraction<T: Real>(sa: T, sb: T) -> T {
    let zero = T::zero();
    if sa >= zero && sb >= zero {
        T::one()
    } else if sa <= zero && sb <= zero {
        zero
    } else {
        (sa.max(zero) + sb.max(zero)) / (sa.abs() + sb.abs())
    }
}

/// Fraction of a point mass's volume under water, the point taken as a sphere of
/// radius `radius` (m) centred on its node, whose centre is submerged by `s` (m): the
/// volume of the submerged cap over the sphere's, `x^2 (3 - 2 x)` with
/// `x = (s + radius) / (2 radius)` clamped to [0, 1] (the cap height over the
/// diameter). It is 1 when the sphere is under water, 0 when it is clear of it, and its
/// slope is continuous too. A point without volume (`radius` 0) is wet when its node is.
#[inline(always)]
pub fn point_wetted_fraction<T: Real>(s: T, radius: T) -> T {
    let zero = T::zero();
    if radius <= zero {
        return if s >= zero { T::one() } else { zero };
    }
    let x = ((s + radius) / (radius + radius)).max(zero).min(T::one());
    x * x * (T::c(3.0) - x - x)
}

/// Radius of the sphere of volume `volume` (m^3), m: the size [`point_wetted_fraction`]
/// gives a point mass.
pub fn sphere_radius(volume: f64) -> f64 {
    (3.0 * volume.max(0.0) / (4.0 * std::f64::consts::PI)).cbrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_fraction_is_the_submerged_share_and_continuous() {
        assert_eq!(wetted_fraction(1.0, 2.0), 1.0);
        assert_eq!(wetted_fraction(0.0, 2.0), 1.0);
        assert_eq!(wetted_fraction(-1.0, -2.0), 0.0);
        assert_eq!(wetted_fraction(0.0, -2.0), 0.0);
        // Node a 1 m under, node b 3 m above: a quarter of the segment is wet.
        assert_eq!(wetted_fraction(1.0, -3.0), 0.25);
        assert_eq!(wetted_fraction(-3.0, 1.0), 0.25);
        // Approaching the ends of the mixed case from inside meets the pure cases.
        assert!(wetted_fraction(1e-12, -1.0) < 1e-11);
        assert!(wetted_fraction(1.0, -1e-12) > 1.0 - 1e-11);
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
}
