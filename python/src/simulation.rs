//! `Simulation`: build a scenario's simulation, step it (the GIL released, Ctrl-C
//! checked between chunks), drive a held end from outside, read its state.

use crate::errors::{to_py, IntoPy};
use crate::output::{summary_dict, PyRunOutput};
use crate::select::{self, index, Which};
use crate::snapshot::{PyBodyState, PySnapshot};
use cablesim::options::{Backend, FormulationChoice, Precision, Scheme};
use cablesim::output::{OutputSink, Summary};
use cablesim::{Error, FileSink, MemorySink, Overrides, Simulation};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyType;
use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

/// Node-steps stepped between two looks at Python's signals (Ctrl-C): about a tenth of
/// a second on one core, short enough to stop promptly, long enough that the checks and
/// the GIL hand-overs cost nothing measurable.
const CHUNK_NODE_STEPS: u64 = 2_000_000;

/// A scenario being simulated.
///
/// Build one with `Simulation.from_file(path)` (a TOML scenario or a MoorDyn input
/// file) or `Simulation.from_toml(text)`; keyword arguments override the scenario's
/// `[simulation]` settings. Then run it to the end (`run`), or step it (`advance`,
/// `advance_to`) and read its state in between (`snapshot`, `end_force`, ...), driving
/// held ends from outside (`set_end_motion`) as a coupling loop does.
#[pyclass(name = "Simulation", module = "cablesim")]
pub struct PySimulation {
    /// The simulation; the lock makes the class shareable between Python threads (the
    /// stepping itself holds it through `&mut self`).
    cell: Mutex<Simulation>,
    cable_names: Vec<String>,
    body_names: Vec<String>,
    /// Steps per chunk between signal checks.
    chunk: u64,
    /// The duration the run goes to, s (the scenario's or the override).
    duration: f64,
}

/// The overrides from the keyword arguments.
#[allow(clippy::too_many_arguments)]
fn overrides(
    backend: Option<&str>,
    precision: Option<&str>,
    scheme: Option<&str>,
    formulation: Option<&str>,
    dt: Option<f64>,
    duration: Option<f64>,
) -> PyResult<Overrides> {
    let mut ov = Overrides {
        backend: select::option::<Backend>("backend", backend)?,
        precision: select::option::<Precision>("precision", precision)?,
        scheme: select::option::<Scheme>("scheme", scheme)?,
        dt,
        duration,
        ..Overrides::default()
    };
    if let Some(f) = select::option::<FormulationChoice>("formulation", formulation)? {
        ov = ov.with_formulation(f);
    }
    Ok(ov)
}

impl PySimulation {
    /// Builds (the initial relaxation can take a while: the GIL is released) and reads
    /// the names and size once.
    fn build(
        py: Python<'_>,
        ov: Overrides,
        make: impl FnOnce(&Overrides) -> Result<Simulation, Error> + Send,
    ) -> PyResult<Self> {
        let mut sim = py.detach(|| make(&ov)).py(py)?;
        let first = sim.snapshot().py(py)?;
        let nodes: usize = first.cables.iter().map(|c| c.positions.len()).sum();
        let duration = ov.duration.unwrap_or(sim.scenario().sim.duration);
        Ok(Self {
            cable_names: first.cables.iter().map(|c| c.name.clone()).collect(),
            body_names: first.bodies.iter().map(|b| b.name.clone()).collect(),
            chunk: (CHUNK_NODE_STEPS / nodes.max(1) as u64).max(1),
            duration,
            cell: Mutex::new(sim),
        })
    }

    /// The simulation, for a method that holds the object mutably.
    fn sim(&mut self) -> &mut Simulation {
        // A panic inside a step poisons the lock; the state is still what it was.
        self.cell.get_mut().unwrap_or_else(|p| p.into_inner())
    }

