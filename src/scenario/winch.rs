//! The `winch` key of a cable: `{ end = "start" | "end", schedule = "constant" |
//! "rates" | "table", rate = .., rates = [[t, rate], ..], file = "payout.csv",
//! drum_length = .. }` (docs/src/scenario.md, "Winches").

use super::{err, finite, positive, EndKind};
use crate::ale::{PayoutSchedule, Winch, WinchEnd};
use crate::error::Error;
use std::path::Path;
use std::sync::Arc;

fn number(p: &Path, f: &str, v: &toml::Value) -> Result<f64, Error> {
    match v {
        toml::Value::Float(x) => finite(p, f, *x),
        toml::Value::Integer(i) => Ok(*i as f64),
        other => Err(err(
            p,
            f,
            format!("must be a number, got {}", other.type_str()),
        )),
    }
}

/// Parses a cable's `winch` table. `field` names the cable (`cables[0] ("x")`),
/// `length` and `segments` are the cable's, `ends` its start and end kinds.
#[allow(clippy::too_many_arguments)]
pub fn parse(
    p: &Path,
    field: &str,
    t: &toml::Table,
    cable: usize,
    length: f64,
    segments: usize,
    ends: [&EndKind; 2],
) -> Result<Winch, Error> {
    let f = |k: &str| format!("{field}.winch.{k}");
    let end = match t.get("end") {
        None => WinchEnd::Start,
        Some(toml::Value::String(s)) if s == "start" => WinchEnd::Start,
        Some(toml::Value::String(s)) if s == "end" => WinchEnd::End,
        Some(v) => {
            return Err(err(
                p,
                f("end"),
                format!("must be \"start\" or \"end\", got {v}"),
            ))
        }
    };
    let (k, name) = match end {
        WinchEnd::Start => (0, "start"),
        WinchEnd::End => (1, "end"),
    };
    match ends[k] {
        EndKind::Fixed(_) | EndKind::Route => {}
        EndKind::Free(_) => {
            return Err(err(
                p,
                f("end"),
                format!(
                    "the winch is at the cable's {name}, which is free; a winch must be held: give `{field}.{name}` `fixed = [x, y, z]` or a route"
                ),
            ))
        }
        EndKind::Point(_) => {
            return Err(err(
                p,
                f("end"),
                format!(
                    "the winch is at the cable's {name}, a shared [[points]] node; a winch needs the cable's own held end (`fixed = [x, y, z]` or a route)"
                ),
            ))
        }
    }
    let kind = match t.get("schedule") {
        Some(toml::Value::String(s)) => s.as_str(),
        Some(_) => return Err(err(p, f("schedule"), "must be a string")),
        None => {
            return Err(err(
                p,
                f("schedule"),
                "missing: \"constant\", \"rates\" or \"table\"",
            ))
        }
    };
    let mut allowed = vec!["end", "schedule", "drum_length"];
    let schedule = match kind {
        "constant" => {
            allowed.push("rate");
            let rate = number(
                p,
                &f("rate"),
                t.get("rate").ok_or_else(|| {
                    err(
                        p,
                        f("rate"),
                        "missing: payout rate, m/s (negative to haul in)",
                    )
                })?,
            )?;
            PayoutSchedule::constant(rate).map_err(|m| err(p, f("rate"), m))?
        }
        "rates" => {
            allowed.push("rates");
            let rows = match t.get("rates") {
                Some(toml::Value::Array(a)) => a,
                Some(_) => return Err(err(p, f("rates"), "must be an array of [t, rate] rows")),
                None => {
                    return Err(err(
                        p,
                        f("rates"),
                        "missing: rows [t, rate] (s, m/s), rate linear in between",
                    ))
                }
            };
            let mut pairs = Vec::with_capacity(rows.len());
            for (i, row) in rows.iter().enumerate() {
                let fi = format!("{}[{i}]", f("rates"));
                match row {
                    toml::Value::Array(x) if x.len() == 2 => pairs.push((
                        number(p, &format!("{fi}[0]"), &x[0])?,
                        number(p, &format!("{fi}[1]"), &x[1])?,
                    )),
                    _ => return Err(err(p, fi, "must be a row [t, rate]")),
                }
            }
            PayoutSchedule::rates(&pairs).map_err(|m| err(p, f("rates"), m))?
        }
        "table" => {
            allowed.push("file");
            let file = t.get("file").and_then(|v| v.as_str()).ok_or_else(|| {
                err(
                    p,
                    f("file"),
                    "missing: CSV file with header t,length (deployed length, m)",
                )
            })?;
            let base = p.parent().unwrap_or(Path::new("."));
            let s = read_table(&base.join(file), p, &f("file"))?;
            let l0 = s.table_length_at_zero().expect("a table");
            if (l0 - length).abs() > 1e-9 * length.max(1.0) {
                return Err(err(
                    p,
                    f("file"),
                    format!(
                        "{}: the table's deployed length at t = 0 is {l0} m, but the cable's `length` (the initially deployed length) is {length} m",
                        base.join(file).display()
                    ),
                ));
            }
            s
        }
        other => {
            return Err(err(
                p,
                f("schedule"),
                format!("unknown schedule \"{other}\" (constant, rates, table)"),
            ))
        }
    };
    if let Some(bad) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(err(
            p,
            f(bad),
            format!("unknown key (allowed here: {})", allowed.join(", ")),
        ));
    }
    let drum_length = match t.get("drum_length") {
        None => f64::INFINITY,
        Some(v) => positive(p, &f("drum_length"), number(p, &f("drum_length"), v)?)?,
    };
    if drum_length < length {
        return Err(err(
            p,
            f("drum_length"),
            format!(
                "the drum holds {drum_length} m, less than the {length} m deployed at the start (`length`)"
            ),
        ));
    }
    Ok(Winch {
        cable,
        end,
        schedule: Arc::new(schedule),
        drum_length,
        element_length: length / segments as f64,
    })
}

/// Reads a payout table: CSV with the header `t,length`.
fn read_table(file: &Path, scenario: &Path, field: &str) -> Result<PayoutSchedule, Error> {
    let shown = file.display();
    let read = super::route_file::read_numbers(file, scenario, field, "payout", &["t", "length"])?;
    let rows: Vec<(f64, f64)> = read.iter().map(|(_, v)| (v[0], v[1])).collect();
    let lines: Vec<usize> = read.iter().map(|(l, _)| *l).collect();
    PayoutSchedule::table(&rows).map_err(|m| {
        // Name the file line of the offending row.
        let msg = match m
            .strip_prefix("row ")
            .and_then(|r| r.split_once(':'))
            .and_then(|(i, rest)| i.parse::<usize>().ok().map(|i| (i, rest)))
        {
            Some((i, rest)) => format!("{shown} line {}:{rest}", lines[i]),
            None => format!("{shown}: {m}"),
        };
        err(scenario, field, msg)
    })
}
