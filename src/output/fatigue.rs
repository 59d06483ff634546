//! `fatigue.csv` of a run whose scenario has a `[fatigue]` table ([`FatigueSink`]).

use super::sink::{OutputSink, Snapshot};
use super::summary::Summary;
use crate::error::Error;
use crate::fatigue::{DamageCounter, FatigueSpec};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Counts the fatigue of a run's locations as its output times stream by, and writes
/// `fatigue.csv` at the end: one row per location, with what its damage is computed
/// from (the curve, the nominal area, the samples' time span), so that anyone can
/// recompute it from `end_forces.csv` (an end's force magnitude at each output time)
/// or `tensions.csv` (an element's tension). Hand it to the run after the
/// [`super::FileSink`] that claims the directory.
pub struct FatigueSink {
    dir: PathBuf,
    spec: FatigueSpec,
    counters: Vec<DamageCounter>,
}

#[derive(Serialize)]
struct Row<'a> {
    cable: &'a str,
    location: String,
    line_type: &'a str,
    curve: &'a str,
    a_d: f64,
    m: f64,
    area_m2: f64,
    transient: f64,
    duration: f64,
    cycles: f64,
    damage: f64,
}

impl FatigueSink {
    /// A sink writing `dir/fatigue.csv` for the locations of `spec`.
    pub fn new(dir: impl Into<PathBuf>, spec: FatigueSpec) -> Self {
        let counters = spec
            .locations
            .iter()
            .map(|l| DamageCounter::new(l, spec.transient))
            .collect();
        FatigueSink {
            dir: dir.into(),
            spec,
            counters,
        }
    }
}

/// Writes the rows of `spec`'s locations with their records to `path`.
fn write(path: &Path, spec: &FatigueSpec, counters: Vec<DamageCounter>) -> Result<(), Error> {
    let e = |source: std::io::Error| Error::Output {
        path: path.to_path_buf(),
        source,
    };
    let mut w = csv::Writer::from_path(path).map_err(|x| e(x.into()))?;
    for (loc, c) in spec.locations.iter().zip(counters) {
        let r = c.finish();
        w.serialize(Row {
            cable: &loc.cable,
            location: loc.location.to_string(),
            line_type: &loc.line_type,
            curve: loc.curve.name.as_deref().unwrap_or(""),
            a_d: loc.curve.a_d,
            m: loc.curve.m,
            area_m2: loc.area_m2,
            transient: spec.transient,
            duration: r.duration,
            cycles: r.cycles,
            damage: r.damage,
        })
        .map_err(|x| e(x.into()))?;
    }
    w.flush().map_err(e)
}

impl OutputSink for FatigueSink {
    fn frame(&mut self, s: &Snapshot) -> Result<(), Error> {
        for (loc, counter) in self.spec.locations.iter().zip(&mut self.counters) {
            let c = &s.cables[loc.cable_index];
            debug_assert_eq!(c.name, loc.cable);
            if let Some(x) = loc.value(&c.tensions, c.end_forces.start, c.end_forces.end) {
                counter.push(s.time, x);
            }
        }
        Ok(())
    }

    fn finish(&mut self, _summary: &Summary) -> Result<(), Error> {
        let counters = std::mem::take(&mut self.counters);
        write(&self.dir.join("fatigue.csv"), &self.spec, counters)
    }
}
