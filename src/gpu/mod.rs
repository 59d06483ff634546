//! The GPU path: every cable of a run stepped together by WGSL compute shaders.
//!
//! Stages of a step (one dispatch each, many steps per submission):
//! 1. `element_forces` (`shaders/element_forces.wgsl`): per element, tangent, axial
//!    force (slack, damping), half external load (normal and tangential drag,
//!    water-acceleration load, weight less buoyancy) and half masses;
//! 2. `node_update` (`shaders/node_update.wgsl`): per node, gather over the incidence
//!    list (no atomics), point-mass weight and drag, seabed contact with regularised
//!    friction, the 3x3 mass block and its solve, or the Baumgarte acceleration of a
//!    fixed or route-driven node (route evaluated in the shader: line, circle, screw,
//!    or a table by binary search over its packed samples), then the symplectic
//!    update; a blow-up sets a status flag that stops later steps.
//!
//! Winch cables (ALE-GLMF, [`crate::ale`]) are part of the same packed layout: the
//! variable element of each is marked in its `ElemParams` and its two nodes in their
//! `NodeParams`; the host writes per submission one `Payout` row per winch and step
//! (`l0_v(t)` formed in f64 as on the CPU, rate, acceleration, tributary change) and
//! the element pass evaluates the variable element with it, subtracts the damping of
//! its changing `l0`, and leaves the mass-flow forces of Eq. 39 in `node_out` for the
//! node pass. Remeshing happens on the host, with the CPU path's code, at the steps the
//! schedules fix in advance: one state read-back and layout re-upload per remeshing
//! ([`GpuSolver`]).
//!
//! Precision: f32 by default, f64 where the adapter has `SHADER_F64`, from one WGSL
//! source (the scalar type is substituted). In f32 an absolute coordinate near 1 km
//! resolves only ~6e-5 m, so positions are stored relative to a per-block origin
//! (whole metres) and as compensated pairs `r_hi + r_lo` updated by an exact two-sum;
//! element vectors are formed from the pairs by two-sums, and an element's stretch
//! `l - l0` from them by exact squares (Veltkamp-Dekker) and two-sums, so that a
//! tension is known to f32 precision of itself rather than of `EA` (plain f32 knows it
//! to `EA 2^-24`, whose noise rings the axial modes of stiff lines); routes are rebased
//! to each submission's start (a circle from its point and angle there). Compilers may
//! contract and reassociate floating-point operations in shaders (Mesa's NIR does), so
//! the compensated arithmetic passes products through an opaque select and multiplies
//! by a run-time 1.0 (see the prelude). `tests/gpu_f32.rs` and `tests/gpu_parity.rs`
//! hold the evidence.
//!
//! Speed: on a datacenter GPU the step is bound by memory bandwidth (about 300 bytes
//! and 400 flops per node-step in f32); on a software adapter by the adapter's own
//! per-lane memory access and per-dispatch synchronisation (BENCHMARKS.md).
//! [`GpuSolver::timings`] splits the host's time into recording, submission and waiting.
//!
//! Not on the GPU yet ([`solver::unsupported`] says which, and `--backend auto` falls
//! back to the CPU): the RK2 and RK4 schemes, the older element frames.
//!
//! Modules: [`context`] (adapter and device), [`layout`] (Rust twins of the WGSL
//! structs), [`shaders`] (WGSL assembly per precision), [`solver`] (buffers, pipelines,
//! stepping and read-back).

pub mod context;
pub mod layout;
pub mod shaders;
pub mod solver;

pub use context::GpuContext;
pub use solver::{GpuKernel, GpuSolver, GpuTimings};

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
