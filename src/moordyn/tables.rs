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
    /// On body N (1-based): its position is in the body's coordinates.
    Body(usize),
}

/// Splits `Body12` into (`BODY`, `12`).
pub(super) fn word_and_number(s: &str) -> (String, String) {
    let letters: String = s.chars().take_while(|c| c.is_ascii_alphabetic()).collect();
    let rest = &s[letters.len()..];
    (letters.to_uppercase(), rest.to_string())
}

pub(super) fn point_kind(p: &Path, r: &PointRow, n_bodies: usize) -> Result<PointKind, Error> {
    let (w, num) = word_and_number(&r.attachment);
    Ok(match w.as_str() {
        "FIXED" | "FIX" | "ANCHOR" => PointKind::Fixed,
        "VESSEL" | "VES" | "FAIRLEAD" | "COUPLED" | "CPLD" => PointKind::Coupled,
        "POINT" | "CONNECT" | "CON" | "FREE" => PointKind::Free,
        "BODY" => match num.parse::<usize>() {
            Ok(b) if b >= 1 && b <= n_bodies => PointKind::Body(b),
            _ => {
                return Err(err_at(
                    p,
                    r.line,
                    format!("point {} attachment", r.id),
                    format!(
                        "\"{}\" names no body of the BODIES section ({} bodies)",
                        r.attachment, n_bodies
                    ),
                ))
            }
        },
        _ => {
            return Err(err_at(
                p,
                r.line,
                format!("point {} attachment", r.id),
                format!(
                    "unknown attachment \"{}\" (Fixed, Vessel/Coupled, Free/Connect, BodyN)",
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

/// A strain-tension curve read from a MoorDyn curve file (EA given as a file name).
#[derive(Clone, Debug)]
pub(super) struct EaCurve {
    /// Rows `(strain, tension)`.
    pub rows: Vec<[f64; 2]>,
    /// The file, as the line type names it.
    pub file: String,
    /// MoorDyn's stiffness for a damping ratio: the last row's secant, N.
    pub secant: f64,
}

/// Reads a MoorDyn curve file (path relative to the input file's folder): three header
/// lines, then a row per line of at least two numbers, strain and tension. Errors name
/// the curve file and its line.
fn read_ea_curve(p: &Path, line: usize, what: &str, entry: &str) -> Result<EaCurve, Error> {
    let file = p.parent().unwrap_or(Path::new(".")).join(entry);
    let text = crate::input::read_text(&file).map_err(|e| {
        err_at(
            p,
            line,
            what,
            format!(
                "\"{entry}\" is neither a number nor a readable curve file ({}: {e})",
                file.display()
            ),
        )
    })?;
    let mut rows = Vec::new();
    for (i, l) in text.lines().enumerate().skip(3) {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.is_empty() {
            continue;
        }
        let num = |k: usize| f.get(k).and_then(|x| x.parse::<f64>().ok());
        match (num(0), num(1)) {
            (Some(x), Some(y)) => rows.push([x, y]),
            _ => {
                return Err(err_at(
                    &file,
                    i + 1,
                    "curve row",
                    format!(
                        "needs two numbers, strain and tension, got \"{}\"",
                        l.trim()
                    ),
                ))
            }
        }
    }
    crate::physics::axial::check_curve(&rows).map_err(|m| {
        err_at(
            &file,
            0,
            "strain-tension curve (rows after the 3 header lines)",
            m,
        )
    })?;
    let last = rows[rows.len() - 1];
    Ok(EaCurve {
        secant: last[1] / last[0],
        rows,
        file: entry.to_string(),
    })
}

/// The viscoelastic cells of a line type: EA `EA_s|EA_d` or `EA_s|EA_Dc|EA_D_Lm`,
/// BA `BA_s|BA_d` (MoorDyn's `ELASTIC_VISCO_CTE` and `ELASTIC_VISCO_MEAN`).
#[derive(Clone, Copy, Debug)]
pub(super) struct MdVisco {
    /// `EA_d`, or `EA_Dc` with a slope, N.
    pub ea_dynamic: f64,
    /// `EA_D_Lm` (0 for `EA_s|EA_d`).
    pub slope: f64,
    /// `BA_d`, N s (0 when the BA cell has one value, as MoorDyn takes it).
    pub ba_dynamic: f64,
}

/// Reads the `|` cells of a line type's EA and BA columns (`None` for a plain EA):
/// numbers only, two or three in EA, at most as many in BA as in EA, two at most,
/// `EA_s` positive, the dynamic stiffness above it, the slope and `BA_d` at least
/// zero. Returns `EA_s`, `BA_s` as written and the rest.
fn visco_cells(
    p: &Path,
    t: &LineTypeRow,
    name: &dyn Fn(&str) -> String,
) -> Result<Option<(f64, f64, MdVisco)>, Error> {
    let l = t.line;
    let ea: Vec<&str> = t.ea.split('|').collect();
    let ba: Vec<&str> = t.ba.split('|').collect();
    if ea.len() == 1 {
        if ba.len() > 1 {
            return Err(err_at(
                p,
                l,
                name("BA/-zeta"),
                format!(
                    "\"{}\": a BA cell cannot have more (|-separated) values than its EA cell \
                     \"{}\"",
                    t.ba, t.ea
                ),
            ));
        }
        return Ok(None);
    }
    let num = |col: &str, what: &str, s: &str| {
        s.trim().parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| {
            err_at(
                p,
                l,
                name(col),
                format!("{what} of \"{s}\" must be a finite number (a curve file is not supported with the viscoelastic model)"),
            )
        })
    };
    if ea.len() > 3 {
        return Err(err_at(
            p,
            l,
            name("EA"),
            format!(
                "\"{}\": at most 3 (|-separated) values, EA_s|EA_d or EA_s|EA_Dc|EA_D_Lm",
                t.ea
            ),
        ));
    }
    if ba.len() > 2 || ba.len() > ea.len() {
        return Err(err_at(
            p,
            l,
            name("BA/-zeta"),
            format!("\"{}\": at most BA_s|BA_d", t.ba),
        ));
    }
    let ks = num("EA", "EA_s", ea[0])?;
    if !(ks > 0.0) {
        return Err(err_at(
            p,
            l,
            name("EA"),
            format!("EA_s must be positive, got {ks}"),
        ));
    }
    let kd = num("EA", if ea.len() == 2 { "EA_d" } else { "EA_Dc" }, ea[1])?;
    if !(kd > ks) {
        return Err(err_at(
            p,
            l,
            name("EA"),
            format!(
                "the dynamic stiffness {kd} must exceed the static EA_s = {ks} (\"{}\")",
                t.ea
            ),
        ));
    }
    let slope = if ea.len() == 3 {
        num("EA", "EA_D_Lm", ea[2])?
    } else {
        0.0
    };
    if slope < 0.0 {
        return Err(err_at(
            p,
            l,
            name("EA"),
            format!("EA_D_Lm must not be negative, got {slope}"),
        ));
    }
    let bs = num("BA/-zeta", "BA_s", ba[0])?;
    let bd = if ba.len() == 2 {
        num("BA/-zeta", "BA_d", ba[1])?
    } else {
        0.0
    };
    if bd < 0.0 {
        return Err(err_at(
            p,
            l,
            name("BA/-zeta"),
            format!("BA_d must not be negative (MoorDyn takes no ratio for it), got {bd}"),
        ));
    }
    if bs == 0.0 {
        return Err(err_at(
            p,
            l,
            name("BA/-zeta"),
            format!(
                "\"{}\": a viscoelastic line needs a static damping BA_s (N s, or a negative \
                 damping ratio), got 0",
                t.ba
            ),
        ));
    }
    Ok(Some((
        ks,
        bs,
        MdVisco {
            ea_dynamic: kd,
            slope,
            ba_dynamic: bd,
        },
    )))
}

/// A line type checked for what cablesim can run: (EA, BA as written, the
/// strain-tension curve when EA names a curve file; EA is then the curve's largest
/// slope; the viscoelastic cells, with EA the static `EA_s` and BA `BA_s`). Its
/// columns are named as the file's `version` names them.
pub(super) fn check_type(
    p: &Path,
    t: &LineTypeRow,
    version: Version,
    warn: &mut Vec<Warning>,
) -> Result<(f64, f64, Option<EaCurve>, Option<MdVisco>), Error> {
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
    let visco = if t.ea.starts_with("SYROPE:") {
        None
    } else {
        visco_cells(p, t, &name)?
    };
    let (ea, curve) = match t.ea.parse::<f64>() {
        _ if visco.is_some() => (visco.map_or(0.0, |v| v.0), None),
        Ok(x) if x.is_finite() => (pos("EA", x)?, None),
        Ok(_) => {
            return Err(err_at(
                p,
                l,
                name("EA"),
                format!("must be finite, got {}", t.ea),
            ));
        }
        Err(_) if t.ea.contains('|') || t.ea.starts_with("SYROPE:") => {
            return Err(err_at(
                p,
                l,
                name("EA"),
                format!(
                    "\"{}\": the Syrope model is not supported (give one EA in N, a \
                     strain-tension curve file, or the viscoelastic EA_s|EA_d)",
                    t.ea
                ),
            ))
        }
        Err(_) => {
            let c = read_ea_curve(p, l, &name("EA"), &t.ea)?;
            (crate::physics::tabulated_max_slope(&c.rows), Some(c))
        }
    };
    let ba = match t.ba.parse::<f64>() {
        _ if visco.is_some() => visco.map_or(0.0, |v| v.1),
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
    Ok((ea, ba, curve, visco.map(|v| v.2)))
}
