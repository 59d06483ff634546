//! Passes and schemes of the CPU reference path (see the module doc of `cpu`).

use super::chain::{advance_chain, ChainConsts, ChainScratch};
use super::water::{node_water, BlockWaves, Water};
use crate::ale::{mass_flow_forces, AleElem, AleState, Winch};
use crate::error::Error;
use crate::math::{Sym3, V3};
use crate::model::{Block, Layout, ModelDef, Route, NO_CONSTRAINT};
use crate::options::{Formulation, Scheme, SolverOptions};
use crate::physics::frames::{frame_element, frenet_virtual_node};
use crate::physics::{
    glmf_element_wet, point_wetted_fraction, seabed_damping, seabed_force, wetted_fraction, Coefs,
    ElementInput, ElementLoads, SeabedCoefs,
};
use crate::sea::cache::{evaluate_nodes, CACHE_STRIDE};
use crate::sea::kinematics::WaveField;
use crate::sea::{SeaSet, SeaState};
use crate::step::{blow_up, Evaluation, StepFailure, WinchStatus};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

type V = V3<f64>;

/// Per-node scratch of the Runge-Kutta schemes.
#[derive(Clone, Copy, Debug, Default)]
struct NodeScratch {
    r0: V,
    v0: V,
    sr: V,
    sv: V,
    acc: V,
}

/// Read-only context of the passes.
struct Ctx<'a> {
    lay: &'a Layout,
    coefs: &'a [Coefs<f64>],
    seabed: SeabedCoefs<f64>,
    opts: SolverOptions,
    elem_in_cable: &'a [u32],
    /// Per current profile: its value when uniform (looked up without a table walk).
    uniform_current: &'a [Option<V>],
    /// Gravity, m/s^2 (the dry weight of what is above the water surface).
    gravity: f64,
    /// The step with which the seabed's damping terms are taken implicitly in the
    /// node solve, `(M + h diag(c)) a = F` (the symplectic scheme: `h = dt`); 0 for
    /// the explicit acceleration (Runge-Kutta stages, evaluation).
    implicit_dt: f64,
}

/// The f64 reference solver: layout, state, and scratch.
#[derive(Clone)]
pub struct CpuSolver {
    /// The packed model.
    layout: Layout,
    /// Options.
    opts: SolverOptions,
    /// Simulated time, s.
    t: f64,
    /// Number of steps taken.
    steps: u64,
    /// Node positions, m.
    pub r: Vec<V>,
    /// Node velocities, m/s.
    pub v: Vec<V>,
    coefs: Vec<Coefs<f64>>,
    elem_in_cable: Vec<u32>,
    uniform_current: Vec<Option<V>>,
    elems: Vec<ElementLoads<f64>>,
    scratch: Vec<NodeScratch>,
    /// Per block: constants of the chain fast path (`None` for networks).
    chain_consts: Vec<Option<ChainConsts>>,
    /// Use the vectorised fast path for chain blocks (GLMF only). On by default; the
    /// general path is the reference the fast path is tested against.
    pub use_chain_kernel: bool,
    /// Groups of consecutive blocks handed to one task each.
    chunks: Vec<std::ops::Range<usize>>,
    /// Winch cables (ALE-GLMF), if any.
    ale: Option<Box<AleState>>,
    /// Node-steps taken: nodes times steps, summed over the meshes a run went through.
    node_steps: u64,
    /// The seas and each cable's (`None`: still water everywhere).
    seas: Option<SeaSet>,
    /// Per sea: its field, for exact evaluation at output times.
    wave_fields: Vec<WaveField>,
    /// Per block: its wave kinematics cache (empty in still water).
    wave_blocks: Vec<BlockWaves>,
    /// Evaluate the waves' component sum at every stage instead of interpolating the
    /// kinematics cache (the reference the cache is tested against; slow).
    exact_waves: bool,
}

/// The state of a [`CpuSolver`] at one step: positions and velocities where that is all
/// it carries from step to step (a fixed mesh in still water: element loads and scratch
/// are recomputed each step); the whole solver where more is (winch cables, whose mesh
/// and payout change, and the waves' kinematics cache).
#[derive(Clone)]
pub struct CpuCheckpoint {
    /// Steps taken.
    pub steps: u64,
    saved: Saved,
}

#[derive(Clone)]
enum Saved {
    State {
        t: f64,
        node_steps: u64,
        r: Vec<V>,
        v: Vec<V>,
    },
    Whole(Box<CpuSolver>),
}

impl std::fmt::Debug for CpuCheckpoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CpuCheckpoint")
            .field("steps", &self.steps)
            .finish_non_exhaustive()
    }
}

impl CpuSolver {
    /// The state now, to go back to with [`CpuSolver::restore`].
    pub fn checkpoint(&self) -> Option<CpuCheckpoint> {
        let saved = if self.ale.is_some() || !self.wave_blocks.is_empty() {
            Saved::Whole(Box::new(self.clone()))
        } else {
            Saved::State {
                t: self.t,
                node_steps: self.node_steps,
                r: self.r.clone(),
                v: self.v.clone(),
            }
        };
        Some(CpuCheckpoint {
            steps: self.steps,
            saved,
        })
    }

    /// Goes back to the state `cp`, taken from this solver.
    pub fn restore(&mut self, cp: &CpuCheckpoint) {
        match &cp.saved {
            Saved::State {
                t,
                node_steps,
                r,
                v,
            } => {
                self.steps = cp.steps;
                self.t = *t;
                self.node_steps = *node_steps;
                self.r.clone_from(r);
                self.v.clone_from(v);
            }
            Saved::Whole(w) => *self = (**w).clone(),
        }
    }

