//! What an ANCF cable is built from: its ends ([`AncfEnd`]) and configuration
//! ([`AncfConfig`]), and the error for a bad one.

use crate::ale::Winch;
use crate::error::Error;
use crate::model::{Current, Environment, LineType, PointMass, Route};
use crate::options::{AddedMass, Scheme};

/// Fraction of the stable step taken when no step is given.
pub const AUTO_SAFETY: f64 = 0.8;

/// One end of an ANCF cable (node 0 or node `n`).
#[derive(Clone, Debug, PartialEq)]
pub struct AncfEnd {
    /// Initial position, m (an end on a route is put on it instead).
    pub position: [f64; 3],
    /// Prescribed motion of the end's position (held or driven); `None`: free.
    pub route: Option<Route>,
    /// Prescribed (clamped) slope `r'`, held constant; `None`: the slope is free (a
    /// pinned or free end). A cantilever's root has both.
    pub slope: Option<[f64; 3]>,
    /// A point mass at the end (mass, buoyancy, isotropic drag and added mass).
    pub point: PointMass,
    /// A constant applied force on the end, N (a tip load, a tow force).
    pub force: [f64; 3],
}

impl AncfEnd {
    /// A free end starting at `p`.
    pub fn free(p: [f64; 3]) -> Self {
        Self {
            position: p,
            route: None,
            slope: None,
            point: PointMass::default(),
            force: [0.0; 3],
        }
    }
    /// An end held at `p` (pinned: its slope is free).
    pub fn fixed(p: [f64; 3]) -> Self {
        Self::driven(Route::Fixed { position: p })
    }
    /// An end driven along `route`.
    pub fn driven(route: Route) -> Self {
        Self {
            position: route.eval(0.0).r,
            route: Some(route),
            ..Self::free([0.0; 3])
        }
    }
    /// An end held at `p` with its slope clamped to `slope` (a cantilever's root).
    pub fn clamped(p: [f64; 3], slope: [f64; 3]) -> Self {
        Self {
            slope: Some(slope),
            ..Self::fixed(p)
        }
    }
    /// The same end carrying point mass `pm`.
    pub fn with_point(mut self, pm: PointMass) -> Self {
        self.point = pm;
        self
    }
    /// The same end with a constant applied force `f`, N.
    pub fn with_force(mut self, f: [f64; 3]) -> Self {
        self.force = f;
        self
    }
}

/// Everything an [`AncfCable`](super::AncfCable) is built from.
#[derive(Clone, Debug, PartialEq)]
pub struct AncfConfig {
    /// Name used in error messages.
    pub name: String,
    /// The line type (`ei` is the bending stiffness; `damping` the time constant `c` of
    /// both the axial and the bending damping).
    pub line_type: LineType,
    /// Unstretched length, m.
    pub length: f64,
    /// Number of equal elements.
    pub elements: usize,
    /// The end at arc length 0 (node 0).
    pub start: AncfEnd,
    /// The end at arc length `length` (node `elements`).
    pub end: AncfEnd,
    /// Gravity, water density, seabed (`depth = f64::INFINITY`: none).
    pub env: Environment,
    /// Current.
    pub current: Current,
    /// Uniform water acceleration `a_w`, m/s^2.
    pub water_accel: [f64; 3],
    /// Gauss points per element for the loads and the normal added mass (default 5:
    /// exact for the elastic axial force of the Green strain, a polynomial of degree 8;
    /// drag, curvature and contact to the rule's accuracy). The constant mass matrix and
    /// weights always use at least 4 points, exact for them.
    pub gauss_points: usize,
    /// Time scheme (default symplectic Euler).
    pub scheme: Scheme,
    /// Time step, s; `None`: [`AUTO_SAFETY`] of the stable step.
    pub dt: Option<f64>,
    /// How the normal added mass enters the mass matrix (default: exactly, with the
    /// tangent at each Gauss point).
    pub added_mass: AddedMass,
    /// A node faster than this, m/s, stops the run as a blow-up.
    pub max_speed: f64,
    /// A winch at one end (ALE-ANCF): that end must be on a route; its `element_length`
    /// is the standard element length of the remeshing rules (`cable` is ignored).
    pub winch: Option<Winch>,
}

impl AncfConfig {
    /// A configuration with the defaults: no current, no water acceleration, 5 Gauss
    /// points, symplectic Euler, automatic step.
    pub fn new(
        line_type: LineType,
        length: f64,
        elements: usize,
        start: AncfEnd,
        end: AncfEnd,
        env: Environment,
    ) -> Self {
        Self {
            name: "ancf".into(),
            line_type,
            length,
            elements,
            start,
            end,
            env,
            current: Current::uniform([0.0; 3]),
            water_accel: [0.0; 3],
            gauss_points: 5,
            scheme: Scheme::Symplectic,
            dt: None,
            added_mass: AddedMass::Normal,
            max_speed: 1e4,
            winch: None,
        }
    }
}

pub(super) fn bad(name: &str, msg: impl std::fmt::Display) -> Error {
    Error::Model(format!("ANCF cable '{name}': {msg}"))
}
