//! The series `cablesim plot` draws, read from a run's or a study's output files.

use crate::error::Error;
use std::collections::BTreeMap;
use std::path::Path;

/// One named series of `(x, y)` points.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points, in drawing order.
    pub points: Vec<(f64, f64)>,
}

fn bad(path: &Path, message: impl Into<String>) -> Error {
    Error::Plot {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// The rows of a CSV file with a header, as `column -> text` maps.
fn rows(path: &Path) -> Result<Vec<BTreeMap<String, String>>, Error> {
    let mut r = csv::Reader::from_path(path).map_err(|e| bad(path, e.to_string()))?;
    let head: Vec<String> = r
        .headers()
        .map_err(|e| bad(path, e.to_string()))?
        .iter()
        .map(str::to_string)
        .collect();
    r.records()
        .map(|rec| {
            let rec = rec.map_err(|e| bad(path, e.to_string()))?;
            Ok(head
                .iter()
                .cloned()
                .zip(rec.iter().map(str::to_string))
                .collect())
        })
        .collect()
}

fn num(path: &Path, row: &BTreeMap<String, String>, col: &str) -> Result<f64, Error> {
    let s = row
        .get(col)
        .ok_or_else(|| bad(path, format!("no column `{col}`")))?;
    s.parse()
        .map_err(|_| bad(path, format!("column `{col}`: `{s}` is not a number")))
}

fn opt_num(row: &BTreeMap<String, String>, col: &str) -> Option<f64> {
    row.get(col).and_then(|s| s.parse().ok())
}

/// `end_forces.csv`: per cable end (`cable start`, `cable end`, in file order), the
/// force magnitude against time, N.
pub fn end_force_series(path: &Path) -> Result<Vec<Series>, Error> {
    let mut out: Vec<Series> = Vec::new();
    for row in rows(path)? {
        let t = num(path, &row, "time")?;
        let f = [
            num(path, &row, "fx")?,
            num(path, &row, "fy")?,
            num(path, &row, "fz")?,
        ];
        let m = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let label = format!("{} {}", row["cable"], row["end"]);
        match out.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push((t, m)),
            None => out.push(Series {
                label,
                points: vec![(t, m)],
            }),
        }
    }
    Ok(out)
}

/// `bodies.csv`: per body, its motion against time.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyMotion {
    /// `x`, `y`, `z` of each body's reference point, m (labels `body x`, ...).
    pub position: Vec<Series>,
    /// Roll, pitch, yaw, degrees.
    pub angles: Vec<Series>,
    /// The reference point's velocity, m/s (runs with free or pinned bodies only).
    pub velocity: Vec<Series>,
    /// The angular velocity, deg/s (likewise).
    pub rates: Vec<Series>,
}

/// Reads `bodies.csv` (`time,body,x,y,z,roll,pitch,yaw,...[,vx,vy,vz,wx,wy,wz]`).
pub fn body_motion(path: &Path) -> Result<BodyMotion, Error> {
    let mut out = BodyMotion {
        position: Vec::new(),
        angles: Vec::new(),
        velocity: Vec::new(),
        rates: Vec::new(),
    };
    let push = |v: &mut Vec<Series>, label: String, t: f64, y: f64| match v
        .iter_mut()
        .find(|s| s.label == label)
    {
        Some(s) => s.points.push((t, y)),
        None => v.push(Series {
            label,
            points: vec![(t, y)],
        }),
    };
    for row in rows(path)? {
        let t = num(path, &row, "time")?;
        let body = row
            .get("body")
            .ok_or_else(|| bad(path, "no column `body`"))?
            .clone();
        for c in ["x", "y", "z"] {
            push(
                &mut out.position,
                format!("{body} {c}"),
                t,
                num(path, &row, c)?,
            );
        }
        for c in ["roll", "pitch", "yaw"] {
            push(
                &mut out.angles,
                format!("{body} {c}"),
                t,
                num(path, &row, c)?,
            );
        }
        for c in ["vx", "vy", "vz"] {
            if let Some(v) = opt_num(&row, c) {
                push(&mut out.velocity, format!("{body} {c}"), t, v);
            }
        }
        for c in ["wx", "wy", "wz"] {
            if let Some(v) = opt_num(&row, c) {
                push(&mut out.rates, format!("{body} {c}"), t, v.to_degrees());
            }
        }
    }
    Ok(out)
}

/// A cable's node positions at one time, m.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Cable name.
    pub cable: String,
    /// The output time, s.
    pub time: f64,
    /// Node positions, start to end, m.
    pub nodes: Vec<[f64; 3]>,
}