    /// The packed model (the current mesh, with winches).
    pub fn layout(&self) -> &Layout {
        &self.layout
    }
    /// The options it steps with.
    pub fn opts(&self) -> &SolverOptions {
        &self.opts
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

    /// A solver at rest at `positions` (packed order), `t = 0`.
    pub fn new(layout: Layout, positions: &[[f64; 3]], opts: SolverOptions) -> Self {
        let mut s = Self {
            chain_consts: Vec::new(),
            use_chain_kernel: true,
            uniform_current: Vec::new(),
            opts,
            t: 0.0,
            steps: 0,
            r: Vec::new(),
            v: Vec::new(),
            coefs: Vec::new(),
            elem_in_cable: Vec::new(),
            elems: Vec::new(),
            scratch: Vec::new(),
            chunks: Vec::new(),
            layout: Layout::build(&ModelDef::default())
                .expect("an empty model packs")
                .0,
            ale: None,
            node_steps: 0,
            seas: None,
            wave_fields: Vec::new(),
            wave_blocks: Vec::new(),
            exact_waves: false,
        };
        let r = positions.iter().map(|p| V::from_f64(*p)).collect();
        let v = vec![V::zero(); positions.len()];
        s.install(layout, r, v);
        s
    }

    /// A solver at rest at `positions` (packed order of `Layout::build(&def)`), `t = 0`,
    /// whose cables listed in `winches` pay out or haul in (ALE-GLMF, [`crate::ale`]).
    /// The description is kept: remeshing edits it and repacks the layout. Only the
    /// GLMF formulation supports winches.
    pub fn with_winches(
        def: ModelDef,
        winches: Vec<Winch>,
        positions: &[[f64; 3]],
        opts: SolverOptions,
    ) -> Result<Self, Error> {
        if winches.is_empty() {
            let (lay, _) = Layout::build(&def)?;
            return Ok(Self::new(lay, positions, opts));
        }
        if opts.formulation != Formulation::Glmf {
            return Err(Error::Model(format!(
                "cable '{}' has a winch: ALE-GLMF needs the glmf formulation, not {}",
                def.cables
                    .get(winches[0].cable)
                    .map_or("?", |c| c.name.as_str()),
                opts.formulation.name()
            )));
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
        let mut s = Self::new(lay, positions, opts);
        s.ale = Some(Box::new(ale));
        // Winch blocks take the general passes.
        s.install_chain_consts();
        Ok(s)
    }

    /// Runs in the sea state `sea` from now on (still water when it has no
    /// components): water velocity = current + wave velocity, the wave acceleration in
    /// the water-acceleration loads, the surface elevation in the wetted fractions.
    /// With `exact`, the component sum is evaluated at every node at every stage
    /// instead of through the kinematics cache (`sea::cache`).
    pub fn set_sea(&mut self, sea: &SeaState, exact: bool) {
        self.set_seas(&SeaSet::single(sea), exact);
    }

    /// [`CpuSolver::set_sea`] with a sea per cable (a packed model's members,
    /// `sea::set`): each block gets the kinematics cache of its cable's sea, with that
    /// sea's own refresh interval, exactly as in a run of that sea alone.
    pub fn set_seas(&mut self, seas: &SeaSet, exact: bool) {
        self.exact_waves = exact;
        if seas.is_still() {
            self.seas = None;
            self.wave_fields = Vec::new();
        } else {
            self.seas = Some(seas.clone());
            self.wave_fields = seas.seas.iter().map(WaveField::new).collect();
        }
        self.install_waves();
    }

    /// The sea index of the block starting at packed node `n0`.
    fn block_sea(&self, seas: &SeaSet, n0: usize) -> usize {
        seas.sea_of_cable(self.layout.node_cable[n0] as usize)
    }

    /// One wave cache per block, in its cable's sea (none in still water).
    fn install_waves(&mut self) {
        self.wave_blocks = match &self.seas {
            None => Vec::new(),
            Some(seas) => self
                .layout
                .blocks
                .iter()
                .map(|b| {
                    let sea = &seas.seas[self.block_sea(seas, b.node_start as usize)];
                    BlockWaves::new(sea, (b.node_end - b.node_start) as usize, self.exact_waves)
                })
                .collect(),
        };
    }

    /// The exact water values of the block of nodes `n0..n1` at the current time
    /// (empty in still water), for evaluations at output times.
    fn water_now(&self, n0: usize, n1: usize) -> Water {
        let Some(seas) = &self.seas else {
            return Water::new();
        };
        let field = &self.wave_fields[self.block_sea(seas, n0)];
        let pos: Vec<f64> = self.r[n0..n1].iter().flat_map(|r| r.to_f64()).collect();
        let mut out = vec![0.0; (n1 - n0) * CACHE_STRIDE];
        evaluate_nodes(field, &pos, self.t, &mut out);
        out
    }

    /// Takes `layout` with state `r`, `v` (packed order) and rebuilds what depends on it.
    fn install(&mut self, layout: Layout, r: Vec<V>, v: Vec<V>) {
        self.install_state(layout, r, v);
        self.install_chain_consts();
    }

    /// Everything [`Self::install`] sets but the chain constants.
    fn install_state(&mut self, layout: Layout, r: Vec<V>, v: Vec<V>) {
        self.coefs = layout.line_coefs.iter().map(Coefs::from_line).collect();
        let mut elem_in_cable = vec![0u32; layout.n_elements()];
        for c in &layout.cables {
            for (k, &e) in c.elements.iter().enumerate() {
                elem_in_cable[e as usize] = k as u32;
            }
        }
        self.elem_in_cable = elem_in_cable;
        self.chunks = make_chunks(&layout.blocks, rayon::current_num_threads());
        self.uniform_current = layout
            .currents
            .iter()
            .map(|c| (c.table.len() <= 1).then(|| c.at(0.0)))
            .collect();
        self.elems = vec![ElementLoads::default(); layout.n_elements()];
        self.scratch = vec![NodeScratch::default(); layout.n_nodes()];
        self.r = r;
        self.v = v;
        self.layout = layout;
        // A remesh changes node counts: the caches restart (evaluated afresh).
        self.install_waves();
    }

    /// [`Self::install`] after a remesh that changed the meshes of `changed` cables
    /// only: the chain constants of every other block are kept (their block is the same
    /// in the new layout, at a new position, and only its constraint numbers may have
    /// changed), so a fleet of winch cables does not rebuild thousands of them at every
    /// remesh of one cable.
    fn install_remeshed(&mut self, layout: Layout, r: Vec<V>, v: Vec<V>, changed: &[usize]) {
        let mut old = std::mem::take(&mut self.chain_consts);
        let same_blocks = old.len() == layout.blocks.len();
        self.install_state(layout, r, v);
        if !same_blocks {
            self.install_chain_consts();
            return;
        }
        let lay = &self.layout;
        let mut redo = vec![false; lay.blocks.len()];
        for &ci in changed {
            let first = lay.cables[ci].nodes[0];
            redo[lay.blocks.partition_point(|b| b.node_end <= first)] = true;
        }
        for (bi, (b, c)) in lay.blocks.iter().zip(old.iter_mut()).enumerate() {
            *c = match (b.is_chain, c.take()) {
                (true, Some(mut k)) if !redo[bi] => {
                    k.refresh_constraints(lay, b);
                    Some(k)
                }
                (true, _) => Some(ChainConsts::new(lay, b)),
                (false, _) => None,
            };
        }
        self.chain_consts = old;
    }

    /// Chain fast-path constants for chain blocks (winch cables included: the fast
    /// path applies the ALE variable element as the general path does).
    fn install_chain_consts(&mut self) {
        let lay = &self.layout;
        self.chain_consts = lay
            .blocks
            .iter()
            .map(|b| b.is_chain.then(|| ChainConsts::new(lay, b)))
            .collect();
    }

    /// The variable elements of block `bi` (none without winches).
    fn ale_block(&self, bi: usize) -> &[AleElem] {
        ale_of(self.ale.as_deref(), bi)
    }

    /// Unstretched length of every packed element now, m (the variable elements of
    /// winch cables at the current time).
    pub fn element_l0(&self) -> Vec<f64> {
        let mut l0 = self.layout.elem_l0.clone();
        if let Some(a) = self.ale.as_deref() {
            for (bi, b) in self.layout.blocks.iter().enumerate() {
                for ae in &a.blocks[bi] {
                    l0[b.elem_start as usize + ae.elem] = ae.l0(ae.sched.eval(self.t).dl);
                }
            }
        }
        l0
    }

    /// Replaces the route of held node `node` (packed index) from now on (a coupling
    /// loop driving an end from outside). Errors when the node is not held.
    pub fn set_route(&mut self, node: usize, route: Route) -> Result<(), Error> {
        let k = self.layout.node_constraint[node];
        if k == NO_CONSTRAINT {
            return Err(Error::Model(format!(
                "node {node} is free: only a held node (fixed or on a route) can be driven"
            )));
        }
        if let Some(ale) = self.ale.as_mut() {
            // Remeshing rebuilds from the description: it must carry the new route.
            if let Some(d) = ale.packed_of_def.iter().position(|&p| p as usize == node) {
                ale.def.nodes[d].route = Some(route.clone());
            }
        }
        self.layout.routes[k as usize] = route;
        Ok(())
    }

    /// Where each winch cable stands now (empty without winches).
    pub fn winch_status(&self) -> Vec<WinchStatus> {
        self.ale
            .as_deref()
            .map_or_else(Vec::new, |a| a.status(self.t))
    }

    /// Advances `nsteps` steps of `opts.dt`. Blocks run independently (in parallel);
    /// on failure the state is left where the failing block stopped and the error names
    /// the cable, node (or element) and time. With winches, the steps are cut where a
    /// winch cable must be remeshed (or passes a limit of its winch), which is done
    /// between steps.
    pub fn advance(&mut self, nsteps: u64) -> Result<(), Error> {
        if self.ale.is_none() {
            return self.advance_fixed(nsteps);
        }
        let dt = self.opts.dt;
        let mut left = nsteps;
        while left > 0 {
            let ale = self.ale.as_deref().expect("winches");
            let k = ale.steps_on_this_mesh(self.steps, left, dt);
            self.advance_fixed(k)?;
            left -= k;
            let ale = self.ale.as_deref_mut().expect("winches");
            let mut lay = std::mem::take(&mut self.layout);
            let (mut r, mut v) = (std::mem::take(&mut self.r), std::mem::take(&mut self.v));
            let changed = ale.remesh_in_place(self.t, &mut lay, &mut r, &mut v);
            let cables = ale.last_changed.clone();
            match changed {
                Ok(true) => self.install_remeshed(lay, r, v, &cables),
                Ok(false) => (self.layout, self.r, self.v) = (lay, r, v),
                Err(e) => {
                    // The description moved on, the layout may be half spliced: the
                    // run ends here (a limit of the winch was passed).
                    (self.layout, self.r, self.v) = (lay, r, v);
                    return Err(e);
                }
            }
        }
        Ok(())
    }

    fn ctx(&self) -> Ctx<'_> {
        let e = &self.layout.env;
        Ctx {
            lay: &self.layout,
            coefs: &self.coefs,
            seabed: SeabedCoefs {
                z: -e.depth,
                k: e.seabed.stiffness,
                c: e.seabed.damping,
                mu: e.seabed.friction,
                v_eps: e.seabed.friction_velocity,
            },
            opts: self.opts,
            elem_in_cable: &self.elem_in_cable,
            uniform_current: &self.uniform_current,
            gravity: self.layout.env.gravity,
            implicit_dt: 0.0,
        }
    }

    /// Advances `nsteps` steps on the current mesh.
    fn advance_fixed(&mut self, nsteps: u64) -> Result<(), Error> {
        if nsteps == 0 {
            return Ok(());
        }
        let step0 = self.steps;
        let dt = self.opts.dt;
        let ctx = Ctx {
            lay: &self.layout,
            coefs: &self.coefs,
            seabed: self.ctx().seabed,
            opts: self.opts,
            elem_in_cable: &self.elem_in_cable,
            uniform_current: &self.uniform_current,
            gravity: self.layout.env.gravity,
            implicit_dt: implicit_dt(&self.opts),
        };
        let blocks = &self.layout.blocks;
        let chain_consts = &self.chain_consts;
        let ale_state = self.ale.as_deref();
        let fast = self.use_chain_kernel && self.opts.formulation == Formulation::Glmf;
        // Big networks are stepped after the rest, each by every thread of the pool.
        let threads = rayon::current_num_threads();
        let threaded: Vec<bool> = blocks
            .iter()
            .enumerate()
            .map(|(bi, b)| {
                threads > 1
                    && !b.is_chain
                    && (b.node_end - b.node_start) as usize >= THREADED_MIN_NODES
                    && self.opts.scheme == Scheme::Symplectic
                    && self.opts.formulation == Formulation::Glmf
                    && ale_of(ale_state, bi).is_empty()
                    && self.seas.is_none()
            })
            .collect();
        // Split the state into disjoint per-chunk slices.
        let mut parts = Vec::with_capacity(self.chunks.len());
        {
            let (mut r, mut v, mut s, mut el) = (
                &mut self.r[..],
                &mut self.v[..],
                &mut self.scratch[..],
                &mut self.elems[..],
            );
            let mut wb = &mut self.wave_blocks[..];
            for ch in &self.chunks {
                let (b0, b1) = (blocks[ch.start], blocks[ch.end - 1]);
                let nn = (b1.node_end - b0.node_start) as usize;
                let ne = (b1.elem_end - b0.elem_start) as usize;
                let (r1, r2) = r.split_at_mut(nn);
                let (v1, v2) = v.split_at_mut(nn);
                let (s1, s2) = s.split_at_mut(nn);
                let (e1, e2) = el.split_at_mut(ne);
                let (w1, w2) = wb.split_at_mut(if wb.is_empty() { 0 } else { ch.len() });
                parts.push((ch.clone(), r1, v1, s1, e1, w1));
                wb = w2;
                r = r2;
                v = v2;
                s = s2;
                el = e2;
            }
        }
        let result: Result<(), StepFailure> =
            parts.into_par_iter().try_for_each(|(ch, r, v, s, el, wb)| {
                let base = blocks[ch.start];
                // Stage buffers of the Runge-Kutta schemes, reused across the chunk's blocks.
                let (mut rs, mut vs) = (Vec::new(), Vec::new());
                let mut wbuf = Water::new();
                let mut wb = wb.iter_mut();
                let mut chain_scratch = ChainScratch::default();
                for (bi, b) in blocks[ch.clone()].iter().enumerate() {
                    let waves = wb.next();
                    if threaded[ch.start + bi] {
                        continue;
                    }
                    let ale = ale_of(ale_state, ch.start + bi);
                    let n0 = (b.node_start - base.node_start) as usize;
                    let n1 = (b.node_end - base.node_start) as usize;
                    let e0 = (b.elem_start - base.elem_start) as usize;
                    let e1 = (b.elem_end - base.elem_start) as usize;
                    match &chain_consts[ch.start + bi] {
                        Some(cc) if fast => advance_chain(
                            cc,
                            ctx.lay,
                            &ctx.opts,
                            &mut chain_scratch,
                            ale,
                            &mut r[n0..n1],
                            &mut v[n0..n1],
                            b.node_start as usize,
                            waves,
                            &mut wbuf,
                            step0,
                            dt,
                            nsteps,
                        )?,
                        _ => advance_block(
                            &ctx,
                            b,
                            ale,
                            &mut r[n0..n1],
                            &mut v[n0..n1],
                            &mut s[n0..n1],
                            &mut el[e0..e1],
                            &mut rs,
                            &mut vs,
                            waves,
                            &mut wbuf,
                            step0,
                            dt,
                            nsteps,
                        )?,
                    }
                }
                Ok(())
            });
        let result = result.and_then(|_| {
            for (b, _) in blocks.iter().zip(&threaded).filter(|(_, &t)| t) {
                let (n0, n1) = (b.node_start as usize, b.node_end as usize);
                let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
                advance_block_threaded(
                    &ctx,
                    b,
                    &mut self.r[n0..n1],
                    &mut self.v[n0..n1],
                    &mut self.elems[e0..e1],
                    step0,
                    dt,
                    nsteps,
                    threads,
                )?;
            }
            Ok(())
        });
        self.steps += nsteps;
        self.node_steps += nsteps * self.layout.n_nodes() as u64;
        self.t = (self.steps as f64) * dt;
        result.map_err(|f| self.name_failure(f))
    }

    /// Turns a failure in packed indices into an error naming cable, node and time.
    pub fn name_failure(&self, f: StepFailure) -> Error {
        match f {
            StepFailure::Diverged { node, time, what } => {
                let (cable, node) = self.layout.describe_node(node);
                Error::Diverged {
                    cable,
                    node,
                    time,
                    what,
                }
            }
            StepFailure::Singular {
                element,
                time,
                frame,
                reason,
            } => {
                let (cable, element) = self.layout.describe_element(element);
                Error::SingularFrame {
                    frame,
                    cable,
                    element,
                    time,
                    reason,
                }
            }
        }
    }

    /// Evaluates loads, accelerations and reactions at the current state.
    pub fn evaluate(&self) -> Result<Evaluation, Error> {
        let ctx = self.ctx();
        let lay = &self.layout;
        let mut ev = Evaluation {
            acc: vec![[0.0; 3]; lay.n_nodes()],
            force: vec![[0.0; 3]; lay.n_nodes()],
            tension: vec![0.0; lay.n_elements()],
            reaction: vec![[0.0; 3]; lay.routes.len()],
            elements: Vec::new(),
        };
        let mut elems = vec![ElementLoads::default(); lay.n_elements()];
        for (bi, b) in lay.blocks.iter().enumerate() {
            let ale = self.ale_block(bi);
            let (n0, n1) = (b.node_start as usize, b.node_end as usize);
            let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
            let topo = GeneralTopo { lay, n0, e0 };
            let w = self.water_now(n0, n1);
            element_pass(
                &ctx,
                &topo,
                b,
                ale,
                &self.r[n0..n1],
                &self.v[n0..n1],
                self.t,
                &w,
                &mut elems[e0..e1],
            )
            .map_err(|f| self.name_failure(f))?;
            for i in n0..n1 {
                let (a, f, m) = node_accel(
                    &ctx,
                    &topo,
                    b,
                    ale,
                    i - n0,
                    &self.r[n0..n1],
                    &self.v[n0..n1],
                    self.t,
                    &w,
                    &elems[e0..e1],
                );
                ev.acc[i] = a.to_f64();
                ev.force[i] = f.to_f64();
                let c = lay.node_constraint[i];
                if c != NO_CONSTRAINT {
                    ev.reaction[c as usize] = (f - m.mul_vec(a)).to_f64();
                }
            }
        }
        for (e, el) in elems.iter().enumerate() {
            ev.tension[e] = el.tension;
        }
        ev.elements = elems;
        Ok(ev)
    }

    /// Total kinetic energy `1/2 v^T M v` (mass blocks with added mass), J.
    pub fn kinetic_energy(&self) -> f64 {
        let ctx = self.ctx();
        let lay = &self.layout;
        let mut elems = vec![ElementLoads::default(); lay.n_elements()];
        let mut ke = 0.0;
        for (bi, b) in lay.blocks.iter().enumerate() {
            let ale = self.ale_block(bi);
            let (n0, n1) = (b.node_start as usize, b.node_end as usize);
            let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
            // Frames can only fail where GLMF would not; energy uses the GLMF masses.
            let ctx = Ctx {
                opts: SolverOptions {
                    formulation: Formulation::Glmf,
                    ..ctx.opts
                },
                ..ctx
            };
            let topo = GeneralTopo { lay, n0, e0 };
            let w = self.water_now(n0, n1);
            let _ = element_pass(
                &ctx,
                &topo,
                b,
                ale,
                &self.r[n0..n1],
                &self.v[n0..n1],
                self.t,
                &w,
                &mut elems[e0..e1],
            );
            for i in n0..n1 {
                let eta = if w.is_empty() {
                    0.0
                } else {
                    node_water(&w, i - n0).0
                };
                let m = node_mass(&ctx, &topo, b, i - n0, self.r[i], eta, &elems[e0..e1]);
                let v = self.v[i];
                ke += 0.5 * v.dot(m.mul_vec(v));
            }
        }
        ke
    }

    /// Elastic strain energy `sum 1/2 EA l0 eps^2` over stretched elements, J.
    pub fn strain_energy(&self) -> f64 {
        let lay = &self.layout;
        let l0s = self.element_l0();
        (0..lay.n_elements())
            .map(|e| {
                let l = (self.r[lay.elem_b[e] as usize] - self.r[lay.elem_a[e] as usize]).norm();
                let l0 = l0s[e];
                let c = &self.coefs[lay.elem_line[e] as usize];
                let eps = l / l0 - 1.0;
                if eps > 0.0 || c.compression > 0.0 {
                    0.5 * c.ea * l0 * eps * eps
                } else {
                    0.0
                }
            })
            .sum()
    }
}

/// The variable elements of block `bi` under `ale` (none without winches).
fn ale_of(ale: Option<&AleState>, bi: usize) -> &[AleElem] {
    ale.map_or(&[], |a| &a.blocks[bi][..])
}

/// Groups consecutive blocks into about `4 * threads` chunks of similar node counts.
fn make_chunks(blocks: &[Block], threads: usize) -> Vec<std::ops::Range<usize>> {
    let total: u64 = blocks
        .iter()
        .map(|b| (b.node_end - b.node_start) as u64)
        .sum();
    let target = (total / (4 * threads.max(1)) as u64).max(1);
    let mut chunks = Vec::new();
    let mut start = 0;
    let mut acc = 0u64;
    for (i, b) in blocks.iter().enumerate() {
        acc += (b.node_end - b.node_start) as u64;
        if acc >= target {
            chunks.push(start..i + 1);
            start = i + 1;
            acc = 0;
        }
    }
    if start < blocks.len() {
        chunks.push(start..blocks.len());
    }
    chunks
}

/// How a block's elements and nodes are connected, in block-local indices.
///
/// Two implementations share the passes: [`ChainTopo`] for a block that is one chain
/// in node order (element `k` joins nodes `k` and `k+1`: no index arrays read at all),
/// and [`GeneralTopo`] for networks (element ends and incidence lists from the layout).
/// Gathers are iterators (one loop body), not callbacks, so they inline.
trait Topo {
    /// The incidence iterator.
    type Inc<'a>: Iterator<Item = (usize, f64)>
    where
        Self: 'a;
    /// Block-local end nodes of block-local element `e`.
    fn ends(&self, e: usize) -> (usize, usize);
    /// `(element, sign)` for each element incident to block-local node `i`; `sign` is
    /// +1 where the node is the element's node a, -1 where it is node b.
    fn incident(&self, i: usize) -> Self::Inc<'_>;
}

/// One chain in node order.
struct ChainTopo {
    n_nodes: usize,
}

/// Incidence of a chain node: element `i-1` (as its node b), then element `i` (as a).
struct ChainInc {
    next: usize,
    end: usize,
}

impl Iterator for ChainInc {
    type Item = (usize, f64);
    #[inline(always)]
    fn next(&mut self) -> Option<(usize, f64)> {
        if self.next >= self.end {
            return None;
        }
        let k = self.next;
        self.next += 1;
        // Side 2i-1 is element i-1 (node b), side 2i is element i (node a).
        Some((k >> 1, if k & 1 == 1 { -1.0 } else { 1.0 }))
    }
}

impl Topo for ChainTopo {
    type Inc<'a> = ChainInc;
    #[inline(always)]
    fn ends(&self, e: usize) -> (usize, usize) {
        (e, e + 1)
    }
    #[inline(always)]
    fn incident(&self, i: usize) -> ChainInc {
        let start = if i > 0 { 2 * i - 1 } else { 0 };
        let end = if i + 1 < self.n_nodes {
            2 * i + 1
        } else {
            2 * i
        };
        ChainInc { next: start, end }
    }
}

/// Any graph, through the layout's element ends and incidence lists.
struct GeneralTopo<'a> {
    lay: &'a Layout,
    n0: usize,
    e0: usize,
}

