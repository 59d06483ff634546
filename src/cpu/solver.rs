//! The solver's API: building a [`CpuSolver`], winches, seas, stepping a run's blocks
//! (chunks over rayon's threads, each block on the chain fast path, the general passes
//! of [`super::passes`] or, for a big network, [`super::threaded`]), evaluation and
//! energies. Checkpoints are in [`checkpoint`], the output-time evaluation and the
//! energies in [`evaluation`].

mod checkpoint;
mod evaluation;
mod free_rk;
mod waves;

pub use checkpoint::CpuCheckpoint;

use super::chain::{
    advance_chain, advance_net, advance_net_threaded, ChainConsts, ChainHeld, ChainScratch,
    NetConsts, NetScratch,
};
use super::free::{end_tension, Failure, FreeRun};
use super::passes::{advance_block, implicit_dt, node_accel_of, Ctx, GeneralTopo, NodeScratch};
use super::threaded::{advance_block_threaded, THREADED_MIN_NODES};
use super::water::node_water;
use super::water::{BlockWaves, Water};
use crate::ale::{advance_with_winches, AleElem, AleState, MeshStepper, Winch};
use crate::error::Error;
use crate::math::{Sym3, V3};
use crate::model::{Block, Layout, ModelDef, Route, NO_CONSTRAINT};
use crate::options::{Formulation, Scheme, SolverOptions};
use crate::physics::{Coefs, ElementLoads, SeabedCoefs};
use crate::sea::bands::BandCensus;
use crate::sea::kinematics::WaveField;
use crate::sea::{SeaSet, SeaState};
use crate::step::{StepFailure, WinchStatus};
use rayon::prelude::*;

type V = V3<f64>;
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
    /// Node positions, m. (In a sea, writing them mid-run leaves the kinematics
    /// cache with values along the old paths: see [`Self::restart_waves`].)
    pub r: Vec<V>,
    /// Node velocities, m/s (as [`Self::r`]).
    pub v: Vec<V>,
    coefs: Vec<Coefs<f64>>,
    elem_in_cable: Vec<u32>,
    uniform_current: Vec<Option<V>>,
    elems: Vec<ElementLoads<f64>>,
    scratch: Vec<NodeScratch>,
    /// Per element: its internal state (a viscoelastic line's static-branch strain,
    /// `physics::visco`); empty without viscoelastic lines.
    visco: Vec<f64>,
    /// Per block: constants of the chain fast path (`None` for networks).
    chain_consts: Vec<Option<ChainConsts>>,
    /// Use the vectorised fast path for chain blocks (GLMF only). On by default; the
    /// general path is the reference the fast path is tested against.
    pub use_chain_kernel: bool,
    /// Per block: constants of the network fast path (`None` for chains, and for
    /// networks with a node of more than 8 elements).
    net_consts: Vec<Option<Box<NetConsts>>>,
    /// Use the vectorised fast path for network blocks (GLMF, symplectic, no winch
    /// elements). On by default; the general path is the reference it is tested against.
    pub use_net_kernel: bool,
    /// Groups of consecutive blocks handed to one task each.
    chunks: Vec<std::ops::Range<usize>>,
    /// Winch cables (ALE-GLMF), if any.
    ale: Option<Box<AleState>>,
    /// Node-steps taken: nodes times steps, summed over the meshes a run went through.
    node_steps: u64,
    /// The seas and each cable's (`None`: still water everywhere).
    seas: Option<SeaSet>,
    /// Per sea: its field, for exact evaluation at output times.
    wave_fields: Vec<std::sync::Arc<WaveField>>,
    /// Per block: its wave kinematics cache (empty in still water).
    wave_blocks: Vec<BlockWaves>,
    /// Evaluate the waves' component sum at every stage instead of interpolating the
    /// kinematics cache (the reference the cache is tested against; slow).
    exact_waves: bool,
    /// Free and pinned bodies, stepped with the lines (`None` without: the steps are
    /// those of a run without bodies of their own).
    free: Option<Box<FreeRun>>,
    /// Cable ends that may fail, and those that did.
    failures: Vec<Failure>,
    /// Every bending hinge (`Layout::hinges`; empty without bending stiffness).
    hinges: Vec<crate::model::Hinge>,
    /// Per block: whether it has a bending hinge (a chain takes its hinges into its
    /// fast path, `chain::bending`; a network takes the general passes).
    bent: Vec<bool>,
}

