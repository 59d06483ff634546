//! `[[cable_arrays]]`: many cables from one table (mooring fleets, ensembles).
//!
//! An array names `count` cables `NAME_0 ... NAME_{count-1}`; every per-cable key takes a
//! constant or a *variation* across the array:
//! - a constant: `length = 250.0`, `current = [0.5, 0.0, 0.0]`, `line_type = "wire"`;
//! - a list, cycled: `length = [240.0, 250.0, 260.0]`, `line_type = ["wire", "chain"]`;
//! - a linear ramp over the array: `length = { from = 240.0, to = 260.0 }`;
//! - uniform random draws: `length = { random = [240.0, 260.0] }`,
//!   `current = { random = [[0.0, 0.0, 0.0], [1.0, 0.5, 0.0]] }` (per component), from the
//!   array's `seed` (default 0): the same file gives the same cables on every machine.
//!
//! Inside `start` and `end`, every vector key (`fixed`, `free`, `offset`, `at`, a route's
//! `start`, `velocity`, `center`, `axis`) and number key (`mass`, `volume`,
//! `drag_area`, `added_mass`, `diameter`, `period`, `phase`, `advance`) varies the same
//! way, and a list of strings (`point = ["a", "b"]`) is cycled.
//!
//! A `winch` table, if given, is the same for every cable of the array.
//!
//! Placement: `offset` (a vector, or a variation) and `grid = { columns = N, spacing =
//! [dx, dy, dz], row_spacing = [...] }` move both ends of cable `i` (positions and
//! routes) by `offset_i + (i % N) spacing + (i / N) row_spacing`.

use super::raw::RawCable;
use super::{err, finite};
use crate::error::Error;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;

const KEYS: [&str; 15] = [
    "name",
    "count",
    "seed",
    "line_type",
    "length",
    "segments",
    "start",
    "end",
    "initial",
    "current",
    "current_profile",
    "output_positions",
    "offset",
    "grid",
    "winch",
];

