//! Extremes across seeds: per sea state and channel, the statistics of the completed
//! members' maxima, their Gumbel fits, and the design check.
//!
//! Every sum here runs over the members in member order, so the same members give the
//! same bits however they were run, sharded or merged.

use super::channel_stats::ChannelStats;
use super::definition::{SeaState, StudyDef};
use super::design::DesignCheck;
use super::gumbel::{Gumbel, GumbelFit};
use super::results::{MemberStatus, StudyResults};
use serde::{Deserialize, Serialize};

/// One channel in one sea state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChannelSummary {
    /// `OWNER.QUANTITY`.
    pub channel: String,
    /// The unit of the values below (`N` or `N m`).
    pub unit: String,
    /// Completed members (seeds) the figures are taken over.
    pub seeds: usize,
    /// Failed members of this sea state, left out.
    pub failed: usize,
    /// Mean of all completed records pooled (the mean tension `T_mean`).
    pub mean: Option<f64>,
    /// Standard deviation of all completed records pooled (about the pooled mean).
    pub std: Option<f64>,
    /// Mean zero-up-crossing period of the pooled records, s.
    pub up_crossing_period: Option<f64>,
    /// Mean of the seed maxima.
    pub max_mean: Option<f64>,
    /// Standard deviation of the seed maxima (divisor `n - 1`).
    pub max_std: Option<f64>,
    /// Largest seed maximum.
    pub max_largest: Option<f64>,
    /// Smallest seed minimum (slack events show here).
    pub min_smallest: Option<f64>,
    /// Maximum-likelihood Gumbel fit of the seed maxima (two or more seeds).
    pub gumbel_mle: Option<Gumbel>,
    /// Method-of-moments Gumbel fit of the seed maxima (two or more seeds).
    pub gumbel_moments: Option<Gumbel>,
    /// Most probable maximum, `mu` of the chosen fit.
    pub mpm: Option<f64>,
    /// The study's quantile of the maxima under the chosen fit.
    pub quantile: Option<f64>,
    /// The design check, for a tension channel whose line type has a capacity.
    pub design: Option<DesignCheck>,
}

/// One sea state in one mooring condition.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeaStateSummary {
    /// Index of the mooring condition in the study (0 without conditions).
    #[serde(default)]
    pub condition: usize,
    /// The condition's name (`intact`, or the broken cable's).
    #[serde(default = "intact_name")]
    pub condition_name: String,
    /// `uls` (intact) or `als` (damaged): whose factors the design check applies.
    #[serde(default = "uls_name")]
    pub limit_state: String,
    /// Index of the sea state in the study.
    pub index: usize,
    /// The sea state.
    pub sea_state: SeaState,
    /// Per channel, in channel order.
    pub channels: Vec<ChannelSummary>,
}

fn intact_name() -> String {
    "intact".into()
}

fn uls_name() -> String {
    "uls".into()
}

/// The largest utilisation of one mooring condition (or of one limit state): where it
/// is, and how large.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Governing {
    /// `uls` or `als`.
    pub limit_state: String,
    /// The condition's index and name.
    pub condition: usize,
    /// The condition's name.
    pub condition_name: String,
    /// The cables broken in it.
    pub broken: Vec<String>,
    /// The sea state where the largest utilisation is (`None`: no channel has a design
    /// check in this condition).
    pub sea_state: Option<usize>,
    /// Its name.
    pub sea_state_name: Option<String>,
    /// The channel (`LINE.QUANTITY`).
    pub channel: Option<String>,
    /// The line (the channel's cable).
    pub line: Option<String>,
    /// The utilisation `T_d / S_C`.
    pub utilisation: Option<f64>,
}

/// The whole study, as `study.json` holds it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StudySummary {
    /// The study hash.
    pub study_hash: String,
    /// The study definition.
    pub study: StudyDef,
    /// Members run.
    pub members: usize,
    /// Members that failed.
    pub failed: usize,
    /// Each failed member, in member order: which it was and what happened.
    pub failed_members: Vec<FailedMember>,
    /// Per sea state.
    pub sea_states: Vec<SeaStateSummary>,
    /// The fatigue of each location (empty without a `[fatigue]` table).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fatigue: Vec<super::fatigue::LocationFatigue>,
    /// Per mooring condition, its largest utilisation (empty without a design check).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub conditions: Vec<Governing>,
    /// The governing condition and line of each limit state run (`uls`, then `als`):
    /// the largest utilisation over its conditions, sea states and channels (empty
    /// without a design check).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub governing: Vec<Governing>,
}

/// A member that blew up, as `study.json` lists it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FailedMember {
    /// The member: its index, sea state, seed number and wave seed.
    #[serde(flatten)]
    pub member: super::members::Member,
    /// What happened, with the cable, node and time.
    pub error: String,
}

