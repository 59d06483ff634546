//! Fatigue of lines (the fatigue limit state): rainflow counting of tension records
//! ([`rainflow`]), T-N curves and Miner's damage ([`curves`]), and where a run or a
//! study counts them ([`FatigueSpec`], from a scenario's `[fatigue]` table).
//!
//! A location is a cable end (the magnitude of the force the cable exerts on its start
//! or end support, as `end_forces.csv` gives it) or one element (its tension, as
//! `tensions.csv` gives it). Its record is counted as it streams
//! ([`DamageCounter`]), so a run or a study member keeps no time series: each closed
//! cycle's damage is added at once, and the residue's half cycles at the end.

pub mod curves;
pub mod rainflow;

pub use curves::{chain_area, narrow_band_damage, TnCurve, NAMED_CURVES};
pub use rainflow::{cycles, Cycle, Rainflow};

use serde::{Deserialize, Serialize};
use std::fmt;

/// Where on a cable a record is counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(into = "String", try_from = "String")]
pub enum Location {
    /// The start end: the magnitude of the force on the start support.
    Start,
    /// The end: the magnitude of the force on the end support.
    End,
    /// The tension of element `K` (from 0 at the start), as `tensions.csv`'s `element`.
    Element(usize),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Start => f.write_str("start"),
            Location::End => f.write_str("end"),
            Location::Element(k) => write!(f, "{k}"),
        }
    }
}

impl From<Location> for String {
    fn from(l: Location) -> String {
        l.to_string()
    }
}

impl TryFrom<String> for Location {
    type Error = String;
    fn try_from(s: String) -> Result<Location, String> {
        match s.as_str() {
            "start" => Ok(Location::Start),
            "end" => Ok(Location::End),
            k => k
                .parse()
                .map(Location::Element)
                .map_err(|_| format!("a location is start, end or an element index, got \"{s}\"")),
        }
    }
}

/// One location whose fatigue is counted, with everything its damage needs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FatigueLocation {
    /// The cable's name.
    pub cable: String,
    /// The cable's index in the model (and in every snapshot).
    pub cable_index: usize,
    /// Where on the cable.
    pub location: Location,
    /// The cable's line type.
    pub line_type: String,
    /// Its T-N curve.
    pub curve: TnCurve,
    /// The nominal area the tension range is divided by, m^2.
    pub area_m2: f64,
}

impl FatigueLocation {
    /// The value this location counts in a snapshot of its cable: the magnitude of an
    /// end force, or an element's tension (`None` for an element a winch has hauled in).
    pub fn value(&self, tensions: &[f64], start: [f64; 3], end: [f64; 3]) -> Option<f64> {
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        match self.location {
            Location::Start => Some(norm(start)),
            Location::End => Some(norm(end)),
            Location::Element(k) => tensions.get(k).copied(),
        }
    }
}

/// A scenario's `[fatigue]` table, resolved against its model.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FatigueSpec {
    /// Samples before this time are not counted (a single run's start-up), s.
    pub transient: f64,
    /// The locations, cable by cable in model order, each cable's in the order given.
    pub locations: Vec<FatigueLocation>,
}

/// The fatigue of one location over one record.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FatigueRecord {
    /// Cycles counted (a half cycle counts 0.5).
    pub cycles: f64,
    /// Miner's damage of the record.
    pub damage: f64,
    /// The record's length counted: last sample time less first, s.
    pub duration: f64,
}

/// Counts one location's record as it streams: rainflow cycles and their damage.
#[derive(Clone, Debug)]
pub struct DamageCounter {
    rainflow: Rainflow,
    curve: TnCurve,
    area_m2: f64,
    transient: f64,
    cycles: f64,
    damage: f64,
    span: Option<(f64, f64)>,
}

impl DamageCounter {
    /// A counter for `loc` that ignores samples before `transient` (s).
    pub fn new(loc: &FatigueLocation, transient: f64) -> Self {
        DamageCounter {
            rainflow: Rainflow::new(),
            curve: loc.curve.clone(),
            area_m2: loc.area_m2,
            transient,
            cycles: 0.0,
            damage: 0.0,
            span: None,
        }
    }

    /// Adds sample `x` (N) at time `t` (s).
    pub fn push(&mut self, t: f64, x: f64) {
        if t < self.transient {
            return;
        }
        let (curve, area) = (&self.curve, self.area_m2);
        let (cycles, damage) = (&mut self.cycles, &mut self.damage);
        self.rainflow.push(x, &mut |c: Cycle| {
            *cycles += c.count;
            *damage += curve.damage(c.range, area, c.count);
        });
        self.span = Some(self.span.map_or((t, t), |(t0, _)| (t0, t)));
    }

    /// The record's cycles and damage, its residue counted as half cycles.
    pub fn finish(self) -> FatigueRecord {
        let (curve, area) = (&self.curve, self.area_m2);
        let (mut cycles, mut damage) = (self.cycles, self.damage);
        self.rainflow.finish(&mut |c: Cycle| {
            cycles += c.count;
            damage += curve.damage(c.range, area, c.count);
        });
        FatigueRecord {
            cycles,
            damage,
            duration: self.span.map_or(0.0, |(t0, t1)| t1 - t0),
        }
    }
}
