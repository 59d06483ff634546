//! Running a study's members packed: a batch of members in one model and one run
//! (`sim::pack`), on the GPU (all members in one layout, one dispatch per submission
//! on the fused path) or on whichever backend `auto` picks for the packed model.
//!
//! Each member of a batch is the scenario of [`StudyRunner::member_toml`], validated
//! alone, then packed with the others under the prefix `m<index>`; its cables keep its
//! own sea (its own components and cache schedule), so its statistics do not depend on
//! which members share its batch: any batch size gives the same files.
//!
//! A blow-up stops a packed run. The member it names (the error names the cable,
//! `m<index>/name`) is then run alone, as a batch of one, which records it as failed
//! with its statistics up to the failure as the CPU path does; the rest of the batch
//! runs again without it. The progress counts each member's simulated time once
//! ([`Counted`]): what a member steps again in those runs is not counted twice.

use super::{is_blow_up, StudyRunner};
use crate::error::Error;
use crate::options::{Backend, Overrides, Precision};
use crate::sim::pack::{pack, Packed};
use crate::sim::Simulation;
use crate::study::members::Member;
use crate::study::results::{MemberResult, MemberStatus};
use crate::study::ChannelStats;
use std::sync::atomic::{AtomicBool, Ordering};

/// How a study runs its members packed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PackedRun {
    /// The backend of the packed runs (`Gpu`, or `Auto` to let the packed model
    /// choose; `Cpu` steps the packed model on the CPU, the GPU's reference).
    pub backend: Backend,
    /// GPU precision (`None`: the backend's default).
    pub precision: Option<Precision>,
    /// Members per packed run (`None`: all of them in one).
    pub batch: Option<usize>,
}

/// How a packed batch ended.
enum BatchEnd {
    /// Every member's record, in batch order (`None`: stopped from outside).
    Done(Option<Vec<MemberResult>>),
    /// Member `.0` (its position in the batch) blew up.
    BlewUp(usize),
}

/// How far each member has been counted in the progress (simulated time, s), so that a
/// member stepped again (alone after a blow-up, or in its batch run again without the
/// member that blew up) adds only the time past what it had reached: the progress of a
/// shard ends at its members times the duration, never past it.
#[derive(Default)]
struct Counted(std::collections::HashMap<usize, f64>);

impl Counted {
    /// Every member of `batch` has reached time `t`: tells `progress` what that adds.
    fn reach(&mut self, batch: &[Member], t: f64, progress: &(dyn Fn(f64) + Sync)) {
        let mut add = 0.0;
        for m in batch {
            let c = self.0.entry(m.index).or_insert(0.0);
            if t > *c {
                add += t - *c;
                *c = t;
            }
        }
        if add > 0.0 {
            progress(add);
        }
    }
}

/// The member prefix in a packed scenario.
fn prefix(m: &Member) -> String {
    format!("m{}", m.index)
}

impl StudyRunner {
    /// Runs `members` in batches of packed runs (module documentation); arguments and
    /// result as [`StudyRunner::run`].
    pub fn run_packed(
        &self,
        members: &[Member],
        how: &PackedRun,
        stop: &AtomicBool,
        progress: &(dyn Fn(f64) + Sync),
        on_done: &(dyn Fn(&MemberResult) -> Result<(), Error> + Sync),
    ) -> Result<Vec<MemberResult>, Error> {
        let size = how.batch.unwrap_or(members.len()).max(1);
        let mut out = Vec::with_capacity(members.len());
        let mut counted = Counted::default();
        let mut reached = |b: &[Member], t: f64| counted.reach(b, t, progress);
        for batch in members.chunks(size) {
            let mut todo: Vec<Member> = batch.to_vec();
            let mut done: Vec<MemberResult> = Vec::new();
            loop {
                if stop.load(Ordering::Relaxed) {
                    return Ok(out);
                }
                match self.run_batch(&todo, how, stop, &mut reached)? {
                    BatchEnd::Done(None) => return Ok(out),
                    BatchEnd::Done(Some(rs)) => {
                        done.extend(rs);
                        break;
                    }
                    BatchEnd::BlewUp(k) => {
                        let m = todo.remove(k);
                        log::info!(
                            "member {} blew up in a packed run: run alone, the others again",
                            m.index
                        );
                        match self.run_batch(&[m], how, stop, &mut reached)? {
                            BatchEnd::Done(Some(rs)) => done.extend(rs),
                            BatchEnd::Done(None) => return Ok(out),
                            BatchEnd::BlewUp(_) => {
                                unreachable!("a batch of one records its blow-up")
                            }
                        }
                        if todo.is_empty() {
                            break;
                        }
                    }
                }
            }
            done.sort_by_key(|r| r.member.index);
            for r in &done {
                on_done(r)?;
            }
            out.extend(done);
        }
        Ok(out)
    }

