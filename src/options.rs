//! Run options, in one place: the enums a scenario's `[simulation]` table and the
//! command line choose from (backend, precision, scheme, formulation, cable model, the
//! ANCF's added mass), each parsed by serde (scenario files) and clap (`--help` lists
//! the values), and the solver options built from them.

use crate::physics::frames::Frame;
use clap::ValueEnum;
use serde::{Deserialize, Deserializer, Serialize};

/// Parses a run option by its name (the names `--help` lists, aliases included): an
/// unknown name is refused with the names allowed (`must be auto, cpu or gpu, got
/// "tpu"`).
pub fn parse_option<T: ValueEnum>(s: &str) -> Result<T, String> {
    T::from_str(s, false).map_err(|_| {
        let names: Vec<String> = T::value_variants()
            .iter()
            .filter_map(|v| v.to_possible_value())
            .map(|p| p.get_name().to_string())
            .collect();
        let list = match names.split_last() {
            Some((last, [])) => last.clone(),
            Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
            None => String::new(),
        };
        format!("must be {list}, got \"{s}\"")
    })
}

/// Scenario files name the run options as the command line does ([`parse_option`]).
macro_rules! deserialize_by_name {
    ($($t:ty),*) => {$(
        impl<'de> Deserialize<'de> for $t {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let s = String::deserialize(d)?;
                parse_option(&s).map_err(serde::de::Error::custom)
            }
        }
    )*};
}
deserialize_by_name!(
    Backend,
    Precision,
    Scheme,
    CableModel,
    FormulationChoice,
    AddedMass,
    OutputFormat
);

/// The format of a run's tables (end forces, tensions, positions, ...): `[output]
/// format` in a scenario, `cablesim run --format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum OutputFormat {
    /// CSV text, one row per line: small runs, any tool.
    #[default]
    Csv,
    /// Apache Parquet (compressed columns, one row group per frame or several small
    /// frames): large runs, read by pandas, polars, DuckDB, pyarrow. Needs the
    /// `parquet` cargo feature (on by default).
    Parquet,
}

impl OutputFormat {
    /// The name used in files and messages (also the files' extension).
    pub fn name(self) -> &'static str {
        match self {
            OutputFormat::Csv => "csv",
            OutputFormat::Parquet => "parquet",
        }
    }

    /// Whether this build can write the format: Parquet needs the `parquet` feature.
    pub fn available(self) -> bool {
        match self {
            OutputFormat::Csv => true,
            OutputFormat::Parquet => cfg!(feature = "parquet"),
        }
    }

    /// `Err` with a message that says what to do when this build cannot write the
    /// format.
    pub fn check_available(self) -> Result<(), String> {
        if self.available() {
            Ok(())
        } else {
            let n = self.name();
            Err(format!(
                "\"{n}\" output is not in this build of cablesim (built without the `{n}` \
                 cargo feature); use \"csv\", or rebuild with `--features {n}`"
            ))
        }
    }
}

/// Which computing path runs the simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Backend {
    /// The GPU when one is usable and faster than the CPU path, else the CPU.
    #[default]
    Auto,
    /// The f64 CPU reference path.
    Cpu,
    /// The GPU path (an error when no adapter is usable).
    Gpu,
}

impl Backend {
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Auto => "auto",
            Backend::Cpu => "cpu",
            Backend::Gpu => "gpu",
        }
    }
}

/// Floating-point precision of the GPU shaders (the CPU path is always f64).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// 32-bit floats (every adapter); positions kept as compensated pairs.
    #[default]
    F32,
    /// 64-bit floats (adapters with `SHADER_F64`).
    F64,
}

impl Precision {
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

/// How element loads are evaluated by the lumped-mass model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Formulation {
    /// Global lumped mass formulation: no element frame.
    #[default]
    Glmf,
    /// An older element frame (CPU only; kept to reproduce the paper's comparison).
    Frame(Frame),
}

impl Formulation {
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Glmf => "glmf",
            Formulation::Frame(f) => f.name(),
        }
    }
}

/// Which cable model a run uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum CableModel {
    /// Lumped masses (GLMF or an older frame: [`Formulation`]), on the CPU or the GPU.
    #[default]
    LumpedMass,
    /// The ANCF reference model (ALE-ANCF with a winch), CPU only ([`crate::ancf`]).
    Ancf,
}

/// The `formulation` a user names (scenario `[simulation] formulation`, `--formulation`):
/// the lumped-mass model with one of its load formulations, or the ANCF reference model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum FormulationChoice {
    /// Lumped mass, global lumped mass formulation (no element frame).
    #[default]
    Glmf,
    /// Lumped mass, rotation-vector element frame (CPU only).
    Rvef,
    /// Lumped mass, Euler-angle element frame (CPU only).
    Euler,
    /// Lumped mass, Frenet element frame (CPU only).
    Frenet,
    /// The ANCF reference model (ALE-ANCF for winch cables; CPU only).
    Ancf,
}

