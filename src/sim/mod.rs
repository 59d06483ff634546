//! The run pipeline and the library API: [`Simulation`].
//!
//! One pipeline, one driver: [`Simulation`] (its doc lists the stages in order).
//!
//! ```no_run
//! use cablesim::{MemorySink, Overrides, Simulation};
//!
//! let mut sim = Simulation::from_file("examples/catenary.toml", &Overrides::default())?;
//! sim.advance_to(10.0)?; // s
//! let now = sim.snapshot()?;
//! println!("top tension {} N", now.cables[0].tensions.last().unwrap());
//! let mut sink = MemorySink::new();
//! let summary = sim.run(&mut sink, |_| {})?; // on to the scenario's duration
//! # Ok::<(), cablesim::Error>(())
//! ```
//!
//! The library prints nothing: it logs through the `log` crate, and progress goes to
//! the callback of [`Simulation::run`].

pub mod ancf;
pub mod backend;
pub mod budget;
pub mod estimate;
pub mod pack;
pub mod plan;
pub mod reach;

pub use crate::initial::prepare;
pub use crate::options::Overrides;
pub use crate::output::{FileSink, MemorySink, Snapshot, Summary};
pub use backend::{choose_backend, cpu_name, BackendChoice, CableEnd};
pub use plan::{fit_step, plan_steps, StepPlan};

use crate::error::Error;
use crate::options::{CableModel, Formulation, Scheme, SolverOptions};
use crate::output::{Extremes, OutputSink};
use crate::scenario::{Backend, DtSpec, Scenario};
use ancf::AncfFleet;
use backend::LumpedStepper;
use plan::output_time;
use reach::ReachWatch;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// How [`run`] carries out a run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Output directory.
    pub out_dir: PathBuf,
    /// Overrides of scenario settings.
    pub overrides: Overrides,
    /// Log the simulated time reached at each output time (info level).
    pub progress: bool,
}

/// Runs a scenario to the end, writing its files into `ro.out_dir` ([`FileSink`]).
pub fn run(sc: &Scenario, ro: &RunOptions) -> Result<Summary, Error> {
    let mut sim = Simulation::new(sc.clone(), &ro.overrides)?;
    let log_progress = ro.progress;
    let mut sink = FileSink::new(&ro.out_dir).format(sc.output_format)?;
    sim.run(&mut sink, |p: Progress| {
        if log_progress && p.at_output {
            log::info!("t = {:.2} s ({} of {} steps)", p.time, p.done, p.total);
        }
    })
}

/// Where a run stands, as [`Simulation::run`] reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Simulated time, s.
    pub time: f64,
    /// Work done: steps (lumped mass) or output intervals (ANCF).
    pub done: u64,
    /// Work of the whole run, in the units of `done`.
    pub total: u64,
    /// Whether the run has just reached an output time.
    pub at_output: bool,
}

/// The backend of a simulation.
enum Engine {
    /// Lumped mass on the CPU or the GPU, with its step plan.
    Lumped(Box<LumpedStepper>, StepPlan),
    /// The ANCF reference model, each cable at its own step.
    Ancf(AncfFleet),
}

/// A scenario being simulated: the library's entry point, and the run pipeline's one
/// driver.
///
/// The stages of the pipeline, in order:
/// 1. **Scenario** ([`crate::scenario::Scenario`]): a TOML file or string, validated,
///    with the caller's [`Overrides`] (backend, precision, scheme, formulation, step,
///    duration) applied over its `[simulation]` table ([`crate::options`]).
/// 2. **Model**: the [`crate::model::ModelDef`] the scenario describes, packed into a
///    [`crate::model::Layout`] (flat arrays over every cable of the run).
/// 3. **Initial state** ([`crate::initial`]): straight lines, or catenaries relaxed to
///    the discrete static equilibrium ([`crate::statics`]).
/// 4. **Step plan** ([`plan`]): the time step from the stability bound
///    ([`crate::stability`]) and the output interval, steps per output, total steps;
///    winch schedules followed over it before anything runs.
/// 5. **Backend** ([`backend`], [`ancf`]): the f64 CPU reference ([`crate::cpu`]), the
///    GPU path ([`crate::gpu`]), or the ANCF reference model ([`crate::ancf`]), stepped
///    behind one interface; step results and the blow-up check are [`crate::step`]'s.
/// 6. **Output sink** ([`crate::output::OutputSink`]): at each output time a
///    [`Snapshot`] goes to the sink the caller chose (files: [`FileSink`], memory:
///    [`MemorySink`], or its own), and the [`Summary`] at the end.
///
/// Build it from a file, a TOML string or a [`Scenario`], advance it by steps
/// or to a time, read its state ([`Simulation::snapshot`] and the getters), drive a
/// held end from outside between steps ([`Simulation::set_end_motion`]), or run it to
/// the end into an [`OutputSink`].
pub struct Simulation {
    scenario: Scenario,
    engine: Engine,
    scheme: Scheme,
    formulation: Formulation,
    model: CableModel,
    relax_residual: f64,
    /// When the build began (the summary's total wall time).
    started: Instant,
    /// Wall time spent stepping, s.
    stepping: f64,
    /// The `[[points]]` that cables attach to: `(name, cable, at its start)`, a cable
    /// end on each (cable ends keep their place when a winch remeshes).
    points: Vec<(String, usize, bool)>,
    /// The check that no node rises above its sea's reach (lumped mass in waves).
    reach_watch: Option<ReachWatch>,
    /// The summary's per-cable part, followed over every snapshot taken.
    extremes: Extremes,
}

