//! Running a study's members on the CPU: each member is the base scenario with its own
//! sea state, stepped through the library's [`Simulation`], its channels streamed into
//! [`ChannelStats`](super::ChannelStats) at every output time and nothing else kept.
//!
//! A member's scenario is the base scenario's text with two things replaced, then
//! validated as any scenario is (so bodies that move in the waves, route files and every
//! check behave as in a single run):
//! - `[environment.waves]`: the trains become one long-crested JONSWAP train from the
//!   sea state's `Hs`, `Tp`, peak factor and heading, with the member's wave seed as
//!   `seed`; the base table's stretching, ramp and cache tolerance are kept;
//! - `[environment] current`: a uniform current of the sea state's speed and heading
//!   (a `current_profile` is removed); currents given per cable are kept.
//!
//! Members run in parallel over rayon's threads. Each member's statistics depend only on
//! the member, and the results are returned in member order, so any thread count gives
//! the same numbers.

mod packed;
pub(crate) mod sea_check;

pub use packed::PackedRun;

use super::channels::ModelChannels;
use super::definition::StudyFile;
use super::members::Member;
use super::results::{MemberResult, MemberStatus};
use super::sampling::{BodySnapshot, CableSnapshot, Sampler};
use super::StudyPlan;
use crate::error::Error;
use crate::options::{Backend, Overrides};
use crate::scenario::{err, Scenario};
use crate::sim::pack::packed_name;
use crate::sim::{Simulation, Snapshot};
use rayon::prelude::*;
use std::ops::Range;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// A planned study with its base scenario, ready to run members.
#[derive(Clone, Debug)]
pub struct StudyRunner {
    plan: StudyPlan,
    /// The base scenario as a TOML table, without any `[study]` table.
    base: toml::Table,
    scenario_path: PathBuf,
    /// The study file (the base scenario's own path when the `[study]` table is in it).
    study_path: PathBuf,
    model: ModelChannels,
    sampler: Sampler,
}

/// Breaks cable `name` of scenario `doc` at time `t` (s): the end held by a body (its
/// `end` when both are), else its `end`, fails at `t` (`fail_time`; 0: from the first
/// step). A cable that is not a `[[cables]]` entry is left to the plan's check
/// ([`StudyRunner::check_conditions`]).
fn break_cable(doc: &mut toml::Table, name: &str, t: f64) {
    let Some(toml::Value::Array(cables)) = doc.get_mut("cables") else {
        return;
    };
    let Some(cable) = cables
        .iter_mut()
        .filter_map(|c| c.as_table_mut())
        .find(|c| c.get("name").and_then(|n| n.as_str()) == Some(name))
    else {
        return;
    };
    let on_body = |k: &str| {
        cable
            .get(k)
            .and_then(|e| e.as_table())
            .is_some_and(|e| e.contains_key("body"))
    };
    let which = if on_body("end") || !on_body("start") {
        "end"
    } else {
        "start"
    };
    if let Some(end) = cable.get_mut(which).and_then(|e| e.as_table_mut()) {
        end.insert("fail_time".into(), toml::Value::Float(t));
    }
}

/// Whether an error is a member's own blow-up (the member fails, the study goes on)
/// rather than a problem of the study's input (the study stops).
pub(crate) fn is_blow_up(e: &Error) -> bool {
    matches!(e, Error::Diverged { .. } | Error::SingularFrame { .. })
}

