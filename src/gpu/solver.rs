//! The GPU stepper: the packed layout uploaded once, many steps per submission.
//!
//! With the fused kernel ([`GpuKernel::Fused`], chosen by [`fused_workgroup`] where it
//! applies) a submission is one dispatch of `fused_steps`, one workgroup per block,
//! looping over the submission's steps inside the shader (in waves, one dispatch from
//! each refresh of the kinematics cache to the next, the refresh dispatches of its
//! own, `wave_refresh` then `wave_refresh_due` over the nodes put on its work list,
//! then `wave_refresh_elems`: see
//! [`fused_segments`](super::wave_schedule::fused_segments)). With the
//! two-pass kernel a step is two dispatches in one compute pass, `element_forces` then
//! `node_update` (wgpu orders the storage writes of one dispatch before the reads of the
//! next). Both read the step's route and payout rows the same way, so the rest of this
//! note holds for both.
//! [`STEPS_PER_SUBMISSION`] steps go into one command buffer; the step index reaches
//! the shaders through a dynamic-offset uniform (one 16-byte `StepInfo` per step,
//! written once; the fused kernel's end step is written at each of its dispatches'
//! first step), so nothing is written between steps. Before each submission the
//! routes are rebased to its start time (see [`RouteParams`](super::layout::RouteParams)): the shaders evaluate
//! `r_d(t0 + tau)` with a small `tau`, which keeps f32 route positions and angles
//! accurate over long runs. Nothing is read back while stepping except, at the end of
//! an [`GpuSolver::advance`] call, the status; state, tensions and reactions
//! come back only when asked for, through one staging buffer created once per layout.
//!
//! Winch cables: per submission the host also writes the `payout` rows (one [`Payout`](super::layout::Payout)
//! per winch and step), and an `advance` call stops its submissions at each step after
//! which a winch cable must be remeshed, reads the state back, remeshes on the host
//! (`ale::AleState::remesh_in_place`, the CPU path's code), rebuilds the layout's buffers
//! and bind group (the pipelines stay) and uploads the state: see [`GpuSolver`].
//!
//! This file holds the public API ([`GpuSolver`], [`GpuCheckpoint`], [`GpuTimings`],
//! [`unsupported`], [`unsupported_winches`]); the machinery this note describes lives
//! in the private modules `kernel`, `host`, `wave_schedule` and `engine` (see
//! [`crate::gpu`]), whose public items are re-exported here.
use super::context::GpuContext;
use super::engine::{Engine, GpuEngine};
use super::host::Host;
use super::kernel::{kernel_from_env, WORKGROUP};
use crate::ale::{advance_with_winches, AleState, MeshStepper, Winch};
use crate::error::Error;
use crate::math::V3;
use crate::model::{Layout, ModelDef};
use crate::options::Precision;
use crate::options::{Formulation, Scheme, SolverOptions};
use crate::sea::{SeaSet, SeaState};
use crate::step::{diverged, Evaluation, StepFailure, WinchStatus};

// The public items of the split-out modules, at the paths they have always had.
pub use super::host::{body_rows, rebased_route, route_samples, HingeRows, NodeStates, NO_HINGE};
pub use super::kernel::{fused_workgroup, GpuKernel, MAX_FUSED_WORKGROUP, STEPS_PER_SUBMISSION};

/// The bending hinges the GPU path cannot hold, or `None` (it runs bending stiffness
/// and clamped ends: [`HingeRows`]; a run with winch cables has no bending in the
/// lumped-mass model: [`GpuSolver::with_winches`]).
pub fn unsupported_bending(lay: &Layout) -> Option<String> {
    if !lay.has_bending() {
        return None;
    }
    HingeRows::new(lay, 0)
        .err()
        .map(|why| format!("{why}; the CPU path runs it"))
}

