//! `cablesim._cablesim`: the Python extension module of cablesim (PyO3).
//!
//! The pure-Python package `cablesim` (python/cablesim/) re-exports what this module
//! defines; its stubs (`_cablesim.pyi`) state the Python signatures. One Rust module per
//! Python class or concern, each with a `register` function called below, so that a new
//! part (studies, for one) is a new module and one more line here.

mod arrays;
mod errors;
mod output;
mod select;
mod simulation;
mod snapshot;

use pyo3::prelude::*;

/// Fast lumped-mass dynamics of underwater cables (mooring lines, towed cables, nets).
#[pymodule]
fn _cablesim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    simulation::register(m)?;
    snapshot::register(m)?;
    output::register(m)?;
    Ok(())
}