/// Incidence of a node from the layout's lists.
struct GeneralInc<'a> {
    it: std::slice::Iter<'a, u32>,
    e0: usize,
}

impl Iterator for GeneralInc<'_> {
    type Item = (usize, f64);
    #[inline(always)]
    fn next(&mut self) -> Option<(usize, f64)> {
        self.it.next().map(|&inc| {
            (
                (inc >> 1) as usize - self.e0,
                if inc & 1 == 0 { 1.0 } else { -1.0 },
            )
        })
    }
}

impl<'l> Topo for GeneralTopo<'l> {
    type Inc<'a>
        = GeneralInc<'a>
    where
        Self: 'a;
    #[inline(always)]
    fn ends(&self, e: usize) -> (usize, usize) {
        let g = self.e0 + e;
        (
            self.lay.elem_a[g] as usize - self.n0,
            self.lay.elem_b[g] as usize - self.n0,
        )
    }
    #[inline(always)]
    fn incident(&self, i: usize) -> GeneralInc<'_> {
        GeneralInc {
            it: self.lay.incidence(self.n0 + i).iter(),
            e0: self.e0,
        }
    }
}

/// Block-local input of element `k`, and the fraction of it under water.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn element_input<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    r: &[V],
    v: &[V],
    w: &[f64],
    k: usize,
    l0: f64,
    current: u32,
    diameter: f64,
) -> (ElementInput<f64>, f64) {
    let (a, bn) = topo.ends(k);
    let (ra, rb) = (r[a], r[bn]);
    let ci = current as usize;
    let current = match ctx.uniform_current[ci] {
        Some(u) => u,
        None => ctx.lay.currents[ci].at(0.5 * (ra.z + rb.z)),
    };
    if w.is_empty() {
        // Still water: the surface is z = 0 and the water does not accelerate.
        let wet = wetted_fraction(-ra.z, -rb.z, diameter);
        let inp = ElementInput {
            ra,
            rb,
            va: v[a],
            vb: v[bn],
            l0,
            current,
            water_accel: V::zero(),
        };
        return (inp, wet);
    }
    // Waves: the mean of the two nodes' wave velocity and acceleration at the
    // midpoint, the surface over each node for the wetted fraction.
    let (eta_a, ua, aa) = node_water(w, a);
    let (eta_b, ub, ab) = node_water(w, bn);
    let mid = |p: [f64; 3], q: [f64; 3]| {
        V::new(
            0.5 * (p[0] + q[0]),
            0.5 * (p[1] + q[1]),
            0.5 * (p[2] + q[2]),
        )
    };
    let wet = wetted_fraction(eta_a - ra.z, eta_b - rb.z, diameter);
    let inp = ElementInput {
        ra,
        rb,
        va: v[a],
        vb: v[bn],
        l0,
        current: current + mid(ua, ub),
        water_accel: mid(aa, ab),
    };
    (inp, wet)
}

