//! The CPU reference path: closed-form physics, the element frames, statics, ALE
//! winches, the ANCF reference model, nets and the threaded network step.
//!
//! One test binary for all of them (each module was once its own binary, and each
//! binary linked the whole crate with wgpu and naga: most of a fresh test build was
//! linking). Shared model builders are in `tests/common`.

#[path = "../common/mod.rs"]
mod common;

mod ale;
mod ancf;
mod axial;
mod bending;
mod bodies;
mod body_knots;
mod body_statics;
mod case1;
mod catenary;
mod chain_kernel;
mod dynamics;
mod frames;
mod free_bodies;
mod froude_krylov;
mod net_kernel;
mod nets;
mod packed;
mod parallel;
mod screen;
mod seabed_friction;
mod seabed_implicit;
mod seabed_slope;
mod statics;
mod stiff_statics;
mod study;
mod study_validation;
mod visco;
mod water_surface;
mod waves_output;
mod waves_steppers;
mod winch_kernel;