/// What the GPU solver does not do yet, or `None`.
pub fn unsupported(lay: &Layout, opts: &SolverOptions) -> Option<String> {
    // Free and pinned bodies run on the GPU (shaders/shared/free_body.wgsl) but for
    // a 6x6 stiffness matrix (its rotation's logarithm) and a table of loads.
    for r in &lay.routes {
        let crate::model::Route::Body { body, .. } = r else {
            continue;
        };
        let Some(d) = body.dynamic() else {
            continue;
        };
        let sp = &d.body.spec;
        if sp.stiffness.iter().flatten().any(|&x| x != 0.0) {
            return Some(format!(
                "a free body's 6x6 stiffness matrix (body '{}'; the CPU path runs it)",
                body.name
            ));
        }
        if sp.loads.is_some() {
            return Some(format!(
                "a free body's table of external loads (body '{}'; the CPU path runs it)",
                body.name
            ));
        }
    }
    if opts.formulation != Formulation::Glmf {
        return Some(format!(
            "the {} formulation (the GPU path is GLMF only)",
            opts.formulation.name()
        ));
    }
    if opts.scheme != Scheme::Symplectic {
        return Some(format!(
            "the {} scheme (the GPU path is symplectic Euler only so far)",
            opts.scheme.name()
        ));
    }
    // One invocation per node or element along x only, so far.
    let most = 65_535 * WORKGROUP as usize;
    if lay.n_nodes() > most || lay.n_elements() > most {
        return Some(format!(
            "more than {most} nodes or elements (one dispatch dimension)"
        ));
    }
    None
}

pub use super::engine::GpuTimings;

/// The GPU solver: the same packed model and options as [`crate::cpu::CpuSolver`],
/// stepped by WGSL compute shaders at f32 or f64.
///
/// Winch cables (ALE-GLMF, [`crate::ale`]; [`GpuSolver::with_winches`]) step inside
/// the same submissions as every other cable: the variable element's `l0_v(t)`, payout
/// rate and acceleration of each step are written by the host per submission (one
/// small row per winch and step, from the schedule, in f64 as the CPU path forms them),
/// and the shaders apply the variable `l0` (its mass, weight, added mass, stretch and
/// tributary lengths), the ALE strain-rate damping and the mass-flow forces of Eq. 39.
/// The schedule fixes in advance the step at which a cable must be remeshed, so an
/// [`GpuSolver::advance`] call ends its submissions exactly there, reads the state
/// back, remeshes on the host with the CPU path's code (`WinchTracker` and the same
/// node insertion or deletion, spliced into the host's packed layout), uploads the
/// layout's buffers (the pipelines are kept), and goes on: one round trip per remeshing, every `l_s / Ldot`
/// seconds, none per step.
pub struct GpuSolver {
    /// The packed model (the current mesh, with winches).
    layout: Layout,
    /// Options (GLMF, symplectic Euler; see [`unsupported`]).
    opts: SolverOptions,
    /// Shader precision.
    precision: Precision,
    /// Simulated time, s.
    t: f64,
    /// Number of steps taken.
    steps: u64,
    /// Node-steps taken: nodes times steps, summed over the meshes a run went through.
    node_steps: u64,
    /// Remeshings of winch cables so far (each one state read-back and re-upload).
    remeshes: u64,
    device: String,
    host: Host,
    engine: Box<dyn Engine>,
    /// Winch cables, if any.
    ale: Option<Box<AleState>>,
    /// The free and pinned bodies' states, read back after each `advance` call (one
    /// per `host.free`).
    free_states: Vec<crate::body::free::FreeBody>,
    /// Cable ends that may fail, and those that did.
    failures: Vec<GpuFailure>,
}

/// A cable end that may fail on the GPU path.
#[derive(Clone, Debug)]
struct GpuFailure {
    spec: crate::model::EndFailure,
    node: usize,
    elem: usize,
    constraint: usize,
    fired: Option<crate::model::FailureEvent>,
}

impl GpuSolver {
    /// The packed model (the current mesh, with winches).
    pub fn layout(&self) -> &Layout {
        &self.layout
    }
    /// The options it steps with.
    pub fn opts(&self) -> &SolverOptions {
        &self.opts
    }
    /// Shader precision.
    pub fn precision(&self) -> Precision {
        self.precision
    }
    /// Simulated time, s.
    pub fn t(&self) -> f64 {
        self.t
    }
    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// Node-steps taken: nodes times steps, summed over the meshes a run went through.
    pub fn node_steps(&self) -> u64 {
        self.node_steps
    }
    /// Remeshings of winch cables so far (each one state read-back and re-upload).
    pub fn remeshes(&self) -> u64 {
        self.remeshes
    }