/// Pass 1 over one block: element loads. `r`, `v`, `out` are block-local slices.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn element_pass<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    ale: &[AleElem],
    r: &[V],
    v: &[V],
    t: f64,
    w: &[f64],
    out: &mut [ElementLoads<f64>],
) -> Result<(), StepFailure> {
    let lay = ctx.lay;
    let e0 = b.elem_start as usize;
    let n_el = out.len();
    let l0s = &lay.elem_l0[e0..e0 + n_el];
    let lines = &lay.elem_line[e0..e0 + n_el];
    let curs = &lay.elem_current[e0..e0 + n_el];
    let diam = |k: usize| lay.line_types[lines[k] as usize].diameter;
    match ctx.opts.formulation {
        Formulation::Glmf => {
            for (k, o) in out.iter_mut().enumerate() {
                let (inp, wet) = element_input(ctx, topo, r, v, w, k, l0s[k], curs[k], diam(k));
                *o = glmf_element_wet(&ctx.coefs[lines[k] as usize], &inp, wet, ctx.gravity);
            }
            // Winch cables: the variable element at this stage's time.
            for ae in ale {
                let k = ae.elem;
                let pay = ae.sched.eval(t);
                let l0 = ae.l0(pay.dl);
                let c = &ctx.coefs[lines[k] as usize];
                let (inp, wet) = element_input(ctx, topo, r, v, w, k, l0, curs[k], diam(k));
                out[k] = glmf_element_wet(c, &inp, wet, ctx.gravity);
                if pay.rate != 0.0 {
                    // Internal damping acts on the material strain rate, and l0 changes:
                    // epsdot = (t . dv - (l / l0) Ldot) / l0 (crate::ale).
                    let (a, bn) = topo.ends(k);
                    let l = (r[bn] - r[a]).norm();
                    out[k].tension -= c.ea_c * l * pay.rate / (l0 * l0);
                }
            }
        }
        Formulation::Frame(frame) => {
            let n0 = b.node_start as usize;
            for (k, o) in out.iter_mut().enumerate() {
                let e = e0 + k;
                // The element frames are the older formulations, compared in still
                // water: they take the element wholly submerged.
                let (inp, _) = element_input(ctx, topo, r, v, w, k, l0s[k], curs[k], diam(k));
                let cable = &lay.cables[lay.elem_cable[e] as usize];
                let j = ctx.elem_in_cable[e] as usize;
                let prev = (j > 0).then(|| r[cable.nodes[j - 1] as usize - n0]);
                let next = cable.nodes.get(j + 2).map(|&n| r[n as usize - n0]);
                let mid = frenet_virtual_node(prev, inp.ra, inp.rb, next);
                *o = frame_element(frame, &ctx.coefs[lines[k] as usize], &inp, mid).map_err(
                    |reason| StepFailure::Singular {
                        element: e,
                        time: t,
                        frame: frame.name(),
                        reason,
                    },
                )?;
            }
        }
    }
    Ok(())
}

