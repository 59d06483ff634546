//! Arguments as Python passes them: a cable or body by name or index, a cable end by
//! name, run options by the names the command line uses.

use cablesim::sim::CableEnd;
use pyo3::exceptions::{PyIndexError, PyKeyError, PyValueError};
use pyo3::prelude::*;

/// A cable or body as Python names it: its index (negative from the last, as in a
/// list) or its name.
#[derive(FromPyObject)]
pub enum Which {
    /// Index in scenario order.
    Index(i64),
    /// Name.
    Name(String),
}

/// The index of `which` among `names`; `what` ("cable", "body") names the kind in
/// messages.
pub fn index(which: &Which, names: &[&str], what: &str) -> PyResult<usize> {
    match which {
        Which::Index(i) => {
            let n = names.len() as i64;
            let k = if *i < 0 { i + n } else { *i };
            if (0..n).contains(&k) {
                Ok(k as usize)
            } else {
                Err(PyIndexError::new_err(format!(
                    "{what} index {i} out of range (there are {n})"
                )))
            }
        }
        Which::Name(s) => names.iter().position(|n| n == s).ok_or_else(|| {
            PyKeyError::new_err(format!(
                "no {what} named '{s}' (there are: {})",
                names.join(", ")
            ))
        }),
    }
}

/// A cable end: `"start"` (its first node) or `"end"` (its last).
pub fn end(s: &str) -> PyResult<CableEnd> {
    match s {
        "start" => Ok(CableEnd::Start),
        "end" => Ok(CableEnd::End),
        _ => Err(PyValueError::new_err(format!(
            "end: must be \"start\" or \"end\", got \"{s}\""
        ))),
    }
}

/// A run option by name (`backend="cpu"`), with the message naming the argument and the
/// names allowed.
pub fn option<T: clap::ValueEnum>(arg: &str, value: Option<&str>) -> PyResult<Option<T>> {
    value
        .map(|s| {
            cablesim::options::parse_option::<T>(s)
                .map_err(|m| PyValueError::new_err(format!("{arg}: {m}")))
        })
        .transpose()
}
