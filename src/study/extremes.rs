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

/// One sea state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeaStateSummary {
    /// Index of the sea state in the study.
    pub index: usize,
    /// The sea state.
    pub sea_state: SeaState,
    /// Per channel, in channel order.
    pub channels: Vec<ChannelSummary>,
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
    let sea_states = def
        .sea_states
        .iter()
        .enumerate()
        .map(|(s, sea_state)| {
            let of_state: Vec<_> = r
                .members
                .iter()
                .filter(|m| m.member.sea_state == s)
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
                .map(|(c, ch)| {
                    let records: Vec<&ChannelStats> = done.iter().map(|m| &m.stats[c]).collect();
                    channel_summary(def, ch, &records, failed)
                })
                .collect();
            SeaStateSummary {
                index: s,
                sea_state: sea_state.clone(),
                channels,
            }
        })
        .collect();
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
    }
}

fn channel_summary(
    def: &StudyDef,
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
    let design = match (&def.design, &ch.line_type, pooled.mean(), mpm) {
        (Some(d), Some(lt), Some(mean), Some(mpm)) if ch.quantity.is_tension() => d
            .capacities
            .get(lt)
            .map(|&cap| DesignCheck::new(cap, d.mean_factor, d.dynamic_factor, mean, mpm)),
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