    /// Uploads the model, at rest at `positions` (packed order), `t = 0`.
    pub fn new(
        ctx: &GpuContext,
        layout: Layout,
        positions: &[[f64; 3]],
        opts: SolverOptions,
        precision: Precision,
    ) -> Result<Self, Error> {
        Self::build(ctx, layout, positions, opts, precision, None)
    }

    /// Uploads the model of `def`, at rest at `positions` (packed order of
    /// `Layout::build(&def)`), `t = 0`, whose cables listed in `winches` pay out or
    /// haul in (ALE-GLMF), as [`crate::cpu::CpuSolver::with_winches`] does on the CPU.
    pub fn with_winches(
        ctx: &GpuContext,
        def: ModelDef,
        winches: Vec<Winch>,
        positions: &[[f64; 3]],
        opts: SolverOptions,
        precision: Precision,
    ) -> Result<Self, Error> {
        if winches.is_empty() {
            let (lay, _) = Layout::build(&def)?;
            return Self::new(ctx, lay, positions, opts, precision);
        }
        // A run with winch cables has no bending in the lumped-mass model yet (the
        // variable elements' hinges are not built): `ei` is the ANCF reference's only,
        // as the scenario's warning says.
        let mut def = def;
        for lt in &mut def.line_types {
            lt.ei = 0.0;
        }
        if let Some(what) = unsupported_winches(&def, &winches) {
            return Err(Error::GpuUnsupported(what));
        }
        let (lay, pos0, packed) = Layout::build_indexed(&def)?;
        if pos0.len() != positions.len() {
            return Err(Error::Model(format!(
                "{} initial positions for {} nodes",
                positions.len(),
                pos0.len()
            )));
        }
        let mut ale = AleState::new(def, winches, packed)?;
        ale.index(&lay);
        Self::build(ctx, lay, positions, opts, precision, Some(Box::new(ale)))
    }

    fn build(
        ctx: &GpuContext,
        layout: Layout,
        positions: &[[f64; 3]],
        opts: SolverOptions,
        precision: Precision,
        ale: Option<Box<AleState>>,
    ) -> Result<Self, Error> {
        if let Some(what) = unsupported(&layout, &opts).or_else(|| unsupported_bending(&layout)) {
            return Err(Error::GpuUnsupported(what));
        }
        if !ctx.supports(precision) {
            return Err(Error::NoAdapter(format!(
                "{} has no SHADER_F64: f64 shaders cannot run (use --precision f32)",
                ctx.describe()
            )));
        }
        let host = Host::new(&layout, positions, ale.as_deref())?;
        let engine: Box<dyn Engine> = match precision {
            Precision::F32 => Box::new(GpuEngine::<f32>::new(
                ctx, &layout, &host, positions, &opts,
            )?),
            Precision::F64 => Box::new(GpuEngine::<f64>::new(
                ctx, &layout, &host, positions, &opts,
            )?),
        };
        let mut engine = engine;
        if let Some(k) = kernel_from_env()? {
            engine.set_kernel(k)?;
        }
        if ale.is_some() && !host.free.is_empty() {
            return Err(Error::GpuUnsupported(
                "winch cables and free or pinned bodies in one run are not supported yet".into(),
            ));
        }
        let free_states = host
            .free
            .iter()
            .map(|f| f.body.dynamic().expect("free").body.clone())
            .collect();
        Ok(Self {
            free_states,
            failures: Vec::new(),
            layout,
            opts,
            precision,
            t: 0.0,
            steps: 0,
            node_steps: 0,
            remeshes: 0,
            device: ctx.describe(),
            host,
            engine,
            ale,
        })
    }

    /// The adapter it runs on.
    pub fn device(&self) -> &str {
        &self.device
    }

    /// Where the wall time of [`Self::advance`] went so far (host recording, submission,
    /// waiting for the device).
    pub fn timings(&self) -> GpuTimings {
        self.engine.timings()
    }

    /// The kernel [`Self::advance`] uses: [`GpuKernel::Fused`] where it applies
    /// ([`fused_workgroup`]), unless [`Self::set_kernel`] or the environment variable
    /// `CABLESIM_GPU_KERNEL=two-pass` asked for the two-pass path.
    pub fn kernel(&self) -> GpuKernel {
        self.engine.kernel()
    }

    /// Why the fused kernel cannot step this layout on this adapter, or `None`.
    pub fn fused_unavailable(&self) -> Option<&str> {
        self.engine.fused_unavailable()
    }

