//! `[output]`: which cables' node positions are written (`positions`), and in which
//! format the tables are (`format`).

use super::err;
use crate::error::Error;
use std::path::Path;

/// The cables whose positions are written: `auto` (all when there are at most 20),
/// all, none, or those named.
pub(super) enum Selection {
    Auto,
    All,
    None,
    Names(Vec<String>),
}

pub(super) fn output_selection(p: &Path, v: &Option<toml::Value>) -> Result<Selection, Error> {
    let f = "output.positions";
    Ok(match v {
        None => Selection::Auto,
        Some(toml::Value::String(s)) => match s.as_str() {
            "auto" => Selection::Auto,
            "all" => Selection::All,
            "none" => Selection::None,
            _ => {
                return Err(err(
                    p,
                    f,
                    format!(
                        "must be \"auto\", \"all\", \"none\" or a list of cable names, got \"{s}\""
                    ),
                ))
            }
        },
        Some(toml::Value::Array(a)) => Selection::Names(
            a.iter()
                .map(|x| {
                    x.as_str()
                        .map(str::to_string)
                        .ok_or_else(|| err(p, f, "list entries must be cable names (strings)"))
                })
                .collect::<Result<_, _>>()?,
        ),
        Some(_) => {
            return Err(err(
                p,
                f,
                "must be \"auto\", \"all\", \"none\" or a list of cable names",
            ))
        }
    })
}

/// `[output] format`: `"csv"` or `"parquet"`; Parquet in a build without the `parquet`
/// feature is an error that says so.
pub(super) fn output_format(
    p: &Path,
    v: &Option<String>,
) -> Result<crate::options::OutputFormat, Error> {
    let Some(s) = v else {
        return Ok(Default::default());
    };
    let f: crate::options::OutputFormat =
        crate::options::parse_option(s).map_err(|m| err(p, "output.format", m))?;
    f.check_available()
        .map_err(|m| err(p, "output.format", m))?;
    Ok(f)
}
