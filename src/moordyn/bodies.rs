//! A MoorDyn file's BODIES and FAILURE rows checked and mapped to cablesim's
//! `[[bodies]]` and failure keys (docs/src/moordyn.md, "Bodies" and "Failures").
//!
//! MoorDyn's body (`Body.cpp`, v2): a mass `M` at the centre of gravity `rCG` (body
//! coordinates from the reference point), a diagonal inertia `I` about it, a volume `V`
//! whose buoyancy `rho V g` acts at the centre of gravity too, added mass
//! `Ca rho V` per body axis at the reference point (translations only), quadratic drag
//! `1/2 rho R diag(CdA) R^T u |u|` on the relative velocity at the reference point and
//! `-1/2 rho R diag(CdA_rot) R^T w |w|` on the rotation, and the points attached to it
//! (their mass, buoyancy and drag lumped into it). The attitude is
//! `R = Rx(r0) Ry(p0) Rz(y0)` (`Euler2Quat`), which cablesim writes as its own roll,
//! pitch and yaw (`R = Rz Ry Rx`).

use super::err_at;
use super::parse::{BodyRow, FailureRow};
use super::Warning;
use crate::error::Error;
use nalgebra::{Matrix3, Rotation3, Vector3};
use std::path::Path;

/// What a body is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum BodyKind {
    /// Moves by its own dynamics.
    Free,
    /// Held at its pose.
    Fixed,
    /// Driven by the caller (a vessel): held at its pose unless given a motion.
    Coupled,
    /// Translation driven, rotation free.
    Pinned,
}

/// A body row read and checked.
#[derive(Clone, Debug)]
pub(super) struct MdBody {
    pub row: BodyRow,
    pub kind: BodyKind,
    pub cg: [f64; 3],
    pub inertia: [f64; 3],
    /// Translational then rotational drag areas.
    pub cda: [f64; 6],
    pub ca: [f64; 3],
    /// MoorDyn's attitude.
    pub rot: Matrix3<f64>,
    /// The same attitude as cablesim's roll, pitch, yaw, degrees.
    pub angles: [f64; 3],
}

impl MdBody {
    /// The cablesim name.
    pub fn name(&self) -> String {
        format!("body{}", self.row.id)
    }

    /// Where a point at body coordinates `p` is at the start, m.
    pub fn place(&self, p: [f64; 3]) -> [f64; 3] {
        let x = Vector3::new(self.row.r6[0], self.row.r6[1], self.row.r6[2])
            + self.rot * Vector3::new(p[0], p[1], p[2]);
        [x.x, x.y, x.z]
    }

    /// The point at body coordinates `p` in the axes of a body written with zero
    /// angles (a prescribed body, which has no roll or pitch of its own).
    pub fn turned(&self, p: [f64; 3]) -> [f64; 3] {
        let x = self.rot * Vector3::new(p[0], p[1], p[2]);
        [x.x, x.y, x.z]
    }
}

/// `a|b|c` as numbers; `Err` says what is wrong with the cell.
fn cell(s: &str) -> Result<Vec<f64>, String> {
    s.split('|')
        .map(|x| match x.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(format!("\"{s}\": \"{x}\" is not a finite number")),
        })
        .collect()
}