    /// Chooses the kernel of later [`Self::advance`] calls (both step the same
    /// physics; results agree to round-off). Asking for [`GpuKernel::Fused`] where it
    /// does not apply is an error.
    pub fn set_kernel(&mut self, k: GpuKernel) -> Result<(), Error> {
        self.engine.set_kernel(k)
    }

    /// Where each winch cable stands now (empty without winches).
    pub fn winch_status(&self) -> Vec<WinchStatus> {
        self.ale
            .as_deref()
            .map_or_else(Vec::new, |a| a.status(self.t))
    }

    /// Advances `nsteps` steps of `opts.dt`, in submissions of
    /// [`STEPS_PER_SUBMISSION`] steps, then reads the 16-byte status. On a blow-up the
    /// state stays where it failed and the error names the cable, node and time, as on
    /// the CPU. With winches, the submissions end at each step after which a winch
    /// cable must be remeshed (known in advance from the schedules); the state is read
    /// back, remeshed on the host as on the CPU path, and uploaded with the new layout.
    pub fn advance(&mut self, nsteps: u64) -> Result<(), Error> {
        advance_with_winches(self, nsteps)
    }

    /// Reads the state back, remeshes the winch cables at the current time and
    /// installs the new layout and state.
    fn remesh(&mut self) -> Result<(), Error> {
        let (r, v) = self.engine.download(&self.host)?;
        let mut r: Vec<V3<f64>> = r.iter().map(|p| V3::from_f64(*p)).collect();
        let mut v: Vec<V3<f64>> = v.iter().map(|p| V3::from_f64(*p)).collect();
        let ale = self.ale.as_deref_mut().expect("winches");
        // The host's layout is spliced in place where it can be (as on the CPU path);
        // the device buffers are uploaded whole.
        if ale.remesh_in_place(self.t, &mut self.layout, &mut r, &mut v)? {
            let r: Vec<[f64; 3]> = r.iter().map(|x| x.to_f64()).collect();
            let v: Vec<[f64; 3]> = v.iter().map(|x| x.to_f64()).collect();
            self.host = Host::new(&self.layout, &r, Some(ale))?;
            self.engine.install(&self.layout, &self.host, &r, &v)?;
            self.remeshes += 1;
        }
        Ok(())
    }

    /// Advances `nsteps` steps on the current mesh.
    fn advance_fixed(&mut self, nsteps: u64) -> Result<(), Error> {
        if nsteps == 0 {
            return Ok(());
        }
        let step0 = self.steps;
        let failed = self
            .engine
            .advance(&self.layout, &self.host, step0, nsteps)?;
        self.steps += nsteps;
        self.node_steps += nsteps * self.layout.n_nodes() as u64;
        self.t = self.steps as f64 * self.opts.dt;
        self.read_free(step0)?;
        if let Some((k, node)) = failed {
            let (r, v) = self.engine.download(&self.host)?;
            let i = node as usize;
            let time = (step0 + k + 1) as f64 * self.opts.dt;
            let f = diverged(&self.opts, V3::from_f64(r[i]), V3::from_f64(v[i]), i, time);
            if let StepFailure::Diverged { node, time, what } = f {
                let (cable, node) = self.layout.describe_node(node);
                return Err(Error::Diverged {
                    cable,
                    node,
                    time,
                    what: format!("{what} (GPU, {})", self.precision.name()),
                });
            }
        }
        Ok(())
    }

    /// Reads the free bodies' states and the failures' records back after an
    /// `advance` call from step `step0` (nothing without them), logs and records the
    /// failures that fired, and writes the unfired ones' time steps for the next call.
    fn read_free(&mut self, step0: u64) -> Result<(), Error> {
        if self.host.free.is_empty() && self.failures.is_empty() {
            return Ok(());
        }
        let (rec, _) = self.engine.read_free()?;
        let dyn_stride = super::host::FREE_STRIDE;
        for (i, f) in self.host.free.iter().enumerate() {
            self.free_states[i] =
                super::host::free_state_of(f, &rec[i * dyn_stride..(i + 1) * dyn_stride]);
        }
        let fo = self.engine.fail_offset();
        let fs = super::host::FAIL_STRIDE;
        let mut fired = false;
        for (j, f) in self.failures.iter_mut().enumerate() {
            let r = &rec[fo + j * fs..fo + (j + 1) * fs];
            if f.fired.is_some() || r[5] == 0.0 {
                continue;
            }
            let t = (step0 + r[6] as u64) as f64 * self.opts.dt;
            let tension = r[7];
            let trigger = if r[5] == 1.0 { "time" } else { "tension" };
            let end = if f.spec.at_start { "start" } else { "end" };
            log::warn!(
                "t = {t} s: cable '{}' failed at its {end} ({trigger}; end tension {tension:.6e} N): the end is free from now on (GPU)",
                f.spec.cable
            );
            f.fired = Some(crate::model::FailureEvent {
                time: t,
                cable: f.spec.cable.clone(),
                end: end.into(),
                tension,
                trigger: trigger.into(),
            });
            self.layout.node_constraint[f.node] = crate::model::NO_CONSTRAINT;
            fired = true;
        }
        let _ = fired;
        self.write_failures();
        Ok(())
    }

