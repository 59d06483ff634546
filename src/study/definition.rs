//! The `[study]` table: what a study runs and reduces, parsed and validated.
//!
//! A study is either a `[study]` table inside a scenario file (the base model is that
//! file), or a study file whose `[study]` table names the base scenario with
//! `scenario = "PATH"` (relative to the study file) and holds nothing else. The keys are
//! documented in `docs/src/studies.md`.

use super::channels;
use super::gumbel::GumbelFit;
use crate::error::Error;
use crate::scenario::{err, finite, non_negative, positive};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One design sea state: irregular waves and a uniform current.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeaState {
    /// A label for the tables (optional).
    pub name: Option<String>,
    /// Significant wave height `Hs`, m.
    pub hs: f64,
    /// Spectral peak period `Tp`, s.
    pub tp: f64,
    /// JONSWAP peak factor `gamma`; `None` leaves it to the waves' default (from `Hs` and
    /// `Tp`, DNV-RP-C205).
    pub gamma: Option<f64>,
    /// Direction the waves travel towards, degrees from +x towards +y.
    pub heading: f64,
    /// Current speed, m/s (uniform over depth).
    pub current_speed: f64,
    /// Direction the current flows towards, degrees from +x towards +y.
    pub current_heading: f64,
    /// Probability of occurrence in the fatigue scatter diagram (fatigue sea states
    /// only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub probability: Option<f64>,
    /// Hours per year in the fatigue scatter diagram (fatigue sea states only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hours: Option<f64>,
    /// How many of the study's seeds this sea state runs (the first ones; `None`: all).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seeds: Option<usize>,
}

impl SeaState {
    /// Whether the sea state is part of the fatigue scatter diagram.
    pub fn in_scatter(&self) -> bool {
        self.probability.is_some() || self.hours.is_some()
    }
}

/// The fatigue limit state's inputs (`[study.fatigue]`): the scatter diagram is the
/// sea states that give a `probability` or `hours`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FatigueInputs {
    /// The design fatigue factor: the fatigue life is `1 / (DFF * annual damage)`.
    pub design_fatigue_factor: f64,
    /// The hours of a year (the total the sea states' `hours` sum to, and what their
    /// probabilities are fractions of), default 8766 (365.25 days).
    pub hours_per_year: f64,
}

/// Tolerance of the scatter diagram's sums: probabilities sum to 1, hours to
/// `hours_per_year`, within this fraction.
pub const SCATTER_TOLERANCE: f64 = 1.0e-3;

/// The default `hours_per_year`: 365.25 days.
pub const HOURS_PER_YEAR: f64 = 8766.0;

/// Partial safety factors and line capacities of the design check
/// `T_d = mean_factor T_mean + dynamic_factor (T_MPM - T_mean)`, utilisation `T_d / S_C`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DesignInputs {
    /// Partial safety factor on the mean tension `g_mean` (ULS: the intact condition).
    pub mean_factor: f64,
    /// Partial safety factor on the dynamic tension `g_dyn` (ULS: the intact condition).
    pub dynamic_factor: f64,
    /// Characteristic strength `S_C` per line type name, N.
    pub capacities: BTreeMap<String, f64>,
    /// The consequence class (1 or 2) the factors were taken from, when given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub consequence_class: Option<u8>,
    /// ALS factors `(g_mean, g_dyn)` of the damaged conditions (`None`: the study has
    /// none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accidental: Option<(f64, f64)>,
}

/// The partial safety factors of DNV-OS-E301 (Ch.2 Sec.2) for a dynamic analysis:
/// `(g_mean, g_dyn)` of the ultimate limit state and of the accidental limit state, by
/// consequence class 1 or 2 (docs/src/studies.md says what was and was not checked).
pub fn dnv_factors(class: u8) -> Option<((f64, f64), (f64, f64))> {
    match class {
        1 => Some(((1.1, 1.5), (1.0, 1.1))),
        2 => Some(((1.4, 2.1), (1.0, 1.25))),
        _ => None,
    }
}

/// Which lines a study breaks (`study.conditions.broken`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Broken {
    /// Each cable of the base scenario, one at a time.
    Each,
    /// These cables, one at a time.
    Lines(Vec<String>),
}

