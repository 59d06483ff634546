//! The water surface: how much of an element, or of a point mass, is under water.
//!
//! A submergence `s = eta - z` is the depth of a point below the instantaneous surface
//! elevation `eta` above it (`eta = 0` in still water): positive under water, negative
//! in air. The rules below are continuous in the node positions, so a cable crossing
//! the surface sees no jump in any load (docs/src/water_surface.md states them in words).

use crate::math::Real;

/// Fraction of a straight element of diameter `diameter` (m) under water, from the
/// submergences `sa`, `sb` of its two nodes.
///
/// The element's section is taken as a band of height `diameter` reaching up from its
/// node line: a point of the element at submergence `s` is wet for the share
/// `clamp(1 + s / d, 0, 1)` of its section, and `f` is that share averaged along the
/// straight element: with `u = 1 + s / d` running linearly from `ua` to `ub`, the
/// mean of `clamp(u, 0, 1)` over `[lo, hi] = [min, max](ua, ub)`, formed from the
/// lengths of its parts in `[0, 1]` and above 1 (no cancellation, however close `ua`
/// and `ub`). So `f = 1` exactly when neither node is above
/// the surface (a submerged line's loads are untouched) and `f = 0` when both are at
/// least a diameter above it; `f` and its slope are continuous, also for an element
/// lying along the surface (a floating line), where a sharp waterline would make the
/// buoyancy jump from none to all over a vanishing height. Crossing the surface, the
/// element counts half a diameter more wet length than its straight segment has below
/// the surface. A diameter of zero gives the sharp segment share.
#[inline(always)]
pub fn wetted_fraction<T: Real>(sa: T, sb: T, diameter: T) -> T {
    let zero = T::zero();
    let one = T::one();
    if sa >= zero && sb >= zero {
        return one;
    }
    if sa <= -diameter && sb <= -diameter {
        return zero;
    }
    if diameter <= zero {
        return (sa.max(zero) + sb.max(zero)) / (sa.abs() + sb.abs());
    }
    let (ua, ub) = (one + sa / diameter, one + sb / diameter);
    let (lo, hi) = (ua.min(ub), ua.max(ub));
    if hi <= lo {
        return lo.max(zero).min(one);
    }
    // The part in [0, 1] (length w0, mean value its midpoint) and the part above 1.
    let (a, b) = (lo.max(zero), hi.min(one));
    let w0 = (b - a).max(zero);
    let w1 = (hi - lo.max(one)).max(zero);
    (w0 * (T::c(0.5) * (a + b)) + w1) / (hi - lo)
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
