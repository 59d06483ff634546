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
        mu_axial: 0.5,
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

/// The friction split along and across the line: on a slope, sliding along the line
/// meets `mu_a F_N`, across it `mu_t F_N`, obliquely the weighted sum; the axial part
/// vanishes where the coefficients are equal, where the line stands normal to the
/// seabed, and off the seabed.
#[test]
fn friction_axis_splits_along_and_across_the_line() {
    let s = SeabedCoefs::<f64> {
        z: 0.0,
        k: 3e6,
        c: 3e4,
        mu: 0.8,
        mu_axial: 0.2,
        v_eps: 0.01,
    };
    // A 10 degree slope rising along x; the line runs up it, a little aslant.
    let g = V3::new(-50.0, 10f64.to_radians().tan(), 0.0);
    let n = seabed_slope_normal(g);
    let (lt, r) = (2.0, V3::new(0.0, 0.0, -50.002));
    let fnorm = s.k * lt * (g.x - r.z) * n.z;
    let up = V3::new(1.0, 0.0, g.y) * (1.0 / (1.0 + g.y * g.y).sqrt());
    let across = V3::new(0.0, 1.0, 0.0);
    let t = up * 2.0 + n * 0.3; // not in the seabed plane: projected
    let friction = |v: V3<f64>| {
        // The contact force less its normal part, plus the axial correction.
        let f = seabed_slope_force(&s, lt, r, v, g);
        let (q, d) = seabed_friction_axis(&s, fnorm, n, v, t);
        let ff = f - n * f.dot(n) - q * (d * v.dot(q));
        (ff, q, d)
    };
    for (v, mu) in [(up * 0.5, s.mu_axial), (across * 0.5, s.mu)] {
        let (ff, q, _) = friction(v);
        assert!((q - up).norm() < 1e-12, "{q:?}");
        let want = v * (-mu * fnorm / v.norm());
        assert!((ff - want).norm() < 1e-9 * fnorm, "{ff:?} vs {want:?}");
    }
    let v = (up + across) * 0.3;
    let (ff, _, d) = friction(v);
    let want = (up * (s.mu_axial * 0.3) + across * (s.mu * 0.3)) * (-fnorm / v.norm());
    assert!((ff - want).norm() < 1e-9 * fnorm && d < 0.0);
    // The same coefficients, a line normal to the seabed, no contact: no split.
    let iso = SeabedCoefs { mu_axial: 0.8, ..s };
    assert_eq!(seabed_friction_axis(&iso, fnorm, n, v, t).1, 0.0);
    assert_eq!(seabed_friction_axis(&s, fnorm, n, v, n * 3.0).1, 0.0);
    assert_eq!(seabed_friction_axis(&s, 0.0, n, v, t).1, 0.0);
}
