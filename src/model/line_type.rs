//! Line types: the material and hydrodynamic properties of a cable.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A line type (docs/src/model/conventions.md). Every field is in SI units.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LineType {
    /// Name that cables refer to.
    pub name: String,
    /// Hydrodynamic (and volumetric) diameter `d`, m.
    pub diameter: f64,
    /// Mass per unit unstretched length `mbar`, kg/m.
    pub mass_per_length: f64,
    /// Axial stiffness `EA`, N.
    pub ea: f64,
    /// Internal damping time constant `c`, s (the axial damping force is `EA c epsdot`).
    #[serde(default)]
    pub damping: f64,
    /// Normal drag coefficient `Cn` (on the diameter).
    #[serde(default = "default_cn")]
    pub cn: f64,
    /// Tangential drag coefficient `Ct` (on the circumference `pi d`).
    #[serde(default = "default_ct")]
    pub ct: f64,
    /// Normal added-mass coefficient `Cm`.
    #[serde(default = "default_cm")]
    pub cm: f64,
    /// Tangential added-mass coefficient `Cat` (MoorDyn's `CaAx`, v1 `Cat`): the added
    /// mass along the line, on the displaced volume (default 0, as MoorDyn's).
    #[serde(default)]
    pub cat: f64,
    /// Bending stiffness `EI`, N m^2 (0: a cable without bending; docs/src/model/bending.md).
    #[serde(default)]
    pub ei: f64,
    /// When true, the elastic force also acts in compression (a rod, not a rope).
    #[serde(default)]
    pub allow_compression: bool,
    /// Nonlinear axial stiffness: the tension as a function of the strain, rows
    /// `(strain, tension)` (`physics::axial`). When given, `ea` is the curve's largest
    /// slope (the stable step and the internal damping `EA c` take it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ea_curve: Option<Vec<[f64; 2]>>,
    /// The static-dynamic (viscoelastic) model of a fibre rope (`physics::visco`):
    /// `ea` is then the static stiffness `EA_s`, and `damping` is zero. Formed from the
    /// scenario keys `ea_dynamic`, `ea_dynamic_slope`, `ba_static`, `ba_dynamic`
    /// (`scenario::materials`), not a key of its own.
    #[serde(skip)]
    pub viscoelastic: Option<Viscoelastic>,
}

/// The viscoelastic (static-dynamic) axial model of a fibre rope
/// (docs/src/model/axial.md#viscoelastic-fibre-rope; MoorDyn's `EA_s|EA_d` and
/// `EA_s|EA_Dc|EA_D_Lm` with `BA_s|BA_d`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Viscoelastic {
    /// The dynamic stiffness `EA_d`, N; with `ea_dynamic_slope`, its value at zero mean
    /// tension `EA_Dc`.
    pub ea_dynamic: f64,
    /// The slope `EA_D_Lm` of the dynamic stiffness against the mean tension (-): 0 for
    /// a constant dynamic stiffness.
    #[serde(default)]
    pub ea_dynamic_slope: f64,
    /// The static branch's damping `BA_s`, N s (on the strain rate).
    pub ba_static: f64,
    /// The dynamic spring's damping `BA_d`, N s.
    #[serde(default)]
    pub ba_dynamic: f64,
}

fn default_cn() -> f64 {
    1.0
}
fn default_ct() -> f64 {
    0.01
}
fn default_cm() -> f64 {
    1.0
}

impl LineType {
    /// Cross-section area `A = pi d^2 / 4`, m^2.
    pub fn area(&self) -> f64 {
        PI * self.diameter * self.diameter / 4.0
    }
    /// Weight less buoyancy per unit length, N/m (positive when the line sinks).
    pub fn wet_weight_per_length(&self, gravity: f64, water_density: f64) -> f64 {
        (self.mass_per_length - water_density * self.area()) * gravity
    }
    /// Axial wave speed `sqrt(EA / mbar)`, m/s.
    pub fn wave_speed(&self) -> f64 {
        (self.ea / self.mass_per_length).sqrt()
    }
}

/// Per-line-type constants folded for the force loops (water density and gravity in).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LineCoefs {
    /// `EA`, N.
    pub ea: f64,
    /// `EA c`, N s.
    pub ea_c: f64,
    /// `1/2 rho Cn d`: normal drag per unit length per (m/s)^2, kg/m^2.
    pub drag_n: f64,
    /// `1/2 rho Ct pi d`: tangential drag per unit length per (m/s)^2, kg/m^2.
    pub drag_t: f64,
    /// `(1 + Cm) rho A`: water-acceleration load per unit length per m/s^2 across the
    /// line, kg/m.
    pub froude_krylov: f64,
    /// `(1 + Cat) rho A`: water-acceleration load per unit length per m/s^2 along the
    /// line, kg/m.
    pub froude_krylov_t: f64,
    /// `mbar`, kg/m.
    pub mass: f64,
    /// `Cm rho A`: normal added mass per unit length, kg/m.
    pub added_mass: f64,
    /// `Cat rho A`: tangential added mass per unit length, kg/m.
    pub added_mass_t: f64,
    /// `(mbar - rho A) g`, the z component of weight less buoyancy per length, N/m (negative: down).
    pub wet_weight_z: f64,
    /// 1.0 when the elastic force acts in compression too, else 0.0.
    pub compression: f64,
}

impl LineCoefs {
    /// Folds a line type with the water density `rho` and gravity magnitude `g`.
    pub fn new(lt: &LineType, rho: f64, g: f64) -> Self {
        let a = lt.area();
        Self {
            ea: lt.ea,
            ea_c: lt.ea * lt.damping,
            drag_n: 0.5 * rho * lt.cn * lt.diameter,
            drag_t: 0.5 * rho * lt.ct * PI * lt.diameter,
            froude_krylov: (1.0 + lt.cm) * rho * a,
            froude_krylov_t: (1.0 + lt.cat) * rho * a,
            mass: lt.mass_per_length,
            added_mass: lt.cm * rho * a,
            added_mass_t: lt.cat * rho * a,
            wet_weight_z: -(lt.mass_per_length - rho * a) * g,
            compression: if lt.allow_compression { 1.0 } else { 0.0 },
        }
    }
}
