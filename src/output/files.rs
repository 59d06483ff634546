//! The files a run writes ([`FileSink`]).

use super::sink::{OutputSink, Snapshot};
use super::summary::{write_summary, Summary};
use crate::error::Error;
use std::collections::HashMap;
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
/// Cable and body names are quoted where CSV needs it (a comma, a quote, a line break).
///
/// A run owns its directory ([`FileSink::claim`], done at the first frame unless the
/// caller claimed it before): the directory is created if needed, and locked for as
/// long as the sink lives (a lock file, [`LOCK_FILE`]), so that a second run into it
/// is refused; a marker file ([`MARKER_FILE`]) says it is a cablesim output folder. A
/// directory already holding cablesim's files ([`OWN_FILES`], from an earlier run) is
/// cleared of them; one holding any other file is refused, and nothing else is ever
/// deleted.
pub struct FileSink {
    dir: PathBuf,
    files: Option<Files>,
    /// The held lock, once the directory is claimed.
    lock: Option<File>,
    /// Each name as one CSV field ([`csv_field`]), formed at its first output: a
    /// `csv::Writer` per field allocates and zeroes an 8 KiB buffer, which at every
    /// output time of every cable cost about 4% of a moored run's instructions.
    quoted: HashMap<String, String>,
}

/// The marker file of a cablesim output folder.
pub const MARKER_FILE: &str = ".cablesim-output";
/// The lock file a run holds while it writes into its folder.
pub const LOCK_FILE: &str = ".cablesim.lock";
/// The files a run may write: cleared from a folder before a new run writes into it.
pub const OWN_FILES: &[&str] = &[
    MARKER_FILE,
    LOCK_FILE,
    "summary.json",
    "end_forces.csv",
    "tensions.csv",
    "positions.csv",
    "winches.csv",
    "bodies.csv",
    "points.csv",
    "fatigue.csv",
];

/// Folders cablesim writes into an output directory, with the extensions of the files it
/// puts there: the ParaView files (`--vtk`) and `cablesim plot`'s images. A folder of
/// that name holding only such files is cablesim's own, and is cleared of them.
pub const OWN_DIRS: &[(&str, &[&str])] = &[("vtk", &["vtp", "pvd"]), ("plots", &["png"])];

/// The files of own folder `dir` (see [`OWN_DIRS`]), or `None` when it holds anything else.
fn own_dir_files(dir: &Path, exts: &[&str]) -> Option<Vec<PathBuf>> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).ok()? {
        let entry = entry.ok()?;
        let path = entry.path();
        let ext = path.extension().and_then(|e| e.to_str());
        if !entry.file_type().ok()?.is_file() || !ext.is_some_and(|e| exts.contains(&e)) {
            return None;
        }
        files.push(path);
    }
    Some(files)
}

/// `name` as one CSV field: quoted where it holds a comma, a quote or a line break.
fn csv_field(name: &str) -> String {
    let mut w = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    w.write_record([name]).expect("writes to memory");
    let mut bytes = w.into_inner().expect("writes to memory");
    bytes.pop(); // the record's terminator
    String::from_utf8(bytes).expect("a field of a UTF-8 string is UTF-8")
}

/// `name` as one CSV field, from `cache` or formed there ([`csv_field`]).
fn quoted<'a>(cache: &'a mut HashMap<String, String>, name: &str) -> &'a str {
    if !cache.contains_key(name) {
        cache.insert(name.to_string(), csv_field(name));
    }
    &cache[name]
}

