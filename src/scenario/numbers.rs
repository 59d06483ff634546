//! Checks of single numbers, and the error they report: each names the file, the
//! field and the value (`show` keeps long numbers short).

use crate::error::Error;
use std::path::Path;

/// Builds `Error::Scenario` for `path`.
pub fn err(path: &Path, field: impl Into<String>, message: impl Into<String>) -> Error {
    Error::Scenario {
        path: path.to_path_buf(),
        field: field.into(),
        message: message.into(),
    }
}

/// A number as a message shows it: plainly in the range people write by hand, in
/// exponent form outside it (`-1e160`, not a hundred and sixty digits).
pub fn show(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Checks a number is finite (TOML allows `nan` and `inf`).
pub fn finite(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(err(
            path,
            field,
            format!("must be a finite number, got {}", show(x)),
        ))
    }
}

/// `x` if it is finite and above zero, else an error naming `field` of `path`.
pub fn positive(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
    finite(path, field, x)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(err(
            path,
            field,
            format!("must be positive, got {}", show(x)),
        ))
    }
}

/// `x` if it is finite and not below zero, else an error naming `field` of `path`.
pub fn non_negative(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
    finite(path, field, x)?;
    if x >= 0.0 {
        Ok(x)
    } else {
        Err(err(
            path,
            field,
            format!("must not be negative, got {}", show(x)),
        ))
    }
}
