//! The analytic elastic catenary, with seabed contact (no seabed friction).
//!
//! A uniform line of unstretched length `L`, axial stiffness `EA` and wet weight `w`
//! per unit length hangs between an *anchor* (the lower end, the origin here) and a
//! *fairlead* at horizontal distance `xf >= 0` and height `zf` above the anchor. With
//! `HF`, `VF` the horizontal and vertical components of the tension at the fairlead,
//! the classical equations (as in MoorPy and MoorDyn) are
//!
//! * fully suspended:
//!   `XF = (HF/w)[asinh(VF/HF) - asinh((VF - wL)/HF)] + HF L/EA`,
//!   `ZF = (HF/w)[sqrt(1+(VF/HF)^2) - sqrt(1+((VF-wL)/HF)^2)] + (VF L - w L^2/2)/EA`;
//! * with the lower part lying on the seabed (`VF < wL`, grounded length
//!   `LB = L - VF/w`): `XF = LB + (HF/w) asinh(VF/HF) + HF L/EA`,
//!   `ZF = (HF/w)(sqrt(1+(VF/HF)^2) - 1) + VF^2/(2 EA w)`.
//!
//! # How it is solved
//! In the unknowns `h = HF/(wL)`, `v = VF/(wL)`, lengths scaled by `L` and the stretch
//! parameter `e = wL/EA`, both systems are the gradient of one function,
//! `G(h, v) = int_0^1 phi(h, V(s)) ds` with `phi = T + e T^2/2`, `T = sqrt(h^2 + V^2)`
//! and `V(s) = v - 1 + s` (suspended) or `max(v - 1 + s, 0)` (on the seabed: the
//! grounded part carries no vertical force). `G` is convex, so the solution is the
//! unique minimiser of `G(h, v) - X h - Z v` over `h >= 0`, and the Jacobian of the
//! equations (the Hessian of `G`) is symmetric and positive definite. The solver is
//! Newton's method with that analytic Jacobian, started from MoorDyn's initial guess
//! (or the straight elastic line when the ends are farther apart than `L`), with a
//! backtracking line search on the convex function (or on the residual, once round-off
//! dominates the function's decrease) and steps that keep `h > 0`. The solutions on
//! the boundary `h = 0` are written in closed form: a vertical line (`xf = 0`) and a
//! line slack on the seabed (more line than the straight path needs: its grounded part
//! carries no tension).
//!
//! Every length is in m, every force in N.

use std::f64::consts::PI;

/// Relative residual (in units of `L`) at which Newton's method stops.
const TOL: f64 = 1e-13;
/// Residual still accepted when round-off stalls the iteration.
const TOL_STALLED: f64 = 1e-9;
/// Newton iterations at most.
const MAX_ITER: usize = 200;

/// A solved catenary (see the module doc). Fairlead forces are the tension components
/// at the fairlead: the line pulls the fairlead towards the anchor with `hf` and down
/// with `vf`. Anchor forces are the tension components at the anchor: the line pulls
/// the anchor towards the fairlead with `ha` and up with `va` (negative `va`: down).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Catenary {
    /// Horizontal span from anchor to fairlead, m.
    pub xf: f64,
    /// Height of the fairlead above the anchor, m.
    pub zf: f64,
    /// Unstretched length `L`, m.
    pub length: f64,
    /// Axial stiffness `EA`, N.
    pub ea: f64,
    /// Wet weight per unit unstretched length `w`, N/m.
    pub w: f64,
    /// Whether the anchor lies on the seabed (contact possible).
    pub seabed: bool,
    /// Horizontal tension at the fairlead `HF`, N.
    pub hf: f64,
    /// Vertical tension at the fairlead `VF`, N.
    pub vf: f64,
    /// Horizontal tension at the anchor `HA`, N (equal to `hf`: no seabed friction).
    pub ha: f64,
    /// Vertical tension at the anchor `VA`, N (0 when part of the line is grounded).
    pub va: f64,
    /// Unstretched length lying on the seabed `LB`, m (0 when fully suspended).
    pub grounded_length: f64,
    /// Horizontal distance from the anchor to the touchdown point, m (0 when fully
    /// suspended).
    pub touchdown: f64,
    /// Newton iterations used (0 for the closed-form cases).
    pub iterations: usize,
}

