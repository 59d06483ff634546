//! The f64 CPU reference stepper.
//!
//! A step runs the same passes the GPU runs, over the same packed layout:
//! 1. `element_forces`: per element, tangent, axial force, half external load and
//!    half mass ([`crate::physics::glmf_element`], or an older frame);
//! 2. `node_update`: per node, gather over the incidence list, add point-mass loads
//!    and seabed contact, build the 3x3 mass block, and solve for the acceleration;
//!    constrained nodes take the Baumgarte acceleration of their route instead and
//!    record the reaction;
//! 3. the time update of the chosen scheme.
//!
//! Blocks (connected components) are independent, so each is advanced through a whole
//! output interval on its own, and blocks are spread over threads with rayon.
//!
//! Three implementations of the passes: the general path over any graph
//! (`passes`: incidence lists, per node; the reference), the vectorised chain path
//! (`chain`: a block that is one chain in node order) and the vectorised network path
//! (`chain::net`: any other block, GLMF and symplectic, the chain path's element loop
//! behind a gather). A big network is stepped by all threads together (`threaded`,
//! `chain::net`).
//!
//! Winch cables (ALE-GLMF, [`crate::ale`]) take the general passes with their variable
//! element's length and mass-flow forces evaluated at each stage's time, and are
//! remeshed between steps ([`CpuSolver::with_winches`]).

pub(crate) mod chain;
mod free;
mod passes;
pub(crate) mod screen;
mod solver;
mod threaded;
mod water;

pub use crate::step::{Evaluation, StepFailure, WinchStatus};
pub use solver::{CpuCheckpoint, CpuSolver};