    /// The simulation, for a method that only reads.
    fn lock(&self) -> MutexGuard<'_, Simulation> {
        self.cell.lock().unwrap_or_else(|p| p.into_inner())
    }

    fn cable(&self, which: &Which) -> PyResult<usize> {
        let names: Vec<&str> = self.cable_names.iter().map(String::as_str).collect();
        index(which, &names, "cable")
    }

    /// Advances `n` steps in chunks, the GIL released during each and the signals
    /// checked after it (Ctrl-C raises KeyboardInterrupt between chunks).
    fn advance_chunked(&mut self, py: Python<'_>, n: u64) -> Result<(), Stop> {
        let target = self.sim().steps() + n;
        while self.sim().steps() < target {
            let k = self.chunk.min(target - self.sim().steps());
            let sim = self.sim();
            py.detach(|| sim.advance(k)).map_err(Stop::Lib)?;
            py.check_signals().map_err(Stop::Py)?;
        }
        Ok(())
    }

    /// Runs on to the end into `sink`: a frame now and at each output time, then the
    /// summary (also after a blow-up, whose error is then raised), as
    /// `cablesim::Simulation::run` does, but in chunks that let Ctrl-C through.
    fn run_into(
        &mut self,
        py: Python<'_>,
        sink: &mut (dyn OutputSink + Send),
    ) -> PyResult<Summary> {
        let Some(plan) = self.sim().plan().cloned() else {
            // The ANCF model: one call, its cables each at their own step.
            let sim = self.sim();
            return py.detach(|| sim.run(sink, |_| {})).py(py);
        };
        sink.frame(&self.sim().snapshot().py(py)?).py(py)?;
        while self.sim().steps() < plan.total_steps {
            let done = self.sim().steps();
            let next = ((done / plan.steps_per_output) + 1) * plan.steps_per_output;
            let target = next.min(plan.total_steps);
            match self.advance_chunked(py, target - done) {
                Ok(()) => {}
                // A blow-up still closes the output with a summary that says so.
                Err(Stop::Lib(e)) => {
                    let summary = self.sim().summary(Some(&e)).py(py)?;
                    sink.finish(&summary).py(py)?;
                    return Err(to_py(py, e));
                }
                // An interrupt leaves what was written.
                Err(Stop::Py(e)) => return Err(e),
            }
            sink.frame(&self.sim().snapshot().py(py)?).py(py)?;
        }
        let summary = self.sim().summary(None).py(py)?;
        sink.finish(&summary).py(py)?;
        Ok(summary)
    }
}

/// Why chunked stepping stopped: the library's error, or Python's (Ctrl-C).
enum Stop {
    Lib(Error),
    Py(PyErr),
}

impl Stop {
    fn py(self, py: Python<'_>) -> PyErr {
        match self {
            Stop::Lib(e) => to_py(py, e),
            Stop::Py(e) => e,
        }
    }
}

#[pymethods]
impl PySimulation {
    /// Reads a scenario file (TOML, or a MoorDyn input file) and builds its simulation.
    ///
    /// Keyword arguments override the scenario's `[simulation]` settings: `backend`
    /// ("auto", "cpu", "gpu"), `precision` ("f32", "f64"), `scheme` ("symplectic",
    /// "rk2", "rk4"), `formulation` ("glmf", "rvef", "euler", "frenet", "ancf"), `dt`
    /// (s) and `duration` (s). A wrong scenario raises ScenarioError naming the file
    /// and the field.
    #[classmethod]
    #[pyo3(signature = (path, *, backend=None, precision=None, scheme=None, formulation=None, dt=None, duration=None))]
    #[allow(clippy::too_many_arguments)]
    fn from_file(
        _cls: &Bound<'_, PyType>,
        py: Python<'_>,
        path: PathBuf,
        backend: Option<&str>,
        precision: Option<&str>,
        scheme: Option<&str>,
        formulation: Option<&str>,
        dt: Option<f64>,
        duration: Option<f64>,
    ) -> PyResult<Self> {
        let ov = overrides(backend, precision, scheme, formulation, dt, duration)?;
        Self::build(py, ov, |ov| Simulation::from_file(&path, ov))
    }