/// Solves the elastic catenary from the anchor (lower end, origin) to the fairlead
/// at horizontal distance `xf >= 0` and height `zf` above it; `length` is the
/// unstretched length `L`, `ea` the axial stiffness (`f64::INFINITY` for an
/// inextensible line), `w > 0` the wet weight per unit length, and `seabed` says whether
/// the anchor lies on the seabed (then `zf >= 0`, and the lower part may lie on it).
///
/// Errors (with a sentence saying why): non-finite or non-positive `length`, `ea` or
/// `w` (a buoyant line has no hanging catenary), negative `xf`, the fairlead below a
/// seabed anchor, ends farther apart than an inextensible line reaches, a solution
/// that would stretch the line by more than 100 % (ends too far apart for the line),
/// or Newton's method failing to converge.
pub fn catenary(
    xf: f64,
    zf: f64,
    length: f64,
    ea: f64,
    w: f64,
    seabed: bool,
) -> Result<Catenary, String> {
    if !(length.is_finite() && length > 0.0) {
        return Err(format!("unstretched length must be positive, got {length}"));
    }
    if ea.is_nan() || ea <= 0.0 {
        return Err(format!("axial stiffness EA must be positive, got {ea}"));
    }
    if !(w.is_finite() && w > 0.0) {
        return Err(format!(
            "wet weight per length must be positive for a catenary, got {w} N/m"
        ));
    }
    if !(xf.is_finite() && xf >= 0.0 && zf.is_finite()) {
        return Err(format!(
            "span must be finite with xf >= 0, got xf = {xf}, zf = {zf}"
        ));
    }
    if seabed && zf < 0.0 {
        return Err(format!(
            "the fairlead is {:.6} m below an anchor on the seabed",
            -zf
        ));
    }
    let big_x = xf / length;
    let big_z = zf / length;
    let e = w * length / ea; // 0 for an inextensible line
    let d = big_x.hypot(big_z);
    if e == 0.0 && d >= 1.0 {
        return Err(format!(
            "the ends are {:.6} m apart, not less than the inextensible line's length {length} m",
            d * length
        ));
    }
    let sol = solve_scaled(big_x, big_z, e, seabed)?;
    let wl = w * length;
    let (h, v) = (sol.h, sol.v);
    let grounded = seabed && v < 1.0;
    let lb = if grounded { 1.0 - v.max(0.0) } else { 0.0 };
    let touchdown = if !grounded {
        0.0
    } else if h == 0.0 {
        big_x
    } else {
        lb * (1.0 + h * e)
    };
    let c = Catenary {
        xf,
        zf,
        length,
        ea,
        w,
        seabed,
        hf: h * wl,
        vf: v * wl,
        ha: h * wl,
        va: if grounded { 0.0 } else { (v - 1.0) * wl },
        grounded_length: lb * length,
        touchdown: touchdown * length,
        iterations: sol.iterations,
    };
    let strain = c.fairlead_tension() / ea;
    if strain > 1.0 {
        return Err(format!(
            "the ends are too far apart: the line would be stretched by {:.0} % (fairlead tension {:.4e} N, EA {ea:.4e} N)",
            strain * 100.0,
            c.fairlead_tension()
        ));
    }
    Ok(c)
}

impl Catenary {
    /// Tension magnitude at the fairlead, `sqrt(HF^2 + VF^2)`, N.
    pub fn fairlead_tension(&self) -> f64 {
        self.hf.hypot(self.vf)
    }

    /// Tension magnitude at the anchor, `sqrt(HA^2 + VA^2)`, N.
    pub fn anchor_tension(&self) -> f64 {
        self.ha.hypot(self.va)
    }

    /// True when no tension acts along the seabed and the grounded part is longer than
    /// the span it covers (the line is slack on the seabed; see [`Self::lateral_offset`]).
    pub fn is_slack(&self) -> bool {
        self.seabed && self.hf == 0.0 && self.grounded_length > 0.0
    }

    /// Vertical tension component at unstretched arclength `s` from the anchor, N.
    fn vertical_at(&self, s: f64) -> f64 {
        let v = self.vf - self.w * (self.length - s);
        if self.seabed && self.vf < self.w * self.length {
            v.max(0.0)
        } else {
            v
        }
    }

    /// Tension magnitude at unstretched arclength `s` from the anchor, N.
    pub fn tension(&self, s: f64) -> f64 {
        self.hf.hypot(self.vertical_at(s.clamp(0.0, self.length)))
    }

