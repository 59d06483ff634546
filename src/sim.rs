//! Runs a scenario: set-up, initial equilibrium, time stepping, output.

use crate::ale::{WinchEnd, WinchTracker};
use crate::cpu::{CpuSolver, Evaluation, WinchStatus};
use crate::error::Error;
use crate::gpu::{GpuContext, GpuSolver, Precision};
use crate::model::{Layout, ModelDef};
use crate::options::{CableModel, Formulation, Scheme, SolverOptions};
use crate::output::{end_forces, CableSummary, OutputWriter, Summary, WinchSummary};
use crate::scenario::{Backend, DtSpec, Scenario};
use crate::stability::{stable_step, StepBound, AUTO_SAFETY};
use std::path::PathBuf;
use std::time::Instant;

/// Overrides from the command line (each `None` keeps the scenario's value).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// Backend.
    pub backend: Option<Backend>,
    /// GPU precision (the CPU path is always f64).
    pub precision: Option<Precision>,
    /// Scheme.
    pub scheme: Option<Scheme>,
    /// Formulation (of the lumped-mass model).
    pub formulation: Option<Formulation>,
    /// Cable model (lumped mass or ANCF).
    pub model: Option<CableModel>,
    /// Time step, s.
    pub dt: Option<f64>,
    /// Duration, s.
    pub duration: Option<f64>,
}

/// How a run is carried out.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Output directory.
    pub out_dir: PathBuf,
    /// Overrides of scenario settings.
    pub overrides: Overrides,
    /// Show a progress bar on stderr.
    pub progress: bool,
}

/// The step plan of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct StepPlan {
    /// Time step, s.
    pub dt: f64,
    /// Steps per output interval.
    pub steps_per_output: u64,
    /// Total steps.
    pub total_steps: u64,
    /// The stability bound.
    pub bound: StepBound,
    /// A warning to show (user step above the bound).
    pub warning: Option<String>,
}

/// Chooses the step: `auto` takes [`AUTO_SAFETY`] of the stable step, rounded down so
/// that a whole number of steps fits each output interval; a given step must divide the
/// output interval and gets a warning when it is above the stable step.
///
/// With winches, the stable step is that of the worst mesh the run can reach (each
/// variable element at its shortest, `0.5 l_s`; a cable hauled in to a single element
/// when the schedule goes that far), and the schedules are followed over the planned
/// step times without dynamics: a drum overrun or a haul-in past the last node is
/// reported here, naming the cable and the time, before anything runs.
pub fn plan_steps(
    sc: &Scenario,
    lay: &Layout,
    opts: &SolverOptions,
    duration: f64,
    dt: DtSpec,
) -> Result<StepPlan, Error> {
    let mut bound = stable_step(lay, opts.scheme, opts.baumgarte);
    if sc.winches.is_empty() {
        return plan_with(sc, opts, duration, dt, bound);
    }
    let worst = |bound: &mut StepBound, collapse: &[usize]| -> Result<(), Error> {
        let (wl, _) = Layout::build(&winch_worst_case(&sc.model, sc, collapse))?;
        let b = stable_step(&wl, opts.scheme, opts.baumgarte);
        if b.dt < bound.dt {
            *bound = StepBound {
                dt: b.dt,
                term: format!("{} (winch mesh at its shortest variable element)", b.term),
            };
        }
        Ok(())
    };
    worst(&mut bound, &[])?;
    let mut plan = plan_with(sc, opts, duration, dt, bound.clone())?;
    let collapse = scan_winches(sc, &plan)?;
    if !collapse.is_empty() {
        worst(&mut bound, &collapse)?;
        plan = plan_with(sc, opts, duration, dt, bound)?;
        scan_winches(sc, &plan)?;
    }
    Ok(plan)
}

