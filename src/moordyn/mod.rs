//! MoorDyn input files (v1 and v2): read ([`parse()`]) and mapped to an equivalent
//! cablesim scenario ([`convert()`]), written as scenario TOML with a comment on every
//! mapping choice. `cablesim run model.dat` runs one through
//! [`Scenario::load_any`](crate::scenario::Scenario::load_any); `cablesim convert model.dat -o model.toml` writes the
//! TOML. docs/src/moordyn.md lists what is read, how each field maps and what is refused.

mod bodies;
pub mod convert;
mod options;
pub mod parse;
mod tables;
pub mod waves;

pub use convert::{convert, ConvertOptions, Converted};
pub use parse::{looks_like_moordyn, parse, MoorDynFile, Version};

use crate::error::Error;
use std::path::Path;

/// Something dropped or approximated, at a line of the file (here, not in `convert.rs`,
/// whose helpers `options.rs` and `tables.rs` report it: no import circle).
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    /// 1-based line number (0: the file as a whole).
    pub line: usize,
    /// What was dropped or approximated, and its effect.
    pub message: String,
}

/// Builds the error for line `line` (1-based; 0 = the file as a whole) of a MoorDyn
/// file: the field names the line and the column or option.
#[doc(hidden)]
pub fn err_at(
    path: &Path,
    line: usize,
    what: impl AsRef<str>,
    message: impl Into<String>,
) -> Error {
    let field = if line == 0 {
        what.as_ref().to_string()
    } else {
        format!("line {line}: {}", what.as_ref())
    };
    Error::Scenario {
        path: path.to_path_buf(),
        field,
        message: message.into(),
    }
}

/// True when the file at `path` with text `text` is to be read as a MoorDyn input
/// file: a `.toml` name never is; any other is when its content has MoorDyn's
/// `--- LINE TYPES ---` and `--- LINES ---` section headers.
pub fn is_moordyn(path: &Path, text: &str) -> bool {
    let toml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    !toml && looks_like_moordyn(text)
}

/// Reads and converts a MoorDyn input file's text (`path` names it in messages).
pub fn convert_text(text: &str, path: &Path, opts: &ConvertOptions) -> Result<Converted, Error> {
    let file = parse(text, path)?;
    convert(&file, path, opts)
}
