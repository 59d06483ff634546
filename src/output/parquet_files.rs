//! The Parquet tables ([`ParquetTables`]): the same tables as the CSV files, in the
//! same long layout (a row per time, cable and element or node), as compressed
//! columns; written on the file sink's writer thread.
//!
//! Each file is written in whole row groups: a frame of a big run is one, the frames
//! of a small run are gathered into one of up to [`GROUP_ROWS`] node rows. A file is
//! closed (its footer written) when the run ends, completed, interrupted or failed;
//! after a failed write (a full disk) it is cut back to its last whole row group and
//! given a footer that lists those.

use super::guard::GuardedFile;
use super::sink::Snapshot;
use super::tables::{Kind, Table, Tables};
use crate::error::Error;
use parquet::basic::{Compression, ConvertedType, LogicalType, Repetition, Type as Physical};
use parquet::column::writer::ColumnWriter;
use parquet::data_type::ByteArray;
use parquet::file::metadata::{FileMetaData, KeyValue, ParquetMetaData, ParquetMetaDataWriter};
use parquet::file::properties::{EnabledStatistics, WriterProperties};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::{ColumnPath, Type};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Node rows gathered before a row group is written (a frame larger than this is a
/// row group of its own).
pub const GROUP_ROWS: usize = 1 << 18;

/// Values handed to a column writer at a time.
const CHUNK: usize = 1 << 14;

fn perr(path: &Path, e: parquet::errors::ParquetError) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        source: match e {
            parquet::errors::ParquetError::External(b) => match b.downcast::<std::io::Error>() {
                Ok(io) => *io,
                Err(b) => std::io::Error::other(b.to_string()),
            },
            other => std::io::Error::other(other.to_string()),
        },
    }
}

/// One Parquet file being written.
struct PqFile {
    /// Its table, with the columns this run writes.
    table: Table,
    path: PathBuf,
    cap: Option<u64>,
    w: Option<SerializedFileWriter<GuardedFile>>,
    /// Bytes on disk at the end of each whole row group (the magic number's end
    /// first).
    ends: Vec<u64>,
    /// What the footer needs, once the writer is gone (its own footer's write
    /// failed, or the file is being cut back after a write error).
    failed_close: Option<Footer>,
}

fn schema(t: &Table) -> Arc<Type> {
    let fields = t
        .columns
        .iter()
        .map(|(name, _, kind)| {
            let b = match kind {
                Kind::F64 => Type::primitive_type_builder(name, Physical::DOUBLE),
                Kind::Int => Type::primitive_type_builder(name, Physical::INT32),
                Kind::Text => Type::primitive_type_builder(name, Physical::BYTE_ARRAY)
                    .with_logical_type(Some(LogicalType::String))
                    .with_converted_type(ConvertedType::UTF8),
            };
            Arc::new(
                b.with_repetition(Repetition::REQUIRED)
                    .build()
                    .expect("a valid column"),
            )
        })
        .collect();
    Arc::new(
        Type::group_type_builder("schema")
            .with_fields(fields)
            .build()
            .expect("a valid schema"),
    )
}

fn properties(t: &Table) -> Arc<WriterProperties> {
    // Snappy throughout; dictionaries only where values repeat (names, times, indices):
    // on the float columns a dictionary is tried, overflows and is thrown away, which
    // costs time and saves nothing. Statistics per column chunk, no page index (the
    // footer then lists the row groups alone, which the cut-back after a write error
    // rewrites).
    let mut b = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .set_dictionary_enabled(false)
        .set_statistics_enabled(EnabledStatistics::Chunk)
        .set_offset_index_disabled(true)
        .set_max_row_group_row_count(None)
        .set_created_by(format!("cablesim {}", env!("CARGO_PKG_VERSION")))
        .set_key_value_metadata(Some(vec![
            KeyValue::new("units".to_string(), t.units_json()),
            KeyValue::new("cablesim.table".to_string(), t.name.to_string()),
        ]));
    for (name, _, kind) in t.columns {
        if *kind != Kind::F64 || *name == "time" {
            b = b.set_column_dictionary_enabled(ColumnPath::from(*name), true);
        }
    }
    Arc::new(b.build())
}