impl StudyRunner {
    /// Plans a loaded study against its base scenario.
    pub fn new(file: &StudyFile) -> Result<StudyRunner, Error> {
        let mut base: toml::Table = file
            .scenario_text
            .parse()
            .map_err(|e| err(&file.scenario_path, "(file)", format!("{e}")))?;
        base.remove("study");
        let scenario = Scenario::parse(
            &toml::to_string(&base).expect("a TOML table"),
            &file.scenario_path,
        )?;
        let mut model = ModelChannels::from_model(&scenario.model);
        if let Some(toml::Value::Array(bodies)) = base.get("bodies") {
            for b in bodies {
                let Some(name) = b.get("name").and_then(|n| n.as_str()) else {
                    continue;
                };
                model.bodies.push(name.to_string());
                let reference = b
                    .get("reference")
                    .and_then(|r| r.as_array())
                    .map(|a| {
                        let mut x = [0.0; 3];
                        for (k, v) in a.iter().take(3).enumerate() {
                            x[k] = v
                                .as_float()
                                .or(v.as_integer().map(|i| i as f64))
                                .unwrap_or(0.0);
                        }
                        x
                    })
                    .unwrap_or_default();
                model.body_references.push(reference);
                model
                    .free_bodies
                    .push(b.get("motion").and_then(|m| m.as_str()) == Some("free"));
            }
        }
        let plan =
            StudyPlan::new(file, &model)?.with_fatigue(scenario.fatigue.as_ref(), &file.path)?;
        let sampler = Sampler::new(&plan.channels, &model);
        let runner = StudyRunner {
            plan,
            base,
            scenario_path: file.scenario_path.clone(),
            study_path: file.path.clone(),
            model,
            sampler,
        };
        runner.check_sea_states()?;
        runner.check_conditions()?;
        Ok(runner)
    }