/// An output error on `path` with message `what`.
fn output_error(path: &Path, what: String) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        source: std::io::Error::other(what),
    }
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
            lock: None,
            quoted: HashMap::new(),
        }
    }

    /// A sink that claims `dir` now: creates it if needed, locks it, clears an earlier
    /// run's files, and writes the marker. Fails, writing nothing, when `dir` is a file,
    /// another run holds it, or it holds files that are not cablesim's.
    pub fn claim(dir: impl Into<PathBuf>) -> Result<Self, Error> {
        let mut s = Self::new(dir);
        s.claim_dir()?;
        Ok(s)
    }

    fn claim_dir(&mut self) -> Result<(), Error> {
        if self.lock.is_some() {
            return Ok(());
        }
        let dir = &self.dir;
        if dir.exists() && !dir.is_dir() {
            return Err(output_error(
                dir,
                "is a file, not a directory: give --out a directory (new or empty)".into(),
            ));
        }
        std::fs::create_dir_all(dir).map_err(|source| Error::Output {
            path: dir.clone(),
            source,
        })?;
        let lock_path = dir.join(LOCK_FILE);
        let lock = File::options()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .map_err(|source| Error::Output {
                path: lock_path.clone(),
                source,
            })?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(output_error(
                    dir,
                    "another cablesim run is writing into this directory; wait for it or choose another --out".into(),
                ))
            }
            Err(std::fs::TryLockError::Error(source)) => {
                return Err(Error::Output {
                    path: lock_path,
                    source,
                })
            }
        }
        let read = |source| Error::Output {
            path: dir.clone(),
            source,
        };
        let mut foreign = Vec::new();
        let mut own = Vec::new();
        let mut own_in_dirs = Vec::new();
        for entry in std::fs::read_dir(dir).map_err(read)? {
            let entry = entry.map_err(read)?;
            let name = entry.file_name();
            let kind = entry.file_type().map_err(read)?;
            let own_dir = OWN_DIRS
                .iter()
                .find(|(d, _)| kind.is_dir() && name.to_str() == Some(*d))
                .and_then(|(_, exts)| own_dir_files(&entry.path(), exts));
            match (name.to_str(), own_dir) {
                (_, Some(files)) => own_in_dirs.extend(files),
                (Some(n), None) if kind.is_file() && OWN_FILES.contains(&n) => {
                    own.push(n.to_string())
                }
                _ => foreign.push(name.to_string_lossy().into_owned()),
            }
        }
        if !foreign.is_empty() {
            foreign.sort();
            foreign.truncate(3);
            return Err(output_error(
                dir,
                format!(
                    "holds files that are not cablesim output ({}); choose a new or empty directory, or one an earlier run wrote",
                    foreign.join(", ")
                ),
            ));
        }
        for n in own.iter().filter(|n| *n != LOCK_FILE && *n != MARKER_FILE) {
            std::fs::remove_file(dir.join(n)).map_err(err(dir, n))?;
        }
        for f in &own_in_dirs {
            std::fs::remove_file(f).map_err(|source| Error::Output {
                path: f.clone(),
                source,
            })?;
        }
        std::fs::write(
            dir.join(MARKER_FILE),
            "cablesim output folder: the next run into it replaces its files\n",
        )
        .map_err(err(dir, MARKER_FILE))?;
        self.lock = Some(lock);
        Ok(())
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

    fn create(&mut self, first: &Snapshot) -> Result<Files, Error> {
        self.claim_dir()?;
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
                    if first.bodies.iter().any(|b| b.velocity.is_some()) {
                        "time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz,vx,vy,vz,wx,wy,wz"
                    } else {
                        "time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz"
                    },
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
            let name = quoted(&mut self.quoted, &c.name);
            let (a, b) = (c.end_forces.start, c.end_forces.end);
            writeln!(f.end_forces, "{t},{name},start,{},{},{}", a[0], a[1], a[2])
                .and_then(|_| writeln!(f.end_forces, "{t},{name},end,{},{},{}", b[0], b[1], b[2]))
                .map_err(&e_ef)?;
        }
        for c in &s.cables {
            let name = quoted(&mut self.quoted, &c.name);
            for (k, x) in c.tensions.iter().enumerate() {
                writeln!(f.tensions, "{t},{name},{k},{x}").map_err(&e_tn)?;
            }
        }
        if let Some(p) = f.positions.as_mut() {
            for c in s.cables.iter().filter(|c| c.output_positions) {
                let name = quoted(&mut self.quoted, &c.name);
                for (k, x) in c.positions.iter().enumerate() {
                    writeln!(p, "{t},{name},{k},{},{},{}", x[0], x[1], x[2]).map_err(&e_pos)?;
                }
            }
        }
        if let Some(w) = f.winches.as_mut() {
            for c in &s.cables {
                if let Some(ws) = &c.winch {
                    writeln!(
                        w,
                        "{t},{},{},{},{}",
                        quoted(&mut self.quoted, &c.name),
                        ws.deployed_length,
                        ws.variable_l0,
                        ws.elements
                    )
                    .map_err(&e_w)?;
                }
            }
        }
        if let Some(w) = f.bodies.as_mut() {
            let e_b = err(&self.dir, "bodies.csv");
            for b in &s.bodies {
                let (x, a, f, m) = (b.position, b.angles, b.force, b.moment);
                write!(
                    w,
                    "{t},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                    quoted(&mut self.quoted, &b.name),
                    x[0],
                    x[1],
                    x[2],
                    a[0],
                    a[1],
                    a[2],
                    f[0],
                    f[1],
                    f[2],
                    m[0],
                    m[1],
                    m[2]
                )
                .map_err(&e_b)?;
                if let Some(u) = b.velocity {
                    write!(w, ",{},{},{},{},{},{}", u[0], u[1], u[2], u[3], u[4], u[5])
                        .map_err(&e_b)?;
                }
                writeln!(w).map_err(&e_b)?;
            }
        }
        if let Some(w) = f.points.as_mut() {
            let e_p = err(&self.dir, "points.csv");
            for p in &s.points {
                let (x, f) = (p.position, p.force);
                writeln!(
                    w,
                    "{t},{},{},{},{},{},{},{}",
                    quoted(&mut self.quoted, &p.name),
                    x[0],
                    x[1],
                    x[2],
                    f[0],
                    f[1],
                    f[2]
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
            self.claim_dir()?;
        }
        write_summary(&self.dir, summary)
    }
}