/// The mooring conditions a study runs (`[study.conditions]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConditionsSpec {
    /// Whether the intact mooring is run.
    pub intact: bool,
    /// The lines broken, one damaged condition each.
    pub broken: Broken,
    /// When the broken line fails, s (`None`: broken from the start).
    pub fail_time: Option<f64>,
}

/// One mooring condition of a study, as the plan expands it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Condition {
    /// `intact`, or the broken cable's name.
    pub name: String,
    /// The cables broken (empty: intact).
    pub broken: Vec<String>,
}

impl Condition {
    /// The intact mooring.
    pub fn intact() -> Condition {
        Condition {
            name: "intact".into(),
            broken: Vec::new(),
        }
    }

    /// Whether it is a damaged condition (the accidental limit state).
    pub fn is_damaged(&self) -> bool {
        !self.broken.is_empty()
    }

    /// `uls` (intact) or `als` (damaged): the limit state its design check is of.
    pub fn limit_state(&self) -> &'static str {
        if self.is_damaged() {
            "als"
        } else {
            "uls"
        }
    }
}

/// A validated study definition. Its JSON form (field order as here) is the canonical
/// text the study hash is taken of.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StudyDef {
    /// The study seed, from which every member's wave seed is derived.
    pub seed: u64,
    /// The seed numbers run in every sea state (`1..=N` for a count).
    pub seeds: Vec<u64>,
    /// Simulated duration of each member, s.
    pub duration: f64,
    /// Start-up time discarded from every record, s (shorter than the duration).
    pub transient: f64,
    /// The sea states.
    pub sea_states: Vec<SeaState>,
    /// Channel entries as written (resolved against the base model by the plan).
    pub channels: Vec<String>,
    /// Probability of the reported quantile of the maxima (default 0.9).
    pub quantile: f64,
    /// The fit that gives the most probable maximum, the quantile and the design tension.
    pub fit: GumbelFit,
    /// The design check, when asked for.
    pub design: Option<DesignInputs>,
    /// The fatigue limit state, when asked for (`[study.fatigue]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fatigue: Option<FatigueInputs>,
    /// The mooring conditions (`[study.conditions]`; `None`: the intact mooring only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conditions: Option<ConditionsSpec>,
}

impl StudyDef {
    /// The seed numbers sea state `s` runs: the study's, or the first `seeds` of them.
    pub fn seeds_of(&self, s: usize) -> &[u64] {
        match self.sea_states[s].seeds {
            Some(n) => &self.seeds[..n.min(self.seeds.len())],
            None => &self.seeds,
        }
    }

    /// The annual hours of sea state `s` in the scatter diagram (`None` when it is not
    /// in it, or the study has no fatigue).
    pub fn annual_hours(&self, s: usize) -> Option<f64> {
        let f = self.fatigue.as_ref()?;
        let ss = &self.sea_states[s];
        ss.hours.or(ss.probability.map(|p| p * f.hours_per_year))
    }
}

/// A study file read from disk: the definition and its base scenario.
#[derive(Clone, Debug)]
pub struct StudyFile {
    /// The file holding the `[study]` table.
    pub path: PathBuf,
    /// The base scenario file (the same file when the table sits inside a scenario).
    pub scenario_path: PathBuf,
    /// The base scenario's text, as read (part of the study hash).
    pub scenario_text: String,
    /// The validated definition.
    pub def: StudyDef,
}

