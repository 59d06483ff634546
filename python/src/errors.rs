//! The library's errors as Python exceptions, with the message the command line prints
//! and, where the error has them, its parts as attributes (`ScenarioError.field`).

use cablesim::Error;
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    cablesim,
    CablesimError,
    PyException,
    "Base class of every error cablesim raises (besides ValueError, KeyError and \
     IndexError for a wrong argument)."
);
create_exception!(
    cablesim,
    ScenarioError,
    CablesimError,
    "A scenario is wrong: `path` (the file), `field` (dotted path such as \
     `cables[2].length`) and `message` (what is wrong) say where and what."
);
create_exception!(
    cablesim,
    DivergedError,
    CablesimError,
    "The simulation blew up: `cable`, `node` and `time` (s) say where and when."
);
create_exception!(
    cablesim,
    GpuError,
    CablesimError,
    "No usable GPU adapter, a GPU failure, or something the GPU path does not do \
     (driving an end from outside, for one: use backend=\"cpu\")."
);
create_exception!(
    cablesim,
    OutputError,
    CablesimError,
    "Writing an output file failed: `path` is the file."
);

/// Adds the exception classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("CablesimError", py.get_type::<CablesimError>())?;
    m.add("ScenarioError", py.get_type::<ScenarioError>())?;
    m.add("DivergedError", py.get_type::<DivergedError>())?;
    m.add("GpuError", py.get_type::<GpuError>())?;
    m.add("OutputError", py.get_type::<OutputError>())?;
    Ok(())
}

/// The Python exception of a library error.
pub fn to_py(py: Python<'_>, e: Error) -> PyErr {
    let message = e.to_string();
    let (err, attrs): (PyErr, Vec<(&str, Py<PyAny>)>) = match &e {
        Error::Scenario {
            path,
            field,
            message: what,
        } => (
            ScenarioError::new_err(message),
            vec![
                (
                    "path",
                    path.display()
                        .to_string()
                        .into_pyobject(py)
                        .unwrap()
                        .into_any()
                        .unbind(),
                ),
                (
                    "field",
                    field.into_pyobject(py).unwrap().into_any().unbind(),
                ),
                (
                    "message",
                    what.into_pyobject(py).unwrap().into_any().unbind(),
                ),
            ],
        ),
        Error::Diverged {
            cable, node, time, ..
        } => (
            DivergedError::new_err(message),
            vec![
                (
                    "cable",
                    cable.into_pyobject(py).unwrap().into_any().unbind(),
                ),
                ("node", node.into_pyobject(py).unwrap().into_any().unbind()),
                ("time", time.into_pyobject(py).unwrap().into_any().unbind()),
            ],
        ),
        Error::NoAdapter(_) | Error::Gpu(_) | Error::GpuUnsupported(_) => {
            (GpuError::new_err(message), vec![])
        }
        Error::Output { path, .. } => (
            OutputError::new_err(message),
            vec![(
                "path",
                path.display()
                    .to_string()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            )],
        ),
        _ => (CablesimError::new_err(message), vec![]),
    };
    let value = err.value(py);
    for (name, v) in attrs {
        // An attribute that cannot be set leaves the message, which says it all.
        let _ = value.setattr(name, v);
    }
    err
}

/// `.map_err` helper: a library result as a Python result.
pub trait IntoPy<T> {
    /// The result with its error as a Python exception.
    fn py(self, py: Python<'_>) -> PyResult<T>;
}

impl<T> IntoPy<T> for Result<T, Error> {
    fn py(self, py: Python<'_>) -> PyResult<T> {
        self.map_err(|e| to_py(py, e))
    }
}
