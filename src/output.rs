//! What a run writes: `summary.json`, `end_forces.csv`, `tensions.csv`, `positions.csv`.

use crate::error::Error;
use crate::model::{Layout, NO_CONSTRAINT};
use serde::Serialize;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// End forces of one cable: the force the cable exerts on each end support, N.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct EndForces {
    /// At the start node.
    pub start: [f64; 3],
    /// At the end node.
    pub end: [f64; 3],
}

/// Per-cable part of the summary.
#[derive(Clone, Debug, Serialize)]
pub struct CableSummary {
    /// Name.
    pub name: String,
    /// Final node positions, m.
    pub final_positions: Vec<[f64; 3]>,
    /// Final axial force per element, N.
    pub final_tensions: Vec<f64>,
    /// Final end forces, N.
    pub end_forces: EndForces,
}

/// `summary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// `completed` or `diverged`.
    pub status: String,
    /// The error that stopped the run, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The scenario file.
    pub scenario: String,
    /// `cpu` or `gpu`.
    pub backend: String,
    /// Adapter or CPU description.
    pub device: String,
    /// `f64` or `f32`.
    pub precision: String,
    /// Time scheme.
    pub scheme: String,
    /// Load formulation.
    pub formulation: String,
    /// Steps taken.
    pub steps: u64,
    /// Time step, s.
    pub dt: f64,
    /// Largest stable step estimated for the scheme, s.
    pub dt_stable: f64,
    /// What sets the stable step.
    pub dt_limited_by: String,
    /// Simulated time reached, s.
    pub simulated_time: f64,
    /// Wall time of the time stepping, s (no set-up, no relaxation, no output).
    pub wall_seconds: f64,
    /// Wall time of the whole run, s.
    pub total_wall_seconds: f64,
    /// Nodes in the model.
    pub nodes: usize,
    /// Elements in the model.
    pub elements: usize,
    /// `nodes * steps / wall_seconds`.
    pub node_steps_per_second: f64,
    /// Worker threads of the CPU path.
    pub threads: usize,
    /// Initial equilibrium: largest residual force left, N (0 when not relaxed).
    pub relax_residual: f64,
    /// Per cable.
    pub cables: Vec<CableSummary>,
}

/// Streams the time series as the run goes, so a run that stops early keeps its output.
pub struct OutputWriter {
    dir: PathBuf,
    end_forces: BufWriter<File>,
    tensions: BufWriter<File>,
    positions: Option<BufWriter<File>>,
}

fn create(dir: &Path, name: &str) -> Result<BufWriter<File>, Error> {
    let path = dir.join(name);
    File::create(&path)
        .map(BufWriter::new)
        .map_err(|source| Error::Output { path, source })
}

/// The force a cable exerts at its end node `node`: the constraint reaction where the
/// node is held, else the pull of the cable's end element on the node.
pub fn end_force(
    lay: &Layout,
    node: u32,
    elem: u32,
    is_start: bool,
    reaction: &[[f64; 3]],
    tension: &[f64],
    r: &[[f64; 3]],
) -> [f64; 3] {
    let c = lay.node_constraint[node as usize];
    if c != NO_CONSTRAINT {
        return reaction[c as usize];
    }
    let (a, b) = (
        r[lay.elem_a[elem as usize] as usize],
        r[lay.elem_b[elem as usize] as usize],
    );
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let s = tension[elem as usize] / l * if is_start { 1.0 } else { -1.0 };
    [d[0] * s, d[1] * s, d[2] * s]
}

impl OutputWriter {
    /// Creates the directory and the CSV files with their headers.
    pub fn create(dir: &Path, lay: &Layout) -> Result<Self, Error> {
        std::fs::create_dir_all(dir).map_err(|source| Error::Output {
            path: dir.to_path_buf(),
            source,
        })?;
        let mut w = Self {
            dir: dir.to_path_buf(),
            end_forces: create(dir, "end_forces.csv")?,
            tensions: create(dir, "tensions.csv")?,
            positions: if lay.cables.iter().any(|c| c.output_positions) {
                Some(create(dir, "positions.csv")?)
            } else {
                None
            },
        };
        w.io("end_forces.csv", |w| {
            writeln!(w.end_forces, "time,cable,end,fx,fy,fz")
        })?;
        w.io("tensions.csv", |w| {
            writeln!(w.tensions, "time,cable,element,tension")
        })?;
        if let Some(p) = w.positions.as_mut() {
            writeln!(p, "time,cable,node,x,y,z").map_err(|source| Error::Output {
                path: dir.join("positions.csv"),
                source,
            })?;
        }
        Ok(w)
    }

    fn io(
        &mut self,
        name: &str,
        f: impl FnOnce(&mut Self) -> std::io::Result<()>,
    ) -> Result<(), Error> {
        let path = self.dir.join(name);
        f(self).map_err(|source| Error::Output { path, source })
    }

    /// Writes one output time.
    pub fn frame(
        &mut self,
        t: f64,
        lay: &Layout,
        r: &[[f64; 3]],
        tension: &[f64],
        reaction: &[[f64; 3]],
    ) -> Result<(), Error> {
        self.io("end_forces.csv", |w| {
            for c in &lay.cables {
                let n = c.nodes.len();
                let s = end_force(lay, c.nodes[0], c.elements[0], true, reaction, tension, r);
                let e = end_force(
                    lay,
                    c.nodes[n - 1],
                    c.elements[n - 2],
                    false,
                    reaction,
                    tension,
                    r,
                );
                writeln!(
                    w.end_forces,
                    "{t},{},start,{},{},{}",
                    c.name, s[0], s[1], s[2]
                )?;
                writeln!(
                    w.end_forces,
                    "{t},{},end,{},{},{}",
                    c.name, e[0], e[1], e[2]
                )?;
            }
            Ok(())
        })?;
        self.io("tensions.csv", |w| {
            for c in &lay.cables {
                for (k, &e) in c.elements.iter().enumerate() {
                    writeln!(w.tensions, "{t},{},{k},{}", c.name, tension[e as usize])?;
                }
            }
            Ok(())
        })?;
        if self.positions.is_some() {
            self.io("positions.csv", |w| {
                let p = w.positions.as_mut().expect("checked");
                for c in lay.cables.iter().filter(|c| c.output_positions) {
                    for (k, &n) in c.nodes.iter().enumerate() {
                        let x = r[n as usize];
                        writeln!(p, "{t},{},{k},{},{},{}", c.name, x[0], x[1], x[2])?;
                    }
                }
                Ok(())
            })?;
        }
        Ok(())
    }

    /// Flushes every file.
    pub fn flush(&mut self) -> Result<(), Error> {
        self.io("end_forces.csv", |w| w.end_forces.flush())?;
        self.io("tensions.csv", |w| w.tensions.flush())?;
        if self.positions.is_some() {
            self.io("positions.csv", |w| {
                w.positions.as_mut().expect("checked").flush()
            })?;
        }
        Ok(())
    }

    /// Writes `summary.json`.
    pub fn summary(&self, s: &Summary) -> Result<(), Error> {
        let path = self.dir.join("summary.json");
        let text = serde_json::to_string_pretty(s).expect("summary serialises");
        std::fs::write(&path, text).map_err(|source| Error::Output { path, source })
    }
}
