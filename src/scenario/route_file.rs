//! Route tables: CSV with the header `t,x,y,z`, linearly interpolated.

use super::err;
use crate::error::Error;
use crate::model::Route;
use std::path::Path;

/// Reads a CSV table of finite numbers with exactly the columns `header` (`what` names
/// the kind of file in messages). Returns each row's file line and values; every
/// problem is an error naming the file, the line, the column and what is wrong.
pub(crate) fn read_numbers(
    file: &Path,
    scenario: &Path,
    field: &str,
    what: &str,
    header: &[&str],
) -> Result<Rows, Error> {
    read_numbers_one_of(file, scenario, field, what, &[header]).map(|(_, rows)| rows)
}

/// Rows of a numeric table: each row's file line and values.
pub(crate) type Rows = Vec<(usize, Vec<f64>)>;

/// As [`read_numbers`], for a file whose header may be any of `headers`: returns which
/// one it has, and the rows.
pub(crate) fn read_numbers_one_of(
    file: &Path,
    scenario: &Path,
    field: &str,
    what: &str,
    headers: &[&[&str]],
) -> Result<(usize, Rows), Error> {
    let shown = file.display();
    let bytes = crate::input::read_bytes(file).map_err(|e| {
        let message = match e.strip_prefix("cannot read: ") {
            Some(why) => format!("cannot read {what} file {shown}: {why}"),
            None => format!("{what} file {shown}: {e}"),
        };
        err(scenario, field, message)
    })?;
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(bytes.as_slice());
    let found = rdr
        .headers()
        .map_err(|e| err(scenario, field, format!("{shown}: {e}")))?
        .clone();
    let h: Vec<&str> = found.iter().collect();
    let Some(which) = headers.iter().position(|x| *x == h.as_slice()) else {
        let names: Vec<String> = headers
            .iter()
            .map(|x| format!("`{}`", x.join(",")))
            .collect();
        return Err(err(
            scenario,
            field,
            format!(
                "{shown}: the header must be {}, found `{}`",
                names.join(" or "),
                h.join(",")
            ),
        ));
    };
    let header = headers[which];
    let names = header.join(",");
    let mut rows = Vec::new();
    for rec in rdr.records() {
        let rec = rec.map_err(|e| err(scenario, field, format!("{shown}: {e}")))?;
        let line = rec.position().map(|p| p.line() as usize).unwrap_or(0);
        if rec.len() != header.len() {
            return Err(err(
                scenario,
                field,
                format!(
                    "{shown} line {line}: expected {} values {names}, found {}",
                    header.len(),
                    rec.len()
                ),
            ));
        }
        let v = rec
            .iter()
            .zip(header)
            .map(|(s, col)| {
                s.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| {
                        err(
                            scenario,
                            field,
                            format!(
                                "{shown} line {line}, column {col}: `{s}` is not a finite number"
                            ),
                        )
                    })
            })
            .collect::<Result<Vec<f64>, Error>>()?;
        rows.push((line, v));
    }
    if rows.is_empty() {
        return Err(err(
            scenario,
            field,
            format!("{shown}: no rows after the header"),
        ));
    }
    Ok((which, rows))
}

/// Reads a route table. `scenario` and `field` name where it was referred from.
pub fn read(file: &Path, scenario: &Path, field: &str) -> Result<Route, Error> {
    let shown = file.display();
    let rows = read_numbers(file, scenario, field, "route", &["t", "x", "y", "z"])?;
    let (mut ts, mut ps) = (Vec::new(), Vec::new());
    for (line, v) in rows {
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
    Ok(Route::Table { t: ts, p: ps })
}
