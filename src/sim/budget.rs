//! The work budget of a run, checked against the step plan before anything runs: node-
//! steps (nodes times steps) and the size of the output files (frames times rows).
//! The model's memory is checked earlier, while the scenario is read
//! ([`crate::scenario::limits`]). Each refusal gives the estimate and how to raise the
//! budget (`[limits]`, `--limit`).

use crate::error::Error;
use crate::scenario::limits::{how_to_raise, GIB};
use crate::scenario::{err, Scenario};

/// Bytes of one `positions.csv` row (`t, cable, node, x, y, z`), about.
pub const BYTES_PER_POSITION_ROW: f64 = 80.0;
/// Bytes of one cable's rows per frame in the other files (end forces, tensions), about.
pub const BYTES_PER_CABLE_FRAME: f64 = 200.0;

/// Refuses a run of `steps` steps of `dt` s over `nodes` nodes beyond the node-step
/// budget; `term` says what sets the step.
pub fn check_node_steps(
    sc: &Scenario,
    nodes: usize,
    duration: f64,
    dt: f64,
    term: &str,
) -> Result<(), Error> {
    let work = (duration / dt) * nodes as f64;
    let budget = sc.limits.node_steps;
    if !(work <= budget) {
        return Err(err(
            &sc.path,
            "simulation.duration",
            format!(
                "{duration} s at dt = {dt:e} s over {nodes} nodes is {work:.3e} node-steps, over the budget of {budget:e} node-steps; the step is set by {term}: shorten the run, coarsen the mesh or change that term, or {}",
                how_to_raise("node_steps")
            ),
        ));
    }
    Ok(())
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