    /// Writes the failures' records for the next `advance` call: each unfired one's
    /// time as a step count from the call's start.
    fn write_failures(&mut self) {
        let fs = super::host::FAIL_STRIDE;
        let mut rec = vec![0.0; self.failures.len() * fs];
        for (j, f) in self.failures.iter().enumerate() {
            let r = &mut rec[j * fs..(j + 1) * fs];
            r[0] = f.node as f64;
            r[1] = f.elem as f64;
            r[2] = f.constraint as f64;
            // The first step count n with n dt >= time (the CPU path's test, after
            // each step, of t = n dt).
            r[3] = match f.spec.time {
                Some(time) => {
                    let dt = self.opts.dt;
                    let mut n = (time / dt).ceil().max(0.0) as u64;
                    while (n as f64) * dt < time {
                        n += 1;
                    }
                    while n > 0 && ((n - 1) as f64) * dt >= time {
                        n -= 1;
                    }
                    n.saturating_sub(self.steps) as f64
                }
                None => -1.0,
            };
            r[4] = f.spec.tension.unwrap_or(0.0);
            if let Some(e) = &f.fired {
                r[5] = if e.trigger == "time" { 1.0 } else { 2.0 };
            }
        }
        self.engine.write_failures(&rec, self.failures.len());
    }

    /// The cable ends that may fail during the run (each held by a fixed point, a
    /// route or a body), as [`crate::cpu::CpuSolver::set_failures`]: detected on the
    /// device after each step, read back at the end of each `advance` call. `Err`
    /// names an end that is not held or a cable not found.
    pub fn set_failures(&mut self, failures: &[crate::model::EndFailure]) -> Result<(), Error> {
        let lay = &self.layout;
        let mut out = Vec::with_capacity(failures.len());
        for f in failures {
            let site = f.site(lay).map_err(Error::Model)?;
            out.push(GpuFailure {
                spec: f.clone(),
                node: site.node,
                elem: site.elem,
                constraint: site.constraint,
                fired: None,
            });
        }
        if let Some(what) = unsupported_failures(lay, failures) {
            return Err(Error::GpuUnsupported(what));
        }
        if out.len() > lay.routes.len() {
            return Err(Error::GpuUnsupported(format!(
                "{} line failures on {} held ends",
                out.len(),
                lay.routes.len()
            )));
        }
        self.failures = out;
        self.write_failures();
        Ok(())
    }

    /// The failures so far, in the order they fired.
    pub fn failure_events(&self) -> Vec<crate::model::FailureEvent> {
        let mut v: Vec<_> = self
            .failures
            .iter()
            .filter_map(|f| f.fired.clone())
            .collect();
        v.sort_by(|a, b| a.time.total_cmp(&b.time));
        v
    }

    /// The free and pinned bodies' states now (as read back after the last `advance`
    /// call; empty without).
    pub fn dynamic_bodies(&self) -> Vec<crate::body::output::DynamicState> {
        self.host
            .free
            .iter()
            .zip(&self.free_states)
            .map(|(f, s)| crate::body::output::DynamicState {
                body: f.body.clone(),
                state: s.body_state(),
                angles: s.angles(),
            })
            .collect()
    }

    /// Runs in the sea state `sea` from now on (still water when it has no
    /// components), as [`crate::cpu::CpuSolver`]'s stepper does with its kinematics
    /// cache: the same refresh times, the same interpolation, the same loads.
    pub fn set_sea(&mut self, sea: &SeaState) -> Result<(), Error> {
        self.set_seas(&SeaSet::single(sea))
    }

