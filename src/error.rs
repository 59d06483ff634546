//! The library's one error type.

use std::path::PathBuf;

/// Everything that can go wrong, with enough context to act on.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scenario file is wrong: which file, which field, what is wrong.
    #[error("{path}: {field}: {message}")]
    Scenario {
        /// The file.
        path: PathBuf,
        /// The offending field, as a dotted path (`cables[2].length`).
        field: String,
        /// What is wrong with it.
        message: String,
    },
    /// A model that cannot be built (inconsistent cables and nodes).
    #[error("model: {0}")]
    Model(String),
    /// The state became non-finite or absurd.
    #[error("simulation diverged at t = {time:.6} s: cable '{cable}', node {node}: {what}")]
    Diverged {
        /// Cable name.
        cable: String,
        /// Node index within the cable.
        node: usize,
        /// Simulated time, s.
        time: f64,
        /// What was found (non-finite position, speed over the limit, ...).
        what: String,
    },
    /// An element frame (Euler, Frenet, RVEF) has no defined orientation.
    #[error(
        "{frame} frame singular at t = {time:.6} s: cable '{cable}', element {element}: {reason}"
    )]
    SingularFrame {
        /// The frame.
        frame: &'static str,
        /// Cable name.
        cable: String,
        /// Element index within the cable.
        element: usize,
        /// Simulated time, s.
        time: f64,
        /// Why.
        reason: String,
    },
    /// A winch cannot follow its payout schedule (drum capacity, hauled in past the
    /// cable's last node).
    #[error("winch of cable '{cable}' at t = {time:.6} s: {message}")]
    Winch {
        /// Cable name.
        cable: String,
        /// Simulated time, s.
        time: f64,
        /// What limit was passed.
        message: String,
    },
    /// The static solver did not reach equilibrium.
    #[error("initial equilibrium: {0}")]
    Statics(String),
    /// Writing output failed.
    #[error("output {path}: {source}")]
    Output {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// No usable GPU adapter.
    #[error("no GPU adapter: {0}")]
    NoAdapter(String),
    /// The GPU device failed (validation error, out of memory, device lost).
    #[error("GPU: {0}")]
    Gpu(String),
    /// A file to plot could not be read, or a plot could not be drawn.
    #[error("plot: {path}: {message}")]
    Plot {
        /// The file read or written.
        path: PathBuf,
        /// The problem (the column and the value, where one is at fault).
        message: String,
    },
    /// The model or options use something the GPU path does not do yet.
    #[error("not supported on the GPU path yet: {0}")]
    GpuUnsupported(String),
}

/// Result with the library's error.
pub type Result<T, E = Error> = std::result::Result<T, E>;
