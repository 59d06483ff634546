//! Scenario files (TOML): parsing, validation with precise messages, and the model
//! they describe. The keys are documented in docs/src/scenario.md.

mod arrays;
mod bodies;
mod ends;
pub mod limits;
pub mod materials;
mod nets;
mod raw;
mod route_file;
mod validate;
mod warnings;
mod wave_checks;
pub use warnings::collect_warnings;
pub mod waves;
mod winch;

use crate::ale::Winch;
use crate::error::Error;
use crate::model::{add_net, CableDef, Current, Environment, ModelDef, NodeDef, PointMass};
pub use crate::options::Backend;
use crate::options::{AncfSettings, Baumgarte, CableModel, Formulation, Precision, Scheme};
pub use ends::EndKind;
pub use limits::{LimitOverrides, Limits};
use raw::{RawDt, RawScenario};
use std::collections::HashMap;
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
    /// The work budget (`[limits]`, with the caller's overrides over it).
    pub limits: Limits,
}

/// A named shared point (`[[points]]`).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedPoint {
    /// Name.
    pub name: String,
    /// Its node: index into `ModelDef::nodes`.
    pub node: usize,
}

/// Builds `Error::Scenario` for `path`.
pub(crate) fn err(path: &Path, field: impl Into<String>, message: impl Into<String>) -> Error {
    Error::Scenario {
        path: path.to_path_buf(),
        field: field.into(),
        message: message.into(),
    }
}

/// A number as a message shows it: plainly in the range people write by hand, in
/// exponent form outside it (`-1e160`, not a hundred and sixty digits).
pub(crate) fn show(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Checks a number is finite (TOML allows `nan` and `inf`).
pub(crate) fn finite(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(err(
            path,
            field,
            format!("must be a finite number, got {}", show(x)),
        ))
    }
}

pub(crate) fn positive(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
    finite(path, field, x)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(err(
            path,
            field,
            format!("must be positive, got {}", show(x)),
        ))
    }
}

pub(crate) fn non_negative(path: &Path, field: &str, x: f64) -> Result<f64, Error> {
    finite(path, field, x)?;
    if x >= 0.0 {
        Ok(x)
    } else {
        Err(err(
            path,
            field,
            format!("must not be negative, got {}", show(x)),
        ))
    }
}

fn vec3(path: &Path, field: &str, v: [f64; 3]) -> Result<[f64; 3], Error> {
    for (k, x) in v.iter().enumerate() {
        finite(path, &format!("{field}[{k}]"), *x)?;
    }
    Ok(v)
}

