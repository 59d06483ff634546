//! The summary of a run (`summary.json`) and the per-cable states it holds.

use crate::error::Error;
use serde::Serialize;
use std::path::Path;

/// End forces of one cable: the force the cable exerts on each end support, N.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct EndForces {
    /// At the start node.
    pub start: [f64; 3],
    /// At the end node.
    pub end: [f64; 3],
}

/// State of a winch cable (ALE-GLMF, ALE-ANCF).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct WinchSummary {
    /// Deployed unstretched length, m.
    pub deployed_length: f64,
    /// Unstretched length of the variable element next to the winch, m.
    pub variable_l0: f64,
    /// Elements of the cable.
    pub elements: usize,
    /// Nodes inserted during the run.
    pub nodes_inserted: u64,
    /// Nodes deleted during the run.
    pub nodes_deleted: u64,
    /// Physical coordinate `p` of each node (cable order, start to end): unstretched
    /// arc length from the far end, m.
    pub physical_coordinates: Vec<f64>,
}

/// Per-cable part of the summary.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct CableSummary {
    /// Name.
    pub name: String,
    /// The winch's final state, for a cable with a winch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub winch: Option<WinchSummary>,
    /// Final node positions, m.
    pub final_positions: Vec<[f64; 3]>,
    /// Final axial force per element, N.
    pub final_tensions: Vec<f64>,
    /// Final end forces, N.
    pub end_forces: EndForces,
}

/// `summary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// `completed` or `diverged`.
    pub status: String,
    /// The error that stopped the run, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The scenario file.
    pub scenario: String,
    /// `cpu` or `gpu`.
    pub backend: String,
    /// Adapter or CPU description.
    pub device: String,
    /// `f64` or `f32`.
    pub precision: String,
    /// Time scheme.
    pub scheme: String,
    /// Load formulation.
    pub formulation: String,
    /// Steps taken.
    pub steps: u64,
    /// Time step, s.
    pub dt: f64,
    /// Largest stable step estimated for the scheme, s.
    pub dt_stable: f64,
    /// What sets the stable step.
    pub dt_limited_by: String,
    /// Whether `dt` (a given step) is above `dt_stable`: the run may blow up, or
    /// complete with results the step has spoiled.
    pub dt_above_stable: bool,
    /// Simulated time reached, s.
    pub simulated_time: f64,
    /// Wall time of the time stepping, s (no set-up, no relaxation, no output).
    pub wall_seconds: f64,
    /// Wall time of the whole run, s.
    pub total_wall_seconds: f64,
    /// Nodes in the model.
    pub nodes: usize,
    /// Elements in the model.
    pub elements: usize,
    /// `nodes * steps / wall_seconds`.
    pub node_steps_per_second: f64,
    /// Worker threads of the CPU path.
    pub threads: usize,
    /// Initial equilibrium: largest residual force left, N (0 when not relaxed).
    pub relax_residual: f64,
    /// Per cable.
    pub cables: Vec<CableSummary>,
    /// The line failures, in the order they fired (left out when none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub failures: Vec<crate::model::FailureEvent>,
}

/// `summary.json` of a run that failed before its first step (the build, the initial
/// equilibrium, the GPU set-up): no state to report, only what stopped it.
#[derive(Clone, Debug, Serialize)]
pub struct FailedStart {
    /// `failed`.
    pub status: String,
    /// The error that stopped the run.
    pub error: String,
    /// The scenario file.
    pub scenario: String,
    /// Steps taken: 0.
    pub steps: u64,
    /// Simulated time reached: 0.
    pub simulated_time: f64,
}

impl FailedStart {
    /// The summary of a run of `scenario` that `error` stopped before its first step.
    pub fn new(scenario: &Path, error: &str) -> Self {
        Self {
            status: "failed".into(),
            error: error.to_string(),
            scenario: scenario.display().to_string(),
            steps: 0,
            simulated_time: 0.0,
        }
    }

    /// Writes it as `summary.json` into `dir`.
    pub fn write(&self, dir: &Path) -> Result<(), Error> {
        let path = dir.join("summary.json");
        let text = serde_json::to_string_pretty(self).expect("summary serialises");
        std::fs::write(&path, text).map_err(|source| Error::Output { path, source })
    }
}

/// Writes `summary.json` into `dir`.
pub fn write_summary(dir: &Path, s: &Summary) -> Result<(), Error> {
    let path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(s).expect("summary serialises");
    std::fs::write(&path, text).map_err(|source| Error::Output { path, source })
}
