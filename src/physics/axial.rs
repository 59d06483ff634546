//! Nonlinear axial stiffness: a line's tension as a tabulated function of its strain
//! (docs/src/model/axial.md).
//!
//! A curve is a list of rows `(strain, tension)` with both columns strictly increasing
//! and the first strain at least zero (checked where the curve is read,
//! `scenario::materials`). Between rows the tension is linear in the strain; from zero
//! strain to the first row it runs from `(0, 0)`; past the last row it goes on with the
//! last segment's slope; at and below zero strain it is zero (slack).

use crate::math::Real;

/// The segment of `rows` that holds strain `eps > 0`: `(x0, y0, x1, y1)`.
#[inline(always)]
fn segment<T: Real>(rows: &[[T; 2]], eps: T) -> (T, T, T, T) {
    let first = rows[0];
    if eps <= first[0] {
        return (T::zero(), T::zero(), first[0], first[1]);
    }
    let n = rows.len();
    let mut i = 1;
    while i + 1 < n && rows[i][0] < eps {
        i += 1;
    }
    (rows[i - 1][0], rows[i - 1][1], rows[i][0], rows[i][1])
}

/// Tension of the curve `rows` at strain `eps`, N (see the module doc). WGSL twin:
/// `tabulated_tension` in `shaders/shared/prelude.wgsl`, which reads the rows from the
/// packed table buffer.
#[inline(always)]
pub fn tabulated_tension<T: Real>(rows: &[[T; 2]], eps: T) -> T {
    if !(eps > T::zero()) {
        return T::zero();
    }
    let (x0, y0, x1, y1) = segment(rows, eps);
    y0 + (eps - x0) * ((y1 - y0) / (x1 - x0))
}

/// The slope `dT/deps` of the curve at strain `eps`, N (zero when slack).
#[inline(always)]
pub fn tabulated_slope(rows: &[[f64; 2]], eps: f64) -> f64 {
    if !(eps > 0.0) {
        return 0.0;
    }
    let (x0, y0, x1, y1) = segment(rows, eps);
    (y1 - y0) / (x1 - x0)
}

/// The work `int_{e0}^{e0 + de} T(eps) deps` of the curve, N, formed piece by piece
/// (exact for the piecewise-linear curve) from the increment `de` itself, so that it
/// stays accurate when `de` is small against `e0`.
pub fn tabulated_work(rows: &[[f64; 2]], e0: f64, de: f64) -> f64 {
    if de < 0.0 {
        return -tabulated_work(rows, e0 + de, -de);
    }
    let e1 = e0 + de;
    if !(e1 > 0.0) {
        return 0.0;
    }
    // Breakpoints inside (e0, e1): zero and the rows' strains.
    let mut a = e0.max(0.0);
    let mut w = 0.0;
    let mut knots = std::iter::once(0.0)
        .chain(rows.iter().map(|r| r[0]))
        .filter(|&x| x > a && x < e1)
        .collect::<Vec<_>>();
    knots.push(e1);
    for b in knots {
        // Linear on [a, b]: the trapezoid is exact.
        let width = if a == e0 && b == e1 { de } else { b - a };
        w += 0.5 * width * (tabulated_tension(rows, a) + tabulated_tension(rows, b));
        a = b;
    }
    w
}

/// The largest slope of the curve, N: the stiffness the stable step and the internal
/// damping (`EA c`) take for a tabulated line.
pub fn tabulated_max_slope(rows: &[[f64; 2]]) -> f64 {
    let mut prev = [0.0, 0.0];
    let mut k: f64 = 0.0;
    for r in rows {
        if r[0] > prev[0] {
            k = k.max((r[1] - prev[1]) / (r[0] - prev[0]));
        }
        prev = *r;
    }
    k
}

/// Checks a curve: at least two rows, every value finite, the strains and the tensions
/// strictly increasing, the first strain at least zero and its tension at least zero,
/// zero tension at zero strain. The error names the row (counted from 1) and the value.
pub fn check_curve(rows: &[[f64; 2]]) -> Result<(), String> {
    if rows.len() < 2 {
        return Err(format!(
            "needs at least two rows (strain, tension), got {}",
            rows.len()
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        if !(r[0].is_finite() && r[1].is_finite()) {
            return Err(format!(
                "row {}: values must be finite, got ({}, {})",
                i + 1,
                r[0],
                r[1]
            ));
        }
    }
    let f = rows[0];
    if f[0] < 0.0 || f[1] < 0.0 {
        return Err(format!(
            "row 1: strain and tension must be at least zero, got ({}, {})",
            f[0], f[1]
        ));
    }
    if f[0] == 0.0 && f[1] != 0.0 {
        return Err(format!(
            "row 1: the tension at zero strain must be zero, got {}",
            f[1]
        ));
    }
    for (i, w) in rows.windows(2).enumerate() {
        if !(w[1][0] > w[0][0]) {
            return Err(format!(
                "row {}: strains must increase, got {} after {}",
                i + 2,
                w[1][0],
                w[0][0]
            ));
        }
        if !(w[1][1] > w[0][1]) {
            return Err(format!(
                "row {}: tensions must increase, got {} after {}",
                i + 2,
                w[1][1],
                w[0][1]
            ));
        }
    }
    if f[0] > 0.0 && !(f[1] > 0.0) {
        return Err(format!(
            "row 1: tensions must increase from zero at zero strain, got {}",
            f[1]
        ));
    }
    Ok(())
}
