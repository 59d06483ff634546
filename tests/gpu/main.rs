//! The GPU path against the CPU reference: each WGSL function (the force functions, and
//! those of a step's element and node passes) against its Rust twin,
//! the struct layouts and shader validation, and whole runs compared node by node
//! (f64 and f32, the fused and the two-pass kernel, winch cables, the run driver's
//! backend choice).
//!
//! Every run-against-run comparison goes through [`compare`], which reports the
//! cable, node and both values where two results differ most. The tests need an
//! adapter (lavapipe will do); without one they say so loudly and skip, or fail with
//! `CABLESIM_REQUIRE_GPU=1` (`common::gpu_context`).
//!
//! One test binary (see `tests/cpu/main.rs` for why); shared model builders are in
//! `tests/common`.

#[path = "../common/mod.rs"]
mod common;

mod axial;
mod backend;
mod bending;
mod bodies;
mod cage;
mod compare;
mod examples_waves;
mod f32_vs_f64;
mod free_bodies;
mod froude_krylov;
mod functions;
mod fused;
mod layout;
mod packed;
mod parity;
mod screen;
mod seabed_friction;
mod seabed_grid;
mod shaders;
mod step_functions;
mod surface;
mod visco;
mod wave_breach;
mod wave_inputs;
mod wave_parity;
mod waves;
mod winch;
mod winch_blow_up;
