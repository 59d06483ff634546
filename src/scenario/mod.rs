//! Scenario files (TOML): parsing, validation with precise messages, and the model
//! they describe. The keys are documented in docs/src/scenario.md.

//!
//! `Scenario::from_raw` reads the tables in file order, each in a module of its own:
//! `simulation` (`[simulation]`, `[ancf]`), `environment` (`[environment]`, currents),
//! `waves`, `materials` (`[[line_types]]`), `arrays`, `bodies`, `points`, `cables`
//! (with `ends` and `winch`), `nets`, `output`; `validate` checks the model they make.
//! `numbers` holds the checks of single values every table uses.

mod arrays;
mod bodies;
mod cables;
mod cage;
mod ends;
mod environment;
mod fatigue;
pub mod limits;
pub mod materials;
mod nets;
pub(crate) mod numbers;
mod output;
mod points;
mod raw;
mod route_file;
mod simulation;
mod validate;
pub(crate) mod warnings;
mod wave_checks;
pub mod wave_inputs;
pub use warnings::collect_warnings;
pub mod waves;
mod winch;

use crate::ale::Winch;
use crate::error::Error;
use crate::model::ModelDef;
pub use crate::options::Backend;
use crate::options::{AncfSettings, Baumgarte, CableModel, Formulation, Precision, Scheme};
pub use ends::EndKind;
use environment::current;
pub use limits::{LimitOverrides, Limits};
pub(crate) use numbers::{err, finite, non_negative, positive, show};
use output::Selection;
use raw::RawScenario;
use std::path::{Path, PathBuf};

/// The time step as asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DtSpec {
    /// The largest stable step times a safety factor, rounded down to divide the
    /// output interval.
    Auto,
    /// A given step, s.
    Fixed(f64),
}

/// How a cable's nodes start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InitialShape {
    /// Evenly spaced on the segment between the ends.
    Straight,
    /// The analytic elastic catenary, then relaxed to the discrete static equilibrium.
    Catenary,
}

/// The `[simulation]` table, validated.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulationConfig {
    /// Simulated duration, s.
    pub duration: f64,
    /// Time step.
    pub dt: DtSpec,
    /// Output interval, s.
    pub output_interval: f64,
    /// Backend.
    pub backend: Backend,
    /// Precision on the GPU (the CPU path is always f64); `None` = the backend's default.
    pub precision: Option<Precision>,
    /// Time scheme.
    pub scheme: Scheme,
    /// Load formulation (of the lumped-mass model).
    pub formulation: Formulation,
    /// Cable model: lumped mass, or the ANCF reference (`formulation = "ancf"`).
    pub model: CableModel,
    /// Constraint stabilisation.
    pub baumgarte: Baumgarte,
    /// Blow-up threshold on node speed, m/s.
    pub max_speed: f64,
}

/// A validated scenario.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The file it came from.
    pub path: PathBuf,
    /// Simulation settings.
    pub sim: SimulationConfig,
    /// The model.
    pub model: ModelDef,
    /// Initial shape of each cable (same order as `model.cables`).
    pub initial: Vec<InitialShape>,
    /// Winches (cables of varying length, ALE-GLMF), at most one per cable.
    pub winches: Vec<Winch>,
    /// The `[ancf]` table (used when the ANCF model runs).
    pub ancf: AncfSettings,
    /// The sea state of `[environment.waves]` (still water without it).
    pub sea: crate::sea::SeaState,
    /// The seas of a packed model, one per member (`crate::model::pack`), each cable
    /// in its member's; `None` for a scenario read from a file, whose every cable is
    /// in `sea`.
    pub member_seas: Option<crate::sea::SeaSet>,
    /// `environment.waves.depth_bands`: whether the CPU path's kinematics cache
    /// refreshes per depth band (`sea::bands`; default true).
    pub depth_bands: bool,
    /// The `[[points]]`, in scenario order: each name and its node (index into
    /// `model.nodes`), for `points.csv`.
    pub points: Vec<NamedPoint>,
    /// `[output] vtk`: also write ParaView files (`vtk/`).
    pub vtk: bool,
    /// `[output] format`: the tables' format (CSV or Parquet).
    pub output_format: crate::options::OutputFormat,
    /// `[fatigue]`, resolved against the model: a run writes `fatigue.csv`.
    pub fatigue: Option<crate::fatigue::FatigueSpec>,
    /// The work budget (`[limits]`, with the caller's overrides over it).
    pub limits: Limits,
    /// The cable ends that may fail during the run.
    pub failures: Vec<crate::model::EndFailure>,
    /// The `[[nets]]`, in scenario order: where their knots and parts are, for
    /// `nets.csv` (`crate::model::cage`).
    pub nets: Vec<crate::model::cage::NetInfo>,
}