/// Reads and checks the BODIES rows.
pub(super) fn read_bodies(
    p: &Path,
    rows: &[BodyRow],
    warn: &mut Vec<Warning>,
) -> Result<Vec<MdBody>, Error> {
    let mut out = Vec::with_capacity(rows.len());
    for (i, r) in rows.iter().enumerate() {
        let l = r.line;
        let what = |c: &str| format!("body {} {c}", r.id);
        if r.id != i + 1 {
            return Err(err_at(
                p,
                l,
                "body ID",
                format!(
                    "body IDs must run 1, 2, 3, ...: expected {}, got {}",
                    i + 1,
                    r.id
                ),
            ));
        }
        let (w, _) = super::tables::word_and_number(&r.attachment);
        let kind = match w.as_str() {
            "FREE" => BodyKind::Free,
            "FIXED" | "FIX" | "ANCHOR" => BodyKind::Fixed,
            "VESSEL" | "VES" | "COUPLED" | "CPLD" => BodyKind::Coupled,
            "VESSELPINNED" | "VESPIN" | "CPLDPIN" | "COUPLEDPINNED" => BodyKind::Pinned,
            _ => {
                return Err(err_at(
                    p,
                    l,
                    what("Attachment"),
                    format!(
                        "unknown attachment \"{}\" (Free, Fixed, Coupled/Vessel, CoupledPinned)",
                        r.attachment
                    ),
                ))
            }
        };
        let bad = |c: &str, m: String| err_at(p, l, what(c), m);
        let cg = match cell(&r.cg).map_err(|m| bad("CG", m))?[..] {
            [z] => [0.0, 0.0, z],
            [x, y, z] => [x, y, z],
            _ => {
                return Err(bad(
                    "CG",
                    format!("\"{}\" must hold 1 value (z) or 3 (x|y|z)", r.cg),
                ))
            }
        };
        let inertia = match cell(&r.inertia).map_err(|m| bad("I", m))?[..] {
            [a] => [a; 3],
            [a, b, c] => [a, b, c],
            _ => {
                return Err(bad(
                    "I",
                    format!("\"{}\" must hold 1 value or 3 (Ixx|Iyy|Izz)", r.inertia),
                ))
            }
        };
        let cda = match cell(&r.cda).map_err(|m| bad("CdA", m))?[..] {
            [a] => [a; 6],
            [t, r] => [t, t, t, r, r, r],
            [a, b, c] => [a, b, c, a, b, c],
            [a, b, c, d, e, f] => [a, b, c, d, e, f],
            _ => {
                return Err(bad(
                    "CdA",
                    format!("\"{}\" must hold 1, 2, 3 or 6 values", r.cda),
                ))
            }
        };
        let n_cda = r.cda.split('|').count();
        if n_cda == 3 || n_cda == 6 {
            warn.push(Warning {
                line: l,
                message: format!(
                    "body {} CdA \"{}\": every value is used (MoorDyn v2.7's reader skips \
                     the first of 3 or 6 values, leaving no surge drag)",
                    r.id, r.cda
                ),
            });
        }
        let ca = match cell(&r.ca).map_err(|m| bad("Ca", m))?[..] {
            [a] => [a; 3],
            [a, b, c] => [a, b, c],
            _ => {
                return Err(bad(
                    "Ca",
                    format!("\"{}\" must hold 1 value or 3 (x|y|z)", r.ca),
                ))
            }
        };
        if matches!(kind, BodyKind::Free | BodyKind::Pinned) {
            for (c, x) in [("Mass", r.mass), ("Volume", r.volume)] {
                if x < 0.0 {
                    return Err(bad(c, format!("must not be negative, got {x}")));
                }
            }
            if kind == BodyKind::Free && r.mass <= 0.0 {
                return Err(bad(
                    "Mass",
                    format!(
                        "a free body needs a positive mass, got {} (cablesim lumps the \
                         points on it into it, but not into its own mass)",
                        r.mass
                    ),
                ));
            }
            for (k, x) in inertia.iter().enumerate() {
                if *x <= 0.0 {
                    return Err(bad(
                        "I",
                        format!(
                            "a {} body needs a positive moment of inertia about each axis, \
                             got {x} about {}",
                            if kind == BodyKind::Free {
                                "free"
                            } else {
                                "pinned"
                            },
                            ["x", "y", "z"][k]
                        ),
                    ));
                }
            }
            for (c, v) in [("CdA", &cda[..]), ("Ca", &ca[..])] {
                if let Some(x) = v.iter().find(|x| **x < 0.0) {
                    return Err(bad(c, format!("must not be negative, got {x}")));
                }
            }
        }
        let [_, _, _, r0, p0, y0] = r.r6.map(f64::to_radians);
        let rot = *(Rotation3::from_axis_angle(&Vector3::x_axis(), r0)
            * Rotation3::from_axis_angle(&Vector3::y_axis(), p0)
            * Rotation3::from_axis_angle(&Vector3::z_axis(), y0))
        .matrix();
        let (a, b, c) = Rotation3::from_matrix_unchecked(rot).euler_angles();
        out.push(MdBody {
            row: r.clone(),
            kind,
            cg,
            inertia,
            cda,
            ca,
            rot,
            angles: [a, b, c].map(|x| {
                let d = x.to_degrees();
                if d.abs() < 1e-12 {
                    0.0
                } else {
                    d
                }
            }),
        });
    }
    Ok(out)
}

/// A failure row read and checked: the point, the lines listed and the triggers.
#[derive(Clone, Debug)]
pub(super) struct MdFailure {
    pub line: usize,
    pub id: String,
    /// Point ID (1-based).
    pub point: usize,
    /// Line IDs (1-based), in the order written.
    pub lines: Vec<usize>,
    pub time: Option<f64>,
    pub tension: Option<f64>,
}