    /// [`GpuSolver::set_sea`] with a sea per cable (a packed model's members,
    /// `sea::set`): each block reads its cable's sea, refreshed on that sea's own
    /// schedule, as [`crate::cpu::CpuSolver::set_seas`] does.
    pub fn set_seas(&mut self, seas: &SeaSet) -> Result<(), Error> {
        self.engine.set_seas(&self.layout, &self.host, seas)
    }

    /// Reads back node positions (absolute, m) and velocities (m/s), packed order.
    pub fn state(&mut self) -> Result<NodeStates, Error> {
        self.engine.download(&self.host)
    }

    /// Reads back the elements' internal states (a viscoelastic line's static-branch
    /// strain, `physics::visco`; zero for every other element), packed element order;
    /// empty without viscoelastic lines.
    pub fn visco_states(&mut self) -> Result<Vec<f64>, Error> {
        if self.layout.has_visco() {
            self.engine.read_visco()
        } else {
            Ok(Vec::new())
        }
    }

    /// The state now, to go back to with [`GpuSolver::restore`] (read back from the
    /// device). With winches it also keeps the host's side of the mesh (layout, host
    /// data, winch state), since a remeshing after it replaces them.
    pub fn checkpoint(&mut self) -> Result<GpuCheckpoint, Error> {
        let (r, v) = self.engine.download(&self.host)?;
        let mesh = self.ale.as_ref().map(|ale| {
            Box::new(SavedMesh {
                layout: self.layout.clone(),
                host: self.host.clone(),
                ale: ale.clone(),
                remeshes: self.remeshes,
            })
        });
        let free = if self.host.free.is_empty() && self.failures.is_empty() {
            None
        } else {
            let (rec, flags) = self.engine.read_free()?;
            Some(Box::new(SavedFree {
                rec,
                flags,
                states: self.free_states.clone(),
                failures: self.failures.clone(),
                constraints: self.layout.node_constraint.clone(),
            }))
        };
        let visco = if self.layout.has_visco() {
            self.engine.read_visco()?
        } else {
            Vec::new()
        };
        Ok(GpuCheckpoint {
            steps: self.steps,
            node_steps: self.node_steps,
            r,
            v,
            visco,
            mesh,
            free,
        })
    }

    /// Goes back to the state `cp`, taken from this solver. Where a winch cable was
    /// remeshed since, the saved layout is installed again (as a remeshing installs
    /// its new one); an error there is the device's, when rebuilding the buffers.
    pub fn restore(&mut self, cp: &GpuCheckpoint) -> Result<(), Error> {
        if let Some(m) = &cp.mesh {
            if m.remeshes != self.remeshes {
                self.engine.install(&m.layout, &m.host, &cp.r, &cp.v)?;
                self.layout.clone_from(&m.layout);
                self.host = m.host.clone();
            }
            self.ale = Some(m.ale.clone());
            self.remeshes = m.remeshes;
        }
        self.steps = cp.steps;
        self.node_steps = cp.node_steps;
        self.t = self.steps as f64 * self.opts.dt;
        self.engine.upload(&self.host, &cp.r, &cp.v);
        if !cp.visco.is_empty() {
            self.engine.write_visco(&cp.visco);
        }
        if let Some(f) = &cp.free {
            self.engine.write_free(&f.rec, &f.flags);
            self.free_states.clone_from(&f.states);
            self.failures.clone_from(&f.failures);
            self.layout.node_constraint.clone_from(&f.constraints);
            // The unfired failures' steps counted from the next call's start.
            self.write_failures();
        }
        // The cache holds values for times ahead of the state now: it starts afresh
        // (so a replay agrees with the first pass within the cache's tolerance).
        self.engine.restart_waves();
        Ok(())
    }

    /// Replaces node positions and velocities (packed order). The waves' cache starts
    /// afresh (it holds values along the nodes' old paths): the next step or
    /// evaluation evaluates the sum at the state set.
    pub fn set_state(&mut self, r: &[[f64; 3]], v: &[[f64; 3]]) {
        assert_eq!(r.len(), self.layout.n_nodes());
        assert_eq!(v.len(), self.layout.n_nodes());
        self.engine.upload(&self.host, r, v);
        self.engine.restart_waves();
    }

