//! The design check of a line, in the style of DNV-OS-E301 (ultimate limit state):
//! the design tension `T_d = g_mean T_mean + g_dyn (T_MPM - T_mean)` from the mean
//! tension and the most probable maximum, and the utilisation `T_d / S_C` against the
//! line's characteristic strength. The partial safety factors `g_mean`, `g_dyn` and the
//! capacities are inputs: the standard's values depend on the consequence class and the
//! analysis (e.g. 1.1 and 1.5, or 1.4 and 2.1), which are the user's call.

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
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn design_tension_and_utilisation_against_hand_values() {
        // T_mean 2.0 MN, T_MPM 3.5 MN, factors 1.1 and 1.5:
        // T_d = 2.2 + 1.5 * 1.5 = 4.45 MN; on S_C = 8.9 MN, utilisation 0.5.
        let c = DesignCheck::new(8.9e6, 1.1, 1.5, 2.0e6, 3.5e6);
        assert!((c.design_tension - 4.45e6).abs() < 1e-6);
        assert!((c.utilisation - 0.5).abs() < 1e-15);
        // Unit factors give back the MPM itself.
        assert_eq!(design_tension(1.0, 1.0, 2.0e6, 3.5e6), 3.5e6);
        // A consequence class 2 set (1.4, 2.1): 2.8 + 3.15 = 5.95 MN.
        assert!((design_tension(1.4, 2.1, 2.0e6, 3.5e6) - 5.95e6).abs() < 1e-6);
    }
}