impl PqFile {
    fn create(dir: &Path, t: &Table, cap: Option<u64>) -> Result<Self, Error> {
        let path = dir.join(t.file("parquet"));
        let g = GuardedFile::create(&path, cap)?;
        let mut w =
            SerializedFileWriter::new(g, schema(t), properties(t)).map_err(|e| perr(&path, e))?;
        // The magic number on disk: the start a cut-back keeps.
        w.flush().map_err(|e| perr(&path, e.into()))?;
        let ends = vec![w.bytes_written() as u64];
        Ok(Self {
            table: *t,
            path,
            cap,
            w: Some(w),
            ends,
            failed_close: None,
        })
    }

    /// Writes `frames` as one row group of table `t`.
    fn group(&mut self, t: &Table, frames: &[&Snapshot]) -> Result<(), Error> {
        let path = self.path.clone();
        let w = self.w.as_mut().expect("open");
        let r = (|| -> parquet::errors::Result<()> {
            let mut rg = w.next_row_group()?;
            for (name, _, _) in t.columns {
                let mut col = rg.next_column()?.expect("a column per schema field");
                let mut o = Out::new(col.untyped());
                for s in frames {
                    fill(t.name, name, s, &mut o);
                }
                o.flush();
                if let Some(e) = o.err.take() {
                    return Err(e);
                }
                col.close()?;
            }
            rg.close()?;
            w.flush()?;
            Ok(())
        })();
        r.map_err(|e| perr(&path, e))?;
        self.ends.push(w.bytes_written() as u64);
        Ok(())
    }

    fn close(&mut self) -> Result<(), Error> {
        if let Some(w) = self.w.take() {
            // What a footer needs, kept should the footer's write fail.
            let parts = Footer::of(&w);
            w.close().map_err(|e| {
                self.failed_close = Some(parts);
                perr(&self.path, e)
            })?;
        }
        Ok(())
    }

    /// Whole row groups on disk.
    fn whole(&self) -> usize {
        self.ends.len() - 1
    }

    /// After a failed write: the file cut back to at most its first `groups` row
    /// groups, with a footer that lists them; returns the row groups it keeps (a file
    /// closed whole is left as it is). On a full disk the footer may not fit in the
    /// room the cut-back freed (it lists every row group kept): then the file is cut
    /// back one row group further, which frees that group's bytes and shortens the
    /// footer, until it fits.
    fn salvage(&mut self, groups: usize) -> usize {
        if let Some(w) = self.w.take() {
            self.failed_close = Some(Footer::of(&w));
        }
        let Some(parts) = self.failed_close.as_ref() else {
            return self.whole();
        };
        let mut last = None;
        for g in (0..=groups.min(self.whole())).rev() {
            let footer = match parts.bytes(g) {
                Ok(b) => b,
                Err(e) => {
                    log::warn!("{}: no footer could be formed: {e}", self.path.display());
                    return 0;
                }
            };
            match GuardedFile::reopen(&self.path, self.cap)
                .and_then(|mut f| f.cut_back(self.ends[g], &footer))
            {
                Ok(()) => return g,
                Err(e) if e.kind() == std::io::ErrorKind::StorageFull => last = Some(e),
                Err(e) => {
                    last = Some(e);
                    break;
                }
            }
        }
        if let Some(e) = last {
            log::warn!(
                "{}: could not be closed after the write error ({e}): it has no footer",
                self.path.display()
            );
        }
        0
    }
}

/// What a file's footer is made of: its row groups, properties and schema.
struct Footer {
    groups: Vec<parquet::file::metadata::RowGroupMetaData>,
    props: Arc<WriterProperties>,
    schema: parquet::schema::types::SchemaDescPtr,
}

impl Footer {
    fn of(w: &SerializedFileWriter<GuardedFile>) -> Self {
        Self {
            groups: w.flushed_row_groups().to_vec(),
            props: w.properties().clone(),
            schema: Arc::new(w.schema_descr().clone()),
        }
    }

    /// The footer listing the first `n` row groups.
    fn bytes(&self, n: usize) -> parquet::errors::Result<Vec<u8>> {
        let groups = self.groups[..n.min(self.groups.len())].to_vec();
        let rows = groups.iter().map(|g| g.num_rows()).sum();
        let meta = ParquetMetaData::new(
            FileMetaData::new(
                self.props.writer_version().as_num(),
                rows,
                Some(self.props.created_by().to_string()),
                self.props.key_value_metadata().cloned(),
                self.schema.clone(),
                None,
            ),
            groups,
        );
        let mut footer = Vec::new();
        ParquetMetaDataWriter::new(&mut footer, &meta).finish()?;
        Ok(footer)
    }
}

