//! The CSV tables ([`CsvTables`]): one text row per line, written on the file sink's
//! writer thread.

use super::guard::GuardedFile;
use super::sink::Snapshot;
use super::tables::{Table, Tables};
use crate::error::Error;
use std::collections::HashMap;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One CSV file and where its whole frames end.
struct CsvFile {
    w: BufWriter<GuardedFile>,
    /// Bytes at the end of each whole frame (the header's end first).
    marks: Vec<u64>,
}

/// The marks' times: `times[k]` is the time of the frame that ends at `marks[k + 1]`.
type Times = Vec<f64>;

impl CsvFile {
    fn create(dir: &Path, t: &Table, cap: Option<u64>) -> Result<Self, Error> {
        let path = dir.join(t.file("csv"));
        let mut w = BufWriter::with_capacity(1 << 18, GuardedFile::create(&path, cap)?);
        let header: Vec<&str> = t.columns.iter().map(|c| c.0).collect();
        writeln!(w, "{}", header.join(",")).map_err(|e| io(&path, e))?;
        let mut f = Self {
            w,
            marks: Vec::new(),
        };
        f.mark();
        Ok(f)
    }

    fn position(&self) -> u64 {
        self.w.get_ref().written() + self.w.buffer().len() as u64
    }

    fn mark(&mut self) {
        let p = self.position();
        self.marks.push(p);
    }

    fn path(&self) -> PathBuf {
        self.w.get_ref().path().to_path_buf()
    }
}

fn io(path: &Path, source: std::io::Error) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        source,
    }
}

/// The CSV tables of a run (`end_forces.csv`, `tensions.csv`, `positions.csv`, ...;
/// [`super::FileSink`] lists them).
pub(crate) struct CsvTables {
    dir: PathBuf,
    cap: Option<u64>,
    /// By table, in [`Table::ALL`] order; `None` for a table the run does not write.
    files: Vec<Option<CsvFile>>,
    /// The time of each whole frame, in order.
    times: Times,
    /// Each name as one CSV field ([`csv_field`]), formed at its first output: a
    /// `csv::Writer` per field allocates and zeroes an 8 KiB buffer, which at every
    /// output time of every cable cost about 4% of a moored run's instructions.
    quoted: HashMap<String, String>,
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

impl CsvTables {
    pub fn new(dir: &Path, cap: Option<u64>) -> Self {
        Self {
            dir: dir.to_path_buf(),
            cap,
            files: Vec::new(),
            times: Vec::new(),
            quoted: HashMap::new(),
        }
    }

