//! `[[cables]]` (and the cables `[[cable_arrays]]` expand to): line type, length,
//! segments, initial shape, current, ends and winch of each, as nodes and cables of
//! the model.

use super::ends::{self, EndKind};
use super::environment::current;
use super::output::Selection;
use super::raw::RawCable;
use super::{bodies, err, finite, positive, validate, winch, InitialShape};
use crate::ale::Winch;
use crate::error::Error;
use crate::model::{CableDef, EndFailure, ModelDef, NodeDef, PointMass};
use std::collections::HashMap;
use std::path::Path;

/// What the cables add besides the model's nodes and cables.
pub(super) struct Cables {
    /// Initial shape of each cable, in order.
    pub initial: Vec<InitialShape>,
    /// The winches, at most one per cable.
    pub winches: Vec<Winch>,
    /// Index of each cable by name.
    pub names: HashMap<String, usize>,
    /// The ends that may fail.
    pub failures: Vec<EndFailure>,
}

/// The keys a cable end takes besides its holding: the failure keys and `clamp`.
const END_KEYS: [&str; 3] = ["fail_time", "fail_tension", "clamp"];

/// The `clamp = [x, y, z]` of end table `t` (field `field`): the direction in which
/// the cable leaves that end, held (made a unit vector); `None` without the key.
fn clamp_dir(p: &Path, field: &str, t: &toml::Table) -> Result<Option<[f64; 3]>, Error> {
    let Some(v) = t.get("clamp") else {
        return Ok(None);
    };
    let f = format!("{field}.clamp");
    let a = match v {
        toml::Value::Array(a) if a.len() == 3 => a,
        _ => {
            return Err(err(
                p,
                f,
                "must be an array of three numbers [x, y, z]: the direction in which the \
                 cable leaves this end",
            ))
        }
    };
    let mut d = [0.0; 3];
    for (k, x) in a.iter().enumerate() {
        d[k] = match x {
            toml::Value::Float(x) => finite(p, &format!("{f}[{k}]"), *x)?,
            toml::Value::Integer(i) => *i as f64,
            _ => return Err(err(p, format!("{f}[{k}]"), "must be a number")),
        };
    }
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if !(l > 0.0 && l.is_finite()) {
        return Err(err(p, f, "must not be the zero vector"));
    }
    Ok(Some(d.map(|x| x / l)))
}

