//! The study's output files: `members.csv` (member x channel), `study.csv`
//! (condition x sea state x channel) and `study.json` (the whole summary). The columns are listed in
//! `docs/src/studies.md`. Both CSVs are long ("tidy") tables, one row per pair, which
//! spreadsheets pivot and data-frame libraries read as they are; text fields are quoted
//! where they need it (a name holding a comma), empty cells mean "not defined" (a fit of
//! fewer than two seeds, a channel without a capacity). Numbers are written in the
//! shortest form that reads back to the same `f64`.

use super::extremes::StudySummary;
use super::results::StudyResults;
use crate::error::Error;
use serde::Serialize;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

#[derive(Serialize)]
struct MemberRow<'a> {
    member: usize,
    condition: &'a str,
    sea_state: usize,
    sea_state_name: &'a str,
    seed: u64,
    wave_seed: u64,
    status: &'a str,
    channel: String,
    unit: &'a str,
    samples: u64,
    max: Option<f64>,
    time_of_max: Option<f64>,
    min: Option<f64>,
    time_of_min: Option<f64>,
    mean: Option<f64>,
    std: Option<f64>,
    up_crossings: u64,
    up_crossing_period: Option<f64>,
    error: &'a str,
}

#[derive(Serialize)]
struct StudyRow<'a> {
    condition: &'a str,
    limit_state: &'a str,
    sea_state: usize,
    sea_state_name: &'a str,
    hs: f64,
    tp: f64,
    gamma: Option<f64>,
    heading: f64,
    current_speed: f64,
    current_heading: f64,
    channel: &'a str,
    unit: &'a str,
    seeds: usize,
    failed: usize,
    mean: Option<f64>,
    std: Option<f64>,
    up_crossing_period: Option<f64>,
    max_mean: Option<f64>,
    max_std: Option<f64>,
    max_largest: Option<f64>,
    min_smallest: Option<f64>,
    mle_mu: Option<f64>,
    mle_beta: Option<f64>,
    moments_mu: Option<f64>,
    moments_beta: Option<f64>,
    fit: &'a str,
    mpm: Option<f64>,
    quantile_p: f64,
    quantile: Option<f64>,
    mean_factor: Option<f64>,
    dynamic_factor: Option<f64>,
    capacity: Option<f64>,
    design_tension: Option<f64>,
    utilisation: Option<f64>,
}

fn io_err(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |source| Error::Output {
        path: path.to_path_buf(),
        source,
    }
}

fn csv_err(path: &Path, e: csv::Error) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        source: e.into(),
    }
}

/// Writes `members.csv`: one row per member and channel, in member then channel order.
pub fn write_members_csv(path: &Path, r: &StudyResults) -> Result<(), Error> {
    let mut w = csv::Writer::from_path(path).map_err(|e| csv_err(path, e))?;
    for m in &r.members {
        let name = r.study.sea_states[m.member.sea_state]
            .name
            .as_deref()
            .unwrap_or("");
        let error = match &m.status {
            super::MemberStatus::Failed { message } => message.as_str(),
            super::MemberStatus::Completed => "",
        };
        for (ch, s) in r.channels.iter().zip(&m.stats) {
            w.serialize(MemberRow {
                member: m.member.index,
                condition: &r.conditions[m.member.condition].name,
                sea_state: m.member.sea_state,
                sea_state_name: name,
                seed: m.member.seed,
                wave_seed: m.member.wave_seed,
                status: m.status.name(),
                channel: ch.name(),
                unit: ch.quantity.unit(),
                samples: s.count(),
                max: s.max().map(|e| e.value),
                time_of_max: s.max().map(|e| e.time),
                min: s.min().map(|e| e.value),
                time_of_min: s.min().map(|e| e.time),
                mean: s.mean(),
                std: s.std(),
                up_crossings: s.up_crossings(),
                up_crossing_period: s.mean_up_crossing_period(),
                error,
            })
            .map_err(|e| csv_err(path, e))?;
        }
    }
    w.flush().map_err(io_err(path))
}

/// Writes `study.csv`: one row per sea state and channel.
pub fn write_study_csv(path: &Path, s: &StudySummary) -> Result<(), Error> {
    let mut w = csv::Writer::from_path(path).map_err(|e| csv_err(path, e))?;
    for ss in &s.sea_states {
        let st = &ss.sea_state;
        for c in &ss.channels {
            w.serialize(StudyRow {
                condition: &ss.condition_name,
                limit_state: &ss.limit_state,
                sea_state: ss.index,
                sea_state_name: st.name.as_deref().unwrap_or(""),
                hs: st.hs,
                tp: st.tp,
                gamma: st.gamma,
                heading: st.heading,
                current_speed: st.current_speed,
                current_heading: st.current_heading,
                channel: &c.channel,
                unit: &c.unit,
                seeds: c.seeds,
                failed: c.failed,
                mean: c.mean,
                std: c.std,
                up_crossing_period: c.up_crossing_period,
                max_mean: c.max_mean,
                max_std: c.max_std,
                max_largest: c.max_largest,
                min_smallest: c.min_smallest,
                mle_mu: c.gumbel_mle.map(|g| g.mu),
                mle_beta: c.gumbel_mle.map(|g| g.beta),
                moments_mu: c.gumbel_moments.map(|g| g.mu),
                moments_beta: c.gumbel_moments.map(|g| g.beta),
                fit: s.study.fit.name(),
                mpm: c.mpm,
                quantile_p: s.study.quantile,
                quantile: c.quantile,
                mean_factor: c.design.map(|d| d.mean_factor),
                dynamic_factor: c.design.map(|d| d.dynamic_factor),
                capacity: c.design.map(|d| d.capacity),
                design_tension: c.design.map(|d| d.design_tension),
                utilisation: c.design.map(|d| d.utilisation),
            })
            .map_err(|e| csv_err(path, e))?;
        }
    }
    w.flush().map_err(io_err(path))
}

/// Writes `study.json`: the summary, pretty-printed.
pub fn write_study_json(path: &Path, s: &StudySummary) -> Result<(), Error> {
    let io = io_err(path);
    let mut w = BufWriter::new(File::create(path).map_err(&io)?);
    serde_json::to_writer_pretty(&mut w, s).map_err(|e| io(e.into()))?;
    w.write_all(b"\n").map_err(&io)?;
    w.flush().map_err(io)
}

/// Writes the three files into `dir` (which must exist), and `fatigue.csv` for a study
/// with fatigue locations; returns the names of the files written.
pub fn write_all(
    dir: &Path,
    r: &StudyResults,
    s: &StudySummary,
) -> Result<Vec<&'static str>, Error> {
    let mut written = vec!["study.csv", "members.csv", "study.json"];
    write_members_csv(&dir.join("members.csv"), r)?;
    write_study_csv(&dir.join("study.csv"), s)?;
    if !r.fatigue.is_empty() {
        super::fatigue::write_fatigue_csv(&dir.join("fatigue.csv"), r, &s.fatigue)?;
        written.push("fatigue.csv");
    }
    write_study_json(&dir.join("study.json"), s)?;
    Ok(written)
}
