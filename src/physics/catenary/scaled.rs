//! Newton's method on the catenary equations in the scaled unknowns `h = HF/(wL)`,
//! `v = VF/(wL)` (lengths in units of `L`, stretch parameter `e = wL/EA`); see the
//! parent module's doc for why the Jacobian is symmetric positive definite.

/// Relative residual (in units of `L`) at which Newton's method stops.
const TOL: f64 = 1e-13;
/// Residual still accepted when round-off stalls the iteration.
const TOL_STALLED: f64 = 1e-9;
/// Newton iterations at most.
const MAX_ITER: usize = 200;

/// A solution in scaled unknowns.
pub(super) struct Scaled {
    pub(super) h: f64,
    pub(super) v: f64,
    pub(super) iterations: usize,
}

/// `asinh(p/h) - asinh(q/h)` without cancellation when `p` and `q` are close (a taut
/// line): `asinh((p^2 - q^2) / (p tq + q tp))` with `tp = hypot(h, p)`,
/// `tq = hypot(h, q)`, where `p` and `q` have the same sign.
pub(super) fn asinh_diff(p: f64, q: f64, h: f64, tp: f64, tq: f64) -> f64 {
    if p * q > 0.0 {
        ((p - q) * (p + q) / (p * tq + q * tp)).asinh()
    } else {
        (p / h).asinh() - (q / h).asinh()
    }
}

/// The scaled equations at `(h > 0, v)`: residual functions `(X(h,v), Z(h,v))` and
/// their symmetric Jacobian `[jxx, jxv, jvv]`.
fn equations(h: f64, v: f64, e: f64, seabed: bool) -> ([f64; 2], [f64; 3]) {
    if seabed && v < 1.0 {
        let v = v.max(0.0);
        let t = h.hypot(v);
        let ash = (v / h).asinh();
        let x = 1.0 - v + h * ash + h * e;
        let z = v * v / (t + h) + 0.5 * e * v * v;
        let jxx = ash - v / t + e;
        let jxv = -v * v / (t * (t + h));
        let jvv = v / t + e * v;
        ([x, z], [jxx, jxv, jvv])
    } else {
        let va = v - 1.0;
        let (tf, ta) = (h.hypot(v), h.hypot(va));
        let dash = asinh_diff(v, va, h, tf, ta);
        let x = h * dash + h * e;
        let z = (2.0 * v - 1.0) / (tf + ta) + e * (v - 0.5);
        let jxx = dash - v / tf + va / ta + e;
        let jxv = h / tf - h / ta;
        let jvv = v / tf - va / ta + e;
        ([x, z], [jxx, jxv, jvv])
    }
}

/// The convex function `G(h, v)` whose gradient is the pair of equations.
fn potential(h: f64, v: f64, e: f64, seabed: bool) -> f64 {
    // int sqrt(h^2 + u^2) du
    let f = |u: f64| 0.5 * (u * h.hypot(u) + h * h * (u / h).asinh());
    if seabed && v < 1.0 {
        let v = v.max(0.0);
        f(v) + 0.5 * e * (h * h * v + v * v * v / 3.0) + (1.0 - v) * (h + 0.5 * e * h * h)
    } else {
        f(v) - f(v - 1.0) + 0.5 * e * (h * h + v * v - v + 1.0 / 3.0)
    }
}