    /// Builds the simulation of scenario text (TOML). `name` stands for the file in
    /// messages and the summary, and relative route and motion files are read beside
    /// it. Keyword arguments as for `from_file`.
    #[classmethod]
    #[pyo3(signature = (text, *, name=None, backend=None, precision=None, scheme=None, formulation=None, dt=None, duration=None))]
    #[allow(clippy::too_many_arguments)]
    fn from_toml(
        _cls: &Bound<'_, PyType>,
        py: Python<'_>,
        text: &str,
        name: Option<PathBuf>,
        backend: Option<&str>,
        precision: Option<&str>,
        scheme: Option<&str>,
        formulation: Option<&str>,
        dt: Option<f64>,
        duration: Option<f64>,
    ) -> PyResult<Self> {
        let ov = overrides(backend, precision, scheme, formulation, dt, duration)?;
        let text = text.to_owned();
        let name = name.unwrap_or_else(|| PathBuf::from("scenario.toml"));
        Self::build(py, ov, |ov| Simulation::from_toml(&text, &name, ov))
    }

    /// Simulated time, s.
    #[getter]
    fn time(&self) -> f64 {
        self.lock().time()
    }

    /// Steps taken.
    #[getter]
    fn steps(&self) -> u64 {
        self.lock().steps()
    }