/// A named shared point (`[[points]]`).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedPoint {
    /// Name.
    pub name: String,
    /// Its node: index into `ModelDef::nodes`.
    pub node: usize,
}

impl Scenario {
    /// The seas the run's cables are in: the packed model's, or `sea` for every cable.
    pub fn sea_set(&self) -> crate::sea::SeaSet {
        match &self.member_seas {
            Some(s) => s.clone(),
            None => crate::sea::SeaSet::single(&self.sea),
        }
    }

    /// Reads and validates a scenario file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scenario, Error> {
        let path = path.as_ref();
        let text = crate::input::read_text(path).map_err(|e| err(path, "(file)", e))?;
        Self::parse(&text, path)
    }

    /// [`Scenario::load_any`] with `limits` over the file's `[limits]` (the memory
    /// budget is checked while the file is read, before the model is built).
    pub fn load_any_with(
        path: impl AsRef<Path>,
        limits: &LimitOverrides,
    ) -> Result<Scenario, Error> {
        let path = path.as_ref();
        let text = crate::input::read_text(path).map_err(|e| err(path, "(file)", e))?;
        if !crate::moordyn::is_moordyn(path, &text) {
            return Self::parse_with(&text, path, limits);
        }
        let conv =
            crate::moordyn::convert_text(&text, path, &crate::moordyn::ConvertOptions::default())?;
        for w in &conv.warnings {
            warnings::warn(format!(
                "{}: line {}: {}",
                path.display(),
                w.line,
                w.message
            ));
        }
        Self::parse_with(&conv.toml, path, limits)
    }

    /// Reads a scenario file or a MoorDyn input file (v1 or v2), told apart by
    /// [`crate::moordyn::is_moordyn`]: a `.toml` name is a scenario; any other file is
    /// MoorDyn's when its section headers are. A MoorDyn file is converted with
    /// [`crate::moordyn::ConvertOptions::default`] (60 s, vessel points held still),
    /// each warning logged with its line, and the converted TOML validated as any
    /// scenario is.
    pub fn load_any(path: impl AsRef<Path>) -> Result<Scenario, Error> {
        Self::load_any_with(path, &LimitOverrides::default())
    }

    /// Parses and validates scenario text; `path` names the file in messages and is the
    /// base for relative route files.
    pub fn parse(text: &str, path: &Path) -> Result<Scenario, Error> {
        Self::parse_with(text, path, &LimitOverrides::default())
    }

    /// [`Scenario::parse`] with `limits` over the text's `[limits]`.
    pub fn parse_with(text: &str, path: &Path, limits: &LimitOverrides) -> Result<Scenario, Error> {
        let de = toml::Deserializer::new(text);
        let raw: RawScenario = serde_path_to_error::deserialize(de).map_err(|e| {
            let field = e.path().to_string();
            let field = if field == "." {
                "(top level)".to_string()
            } else {
                field
            };
            // toml's message carries the line and column of the problem.
            err(path, field, e.into_inner().to_string().trim().to_string())
        })?;
        Self::from_raw(raw, path, limits)
    }

    fn from_raw(raw: RawScenario, path: &Path, cli: &LimitOverrides) -> Result<Scenario, Error> {
        let p = path;
        // The budget first: nothing large is built for a model beyond it.
        let limits = limits::resolve(p, &raw.limits, cli)?;
        limits::check_model_size(p, &raw, &limits)?;
        // [simulation]
        let sim = simulation::simulation(p, &raw.simulation)?;

        // [environment]
        let (env, global_current) = environment::environment(p, &raw.environment)?;
        let depth = env.depth;
        let (sea, sea_warnings) = waves::sea_state_for_run(
            p,
            raw.environment.waves.as_ref(),
            depth,
            env.gravity,
            Some(sim.duration),
        )?;
        sea_warnings
            .iter()
            .for_each(|w| warnings::warn(w.to_string()));

        // [[line_types]]
        let (line_types, lt_index) = materials::line_types(p, &raw.line_types)?;
        let mut cables: Vec<(String, raw::RawCable)> = raw
            .cables
            .iter()
            .enumerate()
            .map(|(i, c)| (format!("cables[{i}] (\"{}\")", c.name), c.clone()))
            .collect();
        cables.extend(arrays::expand(p, &raw.cable_arrays)?);
        if cables.is_empty() && raw.nets.is_empty() {
            return Err(err(
                p,
                "cables",
                "the scenario has no [[cables]], [[cable_arrays]] or [[nets]]",
            ));
        }

        let mut model = ModelDef {
            env,
            line_types,
            currents: vec![global_current],
            ..Default::default()
        };

        // [[bodies]]: bodies with prescribed motion that ends attach to (RAO bodies move
        // in the sea state's wave components, ramped in with them).
        let bodies = bodies::parse(
            p,
            &raw.bodies,
            &sea.components,
            sea.ramp_duration,
            model.env.water_density,
        )?;

        // [[points]]: named shared nodes.
        let points = points::parse(p, &raw.points, &bodies, depth, sim.max_speed, &mut model)?;

        // [[cables]]
        let positions_sel = output::output_selection(p, &raw.output.positions)?;
        let cables::Cables {
            mut initial,
            winches,
            mut names,
            mut failures,
        } = cables::parse(
            p,
            &cables,
            &lt_index,
            &points.index,
            &bodies,
            (depth, sim.max_speed),
            &positions_sel,
            &mut model,
        )?;
        // [[nets]]
        let mut nets = Vec::with_capacity(raw.nets.len());
        for (i, net) in raw.nets.iter().enumerate() {
            let field = format!("nets[{i}] (\"{}\")", net.name);
            let spec =
                nets::parse(
                    p,
                    &field,
                    net,
                    &lt_index,
                    &mut model,
                    |name| match &positions_sel {
                        Selection::All => true,
                        Selection::None | Selection::Auto => false,
                        Selection::Names(v) => v.iter().any(|n| n == name),
                    },
                )?;
            let first = model.cables.len();
            let cage = cage::parse(p, &field, net, &spec, &lt_index, &points.index, &mut model)?;
            let info = crate::model::cage::add_cage(&mut model, &spec, &cage)
                .map_err(|e| err(p, &field, e.to_string()))?;
            cage::check_flotation(p, &field, &model, &info);
            nets.push(info);
            for (k, c) in model.cables[first..].iter().enumerate() {
                if names.insert(c.name.clone(), first + k).is_some() {
                    return Err(err(
                        p,
                        format!("{field}.name"),
                        format!("its twine \"{}\" has the name of another cable", c.name),
                    ));
                }
                initial.push(InitialShape::Straight);
            }
            names.insert(net.name.clone(), first);
        }
        let line_field = |i: usize| format!("line_types[{i}] (\"{}\")", model.line_types[i].name);
        // The entry that gives node `n` its point mass: a point, or a cable's end.
        let node_field = |n: usize| {
            // A net's knot: its point mass is the net's sinker.
            let label = model.nodes[n].label.clone();
            if let Some(l) = &label {
                if let Some((i, net)) = raw
                    .nets
                    .iter()
                    .enumerate()
                    .find(|(_, net)| l.starts_with(&format!("{}.knot", net.name)))
                {
                    return format!("nets[{i}] (\"{}\").sinker", net.name);
                }
            }
            if let Some((f, _, _)) = points.fields.iter().find(|(_, k, _)| *k == n) {
                return f.clone();
            }
            for (i, c) in model.cables.iter().enumerate() {
                for (end, k) in [("start", c.nodes.first()), ("end", c.nodes.last())] {
                    if k == Some(&n) {
                        // Cables before nets, in the order of `cables` (arrays expanded).
                        return match cables.get(i) {
                            Some((prefix, _)) => format!("{prefix}.{end}"),
                            None => format!("cable \"{}\" {end}", c.name),
                        };
                    }
                }
            }
            label.unwrap_or_else(|| format!("node {n}"))
        };
        validate::derived(
            p,
            &model,
            line_field,
            node_field,
            (sim.baumgarte.alpha, sim.baumgarte.beta),
        )?;
        validate::unused_points(p, &model, &points.fields)?;
        // A point that fails takes every cable end on it along.
        for (_, node, fl) in &points.failures {
            for c in &model.cables {
                for (at_start, k) in [(true, c.nodes.first()), (false, c.nodes.last())] {
                    if k == Some(node) {
                        failures.push(crate::model::EndFailure {
                            cable: c.name.clone(),
                            at_start,
                            time: fl.time,
                            tension: fl.tension,
                        });
                    }
                }
            }
        }
        validate::unused_line_types(p, &model, line_field);
        if let Selection::Names(v) = &positions_sel {
            if let Some(bad) = v.iter().find(|n| !names.contains_key(*n)) {
                return Err(err(
                    p,
                    "output.positions",
                    format!("no cable named \"{bad}\""),
                ));
            }
        }
        let fatigue = raw
            .fatigue
            .as_ref()
            .map(|f| fatigue::resolve(p, f, &model))
            .transpose()?;
        Ok(Scenario {
            path: p.to_path_buf(),
            sim,
            model,
            initial,
            winches,
            ancf: simulation::ancf_settings(p, &raw.ancf)?,
            sea,
            member_seas: None,
            depth_bands: raw
                .environment
                .waves
                .as_ref()
                .and_then(|w| w.depth_bands)
                .unwrap_or(true),
            points: points.named,
            vtk: raw.output.vtk.unwrap_or(false),
            output_format: output::output_format(p, &raw.output.format)?,
            fatigue,
            limits,
            failures,
            nets,
        })
    }
}
