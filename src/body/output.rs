//! `bodies.csv`: per body and output time, its pose and the total force and moment its
//! cables exert on it.
//!
//! The force is the sum, over the end nodes held on the body, of each node's
//! constraint reaction `F_k - M_k a_k` (every force on the node but the constraint's,
//! less its inertia: the force the cables, and a point mass at the end, exert on the
//! body there; the same reaction `end_forces.csv` reports). The moment is about the
//! body's reference point at that time: `sum (r_k - X) x F_k`, with `r_k` the node's
//! position.

use super::Body;
use crate::cpu::Evaluation;
use crate::error::Error;
use crate::math::V3;
use crate::model::{Layout, Route};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The bodies of a layout and the constraints (route indices) held on each.
pub fn bodies_of(lay: &Layout) -> Vec<(Arc<Body>, Vec<usize>)> {
    let mut out: Vec<(Arc<Body>, Vec<usize>)> = Vec::new();
    for (c, r) in lay.routes.iter().enumerate() {
        if let Route::Body { body, .. } = r {
            match out.iter_mut().find(|(b, _)| Arc::ptr_eq(b, body)) {
                Some((_, cs)) => cs.push(c),
                None => out.push((body.clone(), vec![c])),
            }
        }
    }
    out
}

/// Total force (N) and moment about the reference point at time `t` (N m) on `body`
/// from the constraints `held` (route indices), given node positions `r` (packed
/// order) and the evaluation's reactions.
pub fn body_load(
    lay: &Layout,
    body: &Body,
    held: &[usize],
    t: f64,
    r: &[[f64; 3]],
    reaction: &[[f64; 3]],
) -> ([f64; 3], [f64; 3]) {
    let x = body.state(t).x;
    let mut f = V3::<f64>::zero();
    let mut m = V3::<f64>::zero();
    for &c in held {
        let fk = V3::from_f64(reaction[c]);
        let rk = V3::from_f64(r[lay.constraint_node[c] as usize]);
        f += fk;
        m += (rk - x).cross(fk);
    }
    (f.to_f64(), m.to_f64())
}

/// The `bodies.csv` writer.
pub struct BodiesCsv {
    path: PathBuf,
    w: BufWriter<File>,
    bodies: Vec<(Arc<Body>, Vec<usize>)>,
}

impl BodiesCsv {
    /// Creates `dir/bodies.csv` with its header when `lay` has ends on bodies.
    pub fn create(dir: &Path, lay: &Layout) -> Result<Option<Self>, Error> {
        let bodies = bodies_of(lay);
        if bodies.is_empty() {
            return Ok(None);
        }
        let path = dir.join("bodies.csv");
        let file = File::create(&path).map_err(|source| Error::Output {
            path: path.clone(),
            source,
        })?;
        let mut out = Self {
            path,
            w: BufWriter::new(file),
            bodies,
        };
        out.io(|w| writeln!(w, "time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz"))?;
        Ok(Some(out))
    }

    fn io(
        &mut self,
        f: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
    ) -> Result<(), Error> {
        f(&mut self.w).map_err(|source| Error::Output {
            path: self.path.clone(),
            source,
        })
    }

    /// Writes one output time: per body the reference point (m), the angles (deg; the
    /// yaw includes the mean heading), force (N) and moment about the reference point
    /// (N m).
    pub fn frame(
        &mut self,
        t: f64,
        lay: &Layout,
        r: &[[f64; 3]],
        ev: &Evaluation,
    ) -> Result<(), Error> {
        let mut rows = Vec::with_capacity(self.bodies.len());
        for (b, held) in &self.bodies {
            let s = b.state(t);
            let d = b.dofs(t);
            let (f, m) = body_load(lay, b, held, t, r, &ev.reaction);
            let ang = [d.q[3], d.q[4], d.q[5] + b.pose.heading].map(f64::to_degrees);
            rows.push(format!(
                "{t},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                b.name,
                s.x.x,
                s.x.y,
                s.x.z,
                ang[0],
                ang[1],
                ang[2],
                f[0],
                f[1],
                f[2],
                m[0],
                m[1],
                m[2]
            ));
        }
        self.io(|w| rows.iter().try_for_each(|row| writeln!(w, "{row}")))
    }

    /// Flushes the file.
    pub fn flush(&mut self) -> Result<(), Error> {
        self.io(|w| w.flush())
    }
}
