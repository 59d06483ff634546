//! Monte Carlo sea-state studies: what to run, and how the members' records are reduced
//! to extremes and a design check. The running of members is the runner's; this module
//! holds everything around it, so that results are the same on any number of threads,
//! shards and machines.
//!
//! The data flow, in order:
//! 1. [`StudyFile::load`] reads the `[study]` table ([`definition`]) and the base scenario
//!    text; [`StudyPlan::new`] resolves the channels against the base model
//!    ([`channels`]), enumerates the members with their wave seeds ([`members`]) and takes
//!    the study hash ([`hash`]).
//! 2. The runner ([`run`], [`StudyRunner`]) runs the members of its shard ([`ShardSpec`], `K/N`), each with its sea
//!    state ([`StudyPlan::sea_state_of`]) and wave seed; at every output time a
//!    [`Sampler`] pushes each channel's value into a [`ChannelStats`] from
//!    [`StudyPlan::new_stats`] (fixed memory, [`channel_stats`]); each finished member becomes a [`MemberResult`], and the
//!    shard a [`ShardResult`] written as `shard.json` ([`results`]). Each member is
//!    written to the run directory as it finishes ([`run_dir`]), so an interrupted
//!    run keeps what it finished and resumes from there.
//! 3. [`merge`] checks that the shard files are the complete set of one study and puts the
//!    members back in member order; [`summarise`] fits the seed maxima of each sea state
//!    and channel ([`gumbel`]) and applies the design check ([`design`]); [`tables`] writes
//!    `members.csv`, `study.csv` and `study.json`.
//!
//! Every reduction runs over members in member order, whatever order they were run or
//! merged in, so a merged study equals a one-machine study bit for bit.

pub mod channel_stats;
pub mod channels;
pub mod definition;
pub mod design;
pub mod extremes;
pub mod fatigue;
pub mod gumbel;
pub mod hash;
pub mod members;
pub mod results;
pub mod run;
pub mod run_dir;
pub mod sampling;
pub mod tables;

pub use channel_stats::{ChannelStats, Extreme};
pub use channels::{BodyComponent, Channel, ModelChannels, Quantity};
pub use definition::{Condition, DesignInputs, SeaState, StudyDef, StudyFile};
pub use extremes::{
    summarise, ChannelSummary, FailedMember, Governing, SeaStateSummary, StudySummary,
};
pub use gumbel::{Gumbel, GumbelFit};
pub use members::{Member, ShardSpec};
pub use results::{merge, MemberResult, MemberStatus, ShardResult, StudyResults};
pub use run::{PackedRun, StudyRunner};
pub use run_dir::{RunDir, RunState, RunStatus};
pub use sampling::{BodySnapshot, CableSnapshot, Sampler};

use crate::error::Error;
use crate::scenario::err;
use std::path::Path;

/// A study ready to run: the definition, its channels resolved against the base model,
/// its members and its hash.
#[derive(Clone, Debug)]
pub struct StudyPlan {
    /// The definition.
    pub def: StudyDef,
    /// The channels every member reduces, in table order.
    pub channels: Vec<Channel>,
    /// Every member, in member order.
    pub members: Vec<Member>,
    /// The study hash (hex SHA-256 of the canonical definition and the base scenario).
    pub hash: String,
    /// The fatigue locations every member counts (the base scenario's `[fatigue]`),
    /// empty without one.
    pub fatigue: Vec<crate::fatigue::FatigueLocation>,
    /// The mooring conditions, in condition order (the intact mooring alone for a
    /// study without `[study.conditions]`).
    pub conditions: Vec<Condition>,
}

impl StudyPlan {
    /// Plans a loaded study against its base model (the cables and bodies it offers).
    pub fn new(file: &StudyFile, model: &ModelChannels) -> Result<StudyPlan, Error> {
        Self::from_parts(file.def.clone(), &file.scenario_text, &file.path, model)
    }

    /// Plans a study from its parts; `path` names the study file in messages.
    pub fn from_parts(
        def: StudyDef,
        scenario_text: &str,
        path: &Path,
        model: &ModelChannels,
    ) -> Result<StudyPlan, Error> {
        let channels = channels::resolve(path, "study.channels", &def.channels, model)?;
        if let Some(d) = &def.design {
            for name in d.capacities.keys() {
                if !model.cables.iter().any(|c| &c.line_type == name) {
                    return Err(err(
                        path,
                        format!("study.design.capacities.{name}"),
                        format!("no cable of the base scenario has line type \"{name}\""),
                    ));
                }
            }
        }
        let conditions = expand_conditions(&def, path, model)?;
        Ok(StudyPlan {
            members: members::members(&def, &conditions),
            hash: hash::study_hash(&def, scenario_text),
            channels,
            def,
            fatigue: Vec::new(),
            conditions,
        })
    }

