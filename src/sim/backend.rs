//! Stage 5 of the pipeline: the backend. [`choose_backend`] picks the CPU reference path
//! or the GPU path for a lumped-mass run (probing adapters quietly and saying in one
//! line what it chose and why); [`LumpedStepper`] steps either behind one interface.
//! The ANCF reference model is the third backend ([`super::ancf`]).

use crate::cpu::CpuSolver;

/// One end of a cable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CableEnd {
    /// Its first node.
    Start,
    /// Its last node.
    End,
}
use crate::error::Error;
use crate::gpu::solver::NodeStates;
use crate::gpu::{GpuContext, GpuSolver};
use crate::model::{Layout, Route, NO_CONSTRAINT};
use crate::options::{Backend, Precision, SolverOptions};
use crate::output::{end_forces, BodyState, CableState, EndForces, PointState, WinchSummary};
use crate::scenario::Scenario;
use crate::sea::SeaSet;
use crate::step::{Evaluation, WinchStatus};

/// The backend a lumped-mass run uses.
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
///
/// One info line says what was chosen and why.
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
            .or_else(|| crate::gpu::solver::unsupported_failures(lay, &sc.failures))
            .or_else(|| {
                // A run with winch cables has no bending in the lumped-mass model.
                sc.winches
                    .is_empty()
                    .then(|| crate::gpu::solver::unsupported_bending(lay))
                    .flatten()
            })
    };
    let need_f64 = precision == Some(Precision::F64);
    let p = precision.unwrap_or_default();
    match backend {
        Backend::Cpu => {
            if precision == Some(Precision::F32) {
                log::warn!("the CPU path is always f64: precision f32 applies to the GPU only");
            }
            log::info!("backend cpu: the f64 CPU reference path");
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

/// A lumped-mass stepper's state at one step, to go back to.
pub enum Checkpoint {
    /// Of the CPU path.
    Cpu(crate::cpu::CpuCheckpoint),
    /// Of the GPU path (read back from the device).
    Gpu(crate::gpu::GpuCheckpoint),
}

impl Checkpoint {
    /// Steps taken when it was made.
    pub fn steps(&self) -> u64 {
        match self {
            Checkpoint::Cpu(c) => c.steps,
            Checkpoint::Gpu(c) => c.steps,
        }
    }
}

/// The solver a lumped-mass run steps: the CPU reference or the GPU path, behind one
/// interface.
pub enum LumpedStepper {
    /// The f64 CPU reference path.
    Cpu(CpuSolver),
    /// The GPU path.
    Gpu(GpuSolver),
}

/// What [`LumpedStepper::snapshot_parts`] reads at an output time: the cables', the
/// bodies' and the shared points' states.
pub type SnapshotParts = (
    Vec<CableState>,
    Vec<BodyState>,
    Vec<PointState>,
    Vec<crate::output::NetState>,
);

impl LumpedStepper {
    /// Builds the chosen solver at rest at `pos` (packed order of `lay`), in the seas
    /// `seas` (`Scenario::sea_set`, with the reach of `sim::reach`).
    pub fn new(
        choice: BackendChoice,
        sc: &Scenario,
        lay: Layout,
        pos: &[[f64; 3]],
        opts: SolverOptions,
        seas: &SeaSet,
    ) -> Result<Self, Error> {
        if !sc.winches.is_empty() && !sc.failures.is_empty() {
            return Err(Error::Model(
                "winch cables and line failures in one run are not supported yet".into(),
            ));
        }
        let mut s = match choice {
            BackendChoice::Cpu if !sc.winches.is_empty() => LumpedStepper::Cpu(
                CpuSolver::with_winches(sc.model.clone(), sc.winches.clone(), pos, opts)?,
            ),
            BackendChoice::Cpu => {
                let mut s = CpuSolver::new(lay, pos, opts);
                s.set_failures(&sc.failures)?;
                LumpedStepper::Cpu(s)
            }
            BackendChoice::Gpu(ctx, p) if !sc.winches.is_empty() => LumpedStepper::Gpu(
                GpuSolver::with_winches(&ctx, sc.model.clone(), sc.winches.clone(), pos, opts, p)?,
            ),
            BackendChoice::Gpu(ctx, p) => {
                let mut g = GpuSolver::new(&ctx, lay, pos, opts, p)?;
                g.set_failures(&sc.failures)?;
                LumpedStepper::Gpu(g)
            }
        };
        match &mut s {
            LumpedStepper::Cpu(c) => c.set_seas(seas, false),
            LumpedStepper::Gpu(g) => g.set_seas(seas)?,
        }
        if let LumpedStepper::Gpu(g) = &s {
            match g.fused_unavailable() {
                Some(why) => log::info!("GPU kernel: {} (not fused: {why})", g.kernel().name()),
                None => log::info!("GPU kernel: {}", g.kernel().name()),
            }
        }
        Ok(s)
    }

    /// A copy of the state to go back to ([`LumpedStepper::restore`]). The CPU path
    /// always has one (the whole solver where the mesh or the waves' cache carry state);
    /// the GPU path reads its state back (one download per call; with winches the
    /// host's mesh and winch state too), and has none should the download fail.
    pub fn checkpoint(&mut self) -> Option<Checkpoint> {
        match self {
            LumpedStepper::Cpu(s) => s.checkpoint().map(Checkpoint::Cpu),
            LumpedStepper::Gpu(s) => match s.checkpoint() {
                Ok(c) => Some(Checkpoint::Gpu(c)),
                Err(e) => {
                    log::warn!("no checkpoint of the GPU state: {e}");
                    None
                }
            },
        }
    }

    /// Puts the state back to `cp`, taken from this stepper. Only the GPU path can
    /// fail here (rebuilding its buffers for a winch run's earlier mesh).
    pub fn restore(&mut self, cp: &Checkpoint) -> Result<(), Error> {
        match (self, cp) {
            (LumpedStepper::Cpu(s), Checkpoint::Cpu(c)) => {
                s.restore(c);
                Ok(())
            }
            (LumpedStepper::Gpu(s), Checkpoint::Gpu(c)) => s.restore(c),
            _ => unreachable!("a checkpoint goes back to the stepper that made it"),
        }
    }

    /// Advances `n` steps.
    pub fn advance(&mut self, n: u64) -> Result<(), Error> {
        match self {
            LumpedStepper::Cpu(s) => s.advance(n),
            LumpedStepper::Gpu(s) => s.advance(n),
        }
    }
    /// Drives end `end` of cable `cable` from now on: its target moves from `position`
    /// (m) at `velocity` (m/s) in a straight line. CPU backend only.
    pub fn set_end_motion(
        &mut self,
        cable: usize,
        end: CableEnd,
        position: [f64; 3],
        velocity: [f64; 3],
    ) -> Result<(), Error> {
        let LumpedStepper::Cpu(s) = self else {
            return Err(Error::GpuUnsupported(
                "driving an end from outside (a coupling loop); use --backend cpu".into(),
            ));
        };
        let c = s.layout().cables.get(cable).ok_or_else(|| {
            Error::Model(format!(
                "no cable {cable} (the run has {})",
                s.layout().cables.len()
            ))
        })?;
        let node = match end {
            CableEnd::Start => c.nodes[0],
            CableEnd::End => c.nodes[c.nodes.len() - 1],
        } as usize;
        let name = c.name.clone();
        // r(t) = position + velocity (t - now), as a line route `start + velocity t`.
        let t = s.t();
        let start = [0, 1, 2].map(|i| position[i] - velocity[i] * t);
        s.set_route(node, Route::Line { start, velocity })
            .map_err(|e| Error::Model(format!("cable '{name}', {end:?} end: {e}")))
    }

    /// Node-steps taken (nodes times steps, counting the nodes each step had).
    pub fn node_steps(&self) -> u64 {
        match self {
            LumpedStepper::Cpu(s) => s.node_steps(),
            LumpedStepper::Gpu(s) => s.node_steps(),
        }
    }
    /// State of the winch cables.
    pub fn winch_status(&self) -> Vec<WinchStatus> {
        match self {
            LumpedStepper::Cpu(s) => s.winch_status(),
            LumpedStepper::Gpu(s) => s.winch_status(),
        }
    }
    /// Steps taken.
    pub fn steps(&self) -> u64 {
        match self {
            LumpedStepper::Cpu(s) => s.steps(),
            LumpedStepper::Gpu(s) => s.steps(),
        }
    }
    /// The packed model (the current mesh).
    pub fn layout(&self) -> &Layout {
        match self {
            LumpedStepper::Cpu(s) => s.layout(),
            LumpedStepper::Gpu(s) => s.layout(),
        }
    }
    /// Node positions and velocities (packed order; read back from the GPU), m, m/s.
    pub fn state(&mut self) -> Result<NodeStates, Error> {
        match self {
            LumpedStepper::Cpu(s) => Ok((
                s.r.iter().map(|x| x.to_f64()).collect(),
                s.v.iter().map(|x| x.to_f64()).collect(),
            )),
            LumpedStepper::Gpu(s) => s.state(),
        }
    }
    /// Tensions, reactions and accelerations at the current state.
    pub fn evaluate(&mut self) -> Result<Evaluation, Error> {
        match self {
            LumpedStepper::Cpu(s) => s.evaluate(),
            LumpedStepper::Gpu(s) => s.evaluate(),
        }
    }
    /// `(backend, device, precision)` for the summary.
    pub fn describe(&self) -> (&'static str, String, &'static str) {
        match self {
            LumpedStepper::Cpu(_) => ("cpu", cpu_name(), "f64"),
            LumpedStepper::Gpu(s) => ("gpu", s.device().to_string(), s.precision().name()),
        }
    }

    /// Every cable's state now, in layout order.
    pub fn cables(&mut self) -> Result<Vec<CableState>, Error> {
        let ev = self.evaluate()?;
        let (r, v) = self.state()?;
        Ok(self.cables_from(&ev, &r, &v))
    }

    /// Every vessel body's pose and load at time `t` (now).
    pub fn bodies(&mut self, t: f64) -> Result<Vec<BodyState>, Error> {
        if !self.has_bodies() {
            return Ok(Vec::new());
        }
        let ev = self.evaluate()?;
        let (r, _) = self.state()?;
        let dynamic = self.dynamic_bodies();
        Ok(crate::body::output::body_states(
            self.layout(),
            t,
            &r,
            &ev,
            &dynamic,
        ))
    }

    /// The shared points' states now. `points` names each point and where it is found:
    /// `(name, cable, at_start)`, the end of a cable (scenario order) attached to it.
    pub fn points(&mut self, points: &[(String, usize, bool)]) -> Result<Vec<PointState>, Error> {
        if points.is_empty() {
            return Ok(Vec::new());
        }
        let ev = self.evaluate()?;
        let (r, _) = self.state()?;
        Ok(self.points_from(points, &ev, &r))
    }

    /// [`Self::cables`], [`Self::bodies`] and [`Self::points`] at time `t` (now) from one
    /// evaluation and one read of the state: an output time evaluates the loads once
    /// (on the GPU, one evaluation dispatch and one read-back), not once per kind.
    pub fn snapshot_parts(
        &mut self,
        t: f64,
        points: &[(String, usize, bool)],
        nets: &[crate::model::cage::NetInfo],
    ) -> Result<SnapshotParts, Error> {
        let ev = match self {
            LumpedStepper::Cpu(s) => {
                let picked = crate::output::elements_read(s.layout(), nets);
                s.evaluate_keeping(Some(picked))?
            }
            LumpedStepper::Gpu(s) => s.evaluate()?,
        };
        // The CPU state read in place (a copy of it would cost 48 bytes a node).
        let read_back = match self {
            LumpedStepper::Gpu(s) => Some(s.state()?),
            LumpedStepper::Cpu(_) => None,
        };
        let (r, v) = match (&*self, &read_back) {
            (_, Some((r, v))) => (&r[..], &v[..]),
            (LumpedStepper::Cpu(s), None) => {
                (crate::math::as_arrays(&s.r), crate::math::as_arrays(&s.v))
            }
            (LumpedStepper::Gpu(_), None) => unreachable!("the GPU's state is read back above"),
        };
        let bodies = if self.has_bodies() {
            let dynamic = self.dynamic_bodies();
            crate::body::output::body_states(self.layout(), t, r, &ev, &dynamic)
        } else {
            Vec::new()
        };
        Ok((
            self.cables_from(&ev, r, v),
            bodies,
            self.points_from(points, &ev, r),
            crate::output::net_states(self.layout(), &ev, r, v, nets),
        ))
    }

    /// The free and pinned bodies' states now (both paths step them).
    fn dynamic_bodies(&self) -> Vec<crate::body::output::DynamicState> {
        match self {
            LumpedStepper::Cpu(s) => s.dynamic_bodies(),
            LumpedStepper::Gpu(s) => s.dynamic_bodies(),
        }
    }

    /// The line failures so far (both paths run them).
    pub fn failure_events(&self) -> Vec<crate::model::FailureEvent> {
        match self {
            LumpedStepper::Cpu(s) => s.failure_events(),
            LumpedStepper::Gpu(s) => s.failure_events(),
        }
    }

    /// Whether a cable end rides on a vessel body.
    fn has_bodies(&self) -> bool {
        self.layout()
            .routes
            .iter()
            .any(|r| matches!(r, Route::Body { .. }))
    }

    /// The cables' states from evaluation `ev` and positions and velocities `r`, `v`.
    fn cables_from(&self, ev: &Evaluation, r: &[[f64; 3]], v: &[[f64; 3]]) -> Vec<CableState> {
        let winches = self.winch_status();
        let lay = self.layout();
        lay.cables
            .iter()
            .enumerate()
            .map(|(ci, c)| CableState {
                name: c.name.clone(),
                output_positions: c.output_positions,
                positions: c.nodes.iter().map(|&i| r[i as usize]).collect(),
                velocities: c.nodes.iter().map(|&i| v[i as usize]).collect(),
                tensions: c.elements.iter().map(|&e| ev.tension[e as usize]).collect(),
                end_forces: end_forces(lay, ev, c),
                winch: winch_summary(&winches, ci),
            })
            .collect()
    }

    /// The shared points' states (as [`Self::points`]) from evaluation `ev` and
    /// positions `r`.
    fn points_from(
        &self,
        points: &[(String, usize, bool)],
        ev: &Evaluation,
        r: &[[f64; 3]],
    ) -> Vec<PointState> {
        if points.is_empty() {
            return Vec::new();
        }
        let lay = self.layout();
        let forces: Vec<EndForces> = lay.cables.iter().map(|c| end_forces(lay, ev, c)).collect();
        points
            .iter()
            .map(|(name, ci, at_start)| {
                let c = &lay.cables[*ci];
                let node = if *at_start {
                    c.nodes[0]
                } else {
                    c.nodes[c.nodes.len() - 1]
                };
                let k = lay.node_constraint[node as usize];
                let force = if k != NO_CONSTRAINT {
                    ev.reaction[k as usize]
                } else {
                    // Each cable's share at the node, summed over every end on it.
                    let mut f = [0.0; 3];
                    for (c, fc) in lay.cables.iter().zip(&forces) {
                        let ends = [(c.nodes[0], fc.start), (c.nodes[c.nodes.len() - 1], fc.end)];
                        for (n, fe) in ends {
                            if n == node {
                                (0..3).for_each(|d| f[d] += fe[d]);
                            }
                        }
                    }
                    f
                };
                PointState {
                    name: name.clone(),
                    position: r[node as usize],
                    force,
                }
            })
            .collect()
    }
}

fn winch_summary(winches: &[WinchStatus], cable: usize) -> Option<WinchSummary> {
    winches
        .iter()
        .find(|w| w.cable == cable)
        .map(|w| WinchSummary {
            deployed_length: w.deployed_length,
            variable_l0: w.variable_l0,
            elements: w.elements,
            nodes_inserted: w.inserted,
            nodes_deleted: w.deleted,
            physical_coordinates: w.physical_coordinates.clone(),
        })
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