fn num(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

fn vec3(v: &toml::Value) -> Option<[f64; 3]> {
    match v {
        toml::Value::Array(a) if a.len() == 3 => Some([num(&a[0])?, num(&a[1])?, num(&a[2])?]),
        _ => None,
    }
}

/// One value per cable of a numeric (`D = 1`) or vector (`D = 3`) key.
fn vary<const D: usize>(
    p: &Path,
    field: &str,
    v: &toml::Value,
    count: usize,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<[f64; D]>, Error> {
    let one = |x: &toml::Value| -> Option<[f64; D]> {
        if D == 1 {
            num(x).map(|n| [n; D])
        } else {
            vec3(x).map(|a| {
                let mut o = [0.0; D];
                o.copy_from_slice(&a[..D]);
                o
            })
        }
    };
    let what = if D == 1 {
        "a number"
    } else {
        "an [x, y, z] array"
    };
    let bad = || {
        err(p, field, format!("must be {what}, a list of them (cycled), {{ from = .., to = .. }} or {{ random = [low, high] }}"))
    };
    let out: Vec<[f64; D]> = if let Some(c) = one(v) {
        vec![c; count]
    } else {
        match v {
            toml::Value::Array(list) if !list.is_empty() => {
                let items: Vec<[f64; D]> = list
                    .iter()
                    .map(|x| one(x).ok_or_else(bad))
                    .collect::<Result<_, _>>()?;
                (0..count).map(|i| items[i % items.len()]).collect()
            }
            toml::Value::Table(t)
                if t.contains_key("from") && t.contains_key("to") && t.len() == 2 =>
            {
                let (a, b) = (
                    one(&t["from"]).ok_or_else(bad)?,
                    one(&t["to"]).ok_or_else(bad)?,
                );
                (0..count)
                    .map(|i| {
                        let s = if count > 1 {
                            i as f64 / (count - 1) as f64
                        } else {
                            0.0
                        };
                        let mut o = [0.0; D];
                        for k in 0..D {
                            o[k] = a[k] + s * (b[k] - a[k]);
                        }
                        o
                    })
                    .collect()
            }
            toml::Value::Table(t) if t.len() == 1 && t.contains_key("random") => {
                let r = match &t["random"] {
                    toml::Value::Array(r) if r.len() == 2 => r,
                    _ => return Err(bad()),
                };
                let (a, b) = (one(&r[0]).ok_or_else(bad)?, one(&r[1]).ok_or_else(bad)?);
                for k in 0..D {
                    // NaN fails this too (`finite` below would catch it later).
                    if !(a[k] <= b[k]) {
                        let which = if D == 1 {
                            String::new()
                        } else {
                            format!(" (component {k})")
                        };
                        return Err(err(
                            p,
                            format!("{field}.random"),
                            format!(
                                "the range [low, high] is reversed or not a number{which}: {} > {}",
                                a[k], b[k]
                            ),
                        ));
                    }
                    // A width that overflows (e.g. [-1e308, 1e308]) cannot be sampled.
                    if !(b[k] - a[k]).is_finite() {
                        return Err(err(
                            p,
                            format!("{field}.random"),
                            format!(
                                "the range [{}, {}] is not finite or too wide to sample",
                                a[k], b[k]
                            ),
                        ));
                    }
                }
                (0..count)
                    .map(|_| {
                        let mut o = [0.0; D];
                        for k in 0..D {
                            o[k] = if b[k] > a[k] {
                                rng.gen_range(a[k]..b[k])
                            } else {
                                a[k]
                            };
                        }
                        o
                    })
                    .collect()
            }
            _ => return Err(bad()),
        }
    };
    for (i, x) in out.iter().enumerate() {
        for v in x {
            finite(p, &format!("{field} (cable {i})"), *v)?;
        }
    }
    Ok(out)
}

/// Keys of an end table that hold an `[x, y, z]` vector, and those that hold a number:
/// each may vary across an array as the array's own keys do.
const END_VECTORS: [&str; 8] = [
    "fixed", "free", "offset", "start", "velocity", "center", "axis", "at",
];
const END_NUMBERS: [&str; 8] = [
    "mass",
    "volume",
    "drag_area",
    "added_mass",
    "diameter",
    "period",
    "phase",
    "advance",
];

/// The end table `end` (field `field`) of each of the `count` cables: every vector or
/// number key varies as the array's keys do (a list, cycled; `{ from, to }`;
/// `{ random = [..] }`), a list of strings is cycled; other keys are copied for
/// [`super::ends::parse_end`] to check.
fn vary_end(
    p: &Path,
    field: &str,
    end: &toml::Table,
    count: usize,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<toml::Table>, Error> {
    let mut out = vec![end.clone(); count];
    for (k, v) in end {
        let f = format!("{field}.{k}");
        let values: Vec<toml::Value> = if END_VECTORS.contains(&k.as_str()) && vec3(v).is_none() {
            vary::<3>(p, &f, v, count, rng)?
                .into_iter()
                .map(|x| toml::Value::Array(x.iter().map(|c| toml::Value::Float(*c)).collect()))
                .collect()
        } else if END_NUMBERS.contains(&k.as_str()) && num(v).is_none() {
            vary::<1>(p, &f, v, count, rng)?
                .into_iter()
                .map(|x| toml::Value::Float(x[0]))
                .collect()
        } else if let toml::Value::Array(a) = v {
            if a.is_empty() || !a.iter().all(|x| x.is_str()) {
                continue;
            }
            (0..count).map(|i| a[i % a.len()].clone()).collect()
        } else {
            continue;
        };
        for (t, x) in out.iter_mut().zip(values) {
            t.insert(k.clone(), x);
        }
    }
    Ok(out)
}

/// Adds `d` to the end table's `offset` (nothing when `d` is zero: a point end takes
/// no offset).
fn shift(t: &mut toml::Table, d: [f64; 3]) {
    if d == [0.0; 3] {
        return;
    }
    let base = t.get("offset").and_then(vec3).unwrap_or([0.0; 3]);
    let o = [base[0] + d[0], base[1] + d[1], base[2] + d[2]];
    t.insert(
        "offset".into(),
        toml::Value::Array(o.iter().map(|x| toml::Value::Float(*x)).collect()),
    );
}

/// Expands the arrays into cables, each with the field prefix its errors should name.
pub fn expand(p: &Path, arrays: &[toml::Table]) -> Result<Vec<(String, RawCable)>, Error> {
    let mut out = Vec::new();
    for (ai, t) in arrays.iter().enumerate() {
        let name = t.get("name").and_then(|v| v.as_str()).ok_or_else(|| {
            err(
                p,
                format!("cable_arrays[{ai}].name"),
                "missing: a string name",
            )
        })?;
        let f = |k: &str| format!("cable_arrays[{ai}] (\"{name}\").{k}");
        if let Some(bad) = t.keys().find(|k| !KEYS.contains(&k.as_str())) {
            return Err(err(
                p,
                f(bad),
                format!("unknown key (allowed: {})", KEYS.join(", ")),
            ));
        }
        let count = match t.get("count") {
            Some(toml::Value::Integer(c)) if *c >= 1 && *c <= 10_000_000 => *c as usize,
            _ => return Err(err(p, f("count"), "must be an integer from 1 to 10000000")),
        };
        let seed = match t.get("seed") {
            None => 0,
            Some(toml::Value::Integer(s)) if *s >= 0 => *s as u64,
            _ => return Err(err(p, f("seed"), "must be a non-negative integer")),
        };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let req = |k: &str| t.get(k).ok_or_else(|| err(p, f(k), "missing"));
        let lengths = vary::<1>(p, &f("length"), req("length")?, count, &mut rng)?;
        let seg_spec = req("segments")?;
        if seg_spec
            .as_table()
            .is_some_and(|t| t.contains_key("random"))
        {
            return Err(err(
                p,
                f("segments"),
                "cannot be random (a count of elements): give a number, a list (cycled) or { from = .., to = .. } with whole steps",
            ));
        }
        let segments = vary::<1>(p, &f("segments"), seg_spec, count, &mut rng)?;
        let line_types: Vec<String> = match req("line_type")? {
            toml::Value::String(s) => vec![s.clone(); count],
            toml::Value::Array(a) if !a.is_empty() && a.iter().all(|x| x.is_str()) => (0..count)
                .map(|i| a[i % a.len()].as_str().expect("checked").to_string())
                .collect(),
            _ => {
                return Err(err(
                    p,
                    f("line_type"),
                    "must be a line type name or a list of them (cycled)",
                ))
            }
        };
        let currents = match t.get("current") {
            None => None,
            Some(v) => Some(vary::<3>(p, &f("current"), v, count, &mut rng)?),
        };
        let mut offsets = match t.get("offset") {
            None => vec![[0.0; 3]; count],
            Some(v) => vary::<3>(p, &f("offset"), v, count, &mut rng)?,
        };
        if let Some(g) = t.get("grid") {
            let g = g.as_table().ok_or_else(|| {
                err(
                    p,
                    f("grid"),
                    "must be { columns = N, spacing = [..], row_spacing = [..] }",
                )
            })?;
            let cols = match g.get("columns") {
                Some(toml::Value::Integer(c)) if *c >= 1 => *c as usize,
                _ => return Err(err(p, f("grid.columns"), "must be a positive integer")),
            };
            let sp = g
                .get("spacing")
                .and_then(vec3)
                .ok_or_else(|| err(p, f("grid.spacing"), "must be [dx, dy, dz]"))?;
            let rs = g.get("row_spacing").and_then(vec3).unwrap_or([0.0; 3]);
            if let Some(bad) = g
                .keys()
                .find(|k| !["columns", "spacing", "row_spacing"].contains(&k.as_str()))
            {
                return Err(err(
                    p,
                    f(&format!("grid.{bad}")),
                    "unknown key (columns, spacing, row_spacing)",
                ));
            }
            for (i, o) in offsets.iter_mut().enumerate() {
                let (c, r) = ((i % cols) as f64, (i / cols) as f64);
                for k in 0..3 {
                    o[k] += c * sp[k] + r * rs[k];
                }
            }
        }
        let placed = t.contains_key("offset") || t.contains_key("grid");
        let mut ends = Vec::with_capacity(2);
        for key in ["start", "end"] {
            let table = req(key)?
                .as_table()
                .ok_or_else(|| err(p, f(key), "must be an end table"))?;
            if placed && table.contains_key("point") {
                let by = if t.contains_key("offset") {
                    "offset"
                } else {
                    "grid"
                };
                return Err(err(
                    p,
                    f(by),
                    format!("moves both ends of every cable, and `{key}` is on a named point, which cannot move: place the cables by their other end's positions (a list or a ramp, e.g. `fixed = [[..], [..]]`) instead"),
                ));
            }
            ends.push(vary_end(p, &f(key), table, count, &mut rng)?);
        }
        let mut end_tables = ends.pop().expect("two ends").into_iter();
        let mut start_tables = ends.pop().expect("two ends").into_iter();
        let initial = match t.get("initial") {
            None => None,
            Some(toml::Value::String(s)) => Some(s.clone()),
            Some(_) => return Err(err(p, f("initial"), "must be \"catenary\" or \"straight\"")),
        };
        let current_profile = match t.get("current_profile") {
            None => None,
            Some(v) => Some(
                v.clone()
                    .try_into::<Vec<[f64; 4]>>()
                    .map_err(|e| err(p, f("current_profile"), e.to_string()))?,
            ),
        };
        let winch = match t.get("winch") {
            None => None,
            Some(toml::Value::Table(w)) => Some(w.clone()),
            Some(_) => return Err(err(p, f("winch"), "must be a winch table")),
        };
        let output_positions = match t.get("output_positions") {
            None => None,
            Some(toml::Value::Boolean(b)) => Some(*b),
            Some(_) => return Err(err(p, f("output_positions"), "must be true or false")),
        };
        for i in 0..count {
            let seg = segments[i][0];
            if seg.fract() != 0.0 {
                return Err(err(
                    p,
                    f("segments"),
                    format!("cable {i}: {seg} is not a whole number"),
                ));
            }
            let (mut start, mut end) = (
                start_tables.next().expect("one per cable"),
                end_tables.next().expect("one per cable"),
            );
            shift(&mut start, offsets[i]);
            shift(&mut end, offsets[i]);
            let cable = RawCable {
                name: format!("{name}_{i}"),
                line_type: line_types[i].clone(),
                length: lengths[i][0],
                segments: seg as i64,
                sections: None,
                start,
                end,
                initial: initial.clone(),
                current: currents.as_ref().map(|c| c[i]),
                current_profile: current_profile.clone(),
                output_positions,
                winch: winch.clone(),
            };
            out.push((
                format!("cable_arrays[{ai}] (\"{name}\") cable {i} (\"{name}_{i}\")"),
                cable,
            ));
        }
    }
    Ok(out)
}