/// The node's mass block at position `r` under surface elevation `eta`: point mass,
/// half masses and half normal added masses.
#[inline(always)]
fn node_mass<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    li: usize,
    r: V,
    eta: f64,
    elems: &[ElementLoads<f64>],
) -> Sym3<f64> {
    let i = b.node_start as usize + li;
    let lay = ctx.lay;
    let dry = 1.0 - point_wetted_fraction(eta - r.z, lay.node_point_radius[i]);
    let mut m = Sym3::scalar(lay.node_point_mass[i] - dry * lay.node_point_added[i]);
    for (e, _) in topo.incident(li) {
        let el = &elems[e];
        let s = el.half_mass;
        m.xx += s;
        m.yy += s;
        m.zz += s;
        m.add_normal_projection(el.half_added, el.t);
    }
    m
}

/// Pass 2 for one node: gathered force, mass block, and acceleration (free or
/// Baumgarte-constrained). `r`, `v`, `elems` are block-local, `li` block-local too.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn node_accel<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    ale: &[AleElem],
    li: usize,
    r: &[V],
    v: &[V],
    t: f64,
    w: &[f64],
    elems: &[ElementLoads<f64>],
) -> (V, V, Sym3<f64>) {
    let wn = (!w.is_empty()).then(|| node_water(w, li));
    node_accel_of(ctx, topo, b, li, r[li], v[li], t, wn, elems, |trib, f| {
        // Winch cables: the variable element's share of the tributary length, and the
        // mass-flow forces of Eq. 39 on its two nodes (crate::ale).
        for ae in ale {
            if li == ae.m || li == ae.w {
                let pay = ae.sched.eval(t);
                let l0 = ae.l0(pay.dl);
                *trib += 0.5 * (l0 - ae.base_l0);
                if pay.rate != 0.0 || pay.accel != 0.0 {
                    let (fm, fw) = mass_flow_forces(
                        ae.mass, l0, pay.rate, pay.accel, r[ae.m], r[ae.w], v[ae.m], v[ae.w],
                    );
                    *f += if li == ae.m { fm } else { fw };
                }
            }
        }
    })
}

