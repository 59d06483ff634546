//! What a run writes: `summary.json`, `end_forces.csv`, `tensions.csv`, `positions.csv`,
//! and `bodies.csv` (`crate::body::output`) when cable ends are attached to bodies.

use crate::cpu::Evaluation;
use crate::error::Error;
use crate::math::{Sym3, V3};
use crate::model::{CableInfo, Layout, NO_CONSTRAINT};
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

/// Final state of a winch cable (ALE-GLMF).
#[derive(Clone, Debug, Serialize)]
pub struct WinchSummary {
    /// Deployed unstretched length, m.
    pub deployed_length: f64,
    /// Unstretched length of the variable element next to the winch, m.
    pub variable_l0: f64,
    /// Elements of the cable.
    pub elements: usize,
    /// Nodes inserted during the run.
    pub nodes_inserted: u64,
    /// Nodes deleted during the run.
    pub nodes_deleted: u64,
    /// Physical coordinate `p` of each node (cable order, start to end): unstretched
    /// arc length from the far end, m.
    pub physical_coordinates: Vec<f64>,
}

/// Per-cable part of the summary.
#[derive(Clone, Debug, Serialize)]
pub struct CableSummary {
    /// Name.
    pub name: String,
    /// The winch's final state, for a cable with a winch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub winch: Option<WinchSummary>,
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
    winches: Option<BufWriter<File>>,
    /// `bodies.csv`, when ends are attached to bodies.
    bodies: Option<crate::body::output::BodiesCsv>,
}

fn create(dir: &Path, name: &str) -> Result<BufWriter<File>, Error> {
    let path = dir.join(name);
    File::create(&path)
        .map(BufWriter::new)
        .map_err(|source| Error::Output { path, source })
}

/// The forces a cable exerts at its two end nodes.
///
/// - An end node that only this cable's end element touches: if it is held, the
///   constraint reaction `F_k - M_k a_k` (MODEL.md: every force on the node, its point
///   mass and seabed contact included); if it is free, `F_e - M_e a_k`, the end
///   element's lumped force less its share of the node's inertia, which is the force the
///   cable exerts on an attached point mass (zero when nothing is attached).
/// - A node shared by several elements (a `[[points]]` knot): `F_e - M_e a_k` of this
///   cable's end element, its own share; the shares of all cables at a held knot add up
///   to the knot's reaction less the point's own weight and inertia.
pub fn end_forces(lay: &Layout, ev: &Evaluation, cable: &CableInfo) -> EndForces {
    let n = cable.nodes.len();
    let one = |node: u32, elem: u32, sign: f64| -> [f64; 3] {
        let i = node as usize;
        let k = lay.node_constraint[i];
        if k != NO_CONSTRAINT && lay.incidence(i).len() == 1 {
            return ev.reaction[k as usize];
        }
        let el = &ev.elements[elem as usize];
        let a = V3::from_f64(ev.acc[i]);
        let mut m = Sym3::scalar(el.half_mass);
        m.add_normal_projection(el.half_added, el.t);
        (el.f_half + el.t * (sign * el.tension) - m.mul_vec(a)).to_f64()
    };
    EndForces {
        start: one(cable.nodes[0], cable.elements[0], 1.0),
        end: one(cable.nodes[n - 1], cable.elements[n - 2], -1.0),
    }
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
            winches: None,
            bodies: crate::body::output::BodiesCsv::create(dir, lay)?,
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
        ev: &Evaluation,
    ) -> Result<(), Error> {
        let tension = &ev.tension;
        self.io("end_forces.csv", |w| {
            for c in &lay.cables {
                let f = end_forces(lay, ev, c);
                let (s, e) = (f.start, f.end);
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
        if let Some(b) = self.bodies.as_mut() {
            b.frame(t, lay, r, ev)?;
        }
        Ok(())
    }

    /// Writes one output time of `winches.csv` (created at the first call with a
    /// winch): `time,cable,deployed_length,variable_l0,elements`.
    pub fn winches(
        &mut self,
        t: f64,
        lay: &Layout,
        winches: &[crate::cpu::WinchStatus],
    ) -> Result<(), Error> {
        if winches.is_empty() {
            return Ok(());
        }
        if self.winches.is_none() {
            let mut w = create(&self.dir, "winches.csv")?;
            writeln!(w, "time,cable,deployed_length,variable_l0,elements").map_err(|source| {
                Error::Output {
                    path: self.dir.join("winches.csv"),
                    source,
                }
            })?;
            self.winches = Some(w);
        }
        self.io("winches.csv", |o| {
            let f = o.winches.as_mut().expect("created above");
            for w in winches {
                writeln!(
                    f,
                    "{t},{},{},{},{}",
                    lay.cables[w.cable].name, w.deployed_length, w.variable_l0, w.elements
                )?;
            }
            Ok(())
        })
    }

    /// Flushes every file.
    pub fn flush(&mut self) -> Result<(), Error> {
        if self.winches.is_some() {
            self.io("winches.csv", |w| {
                w.winches.as_mut().expect("checked").flush()
            })?;
        }
        if let Some(b) = self.bodies.as_mut() {
            b.flush()?;
        }
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
        write_summary(&self.dir, s)
    }
}

/// Writes `summary.json` into `dir`.
pub fn write_summary(dir: &Path, s: &Summary) -> Result<(), Error> {
    let path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(s).expect("summary serialises");
    std::fs::write(&path, text).map_err(|source| Error::Output { path, source })
}
