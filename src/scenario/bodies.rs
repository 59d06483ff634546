//! `[[bodies]]`: bodies with prescribed motion, and cable ends attached to them
//! (`{ body = "ship", at = [x, y, z] }`). The keys are documented in docs/src/bodies.md.

use super::route_file::read_numbers_one_of;
use super::{err, finite};
use crate::body::{Body, MeanPose, Motion, MotionTable, RaoMotion, RaoTable};
use crate::error::Error;
use crate::model::Route;
use crate::sea::WaveComponent;
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::path::Path;
use std::sync::Arc;

/// The scenario's bodies by name.
pub type Bodies = HashMap<String, Arc<Body>>;

const BODY_KEYS: [&str; 6] = [
    "name",
    "reference",
    "offset",
    "heading",
    "motion_file",
    "rao_file",
];

fn number(p: &Path, field: &str, v: &toml::Value) -> Result<f64, Error> {
    match v {
        toml::Value::Float(x) => finite(p, field, *x),
        toml::Value::Integer(i) => Ok(*i as f64),
        other => Err(err(
            p,
            field,
            format!("must be a number, got {}", other.type_str()),
        )),
    }
}

fn vec3(p: &Path, field: &str, v: &toml::Value) -> Result<[f64; 3], Error> {
    match v {
        toml::Value::Array(a) if a.len() == 3 => {
            let mut out = [0.0; 3];
            for (k, x) in a.iter().enumerate() {
                out[k] = number(p, &format!("{field}[{k}]"), x)?;
            }
            Ok(out)
        }
        _ => Err(err(p, field, "must be an array of three numbers [x, y, z]")),
    }
}

fn string<'a>(p: &Path, field: &str, v: &'a toml::Value) -> Result<&'a str, Error> {
    v.as_str()
        .ok_or_else(|| err(p, field, format!("must be a string, got {}", v.type_str())))
}

/// Parses `[[bodies]]`. RAO motions are driven by `waves` (the sea state's wave
/// components; none: the body stays in its mean pose, with a warning), ramped in over
/// `ramp` seconds as the waves are.
pub fn parse(
    p: &Path,
    tables: &[toml::Table],
    waves: &[WaveComponent],
    ramp: f64,
) -> Result<Bodies, Error> {
    let mut out = Bodies::new();
    for (i, t) in tables.iter().enumerate() {
        let name = match t.get("name") {
            Some(toml::Value::String(s)) => s.clone(),
            _ => {
                return Err(err(
                    p,
                    format!("bodies[{i}].name"),
                    "every body needs a string `name`",
                ))
            }
        };
        let field = format!("bodies[{i}] (\"{name}\")");
        let f = |k: &str| format!("{field}.{k}");
        if let Some(bad) = t.keys().find(|k| !BODY_KEYS.contains(&k.as_str())) {
            return Err(err(
                p,
                f(bad),
                format!("unknown key (allowed here: {})", BODY_KEYS.join(", ")),
            ));
        }
        let reference = match t.get("reference") {
            Some(v) => vec3(p, &f("reference"), v)?,
            None => {
                return Err(err(
                    p,
                    f("reference"),
                    "missing: the body's reference point [x, y, z], m",
                ))
            }
        };
        let pose = MeanPose {
            reference,
            offset: match t.get("offset") {
                Some(v) => vec3(p, &f("offset"), v)?,
                None => [0.0; 3],
            },
            heading: match t.get("heading") {
                Some(v) => number(p, &f("heading"), v)?.to_radians(),
                None => 0.0,
            },
        };
        let base = p.parent().unwrap_or(Path::new("."));
        let motion = match (t.get("motion_file"), t.get("rao_file")) {
            (Some(_), Some(_)) => return Err(err(
                p,
                &field,
                "give either `motion_file` (a 6-DOF time series) or `rao_file` (RAOs), not both",
            )),
            (Some(v), None) => {
                let file = base.join(string(p, &f("motion_file"), v)?);
                Motion::Table(read_motion(&file, p, &f("motion_file"))?)
            }
            (None, Some(v)) => {
                let file = base.join(string(p, &f("rao_file"), v)?);
                let rao = read_rao(&file, p, &f("rao_file"))?;
                if waves.is_empty() {
                    super::warnings::warn(format!(
                        "{}: {field}: RAOs given but the scenario has no waves; the body stays in its mean pose",
                        p.display()
                    ));
                }
                let m = pose.position();
                Motion::Rao(RaoMotion::new(&rao, waves, m[0], m[1], pose.heading, ramp))
            }
            (None, None) => Motion::Still,
        };
        if out
            .insert(
                name.clone(),
                Arc::new(Body::new(name.clone(), pose, motion)),
            )
            .is_some()
        {
            return Err(err(p, f("name"), format!("duplicate body name \"{name}\"")));
        }
    }
    Ok(out)
}