/// [`node_accel`] of block-local node `li` at state `(ri, vi)`; `extra` adds to the
/// node's tributary length and force what the winch cables add (nothing elsewhere).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn node_accel_of<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    li: usize,
    ri: V,
    vi: V,
    t: f64,
    wn: Option<(f64, [f64; 3], [f64; 3])>,
    elems: &[ElementLoads<f64>],
    extra: impl FnOnce(&mut f64, &mut V),
) -> (V, V, Sym3<f64>) {
    let lay = ctx.lay;
    let i = b.node_start as usize + li;
    // A point mass loses in air the buoyancy and added mass of its dry share. Fully
    // under water `dry` is 0 and nothing changes.
    let eta = wn.map_or(0.0, |w| w.0);
    let wet = point_wetted_fraction(eta - ri.z, lay.node_point_radius[i]);
    let dry = 1.0 - wet;
    let buoyancy = lay.node_point_displaced[i] * ctx.gravity;
    let mut f = V::new(0.0, 0.0, lay.node_point_weight_z[i] - dry * buoyancy);
    let mut m = Sym3::scalar(lay.node_point_mass[i] - dry * lay.node_point_added[i]);
    for (e, sign) in topo.incident(li) {
        let el = &elems[e];
        f += el.f_half + el.t * (sign * el.tension);
        let s = el.half_mass;
        m.xx += s;
        m.yy += s;
        m.zz += s;
        m.add_normal_projection(el.half_added, el.t);
    }
    let pd = lay.node_point_drag[i];
    if pd > 0.0 {
        let mut u = lay.currents[lay.node_current[i] as usize].at(ri.z);
        if let Some((_, uw, _)) = wn {
            u += V::from_f64(uw);
        }
        let vr = u - vi;
        f += vr * (pd * vr.norm() * wet);
    }
    if let Some((_, _, aw)) = wn {
        // Froude-Krylov and added mass of the wet share: (1 + Ca) rho V a.
        let m_fk = lay.node_point_displaced[i] + lay.node_point_added[i];
        if m_fk > 0.0 {
            f += V::from_f64(aw) * (m_fk * wet);
        }
    }
    let mut trib = lay.node_tributary[i];
    extra(&mut trib, &mut f);
    f += seabed_force(&ctx.seabed, trib, ri, vi);
    let c = lay.node_constraint[i];
    let a = if c == NO_CONSTRAINT {
        if ctx.implicit_dt > 0.0 {
            // The seabed's damping taken implicitly (linearised at this state), so it
            // does not bound the step: (M + dt diag(c)) a = F.
            let cd = seabed_damping(&ctx.seabed, trib, ri, vi) * ctx.implicit_dt;
            let mut mi = m;
            mi.xx += cd.x;
            mi.yy += cd.y;
            mi.zz += cd.z;
            mi.solve(f)
        } else {
            m.solve(f)
        }
    } else {
        let d = lay.routes[c as usize].eval(t);
        let bg = ctx.opts.baumgarte;
        let (rd, vd, ad) = (V::from_f64(d.r), V::from_f64(d.v), V::from_f64(d.a));
        ad - (vi - vd) * bg.beta - (ri - rd) * bg.alpha
    };
    (a, f, m)
}