    /// Position `[x, z]` relative to the anchor (x horizontal towards the fairlead, z
    /// up) of the point at unstretched arclength `s` (clamped to `[0, L]`) from the
    /// anchor. On a line slack on the seabed the grounded part's `x` is its projection
    /// onto the anchor-fairlead direction, `s xf / LB`; [`Self::lateral_offset`] gives
    /// the sideways offset that lays it out at its full length.
    pub fn position(&self, s: f64) -> [f64; 2] {
        let l = self.length;
        let sig = s.clamp(0.0, l) / l;
        let e = self.w * l / self.ea;
        let h = self.hf / (self.w * l);
        let v = self.vf / (self.w * l);
        let big_x = self.xf / l;
        let grounded = self.seabed && v < 1.0;
        let (x, z) = if grounded {
            let lb = 1.0 - v.max(0.0);
            if sig <= lb {
                let x = if h == 0.0 {
                    if lb > 0.0 {
                        sig * big_x / lb
                    } else {
                        0.0
                    }
                } else {
                    sig * (1.0 + h * e)
                };
                (x, 0.0)
            } else {
                let q = sig - lb; // = V(s) / (wL) on the hanging part
                if h == 0.0 {
                    (big_x, q + 0.5 * e * q * q)
                } else {
                    let t = h.hypot(q);
                    (
                        lb * (1.0 + h * e) + h * (q / h).asinh() + h * e * q,
                        q * q / (t + h) + 0.5 * e * q * q,
                    )
                }
            }
        } else {
            let va = v - 1.0;
            if h == 0.0 {
                // Vertical line: dz/ds = sign(V) + V/EA.
                let q = va + sig;
                (0.0, q.abs() - va.abs() + e * sig * (va + 0.5 * sig))
            } else {
                let q = va + sig;
                let (t1, t0) = (h.hypot(q), h.hypot(va));
                (
                    h * asinh_diff(q, va, h, t1, t0) + h * e * sig,
                    sig * (2.0 * va + sig) / (t1 + t0) + e * (va * sig + 0.5 * sig * sig),
                )
            }
        };
        [x * l, z * l]
    }

    /// Sideways offset (perpendicular to the vertical plane through the ends), m, of
    /// the point at unstretched arclength `s` from the anchor. Zero except on a line
    /// slack on the seabed, whose grounded part (longer than the span `xf` it covers)
    /// is laid out as a V on the seabed, each leg `LB/2` long, so that no element of a
    /// discretised line is compressed to zero length.
    pub fn lateral_offset(&self, s: f64) -> f64 {
        if !self.is_slack() {
            return 0.0;
        }
        let lb = self.grounded_length;
        let s = s.clamp(0.0, self.length);
        if s >= lb {
            return 0.0;
        }
        let half = 0.5 * lb;
        let apex = (half * half - 0.25 * self.xf * self.xf).max(0.0).sqrt();
        if s <= half {
            apex * s / half
        } else {
            apex * (lb - s) / half
        }
    }
}

/// A solution in scaled unknowns.
struct Scaled {
    h: f64,
    v: f64,
    iterations: usize,
}