impl Simulation {
    /// Reads a scenario file (TOML, or a MoorDyn input file) and builds its simulation.
    pub fn from_file(path: impl AsRef<Path>, overrides: &Overrides) -> Result<Self, Error> {
        let started = Instant::now();
        let sc = Scenario::load_any(path)?;
        Self::build(sc, overrides, started)
    }

    /// Builds the simulation of scenario text `toml`; `path` names it in messages and
    /// summaries, and relative route files are read beside it.
    pub fn from_toml(
        toml: &str,
        path: impl AsRef<Path>,
        overrides: &Overrides,
    ) -> Result<Self, Error> {
        let started = Instant::now();
        let sc = Scenario::parse(toml, path.as_ref())?;
        Self::build(sc, overrides, started)
    }

    /// Builds the simulation of a validated scenario.
    pub fn new(scenario: Scenario, overrides: &Overrides) -> Result<Self, Error> {
        Self::build(scenario, overrides, Instant::now())
    }

    fn build(mut sc: Scenario, ov: &Overrides, started: Instant) -> Result<Self, Error> {
        let model = ov.model.unwrap_or(sc.sim.model);
        let backend = ov.backend.unwrap_or(sc.sim.backend);
        let precision = ov.precision.or(sc.sim.precision);
        let scheme = ov.scheme.unwrap_or(sc.sim.scheme);
        let formulation = ov.formulation.unwrap_or(sc.sim.formulation);
        let duration = ov.duration.unwrap_or(sc.sim.duration);
        let dt_spec = ov.dt.map(DtSpec::Fixed).unwrap_or(sc.sim.dt);
        if model == CableModel::Ancf && backend == Backend::Gpu {
            return Err(Error::GpuUnsupported(
                "the ANCF model (CPU only); use --backend cpu (or auto)".into(),
            ));
        }
        if model == CableModel::Ancf && precision.is_some() {
            log::warn!("the ANCF model runs on the CPU in f64: precision is ignored");
        }
        let (mut lay, mut pos) = crate::model::Layout::build(&sc.model)?;
        let mut opts = SolverOptions {
            formulation,
            scheme,
            baumgarte: sc.sim.baumgarte,
            max_speed: sc.sim.max_speed,
            ..SolverOptions::default()
        };
        // The step plan and its budget before the static solves: work refused costs
        // nothing (the plan depends on the layout's constants, not on positions).
        let plan = match model {
            CableModel::LumpedMass => Some(plan_steps(&sc, &lay, &opts, duration, dt_spec)?),
            CableModel::Ancf => None,
        };
        let relax_residual = crate::initial::apply(&sc, &mut lay, &mut pos)?;
        let mut reach_watch = None;
        let engine = match model {
            CableModel::Ancf => {
                budget::check_output(&sc, duration)?;
                log::info!("backend cpu: the ANCF model runs on the CPU in f64");
                Engine::Ancf(AncfFleet::new(
                    &sc, &sc.ancf, scheme, duration, dt_spec, &lay, &pos,
                )?)
            }
            CableModel::LumpedMass => {
                let plan = plan.expect("planned above");
                if let Some(w) = &plan.warning {
                    log::warn!("{w}");
                }
                log::info!(
                    "{} nodes, {} elements, {} cables; dt = {:.4e} s (stable {:.4e} s, set by {}); {} steps",
                    lay.n_nodes(),
                    lay.n_elements(),
                    lay.cables.len(),
                    plan.dt,
                    plan.bound.dt,
                    plan.bound.term,
                    plan.total_steps
                );
                opts.dt = plan.dt;
                let choice = choose_backend(backend, precision, &lay, &opts, &sc)?;
                let path = match &choice {
                    BackendChoice::Cpu => estimate::Path::Cpu(rayon::current_num_threads()),
                    BackendChoice::Gpu(ctx, _) if ctx.info.device_type == wgpu::DeviceType::Cpu => {
                        estimate::Path::GpuSoftware
                    }
                    BackendChoice::Gpu(_, p) => estimate::Path::Gpu(*p),
                };
                let est =
                    estimate::lumped(&lay, &opts, plan.total_steps, budget::in_waves(&sc), path);
                log::info!("work: {}", est.describe());
                log::debug!(
                    "step plan: {} steps of {:e} s per output interval of {} s, scheme {}, formulation {}, {} thread(s)",
                    plan.steps_per_output,
                    plan.dt,
                    sc.sim.output_interval,
                    opts.scheme.name(),
                    opts.formulation.name(),
                    rayon::current_num_threads()
                );
                let mut seas = sc.sea_set();
                if !seas.is_still() {
                    seas.reach = reach::sea_reach(&lay, &pos, &seas, duration);
                    // Refresh per depth band (`sea::bands`, on both paths) unless the
                    // scenario says not to.
                    seas.banded = sc.depth_bands;
                    log_refresh_plans(&seas, opts.dt);
                    reach_watch = ReachWatch::new(&seas, lay.cables.len());
                }
                let stepper = LumpedStepper::new(choice, &sc, lay, &pos, opts, &seas)?;
                Engine::Lumped(Box::new(stepper), plan)
            }
        };
        let points = point_ends(&sc);
        if let Engine::Lumped(..) = engine {
            // The scenario's node list (initial positions, point masses, routes: some
            // 200 bytes a node) has been packed into the layout and the solver's state;
            // kept, it would be half the memory of a big fleet's run (docs/src/output.md,
            // "Memory"). The ANCF model reads it as it runs; winch cables' set-up reads it.
            sc.model.nodes = Vec::new();
        }
        Ok(Self {
            points,
            reach_watch,
            extremes: Extremes::default(),
            scenario: sc,
            engine,
            scheme,
            formulation,
            model,
            relax_residual,
            started,
            stepping: 0.0,
        })
    }