/// Solves the scaled problem: span `big_x >= 0`, rise `big_z`, stretch parameter `e`.
pub(super) fn solve_scaled(big_x: f64, big_z: f64, e: f64, seabed: bool) -> Result<Scaled, String> {
    let closed = |h: f64, v: f64| {
        Ok(Scaled {
            h,
            v,
            iterations: 0,
        })
    };
    // Slack on the seabed: the hanging part is vertical, V0 solves
    // Z = v + e v^2 / 2, and the rest (1 - V0) covers the span with no tension.
    if seabed {
        let v0 = 2.0 * big_z / (1.0 + (1.0 + 2.0 * e * big_z).sqrt());
        if v0 <= 1.0 && 1.0 - v0 >= big_x {
            return closed(0.0, v0);
        }
    }
    // Vertical line (h = 0): Z = k(v) - k(v - 1) with k(q) = |q| + e q^2 / 2,
    // i.e. Z = |v| - |v - 1| + e (v - 1/2), increasing in v and piecewise linear;
    // solve it branch by branch.
    if big_x == 0.0 {
        // v >= 1 (taut, the anchor pulls down): Z = 1 + e (v - 1/2).
        if big_z >= 1.0 + 0.5 * e {
            if e == 0.0 {
                return Err("a vertical inextensible line cannot reach its fairlead".into());
            }
            return closed(0.0, (big_z - 1.0) / e + 0.5);
        }
        // 0 <= v <= 1 (the line folds below the anchor): Z = (2 + e)(v - 1/2).
        if big_z >= -1.0 - 0.5 * e {
            return closed(0.0, 0.5 + big_z / (2.0 + e));
        }
        if e == 0.0 {
            return Err("a vertical inextensible line cannot reach its fairlead".into());
        }
        return closed(0.0, (big_z + 1.0) / e + 0.5);
    }
    // Initial guess.
    let d = big_x.hypot(big_z);
    let (mut h, mut v) = if d >= 1.0 && e > 0.0 {
        // Nearly straight and stretched: tension from the strain along the chord.
        let t = (d - 1.0) / e;
        let lam: f64 = 0.2;
        (
            (t * big_x / d).max(big_x / (2.0 * lam)),
            t * big_z / d + 0.5,
        )
    } else {
        let lam = if d >= 1.0 {
            0.2
        } else {
            (3.0 * ((1.0 - big_z * big_z) / (big_x * big_x) - 1.0))
                .max(0.0)
                .sqrt()
                .max(0.2)
        };
        (
            (big_x / (2.0 * lam)).max(1e-12),
            0.5 * (big_z / lam.tanh() + 1.0),
        )
    };
    if seabed && v <= 0.0 {
        v = 1e-3;
    }
    let target = [big_x, big_z];
    let resid = |h: f64, v: f64| {
        let (f, j) = equations(h, v, e, seabed);
        ([f[0] - target[0], f[1] - target[1]], j)
    };
    let merit = |h: f64, v: f64| potential(h, v, e, seabed) - big_x * h - big_z * v;
    let norm = |r: [f64; 2]| r[0].abs().max(r[1].abs());
    let (mut r, mut j) = resid(h, v);
    let mut phi = merit(h, v);
    for it in 0..MAX_ITER {
        if !(r[0].is_finite() && r[1].is_finite()) {
            return Err(format!(
                "catenary iteration produced a non-finite residual at HF/wL = {h}, VF/wL = {v}"
            ));
        }
        if norm(r) < TOL {
            return Ok(Scaled {
                h,
                v,
                iterations: it,
            });
        }
        // Newton direction (the Jacobian is symmetric positive definite; fall back to
        // the steepest descent of the convex function if round-off says otherwise).
        let det = j[0] * j[2] - j[1] * j[1];
        let (mut dh, mut dv) = if det > 0.0 && j[0] > 0.0 {
            (
                -(j[2] * r[0] - j[1] * r[1]) / det,
                -(j[0] * r[1] - j[1] * r[0]) / det,
            )
        } else {
            (-r[0], -r[1])
        };
        // Keep h > 0 (and v > 0 where the seabed formulas need it).
        let mut amax: f64 = 1.0;
        if h + dh <= 0.0 {
            amax = amax.min(0.9 * h / -dh);
        }
        if seabed && v + amax * dv <= 0.0 && v > 0.0 {
            amax = amax.min(0.9 * v / -dv);
        }
        dh *= amax;
        dv *= amax;
        let slope = r[0] * dh + r[1] * dv; // directional derivative of the merit
        let mut alpha = 1.0;
        let mut accepted = false;
        for _ in 0..60 {
            let (hn, vn) = (h + alpha * dh, v + alpha * dv);
            let (rn, jn) = resid(hn, vn);
            let phin = merit(hn, vn);
            if (phin <= phi + 1e-4 * alpha * slope) || norm(rn) < 0.5 * norm(r) {
                h = hn;
                v = vn;
                r = rn;
                j = jn;
                phi = phin;
                accepted = true;
                break;
            }
            alpha *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    if norm(r) < TOL_STALLED {
        return Ok(Scaled {
            h,
            v,
            iterations: MAX_ITER,
        });
    }
    Err(format!(
        "catenary did not converge: residual {:.3e} (of the line length) at HF/wL = {h:.6e}, VF/wL = {v:.6e}",
        norm(r)
    ))
}
