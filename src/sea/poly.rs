//! Sine, cosine and exponential by range reduction and polynomials, as the WGSL twins
//! compute them (`sin_cos` of the prelude, `wave_exp` of waves.wgsl), inlined.
//!
//! Why not `f64::sin_cos` and `f64::exp`: the per-node sum over 200 components is the
//! whole cost of a wave kinematics refresh, and the library calls cost several times
//! these inlined, branch-free forms, whose independent iterations the processor
//! overlaps. Accuracy: within a few units in the last place (the tests compare with
//! the library functions over the ranges the kinematics use).

use std::f64::consts::{FRAC_2_PI, FRAC_PI_2, LOG2_E};

/// `1.5 * 2^52`: adding and subtracting it rounds an f64 of magnitude below 2^51 to
/// the nearest integer without a library call.
const ROUND: f64 = 6755399441055744.0;
const PIO2_LO: f64 = 6.123233995736766e-17;
/// ln 2 split so that `n * LN2_HI` is exact for `|n| < 2^37` (16 significant bits).
const LN2_HI: f64 = 0.693145751953125;
const LN2_LO: f64 = 1.4286068203094172321e-06;

/// Taylor coefficients of `sin(y) / y` in `y^2` (to `y^14`; the next term is below
/// 5e-17 for `|y| <= pi / 4`).
const SIN: [f64; 8] = [
    1.0,
    -1.0 / 6.0,
    1.0 / 120.0,
    -1.0 / 5040.0,
    1.0 / 362880.0,
    -1.0 / 39916800.0,
    1.0 / 6227020800.0,
    -1.0 / 1307674368000.0,
];
/// Taylor coefficients of `cos(y)` in `y^2` (to `y^16`).
const COS: [f64; 9] = [
    1.0,
    -0.5,
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40320.0,
    -1.0 / 3628800.0,
    1.0 / 479001600.0,
    -1.0 / 87178291200.0,
    1.0 / 20922789888000.0,
];
/// Taylor coefficients of `e^r` (to `r^13`; the next term is below 1e-17 for
/// `|r| <= ln 2 / 2`).
const EXP: [f64; 14] = [
    1.0,
    1.0,
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5040.0,
    1.0 / 40320.0,
    1.0 / 362880.0,
    1.0 / 3628800.0,
    1.0 / 39916800.0,
    1.0 / 479001600.0,
    1.0 / 6227020800.0,
];

/// `sum c[i] x^i` by Horner's rule (unrolled by the compiler: the length is fixed);
/// with `FMA`, each step one fused multiply-add (one rounding instead of two: call it
/// only where the target has FMA, or `mul_add` is a library call).
#[inline(always)]
fn horner<const N: usize, const FMA: bool>(c: &[f64; N], x: f64) -> f64 {
    let mut p = c[N - 1];
    for i in (0..N - 1).rev() {
        p = if FMA {
            p.mul_add(x, c[i])
        } else {
            p * x + c[i]
        };
    }
    p
}

/// `(sin x, cos x)` for `|x| < 2^50`.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    sin_cos_with::<false>(x)
}

/// `e^x` for `x <= 0` (0 below -708, where `e^x` leaves the normal numbers).
#[inline(always)]
pub fn exp_neg(x: f64) -> f64 {
    exp_neg_with::<false>(x)
}

/// [`sin_cos`], its polynomials by fused multiply-adds when `FMA` (the same accuracy
/// bound; results may differ from [`sin_cos`] in the last place).
#[inline(always)]
pub fn sin_cos_with<const FMA: bool>(x: f64) -> (f64, f64) {
    let shifted = x * FRAC_2_PI + ROUND;
    let q = shifted - ROUND;
    let y = (x - q * FRAC_PI_2) - q * PIO2_LO;
    let y2 = y * y;
    let s = y * horner::<8, FMA>(&SIN, y2);
    let c = horner::<9, FMA>(&COS, y2);
    // The quadrant `q mod 4` is in the low bits of `shifted` (its unit in the last
    // place is 1), read without a float-to-integer conversion; the quadrant then
    // selects and negates without branches (`0: (s, c)`, `1: (c, -s)`, `2: (-s, -c)`,
    // `3: (-c, s)`), so that a loop of these vectorises.
    let quadrant = shifted.to_bits() & 3;
    let (sin, cos) = if quadrant & 1 != 0 { (c, s) } else { (s, c) };
    let sin = if quadrant & 2 != 0 { -sin } else { sin };
    let cos = if (quadrant + 1) & 2 != 0 { -cos } else { cos };
    (sin, cos)
}

/// [`exp_neg`], its polynomial by fused multiply-adds when `FMA`.
#[inline(always)]
pub fn exp_neg_with<const FMA: bool>(x: f64) -> f64 {
    let shifted = x * LOG2_E + ROUND;
    let n = shifted - ROUND;
    let r = (x - n * LN2_HI) - n * LN2_LO;
    let p = horner::<14, FMA>(&EXP, r);
    // `2^n` from the low bits of `shifted` (`n` in two's complement), without a
    // float-to-integer conversion: `(n + 1023) << 52` is the exponent field, right
    // for `-1022 <= n <= 0`. Below -708 the result is 0, by a select rather than a
    // branch (the arithmetic above is then meaningless but harmless).
    let scaled = p * f64::from_bits(shifted.to_bits().wrapping_add(1023) << 52);
    if x < -708.0 {
        0.0
    } else {
        scaled
    }
}
