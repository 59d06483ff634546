//! cablesim: many underwater cables at once, with the Global Lumped Mass Formulation.
//!
//! # The pipeline
//! One pipeline with one driver, [`Simulation`] ([`sim`]): scenario -> model -> initial
//! state -> step plan -> backend -> output sink.
//! 1. A scenario file or string ([`scenario`]) describes line types, cables and their
//!    ends; the run options ([`options`]: backend, precision, scheme, formulation, cable
//!    model, as enums) come from it and from the caller's [`Overrides`].
//! 2. It becomes a [`model::ModelDef`], packed into a [`model::Layout`] (flat arrays
//!    over every cable of the run).
//! 3. The initial state ([`initial`]): catenaries relaxed to the discrete static
//!    equilibrium ([`statics`]).
//! 4. The step plan ([`sim::plan`]): the stable step ([`stability`]) fitted to the
//!    output interval.
//! 5. A backend steps it: the f64 CPU reference ([`cpu::CpuSolver`]), the GPU path
//!    ([`gpu::GpuSolver`]), or the ANCF reference model ([`ancf`]); the lumped-mass
//!    backends share their step results and blow-up check ([`step`]) and the ALE-GLMF
//!    of winch cables ([`ale`]: payout, remeshing, mass-flow forces).
//! 6. At each output time a [`Snapshot`] goes to the [`OutputSink`] the caller chose
//!    ([`output`]: [`FileSink`] writes the files users read, [`MemorySink`] keeps them).
//!
//! Modules import only modules earlier in the pipeline or below it (`math`, `error`,
//! `options`, `model`, `physics`), never one that imports them.
//!
//! The library prints nothing: it logs through the `log` crate, reports progress to a
//! callback ([`Simulation::run`]), and returns the crate's [`Error`].
#![warn(missing_docs)]
// `!(x <= limit)` and the like are the crate's checks that also catch NaN (a NaN
// compares false, so the negation is true): written so on purpose, not `x > limit`.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod ale;
pub mod ancf;
pub mod body;
pub mod cpu;
pub mod error;
pub mod fatigue;
pub mod gpu;
pub mod initial;
pub mod input;
pub mod lanes;
pub mod math;
pub mod model;
pub mod moordyn;
pub mod options;
pub mod output;
pub mod physics;
pub mod plot;
pub mod scenario;
pub mod sea;
pub mod sim;
pub mod stability;
pub mod statics;
pub mod step;
pub mod study;
#[doc(hidden)]
pub mod testing;

pub use error::{Error, Result};
pub use options::Overrides;
pub use output::{FileSink, MemorySink, OutputSink, Snapshot};
pub use sim::Simulation;
