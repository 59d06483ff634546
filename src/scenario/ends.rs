//! Cable ends and named points: `{ fixed = [...] }`, `{ free = [...] }`,
//! `{ route = "line" | "circle" | "screw" | "table", ... }`, `{ point = "name" }`,
//! `{ body = "name", at = [x, y, z] }` (`super::bodies`), each optionally with a point mass (`mass`, `volume`, `drag_area`, `added_mass`).

use super::{bodies, err, finite, non_negative, positive, route_file};
use crate::error::Error;
use crate::model::{PointMass, Route};
use std::collections::HashMap;
use std::path::Path;

/// What an end is.
#[derive(Clone, Debug, PartialEq)]
pub enum EndKind {
    /// Held at a point (its route is `Route::Fixed`).
    Fixed([f64; 3]),
    /// Free, starting at a point.
    Free([f64; 3]),
    /// Driven along a route (a point on a body included).
    Route,
    /// Attached to a named point (index into the model's nodes).
    Point(usize),
}

/// A parsed end.
#[derive(Clone, Debug)]
pub struct EndSpec {
    pub kind: EndKind,
    pub route: Option<Route>,
    pub mass: PointMass,
}

const MASS_KEYS: [&str; 4] = ["mass", "volume", "drag_area", "added_mass"];

fn get_f64(p: &Path, field: &str, t: &toml::Table, key: &str) -> Result<Option<f64>, Error> {
    match t.get(key) {
        None => Ok(None),
        Some(toml::Value::Float(x)) => Ok(Some(finite(p, &format!("{field}.{key}"), *x)?)),
        Some(toml::Value::Integer(i)) => Ok(Some(*i as f64)),
        Some(v) => Err(err(
            p,
            format!("{field}.{key}"),
            format!("must be a number, got {}", v.type_str()),
        )),
    }
}

fn req_f64(p: &Path, field: &str, t: &toml::Table, key: &str, what: &str) -> Result<f64, Error> {
    get_f64(p, field, t, key)?
        .ok_or_else(|| err(p, format!("{field}.{key}"), format!("missing: {what}")))
}

fn get_vec3(p: &Path, field: &str, t: &toml::Table, key: &str) -> Result<Option<[f64; 3]>, Error> {
    let f = format!("{field}.{key}");
    match t.get(key) {
        None => Ok(None),
        Some(toml::Value::Array(a)) if a.len() == 3 => {
            let mut out = [0.0; 3];
            for (k, v) in a.iter().enumerate() {
                out[k] = match v {
                    toml::Value::Float(x) => finite(p, &format!("{f}[{k}]"), *x)?,
                    toml::Value::Integer(i) => *i as f64,
                    _ => return Err(err(p, format!("{f}[{k}]"), "must be a number")),
                };
            }
            Ok(Some(out))
        }
        Some(_) => Err(err(p, f, "must be an array of three numbers [x, y, z]")),
    }
}

fn req_vec3(
    p: &Path,
    field: &str,
    t: &toml::Table,
    key: &str,
    what: &str,
) -> Result<[f64; 3], Error> {
    get_vec3(p, field, t, key)?
        .ok_or_else(|| err(p, format!("{field}.{key}"), format!("missing: {what}")))
}

fn unit_axis(p: &Path, field: &str, t: &toml::Table) -> Result<[f64; 3], Error> {
    let a = get_vec3(p, field, t, "axis")?.unwrap_or([0.0, 0.0, 1.0]);
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if l == 0.0 {
        return Err(err(
            p,
            format!("{field}.axis"),
            "must not be the zero vector",
        ));
    }
    Ok([a[0] / l, a[1] / l, a[2] / l])
}