/// The model with every winch cable's variable element at `0.5 l_s`, and the cables
/// listed in `collapse` hauled in to that single element.
fn winch_worst_case(def: &ModelDef, sc: &Scenario, collapse: &[usize]) -> ModelDef {
    let mut d = def.clone();
    for (wi, w) in sc.winches.iter().enumerate() {
        let c = &mut d.cables[w.cable];
        let short = crate::ale::DELETE_RATIO * w.element_length;
        if collapse.contains(&wi) {
            // Interior nodes are left loose (no mass, no elements): the step ignores them.
            let (a, b) = (c.nodes[0], c.nodes[c.nodes.len() - 1]);
            c.nodes = vec![a, b];
            c.l0 = vec![short];
        } else {
            let k = match w.end {
                WinchEnd::Start => 0,
                WinchEnd::End => c.l0.len() - 1,
            };
            c.l0[k] = short;
        }
    }
    d
}

/// Follows every winch's schedule over the plan's step times; returns the winches
/// whose cable gets down to a single element (from more), or the first limit passed.
fn scan_winches(sc: &Scenario, plan: &StepPlan) -> Result<Vec<usize>, Error> {
    let mut collapse = Vec::new();
    for (wi, w) in sc.winches.iter().enumerate() {
        let c = &sc.model.cables[w.cable];
        let mut tr = WinchTracker::new(w, &c.l0, w.schedule.eval(0.0).dl);
        let n0 = tr.n_elements();
        let fewest =
            tr.scan(&w.schedule, plan.dt, 0, plan.total_steps)
                .map_err(|(time, lim)| Error::Winch {
                    cable: c.name.clone(),
                    time,
                    message: lim.to_string(),
                })?;
        if fewest == 1 && n0 > 1 {
            collapse.push(wi);
        }
    }
    Ok(collapse)
}

/// The step of `spec` for a model whose stable step is `stable` (s), and the steps per
/// output interval: `auto` takes [`AUTO_SAFETY`] of `stable`, rounded down so that a
/// whole number of steps fits the output interval; a given step must divide it (an
/// error naming the field otherwise).
pub(crate) fn fit_step(sc: &Scenario, spec: DtSpec, stable: f64) -> Result<(f64, u64), Error> {
    let oi = sc.sim.output_interval;
    match spec {
        DtSpec::Auto => {
            let n = (oi / (AUTO_SAFETY * stable)).ceil().max(1.0);
            Ok((oi / n, n as u64))
        }
        DtSpec::Fixed(d) => {
            let n = (oi / d).round().max(1.0);
            if ((n * d) - oi).abs() > 1e-9 * oi {
                return Err(crate::scenario::err(
                    &sc.path,
                    "simulation.output_interval",
                    format!("{oi} s is not a whole number of steps of dt = {d} s"),
                ));
            }
            Ok((d, n as u64))
        }
    }
}

fn plan_with(
    sc: &Scenario,
    opts: &SolverOptions,
    duration: f64,
    dt_spec: DtSpec,
    bound: StepBound,
) -> Result<StepPlan, Error> {
    let (dt, spo) = fit_step(sc, dt_spec, bound.dt)?;
    let warning = (matches!(dt_spec, DtSpec::Fixed(_)) && dt > bound.dt).then(|| {
        format!(
            "dt = {dt} s is above the stable step {:.4e} s of the {} scheme, set by {}; expect a blow-up",
            bound.dt,
            opts.scheme.name(),
            bound.term
        )
    });
    let total = (duration / dt).round().max(1.0) as u64;
    Ok(StepPlan {
        dt,
        steps_per_output: spo,
        total_steps: total,
        bound,
        warning,
    })
}

/// Builds the layout and the initial state (catenary first guesses relaxed to the
/// discrete static equilibrium). Returns the layout, positions and the largest
/// residual force left by the relaxation.
pub fn prepare(sc: &Scenario) -> Result<(Layout, Vec<[f64; 3]>, f64), Error> {
    let (lay, mut pos) = Layout::build(&sc.model)?;
    let residual = crate::initial::apply(sc, &lay, &mut pos)?;
    Ok((lay, pos, residual))
}