    /// The scenario (with its own settings; the overrides are not written into it).
    /// For the lumped-mass model its node list (`model.nodes`) is empty once the run is
    /// set up: the nodes live in the solver's layout and state.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// Simulated time, s: an exact multiple of the output interval at output times.
    pub fn time(&self) -> f64 {
        match &self.engine {
            Engine::Lumped(s, plan) => {
                output_time(plan, self.scenario.sim.output_interval, s.steps())
            }
            Engine::Ancf(f) => f.time(),
        }
    }

    /// Steps taken (the most of any cable for the ANCF model, whose cables each step at
    /// their own `dt`).
    pub fn steps(&self) -> u64 {
        match &self.engine {
            Engine::Lumped(s, _) => s.steps(),
            Engine::Ancf(f) => f.steps(),
        }
    }

    /// The time step, s (the smallest of any cable for the ANCF model).
    pub fn dt(&self) -> f64 {
        match &self.engine {
            Engine::Lumped(_, plan) => plan.dt,
            Engine::Ancf(f) => f.dt(),
        }
    }

    /// The step plan of a lumped-mass run (`None` for the ANCF model).
    pub fn plan(&self) -> Option<&StepPlan> {
        match &self.engine {
            Engine::Lumped(_, plan) => Some(plan),
            Engine::Ancf(_) => None,
        }
    }

    /// The cable model that runs.
    pub fn model(&self) -> CableModel {
        self.model
    }

    /// The largest residual force the initial relaxation left, N (0 when none ran).
    pub fn relax_residual(&self) -> f64 {
        self.relax_residual
    }