    /// The time step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.lock().dt()
    }

    /// The time `run` goes to, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.duration
    }

    /// Time between output times, s.
    #[getter]
    fn output_interval(&self) -> f64 {
        self.lock().scenario().sim.output_interval
    }

    /// The backend that runs: "cpu" or "gpu".
    #[getter]
    fn backend(&self) -> &'static str {
        self.lock().describe().0
    }

    /// The CPU or GPU adapter that runs.
    #[getter]
    fn device(&self) -> String {
        self.lock().describe().1
    }

    /// The arithmetic: "f64" or "f32".
    #[getter]
    fn precision(&self) -> &'static str {
        self.lock().describe().2
    }

    /// Cable names, in scenario order.
    #[getter]
    fn cable_names(&self) -> Vec<String> {
        self.cable_names.clone()
    }

    /// Names of the vessel bodies that cable ends are attached to.
    #[getter]
    fn body_names(&self) -> Vec<String> {
        self.body_names.clone()
    }

    /// Advances `steps` time steps.
    fn advance(&mut self, py: Python<'_>, steps: u64) -> PyResult<()> {
        if self.sim().plan().is_none() {
            let sim = self.sim();
            return py.detach(|| sim.advance(steps)).py(py);
        }
        self.advance_chunked(py, steps).map_err(|e| e.py(py))
    }

    /// Advances to time `t` (s), to the step nearest it; a time already passed does
    /// nothing.
    fn advance_to(&mut self, py: Python<'_>, t: f64) -> PyResult<()> {
        let Some(dt) = self.sim().plan().map(|p| p.dt) else {
            let sim = self.sim();
            return py.detach(|| sim.advance_to(t)).py(py);
        };
        // The step nearest `t`, as the library's advance_to counts it.
        let target = (t / dt).round().max(0.0) as u64;
        let n = target.saturating_sub(self.sim().steps());
        self.advance_chunked(py, n).map_err(|e| e.py(py))
    }

    /// Runs on to the end of the duration. With `out_dir`, writes the output files
    /// there (`end_forces.csv`, `tensions.csv`, ..., `summary.json`, as the command
    /// line does; `format` "csv" or "parquet", default the scenario's `[output]
    /// format`) and returns the summary as a dict; without, keeps every output time
    /// in memory and returns a RunOutput. A blow-up raises DivergedError (the files
    /// then end with a summary whose status is "diverged").
    #[pyo3(signature = (out_dir=None, format=None))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        out_dir: Option<PathBuf>,
        format: Option<&str>,
    ) -> PyResult<Py<PyAny>> {
        let format = crate::select::option::<cablesim::options::OutputFormat>("format", format)?
            .unwrap_or(self.sim().scenario().output_format);
        match out_dir {
            Some(dir) => {
                let mut sink = FileSink::new(dir).format(format).py(py)?;
                let summary = self.run_into(py, &mut sink)?;
                Ok(summary_dict(py, &summary)?.unbind())
            }
            None => {
                let mut sink = MemorySink::new();
                let summary = self.run_into(py, &mut sink)?;
                let out = PyRunOutput {
                    summary,
                    frames: sink.frames,
                };
                Ok(Bound::new(py, out)?.into_any().unbind())
            }
        }
    }

    /// Every cable's (and body's) state now, as a Snapshot (a copy).
    fn snapshot(&mut self, py: Python<'_>) -> PyResult<PySnapshot> {
        Ok(PySnapshot {
            inner: self.sim().snapshot().py(py)?,
        })
    }

    /// Node positions of a cable now: `(nodes, 3)`, m.
    fn positions<'py>(
        &mut self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.cable(&cable)?;
        let s = self.snapshot(py)?;
        Ok(crate::arrays::vec3s(py, &s.cable(&cable)?.positions))
    }

    /// Node velocities of a cable now: `(nodes, 3)`, m/s.
    fn velocities<'py>(
        &mut self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.cable(&cable)?;
        let s = self.snapshot(py)?;
        Ok(crate::arrays::vec3s(py, &s.cable(&cable)?.velocities))
    }

    /// Axial force per element of a cable now: `(nodes - 1,)`, N.
    fn tensions<'py>(
        &mut self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.cable(&cable)?;
        let s = self.snapshot(py)?;
        Ok(crate::arrays::scalars(py, &s.cable(&cable)?.tensions))
    }

    /// The forces a cable exerts on its end supports now: `(2, 3)`, row 0 the start,
    /// row 1 the end, N.
    fn end_forces<'py>(
        &mut self,
        py: Python<'py>,
        cable: Which,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.cable(&cable)?;
        let s = self.snapshot(py)?;
        let f = &s.cable(&cable)?.end_forces;
        Ok(crate::arrays::vec3s(py, &[f.start, f.end]))
    }

    /// The force a cable exerts now on the support at one end (`"start"` or `"end"`),
    /// as a coupling loop reads it back: `(3,)`, N.
    #[pyo3(signature = (cable, end = "end"))]
    fn end_force<'py>(
        &mut self,
        py: Python<'py>,
        cable: Which,
        end: &str,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let e = select::end(end)?;
        self.cable(&cable)?;
        let s = self.snapshot(py)?;
        let f = &s.cable(&cable)?.end_forces;
        Ok(crate::arrays::vec3(
            py,
            match e {
                cablesim::sim::CableEnd::Start => f.start,
                cablesim::sim::CableEnd::End => f.end,
            },
        ))
    }

    /// A vessel body's pose and cable load now.
    fn body(&mut self, py: Python<'_>, body: Which) -> PyResult<PyBodyState> {
        let names: Vec<&str> = self.body_names.iter().map(String::as_str).collect();
        index(&body, &names, "body")?;
        self.snapshot(py)?.body_of(&body)
    }

    /// Drives one end (`"start"` or `"end"`) of a cable from outside, as a coupling
    /// loop does (MoorDyn's API: set the fairlead, step, read the force back): from now
    /// until the next call its target moves from `position` (m) at `velocity` (m/s;
    /// None: at rest) in a straight line, and the end node follows it. The end must be held in the
    /// scenario (`fixed` or on a route); lumped-mass model on the CPU backend
    /// (`backend="cpu"`; the GPU path raises GpuError).
    #[pyo3(signature = (cable, end, position, velocity=None))]
    fn set_end_motion(
        &mut self,
        py: Python<'_>,
        cable: Which,
        end: &str,
        position: [f64; 3],
        velocity: Option<[f64; 3]>,
    ) -> PyResult<()> {
        let c = self.cable(&cable)?;
        let e = select::end(end)?;
        let v = velocity.unwrap_or([0.0; 3]);
        self.sim().set_end_motion(c, e, position, v).py(py)
    }

    /// The summary of the run so far (the content of `summary.json`) as a dict.
    fn summary<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let s = self.sim().summary(None).py(py)?;
        summary_dict(py, &s)
    }

    fn __repr__(&self) -> String {
        let sim = self.lock();
        format!(
            "Simulation(cables={}, time={}, steps={}, dt={:e})",
            self.cable_names.len(),
            sim.time(),
            sim.steps(),
            sim.dt()
        )
    }
}

/// Adds the class to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySimulation>()
}
