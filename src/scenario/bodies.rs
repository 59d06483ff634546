//! `[[bodies]]`: bodies with prescribed motion, and cable ends attached to them
//! (`{ body = "ship", at = [x, y, z] }`). The keys are documented in docs/src/bodies.md.

use super::route_file::read_numbers_one_of;
use super::{err, finite};
use crate::body::free::{self, FreeBody, FreeKind, FreeSpec, LoadTable};
use crate::body::{Body, Dynamic, MeanPose, Motion, MotionTable, RaoMotion, RaoTable};
use crate::error::Error;
use crate::model::Route;
use crate::sea::WaveComponent;
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::path::Path;
use std::sync::Arc;

/// The scenario's bodies by name.
pub type Bodies = HashMap<String, Arc<Body>>;

const BODY_KEYS: [&str; 25] = [
    "angles",
    "initial",
    "name",
    "reference",
    "offset",
    "heading",
    "motion_file",
    "rao_file",
    "motion",
    "mass",
    "cg",
    "inertia",
    "volume",
    "cb",
    "waterplane_area",
    "waterplane_inertia",
    "ca",
    "added_mass",
    "drag_area",
    "rotational_drag",
    "damping",
    "stiffness",
    "force",
    "moment",
    "load_file",
];

/// The keys of a free or pinned body only (its own dynamics).
const DYNAMIC_KEYS: [&str; 18] = [
    "initial",
    "mass",
    "cg",
    "inertia",
    "volume",
    "cb",
    "waterplane_area",
    "waterplane_inertia",
    "ca",
    "added_mass",
    "drag_area",
    "rotational_drag",
    "damping",
    "stiffness",
    "force",
    "moment",
    "load_file",
    "angles",
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
    rho: f64,
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
        let kind = match t.get("motion") {
            None => None,
            Some(v) => match string(p, &f("motion"), v)? {
                "prescribed" => None,
                "free" => Some(FreeKind::Free),
                "pinned" => Some(FreeKind::Pinned),
                other => {
                    return Err(err(
                        p,
                        f("motion"),
                        format!(
                        "unknown motion \"{other}\" (one of \"prescribed\", \"free\", \"pinned\")"
                    ),
                    ))
                }
            },
        };
        if let Some(kind) = kind {
            let dynamic = parse_dynamic(p, &field, t, base, kind, pose, rho)?;
            if out
                .insert(
                    name.clone(),
                    Arc::new(Body::new(
                        name.clone(),
                        pose,
                        Motion::Dynamic(Box::new(dynamic)),
                    )),
                )
                .is_some()
            {
                return Err(err(p, f("name"), format!("duplicate body name \"{name}\"")));
            }
            continue;
        }
        if let Some(k) = t.keys().find(|k| DYNAMIC_KEYS.contains(&k.as_str())) {
            return Err(err(
                p,
                f(k),
                "only a body with its own dynamics has this key (set motion = \"free\" or \"pinned\")",
            ));
        }
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

fn numbers<const N: usize>(p: &Path, field: &str, v: &toml::Value) -> Result<[f64; N], Error> {
    match v {
        toml::Value::Array(a) if a.len() == N => {
            let mut out = [0.0; N];
            for (k, x) in a.iter().enumerate() {
                out[k] = number(p, &format!("{field}[{k}]"), x)?;
            }
            Ok(out)
        }
        _ => Err(err(p, field, format!("must be an array of {N} numbers"))),
    }
}

fn matrix<const N: usize>(p: &Path, field: &str, v: &toml::Value) -> Result<[[f64; N]; N], Error> {
    match v {
        toml::Value::Array(rows) if rows.len() == N => {
            let mut out = [[0.0; N]; N];
            for (i, r) in rows.iter().enumerate() {
                out[i] = numbers::<N>(p, &format!("{field}[{i}]"), r).map_err(|_| {
                    err(
                        p,
                        format!("{field}[{i}]"),
                        format!("must be a row of {N} numbers"),
                    )
                })?;
            }
            Ok(out)
        }
        _ => Err(err(
            p,
            field,
            format!("must be a {N}x{N} matrix: {N} rows of {N} numbers"),
        )),
    }
}

fn symmetric<const N: usize>(p: &Path, field: &str, m: &[[f64; N]; N]) -> Result<(), Error> {
    let scale = m.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    for i in 0..N {
        for j in 0..i {
            if (m[i][j] - m[j][i]).abs() > 1e-9 * scale {
                return Err(err(
                    p,
                    field,
                    format!(
                        "must be symmetric: [{i}][{j}] = {} but [{j}][{i}] = {}",
                        m[i][j], m[j][i]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// A free or pinned body's keys (docs/src/bodies.md, "Free bodies").
fn parse_dynamic(
    p: &Path,
    field: &str,
    t: &toml::Table,
    base: &Path,
    kind: FreeKind,
    pose: MeanPose,
    rho: f64,
) -> Result<Dynamic, Error> {
    let f = |k: &str| format!("{field}.{k}");
    let get3 = |k: &str| -> Result<[f64; 3], Error> {
        t.get(k).map_or(Ok([0.0; 3]), |v| numbers::<3>(p, &f(k), v))
    };
    let get1 =
        |k: &str| -> Result<f64, Error> { t.get(k).map_or(Ok(0.0), |v| number(p, &f(k), v)) };
    let get6 = |k: &str| -> Result<[[f64; 6]; 6], Error> {
        t.get(k)
            .map_or(Ok([[0.0; 6]; 6]), |v| matrix::<6>(p, &f(k), v))
    };
    if t.get("rao_file").is_some() {
        return Err(err(
            p,
            f("rao_file"),
            "a free or pinned body moves by its own dynamics: it has no RAOs",
        ));
    }
    let pin = match (kind, t.get("motion_file")) {
        (FreeKind::Free, Some(_)) => {
            return Err(err(
                p,
                f("motion_file"),
                "a free body moves by its own dynamics: no motion file (a pinned body takes one for its translation)",
            ))
        }
        (FreeKind::Pinned, Some(v)) => {
            let file = base.join(string(p, &f("motion_file"), v)?);
            let m = read_motion(&file, p, &f("motion_file"))?;
            if !m.translation_only() {
                return Err(err(
                    p,
                    f("motion_file"),
                    format!(
                        "{}: a pinned body's rotation is free: its roll, pitch and yaw columns must be zero",
                        file.display()
                    ),
                ));
            }
            Some(m)
        }
        _ => None,
    };
    let mass = match t.get("mass") {
        Some(v) => number(p, &f("mass"), v)?,
        None => {
            return Err(err(
                p,
                f("mass"),
                "missing: a free or pinned body's mass, kg",
            ))
        }
    };
    let inertia = match t.get("inertia") {
        None => {
            return Err(err(
                p,
                f("inertia"),
                "missing: the inertia about the centre of gravity, body axes: [Ixx, Iyy, Izz] or a 3x3 matrix, kg m^2",
            ))
        }
        Some(toml::Value::Array(a)) if a.iter().all(|x| x.is_array()) => {
            let m = matrix::<3>(p, &f("inertia"), &toml::Value::Array(a.clone()))?;
            symmetric(p, &f("inertia"), &m)?;
            m
        }
        Some(v) => {
            let d = numbers::<3>(p, &f("inertia"), v)
                .map_err(|_| err(p, f("inertia"), "must be [Ixx, Iyy, Izz] or a 3x3 matrix, kg m^2"))?;
            [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
        }
    };
    let volume = get1("volume")?;
    if volume < 0.0 {
        return Err(err(
            p,
            f("volume"),
            format!("must not be negative, got {volume}"),
        ));
    }
    let waterplane_area = get1("waterplane_area")?;
    if waterplane_area < 0.0 {
        return Err(err(
            p,
            f("waterplane_area"),
            format!("must not be negative, got {waterplane_area}"),
        ));
    }
    let waterplane_inertia = t.get("waterplane_inertia").map_or(Ok([0.0; 2]), |v| {
        numbers::<2>(p, &f("waterplane_inertia"), v)
    })?;
    let mut added_mass = match (t.get("ca"), t.get("added_mass")) {
        (Some(_), Some(_)) => {
            return Err(err(p, field, "give either `ca` or `added_mass`, not both"))
        }
        (None, Some(_)) => {
            let a = get6("added_mass")?;
            symmetric(p, &f("added_mass"), &a)?;
            a
        }
        _ => [[0.0; 6]; 6],
    };
    if t.get("ca").is_some() {
        let ca = get3("ca")?;
        for k in 0..3 {
            added_mass[k][k] = ca[k] * volume * rho;
        }
    }
    for (k, v) in [
        ("drag_area", get3("drag_area")?),
        ("rotational_drag", get3("rotational_drag")?),
    ] {
        if let Some(x) = v.iter().find(|x| **x < 0.0) {
            return Err(err(p, f(k), format!("must not be negative, got {x}")));
        }
    }
    let loads = match t.get("load_file") {
        None => None,
        Some(v) => {
            let file = base.join(string(p, &f("load_file"), v)?);
            Some(read_loads(&file, p, &f("load_file"))?)
        }
    };
    let angles = get3("angles")?.map(f64::to_radians);
    let spec = FreeSpec {
        mass,
        cg: get3("cg")?,
        inertia,
        volume,
        cb: get3("cb")?,
        waterplane_area,
        waterplane_inertia,
        added_mass,
        drag_area: get3("drag_area")?,
        rotational_drag: get3("rotational_drag")?,
        damping: get6("damping")?,
        stiffness: get6("stiffness")?,
        force: get3("force")?,
        moment: get3("moment")?,
        loads,
        angles,
    };
    free::check(&spec, kind).map_err(|(k, m)| err(p, f(&k), m))?;
    let equilibrium = match t.get("initial") {
        None => true,
        Some(v) => match string(p, &f("initial"), v)? {
            "equilibrium" => true,
            "pose" => false,
            other => {
                return Err(err(
                    p,
                    f("initial"),
                    format!("unknown initial state \"{other}\" (one of \"equilibrium\", \"pose\")"),
                ))
            }
        },
    };
    Ok(Dynamic {
        body: FreeBody::new(spec, kind, &pose),
        pin,
        equilibrium,
    })
}

/// Reads an external load file: header `t,fx,fy,fz,mx,my,mz` (s, N, N m), times
/// strictly increasing.
pub fn read_loads(file: &Path, scenario: &Path, field: &str) -> Result<LoadTable, Error> {
    let shown = file.display();
    let header = ["t", "fx", "fy", "fz", "mx", "my", "mz"];
    let (_, rows) = read_numbers_one_of(file, scenario, field, "load", &[&header])?;
    let mut out = LoadTable {
        t: Vec::with_capacity(rows.len()),
        loads: Vec::with_capacity(rows.len()),
    };
    for (line, v) in rows {
        if let Some(&last) = out.t.last() {
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
        out.t.push(v[0]);
        out.loads.push([v[1], v[2], v[3], v[4], v[5], v[6]]);
    }
    Ok(out)
}