/// The values of one column, gathered in chunks and handed to its writer.
struct Out<'a, 'b> {
    col: &'a mut ColumnWriter<'b>,
    f: Vec<f64>,
    i: Vec<i32>,
    t: Vec<ByteArray>,
    err: Option<parquet::errors::ParquetError>,
}

impl<'a, 'b> Out<'a, 'b> {
    fn new(col: &'a mut ColumnWriter<'b>) -> Self {
        Self {
            col,
            f: Vec::new(),
            i: Vec::new(),
            t: Vec::new(),
            err: None,
        }
    }

    fn f(&mut self, v: f64) {
        self.f.push(v);
        if self.f.len() >= CHUNK {
            self.flush();
        }
    }

    fn i(&mut self, v: usize) {
        self.i.push(v as i32);
        if self.i.len() >= CHUNK {
            self.flush();
        }
    }

    /// `n` rows of text `v`.
    fn t(&mut self, v: &str, n: usize) {
        if n == 0 {
            return;
        }
        let b = ByteArray::from(v.as_bytes().to_vec());
        for _ in 0..n {
            self.t.push(b.clone());
            if self.t.len() >= CHUNK {
                self.flush();
            }
        }
    }

    fn flush(&mut self) {
        if self.err.is_some() {
            self.f.clear();
            self.i.clear();
            self.t.clear();
            return;
        }
        let r = match self.col {
            ColumnWriter::DoubleColumnWriter(w) if !self.f.is_empty() => {
                w.write_batch(&self.f, None, None).map(|_| ())
            }
            ColumnWriter::Int32ColumnWriter(w) if !self.i.is_empty() => {
                w.write_batch(&self.i, None, None).map(|_| ())
            }
            ColumnWriter::ByteArrayColumnWriter(w) if !self.t.is_empty() => {
                w.write_batch(&self.t, None, None).map(|_| ())
            }
            _ => Ok(()),
        };
        if let Err(e) = r {
            self.err = Some(e);
        }
        self.f.clear();
        self.i.clear();
        self.t.clear();
    }
}

/// The axis of a column named `x`, `fy`, `vz`, `mx`, ...
fn axis(col: &str) -> usize {
    match col.as_bytes().last() {
        Some(b'x') => 0,
        Some(b'y') => 1,
        _ => 2,
    }
}

/// Hands column `col` of table `table` at frame `s` to `o`, row by row in the CSV
/// file's order.
fn fill(table: &str, col: &str, s: &Snapshot, o: &mut Out) {
    let time = s.time;
    match table {
        "end_forces" => {
            for c in &s.cables {
                let (a, b) = (c.end_forces.start, c.end_forces.end);
                match col {
                    "time" => (0..2).for_each(|_| o.f(time)),
                    "cable" => o.t(&c.name, 2),
                    "end" => {
                        o.t("start", 1);
                        o.t("end", 1)
                    }
                    _ => {
                        let d = axis(col);
                        o.f(a[d]);
                        o.f(b[d]);
                    }
                }
            }
        }
        "tensions" => {
            for c in &s.cables {
                match col {
                    "time" => c.tensions.iter().for_each(|_| o.f(time)),
                    "cable" => o.t(&c.name, c.tensions.len()),
                    "element" => (0..c.tensions.len()).for_each(|k| o.i(k)),
                    _ => c.tensions.iter().for_each(|&x| o.f(x)),
                }
            }
        }
        "positions" => {
            for c in s.cables.iter().filter(|c| c.output_positions) {
                match col {
                    "time" => c.positions.iter().for_each(|_| o.f(time)),
                    "cable" => o.t(&c.name, c.positions.len()),
                    "node" => (0..c.positions.len()).for_each(|k| o.i(k)),
                    _ => c.positions.iter().for_each(|x| o.f(x[axis(col)])),
                }
            }
        }
        "winches" => {
            for c in &s.cables {
                let Some(w) = &c.winch else { continue };
                match col {
                    "time" => o.f(time),
                    "cable" => o.t(&c.name, 1),
                    "deployed_length" => o.f(w.deployed_length),
                    "variable_l0" => o.f(w.variable_l0),
                    _ => o.i(w.elements),
                }
            }
        }
        "bodies" => {
            for b in &s.bodies {
                match col {
                    "time" => o.f(time),
                    "body" => o.t(&b.name, 1),
                    "x" | "y" | "z" => o.f(b.position[axis(col)]),
                    "roll" => o.f(b.angles[0]),
                    "pitch" => o.f(b.angles[1]),
                    "yaw" => o.f(b.angles[2]),
                    "fx" | "fy" | "fz" => o.f(b.force[axis(col)]),
                    "mx" | "my" | "mz" => o.f(b.moment[axis(col)]),
                    "vx" | "vy" | "vz" => o.f(b.velocity.map_or(0.0, |u| u[axis(col)])),
                    _ => o.f(b.velocity.map_or(0.0, |u| u[3 + axis(col)])),
                }
            }
        }
        "points" => {
            for p in &s.points {
                match col {
                    "time" => o.f(time),
                    "point" => o.t(&p.name, 1),
                    "x" | "y" | "z" => o.f(p.position[axis(col)]),
                    _ => o.f(p.force[axis(col)]),
                }
            }
        }
        "nets" => {
            for n in &s.nets {
                match col {
                    "time" => o.f(time),
                    "net" => o.t(&n.name, 1),
                    "volume" => o.f(n.volume),
                    "volume_ratio" => o.f(n.volume_ratio),
                    "fx" => o.f(n.force[0]),
                    "fy" => o.f(n.force[1]),
                    "drag" => o.f(n.force[0].hypot(n.force[1])),
                    "collar_z" => o.f(n.collar_z),
                    _ => o.f(n.current),
                }
            }
        }
        "final_state" => {
            for c in &s.cables {
                match col {
                    "cable" => o.t(&c.name, c.positions.len()),
                    "node" => (0..c.positions.len()).for_each(|k| o.i(k)),
                    "x" | "y" | "z" => c.positions.iter().for_each(|x| o.f(x[axis(col)])),
                    _ => c.velocities.iter().for_each(|v| o.f(v[axis(col)])),
                }
            }
        }
        other => unreachable!("table {other}"),
    }
}