    /// `(backend, device, precision)`: `cpu` or `gpu`, the CPU or adapter, `f64` or
    /// `f32`.
    pub fn describe(&self) -> (&'static str, String, &'static str) {
        match &self.engine {
            Engine::Lumped(s, _) => s.describe(),
            Engine::Ancf(_) => ("cpu", cpu_name(), "f64"),
        }
    }

    /// Advances `n` steps (for the ANCF model: to the time `n` of the smallest step
    /// ahead, each cable to its step nearest that time).
    pub fn advance(&mut self, n: u64) -> Result<(), Error> {
        let t0 = Instant::now();
        let r = match &mut self.engine {
            Engine::Lumped(s, _) => s.advance(n),
            Engine::Ancf(f) => {
                let t = f.time() + n as f64 * f.dt();
                f.advance_to(t)
            }
        };
        self.stepping += t0.elapsed().as_secs_f64();
        r
    }

    /// Advances to time `t` (s): to the step nearest it (each cable's, for the ANCF
    /// model). A time already passed does nothing.
    pub fn advance_to(&mut self, t: f64) -> Result<(), Error> {
        match &mut self.engine {
            Engine::Lumped(s, plan) => {
                let target = (t / plan.dt).round().max(0.0) as u64;
                let n = target.saturating_sub(s.steps());
                self.advance(n)
            }
            Engine::Ancf(f) => {
                if t <= f.time() {
                    return Ok(());
                }
                let t0 = Instant::now();
                let r = f.advance_to(t);
                self.stepping += t0.elapsed().as_secs_f64();
                r
            }
        }
    }

    /// Drives end `end` of cable `cable` (scenario order) from outside, as a coupling
    /// loop does (MoorDyn's API: set the fairlead's target, step, read the force back):
    /// from now until the next call its target moves from `position` (m) at `velocity`
    /// (m/s) in a straight line, `r(t) = position + velocity (t - now)`, and the node
    /// follows it through the same constraint as a scenario route. Read the force the
    /// cable exerts on it from [`Simulation::snapshot`] (`end_forces`). The end must be
    /// held in the scenario (fixed or on a route); lumped-mass model on the CPU backend.
    pub fn set_end_motion(
        &mut self,
        cable: usize,
        end: CableEnd,
        position: [f64; 3],
        velocity: [f64; 3],
    ) -> Result<(), Error> {
        match &mut self.engine {
            Engine::Lumped(s, _) => s.set_end_motion(cable, end, position, velocity),
            Engine::Ancf(_) => Err(Error::Model(
                "driving an end from outside needs the lumped-mass model (formulation glmf)".into(),
            )),
        }
    }

    /// The CPU solver of a lumped-mass run on the CPU backend (`None` otherwise): for
    /// diagnostics that read its state, as examples/wave_prefix_count.rs does.
    pub fn cpu_solver(&self) -> Option<&crate::cpu::CpuSolver> {
        match &self.engine {
            Engine::Lumped(s, _) => match s.as_ref() {
                LumpedStepper::Cpu(c) => Some(c),
                LumpedStepper::Gpu(_) => None,
            },
            Engine::Ancf(_) => None,
        }
    }

    /// Every cable's state now (read back from the GPU on that backend).
    pub fn snapshot(&mut self) -> Result<Snapshot, Error> {
        let time = self.time();
        let steps = self.steps();
        let (cables, bodies, points, nets) = match &mut self.engine {
            Engine::Lumped(s, _) => s.snapshot_parts(time, &self.points, &self.scenario.nets)?,
            // The ANCF backend follows body ends but does not report body or point loads.
            Engine::Ancf(f) => (f.cables()?, Vec::new(), Vec::new(), Vec::new()),
        };
        let snap = Snapshot {
            time,
            steps,
            cables,
            bodies,
            points,
            nets,
        };
        if let Some(w) = &mut self.reach_watch {
            w.check(&snap);
        }
        self.extremes.observe(&snap);
        Ok(snap)
    }

    /// Runs on to the end of the scenario's duration, handing the sink a snapshot now
    /// and at each output time, then the summary; `progress` is called as the run goes
    /// (about every tenth of a second of stepping on big runs, and at each output time).
    /// A blow-up ends the run: the sink gets a last frame and the summary (status
    /// `diverged`), and the error is returned. [`Simulation::run_until`] can also be
    /// stopped from outside.
    pub fn run(
        &mut self,
        sink: &mut dyn OutputSink,
        progress: impl FnMut(Progress),
    ) -> Result<Summary, Error> {
        self.run_until(sink, progress, || false)
    }

