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

/// One extreme of a cable's axial force over the output times: `[tension, time,
/// element]` in `summary.json` (N, s, element index from the cable's start).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TensionExtreme {
    /// Axial force, N.
    pub tension: f64,
    /// Output time at which it was reached (the first, on ties), s.
    pub time: f64,
    /// Element index from the cable's start.
    pub element: usize,
}

impl Serialize for TensionExtreme {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(3)?;
        t.serialize_element(&self.tension)?;
        t.serialize_element(&self.time)?;
        t.serialize_element(&self.element)?;
        t.end()
    }
}

/// Per-cable part of the summary: a fixed handful of numbers whatever the cable's
/// length (its node-by-node final state is in `final_state.csv` or
/// `final_state.parquet`; a winch cable also lists its nodes' physical coordinates).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct CableSummary {
    /// Name.
    pub name: String,
    /// The winch's final state, for a cable with a winch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub winch: Option<WinchSummary>,
    /// Final end forces, N (NaN, `null` in JSON, when the final state could not be
    /// evaluated: after a blow-up).
    pub end_forces: EndForces,
    /// The largest axial force over the output times.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_tension: Option<TensionExtreme>,
    /// The smallest axial force over the output times, N (negative only through
    /// damping or in compression; its time and element are not kept, to keep the
    /// summary small: they are in the tensions table).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_tension: Option<f64>,
}

impl CableSummary {
    /// A cable's entry before any output time.
    pub fn new(name: String) -> Self {
        Self {
            name,
            winch: None,
            end_forces: EndForces {
                start: [f64::NAN; 3],
                end: [f64::NAN; 3],
            },
            max_tension: None,
            min_tension: None,
        }
    }
}

/// The per-cable summaries of a run, followed frame by frame: the extremes over every
/// snapshot seen, the end forces and winch state of the latest.
#[derive(Clone, Debug, Default)]
pub struct Extremes {
    /// Steps at the latest snapshot seen (`None` before the first).
    pub steps: Option<u64>,
    /// Per cable, in scenario order.
    pub cables: Vec<CableSummary>,
}

impl Extremes {
    /// Takes in one snapshot.
    pub fn observe(&mut self, snap: &super::Snapshot) {
        if self.cables.len() != snap.cables.len() {
            self.cables = snap
                .cables
                .iter()
                .map(|c| CableSummary::new(c.name.clone()))
                .collect();
        }
        for (cs, c) in self.cables.iter_mut().zip(&snap.cables) {
            cs.end_forces = c.end_forces.clone();
            cs.winch = c.winch.clone();
            for (k, &t) in c.tensions.iter().enumerate() {
                if t.is_nan() {
                    continue;
                }
                let here = TensionExtreme {
                    tension: t,
                    time: snap.time,
                    element: k,
                };
                if cs.max_tension.is_none_or(|m| t > m.tension) {
                    cs.max_tension = Some(here);
                }
                if cs.min_tension.is_none_or(|m| t < m) {
                    cs.min_tension = Some(t);
                }
            }
        }
        self.steps = Some(snap.steps);
    }

    /// The state at `steps` could not be evaluated (a blow-up): its end forces are
    /// unknown.
    pub fn unevaluable(&mut self, steps: u64) {
        for c in &mut self.cables {
            c.end_forces = EndForces {
                start: [f64::NAN; 3],
                end: [f64::NAN; 3],
            };
        }
        self.steps = Some(steps);
    }
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
    /// The line failures, in the order they fired (left out when none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub failures: Vec<crate::model::FailureEvent>,
    /// Per cable (the last key: [`summary_text`] writes a line per cable).
    pub cables: Vec<CableSummary>,
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

/// `summary.json`'s text: the run's keys pretty-printed, then one line per cable (a
/// compact object), so that a fleet's summary stays a file an editor opens and `grep`
/// searches by cable name.
pub fn summary_text(s: &Summary) -> String {
    let head = Summary {
        cables: Vec::new(),
        ..s.clone_head()
    };
    let mut text = serde_json::to_string_pretty(&head).expect("summary serialises");
    // The head ends with `"cables": []` and the closing brace.
    let tail = "\"cables\": []\n}";
    assert!(text.ends_with(tail), "cables is the summary's last key");
    text.truncate(text.len() - tail.len());
    text.push_str("\"cables\": [");
    for (i, c) in s.cables.iter().enumerate() {
        text.push_str(if i == 0 { "\n  " } else { ",\n  " });
        text.push_str(&serde_json::to_string(c).expect("summary serialises"));
    }
    text.push_str(if s.cables.is_empty() {
        "]\n}\n"
    } else {
        "\n]\n}\n"
    });
    text
}

impl Summary {
    /// A copy of every key but the cables.
    fn clone_head(&self) -> Summary {
        Summary {
            status: self.status.clone(),
            error: self.error.clone(),
            scenario: self.scenario.clone(),
            backend: self.backend.clone(),
            device: self.device.clone(),
            precision: self.precision.clone(),
            scheme: self.scheme.clone(),
            formulation: self.formulation.clone(),
            steps: self.steps,
            dt: self.dt,
            dt_stable: self.dt_stable,
            dt_limited_by: self.dt_limited_by.clone(),
            dt_above_stable: self.dt_above_stable,
            simulated_time: self.simulated_time,
            wall_seconds: self.wall_seconds,
            total_wall_seconds: self.total_wall_seconds,
            nodes: self.nodes,
            elements: self.elements,
            node_steps_per_second: self.node_steps_per_second,
            threads: self.threads,
            relax_residual: self.relax_residual,
            failures: self.failures.clone(),
            cables: Vec::new(),
        }
    }
}

/// Writes `summary.json` into `dir` ([`summary_text`]).
pub fn write_summary(dir: &Path, s: &Summary) -> Result<(), Error> {
    let path = dir.join("summary.json");
    std::fs::write(&path, summary_text(s)).map_err(|source| Error::Output { path, source })
}