/// The step with which a scheme takes the seabed's damping implicitly: the
/// symplectic scheme's `dt`; 0 (explicit) for the Runge-Kutta schemes, whose stages
/// need the ODE's own acceleration (their stable step keeps the seabed's damping:
/// [`crate::stability`]).
pub(crate) fn implicit_dt(opts: &SolverOptions) -> f64 {
    if opts.scheme == Scheme::Symplectic {
        opts.dt
    } else {
        0.0
    }
}

/// Checks a node's new state; `None` when sane ([`crate::step::blow_up`]).
#[inline(always)]
fn check(ctx: &Ctx, r: V, v: V) -> Option<String> {
    blow_up(&ctx.opts, r, v)
}

/// Evaluates accelerations of every node of a block (block-local), handing each to `store`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn accelerations<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    ale: &[AleElem],
    r: &[V],
    v: &[V],
    t: f64,
    w: &[f64],
    elems: &mut [ElementLoads<f64>],
    mut store: impl FnMut(usize, V),
) -> Result<(), StepFailure> {
    element_pass(ctx, topo, b, ale, r, v, t, w, elems)?;
    for li in 0..r.len() {
        let (a, _, _) = node_accel(ctx, topo, b, ale, li, r, v, t, w, elems);
        store(li, a);
    }
    Ok(())
}

/// Advances one block by `nsteps` steps starting at step number `step0`, with the
/// chain fast path where the block is one chain in node order.
#[allow(clippy::too_many_arguments)]
fn advance_block(
    ctx: &Ctx,
    b: &Block,
    ale: &[AleElem],
    r: &mut [V],
    v: &mut [V],
    s: &mut [NodeScratch],
    elems: &mut [ElementLoads<f64>],
    rs: &mut Vec<V>,
    vs: &mut Vec<V>,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    if b.is_chain {
        let topo = ChainTopo { n_nodes: r.len() };
        advance_block_in(
            ctx, &topo, b, ale, r, v, s, elems, rs, vs, waves, wbuf, step0, dt, nsteps,
        )
    } else {
        let topo = GeneralTopo {
            lay: ctx.lay,
            n0: b.node_start as usize,
            e0: b.elem_start as usize,
        };
        advance_block_in(
            ctx, &topo, b, ale, r, v, s, elems, rs, vs, waves, wbuf, step0, dt, nsteps,
        )
    }
}

/// Fills `buf` with the block's water values at `t` for nodes at `r`, `v` (left empty
/// in still water).
#[inline(always)]
fn fill_water(waves: &mut Option<&mut BlockWaves>, t: f64, r: &[V], v: &[V], buf: &mut Water) {
    if let Some(wb) = waves.as_deref_mut() {
        wb.fill(t, r.len(), |i| (r[i].to_f64(), v[i].to_f64()), buf);
    }
}

#[allow(clippy::too_many_arguments)]
fn advance_block_in<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    ale: &[AleElem],
    r: &mut [V],
    v: &mut [V],
    s: &mut [NodeScratch],
    elems: &mut [ElementLoads<f64>],
    rs: &mut Vec<V>,
    vs: &mut Vec<V>,
    mut waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    let n0 = b.node_start as usize;
    if waves.is_none() {
        wbuf.clear();
    }
    let n = r.len();
    rs.resize(n, V::zero());
    vs.resize(n, V::zero());
    let diverged = |li: usize, t: f64, what: String| StepFailure::Diverged {
        node: n0 + li,
        time: t,
        what,
    };
    for k in 0..nsteps {
        // Time from the step count, not by accumulation: output times stay exact.
        let t = (step0 + k) as f64 * dt;
        match ctx.opts.scheme {
            Scheme::Symplectic => {
                fill_water(&mut waves, t, r, v, wbuf);
                element_pass(ctx, topo, b, ale, r, v, t, wbuf, elems)?;
                // The element pass has read every position and velocity of this step,
                // so each node can be updated as soon as its acceleration is known.
                for li in 0..n {
                    let (a, _, _) = node_accel(ctx, topo, b, ale, li, r, v, t, wbuf, elems);
                    let vn = v[li] + a * dt;
                    let rn = r[li] + vn * dt;
                    v[li] = vn;
                    r[li] = rn;
                    if let Some(what) = check(ctx, rn, vn) {
                        return Err(diverged(li, t + dt, what));
                    }
                }
            }
            Scheme::Rk2 => {
                let h = 0.5 * dt;
                fill_water(&mut waves, t, r, v, wbuf);
                accelerations(ctx, topo, b, ale, r, v, t, wbuf, elems, |li, a| {
                    s[li].acc = a
                })?;
                for li in 0..n {
                    rs[li] = r[li] + v[li] * h;
                    vs[li] = v[li] + s[li].acc * h;
                }
                fill_water(&mut waves, t + h, rs, vs, wbuf);
                accelerations(ctx, topo, b, ale, rs, vs, t + h, wbuf, elems, |li, a| {
                    s[li].acc = a
                })?;
                for li in 0..n {
                    r[li] += vs[li] * dt;
                    v[li] += s[li].acc * dt;
                    if let Some(what) = check(ctx, r[li], v[li]) {
                        return Err(diverged(li, t + dt, what));
                    }
                }
            }
            Scheme::Rk4 => {
                let h = 0.5 * dt;
                for li in 0..n {
                    s[li].r0 = r[li];
                    s[li].v0 = v[li];
                    s[li].sr = V::zero();
                    s[li].sv = V::zero();
                }
                rs.copy_from_slice(r);
                vs.copy_from_slice(v);
                for (stage, (tau, w, next)) in
                    [(0.0, 1.0, h), (h, 2.0, h), (h, 2.0, dt), (dt, 1.0, 0.0)]
                        .into_iter()
                        .enumerate()
                {
                    fill_water(&mut waves, t + tau, rs, vs, wbuf);
                    accelerations(ctx, topo, b, ale, rs, vs, t + tau, wbuf, elems, |li, a| {
                        s[li].acc = a
                    })?;
                    for li in 0..n {
                        let x = &mut s[li];
                        x.sr += vs[li] * w;
                        x.sv += x.acc * w;
                        if stage < 3 {
                            rs[li] = x.r0 + vs[li] * next;
                            vs[li] = x.v0 + x.acc * next;
                        }
                    }
                }
                for li in 0..n {
                    r[li] = s[li].r0 + s[li].sr * (dt / 6.0);
                    v[li] = s[li].v0 + s[li].sv * (dt / 6.0);
                    if let Some(what) = check(ctx, r[li], v[li]) {
                        return Err(diverged(li, t + dt, what));
                    }
                }
            }
        }
    }
    Ok(())
}