    /// The packed scenario of `batch`.
    fn pack_batch(&self, batch: &[Member]) -> Result<Packed, Error> {
        let scenarios = batch
            .iter()
            .map(|m| {
                let sc = self.member_scenario(m)?;
                Ok((prefix(m), sc))
            })
            .collect::<Result<Vec<_>, Error>>()?;
        pack(&scenarios)
    }

    /// Runs one batch packed to the study's duration, streaming every member's
    /// channels at each output time; `reached(batch, t)` is told each time `t` (s) its
    /// members reach (the duration for a member that failed: its share is done).
    fn run_batch(
        &self,
        batch: &[Member],
        how: &PackedRun,
        stop: &AtomicBool,
        reached: &mut dyn FnMut(&[Member], f64),
    ) -> Result<BatchEnd, Error> {
        let def = &self.plan.def;
        let packed = self.pack_batch(batch)?;
        let overrides = Overrides {
            backend: Some(how.backend),
            precision: how.precision,
            duration: Some(def.duration),
            ..Overrides::default()
        };
        let mut sim = Simulation::new(packed.scenario, &overrides)?;
        let interval = sim.scenario().sim.output_interval;
        let mut stats: Vec<Vec<ChannelStats>> =
            batch.iter().map(|_| self.plan.new_stats()).collect();
        let mut fatigue: Vec<Vec<crate::fatigue::DamageCounter>> =
            batch.iter().map(|_| self.plan.new_fatigue()).collect();
        let mut body_index: Vec<Option<Vec<Option<usize>>>> = vec![None; batch.len()];
        let outputs = (def.duration / interval - 1e-9).ceil().max(1.0) as u64;
        let mut failed: Option<String> = None;
        for k in 0..=outputs {
            if k > 0 {
                if stop.load(Ordering::Relaxed) {
                    return Ok(BatchEnd::Done(None));
                }
                let target = (k as f64 * interval).min(def.duration);
                if let Err(e) = sim.advance_to(target) {
                    if !is_blow_up(&e) {
                        return Err(e);
                    }
                    if batch.len() > 1 {
                        return Ok(BatchEnd::BlewUp(blown_member(&e, &packed.members)?));
                    }
                    let e = unprefixed(e, &packed.members[0].prefix);
                    failed = Some(self.failure_message(&batch[0], &e));
                    reached(batch, def.duration);
                    break;
                }
                reached(batch, target);
            }
            let snap = sim.snapshot()?;
            for (j, pm) in packed.members.iter().enumerate() {
                self.record(
                    &mut stats[j],
                    &mut fatigue[j],
                    &snap,
                    pm.cables.clone(),
                    Some(&pm.prefix),
                    &mut body_index[j],
                );
            }
        }
        Ok(BatchEnd::Done(Some(
            batch
                .iter()
                .zip(stats)
                .zip(fatigue)
                .map(|((m, stats), fatigue)| MemberResult {
                    member: *m,
                    status: match &failed {
                        Some(message) => MemberStatus::Failed {
                            message: message.clone(),
                        },
                        None => MemberStatus::Completed,
                    },
                    stats,
                    fatigue: fatigue.into_iter().map(|c| c.finish()).collect(),
                })
                .collect(),
        )))
    }
}

/// The position in the batch of the member whose cable blow-up `e` names.
fn blown_member(e: &Error, members: &[crate::sim::pack::PackedMember]) -> Result<usize, Error> {
    let cable = match e {
        Error::Diverged { cable, .. } | Error::SingularFrame { cable, .. } => cable,
        _ => unreachable!("a blow-up names its cable"),
    };
    members
        .iter()
        .position(|m| cable.starts_with(&format!("{}/", m.prefix)))
        .ok_or_else(|| {
            Error::Model(format!(
                "a packed run blew up in cable '{cable}', of no member"
            ))
        })
}

/// Blow-up `e` with the member prefix taken off its cable name, as the member run
/// alone names it.
fn unprefixed(e: Error, prefix: &str) -> Error {
    let strip = |c: String| match c.strip_prefix(&format!("{prefix}/")) {
        Some(s) => s.to_string(),
        None => c,
    };
    match e {
        Error::Diverged {
            cable,
            node,
            time,
            what,
        } => Error::Diverged {
            cable: strip(cable),
            node,
            time,
            what,
        },
        Error::SingularFrame {
            frame,
            cable,
            element,
            time,
            reason,
        } => Error::SingularFrame {
            frame,
            cable: strip(cable),
            element,
            time,
            reason,
        },
        e => e,
    }
}
