//! Runs a scenario with the ANCF reference model (`formulation = "ancf"` in
//! `[simulation]`, or `cablesim run --formulation ancf`): every cable of the scenario
//! becomes an [`AncfCable`] (ALE-ANCF with its winch), stepped on the CPU in f64 and
//! written out in the same files and formats as a lumped-mass run, so that the two
//! models of one scenario can be compared line by line.
//!
//! # What maps to what
//! - Mesh: elements of `[ancf] element_length` (default: the cable's own lumped-mass
//!   element length), `ceil(length / element_length)` equal elements; with a winch the
//!   same length is the standard length `l_s` of the remeshing rules.
//! - Ends: a fixed or route end is a prescribed position (its slope free: pinned); a
//!   free end carries its point mass. Inner nodes (shared `[[points]]`, networks) are
//!   not supported: the ANCF reference is a model of single cables.
//! - Line type, environment, current: the cable's; `ei` of the line type is the
//!   bending stiffness (0 when not given).
//! - Initial shape: `straight` as the lumped-mass model's; `catenary` the analytic
//!   elastic catenary (on a fine polyline: the lumped-mass nodes' kink at the
//!   touchdown would give cubic elements large spurious strains), then brought to the
//!   ANCF's own static equilibrium, so a line whose ends hold still stays still. Where
//!   that Newton solve stalls (Gauss points slipping in and out of seabed contact) the
//!   run starts from the catenary with a warning.
//! - Step: `dt = "auto"` takes [`crate::stability::AUTO_SAFETY`] of each cable's stable step (with a winch,
//!   of its worst mesh), rounded down to divide the output interval; a given `dt` is
//!   used for every cable, with a warning when it is above a cable's stable step.
//! - Outputs: `positions.csv` has the ANCF nodes (fewer than the lumped mass's: the
//!   last node is the cable's end in both); `tensions.csv` gives per element the mean
//!   of its two node tensions ([`AncfCable::node_tensions`]); `end_forces.csv` the
//!   force on each held end (zero at a free end); `winches.csv` and `summary.json` as
//!   for the lumped-mass model.

use super::{AddedMass, AncfCable, AncfConfig, AncfEnd, StaticOptions};
use crate::error::Error;
use crate::model::ModelDef;
use crate::output::{CableSummary, EndForces, Summary, WinchSummary};
use crate::physics::catenary::catenary_positions;
use crate::scenario::{DtSpec, InitialShape, Scenario};
use crate::sim::RunOptions;
use rayon::prelude::*;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::time::Instant;

/// The `[ancf]` table of a scenario.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AncfSettings {
    /// Element length, m (`None`: each cable's lumped-mass element length).
    pub element_length: Option<f64>,
    /// Gauss points per element.
    pub gauss_points: usize,
    /// How the added mass enters the mass matrix.
    pub added_mass: AddedMass,
}

impl Default for AncfSettings {
    fn default() -> Self {
        Self {
            element_length: None,
            gauss_points: 5,
            added_mass: AddedMass::Normal,
        }
    }
}

/// One cable of the run.
struct Runner {
    cable: AncfCable,
    /// Steps per output interval.
    per_output: u64,
    /// Whether its node positions are written (`output_positions`).
    positions: bool,
}

fn unsupported(sc: &Scenario, ci: usize, what: String) -> Error {
    Error::Model(format!(
        "{}: cable '{}': the ANCF model {what}; run it with the lumped-mass model (formulation = \"glmf\")",
        sc.path.display(),
        sc.model.cables[ci].name
    ))
}

/// How many cable node lists each described node of `def` appears in.
pub fn node_uses(def: &ModelDef) -> Vec<u32> {
    let mut uses = vec![0u32; def.nodes.len()];
    for c in &def.cables {
        for &n in &c.nodes {
            uses[n] += 1;
        }
    }
    uses
}

