//! Initial shapes: straight lines as laid out by the scenario, or catenaries relaxed to
//! the discrete model's static equilibrium (MODEL.md "Initial conditions").

use crate::error::Error;
use crate::model::Layout;
use crate::scenario::{InitialShape, Scenario};

/// Applies each cable's initial shape to `pos` (packed order). Returns the largest
/// residual force left by the relaxation, N (0 when nothing was relaxed).
pub fn apply(sc: &Scenario, lay: &Layout, pos: &mut [[f64; 3]]) -> Result<f64, Error> {
    let _ = (lay, pos);
    if sc.initial.iter().any(|s| *s == InitialShape::Catenary) {
        log::warn!("catenary initial shapes are not wired yet: starting straight");
    }
    Ok(0.0)
}
