//! The fatigue limit state of a study: per location (a cable end or element of the base
//! scenario's `[fatigue]` table) and sea state, the Miner damage of the seeds' records
//! (rainflow-counted as each member ran, `crate::fatigue`), scaled to the sea state's
//! hours per year in the scatter diagram; summed over the scatter diagram, the annual
//! damage and the fatigue life `1 / (DFF * annual damage)`. Written as `fatigue.csv`.
//! The fatigue is the intact mooring's: the members of the first condition (the intact
//! one, which a study with a scatter diagram keeps).
//!
//! Every sum runs over members in member order and sea states in study order, so a
//! merged study gives the same bits as one machine.

use super::results::{MemberStatus, StudyResults};
use crate::error::Error;
use crate::fatigue::FatigueLocation;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One location in one sea state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeaStateDamage {
    /// Index of the sea state.
    pub sea_state: usize,
    /// Completed members (seeds) averaged.
    pub seeds: usize,
    /// Mean record length counted, s.
    pub duration: Option<f64>,
    /// Mean cycles counted per record.
    pub cycles: Option<f64>,
    /// Mean Miner damage per record.
    pub damage: Option<f64>,
    /// Hours per year of the sea state in the scatter diagram (`None`: not in it).
    pub hours: Option<f64>,
    /// Its share of the annual damage: `damage * 3600 hours / duration`.
    pub annual_damage: Option<f64>,
}

/// One location over the whole study.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LocationFatigue {
    /// The location, its curve and nominal area.
    #[serde(flatten)]
    pub location: FatigueLocation,
    /// Per sea state, in study order.
    pub sea_states: Vec<SeaStateDamage>,
    /// The annual damage: the sum over the scatter diagram's sea states (`None` without
    /// a scatter diagram, or when a sea state of it has no completed member).
    pub annual_damage: Option<f64>,
    /// The design fatigue factor applied.
    pub design_fatigue_factor: Option<f64>,
    /// The fatigue life, years: `1 / (DFF * annual damage)` (`None` where the annual
    /// damage is undefined or zero).
    pub life: Option<f64>,
}

/// The fatigue of every location of a study (empty when the base scenario has no
/// `[fatigue]` table).
pub fn summarise(r: &StudyResults) -> Vec<LocationFatigue> {
    let def = &r.study;
    r.fatigue
        .iter()
        .enumerate()
        .map(|(l, loc)| {
            let sea_states: Vec<SeaStateDamage> = (0..def.sea_states.len())
                .map(|s| {
                    let records: Vec<_> = r
                        .members
                        .iter()
                        .filter(|m| {
                            m.member.sea_state == s
                                && m.member.condition == 0
                                && m.status == MemberStatus::Completed
                        })
                        .map(|m| m.fatigue[l])
                        .collect();
                    let n = records.len();
                    let mean = |f: &dyn Fn(&crate::fatigue::FatigueRecord) -> f64| {
                        (n > 0).then(|| records.iter().map(f).sum::<f64>() / n as f64)
                    };
                    let (duration, cycles, damage) = (
                        mean(&|x| x.duration),
                        mean(&|x| x.cycles),
                        mean(&|x| x.damage),
                    );
                    let hours = def.annual_hours(s);
                    let annual_damage = match (hours, damage, duration) {
                        (Some(h), Some(d), Some(t)) if t > 0.0 => Some(d * h * 3600.0 / t),
                        _ => None,
                    };
                    SeaStateDamage {
                        sea_state: s,
                        seeds: n,
                        duration,
                        cycles,
                        damage,
                        hours,
                        annual_damage,
                    }
                })
                .collect();
            let dff = def.fatigue.as_ref().map(|f| f.design_fatigue_factor);
            let annual_damage = dff.and_then(|_| {
                sea_states
                    .iter()
                    .filter(|s| s.hours.is_some())
                    .map(|s| s.annual_damage)
                    .sum::<Option<f64>>()
            });
            let life = match (annual_damage, dff) {
                (Some(d), Some(f)) if d > 0.0 => Some(1.0 / (f * d)),
                _ => None,
            };
            LocationFatigue {
                location: loc.clone(),
                sea_states,
                annual_damage,
                design_fatigue_factor: dff,
                life,
            }
        })
        .collect()
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
    sea_state: usize,
    sea_state_name: &'a str,
    seeds: usize,
    duration: Option<f64>,
    cycles: Option<f64>,
    damage: Option<f64>,
    hours: Option<f64>,
    sea_state_annual_damage: Option<f64>,
    annual_damage: Option<f64>,
    design_fatigue_factor: Option<f64>,
    life: Option<f64>,
}

/// Writes `fatigue.csv`: one row per location and sea state, the location's totals
/// (annual damage, DFF, life) repeated on each of its rows.
pub fn write_fatigue_csv(
    path: &Path,
    r: &StudyResults,
    f: &[LocationFatigue],
) -> Result<(), Error> {
    let e = |source: std::io::Error| Error::Output {
        path: path.to_path_buf(),
        source,
    };
    let mut w = csv::Writer::from_path(path).map_err(|x| e(x.into()))?;
    for lf in f {
        let loc = &lf.location;
        for s in &lf.sea_states {
            w.serialize(Row {
                cable: &loc.cable,
                location: loc.location.to_string(),
                line_type: &loc.line_type,
                curve: loc.curve.name.as_deref().unwrap_or(""),
                a_d: loc.curve.a_d,
                m: loc.curve.m,
                area_m2: loc.area_m2,
                sea_state: s.sea_state,
                sea_state_name: r.study.sea_states[s.sea_state]
                    .name
                    .as_deref()
                    .unwrap_or(""),
                seeds: s.seeds,
                duration: s.duration,
                cycles: s.cycles,
                damage: s.damage,
                hours: s.hours,
                sea_state_annual_damage: s.annual_damage,
                annual_damage: lf.annual_damage,
                design_fatigue_factor: lf.design_fatigue_factor,
                life: lf.life,
            })
            .map_err(|x| e(x.into()))?;
        }
    }
    w.flush().map_err(e)
}
