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
//!
//! The solver in the scaled unknowns is in `scaled.rs`, the node positions along a
//! solved line (the initial shape of a cable) in `positions.rs`.

mod positions;
mod scaled;

pub use positions::{catenary_positions, straight_positions, SEABED_TOLERANCE};
use scaled::{asinh_diff, solve_scaled};
use std::f64::consts::PI;

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

/// Wet weight per unit length of a round line of diameter `d` and mass per length
/// `mbar` in water of density `rho` under gravity `g`, N/m (a convenience for tests and
/// callers without a `LineType` at hand).
pub fn wet_weight(mbar: f64, d: f64, rho: f64, g: f64) -> f64 {
    (mbar - rho * PI * d * d / 4.0) * g
}