/// The route of an end `{ body = "name", at = [x, y, z] }` (`field` names the end).
/// An `offset` (which cable arrays add) must be zero: a point on a body is placed by
/// its `at`, in body coordinates.
pub fn end_route(p: &Path, field: &str, t: &toml::Table, bodies: &Bodies) -> Result<Route, Error> {
    let name = string(p, &format!("{field}.body"), &t["body"])?;
    let body = bodies.get(name).ok_or_else(|| {
        let mut known: Vec<_> = bodies.keys().cloned().collect();
        known.sort();
        err(
            p,
            format!("{field}.body"),
            if known.is_empty() {
                format!("unknown body \"{name}\" (the scenario has no [[bodies]])")
            } else {
                format!(
                    "unknown body \"{name}\" (defined in [[bodies]]: {})",
                    known.join(", ")
                )
            },
        )
    })?;
    let at = match t.get("at") {
        Some(v) => vec3(p, &format!("{field}.at"), v)?,
        None => {
            return Err(err(
                p,
                format!("{field}.at"),
                "missing: the attachment point in body coordinates [x, y, z], m",
            ))
        }
    };
    if let Some(v) = t.get("offset") {
        if vec3(p, &format!("{field}.offset"), v)? != [0.0; 3] {
            return Err(err(
                p,
                format!("{field}.offset"),
                "an end on a body cannot be offset (place it with `at`, in body coordinates)",
            ));
        }
    }
    Ok(Route::Body {
        body: body.clone(),
        at,
    })
}

/// Reads a 6-DOF motion file: header `t,x,y,z,roll,pitch,yaw` (s, m, degrees), times
/// strictly increasing.
pub fn read_motion(file: &Path, scenario: &Path, field: &str) -> Result<MotionTable, Error> {
    let shown = file.display();
    let header = ["t", "x", "y", "z", "roll", "pitch", "yaw"];
    let (_, rows) = read_numbers_one_of(file, scenario, field, "motion", &[&header])?;
    let mut ts = Vec::with_capacity(rows.len());
    let mut dofs = Vec::with_capacity(rows.len());
    for (line, v) in rows {
        if let Some(&last) = ts.last() {
            if v[0] <= last {
                return Err(err(
                    scenario,
                    field,
                    format!(
                        "{shown} line {line}, column t: time {} does not increase (previous {last})",
                        v[0]
                    ),
                ));
            }
        }
        ts.push(v[0]);
        dofs.push([v[1], v[2], v[3], v[4], v[5], v[6]]);
    }
    Ok(MotionTable::new(ts, &dofs))
}

/// The degrees of freedom in an RAO file's columns.
const DOF_NAMES: [&str; 6] = ["surge", "sway", "heave", "roll", "pitch", "yaw"];

