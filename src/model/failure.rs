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

/// Where a failure acts in a packed layout: the end's node, the end element (whose
/// tension triggers it) and the constraint (route) holding the node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FailureSite {
    /// Packed node of the end.
    pub node: usize,
    /// Packed element at the end.
    pub elem: usize,
    /// The constraint holding the node.
    pub constraint: usize,
}

impl EndFailure {
    /// The end's node and element in `lay`, and the constraint holding it; `Err` when
    /// the run has no such cable or the end is not held (nothing to fail). Both
    /// stepping paths resolve failures through this.
    pub fn site(&self, lay: &super::Layout) -> Result<FailureSite, String> {
        let c = lay
            .cables
            .iter()
            .find(|c| c.name == self.cable)
            .ok_or_else(|| {
                format!(
                    "a failure names cable '{}', which the run does not have",
                    self.cable
                )
            })?;
        let (node, elem) = if self.at_start {
            (c.nodes[0], c.elements[0])
        } else {
            (c.nodes[c.nodes.len() - 1], c.elements[c.elements.len() - 1])
        };
        let k = lay.node_constraint[node as usize];
        if k == super::NO_CONSTRAINT {
            return Err(format!(
                "cable '{}': its {} end is not held, so it cannot fail",
                self.cable,
                if self.at_start { "start" } else { "end" }
            ));
        }
        Ok(FailureSite {
            node: node as usize,
            elem: elem as usize,
            constraint: k as usize,
        })
    }
}
