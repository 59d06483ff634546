//! Snapshot data as numpy arrays (float64, C order, copies the caller owns).

use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// `n` vectors as an `(n, 3)` array.
pub fn vec3s<'py>(py: Python<'py>, v: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flatten().copied().collect();
    Array2::from_shape_vec((v.len(), 3), flat)
        .expect("n rows of 3")
        .into_pyarray(py)
}

/// One vector as a `(3,)` array.
pub fn vec3<'py>(py: Python<'py>, v: [f64; 3]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, &v)
}

/// Scalars as a `(n,)` array.
pub fn scalars<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

/// One row per output time, each of the same length: a `(frames, n)` array.
/// A cable whose node count changes during the run (a winch) cannot be stacked: the
/// error says so and where to look instead.
pub fn stack2<'py>(
    py: Python<'py>,
    rows: Vec<Vec<f64>>,
    what: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = rows.first().map_or(0, Vec::len);
    check_same(&rows, n, what)?;
    let frames = rows.len();
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    Ok(Array2::from_shape_vec((frames, n), flat)
        .expect("frames rows of n")
        .into_pyarray(py))
}

/// One `(n, 3)` block per output time: a `(frames, n, 3)` array.
pub fn stack3<'py>(
    py: Python<'py>,
    rows: Vec<Vec<[f64; 3]>>,
    what: &str,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let n = rows.first().map_or(0, Vec::len);
    check_same(&rows, n, what)?;
    let frames = rows.len();
    let flat: Vec<f64> = rows.into_iter().flatten().flatten().collect();
    Ok(Array3::from_shape_vec((frames, n, 3), flat)
        .expect("frames blocks of n by 3")
        .into_pyarray(py))
}

fn check_same<T>(rows: &[Vec<T>], n: usize, what: &str) -> PyResult<()> {
    if let Some((k, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != n) {
        return Err(PyValueError::new_err(format!(
            "{what}: the count changes during the run ({n} at the first output time, {} at \
             output {k}: a winch inserts or deletes nodes); read each time with frame(i)",
            r.len()
        )));
    }
    Ok(())
}

/// Times as a `(frames,)` array.
pub fn times<'py>(py: Python<'py>, t: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    Array1::from_vec(t).into_pyarray(py)
}
