//! Screen-model nets (docs/src/model/screen.md): the netting between a net's knots
//! loaded as panels (solidity, angle to the flow, twine Reynolds number) instead of
//! its twines' Morison drag. A net's knots form a grid; each knot knows its eight grid
//! neighbours, so it can gather the force of the (up to four) panels it is a corner of
//! without atomics: every knot takes a quarter of each of its panels.

use crate::physics::screen::{
    SCREEN_AARSNES, SCREEN_KRISTIANSEN_FALTINSEN, SCREEN_LOLAND, WAKE_CHENG, WAKE_LOLAND, WAKE_NONE,
};
use crate::physics::ScreenCoefs;

/// No neighbour (a knot on the edge of the grid).
pub const NO_KNOT: u32 = u32::MAX;

/// The coefficient set of a screen net.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScreenModel {
    /// Aarsnes (1990).
    Aarsnes,
    /// Løland (1991).
    Loland,
    /// Kristiansen and Faltinsen (2012), with the Reynolds number of the twines.
    KristiansenFaltinsen,
}

impl ScreenModel {
    /// Parses a scenario's `screen_model`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "aarsnes" => Some(Self::Aarsnes),
            "loland" => Some(Self::Loland),
            "kristiansen_faltinsen" => Some(Self::KristiansenFaltinsen),
            _ => None,
        }
    }
    /// The code the force functions take.
    pub fn code(self) -> u32 {
        match self {
            Self::Aarsnes => SCREEN_AARSNES,
            Self::Loland => SCREEN_LOLAND,
            Self::KristiansenFaltinsen => SCREEN_KRISTIANSEN_FALTINSEN,
        }
    }
}

/// How the flow is slowed for the panels in the wake of the net.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WakeModel {
    /// Not slowed.
    None,
    /// Løland: `r = 1 - 0.46 C_D(0)`.
    Loland,
    /// Cheng et al. (2020): `r = (cos a + 0.05 - 0.38 Sn) / (cos a + 0.05)`.
    Cheng,
}

impl WakeModel {
    /// Parses a scenario's `wake`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "none" => Some(Self::None),
            "loland" => Some(Self::Loland),
            "cheng" => Some(Self::Cheng),
            _ => None,
        }
    }
    /// The code the force functions take.
    pub fn code(self) -> u32 {
        match self {
            Self::None => WAKE_NONE,
            Self::Loland => WAKE_LOLAND,
            Self::Cheng => WAKE_CHENG,
        }
    }
}

/// One screen net's constants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenNet {
    /// The coefficient set.
    pub model: ScreenModel,
    /// Solidity `Sn`, 0 < Sn < 1.
    pub solidity: f64,
    /// Diameter of the real twines, m (their Reynolds number).
    pub twine_diameter: f64,
    /// Kinematic viscosity of the water, m^2/s.
    pub viscosity: f64,
    /// The wake rule.
    pub wake: WakeModel,
    /// The vertical axis `(x, y)` whose downstream side is in the wake, m.
    pub axis: [f64; 2],
}

impl ScreenNet {
    /// The constants as the force functions take them, for water of density `rho`,
    /// the axis shifted by `-origin` (the GPU path's block origin).
    pub fn coefs(&self, rho: f64, origin: [f64; 2]) -> ScreenCoefs<f64> {
        ScreenCoefs {
            model: self.model.code(),
            wake: self.wake.code(),
            sn: self.solidity,
            re_scale: self.twine_diameter / (self.viscosity * (1.0 - self.solidity)),
            half_rho: 0.5 * rho,
            axis_x: self.axis[0] - origin[0],
            axis_y: self.axis[1] - origin[1],
        }
    }
}

/// A knot of a screen net and its grid neighbours, in the order (row, column offset)
/// `(-1,-1) (-1,0) (-1,1) (0,1) (1,1) (1,0) (1,-1) (0,-1)` ([`NO_KNOT`] where the grid
/// ends). Its panels are the grid cells it is a corner of: [`knot_panels`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScreenKnot {
    /// The knot's node.
    pub node: u32,
    /// Index of its net in `screens`.
    pub net: u32,
    /// Its neighbours' nodes.
    pub around: [u32; 8],
}

/// The four grid cells around a knot, each by its corners in the order top-left,
/// top-right, bottom-right, bottom-left: entries of `around`, 8 meaning the knot
/// itself. The order is the same for every knot of a cell, so the four knots of a
/// cell compute its force identically.
pub const KNOT_PANELS: [[usize; 4]; 4] = [[0, 1, 8, 7], [1, 2, 3, 8], [8, 3, 4, 5], [7, 8, 5, 6]];

/// The corner nodes of the panels of knot `k` (those whose corners all exist).
pub fn knot_panels(k: &ScreenKnot) -> impl Iterator<Item = [u32; 4]> + '_ {
    KNOT_PANELS.iter().filter_map(move |q| {
        let c = q.map(|j| if j == 8 { k.node } else { k.around[j] });
        c.iter().all(|&n| n != NO_KNOT).then_some(c)
    })
}

/// The screen nets of a model or a layout: the nets and their knots, sorted by node
/// in a layout.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Screens {
    /// The nets.
    pub nets: Vec<ScreenNet>,
    /// Every knot of every screen net.
    pub knots: Vec<ScreenKnot>,
    /// The twines' line types made for screen nets (their drag taken off), each with
    /// the line type it was copied from: `(copy, original)`, indices into the model's
    /// line types.
    pub twine_lines: Vec<(usize, usize)>,
}

impl Screens {
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.knots.is_empty()
    }
    /// The knots whose nodes lie in `start..end` (the knots sorted by node).
    pub fn knots_in(&self, start: u32, end: u32) -> &[ScreenKnot] {
        let a = self.knots.partition_point(|k| k.node < start);
        let b = self.knots.partition_point(|k| k.node < end);
        &self.knots[a..b]
    }
    /// The same nets with node indices mapped by `f` (`NO_KNOT` kept), sorted by node.
    pub fn mapped(&self, f: impl Fn(u32) -> u32) -> Screens {
        let m = |n: u32| if n == NO_KNOT { n } else { f(n) };
        let mut knots: Vec<ScreenKnot> = self
            .knots
            .iter()
            .map(|k| ScreenKnot {
                node: m(k.node),
                net: k.net,
                around: k.around.map(m),
            })
            .collect();
        knots.sort_by_key(|k| k.node);
        Screens {
            nets: self.nets.clone(),
            knots,
            twine_lines: self.twine_lines.clone(),
        }
    }
    /// Appends `o`'s nets and knots, its node indices shifted by `dn` and its line
    /// types by `dl`.
    pub fn append(&mut self, o: &Screens, dn: u32, dl: usize) {
        self.twine_lines
            .extend(o.twine_lines.iter().map(|&(a, b)| (a + dl, b + dl)));
        let n0 = self.nets.len() as u32;
        self.nets.extend_from_slice(&o.nets);
        let m = |n: u32| if n == NO_KNOT { n } else { n + dn };
        self.knots.extend(o.knots.iter().map(|k| ScreenKnot {
            node: m(k.node),
            net: k.net + n0,
            around: k.around.map(m),
        }));
    }
}