fn current(
    path: &Path,
    field: &str,
    uniform: Option<[f64; 3]>,
    profile: &Option<Vec<[f64; 4]>>,
) -> Result<Option<Current>, Error> {
    match (uniform, profile) {
        (Some(_), Some(_)) => Err(err(
            path,
            field,
            "give either `current` or `current_profile`, not both",
        )),
        (Some(u), None) => {
            let f = format!("{field}current");
            let u = vec3(path, &f, u)?;
            validate::current_speed(path, &f, u)?;
            Ok(Some(Current::uniform(u)))
        }
        (None, Some(rows)) => {
            let f = format!("{field}current_profile");
            if rows.is_empty() {
                return Err(err(path, &f, "needs at least one row [z, ux, uy, uz]"));
            }
            let mut table = Vec::with_capacity(rows.len());
            for (i, r) in rows.iter().enumerate() {
                for (k, x) in r.iter().enumerate() {
                    finite(path, &format!("{f}[{i}][{k}]"), *x)?;
                }
                validate::current_speed(path, &format!("{f}[{i}]"), [r[1], r[2], r[3]])?;
                if i > 0 && r[0] <= rows[i - 1][0] {
                    return Err(err(
                        path,
                        format!("{f}[{i}]"),
                        "depths z must increase strictly from row to row",
                    ));
                }
                table.push((r[0], [r[1], r[2], r[3]]));
            }
            Ok(Some(Current { table }))
        }
        (None, None) => Ok(None),
    }
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
        let s = &raw.simulation;
        let duration = positive(p, "simulation.duration", s.duration)?;
        let output_interval = positive(p, "simulation.output_interval", s.output_interval)?;
        let dt = match &s.dt {
            None => DtSpec::Auto,
            Some(RawDt::Word(w)) if w == "auto" => DtSpec::Auto,
            Some(RawDt::Word(w)) => {
                return Err(err(
                    p,
                    "simulation.dt",
                    format!("must be \"auto\" or a step in seconds, got \"{w}\""),
                ))
            }
            Some(RawDt::Number(x)) => DtSpec::Fixed(positive(p, "simulation.dt", *x)?),
        };
        // The enums are parsed by serde (raw.rs): an unknown value is an error naming
        // the field and the values allowed.
        let backend = s.backend.unwrap_or_default();
        let scheme = s.scheme.unwrap_or_default();
        let choice = s.formulation.unwrap_or_default();
        let (cable_model, formulation) = (choice.model(), choice.formulation());
        let mut baumgarte = Baumgarte::default();
        if let Some(a) = s.baumgarte_alpha {
            baumgarte.alpha = non_negative(p, "simulation.baumgarte_alpha", a)?;
        }
        if let Some(b) = s.baumgarte_beta {
            baumgarte.beta = non_negative(p, "simulation.baumgarte_beta", b)?;
        }
        let max_speed = match s.max_speed {
            Some(v) => positive(p, "simulation.max_speed", v)?,
            None => 1.0e4,
        };
        let sim = SimulationConfig {
            duration,
            dt,
            output_interval,
            backend,
            precision: s.precision,
            scheme,
            formulation,
            model: cable_model,
            baumgarte,
            max_speed,
        };

        // [environment]
        let e = &raw.environment;
        let depth = match e.depth {
            Some(d) => positive(p, "environment.depth", d)?,
            None => f64::INFINITY,
        };
        let sb = e.seabed;
        non_negative(p, "environment.seabed.stiffness", sb.stiffness)?;
        non_negative(p, "environment.seabed.damping", sb.damping)?;
        non_negative(p, "environment.seabed.friction", sb.friction)?;
        positive(
            p,
            "environment.seabed.friction_velocity",
            sb.friction_velocity,
        )?;
        let env = Environment {
            gravity: validate::magnitude(
                p,
                "environment.gravity",
                non_negative(p, "environment.gravity", e.gravity)?,
                "m/s^2",
            )?,
            water_density: validate::magnitude(
                p,
                "environment.water_density",
                non_negative(p, "environment.water_density", e.water_density)?,
                "kg/m^3",
            )?,
            depth,
            seabed: sb,
        };
        let global_current =
            current(p, "environment.", e.current, &e.current_profile)?.unwrap_or_default();
        let (sea, sea_warnings) = waves::sea_state(p, e.waves.as_ref(), depth, env.gravity)?;
        sea_warnings
            .iter()
            .for_each(|w| warnings::warn(w.to_string()));

        // [[line_types]]
        let mut lt_index = HashMap::new();
        let line_types = raw
            .line_types
            .iter()
            .enumerate()
            .map(|(i, lt)| lt.resolve(p, i))
            .collect::<Result<Vec<_>, _>>()?;
        for (i, lt) in line_types.iter().enumerate() {
            let f = |k: &str| format!("line_types[{i}] (\"{}\").{k}", lt.name);
            positive(p, &f("diameter"), lt.diameter)?;
            positive(p, &f("mass_per_length"), lt.mass_per_length)?;
            positive(p, &f("ea"), lt.ea)?;
            non_negative(p, &f("damping"), lt.damping)?;
            non_negative(p, &f("cn"), lt.cn)?;
            non_negative(p, &f("ct"), lt.ct)?;
            non_negative(p, &f("cm"), lt.cm)?;
            non_negative(p, &f("ei"), lt.ei)?;
            if lt_index.insert(lt.name.clone(), i).is_some() {
                return Err(err(
                    p,
                    format!("line_types[{i}].name"),
                    format!("duplicate line type name \"{}\"", lt.name),
                ));
            }
        }
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
        let bodies = bodies::parse(p, &raw.bodies, &sea.components, sea.ramp_duration)?;

        // [[points]]: named shared nodes.
        let mut point_index: HashMap<String, usize> = HashMap::new();
        let mut named_points = Vec::with_capacity(raw.points.len());
        // (field, node, free) of each point, for the check of unused points.
        let mut point_fields = Vec::with_capacity(raw.points.len());
        for (i, t) in raw.points.iter().enumerate() {
            let field = format!("points[{i}]");
            let name = match t.get("name") {
                Some(toml::Value::String(s)) => s.clone(),
                _ => {
                    return Err(err(
                        p,
                        format!("{field}.name"),
                        "every point needs a string `name`",
                    ))
                }
            };
            let field = format!("points[{i}] (\"{name}\")");
            let spec = ends::parse_end(p, &field, t, &["name"], &HashMap::new(), &bodies)?;
            let free = matches!(spec.kind, EndKind::Free(_));
            let (position, route, point) = match spec.kind {
                EndKind::Point(_) => {
                    return Err(err(p, field, "a point cannot refer to another point"))
                }
                EndKind::Fixed(x) | EndKind::Free(x) => (x, spec.route, spec.mass),
                EndKind::Route => (
                    spec.route
                        .as_ref()
                        .map(|r| r.eval(0.0).r)
                        .unwrap_or([0.0; 3]),
                    spec.route,
                    spec.mass,
                ),
            };
            validate::position(p, &field, position)?;
            validate::height(p, &field, position[2], depth)?;
            if let Some(r) = &route {
                validate::route_speed(p, &field, r, sim.max_speed)?;
            }
            point_fields.push((field.clone(), model.nodes.len(), free));
            named_points.push(NamedPoint {
                name: name.clone(),
                node: model.nodes.len(),
            });
            if point_index
                .insert(name.clone(), model.nodes.len())
                .is_some()
            {
                return Err(err(
                    p,
                    format!("{field}.name"),
                    format!("duplicate point name \"{name}\""),
                ));
            }
            model.nodes.push(NodeDef {
                position,
                point,
                route,
                label: Some(name),
            });
        }

        // [[cables]]
        let mut initial = Vec::with_capacity(cables.len());
        let mut winches = Vec::new();
        let mut names = HashMap::new();
        let many = cables.len() > 20;
        let positions_sel = output_selection(p, &raw.output.positions)?;
        for (i, (prefix, c)) in cables.iter().enumerate() {
            let f = |k: &str| format!("{prefix}.{k}");
            if names.insert(c.name.clone(), i).is_some() {
                return Err(err(
                    p,
                    f("name"),
                    format!("duplicate cable name \"{}\"", c.name),
                ));
            }
            let &lt = lt_index.get(&c.line_type).ok_or_else(|| {
                let mut known: Vec<_> = lt_index.keys().cloned().collect();
                known.sort();
                err(
                    p,
                    f("line_type"),
                    format!(
                        "unknown line type \"{}\" (defined: {})",
                        c.line_type,
                        known.join(", ")
                    ),
                )
            })?;
            let length = positive(p, &f("length"), c.length)?;
            validate::magnitude(p, &f("length"), length, "m")?;
            if c.segments < 1 || c.segments > 1_000_000 {
                return Err(err(
                    p,
                    f("segments"),
                    format!("must be an integer from 1 to 1000000, got {}", c.segments),
                ));
            }
            let n = c.segments as usize;
            let shape = match c.initial.as_deref() {
                None | Some("straight") => InitialShape::Straight,
                Some("catenary") => InitialShape::Catenary,
                Some(x) => {
                    return Err(err(
                        p,
                        f("initial"),
                        format!("must be \"catenary\" or \"straight\", got \"{x}\""),
                    ))
                }
            };
            let cur = match current(p, &format!("{prefix}."), c.current, &c.current_profile)? {
                Some(cu) => {
                    model.currents.push(cu);
                    model.currents.len() - 1
                }
                None => 0,
            };
            let start = ends::parse_end(p, &f("start"), &c.start, &[], &point_index, &bodies)?;
            let end = ends::parse_end(p, &f("end"), &c.end, &[], &point_index, &bodies)?;
            if let Some(w) = &c.winch {
                winches.push(winch::parse(
                    p,
                    &format!("cables[{i}] (\"{}\")", c.name),
                    w,
                    i,
                    length,
                    n,
                    [&start.kind, &end.kind],
                )?);
            }
            let mut ids = [0usize; 2];
            let mut pos = [[0.0; 3]; 2];
            for (k, spec) in [start, end].into_iter().enumerate() {
                if !matches!(spec.kind, EndKind::Point(_)) {
                    let which = if k == 0 { "start" } else { "end" };
                    let x = match (&spec.kind, &spec.route) {
                        (EndKind::Fixed(x) | EndKind::Free(x), _) => *x,
                        (_, Some(r)) => r.eval(0.0).r,
                        _ => [0.0; 3],
                    };
                    validate::position(p, &f(which), x)?;
                    validate::height(p, &f(which), x[2], depth)?;
                    if let Some(r) = &spec.route {
                        validate::route_speed(p, &f(which), r, sim.max_speed)?;
                    }
                }
                match spec.kind {
                    EndKind::Point(idx) => {
                        ids[k] = idx;
                        pos[k] = model.nodes[idx].position;
                    }
                    EndKind::Fixed(x) | EndKind::Free(x) => {
                        ids[k] = model.nodes.len();
                        pos[k] = x;
                        model.nodes.push(NodeDef {
                            position: x,
                            point: spec.mass,
                            route: spec.route,
                            label: None,
                        });
                    }
                    EndKind::Route => {
                        let r = spec.route.expect("route ends carry a route");
                        pos[k] = r.eval(0.0).r;
                        ids[k] = model.nodes.len();
                        model.nodes.push(NodeDef {
                            position: pos[k],
                            point: spec.mass,
                            route: Some(r),
                            label: None,
                        });
                    }
                }
            }
            if ids[0] == ids[1] {
                return Err(err(
                    p,
                    f("end"),
                    "a cable cannot start and end at the same point",
                ));
            }
            if shape == InitialShape::Straight {
                let ea = model.line_types[lt].ea;
                validate::straight_strain(p, &prefix.to_string(), length, ea, pos[0], pos[1]);
            }
            let mut nodes = Vec::with_capacity(n + 1);
            nodes.push(ids[0]);
            for k in 1..n {
                let s = k as f64 / n as f64;
                let x = [0, 1, 2].map(|d| pos[0][d] + s * (pos[1][d] - pos[0][d]));
                nodes.push(model.nodes.len());
                model.nodes.push(NodeDef {
                    position: x,
                    point: PointMass::default(),
                    route: None,
                    label: None,
                });
            }
            nodes.push(ids[1]);
            let output_positions = c.output_positions.unwrap_or(match &positions_sel {
                Selection::All => true,
                Selection::None => false,
                Selection::Auto => !many,
                Selection::Names(v) => v.contains(&c.name),
            });
            model.cables.push(CableDef {
                name: c.name.clone(),
                line_type: lt,
                nodes,
                l0: vec![length / n as f64; n],
                current: cur,
                output_positions,
            });
            initial.push(shape);
        }
        // [[nets]]
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
            add_net(&mut model, &spec).map_err(|e| err(p, &field, e.to_string()))?;
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
            if let Some((f, _, _)) = point_fields.iter().find(|(_, k, _)| *k == n) {
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
            (baumgarte.alpha, baumgarte.beta),
        )?;
        validate::unused_points(p, &model, &point_fields)?;
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
        Ok(Scenario {
            path: p.to_path_buf(),
            sim,
            model,
            initial,
            winches,
            ancf: ancf_settings(p, &raw.ancf)?,
            sea,
            member_seas: None,
            depth_bands: e.waves.as_ref().and_then(|w| w.depth_bands).unwrap_or(true),
            points: named_points,
            vtk: raw.output.vtk.unwrap_or(false),
            limits,
        })
    }
}