/// Runs a scenario to the end, writing output as it goes.
pub fn run(sc: &Scenario, ro: &RunOptions) -> Result<Summary, Error> {
    let wall0 = Instant::now();
    let ov = &ro.overrides;
    if ov.model.unwrap_or(sc.sim.model) == CableModel::Ancf {
        if ov.backend.unwrap_or(sc.sim.backend) == Backend::Gpu {
            return Err(Error::GpuUnsupported(
                "the ANCF model (CPU only); use --backend cpu (or auto)".into(),
            ));
        }
        return crate::ancf::run::run(sc, ro, &sc.ancf);
    }
    let mut opts = SolverOptions {
        formulation: ov.formulation.unwrap_or(sc.sim.formulation),
        scheme: ov.scheme.unwrap_or(sc.sim.scheme),
        baumgarte: sc.sim.baumgarte,
        max_speed: sc.sim.max_speed,
        ..SolverOptions::default()
    };
    let duration = ov.duration.unwrap_or(sc.sim.duration);
    let dt_spec = ov.dt.map(DtSpec::Fixed).unwrap_or(sc.sim.dt);
    let (lay, pos, relax_residual) = prepare(sc)?;
    let plan = plan_steps(sc, &lay, &opts, duration, dt_spec)?;
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
    let backend = ov.backend.unwrap_or(sc.sim.backend);
    let precision = match ov.precision {
        Some(p) => Some(p),
        None => sc.sim.precision.as_deref().and_then(Precision::parse),
    };
    let choice = choose_backend(backend, precision, &lay, &opts, sc)?;
    let mut out = OutputWriter::create(&ro.out_dir, &lay)?;
    let mut solver = match choice {
        BackendChoice::Cpu if !sc.winches.is_empty() => Stepper::Cpu(CpuSolver::with_winches(
            sc.model.clone(),
            sc.winches.clone(),
            &pos,
            opts,
        )?),
        BackendChoice::Cpu => Stepper::Cpu(CpuSolver::new(lay, &pos, opts)),
        BackendChoice::Gpu(ctx, p) if !sc.winches.is_empty() => Stepper::Gpu(
            GpuSolver::with_winches(&ctx, sc.model.clone(), sc.winches.clone(), &pos, opts, p)?,
        ),
        BackendChoice::Gpu(ctx, p) => Stepper::Gpu(GpuSolver::new(&ctx, lay, &pos, opts, p)?),
    };
    if let Stepper::Cpu(c) = &mut solver {
        c.set_sea(&sc.sea, false);
    }
    if let Stepper::Gpu(g) = &solver {
        match g.fused_unavailable() {
            Some(why) => log::info!("GPU kernel: {} (not fused: {why})", g.kernel().name()),
            None => log::info!("GPU kernel: {}", g.kernel().name()),
        }
    }

    let bar = if ro.progress {
        let b = indicatif::ProgressBar::new(plan.total_steps);
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
    // Sub-chunks of about twenty million node-steps (a tenth of a second or so) keep
    // the bar moving on big runs without cutting the blocks' long runs too short.
    let chunk =
        (20_000_000 / solver.layout().n_nodes().max(1) as u64).clamp(1, plan.steps_per_output);
    let mut stepping = 0.0f64;
    let mut result: Result<(), Error> = Ok(());
    write_frame(&mut out, &mut solver, 0.0)?;
    let mut done = 0u64;
    while done < plan.total_steps {
        let next_out = ((done / plan.steps_per_output) + 1) * plan.steps_per_output;
        let target = next_out.min(plan.total_steps);
        while done < target {
            let n = chunk.min(target - done);
            let t0 = Instant::now();
            let r = solver.advance(n);
            stepping += t0.elapsed().as_secs_f64();
            done += n;
            bar.set_position(done);
            bar.set_message(format!("{:.2} s", solver.t()));
            if let Err(e) = r {
                result = Err(e);
                break;
            }
        }
        if result.is_err() {
            break;
        }
        write_frame(
            &mut out,
            &mut solver,
            output_time(&plan, sc.sim.output_interval, done),
        )?;
    }
    bar.finish_and_clear();
    out.flush()?;

    let ev = solver.evaluate().ok();
    let r: Vec<[f64; 3]> = solver.positions()?;
    let winches = solver.winch_status();
    let (backend_name, device, precision_name) = solver.describe();
    let node_steps = solver.node_steps();
    let steps = solver.steps();
    let lay = solver.layout();
    let cables = lay
        .cables
        .iter()
        .enumerate()
        .map(|(ci, c)| CableSummary {
            winch: winches
                .iter()
                .find(|w| w.cable == ci)
                .map(|w| WinchSummary {
                    deployed_length: w.deployed_length,
                    variable_l0: w.variable_l0,
                    elements: w.elements,
                    nodes_inserted: w.inserted,
                    nodes_deleted: w.deleted,
                    physical_coordinates: w.physical_coordinates.clone(),
                }),
            name: c.name.clone(),
            final_positions: c.nodes.iter().map(|&i| r[i as usize]).collect(),
            final_tensions: c
                .elements
                .iter()
                .map(|&e| ev.as_ref().map_or(f64::NAN, |ev| ev.tension[e as usize]))
                .collect(),
            end_forces: ev.as_ref().map_or(
                crate::output::EndForces {
                    start: [f64::NAN; 3],
                    end: [f64::NAN; 3],
                },
                |ev| end_forces(lay, ev, c),
            ),
        })
        .collect();
    let summary = Summary {
        status: if result.is_ok() {
            "completed".into()
        } else {
            "diverged".into()
        },
        error: result.as_ref().err().map(|e| e.to_string()),
        scenario: sc.path.display().to_string(),
        backend: backend_name.into(),
        device,
        precision: precision_name.into(),
        scheme: opts.scheme.name().into(),
        formulation: opts.formulation.name().into(),
        steps,
        dt: plan.dt,
        dt_stable: plan.bound.dt,
        dt_limited_by: plan.bound.term.clone(),
        simulated_time: output_time(&plan, sc.sim.output_interval, steps),
        wall_seconds: stepping,
        total_wall_seconds: wall0.elapsed().as_secs_f64(),
        nodes: lay.n_nodes(),
        elements: lay.n_elements(),
        node_steps_per_second: if stepping > 0.0 {
            node_steps as f64 / stepping
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

fn write_frame(out: &mut OutputWriter, s: &mut Stepper, t: f64) -> Result<(), Error> {
    let ev = s.evaluate()?;
    let r = s.positions()?;
    out.frame(t, s.layout(), &r, &ev)?;
    out.winches(t, s.layout(), &s.winch_status())
}

/// The backend a run uses.
pub enum BackendChoice {
    /// The f64 CPU reference path.
    Cpu,
    /// The GPU path on this device, at this precision.
    Gpu(Box<GpuContext>, Precision),
}

/// Chooses the backend:
/// - `cpu`: the CPU path (always f64; a precision of f32 is ignored with a warning);
/// - `gpu`: the best adapter (see [`crate::gpu::context`]) at the asked precision
///   (default f32); an error when there is no usable adapter (or none with
///   `SHADER_F64` for f64), or when the model needs what the GPU path lacks;
/// - `auto`: the GPU path where it applies, else the CPU path with a logged reason:
///   no usable adapter, the model needs what the GPU path lacks, or the only adapter
///   is a software one (lavapipe, llvmpipe, WARP: slower than the CPU path; use
///   `--backend gpu` to run on it anyway).
pub fn choose_backend(
    backend: Backend,
    precision: Option<Precision>,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &Scenario,
) -> Result<BackendChoice, Error> {
    let unsupported = || {
        crate::gpu::solver::unsupported(lay, opts)
            .or_else(|| crate::gpu::solver::unsupported_winches(&sc.model, &sc.winches))
            .or_else(|| (!sc.sea.is_still()).then(|| "waves ([environment.waves])".to_string()))
    };
    let need_f64 = precision == Some(Precision::F64);
    let p = precision.unwrap_or_default();
    match backend {
        Backend::Cpu => {
            if precision == Some(Precision::F32) {
                log::warn!("the CPU path is always f64: precision f32 applies to the GPU only");
            }
            Ok(BackendChoice::Cpu)
        }
        Backend::Gpu => {
            if let Some(what) = unsupported() {
                return Err(Error::GpuUnsupported(format!(
                    "{what}; use --backend cpu (or auto)"
                )));
            }
            let ctx = GpuContext::new(need_f64)?;
            log::info!("backend gpu: {} at {}", ctx.describe(), p.name());
            Ok(BackendChoice::Gpu(Box::new(ctx), p))
        }
        Backend::Auto => {
            if let Some(what) = unsupported() {
                log::info!(
                    "backend auto: the GPU path does not do {what} yet; running the f64 CPU reference path"
                );
                return Ok(BackendChoice::Cpu);
            }
            match GpuContext::new(need_f64) {
                Err(e) => {
                    log::warn!("backend auto: {e}; running the f64 CPU reference path");
                    Ok(BackendChoice::Cpu)
                }
                Ok(ctx) if ctx.info.device_type == wgpu::DeviceType::Cpu => {
                    log::info!(
                        "backend auto: the best adapter, {}, is a software one (slower than the CPU path); \
                         running the f64 CPU reference path (--backend gpu runs on it anyway)",
                        ctx.describe()
                    );
                    Ok(BackendChoice::Cpu)
                }
                Ok(ctx) => {
                    log::info!("backend auto: {} at {}", ctx.describe(), p.name());
                    Ok(BackendChoice::Gpu(Box::new(ctx), p))
                }
            }
        }
    }
}

/// The solver a run steps: the CPU reference or the GPU path, behind one interface.
pub enum Stepper {
    /// The f64 CPU reference path.
    Cpu(CpuSolver),
    /// The GPU path.
    Gpu(GpuSolver),
}

impl Stepper {
    /// Advances `n` steps.
    pub fn advance(&mut self, n: u64) -> Result<(), Error> {
        match self {
            Stepper::Cpu(s) => s.advance(n),
            Stepper::Gpu(s) => s.advance(n),
        }
    }
    /// Simulated time, s.
    pub fn t(&self) -> f64 {
        match self {
            Stepper::Cpu(s) => s.t,
            Stepper::Gpu(s) => s.t,
        }
    }
    /// Node-steps taken (nodes times steps, counting the nodes each step had).
    pub fn node_steps(&self) -> u64 {
        match self {
            Stepper::Cpu(s) => s.node_steps,
            Stepper::Gpu(s) => s.node_steps,
        }
    }
    /// State of the winch cables.
    pub fn winch_status(&self) -> Vec<WinchStatus> {
        match self {
            Stepper::Cpu(s) => s.winch_status(),
            Stepper::Gpu(s) => s.winch_status(),
        }
    }
    /// Steps taken.
    pub fn steps(&self) -> u64 {
        match self {
            Stepper::Cpu(s) => s.steps,
            Stepper::Gpu(s) => s.steps,
        }
    }
    /// The packed model.
    pub fn layout(&self) -> &Layout {
        match self {
            Stepper::Cpu(s) => &s.layout,
            Stepper::Gpu(s) => &s.layout,
        }
    }
    /// Node positions (packed order; read back from the GPU), m.
    pub fn positions(&mut self) -> Result<Vec<[f64; 3]>, Error> {
        match self {
            Stepper::Cpu(s) => Ok(s.r.iter().map(|x| x.to_f64()).collect()),
            Stepper::Gpu(s) => Ok(s.state()?.0),
        }
    }
    /// Tensions, reactions and accelerations at the current state.
    pub fn evaluate(&mut self) -> Result<Evaluation, Error> {
        match self {
            Stepper::Cpu(s) => s.evaluate(),
            Stepper::Gpu(s) => s.evaluate(),
        }
    }
    /// `(backend, device, precision)` for the summary.
    pub fn describe(&self) -> (&'static str, String, &'static str) {
        match self {
            Stepper::Cpu(_) => ("cpu", cpu_name(), "f64"),
            Stepper::Gpu(s) => ("gpu", s.device().to_string(), s.precision.name()),
        }
    }
}

/// The time of step `steps` as written out: an exact multiple of the output interval at
/// output steps (`steps * dt` can be off by an ulp), else `steps * dt`.
fn output_time(plan: &StepPlan, oi: f64, steps: u64) -> f64 {
    if steps.is_multiple_of(plan.steps_per_output) {
        (steps / plan.steps_per_output) as f64 * oi
    } else {
        steps as f64 * plan.dt
    }
}

/// The CPU model name, from /proc/cpuinfo where there is one.
pub fn cpu_name() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|x| x.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}
