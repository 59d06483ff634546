//! The files a run writes ([`FileSink`]).

use super::sink::{OutputSink, Snapshot};
use super::summary::{write_summary, Summary};
use super::tables::Tables;
use crate::error::Error;
use crate::options::OutputFormat;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{sync_channel, SyncSender};
use std::sync::Arc;
use std::thread::JoinHandle;

/// Writes a run's output files into one directory, streaming each output time as it
/// comes so that a run that stops early keeps what it wrote. The tables, in CSV
/// (`.csv`, the default) or Parquet (`.parquet`, [`FileSink::format`]), with the same
/// columns in either:
/// - `end_forces`: `time,cable,end,fx,fy,fz`, two rows per cable (`start`, `end`),
///   the force the cable exerts on each end support, N;
/// - `tensions`: `time,cable,element,tension`, N;
/// - `positions`: `time,cable,node,x,y,z`, m, for the cables whose positions are
///   output (the file only when there is one);
/// - `winches`: `time,cable,deployed_length,variable_l0,elements` (the file only
///   with winches);
/// - `bodies`: `time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz` (m, degrees, N,
///   N m about the reference point; the file only when cable ends are on bodies);
/// - `points`: `time,point,x,y,z,fx,fy,fz` (m, N), per shared point
///   (`[[points]]`) its position and the net force of its cables on it, or the reaction
///   for a held point ([`super::PointState`]; the file only with such points);
/// - `final_state`: `cable,node,x,y,z,vx,vy,vz` (m, m/s), every node at the last
///   frame, written when the run ends;
///
/// and `summary.json`, the [`Summary`] (a fixed handful of numbers per cable).
///
/// The tables are written on a thread of their own: each frame is handed over (the run
/// waits only while the writer is still busy with the frame before, so at most two
/// frames exist at once and memory stays flat), and the run steps on while the frame
/// is formatted, compressed and written. The sink's `finish` (or its drop, when the run stops on an error) closes
/// every file; after a failed write (a full disk) each file is cut back to its last
/// whole frame, and the error names the file and the cause.
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
    format: OutputFormat,
    /// The held lock, once the directory is claimed.
    lock: Option<File>,
    /// The writer thread, from the first frame.
    writer: Option<Writer>,
    /// A test's stand-in for a full disk: files fail past this many bytes.
    cap: Option<u64>,
    /// Node rows gathered into a Parquet row group (default
    /// [`super::parquet_files::GROUP_ROWS`]).
    group_rows: Option<usize>,
}

/// The writer thread and its queue.
struct Writer {
    dir: PathBuf,
    tx: Option<SyncSender<Snapshot>>,
    handle: Option<JoinHandle<Result<(), Error>>>,
}

impl Writer {
    fn start(dir: &Path, mut tables: Box<dyn Tables>) -> Self {
        // A hand-over, no queue: the run waits only while the writer is still busy
        // with the frame before, and at most two frames exist at once (the one being
        // written and the one being handed over).
        let (tx, rx) = sync_channel::<Snapshot>(0);
        let handle = std::thread::Builder::new()
            .name("cablesim-output".into())
            .spawn(move || {
                let mut last: Option<Arc<Snapshot>> = None;
                let fail = |tables: &mut Box<dyn Tables>, e: Error| -> Result<(), Error> {
                    let kept = match tables.abort() {
                        Some(t) => format!("the files hold the frames up to t = {t} s"),
                        None => "the files hold no frame".to_string(),
                    };
                    Err(with_kept(e, &kept))
                };
                for snap in rx {
                    // The frame before goes now: one frame held at a time.
                    drop(last.take());
                    let snap = Arc::new(snap);
                    if let Err(e) = tables.frame(&snap) {
                        return fail(&mut tables, e);
                    }
                    last = Some(snap);
                }
                if let Err(e) = tables.finish(last.as_deref()) {
                    return fail(&mut tables, e);
                }
                Ok(())
            })
            .expect("a thread can be started");
        Self {
            dir: dir.to_path_buf(),
            tx: Some(tx),
            handle: Some(handle),
        }
    }

