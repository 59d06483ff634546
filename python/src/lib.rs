//! `cablesim._cablesim`: the Python extension module of cablesim (PyO3).
//!
//! The pure-Python package `cablesim` (python/cablesim/) re-exports what this module
//! defines; its stubs (`_cablesim.pyi`) state the Python signatures. One Rust module per
//! Python class or concern, each with a `register` function called below. A new part
//! (studies, for one) is: a module here with its `register`, one line below, its names
//! in `cablesim/__init__.py`, its stubs in `cablesim/_cablesim.pyi`, its tests in
//! `tests/`. Library errors go through `errors::to_py` (or `.py(py)` on a result), and
//! arrays through `arrays`; long work runs under `py.detach` in chunks with
//! `py.check_signals()` between them, as `simulation::advance_chunked` does.

mod arrays;
mod errors;
mod output;
mod select;
mod simulation;
mod snapshot;
mod study;

use pyo3::prelude::*;

/// Fast lumped-mass dynamics of underwater cables (mooring lines, towed cables, nets).
#[pymodule]
fn _cablesim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    simulation::register(m)?;
    snapshot::register(m)?;
    output::register(m)?;
    study::register(m)?;
    Ok(())
}
