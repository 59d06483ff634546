//! Each sea state's member scenario checked once, before any member runs, with its
//! errors and warnings named by the study's own fields.
//!
//! A member's scenario carries its sea state as `environment.waves.trains[0]` and
//! `environment.current` (module documentation of `run`): validated as is, a sea state
//! whose waves overflow would be reported as `environment.waves.trains[0].hs` of the
//! base scenario, a file that has no such table, and only when its first member starts;
//! a steep sea state's warning would be logged once per member. Here every sea state
//! is validated when the study is planned, a problem is reported as
//! `study.sea_states[i].field` of the study file, and each warning is logged once.

use super::StudyRunner;
use crate::error::Error;
use crate::scenario::{collect_warnings, show, Scenario};
use crate::study::members::Member;

/// The field of the member scenario that carries sea state `i`'s key `field`, as the
/// study names it; `None` when `field` is not the sea state's.
pub fn study_field(i: usize, field: &str) -> Option<String> {
    let base = format!("study.sea_states[{i}]");
    if let Some(rest) = field.strip_prefix("environment.waves.trains[0]") {
        let key = match rest.strip_prefix('.') {
            Some("direction") => Some("heading"),
            Some(k @ ("hs" | "tp" | "gamma")) => Some(k),
            _ => None,
        };
        return Some(match key {
            Some(k) => format!("{base}.{k}"),
            None => base,
        });
    }
    if field.starts_with("environment.current") {
        return Some(format!("{base}.current_speed"));
    }
    if field.starts_with("environment.waves") {
        return Some(base);
    }
    None
}

impl StudyRunner {
    /// `(sea state i, its name)` as messages show it.
    fn sea_state_label(&self, i: usize) -> String {
        let ss = &self.plan.def.sea_states[i];
        match &ss.name {
            Some(n) => format!(
                "sea state {i} \"{n}\": Hs {} m, Tp {} s",
                show(ss.hs),
                show(ss.tp)
            ),
            None => format!("sea state {i}: Hs {} m, Tp {} s", show(ss.hs), show(ss.tp)),
        }
    }

    /// `e`, raised by sea state `i`'s member scenario, named by the study's field when
    /// it is the sea state's; any other error as it is.
    fn sea_state_error(&self, i: usize, e: Error) -> Error {
        match e {
            Error::Scenario {
                path,
                field,
                message,
            } => match study_field(i, &field) {
                Some(f) => Error::Scenario {
                    path: self.study_path.clone(),
                    field: f,
                    message: format!("{message} ({})", self.sea_state_label(i)),
                },
                None => Error::Scenario {
                    path,
                    field,
                    message,
                },
            },
            other => other,
        }
    }

    /// Member `m`'s validated scenario. Its warnings are dropped: [`Self::check_sea_states`]
    /// logged them once for its sea state.
    pub(super) fn member_scenario(&self, m: &Member) -> Result<Scenario, Error> {
        let (sc, _) =
            collect_warnings(|| Scenario::parse(&self.member_toml(m), &self.scenario_path));
        sc.map_err(|e| self.sea_state_error(m.sea_state, e))
    }

    /// Validates the scenario of each sea state's first member; logs every warning once,
    /// those of a sea state under its study field.
    pub(super) fn check_sea_states(&self) -> Result<(), Error> {
        let mut logged: Vec<String> = Vec::new();
        for i in 0..self.plan.def.sea_states.len() {
            let Some(m) = self.plan.members.iter().find(|m| m.sea_state == i) else {
                continue;
            };
            let (sc, warnings) =
                collect_warnings(|| Scenario::parse(&self.member_toml(m), &self.scenario_path));
            sc.map_err(|e| self.sea_state_error(i, e))?;
            let member_prefix = format!("{}: ", self.scenario_path.display());
            for w in warnings {
                let w = match w
                    .strip_prefix(&member_prefix)
                    .and_then(|rest| rest.split_once(": "))
                    .and_then(|(field, msg)| study_field(i, field).map(|f| (f, msg)))
                {
                    Some((f, msg)) => format!(
                        "{}: {f}: {msg} ({})",
                        self.study_path.display(),
                        self.sea_state_label(i)
                    ),
                    None => w,
                };
                if !logged.contains(&w) {
                    log::warn!("{w}");
                    logged.push(w);
                }
            }
        }
        Ok(())
    }
}
