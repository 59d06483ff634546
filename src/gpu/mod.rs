//! The GPU path: every cable of a run stepped together by WGSL compute shaders.
//!
//! Stages of a step (one dispatch each, many steps per submission):
//! 1. `element_forces` (`shaders/element_forces.wgsl`): per element, tangent, axial
//!    force (slack, damping), half external load (normal and tangential drag,
//!    water-acceleration load, weight less buoyancy) and half masses;
//! 2. `node_update` (`shaders/node_update.wgsl`): per node, gather over the incidence
//!    list (no atomics), point-mass weight and drag, seabed contact with regularised
//!    friction, the 3x3 mass block and its solve, or the Baumgarte acceleration of a
//!    fixed or route-driven node (route evaluated in the shader), then the symplectic
//!    update; a blow-up sets a status flag that stops later steps.
//!
//! Modules: [`context`] (adapter and device), [`layout`] (Rust twins of the WGSL
//! structs), [`shaders`] (WGSL assembly per precision), [`solver`] (buffers, pipelines,
//! stepping and read-back).

pub mod context;
pub mod layout;
pub mod shaders;
pub mod solver;

pub use context::GpuContext;
pub use solver::GpuSolver;

/// Floating-point precision of the GPU shaders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Precision {
    /// 32-bit floats (every adapter); positions kept as compensated pairs.
    #[default]
    F32,
    /// 64-bit floats (adapters with `SHADER_F64`).
    F64,
}

impl Precision {
    /// Parses `f32 | f64`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "f32" => Some(Precision::F32),
            "f64" => Some(Precision::F64),
            _ => None,
        }
    }
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}
