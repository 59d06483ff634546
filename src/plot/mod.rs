//! `cablesim plot`: PNG charts of a run's or a study's output files, drawn with
//! `plotters` (bitmap backend; text in DejaVu Sans, shipped in `assets/fonts`).
//!
//! From a run's directory: `end_forces.png` (force magnitude at each cable end against
//! time) and, with `positions.csv`, `profiles.png` (side view x-z and plan view x-y of
//! every cable at chosen times), and with `bodies.csv`, `bodies.png` (each body's
//! reference point and angles against time, and its velocities where the run has them).
//! From a study's directory (`study.csv`,
//! `members.csv`): `gumbel_<sea state>_<channel>.png` (the seed maxima on Gumbel paper
//! with the fitted line) and, when channels have capacities, `utilisation.png` (both of
//! the study's first mooring condition, the intact one) and, for a study of several
//! conditions, `conditions.png` (the governing utilisation of each condition, with its
//! line and sea state). With a `fatigue.csv` (a run's or a study's), `fatigue.png`: the
//! damage per line and location. With a `nets.csv`, `nets.png`: each cage's volume ratio
//! and drag against time; from a folder of runs (folders holding a `nets.csv` each, a
//! sweep of current speeds), `cage_sweep.png`: both against the current speed.

mod charts;
pub mod data;

use crate::error::Error;
use std::path::{Path, PathBuf};

/// Image size, pixels.
pub const SIZE: (u32, u32) = (1200, 800);

/// Draws every chart the files in `dir` allow into `out` (created when needed);
/// `times` picks the profiles' output times (s; first and last when empty). Returns
/// the images written.
pub fn plot_dir(dir: &Path, out: &Path, times: &[f64]) -> Result<Vec<PathBuf>, Error> {
    charts::register_font();
    std::fs::create_dir_all(out).map_err(|source| Error::Output {
        path: out.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    let ef = dir.join("end_forces.csv");
    if ef.exists() {
        let p = out.join("end_forces.png");
        charts::end_forces(&p, &data::end_force_series(&ef)?)?;
        written.push(p);
    }
    let bodies = dir.join("bodies.csv");
    if bodies.exists() {
        let p = out.join("bodies.png");
        charts::bodies(&p, &data::body_motion(&bodies)?)?;
        written.push(p);
    }
    let nets = dir.join("nets.csv");
    if nets.exists() {
        let (v, d) = data::net_series(&nets)?;
        let p = out.join("nets.png");
        charts::nets(&p, &v, &d, false)?;
        written.push(p);
    }
    if let Some((v, d)) = data::net_sweep(dir)? {
        let p = out.join("cage_sweep.png");
        charts::nets(&p, &v, &d, true)?;
        written.push(p);
    }
    let pos = dir.join("positions.csv");
    if pos.exists() {
        let p = out.join("profiles.png");
        charts::profiles(&p, &data::profiles(&pos, times)?)?;
        written.push(p);
    }
    let (members, study) = (dir.join("members.csv"), dir.join("study.csv"));
    if members.exists() && study.exists() {
        for g in data::gumbel_data(&members, &study)? {
            let name = format!("gumbel_{}_{}.png", g.sea_state.0, file_safe(&g.channel.0));
            let p = out.join(name);
            charts::gumbel(&p, &g)?;
            written.push(p);
        }
        let u = data::utilisation(&study)?;
        if !u.is_empty() {
            let p = out.join("utilisation.png");
            charts::utilisation(&p, &u)?;
            written.push(p);
        }
        let g = data::governing(&study)?;
        if !g.is_empty() {
            let p = out.join("conditions.png");
            charts::governing(&p, &g)?;
            written.push(p);
        }
    }
    let fatigue = dir.join("fatigue.csv");
    if fatigue.exists() {
        let (rows, what) = data::fatigue(&fatigue)?;
        if !rows.is_empty() {
            let p = out.join("fatigue.png");
            charts::fatigue(&p, &rows, what)?;
            written.push(p);
        }
    }
    if written.is_empty() {
        let parquet = dir.join("end_forces.parquet").exists();
        return Err(Error::Plot {
            path: dir.to_path_buf(),
            message: if parquet {
                "the run wrote Parquet tables (`--format parquet`): `cablesim plot` reads the CSV \
                 ones; run again with `--format csv`, or plot the Parquet files with pandas"
                    .into()
            } else {
                "nothing to plot: no end_forces.csv, positions.csv, study.csv/members.csv, \
                 or folders of runs with a nets.csv each"
                    .into()
            },
        });
    }
    Ok(written)
}

/// A channel name as a file name part (letters, digits, `-`, `_`; the rest `_`).
fn file_safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