    /// Loads, accelerations and reactions at the current state, evaluated on the GPU
    /// (an `element_forces` and a `node_evaluate` dispatch) and read back. A winch
    /// cable's variable element is evaluated at the current time. In waves, with the
    /// kinematics the next step starts from: the cache interpolated at the current
    /// time, refreshed first (a `wave_refresh` dispatch) where that step would refresh
    /// it, as on the CPU path ([`crate::cpu::CpuSolver::evaluate`]).
    pub fn evaluate(&mut self) -> Result<Evaluation, Error> {
        self.engine.evaluate(&self.layout, &self.host, self.steps)
    }

    /// Where the waves' caches stand (`sea::bands`): per band, how many nodes refresh
    /// in it now, and how many times a node was found above its band's top (and
    /// beyond the margin), read back from the device; as
    /// [`crate::cpu::CpuSolver::wave_band_census`].
    pub fn wave_band_census(&self) -> Result<crate::sea::bands::BandCensus, Error> {
        self.engine.wave_band_census()
    }
}

impl MeshStepper for GpuSolver {
    fn ale(&self) -> Option<&AleState> {
        self.ale.as_deref()
    }

    fn steps(&self) -> u64 {
        self.steps
    }

    fn dt(&self) -> f64 {
        self.opts.dt
    }

    fn advance_fixed(&mut self, nsteps: u64) -> Result<(), Error> {
        GpuSolver::advance_fixed(self, nsteps)
    }

    fn remesh(&mut self) -> Result<(), Error> {
        GpuSolver::remesh(self)
    }
}

/// A GPU run's state at one step ([`GpuSolver::checkpoint`]).
pub struct GpuCheckpoint {
    /// Steps taken.
    pub steps: u64,
    node_steps: u64,
    r: Vec<[f64; 3]>,
    v: Vec<[f64; 3]>,
    /// The elements' internal states (viscoelastic lines; empty without).
    visco: Vec<f64>,
    /// With winches: the mesh then.
    mesh: Option<Box<SavedMesh>>,
    /// With free bodies or failures: their records then.
    free: Option<Box<SavedFree>>,
}

/// The free bodies' and failures' side of a checkpoint.
struct SavedFree {
    rec: Vec<f64>,
    flags: Vec<f64>,
    states: Vec<crate::body::free::FreeBody>,
    failures: Vec<GpuFailure>,
    constraints: Vec<u32>,
}

/// The host's side of a winch run's mesh at a checkpoint.
struct SavedMesh {
    layout: Layout,
    host: Host,
    ale: Box<AleState>,
    /// [`GpuSolver::remeshes`] then: the device holds another layout where it differs.
    remeshes: u64,
}

/// What of a run's line failures the GPU path does not do, or `None`: the cables of a
/// failing `[[points]]` entry share its node and go together (the CPU path releases
/// the others when one fires); the device tests each failure on its own, so by time
/// they fire at the same step, by tension they would not, and that case stays on the
/// CPU.
pub fn unsupported_failures(lay: &Layout, failures: &[crate::model::EndFailure]) -> Option<String> {
    let node = |f: &crate::model::EndFailure| f.site(lay).ok().map(|s| s.node);
    failures.iter().enumerate().find_map(|(i, a)| {
        let na = node(a)?;
        let shared = failures
            .iter()
            .enumerate()
            .any(|(j, b)| j != i && node(b) == Some(na));
        (a.tension.is_some() && shared).then(|| {
            format!(
                "a point that fails by tension with several cables (cable '{}'; the CPU path runs it)",
                a.cable
            )
        })
    })
}

/// What the GPU path cannot do with these winches, or `None`: two winch cables that
/// share a node (a node of both variable elements after remeshing would need two
/// mass-flow forces; the CPU path runs them).
pub fn unsupported_winches(def: &ModelDef, winches: &[Winch]) -> Option<String> {
    let mut owner: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    for w in winches {
        let c = def.cables.get(w.cable)?;
        for &n in &c.nodes {
            if let Some(&o) = owner.get(&n) {
                if o != w.cable {
                    return Some(format!(
                        "winch cables '{}' and '{}' sharing a node (ALE-GLMF on the GPU)",
                        def.cables[o].name, c.name
                    ));
                }
            }
            owner.insert(n, w.cable);
        }
    }
    None
}