/// Node rows a frame adds (what [`GROUP_ROWS`] counts).
fn rows(s: &Snapshot) -> usize {
    s.cables.iter().map(|c| c.positions.len()).sum::<usize>()
        + s.bodies.len()
        + s.points.len()
        + s.nets.len()
}

/// The Parquet tables of a run (`end_forces.parquet`, `tensions.parquet`, ...: the
/// CSV files' tables and columns).
pub(crate) struct ParquetTables {
    dir: PathBuf,
    cap: Option<u64>,
    /// By table, in [`Table::ALL`] order; `None` for a table the run does not write.
    files: Vec<Option<PqFile>>,
    /// Frames not yet in a row group.
    pending: Vec<Arc<Snapshot>>,
    /// The time of the last frame of each row group written.
    group_times: Vec<f64>,
    pending_rows: usize,
    /// Node rows gathered before a row group is written.
    group_rows: usize,
}

impl ParquetTables {
    pub fn new(dir: &Path, cap: Option<u64>, group_rows: usize) -> Self {
        Self {
            dir: dir.to_path_buf(),
            cap,
            files: Vec::new(),
            pending: Vec::new(),
            group_times: Vec::new(),
            pending_rows: 0,
            group_rows,
        }
    }

    fn write_pending(&mut self) -> Result<(), Error> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let frames: Vec<&Snapshot> = self.pending.iter().map(|a| &**a).collect();
        for f in self.files.iter_mut().flatten() {
            let t = f.table;
            f.group(&t, &frames)?;
        }
        self.group_times.push(frames.last().expect("pending").time);
        self.pending.clear();
        self.pending_rows = 0;
        Ok(())
    }
}

impl Tables for ParquetTables {
    fn frame(&mut self, s: &Arc<Snapshot>) -> Result<(), Error> {
        if self.files.is_empty() {
            for t in Table::ALL.iter() {
                self.files.push(if t.present(s) {
                    Some(PqFile::create(&self.dir, &t.for_run(s), self.cap)?)
                } else {
                    None
                });
            }
        }
        self.pending.push(s.clone());
        self.pending_rows += rows(s);
        if self.pending_rows >= self.group_rows {
            self.write_pending()?;
        }
        Ok(())
    }