    /// Checks that each damaged condition's cable is a `[[cables]]` entry of the base
    /// scenario, and validates each damaged condition's first member (an end that cannot
    /// fail is named by the study's key).
    fn check_conditions(&self) -> Result<(), Error> {
        let listed: Vec<&str> = match self.base.get("cables") {
            Some(toml::Value::Array(a)) => a
                .iter()
                .filter_map(|c| c.get("name").and_then(|n| n.as_str()))
                .collect(),
            _ => Vec::new(),
        };
        for (c, cond) in self.plan.conditions.iter().enumerate() {
            if !cond.is_damaged() {
                continue;
            }
            for name in &cond.broken {
                if !listed.contains(&name.as_str()) {
                    return Err(err(
                        &self.study_path,
                        "study.conditions.broken",
                        format!(
                            "cable \"{name}\" is not a [[cables]] entry of the base scenario \
                             (cables of arrays and nets cannot be broken by a study yet)"
                        ),
                    ));
                }
            }
            let Some(m) = self.plan.members.iter().find(|m| m.condition == c) else {
                continue;
            };
            let (sc, _) = crate::scenario::collect_warnings(|| {
                Scenario::parse(&self.member_toml(m), &self.scenario_path)
            });
            if let Err(e) = sc {
                return Err(err(
                    &self.study_path,
                    "study.conditions.broken",
                    format!(
                        "condition \"{}\" (cable \"{}\" broken): {e}",
                        cond.name,
                        cond.broken.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The plan: definition, channels, members, hash.
    pub fn plan(&self) -> &StudyPlan {
        &self.plan
    }

    /// The work of `members` members of this study, before any runs: each member's
    /// node-steps (the first member's model and step plan at the study's duration;
    /// every member has the same model and step) and the wall time estimated for them
    /// on the CPU path, members in parallel on this process's threads
    /// ([`crate::sim::estimate`]). A member beyond the work budget is refused here, as
    /// its run would be.
    pub fn estimate(&self, members: usize) -> Result<crate::sim::estimate::Estimate, Error> {
        use crate::options::SolverOptions;
        let Some(first) = self.plan.members.first() else {
            return Ok(crate::sim::estimate::Estimate {
                node_steps: 0.0,
                seconds: 0.0,
                how: String::new(),
            });
        };
        let sc = self.member_scenario(first)?;
        let (lay, _) = crate::model::Layout::build(&sc.model)?;
        let opts = SolverOptions {
            scheme: sc.sim.scheme,
            formulation: sc.sim.formulation,
            baumgarte: sc.sim.baumgarte,
            ..SolverOptions::default()
        };
        let plan = crate::sim::plan_steps(&sc, &lay, &opts, self.plan.def.duration, sc.sim.dt)?;
        let waves = crate::sim::budget::in_waves(&sc);
        let one = crate::sim::estimate::lumped(
            &lay,
            &opts,
            plan.total_steps,
            waves,
            crate::sim::estimate::Path::Cpu(1),
        );
        let threads = rayon::current_num_threads().clamp(1, members.max(1));
        let seconds = one.seconds * members as f64 / threads as f64;
        Ok(crate::sim::estimate::Estimate {
            node_steps: one.node_steps * members as f64,
            seconds,
            how: format!(
                "on the CPU path ({members} members of {:.3e} node-steps, {threads} at a time; {})",
                one.node_steps,
                one.how.trim_start_matches("on the CPU path ")
            ),
        })
    }

    /// The scenario text member `m` runs (module documentation): writing it to a file
    /// beside the base scenario and running it alone reproduces the member.
    pub fn member_toml(&self, m: &Member) -> String {
        let ss = self.plan.sea_state_of(m);
        let mut doc = self.base.clone();
        let env = doc
            .entry("environment")
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .expect("[environment] is a table in a valid scenario");
        env.remove("current_profile");
        let h = ss.current_heading.to_radians();
        env.insert(
            "current".into(),
            toml::Value::Array(
                [ss.current_speed * h.cos(), ss.current_speed * h.sin(), 0.0]
                    .into_iter()
                    .map(toml::Value::Float)
                    .collect(),
            ),
        );
        let waves = env
            .entry("waves")
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .expect("[environment.waves] is a table in a valid scenario");
        // TOML integers are signed 64-bit: wave seeds are below 2^63 (members.rs).
        waves.insert("seed".into(), toml::Value::Integer(m.wave_seed as i64));
        let mut train = toml::Table::new();
        train.insert("type".into(), "jonswap".into());
        train.insert("hs".into(), ss.hs.into());
        train.insert("tp".into(), ss.tp.into());
        if let Some(g) = ss.gamma {
            train.insert("gamma".into(), g.into());
        }
        train.insert("direction".into(), ss.heading.into());
        waves.insert(
            "trains".into(),
            toml::Value::Array(vec![toml::Value::Table(train)]),
        );
        let fail_time = self
            .plan
            .def
            .conditions
            .as_ref()
            .and_then(|c| c.fail_time)
            .unwrap_or(0.0);
        for cable in &self.plan.condition_of(m).broken {
            break_cable(&mut doc, cable, fail_time);
        }
        toml::to_string(&doc).expect("a TOML table")
    }

    /// Runs member `m` to the study's duration, streaming its channels at every output
    /// time; `progress` is told each stretch of simulated time done (s). Returns `None`
    /// when `stop` was raised before the member finished (its partial record is
    /// dropped), a failed member when it blew up, and an error when its scenario does
    /// not build (a problem of the study's input, not of the member).
    pub fn run_member(
        &self,
        m: &Member,
        stop: &AtomicBool,
        progress: &(dyn Fn(f64) + Sync),
    ) -> Result<Option<MemberResult>, Error> {
        let def = &self.plan.def;
        let overrides = Overrides {
            backend: Some(Backend::Cpu),
            duration: Some(def.duration),
            ..Overrides::default()
        };
        let mut sim = Simulation::new(self.member_scenario(m)?, &overrides)?;
        let interval = sim.scenario().sim.output_interval;
        let mut stats = self.plan.new_stats();
        let mut fatigue = self.plan.new_fatigue();
        let mut body_index: Option<Vec<Option<usize>>> = None;
        let outputs = (def.duration / interval - 1e-9).ceil().max(1.0) as u64;
        let mut done = 0.0;
        let mut status = MemberStatus::Completed;
        for k in 0..=outputs {
            if k > 0 {
                if stop.load(Ordering::Relaxed) {
                    return Ok(None);
                }
                let target = (k as f64 * interval).min(def.duration);
                if let Err(e) = sim.advance_to(target) {
                    if !is_blow_up(&e) {
                        return Err(e);
                    }
                    status = MemberStatus::Failed {
                        message: self.failure_message(m, &e),
                    };
                    progress(def.duration - done);
                    break;
                }
                progress(target - done);
                done = target;
            }
            let snap = sim.snapshot()?;
            let n = snap.cables.len();
            self.record(&mut stats, &mut fatigue, &snap, 0..n, None, &mut body_index);
        }
        Ok(Some(MemberResult {
            member: *m,
            status,
            stats,
            fatigue: fatigue.into_iter().map(|c| c.finish()).collect(),
        }))
    }

    /// The message of member `m`'s blow-up `e`: the member, its sea state and seeds, and
    /// the error (which names the cable, node and time).
    pub(crate) fn failure_message(&self, m: &Member, e: &Error) -> String {
        let ss = self.plan.sea_state_of(m);
        let condition = match self.plan.def.conditions {
            Some(_) => format!("condition \"{}\", ", self.plan.condition_of(m).name),
            None => String::new(),
        };
        format!(
            "member {} ({condition}sea state {}{}, seed {}, wave seed {}): {e}",
            m.index,
            m.sea_state,
            ss.name
                .as_deref()
                .map(|n| format!(" \"{n}\""))
                .unwrap_or_default(),
            m.seed,
            m.wave_seed
        )
    }

    /// Records one member's channels from `snap` into `stats`, and its fatigue
    /// locations' values into `fatigue` (one counter per location): the member's cables are
    /// `cables` (in the base scenario's order), its bodies are named `PREFIX/name`
    /// when `prefix` is given (a packed run, `sim::pack`), else by their own names;
    /// `body_index` caches where they are in the snapshots.
    pub(crate) fn record(
        &self,
        stats: &mut [crate::study::ChannelStats],
        fatigue: &mut [crate::fatigue::DamageCounter],
        snap: &Snapshot,
        cables: Range<usize>,
        prefix: Option<&str>,
        body_index: &mut Option<Vec<Option<usize>>>,
    ) {
        let cables: Vec<CableSnapshot> = snap.cables[cables]
            .iter()
            .map(|c| CableSnapshot {
                tensions: &c.tensions,
                start_force: c.end_forces.start,
                end_force: c.end_forces.end,
            })
            .collect();
        // Bodies no cable end attaches to carry no load and are not in snapshots.
        let index = body_index.get_or_insert_with(|| {
            self.model
                .bodies
                .iter()
                .map(|n| {
                    let name = match prefix {
                        Some(p) => packed_name(p, n),
                        None => n.clone(),
                    };
                    snap.bodies.iter().position(|b| b.name == name)
                })
                .collect()
        });
        let bodies: Vec<BodySnapshot> = index
            .iter()
            .map(|i| match i {
                Some(i) => BodySnapshot {
                    force: snap.bodies[*i].force,
                    moment: snap.bodies[*i].moment,
                    position: Some(snap.bodies[*i].position),
                },
                None => BodySnapshot::default(),
            })
            .collect();
        self.sampler.record(stats, snap.time, &cables, &bodies);
        for (loc, counter) in self.plan.fatigue.iter().zip(fatigue) {
            let c = &cables[loc.cable_index];
            if let Some(x) = loc.value(c.tensions, c.start_force, c.end_force) {
                counter.push(snap.time, x);
            }
        }
    }

    /// Runs `members` in parallel on rayon's threads; `on_done` is called with each
    /// finished member as it finishes (to write it at once), `progress` as in
    /// [`StudyRunner::run_member`]. Returns the finished members in member order;
    /// members not started or not finished when `stop` was raised are missing. An
    /// input error of one member raises `stop` and is returned.
    pub fn run(
        &self,
        members: &[Member],
        stop: &AtomicBool,
        progress: &(dyn Fn(f64) + Sync),
        on_done: &(dyn Fn(&MemberResult) -> Result<(), Error> + Sync),
    ) -> Result<Vec<MemberResult>, Error> {
        let results: Vec<Result<Option<MemberResult>, Error>> = members
            .par_iter()
            .map(|m| {
                if stop.load(Ordering::Relaxed) {
                    return Ok(None);
                }
                let r = self.run_member(m, stop, progress).and_then(|r| {
                    if let Some(r) = &r {
                        on_done(r)?;
                    }
                    Ok(r)
                });
                if r.is_err() {
                    stop.store(true, Ordering::Relaxed);
                }
                r
            })
            .collect();
        let mut out = Vec::with_capacity(results.len());
        for r in results {
            if let Some(r) = r? {
                out.push(r);
            }
        }
        Ok(out)
    }
}