/// The `[ancf]` table, validated.
fn ancf_settings(p: &Path, a: &raw::RawAncf) -> Result<AncfSettings, Error> {
    let mut s = AncfSettings::default();
    if let Some(l) = a.element_length {
        s.element_length = Some(positive(p, "ancf.element_length", l)?);
    }
    if let Some(n) = a.gauss_points {
        if !(1..=16).contains(&n) {
            return Err(err(
                p,
                "ancf.gauss_points",
                format!("must be between 1 and 16, got {n}"),
            ));
        }
        s.gauss_points = n as usize;
    }
    if let Some(m) = a.added_mass {
        s.added_mass = m;
    }
    Ok(s)
}

enum Selection {
    Auto,
    All,
    None,
    Names(Vec<String>),
}

fn output_selection(p: &Path, v: &Option<toml::Value>) -> Result<Selection, Error> {
    let f = "output.positions";
    Ok(match v {
        None => Selection::Auto,
        Some(toml::Value::String(s)) => match s.as_str() {
            "auto" => Selection::Auto,
            "all" => Selection::All,
            "none" => Selection::None,
            _ => {
                return Err(err(
                    p,
                    f,
                    format!(
                        "must be \"auto\", \"all\", \"none\" or a list of cable names, got \"{s}\""
                    ),
                ))
            }
        },
        Some(toml::Value::Array(a)) => Selection::Names(
            a.iter()
                .map(|x| {
                    x.as_str()
                        .map(str::to_string)
                        .ok_or_else(|| err(p, f, "list entries must be cable names (strings)"))
                })
                .collect::<Result<_, _>>()?,
        ),
        Some(_) => {
            return Err(err(
                p,
                f,
                "must be \"auto\", \"all\", \"none\" or a list of cable names",
            ))
        }
    })
}

#[cfg(test)]
mod message_tests {
    use super::*;

    #[test]
    fn numbers_in_messages_are_short() {
        assert_eq!(show(9.81), "9.81");
        assert_eq!(show(-1e160), "-1e160");
        assert_eq!(show(2.5e-200), "2.5e-200");
        assert_eq!(show(0.0), "0");
        let e = non_negative(Path::new("m.toml"), "environment.gravity", -1e160).unwrap_err();
        let text = e.to_string();
        assert!(text.ends_with("must not be negative, got -1e160"), "{text}");
    }
}
