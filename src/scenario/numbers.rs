//! Checks of single numbers, and the error they report: each names the file, the
//! field and the value (`show` keeps long numbers short).

use crate::error::Error;
use std::path::Path;

/// Builds `Error::Scenario` for `path`.
pub(crate) fn err(path: &Path, field: impl Into<String>, message: impl Into<String>) -> Error {
    Error::Scenario {
        path: path.to_path_buf(),
        field: field.into(),
        message: message.into(),
    }
}

/// A number as a message shows it: plainly in the range people write by hand, in
/// exponent form outside it (`-1e160`, not a hundred and sixty digits).
pub(crate) fn show(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Checks a number is finite (TOML allows `nan` and `inf`).
pub(crate) fn finite(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
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

pub(crate) fn positive(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
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

pub(crate) fn non_negative(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
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

#[cfg(test)]
mod message_tests {
    use super::*;

    #[test]
    fn numbers_in_messages_are_short() {
        assert_eq!(show(9.81), "9.81");
        assert_eq!(show(-1e160), "-1e160");
        assert_eq!(show(2.5e-200), "2.5e-200");
        assert_eq!(show(0.0), "0");
        let e = non_negative(Path::new("m.toml"), "environment.gravity", -1e160).unwrap_err();
        let text = e.to_string();
        assert!(text.ends_with("must not be negative, got -1e160"), "{text}");
    }
}
