//! The design check of a line, in the style of DNV-OS-E301 (ultimate limit state):
//! the design tension `T_d = g_mean T_mean + g_dyn (T_MPM - T_mean)` from the mean
//! tension and the most probable maximum, and the utilisation `T_d / S_C` against the
//! line's characteristic strength. The partial safety factors `g_mean`, `g_dyn` and the
//! capacities are inputs, or the factors are taken by consequence class
//! ([`super::definition::dnv_factors`]): the intact mooring's (ULS) and the damaged
//! conditions' (ALS).

use serde::{Deserialize, Serialize};

/// The design check of one channel in one sea state.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DesignCheck {
    /// Characteristic strength of the line `S_C`, N.
    pub capacity: f64,
    /// Mean tension `T_mean`, N.
    pub mean_tension: f64,
    /// Most probable maximum tension `T_MPM`, N.
    pub mpm_tension: f64,
    /// Design tension `T_d`, N.
    pub design_tension: f64,
    /// `T_d / S_C` (the line passes when at most 1).
    pub utilisation: f64,
    /// The partial safety factor applied to the mean tension `g_mean`.
    #[serde(default)]
    pub mean_factor: f64,
    /// The partial safety factor applied to the dynamic tension `g_dyn`.
    #[serde(default)]
    pub dynamic_factor: f64,
}

/// `g_mean T_mean + g_dyn (T_MPM - T_mean)`, N.
pub fn design_tension(mean_factor: f64, dynamic_factor: f64, mean: f64, mpm: f64) -> f64 {
    mean_factor * mean + dynamic_factor * (mpm - mean)
}

impl DesignCheck {
    /// The check of a line of capacity `capacity` (N) with mean tension `mean` and most
    /// probable maximum `mpm` (N), under the factors `mean_factor`, `dynamic_factor`.
    pub fn new(
        capacity: f64,
        mean_factor: f64,
        dynamic_factor: f64,
        mean: f64,
        mpm: f64,
    ) -> DesignCheck {
        let design_tension = design_tension(mean_factor, dynamic_factor, mean, mpm);
        DesignCheck {
            capacity,
            mean_tension: mean,
            mpm_tension: mpm,
            design_tension,
            utilisation: design_tension / capacity,
            mean_factor,
            dynamic_factor,
        }
    }
}
