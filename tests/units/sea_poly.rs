//! `src/sea/poly.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::poly::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Against the library functions: `sin_cos` within `4 eps (1 + |x|)` (the
/// argument's own rounding is `eps |x|`), `exp_neg` within `4 eps` relative.
#[test]
fn agree_with_the_library_functions() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let eps = f64::EPSILON;
    for i in 0..200_000 {
        let x = match i % 3 {
            0 => rng.gen_range(-7.0..7.0),
            1 => rng.gen_range(-300.0..300.0),
            _ => rng.gen_range(-3e4..3e4),
        };
        let (s, c) = sin_cos(x);
        assert!(
            (s - x.sin()).abs() <= 4.0 * eps * (1.0 + x.abs()),
            "sin {x}"
        );
        assert!(
            (c - x.cos()).abs() <= 4.0 * eps * (1.0 + x.abs()),
            "cos {x}"
        );
        let z = match i % 3 {
            0 => rng.gen_range(-1.0..0.0),
            1 => rng.gen_range(-40.0..0.0),
            _ => rng.gen_range(-708.0..0.0),
        };
        assert!((exp_neg(z) / z.exp() - 1.0).abs() <= 4.0 * eps, "exp {z}");
        // The fused forms, within the same bounds.
        let (sf, cf) = sin_cos_with::<true>(x);
        assert!(
            (sf - x.sin()).abs() <= 4.0 * eps * (1.0 + x.abs()),
            "sin fma {x}"
        );
        assert!(
            (cf - x.cos()).abs() <= 4.0 * eps * (1.0 + x.abs()),
            "cos fma {x}"
        );
        let ef = exp_neg_with::<true>(z);
        assert!((ef / z.exp() - 1.0).abs() <= 4.0 * eps, "exp fma {z}");
    }
    assert_eq!(exp_neg(0.0), 1.0);
    assert_eq!(exp_neg(-1000.0), 0.0);
    assert_eq!(exp_neg(f64::NEG_INFINITY), 0.0);
}
