//! `RunOutput`: a run kept in memory (`Simulation.run()` without a directory), read as
//! time series.

use crate::arrays::{stack2, stack3, times};
use crate::select::{index, Which};
use crate::snapshot::PySnapshot;
use cablesim::output::Summary;
use cablesim::Snapshot;
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::PyIndexError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Every output time of a run (`t = 0` first) and its summary. Series come as arrays
/// with the output time first: `positions(cable)` is `(frames, nodes, 3)`.
#[pyclass(name = "RunOutput", module = "cablesim", frozen)]
pub struct PyRunOutput {
    pub frames: Vec<Snapshot>,
    pub summary: Summary,
}

impl PyRunOutput {
    fn cable_index(&self, which: &Which) -> PyResult<usize> {
        let names: Vec<&str> = self
            .frames
            .first()
            .map(|f| f.cables.iter().map(|c| c.name.as_str()).collect())
            .unwrap_or_default();
        index(which, &names, "cable")
    }

    fn body_index(&self, which: &Which) -> PyResult<usize> {
        let names: Vec<&str> = self
            .frames
            .first()
            .map(|f| f.bodies.iter().map(|b| b.name.as_str()).collect())
            .unwrap_or_default();
        index(which, &names, "body")
    }
}

/// The summary (`summary.json`'s content) as a Python dict.
pub fn summary_dict<'py>(py: Python<'py>, s: &Summary) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(s).expect("the summary serialises");
    py.import("json")?.call_method1("loads", (text,))
}

#[pymethods]
impl PyRunOutput {
    /// Output times: `(frames,)`, s.
    #[getter]
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        times(py, self.frames.iter().map(|f| f.time).collect())
    }

    /// The run's summary, the content of `summary.json` (status, backend, dt, steps,
    /// wall time, per-cable final state, ...).
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        summary_dict(py, &self.summary)
    }

    /// Cable names, in scenario order.
    #[getter]
    fn cable_names(&self) -> Vec<String> {
        self.frames
            .first()
            .map(|f| f.cables.iter().map(|c| c.name.clone()).collect())
            .unwrap_or_default()
    }

    fn __len__(&self) -> usize {
        self.frames.len()
    }

    /// The state at output time `i` (negative from the last).
    fn frame(&self, i: i64) -> PyResult<PySnapshot> {
        let n = self.frames.len() as i64;
        let k = if i < 0 { i + n } else { i };
        if !(0..n).contains(&k) {
            return Err(PyIndexError::new_err(format!(
                "frame {i} out of range (there are {n})"
            )));
        }
        Ok(PySnapshot {
            inner: self.frames[k as usize].clone(),
        })
    }

    /// Node positions of a cable at each output time: `(frames, nodes, 3)`, m.
    fn positions<'py>(&self, py: Python<'py>, cable: Which) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let c = self.cable_index(&cable)?;
        let rows = self
            .frames
            .iter()
            .map(|f| f.cables[c].positions.clone())
            .collect();
        stack3(py, rows, "positions")
    }

    /// Node velocities of a cable at each output time: `(frames, nodes, 3)`, m/s.
    fn velocities<'py>(
        &self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let c = self.cable_index(&cable)?;
        let rows = self
            .frames
            .iter()
            .map(|f| f.cables[c].velocities.clone())
            .collect();
        stack3(py, rows, "velocities")
    }

    /// Axial force per element of a cable at each output time: `(frames, nodes - 1)`, N.
    fn tensions<'py>(&self, py: Python<'py>, cable: Which) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let c = self.cable_index(&cable)?;
        let rows = self
            .frames
            .iter()
            .map(|f| f.cables[c].tensions.clone())
            .collect();
        stack2(py, rows, "tensions")
    }

    /// The forces a cable exerts on its end supports at each output time:
    /// `(frames, 2, 3)`, `[:, 0]` the start and `[:, 1]` the end, N.
    fn end_forces<'py>(
        &self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let c = self.cable_index(&cable)?;
        let rows = self
            .frames
            .iter()
            .map(|f| vec![f.cables[c].end_forces.start, f.cables[c].end_forces.end])
            .collect();
        stack3(py, rows, "end forces")
    }

    /// A vessel body's series at each output time, a dict of `(frames, 3)` arrays:
    /// `position` (m), `angles` (roll, pitch, yaw, degrees), `force` (N) and `moment`
    /// (N m about the reference point) of its cables on it.
    fn body<'py>(&self, py: Python<'py>, body: Which) -> PyResult<Bound<'py, PyDict>> {
        let b = self.body_index(&body)?;
        let d = PyDict::new(py);
        let series = |get: fn(&cablesim::output::BodyState) -> [f64; 3]| -> Vec<Vec<f64>> {
            self.frames
                .iter()
                .map(|f| get(&f.bodies[b]).to_vec())
                .collect()
        };
        d.set_item("position", stack2(py, series(|s| s.position), "body")?)?;
        d.set_item("angles", stack2(py, series(|s| s.angles), "body")?)?;
        d.set_item("force", stack2(py, series(|s| s.force), "body")?)?;
        d.set_item("moment", stack2(py, series(|s| s.moment), "body")?)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "RunOutput(frames={}, status={:?})",
            self.frames.len(),
            self.summary.status
        )
    }
}

/// Adds the class to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRunOutput>()
}