impl FormulationChoice {
    /// The cable model it selects.
    pub fn model(self) -> CableModel {
        match self {
            FormulationChoice::Ancf => CableModel::Ancf,
            _ => CableModel::LumpedMass,
        }
    }
    /// The lumped-mass load formulation it selects (`Glmf` for the ANCF model, which
    /// has its own element).
    pub fn formulation(self) -> Formulation {
        match self {
            FormulationChoice::Glmf | FormulationChoice::Ancf => Formulation::Glmf,
            FormulationChoice::Rvef => Formulation::Frame(Frame::Rvef),
            FormulationChoice::Euler => Formulation::Frame(Frame::Euler),
            FormulationChoice::Frenet => Formulation::Frame(Frame::Frenet),
        }
    }
}

/// How the added mass `Cm rho A` (per unit length) enters the ANCF's consistent mass
/// matrix.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum AddedMass {
    /// Normal to the cable only, `Cm rho A (I - t t^T)` with the tangent at each Gauss
    /// point (paper Eqs. 43-44, as the GLMF): the mass matrix depends on the state and is
    /// re-assembled and re-factored at every evaluation.
    #[default]
    Normal,
    /// `Cm rho A I`, also along the cable: the mass matrix is constant and factored once
    /// (about twice as fast), at the price of a tangential added mass the physics does not
    /// have, which matters when `Cm rho A` is not small next to `mbar`.
    Isotropic,
}

/// The `[ancf]` table of a scenario: settings of the ANCF reference model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AncfSettings {
    /// Element length, m (`None`: each cable's lumped-mass element length).
    pub element_length: Option<f64>,
    /// Gauss points per element.
    pub gauss_points: usize,
    /// How the added mass enters the mass matrix.
    pub added_mass: AddedMass,
}

impl Default for AncfSettings {
    fn default() -> Self {
        Self {
            element_length: None,
            gauss_points: 5,
            added_mass: AddedMass::Normal,
        }
    }
}

/// Overrides of a scenario's `[simulation]` settings (each `None` keeps the scenario's
/// value): what the command line's options and a library caller can change.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// Backend.
    pub backend: Option<Backend>,
    /// GPU precision (the CPU path is always f64).
    pub precision: Option<Precision>,
    /// Scheme.
    pub scheme: Option<Scheme>,
    /// Formulation (of the lumped-mass model).
    pub formulation: Option<Formulation>,
    /// Cable model (lumped mass or ANCF).
    pub model: Option<CableModel>,
    /// Time step, s.
    pub dt: Option<f64>,
    /// Duration, s.
    pub duration: Option<f64>,
}

impl Overrides {
    /// Sets the cable model and formulation a user's `formulation` names.
    pub fn with_formulation(mut self, f: FormulationChoice) -> Self {
        self.model = Some(f.model());
        self.formulation = Some(f.formulation());
        self
    }
}

/// Explicit fixed-step time integration schemes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Scheme {
    /// Semi-implicit (symplectic) Euler: `v += dt a(r, v); r += dt v`. One force
    /// evaluation per step; stable for `(omega dt)^2 + 2 gamma dt < 4` (`euler` names
    /// it too).
    #[default]
    #[value(alias = "euler")]
    Symplectic,
    /// Explicit midpoint (second-order Runge-Kutta, as MoorDyn's RK2): two evaluations.
    Rk2,
    /// Classical fourth-order Runge-Kutta: four evaluations.
    Rk4,
}

impl Scheme {
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Symplectic => "symplectic",
            Scheme::Rk2 => "rk2",
            Scheme::Rk4 => "rk4",
        }
    }
    /// Force evaluations per step.
    pub fn stages(self) -> usize {
        match self {
            Scheme::Symplectic => 1,
            Scheme::Rk2 => 2,
            Scheme::Rk4 => 4,
        }
    }
}

/// Baumgarte stabilisation gains for constrained nodes:
/// `qdd = rdd_d - beta (v - rd_d) - alpha (r - r_d)`.
///
/// The defaults, `alpha = 400 s^-2`, `beta = 40 s^-1`, make the constraint error a
/// critically damped oscillator at 20 rad/s (it decays with a 0.05 s time constant),
/// far below any stable step's frequency limit (`omega dt << 2`) and fast next to the
/// cable's own dynamics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Baumgarte {
    /// Position gain `alpha`, s^-2.
    pub alpha: f64,
    /// Velocity gain `beta`, s^-1.
    pub beta: f64,
}

impl Default for Baumgarte {
    fn default() -> Self {
        Self {
            alpha: 400.0,
            beta: 40.0,
        }
    }
}

/// Options of one solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverOptions {
    /// Load formulation.
    pub formulation: Formulation,
    /// Time scheme.
    pub scheme: Scheme,
    /// Time step, s.
    pub dt: f64,
    /// Constraint stabilisation.
    pub baumgarte: Baumgarte,
    /// A node faster than this (m/s) or farther than `max_distance` from the origin is
    /// reported as a blow-up.
    pub max_speed: f64,
    /// See `max_speed`, m.
    pub max_distance: f64,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            formulation: Formulation::Glmf,
            scheme: Scheme::Symplectic,
            dt: 1e-3,
            baumgarte: Baumgarte::default(),
            max_speed: 1.0e4,
            max_distance: 1.0e7,
        }
    }
}
