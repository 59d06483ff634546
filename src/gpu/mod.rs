//! The GPU path: every cable of a run stepped together by WGSL compute shaders.
//!
//! Two kernels step the same physics with the same WGSL functions (the prelude's
//! `element_step`, `gather_begin` / `gather_add` / `gather_end`, `node_advance`,
//! `node_check`; one implementation each), so their results agree to round-off (bit
//! for bit on lavapipe, `tests/gpu/fused.rs`):
//!
//! - **Fused** ([`GpuKernel::Fused`], `shaders/fused_chain.wgsl`), used wherever it
//!   applies: one workgroup per block (a cable, or a small network of cables sharing
//!   nodes) advances it through a whole submission of up to
//!   [`solver::STEPS_PER_SUBMISSION`] steps in one dispatch. Invocation `j` owns the
//!   block's node `j` (its state in registers) and element `j`; node states and
//!   element loads are exchanged through workgroup memory with two
//!   `workgroupBarrier`s a step, and global memory is touched once per dispatch
//!   (state in and out, parameters) apart from small cached tables (incidence,
//!   currents, routes). It applies when every block has at most
//!   [`solver::MAX_FUSED_WORKGROUP`] nodes and elements (the workgroup is the
//!   smallest multiple of 8 that holds the largest block) and fits the adapter's
//!   workgroup memory (18 scalars per invocation: 72 bytes in f32, 144 in f64), and
//!   there are no winch cables ([`solver::fused_workgroup`] says why not).
//!   A blow-up stops its block at the failing step and is reported with the
//!   earliest failing step's cable, node and time; the other blocks finish the
//!   submission, and later submissions do nothing.
//! - **Two-pass** ([`GpuKernel::TwoPass`]), any layout: two dispatches per step over
//!   the whole packed layout, described below.
//!
//! [`GpuSolver::set_kernel`] or `CABLESIM_GPU_KERNEL=two-pass` forces the two-pass
//! kernel (`fused` demands the fused one and fails where it does not apply).
//!
//! Stages of a two-pass step (one dispatch each, many steps per submission):
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
//! by a run-time 1.0 (see the prelude). `tests/gpu/f32_vs_f64.rs` and `tests/gpu/parity.rs`
//! hold the evidence.
//!
//! Speed: on a datacenter GPU the two-pass step is bound by memory bandwidth (about 300
//! bytes and 400 flops per node-step in f32); the fused kernel moves under one byte of
//! global memory per node-step (the state once per submission) and about 220 bytes of
//! workgroup memory in f32, so it is bound by arithmetic and occupancy there, and it
//! launches one dispatch per submission instead of two per step. On a software adapter
//! both are bound by the adapter's own per-lane memory access; the fused kernel removes
//! its per-dispatch synchronisation (BENCHMARKS.md).
//! [`GpuSolver::timings`] splits the host's time into recording, submission and waiting.
//!
//! Not on the GPU yet ([`solver::unsupported`] says which, and `--backend auto` falls
//! back to the CPU): the RK2 and RK4 schemes, the older element frames.
//!
//! Modules: [`context`] (adapter and device), [`layout`] (Rust twins of the WGSL
//! structs), [`shaders`] (WGSL assembly per precision and fused workgroup size),
//! [`solver`] (the public [`GpuSolver`] and its API). Behind it, private modules of
//! one concept each: `kernel` (kernel choice and the dispatch constants), `host` (the
//! layout's host-side data and the route and body rows formed in f64),
//! `wave_schedule` (the waves' cache schedules and where the fused dispatches are
//! cut), `engine` (the device side at one precision: stepping, read-back, evaluation)
//! and `engine::install` (pipelines, buffers, bind groups and per-submission writes).
//! Their public items are re-exported from [`solver`] at the paths they always had.

pub mod context;
mod engine;
mod host;
mod kernel;
pub mod layout;
pub mod shaders;
pub mod solver;
pub(crate) mod wave_schedule;

pub use crate::options::Precision;
pub use context::GpuContext;
pub use solver::{GpuCheckpoint, GpuKernel, GpuSolver, GpuTimings};
pub use wave_schedule::SOFTWARE_MAX_COMPONENTS;
