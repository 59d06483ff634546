//! The scenario file as written (serde), before validation.

use crate::model::Seabed;
use crate::options::{AddedMass, Backend, FormulationChoice, Precision, Scheme};
use serde::Deserialize;

/// Top level of a scenario file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScenario {
    pub simulation: RawSimulation,
    #[serde(default)]
    pub environment: RawEnvironment,
    pub line_types: Vec<super::materials::RawLineType>,
    #[serde(default)]
    pub bodies: Vec<toml::Table>,
    #[serde(default)]
    pub points: Vec<toml::Table>,
    #[serde(default)]
    pub cables: Vec<RawCable>,
    #[serde(default)]
    pub cable_arrays: Vec<toml::Table>,
    #[serde(default)]
    pub nets: Vec<RawNet>,
    #[serde(default)]
    pub output: RawOutput,
    #[serde(default)]
    pub ancf: RawAncf,
    #[serde(default)]
    pub limits: LimitOverrides,
    /// A `[study]` table, read by `cablesim study` (`crate::study`); a single run of the
    /// scenario ignores it (the study reads the table from the file's text itself).
    #[allow(dead_code)]
    pub study: Option<toml::Value>,
    /// `[fatigue]`: T-N curves and the locations whose fatigue a run counts.
    pub fatigue: Option<super::fatigue::RawFatigue>,
}

/// A `[[nets]]` entry: a net panel or cylindrical cage (see `model::net`).
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawNet {
    pub name: String,
    pub line_type: String,
    pub shape: String,
    pub knots: [i64; 2],
    pub size: [f64; 2],
    pub top: [f64; 3],
    pub segments: Option<i64>,
    pub sinker: Option<RawSinker>,
    pub current: Option<[f64; 3]>,
    pub current_profile: Option<Vec<[f64; 4]>>,
    pub output_positions: Option<bool>,
    // A cage's parts (`super::cage`; docs/src/cage.md).
    pub collar: Option<RawCollar>,
    pub sinker_tube: Option<RawSinkerTube>,
    // Screen-model loads (docs/src/model/screen.md; `super::nets::screen`).
    pub loads: Option<String>,
    pub screen_model: Option<String>,
    pub solidity: Option<f64>,
    pub mesh: Option<f64>,
    pub twine_diameter: Option<f64>,
    pub viscosity: Option<f64>,
    pub wake: Option<String>,
}

/// `[nets.collar]`: the floating collar a cylindrical net hangs from.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawCollar {
    pub line_type: Option<String>,
    pub pipe: Option<RawPipe>,
    pub segments: Option<i64>,
    pub points: Option<Vec<String>>,
}

/// `[nets.sinker_tube]`: a heavy ring on chains below a cylindrical net.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawSinkerTube {
    pub line_type: Option<String>,
    pub pipe: Option<RawPipe>,
    pub segments: Option<i64>,
    pub radius: Option<f64>,
    pub chain_line_type: String,
    pub chain_length: f64,
    pub every: Option<i64>,
    pub chain_segments: Option<i64>,
}

/// A pipe given by its section and material (`model::cage::Pipe`).
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawPipe {
    pub diameter: f64,
    pub wall: f64,
    pub density: Option<f64>,
    pub youngs_modulus: Option<f64>,
    pub flooded: Option<bool>,
    pub ballast: Option<f64>,
    pub cn: Option<f64>,
    pub cm: Option<f64>,
}

/// The point mass at each bottom knot of a net.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawSinker {
    pub mass: f64,
    pub volume: Option<f64>,
    pub drag_area: Option<f64>,
    pub added_mass: Option<f64>,
}

/// The `[ancf]` table: settings of the ANCF reference model.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawAncf {
    pub element_length: Option<f64>,
    pub gauss_points: Option<i64>,
    pub added_mass: Option<AddedMass>,
}

/// `dt = "auto"` or a number.
#[derive(Debug, Deserialize, Clone)]
#[serde(untagged)]
pub enum RawDt {
    Number(f64),
    Word(String),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSimulation {
    pub duration: f64,
    pub dt: Option<RawDt>,
    pub output_interval: f64,
    pub backend: Option<Backend>,
    pub precision: Option<Precision>,
    pub scheme: Option<Scheme>,
    pub formulation: Option<FormulationChoice>,
    pub baumgarte_alpha: Option<f64>,
    pub baumgarte_beta: Option<f64>,
    pub max_speed: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEnvironment {
    #[serde(default = "default_g")]
    pub gravity: f64,
    #[serde(default = "default_rho")]
    pub water_density: f64,
    pub depth: Option<f64>,
    pub seabed_file: Option<String>,
    pub current: Option<[f64; 3]>,
    pub current_profile: Option<Vec<[f64; 4]>>,
    #[serde(default)]
    pub seabed: Seabed,
    pub waves: Option<super::waves::RawWaves>,
}

impl Default for RawEnvironment {
    fn default() -> Self {
        Self {
            gravity: default_g(),
            water_density: default_rho(),
            depth: None,
            seabed_file: None,
            current: None,
            current_profile: None,
            seabed: Seabed::default(),
            waves: None,
        }
    }
}

fn default_g() -> f64 {
    9.81
}
fn default_rho() -> f64 {
    1025.0
}

/// One section of a cable of several (chain - rope - chain).
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawSection {
    pub line_type: String,
    pub length: f64,
    pub segments: i64,
}

/// A cable's `length` when the file leaves it out (NaN: told from a written 0).
fn missing_length() -> f64 {
    f64::NAN
}

/// A cable's `segments` when the file leaves it out.
fn missing_segments() -> i64 {
    i64::MIN
}

impl RawCable {
    /// The number of segments, over all sections.
    pub fn total_segments(&self) -> i64 {
        match &self.sections {
            Some(s) => s.iter().map(|x| x.segments.max(0)).sum(),
            None => self.segments,
        }
    }
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawCable {
    pub name: String,
    /// Empty when the cable is given as `sections`.
    #[serde(default)]
    pub line_type: String,
    /// NaN when not given (`missing_length`).
    #[serde(default = "missing_length")]
    pub length: f64,
    /// `i64::MIN` when not given (`missing_segments`).
    #[serde(default = "missing_segments")]
    pub segments: i64,
    /// Several sections, start to end, in place of `line_type`, `length`, `segments`.
    #[serde(default)]
    pub sections: Option<Vec<RawSection>>,
    pub start: toml::Table,
    pub end: toml::Table,
    pub initial: Option<String>,
    pub current: Option<[f64; 3]>,
    pub current_profile: Option<Vec<[f64; 4]>>,
    pub output_positions: Option<bool>,
    pub winch: Option<toml::Table>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawOutput {
    pub positions: Option<toml::Value>,
    pub vtk: Option<bool>,
    pub format: Option<String>,
}

/// `[limits]` as written, or limits given on the command line or by the caller over
/// the file's (`LimitOverrides::over`, in `limits.rs`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitOverrides {
    /// `node_steps`.
    pub node_steps: Option<f64>,
    /// `memory_gib`.
    pub memory_gib: Option<f64>,
    /// `output_gib`.
    pub output_gib: Option<f64>,
}