/// `positions.csv`: every cable's profile at the output times nearest `times` (s; the
/// first and the last output time when `times` is empty).
pub fn profiles(path: &Path, times: &[f64]) -> Result<Vec<Profile>, Error> {
    let all = rows(path)?;
    let mut out_times: Vec<f64> = Vec::new();
    for row in &all {
        let t = num(path, row, "time")?;
        if out_times.last() != Some(&t) {
            out_times.push(t);
        }
    }
    if out_times.is_empty() {
        return Err(bad(path, "no rows"));
    }
    let nearest = |t: f64| {
        *out_times
            .iter()
            .min_by(|a, b| (*a - t).abs().total_cmp(&(*b - t).abs()))
            .expect("not empty")
    };
    let mut chosen: Vec<f64> = if times.is_empty() {
        vec![out_times[0], *out_times.last().expect("not empty")]
    } else {
        times.iter().map(|&t| nearest(t)).collect()
    };
    chosen.dedup();
    let mut out: Vec<Profile> = Vec::new();
    for row in &all {
        let t = num(path, row, "time")?;
        if !chosen.contains(&t) {
            continue;
        }
        let x = [
            num(path, row, "x")?,
            num(path, row, "y")?,
            num(path, row, "z")?,
        ];
        let cable = &row["cable"];
        match out.iter_mut().find(|p| p.time == t && &p.cable == cable) {
            Some(p) => p.nodes.push(x),
            None => out.push(Profile {
                cable: cable.clone(),
                time: t,
                nodes: vec![x],
            }),
        }
    }
    Ok(out)
}

/// The seed maxima of one sea state and channel, with the Gumbel fit of `study.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct GumbelData {
    /// Sea state index and name.
    pub sea_state: (usize, String),
    /// Channel and its unit.
    pub channel: (String, String),
    /// The seed maxima, ascending.
    pub maxima: Vec<f64>,
    /// Fitted location and scale (`mle_mu`, `mle_beta`), when fitted.
    pub fit: Option<(f64, f64)>,
}

impl GumbelData {
    /// The plotted points: `(maximum, reduced variate -ln(-ln(i / (n + 1))))`, the
    /// `i`-th smallest maximum at its plotting position.
    pub fn points(&self) -> Vec<(f64, f64)> {
        let n = self.maxima.len() as f64;
        self.maxima
            .iter()
            .enumerate()
            .map(|(i, &x)| (x, -(-((i as f64 + 1.0) / (n + 1.0)).ln()).ln()))
            .collect()
    }
}

/// Whether a row of `members.csv` or `study.csv` is of the study's first mooring
/// condition (the intact one; every row of a table without the `condition` column).
fn first_condition(row: &BTreeMap<String, String>, first: &Option<String>) -> bool {
    match (row.get("condition"), first) {
        (Some(c), Some(f)) => c == f,
        _ => true,
    }
}

/// `members.csv` and `study.csv`: the seed maxima per sea state and channel (members
/// that completed), with the fits, of the study's first mooring condition.
pub fn gumbel_data(members: &Path, study: &Path) -> Result<Vec<GumbelData>, Error> {
    let mut out: Vec<GumbelData> = Vec::new();
    let member_rows = rows(members)?;
    let first = member_rows
        .first()
        .and_then(|r| r.get("condition").cloned());
    for row in member_rows {
        if !first_condition(&row, &first) {
            continue;
        }
        let Some(max) = opt_num(&row, "max") else {
            continue;
        };
        let ss = (
            num(members, &row, "sea_state")? as usize,
            row["sea_state_name"].clone(),
        );
        let ch = (row["channel"].clone(), row["unit"].clone());
        match out
            .iter_mut()
            .find(|g| g.sea_state.0 == ss.0 && g.channel.0 == ch.0)
        {
            Some(g) => g.maxima.push(max),
            None => out.push(GumbelData {
                sea_state: ss,
                channel: ch,
                maxima: vec![max],
                fit: None,
            }),
        }
    }
    for row in rows(study)? {
        if !first_condition(&row, &first) {
            continue;
        }
        let ss = num(study, &row, "sea_state")? as usize;
        if let Some(g) = out
            .iter_mut()
            .find(|g| g.sea_state.0 == ss && g.channel.0 == row["channel"])
        {
            g.fit = opt_num(&row, "mle_mu").zip(opt_num(&row, "mle_beta"));
        }
    }
    for g in &mut out {
        g.maxima.sort_by(f64::total_cmp);
    }
    Ok(out)
}

/// `study.csv`: `(sea state name, channel, utilisation)` for every row with a capacity
/// of the study's first mooring condition (the intact one).
pub fn utilisation(study: &Path) -> Result<Vec<(String, String, f64)>, Error> {
    let all = rows(study)?;
    let first = all.first().and_then(|r| r.get("condition").cloned());
    Ok(all
        .into_iter()
        .filter(|r| first_condition(r, &first))
        .filter_map(|r| {
            let u = opt_num(&r, "utilisation")?;
            Some((r["sea_state_name"].clone(), r["channel"].clone(), u))
        })
        .collect())
}

/// `study.csv`: per mooring condition, in table order, its governing utilisation:
/// `(condition (limit state), "channel, sea state", utilisation)`, the largest of its
/// rows. Empty for a study of one condition or without capacities.
pub fn governing(study: &Path) -> Result<Vec<(String, String, f64)>, Error> {
    let mut out: Vec<(String, String, f64)> = Vec::new();
    let all = rows(study)?;
    for r in &all {
        let (Some(c), Some(u)) = (r.get("condition"), opt_num(r, "utilisation")) else {
            continue;
        };
        let label = format!(
            "{} ({})",
            c,
            r.get("limit_state").map_or("", |s| s.as_str())
        );
        let what = format!("{}, {}", r["channel"], r["sea_state_name"]);
        match out.iter_mut().find(|g| g.0 == label) {
            Some(g) if u > g.2 => *g = (label, what, u),
            Some(_) => {}
            None => out.push((label, what, u)),
        }
    }
    if out.len() < 2 {
        out.clear();
    }
    Ok(out)
}