/// `asinh(p/h) - asinh(q/h)` without cancellation when `p` and `q` are close (a taut
/// line): `asinh((p^2 - q^2) / (p tq + q tp))` with `tp = hypot(h, p)`,
/// `tq = hypot(h, q)`, where `p` and `q` have the same sign.
fn asinh_diff(p: f64, q: f64, h: f64, tp: f64, tq: f64) -> f64 {
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
fn solve_scaled(big_x: f64, big_z: f64, e: f64, seabed: bool) -> Result<Scaled, String> {
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

/// `n + 1` points evenly spaced on the segment from `a` to `b` (`n >= 1`).
pub fn straight_positions(a: [f64; 3], b: [f64; 3], n: usize) -> Vec<[f64; 3]> {
    let n = n.max(1);
    (0..=n)
        .map(|k| {
            let f = k as f64 / n as f64;
            [
                a[0] + f * (b[0] - a[0]),
                a[1] + f * (b[1] - a[1]),
                a[2] + f * (b[2] - a[2]),
            ]
        })
        .collect()
}

/// Vertical distance within which the lower end counts as lying on the seabed, m.
pub const SEABED_TOLERANCE: f64 = 1e-3;

/// Initial node positions, `end_a` to `end_b`, of a cable of unstretched `length` cut
/// into `n` equal elements (`L/n` each), following the analytic elastic catenary (with
/// seabed contact) in the vertical plane through its ends. The lower end is the anchor;
/// it lies on the seabed when it is within [`SEABED_TOLERANCE`] of `seabed_z` (or
/// below it). `ea` is the axial stiffness and `w` the wet weight per unit length
/// (`LineType::wet_weight_per_length`). A line slack on the seabed lays its
/// surplus out as a V on the seabed (see [`Catenary::lateral_offset`]).
///
/// Falls back to [`straight_positions`] when no hanging catenary applies: a buoyant or
/// neutral line (`w <= 0`), a non-positive length or stiffness, or any other case where
/// [`catenary`] reports an error (which is logged as a warning). The two ends are
/// returned exactly as given.
pub fn catenary_positions(
    end_a: [f64; 3],
    end_b: [f64; 3],
    length: f64,
    n: usize,
    ea: f64,
    w: f64,
    seabed_z: f64,
) -> Vec<[f64; 3]> {
    let n = n.max(1);
    if !(w > 0.0 && length > 0.0 && ea > 0.0) {
        return straight_positions(end_a, end_b, n);
    }
    let a_is_anchor = end_a[2] <= end_b[2];
    let (anchor, fair) = if a_is_anchor {
        (end_a, end_b)
    } else {
        (end_b, end_a)
    };
    let (dx, dy) = (fair[0] - anchor[0], fair[1] - anchor[1]);
    let xf = dx.hypot(dy);
    let zf = fair[2] - anchor[2];
    let (dir, xf) = if xf > 1e-12 * length {
        ([dx / xf, dy / xf], xf)
    } else {
        ([1.0, 0.0], 0.0)
    };
    let side = [-dir[1], dir[0]];
    let on_seabed = anchor[2] <= seabed_z + SEABED_TOLERANCE;
    let cat = match catenary(xf, zf, length, ea, w, on_seabed) {
        Ok(c) => c,
        Err(e) => {
            log::warn!("no catenary initial shape ({e}); using a straight line");
            return straight_positions(end_a, end_b, n);
        }
    };
    let mut out: Vec<[f64; 3]> = (0..=n)
        .map(|k| {
            let s = length * k as f64 / n as f64;
            let s = if a_is_anchor { s } else { length - s };
            let [x, z] = cat.position(s);
            let y = cat.lateral_offset(s);
            [
                anchor[0] + dir[0] * x + side[0] * y,
                anchor[1] + dir[1] * x + side[1] * y,
                anchor[2] + z,
            ]
        })
        .collect();
    out[0] = end_a;
    out[n] = end_b;
    out
}

/// Wet weight per unit length of a round line of diameter `d` and mass per length
/// `mbar` in water of density `rho` under gravity `g`, N/m (a convenience for tests and
/// callers without a `LineType` at hand).
pub fn wet_weight(mbar: f64, d: f64, rho: f64, g: f64) -> f64 {
    (mbar - rho * PI * d * d / 4.0) * g
}

#[cfg(test)]
mod tests {
    use super::*;

    // The catenary example: chain-like line of the project's examples.
    const EA: f64 = 6.2832e7;
    fn w() -> f64 {
        wet_weight(5.0265, 0.04, 1025.0, 9.81)
    }

    /// The brief's equations written out literally (independently of the solver's
    /// scaled form): residuals of XF and ZF, m.
    fn literal_residuals(c: &Catenary) -> [f64; 2] {
        let (hf, vf, l, ea, w) = (c.hf, c.vf, c.length, c.ea, c.w);
        if c.seabed && vf < w * l {
            let lb = l - vf / w;
            let xf = lb + hf / w * (vf / hf).asinh() + hf * l / ea;
            let zf = hf / w * ((1.0 + (vf / hf).powi(2)).sqrt() - 1.0) + vf * vf / (2.0 * ea * w);
            [xf - c.xf, zf - c.zf]
        } else {
            let xf = hf / w * ((vf / hf).asinh() - ((vf - w * l) / hf).asinh()) + hf * l / ea;
            let zf = hf / w
                * ((1.0 + (vf / hf).powi(2)).sqrt() - (1.0 + ((vf - w * l) / hf).powi(2)).sqrt())
                + (vf * l - w * l * l / 2.0) / ea;
            [xf - c.xf, zf - c.zf]
        }
    }

    fn check_solution(c: &Catenary, tol: f64) {
        // The literal forms lose about eps * T / w to cancellation (very taut lines).
        let r = literal_residuals(c);
        let tol = tol + 64.0 * f64::EPSILON * c.fairlead_tension() / c.w;
        assert!(
            r[0].abs() < tol && r[1].abs() < tol,
            "residuals {r:?} for {c:?}"
        );
        // The profile ends at the fairlead.
        let p = c.position(c.length);
        assert!(
            (p[0] - c.xf).abs() < tol && (p[1] - c.zf).abs() < tol,
            "profile end {p:?} for {c:?}"
        );
        let t = c.fairlead_tension();
        assert!((t * t - (c.hf * c.hf + c.vf * c.vf)).abs() <= 1e-12 * t * t);
        assert!((c.tension(c.length) - t).abs() <= 1e-12 * t);
    }

    #[test]
    fn mooring_line_with_grounded_part() {
        // The catenary example: L = 250 m, anchor 220 m away and 90 m below.
        let c = catenary(220.0, 90.0, 250.0, EA, w(), true).unwrap();
        check_solution(&c, 1e-9);
        assert!(c.grounded_length > 0.0 && c.grounded_length < 250.0);
        assert_eq!(c.va, 0.0);
        assert_eq!(c.ha, c.hf);
        // Vertical fairlead force = weight of the hanging part.
        assert!((c.vf - c.w * (c.length - c.grounded_length)).abs() < 1e-9 * c.vf);
        // Touchdown: the grounded part stretched by HF.
        assert!((c.touchdown - c.grounded_length * (1.0 + c.hf / EA)).abs() < 1e-9);
        // The profile is flat up to touchdown and leaves the seabed tangentially.
        let p = c.position(c.grounded_length);
        assert!(p[1].abs() < 1e-12 && (p[0] - c.touchdown).abs() < 1e-9);
        let q = c.position(c.grounded_length + 1e-3);
        assert!(q[1] > 0.0 && q[1] < 1e-6);
        // The profile has the unstretched-plus-stretch arclength: sum of chords over a
        // fine subdivision equals int (1 + T/EA) ds.
        let n = 20000;
        let (mut arc, mut stretched) = (0.0, 0.0);
        for k in 0..n {
            let (s0, s1) = (
                250.0 * k as f64 / n as f64,
                250.0 * (k + 1) as f64 / n as f64,
            );
            let (a, b) = (c.position(s0), c.position(s1));
            arc += (b[0] - a[0]).hypot(b[1] - a[1]);
            stretched += (s1 - s0) * (1.0 + c.tension(0.5 * (s0 + s1)) / EA);
        }
        assert!((arc - stretched).abs() < 1e-6, "{arc} vs {stretched}");
    }

    #[test]
    fn long_grounded_portion() {
        // 330 m of line over a 300 m span, 50 m deep: most of it on the seabed.
        let c = catenary(300.0, 50.0, 330.0, EA, w(), true).unwrap();
        check_solution(&c, 1e-9);
        assert!(c.grounded_length > 200.0, "{c:?}");
        // Closed-form check of the inextensible limit of the hanging part: with
        // a = HF/w, the hanging part spans zf = a (cosh(x_s/a) - 1).
        let a = c.hf / c.w;
        let hang = c.length - c.grounded_length;
        // Suspended length from the touchdown: s = a sinh(x/a) (inextensible part).
        let xs = a * (hang / a).asinh();
        let z_inext = a * ((xs / a).cosh() - 1.0);
        assert!((z_inext - 50.0).abs() < 0.05, "{z_inext}");
    }

    #[test]
    fn fully_suspended_symmetric() {
        // Both ends at the same height, no seabed: VF = VA in magnitude = wL/2.
        let c = catenary(80.0, 0.0, 100.0, EA, w(), false).unwrap();
        check_solution(&c, 1e-9);
        assert!((c.vf - 0.5 * c.w * c.length).abs() < 1e-9 * c.vf);
        assert!((c.va + 0.5 * c.w * c.length).abs() < 1e-9 * c.vf);
        // The lowest point is at mid-length, the profile is symmetric.
        let mid = c.position(50.0);
        assert!((mid[0] - 40.0).abs() < 1e-9);
        for s in [10.0, 25.0, 40.0] {
            let (p, q) = (c.position(s), c.position(100.0 - s));
            assert!((p[0] + q[0] - 80.0).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9);
        }
        // Sag against the inextensible closed form: L = 2 a sinh(X/(2a)).
        let a = c.hf / c.w;
        let l_inext = 2.0 * a * (40.0 / a).sinh();
        assert!((l_inext - 100.0).abs() < 0.01, "{l_inext}");
    }

    #[test]
    fn inextensible_limit() {
        // Parametrise an inextensible catenary z = a (cosh((x - x0)/a) - cosh(x0/a)):
        // choose a and x0, derive span, rise and length, and recover HF = w a.
        let w = w();
        for &(a, x0, span) in &[
            (50.0f64, -20.0f64, 100.0f64),
            (200.0, 30.0, 150.0),
            (10.0, 5.0, 40.0),
        ] {
            let zf = a * (((span - x0) / a).cosh() - (-x0 / a).cosh());
            let len = a * (((span - x0) / a).sinh() - (-x0 / a).sinh());
            let c = catenary(span, zf, len, 1e15, w, false).unwrap();
            check_solution(&c, 1e-7);
            assert!((c.hf - w * a).abs() < 1e-6 * w * a, "{} vs {}", c.hf, w * a);
            // VF = w a sinh((span - x0)/a).
            let vf = w * a * ((span - x0) / a).sinh();
            assert!((c.vf - vf).abs() < 1e-6 * vf.abs().max(w * a));
            // And EA = infinity itself works for a slack line.
            let c2 = catenary(span, zf, len, f64::INFINITY, w, false).unwrap();
            assert!((c2.hf - w * a).abs() < 1e-9 * w * a);
        }
    }

    #[test]
    fn taut_line_stretches() {
        // Ends 1 % farther apart than the unstretched length.
        let l = 100.0;
        let c = catenary(101.0 * 0.8, 101.0 * 0.6, l, EA, w(), true).unwrap();
        check_solution(&c, 1e-9);
        assert_eq!(c.grounded_length, 0.0);
        assert!(c.va > 0.0);
        // Tension about EA * 1 %.
        let t = c.fairlead_tension();
        assert!((t / (0.01 * EA) - 1.0).abs() < 0.02, "{t}");
    }

    #[test]
    fn nearly_vertical_and_vertical_lines() {
        let w = w();
        // Exactly vertical, taut.
        let c = catenary(0.0, 100.5, 100.0, EA, w, false).unwrap();
        assert_eq!(c.hf, 0.0);
        let p = c.position(100.0);
        assert!(p[0] == 0.0 && (p[1] - 100.5).abs() < 1e-9);
        assert!((c.vf - c.va - w * 100.0).abs() < 1e-9 * c.vf);
        // Nearly vertical: continuous with it.
        let c2 = catenary(1e-6, 100.5, 100.0, EA, w, false).unwrap();
        check_solution(&c2, 1e-9);
        assert!((c2.vf - c.vf).abs() < 1e-6 * c.vf, "{} {}", c2.vf, c.vf);
        // Vertical above a seabed anchor with surplus line: slack on the seabed, the
        // hanging part weighs VF.
        let c3 = catenary(0.0, 60.0, 100.0, EA, w, true).unwrap();
        assert!(c3.is_slack());
        assert!((c3.position(100.0)[1] - 60.0).abs() < 1e-9);
        assert!(c3.grounded_length > 40.0 && c3.grounded_length < 40.01);
        // Small span over the seabed: slack until the grounded part is straight.
        let c4 = catenary(10.0, 60.0, 100.0, EA, w, true).unwrap();
        assert!(c4.is_slack());
        let p = c4.position(100.0);
        assert!((p[0] - 10.0).abs() < 1e-9 && (p[1] - 60.0).abs() < 1e-9);
        // And with the grounded part just taut it is a normal catenary.
        let c5 = catenary(45.0, 60.0, 100.0, EA, w, true).unwrap();
        assert!(!c5.is_slack() && c5.hf > 0.0);
        check_solution(&c5, 1e-9);
        // Folded vertical line (no seabed): ends at the same point.
        let c6 = catenary(0.0, 0.0, 100.0, EA, w, false).unwrap();
        let lowest = c6.position(50.0);
        assert!(lowest[1] < -49.0);
        assert!(c6.position(100.0)[1].abs() < 1e-9);
    }

    #[test]
    fn sweep_converges_everywhere() {
        // A grid of spans and rises, with and without seabed, stiff and soft lines.
        let w = w();
        let l = 100.0;
        let mut max_it = 0;
        for &ea in &[1e4, 1e6, EA, 1e12] {
            for i in 0..=24 {
                for k in 0..=24 {
                    let xf = 1.3 * l * i as f64 / 24.0;
                    let zf = 1.3 * l * k as f64 / 24.0;
                    for seabed in [false, true] {
                        match catenary(xf, zf, l, ea, w, seabed) {
                            Ok(c) => {
                                assert!(c.iterations < 50, "{c:?}");
                                max_it = max_it.max(c.iterations);
                                let tol = 1e-8 * l;
                                if c.hf > 0.0 {
                                    check_solution(&c, tol);
                                } else {
                                    let p = c.position(l);
                                    assert!(
                                        (p[0] - xf).abs() < tol && (p[1] - zf).abs() < tol,
                                        "{p:?} for {c:?}"
                                    );
                                }
                            }
                            Err(e) => {
                                // Only "too far apart" may fail.
                                assert!(
                                    e.contains("too far apart") && xf.hypot(zf) > l,
                                    "xf {xf} zf {zf} ea {ea} seabed {seabed}: {e}"
                                );
                            }
                        }
                    }
                }
            }
        }
        eprintln!("most Newton iterations over the sweep: {max_it}");
    }

    #[test]
    fn errors_are_reported() {
        assert!(catenary(10.0, 10.0, 100.0, EA, -1.0, false)
            .unwrap_err()
            .contains("wet weight"));
        assert!(catenary(10.0, 10.0, 100.0, EA, 0.0, false).is_err());
        assert!(catenary(-1.0, 10.0, 100.0, EA, 1.0, false).is_err());
        assert!(catenary(10.0, 10.0, 0.0, EA, 1.0, false).is_err());
        assert!(catenary(10.0, -5.0, 100.0, EA, 1.0, true).is_err());
        assert!(catenary(200.0, 0.0, 100.0, f64::INFINITY, 1.0, false)
            .unwrap_err()
            .contains("inextensible"));
        assert!(catenary(300.0, 0.0, 100.0, 1e3, 1.0, false)
            .unwrap_err()
            .contains("too far apart"));
    }

    #[test]
    fn positions_follow_the_catenary() {
        let w = w();
        let a = [-220.0, 0.0, -100.0];
        let b = [0.0, 0.0, -10.0];
        let pts = catenary_positions(a, b, 250.0, 50, EA, w, -100.0);
        assert_eq!(pts.len(), 51);
        assert_eq!(pts[0], a);
        assert_eq!(pts[50], b);
        // Reversed ends give the same points in reverse order.
        let rev = catenary_positions(b, a, 250.0, 50, EA, w, -100.0);
        for k in 0..=50 {
            for j in 0..3 {
                assert!((pts[k][j] - rev[50 - k][j]).abs() < 1e-9);
            }
        }
        // Grounded nodes lie on the seabed; chords are no longer than L/n stretched.
        let c = catenary(220.0, 90.0, 250.0, EA, w, true).unwrap();
        let tmax = c.fairlead_tension();
        for k in 0..50 {
            let d: f64 = (0..3)
                .map(|j| (pts[k + 1][j] - pts[k][j]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(d <= 5.0 * (1.0 + tmax / EA) + 1e-9);
        }
        assert!(pts[5][2] == -100.0);
        // A rotated plane: the line stays in the vertical plane through its ends.
        let b2 = [0.0, 100.0, -10.0];
        let a2 = [0.0, -120.0, -100.0];
        let p2 = catenary_positions(a2, b2, 250.0, 25, EA, w, -100.0);
        assert!(p2.iter().all(|p| p[0].abs() < 1e-12));
        // Buoyant: straight.
        let s = catenary_positions(a, b, 250.0, 10, EA, -5.0, -100.0);
        assert_eq!(s, straight_positions(a, b, 10));
        // Slack on the seabed: no zero-length element.
        let p3 = catenary_positions(
            [0.0, 0.0, -100.0],
            [0.0, 0.0, -40.0],
            100.0,
            20,
            EA,
            w,
            -100.0,
        );
        for k in 0..20 {
            let d: f64 = (0..3)
                .map(|j| (p3[k + 1][j] - p3[k][j]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(d > 4.0, "element {k} has length {d}");
        }
    }
}