    /// Adds the fatigue locations of the base scenario's `[fatigue]` table (`spec`);
    /// a study with a scatter diagram (`[study.fatigue]`) needs one. `path` names the
    /// study file in messages.
    pub fn with_fatigue(
        mut self,
        spec: Option<&crate::fatigue::FatigueSpec>,
        path: &Path,
    ) -> Result<StudyPlan, Error> {
        match spec {
            Some(s) => self.fatigue = s.locations.clone(),
            None if self.def.fatigue.is_some() => {
                return Err(err(
                    path,
                    "study.fatigue",
                    "the base scenario has no [fatigue] table: give the T-N curve and \
                     nominal area of its line types there ([fatigue.line_types])",
                ))
            }
            None => {}
        }
        Ok(self)
    }

    /// Empty fatigue counters for one member: one per fatigue location, in order.
    pub fn new_fatigue(&self) -> Vec<crate::fatigue::DamageCounter> {
        self.fatigue
            .iter()
            .map(|l| crate::fatigue::DamageCounter::new(l, self.def.transient))
            .collect()
    }

    /// The members a shard runs (checked against the study's size; `source` names where
    /// the shard spec came from).
    pub fn shard_members(&self, shard: ShardSpec, source: &Path) -> Result<&[Member], Error> {
        shard.check(self.members.len(), source)?;
        Ok(&self.members[shard.range(self.members.len())])
    }

    /// The sea state a member runs.
    pub fn sea_state_of(&self, m: &Member) -> &SeaState {
        &self.def.sea_states[m.sea_state]
    }

    /// Empty statistics for one member: one per channel, in channel order.
    pub fn new_stats(&self) -> Vec<ChannelStats> {
        vec![ChannelStats::new(self.def.transient); self.channels.len()]
    }

    /// A shard's result, from its finished members (in any order).
    pub fn shard_result(&self, shard: ShardSpec, mut members: Vec<MemberResult>) -> ShardResult {
        members.sort_by_key(|m| m.member.index);
        ShardResult {
            format: results::SHARD_FORMAT,
            study_hash: self.hash.clone(),
            shard,
            study: self.def.clone(),
            channels: self.channels.clone(),
            fatigue: self.fatigue.clone(),
            conditions: if self.def.conditions.is_some() {
                self.conditions.clone()
            } else {
                Vec::new()
            },
            members,
        }
    }

    /// The condition member `m` runs.
    pub fn condition_of(&self, m: &Member) -> &Condition {
        &self.conditions[m.condition]
    }
}

/// The mooring conditions of `def` against the base model: the intact one (unless
/// `intact = false`), then one per broken cable, in the order given (`"each"`: model
/// order). A cable the base scenario lacks is an error naming its key.
fn expand_conditions(
    def: &StudyDef,
    path: &Path,
    model: &ModelChannels,
) -> Result<Vec<Condition>, Error> {
    use definition::Broken;
    let Some(spec) = &def.conditions else {
        return Ok(vec![Condition::intact()]);
    };
    let mut out = Vec::new();
    if spec.intact {
        out.push(Condition::intact());
    }
    let names: Vec<String> = match &spec.broken {
        Broken::Each => model.cables.iter().map(|c| c.name.clone()).collect(),
        Broken::Lines(l) => {
            for (i, n) in l.iter().enumerate() {
                if !model.cables.iter().any(|c| &c.name == n) {
                    return Err(err(
                        path,
                        format!("study.conditions.broken[{i}]"),
                        format!(
                            "no cable named \"{n}\" in the base scenario (its cables: {})",
                            model
                                .cables
                                .iter()
                                .map(|c| c.name.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ));
                }
            }
            l.clone()
        }
    };
    for n in names {
        out.push(Condition {
            name: n.clone(),
            broken: vec![n],
        });
    }
    if !spec.intact && def.fatigue.is_some() {
        return Err(err(
            path,
            "study.conditions.intact",
            "the fatigue scatter diagram ([study.fatigue]) runs in the intact condition: \
             keep intact = true",
        ));
    }
    if out.iter().any(|c| c.is_damaged()) && def.sea_states.iter().all(|s| s.in_scatter()) {
        return Err(err(
            path,
            "study.conditions.broken",
            "a damaged condition runs the sea states outside the fatigue scatter diagram, \
             and every sea state is in it: add an extreme sea state (no probability or hours)",
        ));
    }
    Ok(out)
}
