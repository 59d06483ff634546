//! The files a run writes ([`FileSink`]).

use super::sink::{OutputSink, Snapshot};
use super::summary::{write_summary, Summary};
use crate::error::Error;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes a run's output files into one directory, streaming each output time as it
/// comes so that a run that stops early keeps what it wrote:
/// - `end_forces.csv`: `time,cable,end,fx,fy,fz`, two rows per cable (`start`, `end`),
///   the force the cable exerts on each end support, N;
/// - `tensions.csv`: `time,cable,element,tension`, N;
/// - `positions.csv`: `time,cable,node,x,y,z`, m, for the cables whose positions are
///   output (the file only when there is one);
/// - `winches.csv`: `time,cable,deployed_length,variable_l0,elements` (the file only
///   with winches);
/// - `bodies.csv`: `time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz` (m, degrees, N,
///   N m about the reference point; the file only when cable ends are on bodies);
/// - `points.csv`: `time,point,x,y,z,fx,fy,fz` (m, N), per shared point
///   (`[[points]]`) its position and the net force of its cables on it, or the reaction
///   for a held point ([`super::PointState`]; the file only with such points);
/// - `summary.json`: the [`Summary`].
///
/// The directory and the files are created at the first frame.
pub struct FileSink {
    dir: PathBuf,
    files: Option<Files>,
}

struct Files {
    end_forces: BufWriter<File>,
    tensions: BufWriter<File>,
    positions: Option<BufWriter<File>>,
    winches: Option<BufWriter<File>>,
    bodies: Option<BufWriter<File>>,
    points: Option<BufWriter<File>>,
}

/// The error of an I/O failure on file `name` in `dir`.
fn err(dir: &Path, name: &str) -> impl Fn(std::io::Error) -> Error {
    let path = dir.join(name);
    move |source| Error::Output {
        path: path.clone(),
        source,
    }
}

impl FileSink {
    /// A sink writing into `dir` (created when needed).
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Self {
            dir: dir.into(),
            files: None,
        }
    }

    /// The output directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    fn open(&self, name: &str, header: &str) -> Result<BufWriter<File>, Error> {
        let mut f =
            BufWriter::new(File::create(self.dir.join(name)).map_err(err(&self.dir, name))?);
        writeln!(f, "{header}").map_err(err(&self.dir, name))?;
        Ok(f)
    }

    fn create(&self, first: &Snapshot) -> Result<Files, Error> {
        std::fs::create_dir_all(&self.dir).map_err(|source| Error::Output {
            path: self.dir.clone(),
            source,
        })?;
        let positions = first.cables.iter().any(|c| c.output_positions);
        let winches = first.cables.iter().any(|c| c.winch.is_some());
        let bodies = !first.bodies.is_empty();
        let points = !first.points.is_empty();
        Ok(Files {
            end_forces: self.open("end_forces.csv", "time,cable,end,fx,fy,fz")?,
            tensions: self.open("tensions.csv", "time,cable,element,tension")?,
            positions: if positions {
                Some(self.open("positions.csv", "time,cable,node,x,y,z")?)
            } else {
                None
            },
            winches: if winches {
                Some(self.open(
                    "winches.csv",
                    "time,cable,deployed_length,variable_l0,elements",
                )?)
            } else {
                None
            },
            bodies: if bodies {
                Some(self.open(
                    "bodies.csv",
                    "time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz",
                )?)
            } else {
                None
            },
            points: if points {
                Some(self.open("points.csv", "time,point,x,y,z,fx,fy,fz")?)
            } else {
                None
            },
        })
    }
}

impl OutputSink for FileSink {
    fn frame(&mut self, s: &Snapshot) -> Result<(), Error> {
        if self.files.is_none() {
            self.files = Some(self.create(s)?);
        }
        let t = s.time;
        let (e_ef, e_tn, e_pos, e_w) = (
            err(&self.dir, "end_forces.csv"),
            err(&self.dir, "tensions.csv"),
            err(&self.dir, "positions.csv"),
            err(&self.dir, "winches.csv"),
        );
        let f = self.files.as_mut().expect("created above");
        for c in &s.cables {
            let name = &c.name;
            let (a, b) = (c.end_forces.start, c.end_forces.end);
            writeln!(f.end_forces, "{t},{name},start,{},{},{}", a[0], a[1], a[2])
                .and_then(|_| writeln!(f.end_forces, "{t},{name},end,{},{},{}", b[0], b[1], b[2]))
                .map_err(&e_ef)?;
        }
        for c in &s.cables {
            for (k, x) in c.tensions.iter().enumerate() {
                writeln!(f.tensions, "{t},{},{k},{x}", c.name).map_err(&e_tn)?;
            }
        }
        if let Some(p) = f.positions.as_mut() {
            for c in s.cables.iter().filter(|c| c.output_positions) {
                for (k, x) in c.positions.iter().enumerate() {
                    writeln!(p, "{t},{},{k},{},{},{}", c.name, x[0], x[1], x[2]).map_err(&e_pos)?;
                }
            }
        }
        if let Some(w) = f.winches.as_mut() {
            for c in &s.cables {
                if let Some(ws) = &c.winch {
                    writeln!(
                        w,
                        "{t},{},{},{},{}",
                        c.name, ws.deployed_length, ws.variable_l0, ws.elements
                    )
                    .map_err(&e_w)?;
                }
            }
        }
        if let Some(w) = f.bodies.as_mut() {
            let e_b = err(&self.dir, "bodies.csv");
            for b in &s.bodies {
                let (x, a, f, m) = (b.position, b.angles, b.force, b.moment);
                writeln!(
                    w,
                    "{t},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                    b.name, x[0], x[1], x[2], a[0], a[1], a[2], f[0], f[1], f[2], m[0], m[1], m[2]
                )
                .map_err(&e_b)?;
            }
        }
        if let Some(w) = f.points.as_mut() {
            let e_p = err(&self.dir, "points.csv");
            for p in &s.points {
                let (x, f) = (p.position, p.force);
                writeln!(
                    w,
                    "{t},{},{},{},{},{},{},{}",
                    p.name, x[0], x[1], x[2], f[0], f[1], f[2]
                )
                .map_err(&e_p)?;
            }
        }
        Ok(())
    }

    fn finish(&mut self, summary: &Summary) -> Result<(), Error> {
        let dir = &self.dir;
        if let Some(f) = self.files.as_mut() {
            f.end_forces.flush().map_err(err(dir, "end_forces.csv"))?;
            f.tensions.flush().map_err(err(dir, "tensions.csv"))?;
            if let Some(p) = f.positions.as_mut() {
                p.flush().map_err(err(dir, "positions.csv"))?;
            }
            if let Some(w) = f.winches.as_mut() {
                w.flush().map_err(err(dir, "winches.csv"))?;
            }
            if let Some(w) = f.bodies.as_mut() {
                w.flush().map_err(err(dir, "bodies.csv"))?;
            }
            if let Some(w) = f.points.as_mut() {
                w.flush().map_err(err(dir, "points.csv"))?;
            }
        } else {
            std::fs::create_dir_all(&self.dir).map_err(|source| Error::Output {
                path: self.dir.clone(),
                source,
            })?;
        }
        write_summary(&self.dir, summary)
    }
}
