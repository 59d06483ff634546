//! The output tables in either format: the Parquet files hold the CSV files' numbers
//! bit for bit, every column with its unit; an interrupted run's Parquet files open and
//! hold every frame; a full disk stops the run with a clear error and leaves every file
//! readable up to its last whole frame; the summary stays small per cable; an output
//! directory on a read-only file system is refused before any work.

use cablesim::output::{FileSink, MemorySink};
use cablesim::{Overrides, Simulation};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

fn run_cli(scenario: &str, out: &Path, extra: &[&str]) {
    let o = Command::new(BIN)
        .args(["run", "-q", scenario, "--out"])
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{scenario} {extra:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The CSV file `path` as columns of text.
fn csv_columns(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let names: Vec<String> = r.headers().unwrap().iter().map(str::to_string).collect();
    let mut cols = vec![Vec::new(); names.len()];
    for rec in r.records() {
        let rec = rec.unwrap();
        for (c, f) in cols.iter_mut().zip(rec.iter()) {
            c.push(f.to_string());
        }
    }
    (names, cols)
}

#[cfg(feature = "parquet")]
mod parquet_tables {
    use super::*;
    use cablesim::options::OutputFormat;
    use cablesim::output::{read_parquet, Column, Table};

    /// Every table of a CSV run against the same table of a Parquet run: the same
    /// columns, rows and values (floats bit for bit: CSV writes the shortest text that
    /// reads back to the same f64), and a unit for every column.
    fn same_tables(csv_dir: &Path, pq_dir: &Path) -> usize {
        let mut compared = 0;
        for t in Table::ALL.iter().chain([&Table::FINAL_STATE]) {
            let (c, p) = (csv_dir.join(t.file("csv")), pq_dir.join(t.file("parquet")));
            assert_eq!(
                c.exists(),
                p.exists(),
                "{} and {}",
                c.display(),
                p.display()
            );
            if !c.exists() {
                continue;
            }
            let (names, cols) = csv_columns(&c);
            let pt = read_parquet(&p).unwrap();
            let pnames: Vec<&str> = pt.columns.iter().map(|(n, _)| n.as_str()).collect();
            assert_eq!(names, pnames, "{}", t.name);
            for (n, unit, _) in t.columns {
                let u = pt.units.iter().find(|(c, _)| c.as_str() == *n);
                assert_eq!(
                    u.map(|x| x.1.as_str()),
                    Some(*unit),
                    "{}: unit of {n}",
                    t.name
                );
            }
            for ((name, text), (_, col)) in names.iter().zip(&cols).zip(&pt.columns) {
                match col {
                    Column::F64(v) => {
                        assert_eq!(v.len(), text.len(), "{}.{name}", t.name);
                        for (k, (a, b)) in text.iter().zip(v).enumerate() {
                            let a: f64 = a.parse().unwrap();
                            assert_eq!(a.to_bits(), b.to_bits(), "{}.{name} row {k}", t.name);
                        }
                    }
                    Column::Int(v) => {
                        let a: Vec<i64> = text.iter().map(|x| x.parse().unwrap()).collect();
                        assert_eq!(&a, v, "{}.{name}", t.name);
                    }
                    Column::Text(v) => assert_eq!(text, v, "{}.{name}", t.name),
                }
            }
            compared += 1;
        }
        compared
    }

    #[test]
    fn parquet_tables_hold_the_csv_numbers_bit_for_bit() {
        let dir = tempfile::tempdir().unwrap();
        // Points (a buoy), bodies (a vessel in waves; a free buoy), a winch: every table.
        let cases = [
            ("examples/buoy_spread.toml", "points"),
            ("examples/spread_mooring_waves.toml", "bodies"),
            ("examples/winch_deploy.toml", "winches"),
            // A free body: bodies with their velocity columns.
            ("tests/data/free_buoy.toml", "bodies"),
        ];
        for (scenario, table) in cases {
            let (c, p) = (dir.path().join("csv"), dir.path().join("pq"));
            run_cli(scenario, &c, &["--duration", "2", "--backend", "cpu"]);
            run_cli(
                scenario,
                &p,
                &["--duration", "2", "--backend", "cpu", "--format", "parquet"],
            );
            assert!(p.join(format!("{table}.parquet")).exists(), "{scenario}");
            let n = same_tables(&c, &p);
            assert!(n >= 4, "{scenario}: {n} tables");
            // No CSV table in the Parquet run's folder.
            assert!(!p.join("tensions.csv").exists());
        }
    }

    #[test]
    fn the_scenario_key_chooses_parquet() {
        let dir = tempfile::tempdir().unwrap();
        let text = std::fs::read_to_string("examples/catenary.toml").unwrap();
        let text = format!("{text}\n[output]\nformat = \"parquet\"\n");
        let path = dir.path().join("c.toml");
        std::fs::write(&path, text).unwrap();
        let out = dir.path().join("out");
        run_cli(path.to_str().unwrap(), &out, &["--duration", "1"]);
        let t = read_parquet(&out.join("tensions.parquet")).unwrap();
        // Two output times of 50 elements.
        assert_eq!(t.rows(), 2 * 50);
        // The flag wins over the key.
        let out2 = dir.path().join("out2");
        run_cli(
            path.to_str().unwrap(),
            &out2,
            &["--duration", "1", "--format", "csv"],
        );
        assert!(out2.join("tensions.csv").exists());
        assert!(!out2.join("tensions.parquet").exists());
        // An unknown format is refused with the names allowed.
        let bad = std::fs::read_to_string(&path)
            .unwrap()
            .replace("format = \"parquet\"", "format = \"hdf5\"");
        std::fs::write(&path, bad).unwrap();
        let o = Command::new(BIN)
            .args(["check"])
            .arg(&path)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success());
        assert!(
            err.contains("output.format") && err.contains("csv or parquet"),
            "{err}"
        );
        assert_eq!(OutputFormat::Parquet.check_available(), Ok(()));
    }

    /// `examples/catenary.toml` for `duration` s with an output every 0.05 s.
    fn dense_catenary(dir: &Path, duration: f64) -> PathBuf {
        let text = std::fs::read_to_string("examples/catenary.toml")
            .unwrap()
            .replace("duration = 60.0 ", &format!("duration = {duration:e} "))
            .replace("output_interval = 1.0 ", "output_interval = 0.05 ");
        assert!(
            text.contains("output_interval = 0.05"),
            "the example changed"
        );
        let path = dir.join("dense.toml");
        std::fs::write(&path, text).unwrap();
        path
    }

    /// The output times of a table: distinct, in file order.
    fn times(t: &cablesim::output::ParquetTable) -> Vec<f64> {
        let Some(Column::F64(v)) = t.column("time") else {
            panic!("no time column")
        };
        let mut out: Vec<f64> = Vec::new();
        for &x in v {
            if out.last() != Some(&x) {
                out.push(x);
            }
        }
        out
    }

    #[test]
    fn an_interrupted_parquet_run_keeps_every_frame() {
        for signal in ["-INT", "-TERM"] {
            let dir = tempfile::tempdir().unwrap();
            let scenario = dense_catenary(dir.path(), 1e5);
            let out = dir.path().join("out");
            let mut child = Command::new(BIN)
                .args(["run", "-q", "--format", "parquet", "--out"])
                .arg(&out)
                .arg(&scenario)
                .spawn()
                .unwrap();
            // The files are created at the first frame; let it step a while.
            let t0 = Instant::now();
            while !out.join("tensions.parquet").exists() {
                assert!(t0.elapsed() < Duration::from_secs(120), "no output");
                std::thread::sleep(Duration::from_millis(50));
            }
            std::thread::sleep(Duration::from_millis(1500));
            assert!(
                child.try_wait().unwrap().is_none(),
                "the run ended by itself"
            );
            let killed = Command::new("kill")
                .args([signal, &child.id().to_string()])
                .status()
                .unwrap();
            assert!(killed.success());
            let t0 = Instant::now();
            let status = loop {
                if let Some(s) = child.try_wait().unwrap() {
                    break s;
                }
                assert!(t0.elapsed() < Duration::from_secs(30), "did not stop");
                std::thread::sleep(Duration::from_millis(50));
            };
            assert_eq!(status.code(), Some(130), "{signal}");
            let s: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                    .unwrap();
            assert_eq!(s["status"], "interrupted");
            let t_end = s["simulated_time"].as_f64().unwrap();
            for name in ["tensions", "end_forces", "positions"] {
                let t = read_parquet(&out.join(format!("{name}.parquet"))).unwrap();
                let ts = times(&t);
                // Every output time from 0, 0.05 s apart, then the time reached.
                assert!(ts.len() > 2, "{signal} {name}: {} frames", ts.len());
                for (k, w) in ts.windows(2).enumerate() {
                    if k + 2 < ts.len() {
                        assert!((w[1] - w[0] - 0.05).abs() < 1e-9, "{name}: {w:?}");
                    }
                }
                assert_eq!(ts[0], 0.0);
                assert_eq!(*ts.last().unwrap(), t_end, "{signal} {name}");
                let per_frame = match name {
                    "tensions" => 50,
                    "end_forces" => 2,
                    _ => 51,
                };
                assert_eq!(
                    t.rows(),
                    per_frame * ts.len(),
                    "{signal} {name}: whole frames"
                );
            }
            let fin = read_parquet(&out.join("final_state.parquet")).unwrap();
            assert_eq!(fin.rows(), 51);
        }
    }

    /// A full disk (a test's limit on each file's size) stops the run with an error
    /// naming the file and what the files hold; each file opens and holds whole frames.
    #[test]
    fn a_full_disk_stops_the_run_and_leaves_readable_files() {
        // Under this limit a Parquet file's footer (which lists every row group) does
        // not fit in the room its last, partial row group freed: the file gives up row
        // groups until it does, and the other files are cut back to match.
        for format in [OutputFormat::Csv, OutputFormat::Parquet] {
            let dir = tempfile::tempdir().unwrap();
            let scenario = dense_catenary(dir.path(), 20.0);
            let out = dir.path().join("out");
            let mut sim = Simulation::from_file(&scenario, &Overrides::default()).unwrap();
            // Room for some of the 401 frames but not all (Parquet: a row group per
            // frame, as a big run's frames are).
            let limit = match format {
                OutputFormat::Parquet => 60_000,
                OutputFormat::Csv => 150_000,
            };
            let mut sink = FileSink::new(&out)
                .format(format)
                .unwrap()
                .with_disk_limit(limit)
                .with_group_rows(1);
            let e = sim.run(&mut sink, |_| {}).unwrap_err().to_string();
            drop(sink);
            assert!(
                e.contains("no space left") && e.contains("the files hold"),
                "{format:?}: {e}"
            );
            let name = format.name();
            assert!(e.contains(&format!(".{name}")), "{e}");
            match format {
                OutputFormat::Parquet => {
                    for t in ["tensions", "end_forces", "positions"] {
                        let tb = read_parquet(&out.join(format!("{t}.parquet"))).unwrap();
                        let ts = times(&tb);
                        assert!(!ts.is_empty() && ts.len() < 401, "{t}: {} frames", ts.len());
                        let per = tb.rows() / ts.len();
                        assert_eq!(per * ts.len(), tb.rows(), "{t}: whole frames");
                        assert_eq!(tb.row_groups.len(), ts.len(), "{t}: a group per frame");
                    }
                }
                OutputFormat::Csv => {
                    for t in ["tensions", "end_forces", "positions"] {
                        let text = std::fs::read_to_string(out.join(format!("{t}.csv"))).unwrap();
                        assert!(text.ends_with('\n'), "{t} ends mid-row");
                        let (_, cols) = csv_columns(&out.join(format!("{t}.csv")));
                        let n = cols[0].len();
                        let mut frames = cols[0].clone();
                        frames.dedup();
                        assert!(!frames.is_empty() && frames.len() < 401, "{t}");
                        assert_eq!(n % frames.len(), 0, "{t}: whole frames");
                    }
                }
            }
        }
    }
}

/// `summary.json` holds a handful of numbers per cable, whatever the cables' length:
/// a fleet of 200 lines of 51 nodes stays under 250 bytes a cable (10 MB for 40,000).
#[test]
fn the_summary_stays_small_per_cable() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string("examples/fleet.toml")
        .unwrap()
        .replace("count = 1000", "count = 200")
        .replace("columns = 40", "columns = 20");
    assert!(text.contains("count = 200"), "the example changed");
    let path = dir.path().join("fleet.toml");
    std::fs::write(&path, text).unwrap();
    let out = dir.path().join("out");
    run_cli(
        path.to_str().unwrap(),
        &out,
        &["--duration", "0.5", "--backend", "cpu"],
    );
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let s: serde_json::Value = serde_json::from_str(&text).unwrap();
    let cables = s["cables"].as_array().unwrap();
    assert_eq!(cables.len(), 200);
    // A line per cable; what grows with the fleet is those lines.
    let lines: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("  {\"name\""))
        .collect();
    assert_eq!(lines.len(), 200);
    let per_cable = lines.iter().map(|l| l.len() + 1).sum::<usize>() / 200;
    println!("summary.json: {} bytes, {per_cable} a cable", text.len());
    assert!(per_cable < 250, "{per_cable} bytes a cable");
    assert!(text.len() < 200 * 250 + 2000, "{} bytes", text.len());
    // The final state is in its own file, every node of every cable.
    let fin = super::common::final_state(&out);
    assert_eq!(fin.len(), 200);
    assert!(fin.iter().all(|(_, n)| n.len() == 51));
    // Each cable's extremes bound its tensions at every output time.
    let (_, cols) = csv_columns(&out.join("tensions.csv"));
    let c0 = &cables[0];
    let name = c0["name"].as_str().unwrap();
    let t: Vec<f64> = cols[1]
        .iter()
        .zip(&cols[3])
        .filter(|(c, _)| c.as_str() == name)
        .map(|(_, x)| x.parse().unwrap())
        .collect();
    let max = t.iter().copied().fold(f64::MIN, f64::max);
    let min = t.iter().copied().fold(f64::MAX, f64::min);
    assert_eq!(c0["max_tension"][0].as_f64().unwrap(), max);
    assert_eq!(c0["min_tension"].as_f64().unwrap(), min);
}

