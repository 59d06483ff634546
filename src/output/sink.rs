//! The sink interface and the state it receives.

use super::summary::{EndForces, Summary, WinchSummary};
use crate::error::Error;

/// Where a run's output goes: a frame at each output time (`t = 0` first), then the
/// summary once the run ends, completed or not.
pub trait OutputSink {
    /// Takes the state at one output time.
    fn frame(&mut self, snapshot: &Snapshot) -> Result<(), Error>;
    /// Takes the state at one output time, owned: what the run hands out, so that a
    /// sink that keeps or sends a frame on (the file writer's thread) need not copy it.
    /// By default [`OutputSink::frame`].
    fn frame_owned(&mut self, snapshot: Snapshot) -> Result<(), Error> {
        self.frame(&snapshot)
    }
    /// Takes the summary of the run (after its last frame; also when it diverged).
    fn finish(&mut self, summary: &Summary) -> Result<(), Error>;
}

/// The state of every cable at one time: a read-only copy, in scenario order.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// Simulated time, s.
    pub time: f64,
    /// Steps taken (the most of any cable for the ANCF model, whose cables each step at
    /// their own `dt`).
    pub steps: u64,
    /// Per cable.
    pub cables: Vec<CableState>,
    /// Per vessel body that cable ends are attached to (empty without bodies).
    pub bodies: Vec<BodyState>,
    /// Per shared point (`[[points]]` that cables attach to), in scenario order; empty
    /// for the ANCF model.
    pub points: Vec<PointState>,
    /// Per cylindrical net (`[[nets]]` of `shape = "cylinder"`), in scenario order: its
    /// volume and the water's force on it (`nets.csv`); empty for the ANCF model.
    pub nets: Vec<NetState>,
}

/// A cylindrical net's (a cage's) enclosed volume and the water's force on it, at one
/// time (`crate::model::cage`).
#[derive(Clone, Debug, PartialEq)]
pub struct NetState {
    /// Name.
    pub name: String,
    /// The volume its knots enclose, closed by its top and bottom rows' polygons
    /// ([`crate::model::cage::enclosed_volume`]), m^3.
    pub volume: f64,
    /// `volume` over the volume of the net as generated (its knots on the cylinder).
    pub volume_ratio: f64,
    /// The water's horizontal force on its twines (drag and the water-acceleration
    /// load, summed over their elements; the weight has none), N.
    pub force: [f64; 2],
    /// The mean height of its collar's nodes (of its top knots without a collar), m.
    pub collar_z: f64,
    /// The speed of its current at its top knots' centre, m/s.
    pub current: f64,
}

/// A shared point's (`[[points]]`: buoy, knot) position and the load on it, at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct PointState {
    /// Name.
    pub name: String,
    /// Position, m.
    pub position: [f64; 3],
    /// For a free point, the net force of the cables attached to it (the sum of their
    /// `end_forces` there, each less its share of the node's inertia: at rest it
    /// balances the point's weight less buoyancy); for a held point, the reaction on
    /// its support (every force on the node but the constraint's, less its inertia), N.
    pub force: [f64; 3],
}

/// A vessel body's pose and the load its cables exert on it, at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyState {
    /// Name.
    pub name: String,
    /// Reference point, m.
    pub position: [f64; 3],
    /// Roll, pitch and yaw (the yaw includes the mean heading), degrees.
    pub angles: [f64; 3],
    /// Total force of the cables on the body, N.
    pub force: [f64; 3],
    /// Their moment about the reference point, N m.
    pub moment: [f64; 3],
    /// Velocity of the reference point (m/s) and angular velocity (rad/s), global
    /// axes: in runs with free or pinned bodies (`None` otherwise).
    pub velocity: Option<[f64; 6]>,
}

/// One cable's state at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct CableState {
    /// Name.
    pub name: String,
    /// Whether the scenario asks for its node positions in the output files
    /// (`output_positions`).
    pub output_positions: bool,
    /// Node positions, start to end, m.
    pub positions: Vec<[f64; 3]>,
    /// Node velocities, start to end, m/s.
    pub velocities: Vec<[f64; 3]>,
    /// Axial force per element, start to end, N.
    pub tensions: Vec<f64>,
    /// The forces the cable exerts on its end supports, N.
    pub end_forces: EndForces,
    /// The winch's state, for a cable with a winch.
    pub winch: Option<WinchSummary>,
}