    /// At the `debug` log level, on the CPU path in waves: nodes per depth band now
    /// and the breaches so far (`CpuSolver::wave_band_census`), at each output time:
    /// what scripts/gpu_wave_counts.py reads for a member's band census.
    fn log_wave_band_census(&self) {
        if !log::log_enabled!(log::Level::Debug) {
            return;
        }
        if let Engine::Lumped(s, _) = &self.engine {
            if let LumpedStepper::Cpu(c) = s.as_ref() {
                let c = c.wave_band_census();
                if !c.nodes.is_empty() {
                    log::debug!(
                        "waves: t = {:.2} s, nodes per depth band {:?}, breaches {} ({} beyond the margin)",
                        self.time(),
                        c.nodes,
                        c.breaches,
                        c.beyond_margin
                    );
                }
            }
        }
    }

    /// [`Simulation::run`], stopped early when `stop` returns true: it is asked between
    /// chunks of stepping (about every tenth of a second on big runs, and at each output
    /// time), so a stop takes effect at the next step boundary. A stopped run hands the
    /// sink a last frame at the time reached and a summary with status `interrupted`,
    /// and returns that summary (`Ok`): what was done is kept, not an error.
    ///
    /// A signal handler that sets an `AtomicBool` makes a clean Ctrl-C:
    ///
    /// ```no_run
    /// use cablesim::{MemorySink, Overrides, Simulation};
    /// use std::sync::atomic::{AtomicBool, Ordering};
    ///
    /// static STOP: AtomicBool = AtomicBool::new(false);
    /// let mut sim = Simulation::from_file("examples/catenary.toml", &Overrides::default())?;
    /// let summary = sim.run_until(&mut MemorySink::new(), |_| {}, || STOP.load(Ordering::Relaxed))?;
    /// assert!(summary.status == "completed" || summary.status == "interrupted");
    /// # Ok::<(), cablesim::Error>(())
    /// ```
    pub fn run_until(
        &mut self,
        sink: &mut dyn OutputSink,
        mut progress: impl FnMut(Progress),
        mut stop: impl FnMut() -> bool,
    ) -> Result<Summary, Error> {
        sink.frame_owned(self.snapshot()?)?;
        // Steps at the last frame handed out: a stop right at an output time does not
        // repeat it.
        let mut framed = self.steps();
        let mut end = RunEnd::Completed;
        loop {
            if stop() {
                end = RunEnd::Interrupted;
                break;
            }
            let r = match &mut self.engine {
                Engine::Lumped(s, plan) => {
                    let done = s.steps();
                    if done >= plan.total_steps {
                        break;
                    }
                    let next = ((done / plan.steps_per_output) + 1) * plan.steps_per_output;
                    let target = next.min(plan.total_steps);
                    let oi = self.scenario.sim.output_interval;
                    advance_lumped(
                        s,
                        plan,
                        oi,
                        target,
                        &mut self.stepping,
                        &mut progress,
                        &mut stop,
                    )
                }
                Engine::Ancf(f) => {
                    let total = f.n_outputs();
                    // The next output after the time reached.
                    let k = (1..=total)
                        .find(|&k| f.output_time(k) > f.time() + 1e-9 * f.output_time(k).abs());
                    let Some(k) = k else { break };
                    let t0 = Instant::now();
                    let r = f.advance_to_output(k);
                    self.stepping += t0.elapsed().as_secs_f64();
                    progress(Progress {
                        time: f.output_time(k),
                        done: k,
                        total,
                        at_output: r.is_ok(),
                    });
                    r.map(|_| Chunked::Done)
                }
            };
            match r {
                Ok(Chunked::Done) => {
                    sink.frame_owned(self.snapshot()?)?;
                    framed = self.steps();
                    self.log_wave_band_census();
                }
                Ok(Chunked::Stopped) => {
                    end = RunEnd::Interrupted;
                    break;
                }
                Err(e) => {
                    end = RunEnd::Failed(e);
                    break;
                }
            }
        }
        if !matches!(end, RunEnd::Completed) && self.steps() != framed {
            // The last frame: where the run stopped. After a blow-up the state may not
            // evaluate; then the summary alone tells.
            match self.snapshot() {
                Ok(s) => sink.frame_owned(s)?,
                Err(e) => log::warn!("no frame at the failure: {e}"),
            }
        }
        let summary = match &end {
            RunEnd::Completed => self.summary_as("completed", None)?,
            RunEnd::Interrupted => self.summary_as("interrupted", None)?,
            RunEnd::Failed(e) => self.summary_as("diverged", Some(e))?,
        };
        sink.finish(&summary)?;
        match end {
            RunEnd::Failed(e) => Err(e),
            _ => Ok(summary),
        }
    }