impl CpuSolver {
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
            net_consts: Vec::new(),
            use_net_kernel: true,
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
            visco: Vec::new(),
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
            free: None,
            failures: Vec::new(),
            hinges: Vec::new(),
            bent: Vec::new(),
        };
        let r = positions.iter().map(|p| V::from_f64(*p)).collect();
        let v = vec![V::zero(); positions.len()];
        s.install(layout, r, v);
        s.free = FreeRun::new(&s.layout).map(Box::new);
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
        // A run with winch cables has no bending in the lumped-mass model yet (the
        // variable elements' hinges are not built): `ei` is the ANCF reference's only,
        // as the scenario's warning says.
        let mut def = def;
        for lt in &mut def.line_types {
            lt.ei = 0.0;
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
        if lay
            .routes
            .iter()
            .any(|r| matches!(r, Route::Body { body, .. } if body.dynamic().is_some()))
        {
            return Err(Error::Model(
                "winch cables and free or pinned bodies in one run are not supported yet".into(),
            ));
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
            self.wave_fields = seas.seas.iter().map(|s| WaveField::new(s).into()).collect();
        }
        self.install_waves();
    }

    /// Where the waves' caches stand (`sea::bands`): per band, how many nodes refresh
    /// in it now, and how many times a node was found above its band's top (and more
    /// than the margin above it).
    pub fn wave_band_census(&self) -> BandCensus {
        let mut out = BandCensus::default();
        for w in &self.wave_blocks {
            let c = w.cache();
            out.breaches += c.breaches;
            out.beyond_margin += c.beyond_margin;
            // The earliest (blocks in node order: the lowest node at that time).
            if let Some(f) = c.first_beyond_margin {
                if out.first_beyond_margin.is_none_or(|g| f[0] < g[0]) {
                    out.first_beyond_margin = Some(f);
                }
            }
            for i in 0..c.v0.len() / crate::sea::cache::CACHE_STRIDE {
                let b = c.band_of(i);
                if out.nodes.len() <= b {
                    out.nodes.resize(b + 1, 0);
                }
                out.nodes[b] += 1;
            }
        }
        out
    }

    /// The sea index of the block starting at packed node `n0`.
    fn block_sea(&self, seas: &SeaSet, n0: usize) -> usize {
        seas.sea_of_cable(self.layout.node_cable[n0] as usize)
    }

    /// One wave cache per block, in its cable's sea (none in still water).
    fn install_waves(&mut self) {
        self.wave_blocks = match &self.seas {
            None => Vec::new(),
            Some(seas) => {
                // Each sea's bands once (a bisection per band), shared by its blocks.
                let plans: Vec<_> = (0..seas.seas.len())
                    .map(|q| seas.band_plan(q, self.opts.dt))
                    .collect();
                self.layout
                    .blocks
                    .iter()
                    .map(|b| {
                        let q = self.block_sea(seas, b.node_start as usize);
                        let n = (b.node_end - b.node_start) as usize;
                        BlockWaves::new(&seas.seas[q], n, self.exact_waves, &plans[q])
                    })
                    .collect()
            }
        };
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
        // The general passes' node scratch and element loads (120 and 104 bytes a node
        // and an element) are allocated at the first step that takes those passes
        // (`Self::advance_blocks`): a fleet on the fast paths never needs them.
        self.elems = Vec::new();
        self.scratch = Vec::new();
        // The viscoelastic elements start at rest at their initial lengths.
        self.visco = crate::physics::visco::visco_rest_states(&layout, |e| {
            (r[layout.elem_b[e] as usize] - r[layout.elem_a[e] as usize]).norm()
        });
        self.hinges = layout.hinges();
        self.bent = layout
            .blocks
            .iter()
            .map(|b| {
                !crate::model::block_hinges(
                    &self.hinges,
                    b.elem_start as usize,
                    b.elem_end as usize,
                )
                .is_empty()
            })
            .collect();
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
        let mut old_net = std::mem::take(&mut self.net_consts);
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
                (true, _) => (!lay.block_has_curves(b)).then(|| ChainConsts::new(lay, b)),
                (false, _) => None,
            };
        }
        for (bi, (b, c)) in lay.blocks.iter().zip(old_net.iter_mut()).enumerate() {
            *c = match (b.is_chain, c.take()) {
                (false, Some(mut k)) if !redo[bi] => {
                    k.refresh_constraints(lay, b);
                    Some(k)
                }
                (false, _) => NetConsts::new(lay, b).map(Box::new),
                (true, _) => None,
            };
        }
        self.chain_consts = old;
        self.net_consts = old_net;
        self.drop_bent_consts();
    }

    /// Blocks with bending hinges: a chain's fast-path constants take its hinges
    /// (`chain::bending`); a network takes the general passes (no network constants).
    fn drop_bent_consts(&mut self) {
        // Seabed friction split along and across the line: the general passes, which
        // take the line direction at each node (the fast paths' friction is isotropic).
        if self.layout.env.seabed.split_friction() {
            self.chain_consts.iter_mut().for_each(|c| *c = None);
            self.net_consts.iter_mut().for_each(|c| *c = None);
            return;
        }
        for (bi, &bent) in self.bent.iter().enumerate() {
            if bent {
                self.net_consts[bi] = None;
                if let Some(c) = self.chain_consts[bi].as_mut() {
                    let b = &self.layout.blocks[bi];
                    let h = crate::model::block_hinges(
                        &self.hinges,
                        b.elem_start as usize,
                        b.elem_end as usize,
                    );
                    match crate::cpu::chain::bending::ChainBend::new(&self.layout, b, h) {
                        Some(bd) => c.bend = Some(Box::new(bd)),
                        None => self.chain_consts[bi] = None,
                    }
                }
            }
        }
    }

    /// Chain fast-path constants for chain blocks (winch cables included: the fast
    /// path applies the ALE variable element as the general path does).
    fn install_chain_consts(&mut self) {
        let lay = &self.layout;
        self.chain_consts = lay
            .blocks
            .iter()
            // A block with a tabulated strain-tension curve takes the general passes.
            .map(|b| (b.is_chain && !lay.block_has_curves(b)).then(|| ChainConsts::new(lay, b)))
            .collect();
        self.net_consts = lay
            .blocks
            .iter()
            .map(|b| {
                if b.is_chain {
                    None
                } else {
                    NetConsts::new(lay, b).map(Box::new)
                }
            })
            .collect();
        self.drop_bent_consts();
    }

    /// The elements' internal states (a viscoelastic line's static-branch strain,
    /// `physics::visco`, packed element order; zero for every other element), empty
    /// without viscoelastic lines.
    pub fn visco_states(&self) -> &[f64] {
        &self.visco
    }

    /// The internal states of elements `e0..e1` (empty without viscoelastic lines).
    fn visco_block(&self, e0: usize, e1: usize) -> &[f64] {
        if self.visco.is_empty() {
            &[]
        } else {
            &self.visco[e0..e1]
        }
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

    /// The free and pinned bodies' states now (empty without).
    pub fn dynamic_bodies(&self) -> Vec<crate::body::output::DynamicState> {
        self.free.as_deref().map_or_else(Vec::new, |f| {
            f.bodies
                .iter()
                .map(|e| crate::body::output::DynamicState {
                    body: e.body.clone(),
                    state: e.state.body_state(),
                    angles: e.state.angles(),
                })
                .collect()
        })
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
        advance_with_winches(self, nsteps)
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
                mu_axial: e.seabed.mu_axial(),
                v_eps: e.seabed.friction_velocity,
            },
            opts: self.opts,
            elem_in_cable: &self.elem_in_cable,
            uniform_current: &self.uniform_current,
            gravity: self.layout.env.gravity,
            implicit_dt: 0.0,
            targets: self.free.as_deref().map_or(&[], |f| &f.targets[..]),
            hinges: &self.hinges,
        }
    }

    /// Advances `nsteps` steps on the current mesh.
    fn advance_fixed(&mut self, nsteps: u64) -> Result<(), Error> {
        if nsteps == 0 {
            return Ok(());
        }
        let pending = self.failures.iter().any(|f| f.fired.is_none());
        if self.free.is_none() && !pending {
            return self.advance_blocks(nsteps, false).map(|_| ());
        }
        if self.units_ok() {
            // The units several steps a call (one while failures are pending), the
            // other blocks as without bodies.
            let mut k = 0;
            while k < nsteps {
                let pending = self.failures.iter().any(|f| f.fired.is_none());
                let n = if pending { 1 } else { nsteps - k };
                let step0 = self.steps;
                self.advance_units(step0, n)?;
                self.advance_blocks(n, true)?;
                if pending {
                    self.check_failures();
                }
                k += n;
            }
            return Ok(());
        }
        if self.free.is_some() && self.opts.scheme != Scheme::Symplectic {
            // The Runge-Kutta schemes: the units through the stages with their bodies
            // (one step a call while failures are pending), the other blocks as
            // without bodies.
            let mut k = 0;
            while k < nsteps {
                let pending = self.failures.iter().any(|f| f.fired.is_none());
                let n = if pending { 1 } else { nsteps - k };
                let step0 = self.steps;
                self.advance_units_rk(step0, n)?;
                self.advance_blocks(n, true)?;
                if pending {
                    self.check_failures();
                }
                k += n;
            }
            return Ok(());
        }
        // The lines and the bodies step by step together; failures are checked after
        // each step.
        for k in 0..nsteps {
            let t = self.t;
            let lumps = self.advance_blocks(1, false)?;
            if let Some(free) = self.free.as_deref_mut() {
                free.step(
                    &self.layout,
                    t,
                    self.opts.dt,
                    &lumps,
                    &mut self.r,
                    &mut self.v,
                )
                .map_err(|m| Error::Diverged {
                    cable: m,
                    node: 0,
                    time: t + self.opts.dt,
                    what: "a free body's state".into(),
                })?;
            }
            if pending {
                self.check_failures();
                if self.free.is_none() && self.failures.iter().all(|f| f.fired.is_some()) {
                    return self.advance_blocks(nsteps - k - 1, false).map(|_| ());
                }
            }
        }
        Ok(())
    }

    /// The cable ends that may fail during the run (each held by a fixed point, a
    /// route or a body). `Err` names an end that is not held or a cable not found.
    pub fn set_failures(&mut self, failures: &[crate::model::EndFailure]) -> Result<(), Error> {
        let mut out = Vec::with_capacity(failures.len());
        for f in failures {
            let site = f.site(&self.layout).map_err(Error::Model)?;
            out.push(Failure {
                spec: f.clone(),
                node: site.node,
                elem: site.elem,
                fired: None,
            });
        }
        self.failures = out;
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

    /// Fires the failures due now (time reached, or the end element's tension at or
    /// above its threshold) and lets their ends go.
    fn check_failures(&mut self) {
        let t = self.t;
        let mut released = Vec::new();
        for f in self.failures.iter_mut().filter(|f| f.fired.is_none()) {
            let tension = end_tension(&self.layout, &self.r, f.elem);
            let trigger = if f.spec.time.is_some_and(|x| t >= x) {
                "time"
            } else if f.spec.tension.is_some_and(|x| tension >= x) {
                "tension"
            } else {
                continue;
            };
            let end = if f.spec.at_start { "start" } else { "end" };
            log::warn!(
                "t = {t} s: cable '{}' failed at its {end} ({trigger}; end tension {tension:.6e} N): the end is free from now on",
                f.spec.cable
            );
            f.fired = Some(crate::model::FailureEvent {
                time: t,
                cable: f.spec.cable.clone(),
                end: end.into(),
                tension,
                trigger: trigger.into(),
            });
            released.push((f.node, trigger));
        }
        // The other ends on a node let go fail with it (the cables of a `[[points]]`
        // entry that fails), each with its own tension.
        for f in self.failures.iter_mut().filter(|f| f.fired.is_none()) {
            let Some(&(_, trigger)) = released.iter().find(|(n, _)| *n == f.node) else {
                continue;
            };
            let tension = end_tension(&self.layout, &self.r, f.elem);
            let end = if f.spec.at_start { "start" } else { "end" };
            log::warn!(
                "t = {t} s: cable '{}' failed at its {end} with the other cables of its point ({trigger}; end tension {tension:.6e} N)",
                f.spec.cable
            );
            f.fired = Some(crate::model::FailureEvent {
                time: t,
                cable: f.spec.cable.clone(),
                end: end.into(),
                tension,
                trigger: trigger.into(),
            });
        }
        released.sort_by_key(|x| x.0);
        released.dedup_by_key(|x| x.0);
        for (node, _) in released {
            self.release(node);
        }
    }

    /// Lets the held node `node` go: free from now on.
    fn release(&mut self, node: usize) {
        self.layout.node_constraint[node] = NO_CONSTRAINT;
        let bi = self
            .layout
            .blocks
            .partition_point(|b| (b.node_end as usize) <= node);
        let b = self.layout.blocks[bi];
        if let Some(k) = self.chain_consts[bi].as_mut() {
            k.refresh_constraints(&self.layout, &b);
        }
        if let Some(k) = self.net_consts[bi].as_deref_mut() {
            k.refresh_constraints(&self.layout, &b);
        }
        if let Some(f) = self.free.as_deref_mut() {
            f.release(node, &self.layout);
        }
    }

    /// Advances every block `nsteps` steps; with free bodies (one step), returns the
    /// force and mass block of each node held on one at the step's starting state.
    ///
    /// With `skip_units`, the blocks of the free bodies' units are left alone
    /// ([`Self::advance_units`] steps them).
    fn advance_blocks(
        &mut self,
        nsteps: u64,
        skip_units: bool,
    ) -> Result<Vec<(usize, V, Sym3<f64>)>, Error> {
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
            targets: self.free.as_deref().map_or(&[], |f| &f.targets[..]),
            hinges: &self.hinges,
        };
        let touched = self
            .free
            .as_deref()
            .map(|f| (&f.touched[..], &f.held_local[..]));
        let is_touched = |bi: usize| touched.is_some_and(|(t, _)| t[bi]);
        let unit_of = self.free.as_deref().map(|f| &f.unit_of[..]);
        let skipped = |bi: usize| skip_units && unit_of.is_some_and(|u| u[bi].is_some());
        let blocks = &self.layout.blocks;
        let chain_consts = &self.chain_consts;
        let ale_state = self.ale.as_deref();
        // A seabed grid takes the general passes: the fast paths' node loops know the
        // flat seabed only (docs/src/limitations.md).
        let flat = self.layout.env.seabed.grid.is_none();
        let fast = self.use_chain_kernel && self.opts.formulation == Formulation::Glmf && flat;
        // The network fast path: GLMF, symplectic, no winch elements in the block.
        let net_consts = &self.net_consts;
        let net_fast = self.use_net_kernel
            && flat
            && self.opts.formulation == Formulation::Glmf
            && self.opts.scheme == Scheme::Symplectic;
        let net_of = |bi: usize| {
            net_consts[bi]
                .as_deref()
                .filter(|_| net_fast && ale_of(ale_state, bi).is_empty())
        };
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
                    && !is_touched(bi)
                    && !self.layout.block_has_curves(b)
                    && !self.bent[bi]
                    && !self.layout.block_has_screen(b)
            })
            .collect();
        // Whether a block takes the general passes (which need the node scratch and the
        // element loads; the fast paths keep their own): allocate those on first need.
        let general = blocks.iter().enumerate().any(|(bi, _)| {
            !skipped(bi)
                && (is_touched(bi)
                    || (threaded[bi] && net_of(bi).is_none())
                    || (!threaded[bi]
                        && net_of(bi).is_none()
                        && !(fast && chain_consts[bi].is_some())))
        });
        if general && self.scratch.is_empty() {
            // As `Self::general_buffers` (field by field: `ctx` borrows the layout).
            self.scratch = vec![NodeScratch::default(); self.layout.n_nodes()];
            self.elems = vec![ElementLoads::default(); self.layout.n_elements()];
        }
        // Split the state into disjoint per-chunk slices.
        let mut parts = Vec::with_capacity(self.chunks.len());
        {
            let (mut r, mut v, mut s, mut el) = (
                &mut self.r[..],
                &mut self.v[..],
                &mut self.scratch[..],
                &mut self.elems[..],
            );
            let mut xv = &mut self.visco[..];
            let mut wb = &mut self.wave_blocks[..];
            for ch in &self.chunks {
                let (b0, b1) = (blocks[ch.start], blocks[ch.end - 1]);
                let nn = (b1.node_end - b0.node_start) as usize;
                let ne = (b1.elem_end - b0.elem_start) as usize;
                let (r1, r2) = r.split_at_mut(nn);
                let (v1, v2) = v.split_at_mut(nn);
                let (s1, s2) = s.split_at_mut(if s.is_empty() { 0 } else { nn });
                let (e1, e2) = el.split_at_mut(if el.is_empty() { 0 } else { ne });
                let (x1, x2) = xv.split_at_mut(if xv.is_empty() { 0 } else { ne });
                let (w1, w2) = wb.split_at_mut(if wb.is_empty() { 0 } else { ch.len() });
                parts.push((ch.clone(), r1, v1, s1, e1, x1, w1));
                xv = x2;
                wb = w2;
                r = r2;
                v = v2;
                s = s2;
                el = e2;
            }
        }
        let result: Result<Vec<Vec<(usize, V, Sym3<f64>)>>, StepFailure> = parts
            .into_par_iter()
            .map(|(ch, r, v, s, el, xv, wb)| {
                let mut lumps = Vec::new();
                let base = blocks[ch.start];
                // Stage buffers of the Runge-Kutta schemes, reused across the chunk's blocks.
                let (mut rs, mut vs) = (Vec::new(), Vec::new());
                let mut wbuf = Water::new();
                let mut wb = wb.iter_mut();
                let mut chain_scratch = ChainScratch::default();
                let mut net_scratch = NetScratch::default();
                for (bi, b) in blocks[ch.clone()].iter().enumerate() {
                    let waves = wb.next();
                    if threaded[ch.start + bi] || skipped(ch.start + bi) {
                        continue;
                    }
                    let ale = ale_of(ale_state, ch.start + bi);
                    let n0 = (b.node_start - base.node_start) as usize;
                    let n1 = (b.node_end - base.node_start) as usize;
                    let e0 = (b.elem_start - base.elem_start) as usize;
                    let e1 = (b.elem_end - base.elem_start) as usize;
                    let xb: &mut [f64] = if xv.is_empty() {
                        &mut []
                    } else {
                        &mut xv[e0..e1]
                    };
                    if is_touched(ch.start + bi) {
                        // Held on a free body: the general passes (one step), then the
                        // held nodes' forces and mass blocks at the step's start.
                        let held = &touched.expect("free bodies").1[ch.start + bi];
                        let saved: Vec<(usize, V, V)> = held
                            .iter()
                            .map(|&(li, _)| (li, r[n0 + li], v[n0 + li]))
                            .collect();
                        advance_block(
                            &ctx,
                            b,
                            ale,
                            &mut r[n0..n1],
                            &mut v[n0..n1],
                            xb,
                            &mut s[n0..n1],
                            &mut el[e0..e1],
                            &mut rs,
                            &mut vs,
                            waves,
                            &mut wbuf,
                            step0,
                            dt,
                            nsteps,
                        )?;
                        let topo = GeneralTopo {
                            lay: ctx.lay,
                            n0: b.node_start as usize,
                            e0: b.elem_start as usize,
                        };
                        for (li, ri, vi) in saved {
                            let wn = (!wbuf.is_empty()).then(|| node_water(&wbuf, li));
                            let (_, f, m) = node_accel_of(
                                &ctx,
                                &topo,
                                b,
                                li,
                                ri,
                                vi,
                                step0 as f64 * dt,
                                wn,
                                &el[e0..e1],
                                |_, _| {},
                            );
                            lumps.push((b.node_start as usize + li, f, m));
                        }
                        continue;
                    }
                    if let Some(nc) = net_of(ch.start + bi) {
                        advance_net(
                            nc,
                            ctx.lay,
                            &ctx.opts,
                            &mut net_scratch,
                            &mut r[n0..n1],
                            &mut v[n0..n1],
                            b.node_start as usize,
                            waves,
                            &mut wbuf,
                            step0,
                            dt,
                            nsteps,
                        )?;
                        continue;
                    }
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
                            ChainHeld::default(),
                        )?,
                        _ => advance_block(
                            &ctx,
                            b,
                            ale,
                            &mut r[n0..n1],
                            &mut v[n0..n1],
                            xb,
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
                Ok(lumps)
            })
            .collect();
        let result = result.and_then(|lumps| {
            let mut net_scratch = NetScratch::default();
            for (bi, b) in blocks.iter().enumerate().filter(|(bi, _)| threaded[*bi]) {
                let (n0, n1) = (b.node_start as usize, b.node_end as usize);
                let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
                if let Some(nc) = net_of(bi) {
                    advance_net_threaded(
                        nc,
                        ctx.lay,
                        &ctx.opts,
                        &mut net_scratch,
                        &mut self.r[n0..n1],
                        &mut self.v[n0..n1],
                        n0,
                        step0,
                        dt,
                        nsteps,
                        threads,
                    )?;
                    continue;
                }
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
            Ok(lumps.into_iter().flatten().collect())
        });
        self.steps += nsteps;
        self.node_steps += nsteps * self.layout.n_nodes() as u64;
        self.t = (self.steps as f64) * dt;
        result.map_err(|f| self.name_failure(f))
    }

    /// Allocates the general passes' node scratch and element loads, if not yet done
    /// (`Self::install_state` leaves them empty: a run on the fast paths never needs them).
    fn general_buffers(&mut self) {
        if self.scratch.is_empty() {
            self.scratch = vec![NodeScratch::default(); self.layout.n_nodes()];
            self.elems = vec![ElementLoads::default(); self.layout.n_elements()];
        }
    }

    /// Whether the free bodies' units can step on their own, several steps a call
    /// ([`Self::advance_units`]): every block of a unit on the chain fast path
    /// (symplectic scheme, GLMF, a flat seabed, no bending or tabulated curves, no
    /// winches). Otherwise the run steps one step a call, the held blocks on the
    /// general passes.
    fn units_ok(&self) -> bool {
        let Some(f) = self.free.as_deref() else {
            return false;
        };
        self.use_chain_kernel
            && self.opts.formulation == Formulation::Glmf
            && self.opts.scheme == Scheme::Symplectic
            && self.layout.env.seabed.grid.is_none()
            && self.ale.is_none()
            && f.units
                .iter()
                .flat_map(|u| &u.blocks)
                .all(|&bi| self.layout.blocks[bi].is_chain && self.chain_consts[bi].is_some())
    }

    /// Steps the free bodies' units `nsteps` steps from step `step0`, in parallel: in
    /// each unit, at each step, every block one step on the chain fast path (its
    /// scratch kept from step to step, its held nodes' forces and mass blocks at the
    /// step's start collected), then each body with its held nodes lumped in, its held
    /// nodes placed on its points. The blocks outside the units are not touched, nor
    /// the step count.
    fn advance_units(&mut self, step0: u64, nsteps: u64) -> Result<(), Error> {
        let dt = self.opts.dt;
        let free = self.free.as_deref_mut().expect("free bodies");
        let lay = &self.layout;
        let opts = &self.opts;
        let chain_consts = &self.chain_consts;
        // SAFETY (every use below): each block, body and held route is in one unit
        // only, and a unit reaches only its own: the units' parallel tasks touch
        // disjoint entries of these buffers, which nothing else reaches meanwhile.
        let r = Shared(self.r.as_mut_ptr());
        let v = Shared(self.v.as_mut_ptr());
        let wave = Shared(self.wave_blocks.as_mut_ptr());
        let has_waves = !self.wave_blocks.is_empty();
        let bodies = Shared(free.bodies.as_mut_ptr());
        let targets = Shared(free.targets.as_mut_ptr());
        let held_local = &free.held_local;
        type Lumps = Vec<(usize, V, Sym3<f64>)>;
        let res: Result<(), Result<StepFailure, (String, f64)>> = free
            .units
            .par_iter()
            .map_init(
                || {
                    (
                        Vec::<ChainScratch>::new(),
                        Water::new(),
                        Lumps::new(),
                        Vec::new(),
                        Vec::new(),
                    )
                },
                |(scr, wbuf, lumps, tg, ls), unit| {
                    if scr.len() < unit.blocks.len() {
                        scr.resize_with(unit.blocks.len(), Default::default);
                    }
                    for k in 0..nsteps {
                        let step = step0 + k;
                        let t = step as f64 * dt;
                        lumps.clear();
                        for (j, &bi) in unit.blocks.iter().enumerate() {
                            let b = lay.blocks[bi];
                            let (n0, n1) = (b.node_start as usize, b.node_end as usize);
                            tg.clear();
                            for &(li, route) in &held_local[bi] {
                                // SAFETY: the unit's own route.
                                if let Some(d) = unsafe { *targets.at(route) } {
                                    tg.push((li, d));
                                }
                            }
                            // SAFETY: the unit's own block.
                            let (rb, vb) = unsafe { (r.slice(n0, n1), v.slice(n0, n1)) };
                            let waves = has_waves.then(|| unsafe { &mut *wave.at(bi) });
                            let cc = chain_consts[bi].as_ref().expect("a unit's chain");
                            advance_chain(
                                cc,
                                lay,
                                opts,
                                &mut scr[j],
                                &[],
                                rb,
                                vb,
                                n0,
                                waves,
                                wbuf,
                                step,
                                dt,
                                1,
                                ChainHeld {
                                    targets: tg,
                                    lumps: Some(lumps),
                                    prepared: k > 0,
                                },
                            )
                            .map_err(Ok)?;
                        }
                        for &e in &unit.bodies {
                            // SAFETY: the unit's own body.
                            let entry = unsafe { &mut *bodies.at(e) };
                            let lumps = &*lumps;
                            entry
                                .step(
                                    lay,
                                    t,
                                    dt,
                                    |node| lumps.iter().find(|l| l.0 == node).map(|l| (l.1, l.2)),
                                    // SAFETY: the unit's own nodes.
                                    |i| unsafe { *r.at(i) },
                                    ls,
                                )
                                .map_err(|m| Err((m, t + dt)))?;
                            for (h, p) in entry.points() {
                                // SAFETY: the unit's own nodes and routes.
                                unsafe {
                                    *r.at(h.node) = V::from_f64(p.r);
                                    *v.at(h.node) = V::from_f64(p.v);
                                    *targets.at(h.route) = Some(p);
                                }
                            }
                        }
                    }
                    Ok(())
                },
            )
            .collect();
        match res {
            Ok(()) => Ok(()),
            Err(Ok(f)) => Err(self.name_failure(f)),
            Err(Err((m, time))) => Err(Error::Diverged {
                cable: m,
                node: 0,
                time,
                what: "a free body's state".into(),
            }),
        }
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
}
/// The variable elements of block `bi` under `ale` (none without winches).
impl MeshStepper for CpuSolver {
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
        CpuSolver::advance_fixed(self, nsteps)
    }

    fn remesh(&mut self) -> Result<(), Error> {
        let ale = self.ale.as_deref_mut().expect("winches");
        let mut lay = std::mem::take(&mut self.layout);
        let (mut r, mut v) = (std::mem::take(&mut self.r), std::mem::take(&mut self.v));
        let changed = ale.remesh_in_place(self.t, &mut lay, &mut r, &mut v);
        let cables = ale.last_changed.clone();
        match changed {
            Ok(true) => self.install_remeshed(lay, r, v, &cables),
            Ok(false) => (self.layout, self.r, self.v) = (lay, r, v),
            Err(e) => {
                // The description moved on, the layout may be half spliced: the run
                // ends here (a limit of the winch was passed).
                (self.layout, self.r, self.v) = (lay, r, v);
                return Err(e);
            }
        }
        Ok(())
    }
}

/// A buffer's base pointer shared by the free bodies' units' tasks
/// ([`CpuSolver::advance_units`]), which reach disjoint entries of it.
struct Shared<T>(*mut T);
impl<T> Clone for Shared<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Shared<T> {}
// SAFETY: the tasks reach disjoint entries (the caller's contract).
unsafe impl<T: Send> Send for Shared<T> {}
// SAFETY: as above.
unsafe impl<T: Send> Sync for Shared<T> {}

impl<T> Shared<T> {
    /// Entry `i`.
    ///
    /// # Safety
    /// `i` is in the buffer, and no other task reaches it meanwhile.
    unsafe fn at(self, i: usize) -> *mut T {
        // SAFETY: the caller's.
        unsafe { self.0.add(i) }
    }

    /// Entries `a..b`.
    ///
    /// # Safety
    /// As [`Shared::at`], for each; the slice is the only way to them while it lives.
    #[allow(clippy::mut_from_ref)]
    unsafe fn slice<'a>(self, a: usize, b: usize) -> &'a mut [T] {
        // SAFETY: the caller's.
        unsafe { std::slice::from_raw_parts_mut(self.0.add(a), b - a) }
    }
}

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
