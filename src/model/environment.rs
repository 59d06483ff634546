//! Water, gravity, seabed, and currents.

use crate::math::{Real, V3};
use serde::{Deserialize, Serialize};

/// Seabed contact constants (docs/src/model/seabed.md), per metre of cable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seabed {
    /// Normal stiffness `K`, N/m per m of cable (Pa).
    #[serde(default = "default_k")]
    pub stiffness: f64,
    /// Normal damping `C`, N s/m per m of cable.
    #[serde(default = "default_c")]
    pub damping: f64,
    /// Coulomb friction coefficient `mu`: in every direction, or across the line
    /// (transverse) where `friction_axial` differs. Set by `friction` or
    /// `friction_transverse` (the scenario reader resolves the latter into this).
    #[serde(default)]
    pub friction: f64,
    /// The transverse coefficient `mu_t` as the scenario gives it (`None`: `friction`).
    /// Resolved into `friction` when the scenario is read.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_transverse: Option<f64>,
    /// The axial coefficient `mu_a` (along the line); `None`: `friction`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_axial: Option<f64>,
    /// Regularisation velocity `v_eps` of the friction law, m/s: below it friction
    /// grows linearly with sliding speed instead of jumping (so a line at rest feels none).
    #[serde(default = "default_v_eps")]
    pub friction_velocity: f64,
    /// A seabed grid (`[environment] seabed_file`): contact with it instead of the plane
    /// `z = -depth` (docs/src/model/seabed.md). Not a key of `[environment.seabed]`.
    #[serde(skip)]
    pub grid: Option<&'static super::Bathymetry>,
}

impl Seabed {
    /// The axial friction coefficient `mu_a` (`friction` unless `friction_axial`).
    pub fn mu_axial(&self) -> f64 {
        self.friction_axial.unwrap_or(self.friction)
    }

    /// Whether the friction differs along and across the line.
    pub fn split_friction(&self) -> bool {
        self.mu_axial() != self.friction
    }
}

fn default_k() -> f64 {
    3.0e6
}
fn default_c() -> f64 {
    3.0e4
}
fn default_v_eps() -> f64 {
    0.01
}

impl Default for Seabed {
    fn default() -> Self {
        Self {
            stiffness: default_k(),
            damping: default_c(),
            friction: 0.0,
            friction_transverse: None,
            friction_axial: None,
            friction_velocity: default_v_eps(),
            grid: None,
        }
    }
}

/// The environment every cable of a run shares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Environment {
    /// Gravity magnitude `g`, m/s^2 (acting along -z).
    pub gravity: f64,
    /// Water density `rho`, kg/m^3.
    pub water_density: f64,
    /// Water depth, m: the seabed plane is `z = -depth`.
    pub depth: f64,
    /// Seabed contact constants.
    pub seabed: Seabed,
}

impl Default for Environment {
    fn default() -> Self {
        Self {
            gravity: 9.81,
            water_density: 1025.0,
            depth: 100.0,
            seabed: Seabed::default(),
        }
    }
}

/// A current, uniform or varying with depth (piecewise linear in `z`, constant beyond
/// the table's ends). Each cable has its own (per-cable environment).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Current {
    /// `(z, [ux, uy, uz])`, sorted by increasing `z`; one entry means uniform.
    pub table: Vec<(f64, [f64; 3])>,
}

impl Current {
    /// A uniform current.
    pub fn uniform(u: [f64; 3]) -> Self {
        Self {
            table: vec![(0.0, u)],
        }
    }
    /// True when the current is zero everywhere.
    pub fn is_still(&self) -> bool {
        self.table.iter().all(|(_, u)| u.iter().all(|c| *c == 0.0))
    }
    /// Current velocity at height `z`, m/s.
    #[inline]
    pub fn at<T: Real>(&self, z: T) -> V3<T> {
        let tab = &self.table;
        match tab.len() {
            0 => V3::zero(),
            1 => V3::from_f64(tab[0].1),
            n => {
                let z = z.f64();
                if z <= tab[0].0 {
                    return V3::from_f64(tab[0].1);
                }
                if z >= tab[n - 1].0 {
                    return V3::from_f64(tab[n - 1].1);
                }
                // Tables are short (a handful of depths): a linear scan beats a search.
                let mut i = 1;
                while tab[i].0 < z {
                    i += 1;
                }
                let (z0, u0) = tab[i - 1];
                let (z1, u1) = tab[i];
                let s = (z - z0) / (z1 - z0);
                V3::new(
                    T::c(u0[0] + s * (u1[0] - u0[0])),
                    T::c(u0[1] + s * (u1[1] - u0[1])),
                    T::c(u0[2] + s * (u1[2] - u0[2])),
                )
            }
        }
    }
}