    /// The summary of the run so far; `error` is what stopped it, if anything.
    pub fn summary(&mut self, error: Option<&Error>) -> Result<Summary, Error> {
        let status = if error.is_none() {
            "completed"
        } else {
            "diverged"
        };
        self.summary_as(status, error)
    }

    fn summary_as(&mut self, status: &str, error: Option<&Error>) -> Result<Summary, Error> {
        let (backend, device, precision) = self.describe();
        let sim_time = self.time();
        let steps = self.steps();
        // The per-cable part from the last snapshot, taken now if the state moved on
        // since (a caller that advanced without one); a state that cannot be evaluated
        // (after a blow-up) leaves the end forces unknown.
        if self.extremes.steps != Some(steps) {
            if let Err(e) = self.snapshot() {
                log::debug!("no final state for the summary: {e}");
                self.extremes.unevaluable(steps);
            }
        }
        let cables = self.extremes.cables.clone();
        let (dt, dt_stable, limited_by, nodes, elements, node_steps, formulation) =
            match &mut self.engine {
                Engine::Lumped(s, plan) => {
                    let lay = s.layout();
                    (
                        plan.dt,
                        plan.bound.dt,
                        plan.bound.term.clone(),
                        lay.n_nodes(),
                        lay.n_elements(),
                        s.node_steps() as f64,
                        self.formulation.name(),
                    )
                }
                Engine::Ancf(f) => {
                    let (dt_stable, term) = f.stable_dt();
                    (
                        f.dt(),
                        dt_stable,
                        term,
                        f.n_nodes(),
                        f.n_elements(),
                        f.node_steps(),
                        "ancf",
                    )
                }
            };
        Ok(Summary {
            status: status.into(),
            error: error.map(|e| e.to_string()),
            scenario: self.scenario.path.display().to_string(),
            backend: backend.into(),
            device,
            precision: precision.into(),
            scheme: self.scheme.name().into(),
            formulation: formulation.into(),
            steps,
            dt,
            dt_stable,
            dt_above_stable: dt > dt_stable,
            dt_limited_by: limited_by,
            simulated_time: sim_time,
            wall_seconds: self.stepping,
            total_wall_seconds: self.started.elapsed().as_secs_f64(),
            nodes,
            elements,
            node_steps_per_second: if self.stepping > 0.0 {
                node_steps / self.stepping
            } else {
                0.0
            },
            threads: rayon::current_num_threads(),
            relax_residual: self.relax_residual,
            cables,
            failures: match &self.engine {
                Engine::Lumped(s, _) => s.failure_events(),
                _ => Vec::new(),
            },
        })
    }
}

/// How a run ended.
enum RunEnd {
    Completed,
    Interrupted,
    Failed(Error),
}

/// What a stretch of stepping came to.
enum Chunked {
    /// The target was reached.
    Done,
    /// The caller's `stop` asked to stop, at a step boundary before the target.
    Stopped,
}