/// Reads an RAO file: header `omega,heading,...` (rad/s) or `period,heading,...` (s),
/// then `<dof>_amp,<dof>_phase` for surge, sway, heave, roll, pitch, yaw (m/m or
/// deg/m, and degrees). Rows sorted by the first column, then by heading, on a full
/// grid: every frequency lists the same headings.
pub fn read_rao(file: &Path, scenario: &Path, field: &str) -> Result<RaoTable, Error> {
    let shown = file.display();
    let mut cols: Vec<String> = Vec::new();
    for d in DOF_NAMES {
        cols.push(format!("{d}_amp"));
        cols.push(format!("{d}_phase"));
    }
    let header = |first: &'static str| {
        let mut h: Vec<&str> = vec![first, "heading"];
        h.extend(cols.iter().map(String::as_str));
        h
    };
    let (h_omega, h_period) = (header("omega"), header("period"));
    let (which, rows) = read_numbers_one_of(file, scenario, field, "RAO", &[&h_omega, &h_period])?;
    let first = ["omega", "period"][which];
    let bad = |line: usize, col: &str, msg: String| {
        err(
            scenario,
            field,
            format!("{shown} line {line}, column {col}: {msg}"),
        )
    };
    // Group rows by their first column (frequency or period).
    let mut keys: Vec<f64> = Vec::new();
    let mut headings: Vec<f64> = Vec::new();
    let mut blocks: Vec<Vec<[(f64, f64); 6]>> = Vec::new();
    let mut block_headings: Vec<f64> = Vec::new();
    let mut prev_line = 0;
    for (line, v) in &rows {
        let (key, hd) = (v[0], v[1]);
        if key <= 0.0 {
            return Err(bad(*line, first, format!("must be positive, got {key}")));
        }
        let new_block = keys.last().is_none_or(|&k| key != k);
        if new_block {
            if let Some(&k) = keys.last() {
                if key < k {
                    return Err(bad(
                        *line,
                        first,
                        format!("{key} after {k}: rows must be sorted by {first}, then by heading"),
                    ));
                }
                check_headings(&block_headings, &headings, k, first)
                    .map_err(|m| bad(prev_line, "heading", m))?;
                if headings.is_empty() {
                    headings = block_headings.clone();
                }
            }
            keys.push(key);
            blocks.push(Vec::new());
            block_headings.clear();
        } else if let Some(&h) = block_headings.last() {
            if hd <= h {
                return Err(bad(
                    *line,
                    "heading",
                    format!("{hd} after {h}: headings must increase within each {first}"),
                ));
            }
        }
        if let Some(&h0) = block_headings.first() {
            if hd - h0 >= 360.0 {
                return Err(bad(
                    *line,
                    "heading",
                    format!("{hd} is a full turn or more from the first heading {h0}"),
                ));
            }
        }
        block_headings.push(hd);
        let mut r = [(0.0, 0.0); 6];
        for (k, d) in DOF_NAMES.iter().enumerate() {
            let amp = v[2 + 2 * k];
            if amp < 0.0 {
                return Err(bad(
                    *line,
                    &format!("{d}_amp"),
                    format!("must not be negative, got {amp}"),
                ));
            }
            // Rotations are given in deg/m; the library works in rad/m.
            r[k] = (
                if k >= 3 { amp.to_radians() } else { amp },
                v[3 + 2 * k].to_radians(),
            );
        }
        blocks.last_mut().expect("a block was opened").push(r);
        prev_line = *line;
    }
    let last_line = rows.last().map_or(0, |r| r.0);
    let k_last = *keys.last().expect("rows are not empty");
    check_headings(&block_headings, &headings, k_last, first)
        .map_err(|m| bad(last_line, "heading", m))?;
    if headings.is_empty() {
        headings = block_headings;
    }
    // Frequency-major, increasing frequency (a period table runs backwards).
    let (mut omega, mut values): (Vec<f64>, Vec<[(f64, f64); 6]>) = (Vec::new(), Vec::new());
    let order: Vec<usize> = if which == 0 {
        (0..keys.len()).collect()
    } else {
        (0..keys.len()).rev().collect()
    };
    for i in order {
        omega.push(if which == 0 { keys[i] } else { TAU / keys[i] });
        values.extend(&blocks[i]);
    }
    Ok(RaoTable::new(
        omega,
        headings.iter().map(|h| h.to_radians()).collect(),
        values,
    ))
}

/// A frequency's headings against the first frequency's (a full grid): `Err` names
/// the heading missing or extra.
fn check_headings(got: &[f64], want: &[f64], key: f64, first: &str) -> Result<(), String> {
    if want.is_empty() || got == want {
        return Ok(());
    }
    if let Some(h) = want.iter().find(|h| !got.contains(h)) {
        return Err(format!(
            "{first} {key} has no row for heading {h} (every {first} needs the headings of the first: {want:?})"
        ));
    }
    let h = got
        .iter()
        .find(|h| !want.contains(h))
        .expect("lists differ");
    Err(format!(
        "{first} {key} has heading {h}, which the first {first} does not (every {first} needs the same headings: {want:?})"
    ))
}
