//! `[output] positions`: which cables' node positions are written.

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