/// Reduces a whole study (module documentation).
pub fn summarise(r: &StudyResults) -> StudySummary {
    let def = &r.study;
    let mut sea_states = Vec::new();
    for (c, cond) in r.conditions.iter().enumerate() {
        for (s, sea_state) in def.sea_states.iter().enumerate() {
            if !super::members::runs(def, cond, s) {
                continue;
            }
            let of_state: Vec<_> = r
                .members
                .iter()
                .filter(|m| m.member.sea_state == s && m.member.condition == c)
                .collect();
            let done: Vec<_> = of_state
                .iter()
                .filter(|m| m.status == MemberStatus::Completed)
                .collect();
            let failed = of_state.len() - done.len();
            let channels = r
                .channels
                .iter()
                .enumerate()
                .map(|(k, ch)| {
                    let records: Vec<&ChannelStats> = done.iter().map(|m| &m.stats[k]).collect();
                    channel_summary(def, cond, ch, &records, failed)
                })
                .collect();
            sea_states.push(SeaStateSummary {
                condition: c,
                condition_name: cond.name.clone(),
                limit_state: cond.limit_state().into(),
                index: s,
                sea_state: sea_state.clone(),
                channels,
            });
        }
    }
    let (conditions, governing) = governing(r, &sea_states);
    StudySummary {
        study_hash: r.study_hash.clone(),
        study: def.clone(),
        members: r.members.len(),
        failed: r
            .members
            .iter()
            .filter(|m| m.status != MemberStatus::Completed)
            .count(),
        failed_members: r
            .members
            .iter()
            .filter_map(|m| match &m.status {
                MemberStatus::Completed => None,
                MemberStatus::Failed { message } => Some(FailedMember {
                    member: m.member,
                    error: message.clone(),
                }),
            })
            .collect(),
        sea_states,
        fatigue: super::fatigue::summarise(r),
        conditions,
        governing,
    }
}

/// Per condition its largest utilisation, and per limit state the governing one (the
/// first of equal ones in condition, sea state and channel order). Empty without a
/// design check.
fn governing(r: &StudyResults, sea_states: &[SeaStateSummary]) -> (Vec<Governing>, Vec<Governing>) {
    if r.study.design.is_none() {
        return (Vec::new(), Vec::new());
    }
    let per_condition: Vec<Governing> = r
        .conditions
        .iter()
        .enumerate()
        .map(|(c, cond)| {
            let mut g = Governing {
                limit_state: cond.limit_state().into(),
                condition: c,
                condition_name: cond.name.clone(),
                broken: cond.broken.clone(),
                sea_state: None,
                sea_state_name: None,
                channel: None,
                line: None,
                utilisation: None,
            };
            for ss in sea_states.iter().filter(|s| s.condition == c) {
                for (k, ch) in ss.channels.iter().enumerate() {
                    let Some(u) = ch.design.map(|d| d.utilisation) else {
                        continue;
                    };
                    if g.utilisation.is_none_or(|x| u > x) {
                        g.sea_state = Some(ss.index);
                        g.sea_state_name = ss.sea_state.name.clone();
                        g.channel = Some(ch.channel.clone());
                        g.line = Some(r.channels[k].owner.clone());
                        g.utilisation = Some(u);
                    }
                }
            }
            g
        })
        .collect();
    let mut by_state: Vec<Governing> = Vec::new();
    for state in ["uls", "als"] {
        let best = per_condition
            .iter()
            .filter(|g| g.limit_state == state)
            .fold(None::<&Governing>, |best, g| match (best, g.utilisation) {
                (None, _) => Some(g),
                (Some(b), Some(u)) if b.utilisation.is_none_or(|x| u > x) => Some(g),
                (b, _) => b,
            });
        if let Some(b) = best {
            by_state.push(b.clone());
        }
    }
    (per_condition, by_state)
}

fn channel_summary(
    def: &StudyDef,
    cond: &super::definition::Condition,
    ch: &super::channels::Channel,
    records: &[&ChannelStats],
    failed: usize,
) -> ChannelSummary {
    let mut pooled = ChannelStats::new(def.transient);
    for s in records {
        pooled.pool(s);
    }
    let maxima: Vec<f64> = records
        .iter()
        .filter_map(|s| s.max().map(|e| e.value))
        .collect();
    let n = maxima.len();
    let max_mean = (n > 0).then(|| maxima.iter().sum::<f64>() / n as f64);
    let max_std = max_mean
        .filter(|_| n > 1)
        .map(|m| (maxima.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1) as f64).sqrt());
    let gumbel_mle = Gumbel::fit_mle(&maxima).ok();
    let gumbel_moments = Gumbel::fit_moments(&maxima).ok();
    let chosen = match def.fit {
        GumbelFit::Mle => gumbel_mle,
        GumbelFit::Moments => gumbel_moments,
    };
    let mpm = chosen.map(|g| g.most_probable());
    // A broken line's own channels are not checked in its damaged condition.
    let broken = cond.broken.contains(&ch.owner);
    let design = match (&def.design, &ch.line_type, pooled.mean(), mpm) {
        (Some(d), Some(lt), Some(mean), Some(mpm)) if ch.quantity.is_tension() && !broken => {
            let (gm, gd) = if cond.is_damaged() {
                d.accidental.unwrap_or((d.mean_factor, d.dynamic_factor))
            } else {
                (d.mean_factor, d.dynamic_factor)
            };
            d.capacities
                .get(lt)
                .map(|&cap| DesignCheck::new(cap, gm, gd, mean, mpm))
        }
        _ => None,
    };
    ChannelSummary {
        channel: ch.name(),
        unit: ch.quantity.unit().to_string(),
        seeds: records.len(),
        failed,
        mean: pooled.mean(),
        std: pooled.std(),
        up_crossing_period: pooled.mean_up_crossing_period(),
        max_mean,
        max_std,
        max_largest: maxima.iter().copied().reduce(f64::max),
        min_smallest: records
            .iter()
            .filter_map(|s| s.min().map(|e| e.value))
            .reduce(f64::min),
        gumbel_mle,
        gumbel_moments,
        mpm,
        quantile: chosen.map(|g| g.quantile(def.quantile)),
        design,
    }
}