/// The summary of the library's own run matches what the sink was handed: the end
/// forces of the last frame.
#[test]
fn the_summary_end_forces_are_the_last_frames() {
    let mut sim = Simulation::from_file(
        "examples/catenary.toml",
        &Overrides {
            duration: Some(2.0),
            ..Overrides::default()
        },
    )
    .unwrap();
    let mut sink = MemorySink::new();
    let s = sim.run(&mut sink, |_| {}).unwrap();
    let last = sink.frames.last().unwrap();
    assert_eq!(s.cables[0].end_forces, last.cables[0].end_forces);
    let m = s.cables[0].max_tension.unwrap();
    let top = sink
        .frames
        .iter()
        .flat_map(|f| f.cables[0].tensions.iter().copied())
        .fold(f64::MIN, f64::max);
    assert_eq!(m.tension, top);
}

/// A tmpfs mounted at a fresh folder for the test's life (`options` such as `ro` or
/// `size=1m`): `None` where this process may not mount (not root, no mount
/// namespace), and the test that asked is skipped.
struct Tmpfs {
    dir: tempfile::TempDir,
}

impl Tmpfs {
    fn mount(options: &str) -> Option<Self> {
        let dir = tempfile::tempdir().ok()?;
        let ok = Command::new("mount")
            .args(["-t", "tmpfs", "-o", options, "tmpfs"])
            .arg(dir.path())
            .stderr(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        ok.then_some(Self { dir })
    }

    fn path(&self) -> &Path {
        self.dir.path()
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(self.dir.path()).status();
    }
}

/// An output directory on a read-only file system is refused before the run is set
/// up, naming the directory and the cause.
#[test]
fn a_read_only_output_directory_is_refused_before_any_work() {
    let Some(fs) = Tmpfs::mount("ro,size=1m") else {
        eprintln!("skipped: cannot mount a tmpfs here");
        return;
    };
    let out = fs.path().join("out");
    let o = Command::new(BIN)
        .args(["run", "examples/fleet.toml", "--backend", "cpu", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains(out.to_str().unwrap()) && err.contains("Read-only file system"),
        "{err}"
    );
    // Refused before the set-up: the fleet's mesh and step plan were never logged.
    assert!(!err.contains("nodes,"), "{err}");
}

/// A real full disk (a 1 MiB tmpfs): the run stops with an error that names the file
/// and says what the files hold, and every table opens with whole frames.
#[test]
fn a_full_tmpfs_stops_the_run_with_readable_files() {
    // Parquet in a smaller tmpfs (the catenary's compressed tables fit in 1 MiB). A run
    // this small gathers its frames into one row group, so here the files keep no frame
    // but must still open (a footer, no partial group); frames kept row group by row
    // group are checked under a size limit above (`a_full_disk_...`).
    for (format, size) in [("csv", "size=1m"), ("parquet", "size=48k")] {
        if format == "parquet" && !cfg!(feature = "parquet") {
            continue;
        }
        let Some(fs) = Tmpfs::mount(size) else {
            eprintln!("skipped: cannot mount a tmpfs here");
            return;
        };
        let dir = tempfile::tempdir().unwrap();
        let text = std::fs::read_to_string("examples/catenary.toml")
            .unwrap()
            .replace("output_interval = 1.0 ", "output_interval = 0.05 ");
        let scenario = dir.path().join("dense.toml");
        std::fs::write(&scenario, text).unwrap();
        let out = fs.path().join("out");
        let o = Command::new(BIN)
            .args(["run", "-q", "--format", format, "--out"])
            .arg(&out)
            .arg(&scenario)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{format}: the run should fail");
        assert!(
            err.contains("No space left on device") && err.contains("the files hold"),
            "{format}: {err}"
        );
        if format == "csv" {
            for t in ["tensions", "end_forces", "positions"] {
                let p = out.join(format!("{t}.csv"));
                let text = std::fs::read_to_string(&p).unwrap();
                assert!(text.is_empty() || text.ends_with('\n'), "{t} ends mid-row");
            }
        }
        #[cfg(feature = "parquet")]
        if format == "parquet" {
            for t in ["tensions", "end_forces", "positions"] {
                let tb = cablesim::output::read_parquet(&out.join(format!("{t}.parquet")))
                    .unwrap_or_else(|e| panic!("{t}: {e}"));
                println!("{t}.parquet after the disk filled: {} rows", tb.rows());
                // Whole frames: the same number of rows at every time.
                let Some(cablesim::output::Column::F64(times)) = tb.column("time") else {
                    panic!("{t}: no time column")
                };
                let mut frames = times.clone();
                frames.dedup();
                assert!(frames.len() < 401, "{t}: the disk filled before the end");
                if !frames.is_empty() {
                    assert_eq!(tb.rows() % frames.len(), 0, "{t}: whole frames");
                }
            }
        }
    }
}