/// The fatigue damage per location of a `fatigue.csv`, and what it is: for a study's
/// (with a scatter diagram) `DFF * annual damage` per location (one value per
/// location, the reciprocal of its life in years); for a run's, the damage of the
/// record. Labels are `cable location`. Empty for a study without a scatter diagram.
pub fn fatigue(path: &Path) -> Result<(Vec<(String, f64)>, &'static str), Error> {
    let rows = rows(path)?;
    let study = rows
        .first()
        .is_some_and(|r| r.contains_key("annual_damage"));
    let mut out: Vec<(String, f64)> = Vec::new();
    for r in &rows {
        let label = format!("{} {}", r["cable"], r["location"]);
        if out.last().is_some_and(|l| l.0 == label) {
            continue; // a study's further sea states of the same location
        }
        let value = if study {
            match (
                opt_num(r, "annual_damage"),
                opt_num(r, "design_fatigue_factor"),
            ) {
                (Some(d), Some(f)) => d * f,
                _ => continue,
            }
        } else {
            num(path, r, "damage")?
        };
        out.push((label, value));
    }
    Ok((
        out,
        if study {
            "DFF x annual damage (1 / fatigue life, per year)"
        } else {
            "Miner damage of the record"
        },
    ))
}

/// `nets.csv`: per net, its volume ratio and the drag on it (kN) against time.
pub fn net_series(path: &Path) -> Result<(Vec<Series>, Vec<Series>), Error> {
    let (mut vol, mut drag): (Vec<Series>, Vec<Series>) = (Vec::new(), Vec::new());
    for row in rows(path)? {
        let t = num(path, &row, "time")?;
        let net = row
            .get("net")
            .cloned()
            .ok_or_else(|| bad(path, "no column `net`"))?;
        let v = num(path, &row, "volume_ratio")?;
        let d = num(path, &row, "drag")? / 1e3;
        for (out, y) in [(&mut vol, v), (&mut drag, d)] {
            match out.iter_mut().find(|s| s.label == net) {
                Some(s) => s.points.push((t, y)),
                None => out.push(Series {
                    label: net.clone(),
                    points: vec![(t, y)],
                }),
            }
        }
    }
    Ok((vol, drag))
}

/// A sweep of runs: the folders right inside `dir` that hold a `nets.csv`, each a run
/// (`dir` itself holds none). Per net, its volume ratio and drag (kN) against the
/// current speed, one point per run: each the mean over the run's second half of
/// output times (the first half left to the start's transient). `None` with fewer than
/// two such runs.
pub fn net_sweep(dir: &Path) -> Result<Option<(Vec<Series>, Vec<Series>)>, Error> {
    if dir.join("nets.csv").exists() {
        return Ok(None);
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(None);
    };
    let mut runs: Vec<std::path::PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path().join("nets.csv")))
        .filter(|p| p.exists())
        .collect();
    runs.sort();
    if runs.len() < 2 {
        return Ok(None);
    }
    let (mut vol, mut drag): (Vec<Series>, Vec<Series>) = (Vec::new(), Vec::new());
    for path in &runs {
        let rows = rows(path)?;
        let end = rows
            .iter()
            .filter_map(|r| opt_num(r, "time"))
            .fold(f64::NEG_INFINITY, f64::max);
        // net -> (sums of current, ratio, drag; count)
        let mut acc: Vec<(String, [f64; 3], f64)> = Vec::new();
        for row in &rows {
            let t = num(path, row, "time")?;
            if t < 0.5 * end {
                continue;
            }
            let net = row
                .get("net")
                .cloned()
                .ok_or_else(|| bad(path, "no column `net`"))?;
            let x = [
                num(path, row, "current")?,
                num(path, row, "volume_ratio")?,
                num(path, row, "drag")? / 1e3,
            ];
            match acc.iter_mut().find(|a| a.0 == net) {
                Some(a) => {
                    (0..3).for_each(|k| a.1[k] += x[k]);
                    a.2 += 1.0;
                }
                None => acc.push((net, x, 1.0)),
            }
        }
        for (net, s, n) in acc {
            let (u, v, d) = (s[0] / n, s[1] / n, s[2] / n);
            for (out, y) in [(&mut vol, v), (&mut drag, d)] {
                match out.iter_mut().find(|s| s.label == net) {
                    Some(s) => s.points.push((u, y)),
                    None => out.push(Series {
                        label: net.clone(),
                        points: vec![(u, y)],
                    }),
                }
            }
        }
    }
    for s in vol.iter_mut().chain(drag.iter_mut()) {
        s.points.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    Ok(Some((vol, drag)))
}
