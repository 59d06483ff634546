//! Rows of a MoorDyn file's tables checked for what cablesim can run: what a point
//! is, which point a line end names, and a line type's stiffness and damping.

use super::err_at;
use super::parse::{LineRow, LineTypeRow, PointRow, Version};
use super::Warning;
use crate::error::Error;
use std::path::Path;

/// What a point is in MoorDyn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum PointKind {
    Fixed,
    Coupled,
    Free,
}

/// Splits `Body12` into (`BODY`, `12`).
pub(super) fn word_and_number(s: &str) -> (String, String) {
    let letters: String = s.chars().take_while(|c| c.is_ascii_alphabetic()).collect();
    let rest = &s[letters.len()..];
    (letters.to_uppercase(), rest.to_string())
}

pub(super) fn point_kind(p: &Path, r: &PointRow) -> Result<PointKind, Error> {
    let (w, _) = word_and_number(&r.attachment);
    Ok(match w.as_str() {
        "FIXED" | "FIX" | "ANCHOR" => PointKind::Fixed,
        "VESSEL" | "VES" | "FAIRLEAD" | "COUPLED" | "CPLD" => PointKind::Coupled,
        "POINT" | "CONNECT" | "CON" | "FREE" => PointKind::Free,
        "BODY" => {
            return Err(err_at(
                p,
                r.line,
                format!("point {} attachment", r.id),
                format!(
                    "\"{}\": points on bodies are not supported (cablesim has no MoorDyn \
                     bodies); make it Fixed or Coupled",
                    r.attachment
                ),
            ))
        }
        _ => {
            return Err(err_at(
                p,
                r.line,
                format!("point {} attachment", r.id),
                format!(
                    "unknown attachment \"{}\" (Fixed, Vessel/Coupled, Free/Connect)",
                    r.attachment
                ),
            ))
        }
    })
}

/// The point ID a line end names (`3`, `C3`, `P3`, `Con3`, `Point3`).
pub(super) fn attach_point(
    p: &Path,
    l: &LineRow,
    end: &str,
    s: &str,
    n_points: usize,
) -> Result<usize, Error> {
    let (w, num) = word_and_number(s);
    let what = format!("line {} {end}", l.id);
    if w == "R" || w == "ROD" {
        return Err(err_at(
            p,
            l.line,
            what,
            format!("\"{s}\": lines on rod ends are not supported (cablesim has no rods)"),
        ));
    }
    if !["", "C", "CON", "P", "POINT"].contains(&w.as_str()) {
        return Err(err_at(
            p,
            l.line,
            what,
            format!("\"{s}\" is not a point ID"),
        ));
    }
    match num.parse::<usize>() {
        Ok(id) if id >= 1 && id <= n_points => Ok(id),
        _ => Err(err_at(
            p,
            l.line,
            what,
            format!("\"{s}\": there is no point with that ID ({n_points} points)"),
        )),
    }
}

/// A line type checked for what cablesim can run: (EA, BA as written). Its columns are
/// named as the file's `version` names them.
pub(super) fn check_type(
    p: &Path,
    t: &LineTypeRow,
    version: Version,
    warn: &mut Vec<Warning>,
) -> Result<(f64, f64), Error> {
    let l = t.line;
    let name = |c: &str| format!("line type \"{}\" {c}", t.name);
    let pos = |c: &str, x: f64| {
        if x > 0.0 {
            Ok(x)
        } else {
            Err(err_at(p, l, name(c), format!("must be positive, got {x}")))
        }
    };
    pos("Diam", t.diam)?;
    pos("Mass/m", t.mass)?;
    let ea = match t.ea.parse::<f64>() {
        Ok(x) if x.is_finite() => pos("EA", x)?,
        _ => {
            return Err(err_at(
                p,
                l,
                name("EA"),
                format!(
                    "\"{}\": nonlinear, viscoelastic or Syrope stiffness is not supported \
                     (cablesim's lines are linear elastic: give one EA in N)",
                    t.ea
                ),
            ))
        }
    };
    let ba = match t.ba.parse::<f64>() {
        Ok(x) if x.is_finite() => x,
        _ => {
            return Err(err_at(
                p,
                l,
                name("BA/-zeta"),
                format!(
                    "\"{}\": static/dynamic or tabulated damping is not supported (give one \
                     BA in N s, or a negative damping ratio)",
                    t.ba
                ),
            ))
        }
    };
    let [cd, ca, cdax, caax] = match version {
        Version::V1 => ["Cdn", "Can", "Cdt", "Cat"],
        Version::V2 => ["Cd", "Ca", "CdAx", "CaAx"],
    };
    for (c, x) in [(cd, t.cd), (ca, t.ca), (cdax, t.cdax), (caax, t.caax)] {
        if x < 0.0 {
            return Err(err_at(
                p,
                l,
                name(c),
                format!("must not be negative, got {x}"),
            ));
        }
    }
    if t.cl != 0.0 {
        warn.push(Warning {
            line: l,
            message: format!(
                "line type \"{}\": VIV lift coefficient Cl = {} is ignored (no vortex-induced \
                 vibration model)",
                t.name, t.cl
            ),
        });
    }
    Ok((ea, ba))
}