    fn finish(&mut self, last: Option<&Snapshot>) -> Result<(), Error> {
        self.write_pending()?;
        for f in self.files.iter_mut().flatten() {
            f.close()?;
        }
        if let Some(s) = last {
            let t = &Table::FINAL_STATE;
            let mut f = PqFile::create(&self.dir, t, self.cap)?;
            if let Err(e) = f.group(t, &[s]).and_then(|_| f.close()) {
                // Not left half-written: the error says it is missing.
                let _ = std::fs::remove_file(&f.path);
                return Err(e);
            }
        }
        Ok(())
    }

    fn abort(&mut self) -> Option<f64> {
        self.pending.clear();
        // The row groups whole in every file (the tables are written in turn, a row
        // group each).
        let whole = self
            .files
            .iter()
            .flatten()
            .map(PqFile::whole)
            .min()
            .unwrap_or(0)
            .min(self.group_times.len());
        // A file that had to give up row groups for its footer's room sets what all
        // keep: the others are cut back to match (their footers only shrink).
        let mut kept = whole;
        for f in self.files.iter_mut().flatten() {
            kept = kept.min(f.salvage(whole));
        }
        if kept < whole {
            for f in self.files.iter_mut().flatten() {
                f.salvage(kept);
            }
        }
        kept.checked_sub(1).map(|k| self.group_times[k])
    }
}

/// A column of a table read back ([`read_parquet`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// Floats.
    F64(Vec<f64>),
    /// Indices.
    Int(Vec<i64>),
    /// Names.
    Text(Vec<String>),
}

/// A Parquet table of a run read back whole: each column by name, and the units the
/// file's `units` metadata gives.
#[derive(Clone, Debug, PartialEq)]
pub struct ParquetTable {
    /// `(name, values)` in file order.
    pub columns: Vec<(String, Column)>,
    /// `(column, unit)` from the file's metadata.
    pub units: Vec<(String, String)>,
    /// Rows in each row group.
    pub row_groups: Vec<usize>,
}

impl ParquetTable {
    /// The column named `name`.
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, c)| c)
    }

    /// Rows.
    pub fn rows(&self) -> usize {
        self.row_groups.iter().sum()
    }
}

/// Reads a Parquet table a run wrote (the project's own reader; pandas, polars, DuckDB
/// and pyarrow read them as well).
pub fn read_parquet(path: &Path) -> Result<ParquetTable, Error> {
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::Field;
    let e = |e| perr(path, e);
    let file = std::fs::File::open(path).map_err(|source| Error::Output {
        path: path.to_path_buf(),
        source,
    })?;
    let r = SerializedFileReader::new(file).map_err(e)?;
    let meta = r.metadata();
    let schema = meta.file_metadata().schema_descr();
    let mut columns: Vec<(String, Column)> = schema
        .columns()
        .iter()
        .map(|c| {
            let v = match c.physical_type() {
                Physical::DOUBLE => Column::F64(Vec::new()),
                Physical::INT32 | Physical::INT64 => Column::Int(Vec::new()),
                _ => Column::Text(Vec::new()),
            };
            (c.name().to_string(), v)
        })
        .collect();
    let mut units = Vec::new();
    if let Some(kv) = meta.file_metadata().key_value_metadata() {
        for k in kv.iter().filter(|k| k.key == "units") {
            let v: serde_json::Value = serde_json::from_str(k.value.as_deref().unwrap_or("{}"))
                .map_err(|x| perr(path, parquet::errors::ParquetError::General(x.to_string())))?;
            if let Some(m) = v.as_object() {
                for (c, u) in m {
                    units.push((c.clone(), u.as_str().unwrap_or_default().to_string()));
                }
            }
        }
    }
    let row_groups = meta
        .row_groups()
        .iter()
        .map(|g| g.num_rows() as usize)
        .collect();
    for row in r.get_row_iter(None).map_err(e)? {
        let row = row.map_err(e)?;
        for ((_, col), (_, f)) in columns.iter_mut().zip(row.get_column_iter()) {
            match (col, f) {
                (Column::F64(v), Field::Double(x)) => v.push(*x),
                (Column::Int(v), Field::Int(x)) => v.push(*x as i64),
                (Column::Int(v), Field::Long(x)) => v.push(*x),
                (Column::Text(v), Field::Str(x)) => v.push(x.clone()),
                (_, other) => {
                    return Err(perr(
                        path,
                        parquet::errors::ParquetError::General(format!(
                            "unexpected value {other:?}"
                        )),
                    ))
                }
            }
        }
    }
    Ok(ParquetTable {
        columns,
        units,
        row_groups,
    })
}