    fn write_frame(&mut self, s: &Snapshot) -> Result<(), Error> {
        let t = s.time;
        let q = &mut self.quoted;
        for (table, slot) in Table::ALL.iter().zip(self.files.iter_mut()) {
            let Some(f) = slot.as_mut() else { continue };
            let w = &mut f.w;
            let r: std::io::Result<()> = (|| {
                match table.name {
                    "end_forces" => {
                        for c in &s.cables {
                            let name = quoted(q, &c.name);
                            let (a, b) = (c.end_forces.start, c.end_forces.end);
                            writeln!(w, "{t},{name},start,{},{},{}", a[0], a[1], a[2])?;
                            writeln!(w, "{t},{name},end,{},{},{}", b[0], b[1], b[2])?;
                        }
                    }
                    "tensions" => {
                        for c in &s.cables {
                            let name = quoted(q, &c.name);
                            for (k, x) in c.tensions.iter().enumerate() {
                                writeln!(w, "{t},{name},{k},{x}")?;
                            }
                        }
                    }
                    "positions" => {
                        for c in s.cables.iter().filter(|c| c.output_positions) {
                            let name = quoted(q, &c.name);
                            for (k, x) in c.positions.iter().enumerate() {
                                writeln!(w, "{t},{name},{k},{},{},{}", x[0], x[1], x[2])?;
                            }
                        }
                    }
                    "winches" => {
                        for c in &s.cables {
                            if let Some(ws) = &c.winch {
                                writeln!(
                                    w,
                                    "{t},{},{},{},{}",
                                    quoted(q, &c.name),
                                    ws.deployed_length,
                                    ws.variable_l0,
                                    ws.elements
                                )?;
                            }
                        }
                    }
                    "bodies" => {
                        for b in &s.bodies {
                            let (x, a, f, m) = (b.position, b.angles, b.force, b.moment);
                            write!(
                                w,
                                "{t},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                                quoted(q, &b.name),
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
                            )?;
                            if let Some(u) = b.velocity {
                                write!(
                                    w,
                                    ",{},{},{},{},{},{}",
                                    u[0], u[1], u[2], u[3], u[4], u[5]
                                )?;
                            }
                            writeln!(w)?;
                        }
                    }
                    "points" => {
                        for p in &s.points {
                            let (x, f) = (p.position, p.force);
                            writeln!(
                                w,
                                "{t},{},{},{},{},{},{},{}",
                                quoted(q, &p.name),
                                x[0],
                                x[1],
                                x[2],
                                f[0],
                                f[1],
                                f[2]
                            )?;
                        }
                    }
                    "nets" => {
                        for n in &s.nets {
                            let f = n.force;
                            writeln!(
                                w,
                                "{t},{},{},{},{},{},{},{},{}",
                                quoted(q, &n.name),
                                n.volume,
                                n.volume_ratio,
                                f[0],
                                f[1],
                                f[0].hypot(f[1]),
                                n.collar_z,
                                n.current
                            )?;
                        }
                    }
                    other => unreachable!("table {other}"),
                }
                Ok(())
            })();
            r.map_err(|e| io(&f.path(), e))?;
        }
        // Every table has this frame whole: mark it.
        for f in self.files.iter_mut().flatten() {
            f.mark();
        }
        self.times.push(t);
        Ok(())
    }
}

impl Tables for CsvTables {
    fn frame(&mut self, s: &Arc<Snapshot>) -> Result<(), Error> {
        if self.files.is_empty() {
            for t in Table::ALL.iter() {
                self.files.push(if t.present(s) {
                    Some(CsvFile::create(&self.dir, &t.for_run(s), self.cap)?)
                } else {
                    None
                });
            }
        }
        self.write_frame(s)
    }

    fn finish(&mut self, last: Option<&Snapshot>) -> Result<(), Error> {
        for f in self.files.iter_mut().flatten() {
            let path = f.path();
            f.w.flush().map_err(|e| io(&path, e))?;
        }
        if let Some(s) = last {
            let t = &Table::FINAL_STATE;
            let mut f = CsvFile::create(&self.dir, t, self.cap)?;
            let path = f.path();
            let r: std::io::Result<()> = (|| {
                for c in &s.cables {
                    let name = quoted(&mut self.quoted, &c.name);
                    for (k, (x, v)) in c.positions.iter().zip(&c.velocities).enumerate() {
                        writeln!(
                            f.w,
                            "{name},{k},{},{},{},{},{},{}",
                            x[0], x[1], x[2], v[0], v[1], v[2]
                        )?;
                    }
                }
                f.w.flush()
            })();
            if let Err(e) = r {
                // Not left half-written: the error says it is missing.
                drop(f);
                let _ = std::fs::remove_file(&path);
                return Err(io(&path, e));
            }
        }
        Ok(())
    }

    fn abort(&mut self) -> Option<f64> {
        // What the disk still takes goes out; then every file is cut back to the last
        // frame whole in all of them.
        let mut whole = self.times.len();
        let mut files = Vec::new();
        for f in self.files.iter_mut().filter_map(Option::take) {
            let mut w = f.w;
            let _ = w.flush();
            let (g, _) = w.into_parts();
            let on_disk = g.written();
            // marks[0] is the header; marks[k] the end of frame k (1-based).
            let frames = f
                .marks
                .iter()
                .filter(|&&m| m <= on_disk)
                .count()
                .saturating_sub(1);
            whole = whole.min(frames);
            files.push((g, f.marks));
        }
        for (mut g, marks) in files {
            let keep = marks.get(whole).copied().unwrap_or(0);
            let keep = if g.written() >= keep { keep } else { 0 };
            if let Err(e) = g.cut_back(keep, b"") {
                log::warn!(
                    "{}: could not cut back to its last whole frame: {e}",
                    g.path().display()
                );
            }
        }
        whole.checked_sub(1).map(|k| self.times[k])
    }
}
