//! Solver options shared by the CPU and GPU paths.

use crate::physics::frames::Frame;
use serde::{Deserialize, Serialize};

/// How element loads are evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Formulation {
    /// Global lumped mass formulation: no element frame.
    #[default]
    Glmf,
    /// An older element frame (CPU only; kept to reproduce the paper's comparison).
    Frame(Frame),
}

impl Formulation {
    /// Parses `glmf | rvef | euler | frenet`.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "glmf" => Formulation::Glmf,
            "rvef" => Formulation::Frame(Frame::Rvef),
            "euler" => Formulation::Frame(Frame::Euler),
            "frenet" => Formulation::Frame(Frame::Frenet),
            _ => return None,
        })
    }
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Glmf => "glmf",
            Formulation::Frame(f) => f.name(),
        }
    }
}

/// Which cable model a run uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum CableModel {
    /// Lumped masses (GLMF or an older frame: [`Formulation`]), on the CPU or the GPU.
    #[default]
    LumpedMass,
    /// The ANCF reference model (ALE-ANCF with a winch), CPU only ([`crate::ancf`]).
    Ancf,
}

/// Parses a `formulation` value: `glmf | rvef | euler | frenet` (lumped mass, with
/// that formulation) or `ancf` (the ANCF reference model).
pub fn parse_formulation(s: &str) -> Option<(CableModel, Formulation)> {
    if s == "ancf" {
        return Some((CableModel::Ancf, Formulation::Glmf));
    }
    Formulation::parse(s).map(|f| (CableModel::LumpedMass, f))
}

/// Explicit fixed-step time integration schemes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Scheme {
    /// Semi-implicit (symplectic) Euler: `v += dt a(r, v); r += dt v`. One force
    /// evaluation per step; stable for `(omega dt)^2 + 2 gamma dt < 4`.
    #[default]
    Symplectic,
    /// Explicit midpoint (second-order Runge-Kutta, as MoorDyn's RK2): two evaluations.
    Rk2,
    /// Classical fourth-order Runge-Kutta: four evaluations.
    Rk4,
}

impl Scheme {
    /// Parses `symplectic | euler | rk2 | rk4` (`euler` means the symplectic scheme).
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "symplectic" | "euler" => Scheme::Symplectic,
            "rk2" => Scheme::Rk2,
            "rk4" => Scheme::Rk4,
            _ => return None,
        })
    }
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