/// The ANCF configuration of cable `ci` (see the module doc); `uses` is
/// [`node_uses`]`(&sc.model)`.
pub fn cable_config(
    sc: &Scenario,
    settings: &AncfSettings,
    ci: usize,
    uses: &[u32],
) -> Result<AncfConfig, Error> {
    let def: &ModelDef = &sc.model;
    let c = &def.cables[ci];
    for (k, &n) in c.nodes.iter().enumerate() {
        let inner = k > 0 && k + 1 < c.nodes.len();
        let nd = &def.nodes[n];
        if uses[n] > 1 {
            let label = nd.label.clone().unwrap_or_else(|| format!("node {n}"));
            return Err(unsupported(
                sc,
                ci,
                format!("runs single cables, and this one shares '{label}' with another cable"),
            ));
        }
        if inner && (nd.route.is_some() || nd.point.mass > 0.0 || nd.point.volume > 0.0) {
            return Err(unsupported(
                sc,
                ci,
                format!("takes point masses and routes at the ends only (inner node {k})"),
            ));
        }
    }
    let length: f64 = c.l0.iter().sum();
    let l_std = settings
        .element_length
        .unwrap_or(length / c.l0.len() as f64);
    let elements = ((length / l_std) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
    let end = |n: usize| {
        let nd = &def.nodes[n];
        let e = match &nd.route {
            Some(r) => AncfEnd::driven(r.clone()),
            None => AncfEnd::free(nd.position),
        };
        e.with_point(nd.point)
    };
    let mut cfg = AncfConfig::new(
        def.line_types[c.line_type].clone(),
        length,
        elements,
        end(c.nodes[0]),
        end(*c.nodes.last().expect("a cable has nodes")),
        def.env,
    );
    cfg.name = c.name.clone();
    cfg.current = def.currents[c.current].clone();
    cfg.gauss_points = settings.gauss_points;
    cfg.added_mass = settings.added_mass;
    cfg.max_speed = sc.sim.max_speed;
    cfg.winch = sc.winches.iter().find(|w| w.cable == ci).map(|w| {
        let mut w = w.clone();
        w.element_length = l_std;
        w
    });
    Ok(cfg)
}

/// Checks that every cable of `sc` can run with the ANCF model; returns per cable its
/// name, element count and stable step (s) with what sets it.
pub fn check(
    sc: &Scenario,
    settings: &AncfSettings,
) -> Result<Vec<(String, usize, f64, String)>, Error> {
    let uses = node_uses(&sc.model);
    (0..sc.model.cables.len())
        .map(|ci| {
            let mut cfg = cable_config(sc, settings, ci, &uses)?;
            cfg.scheme = sc.sim.scheme;
            let c = AncfCable::new(cfg)?;
            let (dt, term) = c.stable_dt();
            Ok((c.name().to_string(), c.n_elements(), dt, term.to_string()))
        })
        .collect()
}

/// Position at arc length `s` along the polyline `pts` whose segments have unstretched
/// lengths `l0` (linear between nodes, and extended straight beyond the ends, so that
/// the central differences giving the end slopes see the end segments).
fn along(pts: &[[f64; 3]], l0: &[f64], s: f64) -> [f64; 3] {
    let mut x = s;
    for (k, &l) in l0.iter().enumerate() {
        if x <= l || k + 1 == l0.len() {
            let u = x / l;
            let (a, b) = (pts[k], pts[k + 1]);
            return [0, 1, 2].map(|i| a[i] + u * (b[i] - a[i]));
        }
        x -= l;
    }
    unreachable!("a cable has elements")
}

/// Runs `sc` with the ANCF model to the end, writing output as it goes (module doc).
pub fn run(sc: &Scenario, ro: &RunOptions, settings: &AncfSettings) -> Result<Summary, Error> {
    let wall0 = Instant::now();
    let ov = &ro.overrides;
    let scheme = ov.scheme.unwrap_or(sc.sim.scheme);
    let duration = ov.duration.unwrap_or(sc.sim.duration);
    let dt_spec = ov.dt.map(DtSpec::Fixed).unwrap_or(sc.sim.dt);
    let oi = sc.sim.output_interval;
    if ov.precision.is_some() || sc.sim.precision.is_some() {
        log::warn!("the ANCF model runs on the CPU in f64: precision is ignored");
    }
    // The lumped-mass initial state (relaxed catenaries included) gives the shapes.
    let (lay, pos, relax_residual) = crate::sim::prepare(sc)?;
    let uses = node_uses(&sc.model);
    // Per-cable lines at info level only for a few cables.
    let level = if sc.model.cables.len() <= 20 {
        log::Level::Info
    } else {
        log::Level::Debug
    };
    // Cables are set up (static solves included) one per thread.
    let build = |ci: usize| -> Result<Runner, Error> {
        let mut cfg = cable_config(sc, settings, ci, &uses)?;
        cfg.scheme = scheme;
        let info = &lay.cables[ci];
        let pts: Vec<[f64; 3]> = info.nodes.iter().map(|&n| pos[n as usize]).collect();
        let l0: Vec<f64> = info
            .elements
            .iter()
            .map(|&e| lay.elem_l0[e as usize])
            .collect();
        let mut cable = AncfCable::new(cfg)?;
        let (stable, term) = cable.stable_dt();
        let term = term.to_string();
        let (dt, per_output) = crate::sim::fit_step(sc, dt_spec, stable)?;
        if matches!(dt_spec, DtSpec::Fixed(_)) && dt > stable {
            log::warn!(
                "cable '{}': dt = {dt} s is above the ANCF stable step {stable:.4e} s ({term}); expect a blow-up",
                cable.name()
            );
        }
        cable.set_dt(dt);
        if sc.initial[ci] == InitialShape::Catenary {
            // The analytic elastic catenary on a fine polyline: the lumped-mass nodes'
            // kinks (touchdown) would give the cubic elements large spurious strains.
            let lt = &sc.model.line_types[sc.model.cables[ci].line_type];
            let env = &sc.model.env;
            let w = lt.wet_weight_per_length(env.gravity, env.water_density);
            let length: f64 = l0.iter().sum();
            let n_fine = 64 * cable.n_elements();
            let fine = catenary_positions(
                pts[0],
                pts[pts.len() - 1],
                length,
                n_fine,
                lt.ea,
                w,
                -env.depth,
            );
            let fl = vec![length / n_fine as f64; n_fine];
            cable.set_shape(|s| along(&fine, &fl, s));
        } else {
            cable.set_shape(|s| along(&pts, &l0, s));
        }
        if sc.initial[ci] == InitialShape::Catenary {
            let mut trial = cable.clone();
            match trial.solve_static(&StaticOptions::default()) {
                Ok(rep) => {
                    log::log!(
                        level,
                        "cable '{}': ANCF static equilibrium in {} Newton iterations, residual {:.3e} N",
                        info.name,
                        rep.iterations,
                        rep.max_residual
                    );
                    cable = trial;
                }
                // Newton can stall where Gauss points slip in and out of seabed
                // contact; the analytic catenary is then a close start.
                Err(e) => log::warn!(
                    "cable '{}': {e}; starting from the analytic catenary instead (expect a short transient)",
                    info.name
                ),
            }
        }
        log::log!(
            level,
            "cable '{}': ANCF, {} elements, dt = {dt:.4e} s (stable {stable:.4e} s: {term})",
            info.name,
            cable.n_elements()
        );
        Ok(Runner {
            cable,
            per_output,
            positions: sc.model.cables[ci].output_positions,
        })
    };
    let mut runners: Vec<Runner> = (0..sc.model.cables.len())
        .into_par_iter()
        .map(build)
        .collect::<Result<_, _>>()?;
    log::info!(
        "ANCF: {} cables, {} nodes",
        runners.len(),
        runners.iter().map(|r| r.cable.n_nodes()).sum::<usize>()
    );

    let mut out = Files::create(
        &ro.out_dir,
        sc.winches.is_empty(),
        runners.iter().any(|r| r.positions),
    )?;
    // Whole output intervals, then what is left of the duration (each cable at its own
    // step, the lumped-mass plan's rounding: `round(duration / dt)` steps in all).
    let outputs = (duration / oi + 1e-9).floor() as u64;
    let tail: Vec<u64> = runners
        .iter()
        .map(|r| {
            let total = (duration / r.cable.dt()).round().max(1.0) as u64;
            total.saturating_sub(outputs * r.per_output)
        })
        .collect();
    let has_tail = tail.iter().any(|&n| n > 0);
    let bar = if ro.progress {
        let b = indicatif::ProgressBar::new(outputs + u64::from(has_tail));
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {percent}% t = {msg} (eta {eta})",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        b
    } else {
        indicatif::ProgressBar::hidden()
    };
    out.frame(0.0, &mut runners)?;
    let mut stepping = 0.0;
    let mut result = Ok(());
    let mut reached = 0.0;
    for k in 1..=outputs + u64::from(has_tail) {
        let last = k > outputs;
        let t0 = Instant::now();
        // Cables are independent: one thread each.
        let r: Result<(), Error> = runners
            .par_iter_mut()
            .zip(&tail)
            .try_for_each(|(c, &n)| c.cable.advance(if last { n } else { c.per_output }));
        stepping += t0.elapsed().as_secs_f64();
        let t = if last { duration } else { k as f64 * oi };
        bar.set_position(k);
        bar.set_message(format!("{t:.2} s"));
        if let Err(e) = r {
            result = Err(e);
            break;
        }
        reached = t;
        out.frame(t, &mut runners)?;
    }
    bar.finish_and_clear();
    out.flush()?;

    let node_steps: f64 = runners
        .iter()
        .map(|r| r.cable.steps() as f64 * r.cable.n_nodes() as f64)
        .sum();
    let mut cables = Vec::new();
    for r in &mut runners {
        let c = &mut r.cable;
        let tensions = c.node_tensions().unwrap_or_default();
        let ef = c.end_forces().unwrap_or([None, None]);
        let winch = c.variable_length().map(|variable_l0| {
            let (inserted, deleted) = c.remeshes();
            WinchSummary {
                deployed_length: c.length(),
                variable_l0,
                elements: c.n_elements(),
                nodes_inserted: inserted,
                nodes_deleted: deleted,
                physical_coordinates: c.physical_coordinates().unwrap_or_default(),
            }
        });
        cables.push(CableSummary {
            name: c.name().to_string(),
            winch,
            final_positions: c.node_positions(),
            final_tensions: tensions.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect(),
            end_forces: EndForces {
                start: ef[0].unwrap_or([0.0; 3]),
                end: ef[1].unwrap_or([0.0; 3]),
            },
        });
    }
    let steps = runners.iter().map(|r| r.cable.steps()).max().unwrap_or(0);
    let dt = runners
        .iter()
        .map(|r| r.cable.dt())
        .fold(f64::INFINITY, f64::min);
    let (dt_stable, term) = runners.iter().map(|r| r.cable.stable_dt()).fold(
        (f64::INFINITY, String::new()),
        |a, (d, t)| {
            if d < a.0 {
                (d, t.to_string())
            } else {
                a
            }
        },
    );
    let summary = Summary {
        status: if result.is_ok() {
            "completed".into()
        } else {
            "diverged".into()
        },
        error: result.as_ref().err().map(|e: &Error| e.to_string()),
        scenario: sc.path.display().to_string(),
        backend: "cpu".into(),
        device: crate::sim::cpu_name(),
        precision: "f64".into(),
        scheme: scheme.name().into(),
        formulation: "ancf".into(),
        steps,
        dt,
        dt_stable,
        dt_limited_by: term,
        simulated_time: reached,
        wall_seconds: stepping,
        total_wall_seconds: wall0.elapsed().as_secs_f64(),
        nodes: runners.iter().map(|r| r.cable.n_nodes()).sum(),
        elements: runners.iter().map(|r| r.cable.n_elements()).sum(),
        node_steps_per_second: if stepping > 0.0 {
            node_steps / stepping
        } else {
            0.0
        },
        threads: rayon::current_num_threads(),
        relax_residual,
        cables,
    };
    out.summary(&summary)?;
    result.map(|_| summary)
}

/// The output files of an ANCF run (the formats of [`crate::output`]).
struct Files {
    dir: std::path::PathBuf,
    end_forces: BufWriter<File>,
    tensions: BufWriter<File>,
    positions: Option<BufWriter<File>>,
    winches: Option<BufWriter<File>>,
}

fn io_err(dir: &Path, name: &str) -> impl Fn(std::io::Error) -> Error {
    let path = dir.join(name);
    move |source| Error::Output {
        path: path.clone(),
        source,
    }
}

impl Files {
    fn create(dir: &Path, no_winch: bool, positions: bool) -> Result<Self, Error> {
        std::fs::create_dir_all(dir).map_err(io_err(dir, ""))?;
        let open = |name: &str, header: &str| -> Result<BufWriter<File>, Error> {
            let mut f = BufWriter::new(File::create(dir.join(name)).map_err(io_err(dir, name))?);
            writeln!(f, "{header}").map_err(io_err(dir, name))?;
            Ok(f)
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            end_forces: open("end_forces.csv", "time,cable,end,fx,fy,fz")?,
            tensions: open("tensions.csv", "time,cable,element,tension")?,
            positions: if positions {
                Some(open("positions.csv", "time,cable,node,x,y,z")?)
            } else {
                None
            },
            winches: if no_winch {
                None
            } else {
                Some(open(
                    "winches.csv",
                    "time,cable,deployed_length,variable_l0,elements",
                )?)
            },
        })
    }

    fn frame(&mut self, t: f64, runners: &mut [Runner]) -> Result<(), Error> {
        for r in runners.iter_mut() {
            let c = &mut r.cable;
            let name = c.name().to_string();
            let ef = c.end_forces()?;
            let tn = c.node_tensions()?;
            let d = self.dir.clone();
            for (k, which) in ["start", "end"].iter().enumerate() {
                let f = ef[k].unwrap_or([0.0; 3]);
                writeln!(
                    self.end_forces,
                    "{t},{name},{which},{},{},{}",
                    f[0], f[1], f[2]
                )
                .map_err(io_err(&d, "end_forces.csv"))?;
            }
            for (k, w) in tn.windows(2).enumerate() {
                writeln!(self.tensions, "{t},{name},{k},{}", 0.5 * (w[0] + w[1]))
                    .map_err(io_err(&d, "tensions.csv"))?;
            }
            if let (Some(p), true) = (self.positions.as_mut(), r.positions) {
                for (k, x) in c.node_positions().iter().enumerate() {
                    writeln!(p, "{t},{name},{k},{},{},{}", x[0], x[1], x[2])
                        .map_err(io_err(&d, "positions.csv"))?;
                }
            }
            if let (Some(w), Some(var)) = (self.winches.as_mut(), c.variable_length()) {
                writeln!(w, "{t},{name},{},{var},{}", c.length(), c.n_elements())
                    .map_err(io_err(&d, "winches.csv"))?;
            }
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), Error> {
        let d = self.dir.clone();
        self.end_forces
            .flush()
            .map_err(io_err(&d, "end_forces.csv"))?;
        self.tensions.flush().map_err(io_err(&d, "tensions.csv"))?;
        if let Some(p) = self.positions.as_mut() {
            p.flush().map_err(io_err(&d, "positions.csv"))?;
        }
        if let Some(w) = self.winches.as_mut() {
            w.flush().map_err(io_err(&d, "winches.csv"))?;
        }
        Ok(())
    }

    fn summary(&self, s: &Summary) -> Result<(), Error> {
        crate::output::write_summary(&self.dir, s)
    }
}
