//! `cablesim.run_study`: a Monte Carlo sea-state study (the `[study]` table of
//! docs/src/studies.md) run from Python, as `cablesim study run` runs it, with its
//! tables written to a directory and returned.

use crate::errors::IntoPy;
use crate::select;
use cablesim::options::{Backend, Precision};
use cablesim::study::{merge, summarise, tables, PackedRun, ShardSpec, StudyFile, StudyRunner};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Runs every member of the study in `path` and writes `study.csv`, `members.csv` and
/// `study.json` into `out_dir` (and `fatigue.csv` for a base scenario with `[fatigue]`);
/// returns the content of `study.json` (a dict: per sea state and channel, the Gumbel
/// fits, the most probable maximum, the quantile and, with capacities, the
/// utilisation; with fatigue, `fatigue`: per location the damage per sea state, the
/// annual damage and the life). `backend` as `study run --backend`: "cpu" (the
/// default: each member its own run, members across all threads), "gpu" or "auto"
/// (members packed into one run, `batch` members at a time, `precision` "f32" or
/// "f64"). Ctrl-C stops the running members and raises KeyboardInterrupt (nothing is
/// written then).
#[pyfunction]
#[pyo3(signature = (path, out_dir, *, backend=None, precision=None, batch=None))]
fn run_study<'py>(
    py: Python<'py>,
    path: PathBuf,
    out_dir: PathBuf,
    backend: Option<&str>,
    precision: Option<&str>,
    batch: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    let backend = select::option::<Backend>("backend", backend)?.unwrap_or(Backend::Cpu);
    let precision = select::option::<Precision>("precision", precision)?;
    if batch == Some(0) {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "batch: must be at least 1",
        ));
    }
    let packed = (backend != Backend::Cpu).then_some(PackedRun {
        backend,
        precision,
        batch,
    });
    let study = StudyFile::load(&path).py(py)?;
    let runner = StudyRunner::new(&study).py(py)?;
    let plan = runner.plan();
    let members = plan
        .shard_members(ShardSpec::WHOLE, Path::new("shard"))
        .py(py)?;
    let stop = AtomicBool::new(false);
    // The members run on rayon's threads from a scoped thread, while this one waits
    // with the GIL released and checks for Ctrl-C every tenth of a second.
    let results = std::thread::scope(|s| {
        let job = s.spawn(|| match &packed {
            None => runner.run(&members, &stop, &|_| {}, &|_| Ok(())),
            Some(how) => runner.run_packed(&members, how, &stop, &|_| {}, &|_| Ok(())),
        });
        loop {
            if job.is_finished() {
                return Ok(job.join().expect("the study thread does not panic"));
            }
            py.detach(|| std::thread::sleep(Duration::from_millis(100)));
            if let Err(e) = py.check_signals() {
                stop.store(true, Ordering::SeqCst);
                let _ = job.join();
                return Err(e);
            }
        }
    })?
    .py(py)?;
    let shard = plan.shard_result(ShardSpec::WHOLE, results);
    let merged = merge(vec![(out_dir.join("shard.json"), shard)]).py(py)?;
    let summary = summarise(&merged);
    std::fs::create_dir_all(&out_dir).map_err(|e| {
        pyo3::exceptions::PyOSError::new_err(format!("cannot create {}: {e}", out_dir.display()))
    })?;
    tables::write_all(&out_dir, &merged, &summary).py(py)?;
    let text = std::fs::read_to_string(out_dir.join("study.json")).map_err(|e| {
        pyo3::exceptions::PyOSError::new_err(format!("cannot read study.json: {e}"))
    })?;
    py.import("json")?.call_method1("loads", (text,))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run_study, m)?)
}