/// Advances a lumped-mass run to step `target`, in sub-chunks of about twenty million
/// node-steps (a tenth of a second or so), which keep progress moving and a stop
/// request answered on big runs without cutting the blocks' long runs too short.
///
/// On a blow-up the blocks of a chunk stand at different steps (each steps on its own
/// until it fails or finishes). Where the state can be put back (always, unless the GPU
/// path cannot read its state back), the stretch is stepped again from a checkpoint up
/// to the step before the failure, so that every cable is at that one time, the last state that exists. The CPU path
/// keeps a checkpoint per chunk (a copy in memory); the GPU path one per call (an
/// output interval), since it must read its state back from the device for it.
fn advance_lumped(
    s: &mut LumpedStepper,
    plan: &StepPlan,
    oi: f64,
    target: u64,
    stepping: &mut f64,
    progress: &mut impl FnMut(Progress),
    stop: &mut impl FnMut() -> bool,
) -> Result<Chunked, Error> {
    let chunk = (20_000_000 / s.layout().n_nodes().max(1) as u64).clamp(1, plan.steps_per_output);
    let mut first = true;
    let gpu = matches!(s, LumpedStepper::Gpu(_));
    let mut saved_gpu = if gpu { s.checkpoint() } else { None };
    while s.steps() < target {
        if !first && stop() {
            return Ok(Chunked::Stopped);
        }
        first = false;
        let n = chunk.min(target - s.steps());
        let saved = if gpu { None } else { s.checkpoint() };
        let t0 = Instant::now();
        let r = s.advance(n);
        if let (Err(e), Some(saved)) = (&r, saved.or_else(|| saved_gpu.take())) {
            rewind_to_failure(s, saved, e, plan.dt);
        }
        *stepping += t0.elapsed().as_secs_f64();
        let done = s.steps();
        progress(Progress {
            time: output_time(plan, oi, done),
            done,
            total: plan.total_steps,
            at_output: r.is_ok() && done == target,
        });
        r?;
    }
    Ok(Chunked::Done)
}

/// Puts the stepper back at `saved` and steps it to the step before the failure `e`
/// (step `dt`, s). Should the replay fail earlier (it does not: stepping is
/// deterministic), the stepper stays at `saved`, where every cable is at one time too.
/// Should putting it back fail (the device, rebuilding a winch run's buffers), the log
/// says so and the state is the device's, whatever it holds.
fn rewind_to_failure(s: &mut LumpedStepper, saved: backend::Checkpoint, e: &Error, dt: f64) {
    let t_fail = match e {
        Error::Diverged { time, .. }
        | Error::SingularFrame { time, .. }
        | Error::Winch { time, .. } => *time,
        _ => return,
    };
    let start = saved.steps();
    let failing = (t_fail / dt).round() as u64;
    if let Err(why) = s.restore(&saved) {
        log::warn!("blow-up at t = {t_fail} s: the state could not be put back ({why})");
        return;
    }
    let good = failing.saturating_sub(1).saturating_sub(start);
    if good > 0 && s.advance(good).is_err() {
        if let Err(why) = s.restore(&saved) {
            log::warn!("blow-up at t = {t_fail} s: the state could not be put back ({why})");
            return;
        }
    }
    log::info!(
        "blow-up at t = {t_fail} s: every cable's state kept at t = {} s, the step before",
        s.steps() as f64 * dt
    );
}

/// Where each `[[points]]` entry is found in the layout: `(name, cable, at its start)`,
/// the first cable end attached to it; points no cable attaches to are left out.
/// Logs each sea's refresh plan (`sea::schedule`): the reach, the trough, the factor
/// and the interval on the grid.
fn log_refresh_plans(seas: &crate::sea::SeaSet, dt: f64) {
    for (q, sea) in seas.seas.iter().enumerate() {
        if sea.is_still() {
            continue;
        }
        let bands = seas.band_plan(q, dt);
        let p = bands.base;
        log::info!(
            "waves, sea {q}: nodes reach z = {:.2} m, lowest trough assumed {:.2} m, \
             evaluation depth {:.2} m; refresh every {} steps ({:.4} s: {} x the rule at \
             that depth, {:.4} s, rounded down to dt 2^m or 3 dt 2^m)",
            p.reach,
            p.trough,
            p.eval_depth,
            p.steps,
            p.interval,
            p.factor,
            p.unrounded
        );
        if bands.len() > 1 {
            let rungs: Vec<String> = (1..bands.len())
                .map(|m| format!("{} steps under z = {:.1} m", bands.steps[m], bands.tops[m]))
                .collect();
            log::info!(
                "waves, sea {q}: refresh per depth band (each node's decided at its \
                 band's refreshes, band 0 every {:.4} s): {}",
                bands.band(0).interval,
                rungs.join(", ")
            );
        }
    }
}

fn point_ends(sc: &Scenario) -> Vec<(String, usize, bool)> {
    sc.points
        .iter()
        .filter_map(|p| {
            sc.model.cables.iter().enumerate().find_map(|(ci, c)| {
                if c.nodes.first() == Some(&p.node) {
                    Some((p.name.clone(), ci, true))
                } else if c.nodes.last() == Some(&p.node) {
                    Some((p.name.clone(), ci, false))
                } else {
                    None
                }
            })
        })
        .collect()
}
