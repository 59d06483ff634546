//! The work budget of a run, checked against the step plan before anything runs: node-
//! steps (nodes times steps) and the size of the output files (frames times rows).
//! The model's memory is checked earlier, while the scenario is read
//! ([`crate::scenario::limits`]). Each refusal gives the estimate and how to raise the
//! budget (`[limits]`, `--limit`).

use super::estimate::{self, Estimate};
use crate::error::Error;
use crate::model::Layout;
use crate::options::SolverOptions;
use crate::scenario::limits::{how_to_raise, GIB};
use crate::scenario::{err, DtSpec, Scenario};
use crate::stability::{StepBound, AUTO_SAFETY};

/// Bytes of one `positions.csv` row (`t, cable, node, x, y, z`), about.
pub const BYTES_PER_POSITION_ROW: f64 = 80.0;
/// Bytes of one cable's rows per frame in the other files (end forces, tensions), about.
pub const BYTES_PER_CABLE_FRAME: f64 = 200.0;

/// Refuses a run of `steps` steps of `dt` s over `nodes` nodes beyond the node-step
/// budget; `term` says what sets the step (the ANCF model's check; a lumped-mass run
/// goes through [`check_lumped_node_steps`], whose message says more).
pub fn check_node_steps(
    sc: &Scenario,
    nodes: usize,
    duration: f64,
    dt: f64,
    term: &str,
) -> Result<(), Error> {
    let work = (duration / dt) * nodes as f64;
    refuse_over(
        sc,
        work,
        format!("{duration} s at dt = {dt:e} s over {nodes} nodes is {work:.3e} node-steps"),
        format!("the step is set by {term}: shorten the run, coarsen the mesh or change that term"),
    )
}

/// Whether the run's cables are in waves (the estimate's rate).
pub fn in_waves(sc: &Scenario) -> bool {
    !sc.sea.is_still() || sc.member_seas.as_ref().is_some_and(|s| !s.is_still())
}

/// The estimate of a lumped-mass run of `steps` steps on the CPU path with this
/// process's threads: the path `check` and the budget's message assume, since the
/// backend is chosen later (and the CPU path is always there).
pub fn cpu_estimate(sc: &Scenario, lay: &Layout, opts: &SolverOptions, steps: u64) -> Estimate {
    estimate::lumped(
        lay,
        opts,
        steps,
        in_waves(sc),
        estimate::Path::Cpu(rayon::current_num_threads()),
    )
}

/// Refuses a lumped-mass run beyond the node-step budget, with the estimate of its
/// wall time on the CPU path, what sets the step and the key that changes it, and how
/// to raise the budget.
#[allow(clippy::too_many_arguments)]
pub fn check_lumped_node_steps(
    sc: &Scenario,
    lay: &Layout,
    opts: &SolverOptions,
    duration: f64,
    dt: f64,
    dt_spec: DtSpec,
    bound: &StepBound,
) -> Result<(), Error> {
    let nodes = lay.n_nodes();
    let work = (duration / dt) * nodes as f64;
    if work <= sc.limits.node_steps {
        return Ok(());
    }
    let steps = (duration / dt).round().min(u64::MAX as f64) as u64;
    let est = cpu_estimate(sc, lay, opts, steps);
    let cause = match dt_spec {
        // A given step well below the stable one: the step itself is the cause.
        DtSpec::Fixed(d) if d < 0.5 * AUTO_SAFETY * bound.dt => format!(
            "the step is the scenario's `dt` (or --dt), {d:e} s, {:.1e} times below the stable step {:.3e} s: \
             use a longer one or `dt = \"auto\"`",
            AUTO_SAFETY * bound.dt / d,
            bound.dt
        ),
        _ => format!(
            "the stable step {:.3e} s is set by {}: {}",
            bound.dt, bound.term, bound.fix
        ),
    };
    refuse_over(
        sc,
        work,
        format!(
            "{duration} s at dt = {dt:.3e} s ({:.3e} steps) over {nodes} nodes is {}",
            duration / dt,
            est.describe()
        ),
        format!("{cause}; or shorten the run (`[simulation] duration`)"),
    )
}

/// The refusal of `work` node-steps beyond the budget: `what` the work and its
/// estimate, `cause` what sets the step and what to change.
fn refuse_over(sc: &Scenario, work: f64, what: String, cause: String) -> Result<(), Error> {
    let budget = sc.limits.node_steps;
    if work <= budget {
        return Ok(());
    }
    Err(err(
        &sc.path,
        "simulation.duration",
        format!(
            "{what}, over the budget of {budget:e} node-steps. Why so many: {cause}. To run it anyway, {}",
            how_to_raise("node_steps")
        ),
    ))
}

/// Refuses a run whose output files would exceed the output budget: one frame per
/// output interval, a `positions.csv` row per written node and a few rows per cable.
pub fn check_output(sc: &Scenario, duration: f64) -> Result<(), Error> {
    let frames = (duration / sc.sim.output_interval).floor() + 1.0;
    let m = &sc.model;
    let rows: usize = m
        .cables
        .iter()
        .filter(|c| c.output_positions)
        .map(|c| c.nodes.len())
        .sum();
    let vtk = if sc.vtk { m.nodes.len() as f64 } else { 0.0 };
    let per_frame = (rows as f64 + vtk) * BYTES_PER_POSITION_ROW
        + m.cables.len() as f64 * BYTES_PER_CABLE_FRAME;
    let gib = frames * per_frame / GIB;
    let budget = sc.limits.output_gib;
    if !(gib <= budget) {
        return Err(err(
            &sc.path,
            "simulation.output_interval",
            format!(
                "{frames:.3e} frames ({duration} s every {} s) of {rows} node rows and {} cables would write about {gib:.3e} GiB, over the budget of {budget} GiB: write less often, fewer positions (`[output] positions`), or {}",
                sc.sim.output_interval,
                m.cables.len(),
                how_to_raise("output_gib")
            ),
        ));
    }
    Ok(())
}

/// Bytes of memory per ANCF element (its state, the banded static and mass matrices),
/// rounded up.
pub const BYTES_PER_ANCF_ELEMENT: f64 = 4096.0;

/// Refuses an ANCF model whose element count (each cable's length over
/// `[ancf] element_length`) would take more memory than the budget, before any
/// element is built.
pub fn check_ancf_size(sc: &Scenario, element_length: Option<f64>) -> Result<(), Error> {
    let elements: f64 = sc
        .model
        .cables
        .iter()
        .map(|c| {
            let length: f64 = c.l0.iter().sum();
            let l_std = element_length.unwrap_or(length / c.l0.len() as f64);
            (length / l_std).ceil().max(1.0)
        })
        .sum();
    let gib = elements * BYTES_PER_ANCF_ELEMENT / GIB;
    let budget = sc.limits.memory_gib;
    if !(gib <= budget) {
        return Err(err(
            &sc.path,
            "ancf.element_length",
            format!(
                "{elements:.3e} ANCF elements would take about {gib:.3e} GiB of memory, over the budget of {budget} GiB: use longer elements, or {}",
                how_to_raise("memory_gib")
            ),
        ));
    }
    Ok(())
}