    /// Hands `s` to the thread; its error if it has stopped on one.
    fn send(&mut self, s: Snapshot) -> Result<(), Error> {
        let Some(tx) = self.tx.as_ref() else {
            return Err(output_error(
                &self.dir,
                "the output writer stopped on an earlier error".into(),
            ));
        };
        if tx.send(s).is_err() {
            return self.close();
        }
        Ok(())
    }

    /// Closes the queue and waits for the thread to write what it holds and close
    /// the files.
    fn close(&mut self) -> Result<(), Error> {
        drop(self.tx.take());
        match self.handle.take().map(|h| h.join()) {
            None => Ok(()),
            Some(Ok(r)) => r,
            Some(Err(p)) => std::panic::resume_unwind(p),
        }
    }
}

impl Drop for Writer {
    fn drop(&mut self) {
        if let Err(e) = self.close() {
            log::warn!("{e}");
        }
    }
}

/// `e`, with what the files hold after it.
fn with_kept(e: Error, kept: &str) -> Error {
    match e {
        Error::Output { path, source } => super::guard::write_error(&path, source, kept),
        other => other,
    }
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
    "nets.csv",
    "final_state.csv",
    "end_forces.parquet",
    "tensions.parquet",
    "positions.parquet",
    "winches.parquet",
    "bodies.parquet",
    "points.parquet",
    "nets.parquet",
    "final_state.parquet",
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

/// An output error on `path` with message `what`.
fn output_error(path: &Path, what: String) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        source: std::io::Error::other(what),
    }
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
            format: OutputFormat::Csv,
            lock: None,
            writer: None,
            cap: None,
            group_rows: None,
        }
    }

    /// The tables' format (CSV by default); Parquet in a build without the `parquet`
    /// feature is an error that says so.
    pub fn format(mut self, format: OutputFormat) -> Result<Self, Error> {
        format
            .check_available()
            .map_err(|m| output_error(&self.dir, m))?;
        self.format = format;
        Ok(self)
    }

    /// For tests: Parquet row groups of at least `rows` node rows (1: a row group per
    /// frame).
    #[doc(hidden)]
    pub fn with_group_rows(mut self, rows: usize) -> Self {
        self.group_rows = Some(rows);
        self
    }

    /// For tests: every table file acts as a full disk past `bytes` (its writes fail
    /// with "no space left on device").
    #[doc(hidden)]
    pub fn with_disk_limit(mut self, bytes: u64) -> Self {
        self.cap = Some(bytes);
        self
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

    fn start(&mut self) -> Result<(), Error> {
        self.claim_dir()?;
        let tables: Box<dyn Tables> = match self.format {
            OutputFormat::Csv => Box::new(super::csv_files::CsvTables::new(&self.dir, self.cap)),
            #[cfg(feature = "parquet")]
            OutputFormat::Parquet => Box::new(super::parquet_files::ParquetTables::new(
                &self.dir,
                self.cap,
                self.group_rows.unwrap_or(super::parquet_files::GROUP_ROWS),
            )),
            #[cfg(not(feature = "parquet"))]
            OutputFormat::Parquet => unreachable!("refused by FileSink::format"),
        };
        self.writer = Some(Writer::start(&self.dir, tables));
        Ok(())
    }
}

impl OutputSink for FileSink {
    fn frame(&mut self, s: &Snapshot) -> Result<(), Error> {
        self.frame_owned(s.clone())
    }

    fn frame_owned(&mut self, s: Snapshot) -> Result<(), Error> {
        if self.writer.is_none() {
            self.start()?;
        }
        self.writer.as_mut().expect("started above").send(s)
    }

    fn finish(&mut self, summary: &Summary) -> Result<(), Error> {
        match self.writer.as_mut() {
            Some(w) => w.close()?,
            None => self.claim_dir()?,
        }
        write_summary(&self.dir, summary)
    }
}
