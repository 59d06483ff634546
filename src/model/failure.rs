//! Line failures: a cable end that leaves its support (a fixed point, a route or a
//! body) at a given time, or when its tension first reaches a given value, and carries
//! on as a free end (with its point mass, if it has one).

use serde::Serialize;

/// A cable end that may fail during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct EndFailure {
    /// The cable's name.
    pub cable: String,
    /// Whether it is the cable's start (else its end).
    pub at_start: bool,
    /// Fails at this time, s (when `t >= time`).
    pub time: Option<f64>,
    /// Fails when the end element's tension first reaches this value, N.
    pub tension: Option<f64>,
}

/// A failure that happened.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FailureEvent {
    /// Time, s (the end of the step at which it fired).
    pub time: f64,
    /// The cable's name.
    pub cable: String,
    /// `"start"` or `"end"`.
    pub end: String,
    /// The end element's tension when it failed, N.
    pub tension: f64,
    /// What fired it: `"time"` or `"tension"`.
    pub trigger: String,
}