/// The failure of end `t` (`field`) of cable `cable`, if it has one: `fail_time` (s,
/// finite, not negative) and/or `fail_tension` (N, positive), on an end held by a fixed
/// point, a route or a body. (A `[[points]]` entry's are read the same way, with the
/// point's name for `cable`.)
pub(super) fn failure(
    p: &Path,
    field: &str,
    t: &toml::Table,
    kind: &EndKind,
    cable: &str,
    at_start: bool,
) -> Result<Option<EndFailure>, Error> {
    let get = |k: &str| -> Result<Option<f64>, Error> {
        match t.get(k) {
            None => Ok(None),
            Some(toml::Value::Float(x)) => Ok(Some(super::finite(p, &format!("{field}.{k}"), *x)?)),
            Some(toml::Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(v) => Err(err(
                p,
                format!("{field}.{k}"),
                format!("must be a number, got {}", v.type_str()),
            )),
        }
    };
    let (time, tension) = (get("fail_time")?, get("fail_tension")?);
    if time.is_none() && tension.is_none() {
        return Ok(None);
    }
    let key = if time.is_some() {
        "fail_time"
    } else {
        "fail_tension"
    };
    match kind {
        EndKind::Free(_) => {
            return Err(err(
                p,
                format!("{field}.{key}"),
                "a free end has no support to leave",
            ))
        }
        EndKind::Point(_) => {
            return Err(err(
                p,
                format!("{field}.{key}"),
                "an end on a named [[points]] entry fails with its point: give `fail_time` or `fail_tension` on the point (all its cables fail together), or give the ends that fail a [[points]] entry of their own at the same place",
            ))
        }
        _ => {}
    }
    if let Some(x) = time {
        if x < 0.0 {
            return Err(err(
                p,
                format!("{field}.fail_time"),
                format!("must not be negative, got {x}"),
            ));
        }
    }
    if let Some(x) = tension {
        if x <= 0.0 {
            return Err(err(
                p,
                format!("{field}.fail_tension"),
                format!("must be positive, got {x}"),
            ));
        }
    }
    Ok(Some(EndFailure {
        cable: cable.to_string(),
        at_start,
        time,
        tension,
    }))
}

/// Adds each cable of `cables` (its field prefix in messages and its table) to `model`:
/// its end nodes (or the points it names) and `segments - 1` nodes between them.
#[allow(clippy::too_many_arguments)]
pub(super) fn parse(
    p: &Path,
    cables: &[(String, RawCable)],
    lt_index: &HashMap<String, usize>,
    point_index: &HashMap<String, usize>,
    bodies: &bodies::Bodies,
    (depth, max_speed): (f64, f64),
    positions_sel: &Selection,
    model: &mut ModelDef,
) -> Result<Cables, Error> {
    let mut initial = Vec::with_capacity(cables.len());
    let mut winches = Vec::new();
    let mut names = HashMap::new();
    let mut failures = Vec::new();
    let many = cables.len() > 20;
    for (i, (prefix, c)) in cables.iter().enumerate() {
        let f = |k: &str| format!("{prefix}.{k}");
        if names.insert(c.name.clone(), i).is_some() {
            return Err(err(
                p,
                f("name"),
                format!("duplicate cable name \"{}\"", c.name),
            ));
        }
        let line = |name: &str, field: String| {
            lt_index.get(name).copied().ok_or_else(|| {
                let mut known: Vec<_> = lt_index.keys().cloned().collect();
                known.sort();
                err(
                    p,
                    field,
                    format!(
                        "unknown line type \"{name}\" (defined: {})",
                        known.join(", ")
                    ),
                )
            })
        };
        let segments = |field: String, s: i64| {
            if !(1..=1_000_000).contains(&s) {
                return Err(err(
                    p,
                    field,
                    format!("must be an integer from 1 to 1000000, got {s}"),
                ));
            }
            Ok(s as usize)
        };
        // One line type, or sections (chain - rope - chain) each with its own line
        // type, length and segment count: `(line type, length, segments)` per section.
        let parts: Vec<(usize, f64, usize)> = match &c.sections {
            None => {
                if c.line_type.is_empty() {
                    return Err(err(
                        p,
                        f("line_type"),
                        "missing field `line_type` (or give `sections`)",
                    ));
                }
                let lt = line(&c.line_type, f("line_type"))?;
                for (key, missing) in [
                    ("length", c.length.is_nan()),
                    ("segments", c.segments == i64::MIN),
                ] {
                    if missing {
                        return Err(err(
                            p,
                            f(key),
                            format!("missing field `{key}` (or give `sections`)"),
                        ));
                    }
                }
                let length = positive(p, &f("length"), c.length)?;
                validate::magnitude(p, &f("length"), length, "m")?;
                vec![(lt, length, segments(f("segments"), c.segments)?)]
            }
            Some(secs) => {
                if !c.line_type.is_empty() || !c.length.is_nan() || c.segments != i64::MIN {
                    return Err(err(
                        p,
                        f("sections"),
                        "give `sections` or `line_type`, `length` and `segments`, not both",
                    ));
                }
                if secs.is_empty() {
                    return Err(err(p, f("sections"), "needs at least one section"));
                }
                if c.winch.is_some() {
                    return Err(err(
                        p,
                        f("winch"),
                        "a cable of several sections cannot have a winch yet",
                    ));
                }
                let mut v = Vec::with_capacity(secs.len());
                for (k, s) in secs.iter().enumerate() {
                    let g = |key: &str| f(&format!("sections[{k}].{key}"));
                    let lt = line(&s.line_type, g("line_type"))?;
                    let length = positive(p, &g("length"), s.length)?;
                    validate::magnitude(p, &g("length"), length, "m")?;
                    v.push((lt, length, segments(g("segments"), s.segments)?));
                }
                v
            }
        };
        let lt = parts[0].0;
        if c.winch.is_some() && model.line_types[lt].ea_curve.is_some() {
            return Err(err(
                p,
                f("winch"),
                "a winch cable cannot have a line type with a strain-tension curve yet",
            ));
        }
        if c.winch.is_some() && model.line_types[lt].viscoelastic.is_some() {
            return Err(err(
                p,
                f("winch"),
                "a winch cable cannot have a viscoelastic line type yet",
            ));
        }
        let length: f64 = parts.iter().map(|s| s.1).sum();
        let n: usize = parts.iter().map(|s| s.2).sum();
        if n > 1_000_000 {
            return Err(err(
                p,
                f("sections"),
                format!("at most 1000000 segments in all, got {n}"),
            ));
        }
        let shape = match c.initial.as_deref() {
            None | Some("straight") => InitialShape::Straight,
            Some("catenary") => InitialShape::Catenary,
            Some(x) => {
                return Err(err(
                    p,
                    f("initial"),
                    format!("must be \"catenary\" or \"straight\", got \"{x}\""),
                ))
            }
        };
        let cur = match current(p, &format!("{prefix}."), c.current, &c.current_profile)? {
            Some(cu) => {
                model.currents.push(cu);
                model.currents.len() - 1
            }
            None => 0,
        };
        let start = ends::parse_end(p, &f("start"), &c.start, &END_KEYS, point_index, bodies)?;
        let end = ends::parse_end(p, &f("end"), &c.end, &END_KEYS, point_index, bodies)?;
        let ei = model.line_types[lt].ei;
        if ei > 0.0 && c.winch.is_some() {
            super::warnings::warn(format!(
                "{}: {}: line type \"{}\" has bending stiffness ei = {ei:e} N m^2, but a run \
                 with winch cables has no bending in the lumped-mass model yet: ei is used \
                 by the ANCF reference only in this run",
                p.display(),
                f("winch"),
                c.line_type
            ));
        }
        for (k, (t, spec)) in [(&c.start, &start), (&c.end, &end)].into_iter().enumerate() {
            let which = if k == 0 { "start" } else { "end" };
            let Some(d) = clamp_dir(p, &f(which), t)? else {
                continue;
            };
            if ei <= 0.0 {
                return Err(err(
                    p,
                    format!("{}.clamp", f(which)),
                    format!(
                        "a clamped end needs bending stiffness: line type \"{}\" has ei = 0",
                        c.line_type
                    ),
                ));
            }
            if !matches!(spec.kind, EndKind::Fixed(_)) {
                return Err(err(
                    p,
                    format!("{}.clamp", f(which)),
                    "only a `fixed` end can be clamped yet (not a free, route, point or body end)",
                ));
            }
            model.clamps.push(crate::model::Clamp {
                cable: model.cables.len(),
                end_b: k == 1,
                // Held as the tangent from end a towards end b.
                tangent: if k == 0 { d } else { d.map(|x| -x) },
            });
        }
        for (k, (t, spec)) in [(&c.start, &start), (&c.end, &end)].into_iter().enumerate() {
            let which = if k == 0 { "start" } else { "end" };
            if let Some(fl) = failure(p, &f(which), t, &spec.kind, &c.name, k == 0)? {
                failures.push(fl);
            }
        }
        if let Some(w) = &c.winch {
            winches.push(winch::parse(
                p,
                &format!("cables[{i}] (\"{}\")", c.name),
                w,
                i,
                length,
                n,
                [&start.kind, &end.kind],
            )?);
        }
        let mut ids = [0usize; 2];
        let mut pos = [[0.0; 3]; 2];
        for (k, spec) in [start, end].into_iter().enumerate() {
            if !matches!(spec.kind, EndKind::Point(_)) {
                let which = if k == 0 { "start" } else { "end" };
                let x = match (&spec.kind, &spec.route) {
                    (EndKind::Fixed(x) | EndKind::Free(x), _) => *x,
                    (_, Some(r)) => r.eval(0.0).r,
                    _ => [0.0; 3],
                };
                validate::position(p, &f(which), x)?;
                validate::height(p, &f(which), x, depth, model.env.seabed.grid)?;
                if let Some(r) = &spec.route {
                    validate::route_speed(p, &f(which), r, max_speed)?;
                }
            }
            match spec.kind {
                EndKind::Point(idx) => {
                    ids[k] = idx;
                    pos[k] = model.nodes[idx].position;
                }
                EndKind::Fixed(x) | EndKind::Free(x) => {
                    ids[k] = model.nodes.len();
                    pos[k] = x;
                    model.nodes.push(NodeDef {
                        position: x,
                        point: spec.mass,
                        route: spec.route,
                        label: None,
                    });
                }
                EndKind::Route => {
                    let r = spec.route.expect("route ends carry a route");
                    pos[k] = r.eval(0.0).r;
                    ids[k] = model.nodes.len();
                    model.nodes.push(NodeDef {
                        position: pos[k],
                        point: spec.mass,
                        route: Some(r),
                        label: None,
                    });
                }
            }
        }
        if ids[0] == ids[1] {
            return Err(err(
                p,
                f("end"),
                "a cable cannot start and end at the same point",
            ));
        }
        if shape == InitialShape::Straight {
            // The softest section's stiffness: the largest strain.
            let ea = parts
                .iter()
                .map(|s| model.line_types[s.0].ea)
                .fold(f64::INFINITY, f64::min);
            validate::straight_strain(p, &prefix.to_string(), length, ea, pos[0], pos[1]);
        }
        // Element lengths and line types, section by section; the nodes between the ends
        // at their unstretched arc length along the chord.
        let mut l0 = Vec::with_capacity(n);
        let mut elem_lines = Vec::with_capacity(n);
        for &(lt, len, m) in &parts {
            l0.extend(std::iter::repeat_n(len / m as f64, m));
            elem_lines.extend(std::iter::repeat_n(lt, m));
        }
        let mut nodes = Vec::with_capacity(n + 1);
        nodes.push(ids[0]);
        let mut arc = 0.0;
        for k in 1..n {
            arc += l0[k - 1];
            let s = if parts.len() > 1 {
                arc / length
            } else {
                k as f64 / n as f64
            };
            let x = [0, 1, 2].map(|d| pos[0][d] + s * (pos[1][d] - pos[0][d]));
            nodes.push(model.nodes.len());
            model.nodes.push(NodeDef {
                position: x,
                point: PointMass::default(),
                route: None,
                label: None,
            });
        }
        nodes.push(ids[1]);
        let output_positions = c.output_positions.unwrap_or(match positions_sel {
            Selection::All => true,
            Selection::None => false,
            Selection::Auto => !many,
            Selection::Names(v) => v.contains(&c.name),
        });
        model.cables.push(CableDef {
            name: c.name.clone(),
            line_type: lt,
            nodes,
            l0,
            current: cur,
            output_positions,
            // One section: every element is `line_type` (no per-element list).
            elem_lines: if parts.len() > 1 {
                elem_lines
            } else {
                Vec::new()
            },
        });
        initial.push(shape);
    }
    Ok(Cables {
        initial,
        winches,
        names,
        failures,
    })
}