/// Parses an end (or a point's) table. `extra` lists further allowed keys.
pub fn parse_end(
    p: &Path,
    field: &str,
    t: &toml::Table,
    extra: &[&str],
    points: &HashMap<String, usize>,
    bodies: &bodies::Bodies,
) -> Result<EndSpec, Error> {
    let kinds: Vec<&str> = ["fixed", "free", "route", "point", "body"]
        .into_iter()
        .filter(|k| t.contains_key(*k))
        .collect();
    if kinds.len() != 1 {
        return Err(err(
            p,
            field,
            if kinds.is_empty() {
                "needs one of `fixed = [x, y, z]`, `free = [x, y, z]`, `route = \"...\"`, `point = \"name\"` or `body = \"name\"`".to_string()
            } else {
                format!("give only one of {}", kinds.join(", "))
            },
        ));
    }
    if kinds[0] == "point" {
        // The point carries the mass: keys here would be dropped without a word.
        if let Some(k) = MASS_KEYS.into_iter().find(|k| t.contains_key(*k)) {
            return Err(err(
                p,
                format!("{field}.{k}"),
                "an end on a named point takes no point mass: give it on the point in [[points]]",
            ));
        }
    }
    let mut allowed: Vec<&str> = vec![kinds[0], "offset"];
    allowed.extend(MASS_KEYS);
    allowed.extend(extra);
    let (kind, route) = match kinds[0] {
        "fixed" => {
            let x = req_vec3(p, field, t, "fixed", "position")?;
            (EndKind::Fixed(x), Some(Route::Fixed { position: x }))
        }
        "free" => (
            EndKind::Free(req_vec3(p, field, t, "free", "position")?),
            None,
        ),
        "point" => {
            let name = t["point"]
                .as_str()
                .ok_or_else(|| err(p, format!("{field}.point"), "must be a point name (string)"))?;
            let idx = *points.get(name).ok_or_else(|| {
                let mut known: Vec<_> = points.keys().cloned().collect();
                known.sort();
                err(
                    p,
                    format!("{field}.point"),
                    format!(
                        "unknown point \"{name}\" (defined in [[points]]: {})",
                        known.join(", ")
                    ),
                )
            })?;
            (EndKind::Point(idx), None)
        }
        "body" => {
            allowed.push("at");
            (
                EndKind::Route,
                Some(bodies::end_route(p, field, t, bodies)?),
            )
        }
        _ => {
            let kind = t["route"]
                .as_str()
                .ok_or_else(|| err(p, format!("{field}.route"), "must be a string"))?;
            let r = match kind {
                "line" => {
                    allowed.extend(["start", "velocity"]);
                    Route::Line {
                        start: req_vec3(p, field, t, "start", "start position of the line route")?,
                        velocity: req_vec3(p, field, t, "velocity", "velocity of the line route")?,
                    }
                }
                "circle" | "screw" => {
                    allowed.extend(["center", "diameter", "period", "axis", "phase"]);
                    let advance = if kind == "screw" {
                        allowed.push("advance");
                        finite(
                            p,
                            &format!("{field}.advance"),
                            req_f64(
                                p,
                                field,
                                t,
                                "advance",
                                "advance along the axis per revolution, m",
                            )?,
                        )?
                    } else {
                        0.0
                    };
                    let d = positive(
                        p,
                        &format!("{field}.diameter"),
                        req_f64(p, field, t, "diameter", "circle diameter, m")?,
                    )?;
                    Route::Circle {
                        center: req_vec3(p, field, t, "center", "circle centre")?,
                        radius: 0.5 * d,
                        period: positive(
                            p,
                            &format!("{field}.period"),
                            req_f64(p, field, t, "period", "time of one revolution, s")?,
                        )?,
                        axis: unit_axis(p, field, t)?,
                        phase: get_f64(p, field, t, "phase")?.unwrap_or(0.0).to_radians(),
                        advance,
                    }
                }
                "table" => {
                    allowed.push("file");
                    let f = t.get("file").and_then(|v| v.as_str()).ok_or_else(|| {
                        err(
                            p,
                            format!("{field}.file"),
                            "missing: CSV file with header t,x,y,z",
                        )
                    })?;
                    let base = p.parent().unwrap_or(Path::new("."));
                    route_file::read(&base.join(f), p, &format!("{field}.file"))?
                }
                other => {
                    return Err(err(
                        p,
                        format!("{field}.route"),
                        format!("unknown route \"{other}\" (line, circle, screw, table)"),
                    ));
                }
            };
            allowed.push("route");
            (EndKind::Route, Some(r))
        }
    };
    if let Some(bad) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(err(
            p,
            format!("{field}.{bad}"),
            format!("unknown key (allowed here: {})", allowed.join(", ")),
        ));
    }
    // `offset` moves the whole end (position or route): patterns of cables use it.
    let (kind, route) = match get_vec3(p, field, t, "offset")? {
        None => (kind, route),
        // Checked by bodies::end_route: zero.
        Some(_) if kinds[0] == "body" => (kind, route),
        Some(d) => {
            let add = |a: [f64; 3]| [a[0] + d[0], a[1] + d[1], a[2] + d[2]];
            let kind = match kind {
                EndKind::Fixed(x) => EndKind::Fixed(add(x)),
                EndKind::Free(x) => EndKind::Free(add(x)),
                EndKind::Point(_) => {
                    return Err(err(
                        p,
                        format!("{field}.offset"),
                        "a point end cannot be offset (move the point)",
                    ))
                }
                k => k,
            };
            (kind, route.map(|r| r.translated(d)))
        }
    };
    let mass = PointMass {
        mass: non_negative(
            p,
            &format!("{field}.mass"),
            get_f64(p, field, t, "mass")?.unwrap_or(0.0),
        )?,
        volume: non_negative(
            p,
            &format!("{field}.volume"),
            get_f64(p, field, t, "volume")?.unwrap_or(0.0),
        )?,
        drag_area: non_negative(
            p,
            &format!("{field}.drag_area"),
            get_f64(p, field, t, "drag_area")?.unwrap_or(0.0),
        )?,
        added_mass_coef: non_negative(
            p,
            &format!("{field}.added_mass"),
            get_f64(p, field, t, "added_mass")?.unwrap_or(0.0),
        )?,
    };
    Ok(EndSpec { kind, route, mass })
}