#[derive(Deserialize)]
struct RawDoc {
    study: Option<RawStudy>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    scenario: Option<String>,
    seed: Option<u64>,
    seeds: Option<toml::Value>,
    duration: Option<f64>,
    transient: Option<f64>,
    sea_states: Option<Vec<RawSeaState>>,
    sea_states_file: Option<String>,
    channels: Option<Vec<String>>,
    quantile: Option<f64>,
    fit: Option<String>,
    design: Option<RawDesign>,
    fatigue: Option<RawStudyFatigue>,
    conditions: Option<RawConditions>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConditions {
    intact: Option<bool>,
    broken: Option<toml::Value>,
    fail_time: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudyFatigue {
    design_fatigue_factor: Option<f64>,
    hours_per_year: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSeaState {
    name: Option<String>,
    hs: Option<f64>,
    tp: Option<f64>,
    gamma: Option<f64>,
    heading: Option<f64>,
    current_speed: Option<f64>,
    current_heading: Option<f64>,
    probability: Option<f64>,
    hours: Option<f64>,
    seeds: Option<i64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDesign {
    consequence_class: Option<i64>,
    mean_factor: Option<f64>,
    dynamic_factor: Option<f64>,
    accidental_mean_factor: Option<f64>,
    accidental_dynamic_factor: Option<f64>,
    capacities: Option<BTreeMap<String, f64>>,
}

const SEA_STATE_COLUMNS: [&str; 10] = [
    "name",
    "hs",
    "tp",
    "gamma",
    "heading",
    "current_speed",
    "current_heading",
    "probability",
    "hours",
    "seeds",
];

impl StudyFile {
    /// Reads a study: the `[study]` table of `path`, and its base scenario.
    pub fn load(path: impl AsRef<Path>) -> Result<StudyFile, Error> {
        let path = path.as_ref();
        let text = crate::input::read_text(path).map_err(|e| err(path, "(file)", e))?;
        let (def, scenario) = parse_study(&text, path)?;
        match scenario {
            None => Ok(StudyFile {
                path: path.to_path_buf(),
                scenario_path: path.to_path_buf(),
                scenario_text: text,
                def,
            }),
            Some(rel) => {
                let scenario_path = path.parent().unwrap_or(Path::new(".")).join(&rel);
                let scenario_text = crate::input::read_text(&scenario_path).map_err(|e| {
                    err(
                        path,
                        "study.scenario",
                        format!("\"{}\": {e}", scenario_path.display()),
                    )
                })?;
                Ok(StudyFile {
                    path: path.to_path_buf(),
                    scenario_path,
                    scenario_text,
                    def,
                })
            }
        }
    }
}

/// Parses and validates the `[study]` table of `text`; `path` names the file in
/// messages and is the base for relative paths. Returns the definition and the base
/// scenario path as written (`None` when the table sits inside the scenario).
pub fn parse_study(text: &str, path: &Path) -> Result<(StudyDef, Option<String>), Error> {
    let de = toml::Deserializer::new(text);
    let doc: RawDoc = serde_path_to_error::deserialize(de).map_err(|e| {
        let field = e.path().to_string();
        // toml's message carries the line and column of the problem.
        err(path, field, e.into_inner().to_string().trim().to_string())
    })?;
    let raw = doc
        .study
        .ok_or_else(|| err(path, "study", "the file has no [study] table"))?;
    if raw.scenario.is_some() {
        let table: toml::Table = text
            .parse()
            .map_err(|e| err(path, "(top level)", format!("{e}")))?;
        if let Some(k) = table.keys().find(|k| *k != "study") {
            return Err(err(
                path,
                k.as_str(),
                "a study file that names its base scenario (study.scenario) holds only the \
                 [study] table: put the model in the base scenario",
            ));
        }
    }
    let def = validate(&raw, path)?;
    Ok((def, raw.scenario))
}

fn required<T: Copy>(path: &Path, field: &str, v: Option<T>) -> Result<T, Error> {
    v.ok_or_else(|| err(path, field, "missing"))
}

fn validate(raw: &RawStudy, p: &Path) -> Result<StudyDef, Error> {
    let duration = positive(
        p,
        "study.duration",
        required(p, "study.duration", raw.duration)?,
    )?;
    let transient = non_negative(
        p,
        "study.transient",
        required(p, "study.transient", raw.transient)?,
    )?;
    if transient >= duration {
        return Err(err(
            p,
            "study.transient",
            format!(
                "the transient ({transient} s) must be shorter than the duration ({duration} s): \
                 nothing of the record would be left"
            ),
        ));
    }
    let seeds = seeds(p, raw.seeds.as_ref())?;
    let sea_states = match (&raw.sea_states, &raw.sea_states_file) {
        (Some(_), Some(_)) => {
            return Err(err(
                p,
                "study.sea_states_file",
                "give either `sea_states` (rows) or `sea_states_file` (a CSV), not both",
            ))
        }
        (None, None) => {
            return Err(err(
                p,
                "study.sea_states",
                "missing: give `sea_states` (rows) or `sea_states_file` (a CSV)",
            ))
        }
        (Some(rows), None) => rows
            .iter()
            .enumerate()
            .map(|(i, r)| sea_state(p, &|k| format!("study.sea_states[{i}].{k}"), r))
            .collect::<Result<Vec<_>, _>>()?,
        (None, Some(file)) => {
            let csv_path = p.parent().unwrap_or(Path::new(".")).join(file);
            read_sea_states_csv(&csv_path)?
        }
    };
    if sea_states.is_empty() {
        return Err(err(p, "study.sea_states", "no sea state given"));
    }
    for (i, ss) in sea_states.iter().enumerate() {
        if let Some(n) = ss.seeds.filter(|n| *n > seeds.len()) {
            return Err(err(
                p,
                match &raw.sea_states_file {
                    Some(file) => {
                        format!("study.sea_states_file (\"{file}\"): row {}: seeds", i + 1)
                    }
                    None => format!("study.sea_states[{i}].seeds"),
                },
                format!(
                    "{n} seeds, more than the study's {} (study.seeds)",
                    seeds.len()
                ),
            ));
        }
    }
    let channels = raw
        .channels
        .clone()
        .unwrap_or_else(|| vec!["default".to_string()]);
    if channels.is_empty() {
        return Err(err(p, "study.channels", "the list is empty"));
    }
    channels::check_entries(p, "study.channels", &channels)?;
    let quantile = raw.quantile.unwrap_or(0.9);
    finite(p, "study.quantile", quantile)?;
    if !(quantile > 0.0 && quantile < 1.0) {
        return Err(err(
            p,
            "study.quantile",
            format!("must be a probability strictly between 0 and 1, got {quantile}"),
        ));
    }
    let fit = match raw.fit.as_deref() {
        None | Some("mle") => GumbelFit::Mle,
        Some("moments") => GumbelFit::Moments,
        Some(x) => {
            return Err(err(
                p,
                "study.fit",
                format!("must be mle or moments, got \"{x}\""),
            ))
        }
    };
    let conditions = conditions(p, raw.conditions.as_ref(), duration)?;
    let damaged = conditions
        .as_ref()
        .is_some_and(|c| !matches!(&c.broken, Broken::Lines(l) if l.is_empty()));
    let design = match &raw.design {
        None => None,
        Some(d) => Some(design_inputs(p, d, damaged)?),
    };
    let sea_states_field = match &raw.sea_states_file {
        Some(f) => format!("study.sea_states_file (\"{f}\")"),
        None => "study.sea_states".to_string(),
    };
    let fatigue = fatigue_inputs(p, raw.fatigue.as_ref(), &sea_states, &sea_states_field)?;
    Ok(StudyDef {
        seed: raw.seed.unwrap_or(0),
        seeds,
        duration,
        transient,
        sea_states,
        channels,
        quantile,
        fit,
        design,
        fatigue,
        conditions,
    })
}

/// `[study.design]`: the factors from `consequence_class` (DNV-OS-E301) or given, the
/// ALS ones needed when the study has damaged conditions (`damaged`).
fn design_inputs(p: &Path, d: &RawDesign, damaged: bool) -> Result<DesignInputs, Error> {
    let class = match d.consequence_class {
        None => None,
        Some(c) => Some(
            match u8::try_from(c).ok().filter(|c| dnv_factors(*c).is_some()) {
                Some(c) => c,
                None => {
                    return Err(err(
                        p,
                        "study.design.consequence_class",
                        format!("must be 1 or 2 (DNV-OS-E301), got {c}"),
                    ))
                }
            },
        ),
    };
    let table = class.and_then(dnv_factors);
    let factor = |key: &str, given: Option<f64>, from_class: Option<f64>, what: &str| {
        let f = format!("study.design.{key}");
        match given.or(from_class) {
            Some(x) => positive(p, &f, x),
            None => Err(err(
                p,
                f,
                format!("missing: the partial safety factor on {what}, or a consequence_class (1 or 2) to take it from DNV-OS-E301"),
            )),
        }
    };
    let mean_factor = factor(
        "mean_factor",
        d.mean_factor,
        table.map(|t| t.0 .0),
        "the mean tension (ULS)",
    )?;
    let dynamic_factor = factor(
        "dynamic_factor",
        d.dynamic_factor,
        table.map(|t| t.0 .1),
        "the dynamic tension (ULS)",
    )?;
    let accidental = if damaged {
        Some((
            factor(
                "accidental_mean_factor",
                d.accidental_mean_factor,
                table.map(|t| t.1 .0),
                "the mean tension of the damaged conditions (ALS)",
            )?,
            factor(
                "accidental_dynamic_factor",
                d.accidental_dynamic_factor,
                table.map(|t| t.1 .1),
                "the dynamic tension of the damaged conditions (ALS)",
            )?,
        ))
    } else {
        for (k, v) in [
            ("accidental_mean_factor", d.accidental_mean_factor),
            ("accidental_dynamic_factor", d.accidental_dynamic_factor),
        ] {
            if v.is_some() {
                return Err(err(
                    p,
                    format!("study.design.{k}"),
                    "the study has no damaged condition to apply it to: break lines with \
                     [study.conditions] broken = \"each\" or a list of cables",
                ));
            }
        }
        None
    };
    let capacities = d.capacities.clone().ok_or_else(|| {
        err(
            p,
            "study.design.capacities",
            "missing: the capacity S_C of each line type, N",
        )
    })?;
    if capacities.is_empty() {
        return Err(err(p, "study.design.capacities", "the table is empty"));
    }
    for (name, c) in &capacities {
        positive(p, &format!("study.design.capacities.{name}"), *c)?;
    }
    Ok(DesignInputs {
        mean_factor,
        dynamic_factor,
        capacities,
        consequence_class: class,
        accidental,
    })
}

/// `[study.conditions]`: `intact` (default true), `broken` (`"each"` or a list of
/// cable names, checked against the base model by the plan), `fail_time` (s, before
/// the end of the record).
fn conditions(
    p: &Path,
    raw: Option<&RawConditions>,
    duration: f64,
) -> Result<Option<ConditionsSpec>, Error> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let broken = match &raw.broken {
        None => Broken::Lines(Vec::new()),
        Some(toml::Value::String(s)) if s == "each" => Broken::Each,
        Some(toml::Value::Array(a)) => {
            let mut names: Vec<String> = Vec::new();
            for (i, v) in a.iter().enumerate() {
                let f = format!("study.conditions.broken[{i}]");
                let Some(n) = v.as_str() else {
                    return Err(err(
                        p,
                        f,
                        format!("must be a cable name, got {}", v.type_str()),
                    ));
                };
                if names.iter().any(|x| x == n) {
                    return Err(err(p, f, format!("cable \"{n}\" is listed twice")));
                }
                names.push(n.to_string());
            }
            if names.is_empty() {
                return Err(err(
                    p,
                    "study.conditions.broken",
                    "the list is empty: name the cables to break, or \"each\"",
                ));
            }
            Broken::Lines(names)
        }
        Some(v) => {
            return Err(err(
                p,
                "study.conditions.broken",
                format!("must be \"each\" or a list of cable names, got {v}"),
            ))
        }
    };
    let intact = raw.intact.unwrap_or(true);
    if !intact && matches!(&broken, Broken::Lines(l) if l.is_empty()) {
        return Err(err(
            p,
            "study.conditions.intact",
            "false with no line broken leaves no condition to run",
        ));
    }
    let fail_time = match raw.fail_time {
        None => None,
        Some(t) => {
            let t = non_negative(p, "study.conditions.fail_time", t)?;
            if t >= duration {
                return Err(err(
                    p,
                    "study.conditions.fail_time",
                    format!("the line would fail at {t} s, after the record ends ({duration} s)"),
                ));
            }
            if matches!(&broken, Broken::Lines(l) if l.is_empty()) {
                return Err(err(
                    p,
                    "study.conditions.fail_time",
                    "no line is broken (study.conditions.broken)",
                ));
            }
            Some(t)
        }
    };
    Ok(Some(ConditionsSpec {
        intact,
        broken,
        fail_time,
    }))
}

/// `[study.fatigue]` and the scatter diagram of the sea states: probabilities that sum
/// to 1, or hours that sum to `hours_per_year`, within [`SCATTER_TOLERANCE`].
fn fatigue_inputs(
    p: &Path,
    raw: Option<&RawStudyFatigue>,
    sea_states: &[SeaState],
    field: &str,
) -> Result<Option<FatigueInputs>, Error> {
    let in_scatter: Vec<&SeaState> = sea_states.iter().filter(|s| s.in_scatter()).collect();
    let Some(raw) = raw else {
        if !in_scatter.is_empty() {
            return Err(err(
                p,
                "study.fatigue",
                "missing: sea states give a `probability` or `hours` (a fatigue scatter \
                 diagram), which needs [study.fatigue] with its design_fatigue_factor",
            ));
        }
        return Ok(None);
    };
    let dff = positive(
        p,
        "study.fatigue.design_fatigue_factor",
        required(
            p,
            "study.fatigue.design_fatigue_factor",
            raw.design_fatigue_factor,
        )?,
    )?;
    let hours_per_year = positive(
        p,
        "study.fatigue.hours_per_year",
        raw.hours_per_year.unwrap_or(HOURS_PER_YEAR),
    )?;
    if in_scatter.is_empty() {
        return Err(err(
            p,
            format!("{field}: probability"),
            "[study.fatigue] needs a scatter diagram: give the fatigue sea states a \
             `probability` of occurrence or their `hours` per year",
        ));
    }
    let with_p = in_scatter
        .iter()
        .filter(|s| s.probability.is_some())
        .count();
    if with_p != 0 && with_p != in_scatter.len() {
        return Err(err(
            p,
            format!("{field}: hours"),
            "the scatter diagram mixes probabilities and hours: give every fatigue sea \
             state the same one",
        ));
    }
    if with_p > 0 {
        let sum: f64 = in_scatter.iter().filter_map(|s| s.probability).sum();
        if (sum - 1.0).abs() > SCATTER_TOLERANCE {
            return Err(err(
                p,
                format!("{field}: probability"),
                format!(
                    "the probabilities of the {} fatigue sea states sum to {sum}, not 1 \
                     (tolerance {SCATTER_TOLERANCE})",
                    in_scatter.len()
                ),
            ));
        }
    } else {
        let sum: f64 = in_scatter.iter().filter_map(|s| s.hours).sum();
        if (sum - hours_per_year).abs() > SCATTER_TOLERANCE * hours_per_year {
            return Err(err(
                p,
                format!("{field}: hours"),
                format!(
                    "the hours of the {} fatigue sea states sum to {sum}, not \
                     study.fatigue.hours_per_year = {hours_per_year} (tolerance {} h)",
                    in_scatter.len(),
                    SCATTER_TOLERANCE * hours_per_year
                ),
            ));
        }
    }
    Ok(Some(FatigueInputs {
        design_fatigue_factor: dff,
        hours_per_year,
    }))
}

/// `seeds = N` (the seed numbers 1 to N) or `seeds = [a, b, ...]` (distinct, >= 0).
fn seeds(p: &Path, v: Option<&toml::Value>) -> Result<Vec<u64>, Error> {
    let f = "study.seeds";
    match v {
        None => Err(err(
            p,
            f,
            "missing: a count of seeds, or a list of seed numbers",
        )),
        Some(toml::Value::Integer(n)) => {
            if *n <= 0 {
                Err(err(
                    p,
                    f,
                    format!("a study needs at least one seed, got {n}"),
                ))
            } else {
                Ok((1..=*n as u64).collect())
            }
        }
        Some(toml::Value::Array(a)) => {
            if a.is_empty() {
                return Err(err(
                    p,
                    f,
                    "a study needs at least one seed, the list is empty",
                ));
            }
            let mut seen = BTreeSet::new();
            a.iter()
                .enumerate()
                .map(|(i, v)| match v {
                    toml::Value::Integer(s) if *s >= 0 => {
                        if seen.insert(*s) {
                            Ok(*s as u64)
                        } else {
                            Err(err(
                                p,
                                format!("{f}[{i}]"),
                                format!("seed {s} is listed twice"),
                            ))
                        }
                    }
                    other => Err(err(
                        p,
                        format!("{f}[{i}]"),
                        format!("must be a seed number, an integer >= 0, got {other}"),
                    )),
                })
                .collect()
        }
        Some(other) => Err(err(
            p,
            f,
            format!(
                "must be a count of seeds or a list of seed numbers, got {}",
                other.type_str()
            ),
        )),
    }
}

fn sea_state(p: &Path, f: &dyn Fn(&str) -> String, r: &RawSeaState) -> Result<SeaState, Error> {
    let hs = positive(p, &f("hs"), required(p, &f("hs"), r.hs)?)?;
    let tp = positive(p, &f("tp"), required(p, &f("tp"), r.tp)?)?;
    let gamma = match r.gamma {
        None => None,
        Some(g) => {
            finite(p, &f("gamma"), g)?;
            if g < 1.0 {
                return Err(err(
                    p,
                    f("gamma"),
                    format!("a JONSWAP peak factor is at least 1 (1 = Pierson-Moskowitz), got {g}"),
                ));
            }
            Some(crate::scenario::waves::jonswap_gamma_in_range(
                p,
                &f("gamma"),
                g,
            )?)
        }
    };
    Ok(SeaState {
        name: r.name.clone(),
        hs,
        tp,
        gamma,
        heading: finite(p, &f("heading"), r.heading.unwrap_or(0.0))?,
        current_speed: non_negative(p, &f("current_speed"), r.current_speed.unwrap_or(0.0))?,
        current_heading: finite(p, &f("current_heading"), r.current_heading.unwrap_or(0.0))?,
        probability: match (r.probability, r.hours) {
            (Some(_), Some(_)) => {
                return Err(err(
                    p,
                    f("hours"),
                    "give either a probability of occurrence or hours per year, not both",
                ))
            }
            (Some(x), None) => {
                non_negative(p, &f("probability"), x)?;
                if x > 1.0 {
                    return Err(err(
                        p,
                        f("probability"),
                        format!("a probability is at most 1, got {x}"),
                    ));
                }
                Some(x)
            }
            (None, _) => None,
        },
        hours: r
            .hours
            .map(|h| non_negative(p, &f("hours"), h))
            .transpose()?,
        seeds: match r.seeds {
            None => None,
            Some(n) if n >= 1 => Some(n as usize),
            Some(n) => {
                return Err(err(
                    p,
                    f("seeds"),
                    format!("a sea state runs at least one seed, got {n}"),
                ))
            }
        },
    })
}

/// Reads sea states from a CSV file with a header row; columns `hs` and `tp` are
/// required, `name`, `gamma`, `heading`, `current_speed`, `current_heading` optional
/// (an empty cell takes the default).
pub fn read_sea_states_csv(path: &Path) -> Result<Vec<SeaState>, Error> {
    let bytes = crate::input::read_bytes(path).map_err(|e| err(path, "(file)", e))?;
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(bytes.as_slice());
    let headers = rdr
        .headers()
        .map_err(|e| err(path, "(header)", e.to_string()))?
        .clone();
    for (i, h) in headers.iter().enumerate() {
        if !SEA_STATE_COLUMNS.contains(&h) {
            return Err(err(
                path,
                format!("column {} (\"{h}\")", i + 1),
                format!("unknown column (known: {})", SEA_STATE_COLUMNS.join(", ")),
            ));
        }
    }
    for need in ["hs", "tp"] {
        if !headers.iter().any(|h| h == need) {
            return Err(err(path, "(header)", format!("no `{need}` column")));
        }
    }
    let mut out = Vec::new();
    for rec in rdr.records() {
        let rec = rec.map_err(|e| err(path, "(rows)", e.to_string()))?;
        let line = rec.position().map_or(0, |q| q.line());
        let raw: RawSeaState = rec
            .deserialize(Some(&headers))
            .map_err(|e| err(path, format!("line {line}"), e.to_string()))?;
        out.push(sea_state(path, &|k| format!("line {line}: {k}"), &raw)?);
    }
    Ok(out)
}