// ------------------------------------------------------------------ big networks

/// A network block (a net cage) with at least this many nodes is stepped by all the
/// pool's threads together (symplectic GLMF without winch elements); smaller blocks
/// go one per thread as usual.
pub const THREADED_MIN_NODES: usize = 4096;

/// A sense-reversing barrier that spins (then yields): the threads of one block meet
/// twice per step, far more often than a sleeping barrier's wake-up allows.
struct SpinBarrier {
    n: usize,
    count: AtomicUsize,
    sense: AtomicBool,
}

impl SpinBarrier {
    fn new(n: usize) -> Self {
        Self {
            n,
            count: AtomicUsize::new(0),
            sense: AtomicBool::new(false),
        }
    }

    /// Waits for all `n` threads; `local` is the caller's sense, flipped each call.
    fn wait(&self, local: &mut bool) {
        *local = !*local;
        if self.count.fetch_add(1, Ordering::AcqRel) + 1 == self.n {
            self.count.store(0, Ordering::Relaxed);
            self.sense.store(*local, Ordering::Release);
        } else {
            let mut spins = 0u32;
            while self.sense.load(Ordering::Acquire) != *local {
                spins += 1;
                if spins < 1 << 8 {
                    std::hint::spin_loop();
                } else {
                    std::thread::yield_now();
                }
            }
        }
    }
}

/// Raw views of a block's state shared by the threads of [`advance_block_threaded`].
/// Within each phase of a step every element and every node has exactly one writer and
/// nothing reads what is being written (see the function), which the barriers between
/// the phases order.
#[derive(Clone, Copy)]
struct Shared {
    r: *mut V,
    v: *mut V,
    el: *mut ElementLoads<f64>,
}
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

/// Steps one network block (no winch elements, GLMF, symplectic Euler) by `nsteps` with
/// `threads` threads: each owns a contiguous range of elements and of nodes. Per step,
/// phase 1: each thread evaluates its elements (reading every position and velocity,
/// which nobody writes in this phase); barrier; phase 2: each thread updates its nodes
/// (reading every element's loads, which nobody writes now, and its own nodes' state);
/// barrier. The arithmetic per element and per node is the single-thread path's, so
/// the result is the same bit for bit, and a blow-up names the lowest failing node of
/// the first failing step, as there.
#[allow(clippy::too_many_arguments)]
fn advance_block_threaded(
    ctx: &Ctx,
    b: &Block,
    r: &mut [V],
    v: &mut [V],
    elems: &mut [ElementLoads<f64>],
    step0: u64,
    dt: f64,
    nsteps: u64,
    threads: usize,
) -> Result<(), StepFailure> {
    let (n, ne) = (r.len(), elems.len());
    let topo = GeneralTopo {
        lay: ctx.lay,
        n0: b.node_start as usize,
        e0: b.elem_start as usize,
    };
    let e0 = b.elem_start as usize;
    let l0s = &ctx.lay.elem_l0[e0..e0 + ne];
    let lines = &ctx.lay.elem_line[e0..e0 + ne];
    let curs = &ctx.lay.elem_current[e0..e0 + ne];
    let sh = Shared {
        r: r.as_mut_ptr(),
        v: v.as_mut_ptr(),
        el: elems.as_mut_ptr(),
    };
    let barrier = SpinBarrier::new(threads);
    // Lowest failing node of the current step (usize::MAX: none yet).
    let failed = AtomicUsize::new(usize::MAX);
    let range = |tid: usize, len: usize| (len * tid / threads)..(len * (tid + 1) / threads);
    let work = |tid: usize| {
        // Capture the whole `Shared` (Sync), not its raw-pointer fields one by one, as
        // the closure's disjoint field capture would.
        #[allow(clippy::redundant_locals)]
        let sh = sh;
        let (er, nr) = (range(tid, ne), range(tid, n));
        let mut sense = false;
        for k in 0..nsteps {
            let t = (step0 + k) as f64 * dt;
            {
                // SAFETY: phase 1 writes only this thread's elements; r and v are only
                // read (the last writes to them happened before the barrier).
                let (r, v) = unsafe {
                    (
                        std::slice::from_raw_parts(sh.r, n),
                        std::slice::from_raw_parts(sh.v, n),
                    )
                };
                let out = unsafe { std::slice::from_raw_parts_mut(sh.el.add(er.start), er.len()) };
                for (o, k) in out.iter_mut().zip(er.clone()) {
                    let d = ctx.lay.line_types[lines[k] as usize].diameter;
                    let (inp, wet) = element_input(ctx, &topo, r, v, &[], k, l0s[k], curs[k], d);
                    *o = glmf_element_wet(&ctx.coefs[lines[k] as usize], &inp, wet, ctx.gravity);
                }
            }
            barrier.wait(&mut sense);
            {
                // SAFETY: phase 2 only reads the elements (written before the barrier)
                // and reads and writes this thread's own nodes.
                let el = unsafe { std::slice::from_raw_parts(sh.el, ne) };
                let rs = unsafe { std::slice::from_raw_parts_mut(sh.r.add(nr.start), nr.len()) };
                let vs = unsafe { std::slice::from_raw_parts_mut(sh.v.add(nr.start), nr.len()) };
                for (j, (ri, vi)) in rs.iter_mut().zip(vs.iter_mut()).enumerate() {
                    let li = nr.start + j;
                    let (a, _, _) =
                        node_accel_of(ctx, &topo, b, li, *ri, *vi, t, None, el, |_, _| {});
                    let vn = *vi + a * dt;
                    let rn = *ri + vn * dt;
                    *vi = vn;
                    *ri = rn;
                    if check(ctx, rn, vn).is_some() {
                        failed.fetch_min(li, Ordering::AcqRel);
                        break;
                    }
                }
            }
            barrier.wait(&mut sense);
            if failed.load(Ordering::Acquire) != usize::MAX {
                return Some(t + dt);
            }
        }
        None
    };
    let stop = std::thread::scope(|sc| {
        let helpers: Vec<_> = (1..threads)
            .map(|tid| sc.spawn(move || work(tid)))
            .collect();
        let mine = work(0);
        for h in helpers {
            h.join().expect("a stepping thread panicked");
        }
        mine
    });
    match stop {
        None => Ok(()),
        Some(time) => {
            let li = failed.load(Ordering::Acquire);
            let what = check(ctx, r[li], v[li]).expect("the failing node fails its check");
            Err(StepFailure::Diverged {
                node: b.node_start as usize + li,
                time,
                what,
            })
        }
    }
}
