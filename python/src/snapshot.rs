//! `Snapshot` and `BodyState`: every cable's (and body's) state at one time, read as
//! numpy arrays.

use crate::arrays::{scalars, vec3, vec3s};
use crate::select::{index, Which};
use cablesim::output::BodyState;
use cablesim::sim::CableEnd;
use cablesim::Snapshot;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The state of every cable (and vessel body) at one time: a copy, which later steps do
/// not change. Cables are chosen by index (scenario order) or name.
#[pyclass(name = "Snapshot", module = "cablesim", frozen)]
pub struct PySnapshot {
    pub inner: Snapshot,
}

impl PySnapshot {
    pub fn cable(&self, which: &Which) -> PyResult<&cablesim::output::CableState> {
        let names: Vec<&str> = self.inner.cables.iter().map(|c| c.name.as_str()).collect();
        Ok(&self.inner.cables[index(which, &names, "cable")?])
    }

    /// A body's state, by index or name.
    pub fn body_of(&self, which: &Which) -> PyResult<PyBodyState> {
        Ok(PyBodyState {
            inner: self.body_state(which)?.clone(),
        })
    }

    fn body_state(&self, which: &Which) -> PyResult<&BodyState> {
        let names: Vec<&str> = self.inner.bodies.iter().map(|b| b.name.as_str()).collect();
        Ok(&self.inner.bodies[index(which, &names, "body")?])
    }
}

#[pymethods]
impl PySnapshot {
    /// Simulated time, s.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time
    }

    /// Steps taken.
    #[getter]
    fn steps(&self) -> u64 {
        self.inner.steps
    }

    /// Cable names, in scenario order.
    #[getter]
    fn cable_names(&self) -> Vec<String> {
        self.inner.cables.iter().map(|c| c.name.clone()).collect()
    }

    /// Names of the vessel bodies that cable ends are attached to.
    #[getter]
    fn body_names(&self) -> Vec<String> {
        self.inner.bodies.iter().map(|b| b.name.clone()).collect()
    }

    /// Node positions of a cable, start to end: `(nodes, 3)`, m.
    fn positions<'py>(&self, py: Python<'py>, cable: Which) -> PyResult<Bound<'py, PyArray2<f64>>> {
        Ok(vec3s(py, &self.cable(&cable)?.positions))
    }

    /// Node velocities of a cable, start to end: `(nodes, 3)`, m/s.
    fn velocities<'py>(
        &self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        Ok(vec3s(py, &self.cable(&cable)?.velocities))
    }

    /// Axial force per element of a cable, start to end: `(nodes - 1,)`, N.
    fn tensions<'py>(&self, py: Python<'py>, cable: Which) -> PyResult<Bound<'py, PyArray1<f64>>> {
        Ok(scalars(py, &self.cable(&cable)?.tensions))
    }

    /// The forces a cable exerts on its end supports: `(2, 3)`, row 0 the start, row 1
    /// the end, N.
    fn end_forces<'py>(
        &self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let f = &self.cable(&cable)?.end_forces;
        Ok(vec3s(py, &[f.start, f.end]))
    }

    /// The force a cable exerts on the support at one end (`"start"` or `"end"`):
    /// `(3,)`, N.
    #[pyo3(signature = (cable, end = "end"))]
    fn end_force<'py>(
        &self,
        py: Python<'py>,
        cable: Which,
        end: &str,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let f = &self.cable(&cable)?.end_forces;
        Ok(vec3(
            py,
            match crate::select::end(end)? {
                CableEnd::Start => f.start,
                CableEnd::End => f.end,
            },
        ))
    }

    /// A winch cable's state (`deployed_length` and `variable_l0` in m, `elements`,
    /// `nodes_inserted`, `nodes_deleted`, `physical_coordinates` in m), or None for a
    /// cable without a winch.
    fn winch<'py>(&self, py: Python<'py>, cable: Which) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(w) = &self.cable(&cable)?.winch else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("deployed_length", w.deployed_length)?;
        d.set_item("variable_l0", w.variable_l0)?;
        d.set_item("elements", w.elements)?;
        d.set_item("nodes_inserted", w.nodes_inserted)?;
        d.set_item("nodes_deleted", w.nodes_deleted)?;
        d.set_item("physical_coordinates", scalars(py, &w.physical_coordinates))?;
        Ok(Some(d))
    }

    /// A vessel body's pose and the load its cables exert on it, by index or name.
    fn body(&self, body: Which) -> PyResult<PyBodyState> {
        self.body_of(&body)
    }

    fn __repr__(&self) -> String {
        format!(
            "Snapshot(time={}, steps={}, cables={}, bodies={})",
            self.inner.time,
            self.inner.steps,
            self.inner.cables.len(),
            self.inner.bodies.len()
        )
    }
}

/// A vessel body's pose and the load its cables exert on it, at one time.
#[pyclass(name = "BodyState", module = "cablesim", frozen)]
pub struct PyBodyState {
    inner: BodyState,
}

#[pymethods]
impl PyBodyState {
    /// Name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }

    /// Reference point: `(3,)`, m.
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, self.inner.position)
    }

    /// Roll, pitch and yaw (the yaw includes the mean heading): `(3,)`, degrees.
    #[getter]
    fn angles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, self.inner.angles)
    }

    /// Total force of the cables on the body: `(3,)`, N.
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, self.inner.force)
    }

    /// Their moment about the reference point: `(3,)`, N m.
    #[getter]
    fn moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, self.inner.moment)
    }

    fn __repr__(&self) -> String {
        format!(
            "BodyState(name={:?}, position={:?})",
            self.inner.name, self.inner.position
        )
    }
}

/// Adds the classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySnapshot>()?;
    m.add_class::<PyBodyState>()?;
    Ok(())
}
