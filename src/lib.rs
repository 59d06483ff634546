//! cablesim: many underwater cables at once, with the Global Lumped Mass Formulation.
//!
//! Data flow: a scenario file ([`scenario`]) describes line types, cables and their
//! ends; it becomes a [`model::ModelDef`], which is packed into a [`model::Layout`]
//! (flat arrays over every cable of the run); the initial shape is relaxed to static
//! equilibrium ([`statics`]); a stepper ([`cpu::CpuSolver`], the f64 reference path)
//! advances it; [`sim`] drives the run and [`output`] writes what users read. Cables
//! of varying length (winch payout and retrieval) are the ALE-GLMF of [`ale`], which
//! the CPU stepper applies and remeshes between steps.
#![warn(missing_docs)]

pub mod ale;
pub mod ancf;
pub mod body;
pub mod cpu;
pub mod error;
pub mod gpu;
pub mod math;
pub mod model;
pub mod options;
pub mod physics;
pub mod statics;

pub use error::{Error, Result};
pub mod initial;
pub mod output;
pub mod scenario;
pub mod sea;
pub mod sim;
pub mod stability;
