//! Route tables: CSV with the header `t,x,y,z`, linearly interpolated.

use super::err;
use crate::error::Error;
use crate::model::Route;
use std::path::Path;

/// Reads a route table. `scenario` and `field` name where it was referred from.
pub fn read(file: &Path, scenario: &Path, field: &str) -> Result<Route, Error> {
    let shown = file.display();
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_path(file)
        .map_err(|e| {
            err(
                scenario,
                field,
                format!("cannot read route file {shown}: {e}"),
            )
        })?;
    let header = rdr
        .headers()
        .map_err(|e| err(scenario, field, format!("{shown}: {e}")))?
        .clone();
    let h: Vec<&str> = header.iter().collect();
    if h != ["t", "x", "y", "z"] {
        return Err(err(
            scenario,
            field,
            format!(
                "{shown}: the header must be `t,x,y,z`, found `{}`",
                h.join(",")
            ),
        ));
    }
    let (mut ts, mut ps) = (Vec::new(), Vec::new());
    for rec in rdr.records() {
        let rec = rec.map_err(|e| err(scenario, field, format!("{shown}: {e}")))?;
        let line = rec.position().map(|p| p.line()).unwrap_or(0);
        if rec.len() != 4 {
            return Err(err(
                scenario,
                field,
                format!(
                    "{shown} line {line}: expected 4 values t,x,y,z, found {}",
                    rec.len()
                ),
            ));
        }
        let mut v = [0.0; 4];
        for (k, s) in rec.iter().enumerate() {
            v[k] = s
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    err(
                        scenario,
                        field,
                        format!("{shown} line {line}: `{s}` is not a finite number"),
                    )
                })?;
        }
        if let Some(&last) = ts.last() {
            if v[0] <= last {
                return Err(err(
                    scenario,
                    field,
                    format!(
                        "{shown} line {line}: time {} does not increase (previous {last})",
                        v[0]
                    ),
                ));
            }
        }
        ts.push(v[0]);
        ps.push([v[1], v[2], v[3]]);
    }
    if ts.is_empty() {
        return Err(err(
            scenario,
            field,
            format!("{shown}: no rows after the header"),
        ));
    }
    Ok(Route::Table { t: ts, p: ps })
}
