//! The tables a run writes, their columns and units, in either format: what the CSV and
//! the Parquet writers share.

use super::sink::Snapshot;
use crate::error::Error;
use std::sync::Arc;

/// The type of a column's values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A float (Parquet DOUBLE).
    F64,
    /// An index (Parquet INT32).
    Int,
    /// A name (Parquet UTF-8 string, dictionary-encoded).
    Text,
}

/// One table: its file's stem and its columns `(name, unit, kind)` (`-`: no unit).
#[derive(Clone, Copy, Debug)]
pub struct Table {
    /// The file's name without its extension.
    pub name: &'static str,
    /// `(name, unit, kind)`.
    pub columns: &'static [(&'static str, &'static str, Kind)],
}

use Kind::{Int, Text, F64};

impl Table {
    /// The per-frame tables, in the order every writer keeps them.
    pub const ALL: [Table; 7] = [
        Table {
            name: "end_forces",
            columns: &[
                ("time", "s", F64),
                ("cable", "-", Text),
                ("end", "-", Text),
                ("fx", "N", F64),
                ("fy", "N", F64),
                ("fz", "N", F64),
            ],
        },
        Table {
            name: "tensions",
            columns: &[
                ("time", "s", F64),
                ("cable", "-", Text),
                ("element", "-", Int),
                ("tension", "N", F64),
            ],
        },
        Table {
            name: "positions",
            columns: &[
                ("time", "s", F64),
                ("cable", "-", Text),
                ("node", "-", Int),
                ("x", "m", F64),
                ("y", "m", F64),
                ("z", "m", F64),
            ],
        },
        Table {
            name: "winches",
            columns: &[
                ("time", "s", F64),
                ("cable", "-", Text),
                ("deployed_length", "m", F64),
                ("variable_l0", "m", F64),
                ("elements", "-", Int),
            ],
        },
        Table {
            name: "bodies",
            columns: &[
                ("time", "s", F64),
                ("body", "-", Text),
                ("x", "m", F64),
                ("y", "m", F64),
                ("z", "m", F64),
                ("roll", "deg", F64),
                ("pitch", "deg", F64),
                ("yaw", "deg", F64),
                ("fx", "N", F64),
                ("fy", "N", F64),
                ("fz", "N", F64),
                ("mx", "N m", F64),
                ("my", "N m", F64),
                ("mz", "N m", F64),
            ],
        },
        Table {
            name: "points",
            columns: &[
                ("time", "s", F64),
                ("point", "-", Text),
                ("x", "m", F64),
                ("y", "m", F64),
                ("z", "m", F64),
                ("fx", "N", F64),
                ("fy", "N", F64),
                ("fz", "N", F64),
            ],
        },
        Table {
            name: "nets",
            columns: &[
                ("time", "s", F64),
                ("net", "-", Text),
                ("volume", "m^3", F64),
                ("volume_ratio", "-", F64),
                ("fx", "N", F64),
                ("fy", "N", F64),
                ("drag", "N", F64),
                ("collar_z", "m", F64),
                ("current", "m/s", F64),
            ],
        },
    ];

    /// `bodies` of a run with free or pinned bodies: with their velocities (the
    /// reference point's, m/s, and the angular velocity, rad/s; global axes).
    pub const BODIES_MOVING: Table = Table {
        name: "bodies",
        columns: &[
            ("time", "s", F64),
            ("body", "-", Text),
            ("x", "m", F64),
            ("y", "m", F64),
            ("z", "m", F64),
            ("roll", "deg", F64),
            ("pitch", "deg", F64),
            ("yaw", "deg", F64),
            ("fx", "N", F64),
            ("fy", "N", F64),
            ("fz", "N", F64),
            ("mx", "N m", F64),
            ("my", "N m", F64),
            ("mz", "N m", F64),
            ("vx", "m/s", F64),
            ("vy", "m/s", F64),
            ("vz", "m/s", F64),
            ("wx", "rad/s", F64),
            ("wy", "rad/s", F64),
            ("wz", "rad/s", F64),
        ],
    };

    /// The final state: every node of every cable at the last output time.
    pub const FINAL_STATE: Table = Table {
        name: "final_state",
        columns: &[
            ("cable", "-", Text),
            ("node", "-", Int),
            ("x", "m", F64),
            ("y", "m", F64),
            ("z", "m", F64),
            ("vx", "m/s", F64),
            ("vy", "m/s", F64),
            ("vz", "m/s", F64),
        ],
    };

    /// The file's name with extension `ext`.
    pub fn file(&self, ext: &str) -> String {
        format!("{}.{ext}", self.name)
    }

    /// Whether a run whose first frame is `s` writes this table: end forces and
    /// tensions always, the others when there is something to write.
    pub fn present(&self, s: &Snapshot) -> bool {
        match self.name {
            "positions" => s.cables.iter().any(|c| c.output_positions),
            "winches" => s.cables.iter().any(|c| c.winch.is_some()),
            "bodies" => !s.bodies.is_empty(),
            "points" => !s.points.is_empty(),
            "nets" => !s.nets.is_empty(),
            _ => true,
        }
    }

    /// This table as a run whose first frame is `s` writes it: `bodies` with the
    /// velocity columns ([`Table::BODIES_MOVING`]) when the bodies have velocities.
    pub fn for_run(&self, s: &Snapshot) -> Table {
        if self.name == "bodies" && s.bodies.iter().any(|b| b.velocity.is_some()) {
            Table::BODIES_MOVING
        } else {
            *self
        }
    }

    /// The units as a JSON object `{"column": "unit", ...}` (the Parquet files'
    /// `units` metadata).
    pub fn units_json(&self) -> String {
        let m: serde_json::Map<String, serde_json::Value> = self
            .columns
            .iter()
            .map(|(n, u, _)| (n.to_string(), serde_json::Value::from(*u)))
            .collect();
        serde_json::Value::Object(m).to_string()
    }
}

/// A format's writer of a run's tables, driven by the file sink's writer thread.
pub(crate) trait Tables: Send {
    /// Writes one frame (the first creates the files).
    fn frame(&mut self, s: &Arc<Snapshot>) -> Result<(), Error>;
    /// Writes what is pending and the final state (`last`, the last frame), and closes
    /// every file.
    fn finish(&mut self, last: Option<&Snapshot>) -> Result<(), Error>;
    /// After a failed write: leaves every file readable up to the last frame whole in
    /// all of them, as far as the disk allows, and returns that frame's time (`None`:
    /// no frame).
    fn abort(&mut self) -> Option<f64>;
}