/// Reads and checks the FAILURE rows against the points and the lines' ends
/// (`ends[k]`: line k+1's points).
pub(super) fn read_failures(
    p: &Path,
    rows: &[FailureRow],
    n_points: usize,
    ends: &[(usize, usize)],
    warn: &mut Vec<Warning>,
) -> Result<Vec<MdFailure>, Error> {
    let mut out: Vec<MdFailure> = Vec::with_capacity(rows.len());
    for r in rows {
        let l = r.line;
        let what = |c: &str| format!("failure {} {c}", r.id);
        let (w, num) = super::tables::word_and_number(&r.point);
        if w == "R" || w == "ROD" {
            return Err(err_at(
                p,
                l,
                what("Point"),
                format!(
                    "\"{}\": failures at rod ends are not supported (no rods)",
                    r.point
                ),
            ));
        }
        let point = match (w.as_str(), num.parse::<usize>()) {
            ("" | "C" | "CON" | "P" | "POINT", Ok(n)) if n >= 1 && n <= n_points => n,
            ("" | "C" | "CON" | "P" | "POINT", Ok(n)) => {
                return Err(err_at(
                    p,
                    l,
                    what("Point"),
                    format!("point {n} does not exist (the file has {n_points} points)"),
                ))
            }
            _ => {
                return Err(err_at(
                    p,
                    l,
                    what("Point"),
                    format!("\"{}\" is not a point ID", r.point),
                ))
            }
        };
        let mut lines = Vec::new();
        for x in r.lines.split(',').filter(|x| !x.is_empty()) {
            let id = match x.parse::<usize>() {
                Ok(id) if id >= 1 && id <= ends.len() => id,
                _ => {
                    return Err(err_at(
                        p,
                        l,
                        what("Line(s)"),
                        format!(
                            "\"{x}\" is not a line of the file (lines 1 to {})",
                            ends.len()
                        ),
                    ))
                }
            };
            let (a, b) = ends[id - 1];
            if a != point && b != point {
                return Err(err_at(
                    p,
                    l,
                    what("Line(s)"),
                    format!("line {id} has no end at point {point} (its ends: points {a} and {b})"),
                ));
            }
            if a == point && b == point {
                return Err(err_at(
                    p,
                    l,
                    what("Line(s)"),
                    format!("line {id} has both ends at point {point}"),
                ));
            }
            if !lines.contains(&id) {
                lines.push(id);
            }
        }
        if lines.is_empty() {
            return Err(err_at(p, l, what("Line(s)"), "names no line"));
        }
        for (c, x) in [("FailTime", r.time), ("FailTen", r.tension)] {
            if x < 0.0 {
                return Err(err_at(
                    p,
                    l,
                    what(c),
                    format!("must not be negative, got {x} (0 means no such trigger)"),
                ));
            }
        }
        let time = (r.time > 0.0).then_some(r.time);
        let tension = (r.tension > 0.0).then_some(r.tension);
        if time.is_none() && tension.is_none() {
            return Err(err_at(
                p,
                l,
                what("FailTime"),
                "neither FailTime nor FailTen is set (both 0): the failure could never fire",
            ));
        }
        let mut sorted = lines.clone();
        sorted.sort_unstable();
        if let Some(prev) = out.iter().find(|f| {
            let mut s = f.lines.clone();
            s.sort_unstable();
            f.point == point && s == sorted
        }) {
            warn.push(Warning {
                line: l,
                message: format!(
                    "failure {} repeats failure {} (point {point}, the same lines): ignored, \
                     as MoorDyn ignores it",
                    r.id, prev.id
                ),
            });
            continue;
        }
        for f in out.iter().filter(|f| f.point == point) {
            if let Some(id) = f.lines.iter().find(|x| lines.contains(x)) {
                return Err(err_at(
                    p,
                    l,
                    what("Line(s)"),
                    format!(
                        "line {id} at point {point} is also in failure {} (line {}): each \
                         line end can fail once",
                        f.id, f.line
                    ),
                ));
            }
        }
        out.push(MdFailure {
            line: l,
            id: r.id.clone(),
            point,
            lines,
            time,
            tension,
        });
    }
    Ok(out)
}

/// `, fail_time = t, fail_tension = T` for a failure's triggers.
pub(super) fn fail_keys(f: &MdFailure) -> String {
    let mut s = String::new();
    if let Some(t) = f.time {
        s += &format!(", fail_time = {t:?}");
    }
    if let Some(t) = f.tension {
        s += &format!(", fail_tension = {t:?}");
    }
    s
}
