//! ALE-GLMF in the lumped-mass solvers: the variable elements as the passes see them,
//! and remeshing (both backends; the GPU path remeshes on the host with this code).
//!
//! A winch cable is stepped by the chain fast path (or the general passes when it is
//! part of a network), with two additions at every stage, both evaluated at the stage's
//! time: the variable element gets `l0_v(t)` (and with it its mass, weight and added
//! mass; the tributary lengths of its two nodes follow), and its material node and
//! winch node receive the mass-flow forces of Eq. 39. Remeshing happens between steps:
//! the model description is edited (a node inserted or deleted next to the winch, the
//! other nodes kept in order) and the remeshed cable, when it is a block of its own, is
//! spliced into the packed layout in place ([`AleState::remesh_in_place`]; equal to a
//! full rebuild, which is what a cable in a network and the GPU path get), the state
//! carried over node by node.

use super::schedule::PayoutSchedule;
use super::winch::{MeshOp, Winch, WinchEnd, WinchTracker};
use crate::error::Error;
use crate::math::V3;
use crate::model::{CableDef, Layout, ModelDef, NodeDef, PointMass, NO_CONSTRAINT};
use crate::step::WinchStatus;
use std::sync::Arc;

type V = V3<f64>;

/// The variable element of one winch cable, in block-local indices, as the passes see it.
#[derive(Clone, Debug)]
pub struct AleElem {
    /// Block-local index of the variable element.
    pub elem: usize,
    /// Block-local index of the material node next to the winch.
    pub m: usize,
    /// Block-local index of the winch node.
    pub w: usize,
    /// `l0` of the variable element at the last remeshing (the layout's `elem_l0`).
    pub base_l0: f64,
    /// Payout at the last remeshing.
    pub base_dl: f64,
    /// `mbar` of the cable, kg/m.
    pub mass: f64,
    /// The payout schedule.
    pub sched: Arc<PayoutSchedule>,
}

impl AleElem {
    /// The variable element's `l0` at payout `dl` (bitwise `base_l0` when nothing was
    /// paid out since the last remeshing).
    #[inline(always)]
    pub fn l0(&self, dl: f64) -> f64 {
        self.base_l0 + (dl - self.base_dl)
    }
}

/// Everything the solver keeps for its winch cables.
#[derive(Clone, Debug)]
pub struct AleState {
    /// The current mesh as a model description (edited at each remeshing).
    pub def: ModelDef,
    /// Packed index of each described node.
    pub packed_of_def: Vec<u32>,
    /// The winches and their mesh states.
    pub winches: Vec<(Winch, WinchTracker)>,
    /// Per block of the current layout: its variable elements (usually none or one).
    pub blocks: Vec<Vec<AleElem>>,
    /// Cables whose mesh the last [`Self::remesh_in_place`] changed (every other block of the
    /// new layout equals the old one but for its position and constraint numbers).
    pub last_changed: Vec<usize>,
}

impl AleState {
    /// Checks the winches against the model and sets up their mesh states at `t = 0`.
    pub fn new(def: ModelDef, winches: Vec<Winch>, packed_of_def: Vec<u32>) -> Result<Self, Error> {
        let mut seen = vec![false; def.cables.len()];
        let mut out = Vec::with_capacity(winches.len());
        for w in winches {
            let Some(c) = def.cables.get(w.cable) else {
                return Err(Error::Model(format!(
                    "a winch refers to missing cable {}",
                    w.cable
                )));
            };
            if std::mem::replace(&mut seen[w.cable], true) {
                return Err(Error::Model(format!("cable '{}' has two winches", c.name)));
            }
            let node = match w.end {
                WinchEnd::Start => c.nodes[0],
                WinchEnd::End => c.nodes[c.nodes.len() - 1],
            };
            if def.nodes[node].route.is_none() {
                return Err(Error::Model(format!(
                    "cable '{}': the winch end must be held (fixed or on a route)",
                    c.name
                )));
            }
            let uses = def
                .cables
                .iter()
                .map(|c| c.nodes.iter().filter(|&&n| n == node).count())
                .sum::<usize>();
            if uses != 1 {
                return Err(Error::Model(format!(
                    "cable '{}': the winch node must belong to this cable alone",
                    c.name
                )));
            }
            if !(w.element_length > 0.0 && w.element_length.is_finite()) {
                return Err(Error::Model(format!(
                    "cable '{}': the winch's standard element length must be positive, got {}",
                    c.name, w.element_length
                )));
            }
            let dl0 = w.schedule.eval(0.0).dl;
            let tr = WinchTracker::new(&w, &c.l0, dl0);
            out.push((w, tr));
        }
        Ok(Self {
            def,
            packed_of_def,
            winches: out,
            blocks: Vec::new(),
            last_changed: Vec::new(),
        })
    }

    /// Fills `blocks` for layout `lay` (built from `def`).
    pub fn index(&mut self, lay: &Layout) {
        let mut blocks = vec![Vec::new(); lay.blocks.len()];
        for (w, tr) in &self.winches {
            let c = &lay.cables[w.cable];
            let n = c.nodes.len();
            let (elem, m, wn) = match w.end {
                WinchEnd::Start => (c.elements[0], c.nodes[1], c.nodes[0]),
                WinchEnd::End => (c.elements[n - 2], c.nodes[n - 2], c.nodes[n - 1]),
            };
            // Blocks are in node order.
            let bi = lay.blocks.partition_point(|b| b.node_end <= wn);
            debug_assert!(lay.blocks[bi].node_start <= wn && wn < lay.blocks[bi].node_end);
            let b = lay.blocks[bi];
            debug_assert_eq!(lay.elem_l0[elem as usize], tr.base_l0);
            blocks[bi].push(AleElem {
                elem: (elem - b.elem_start) as usize,
                m: (m - b.node_start) as usize,
                w: (wn - b.node_start) as usize,
                base_l0: tr.base_l0,
                base_dl: tr.base_dl,
                mass: lay.line_coefs[c.line_type].mass,
                sched: w.schedule.clone(),
            });
        }
        self.blocks = blocks;
    }

    /// Where each winch cable stands at time `t`.
    pub fn status(&self, t: f64) -> Vec<WinchStatus> {
        self.winches
            .iter()
            .map(|(w, tr)| {
                let dl = w.schedule.eval(t).dl;
                let mut p = tr.physical_coordinates(dl);
                // Far end first; the cable's node order runs from the winch when the
                // winch is at its start.
                if w.end == WinchEnd::Start {
                    p.reverse();
                }
                WinchStatus {
                    cable: w.cable,
                    deployed_length: tr.deployed(dl),
                    variable_l0: tr.variable_l0(dl),
                    physical_coordinates: p,
                    elements: tr.n_elements(),
                    inserted: tr.inserted,
                    deleted: tr.deleted,
                }
            })
            .collect()
    }

    /// The variable elements of layout `lay` (the one [`Self::index`] was last given)
    /// in packed indices, block by block: `(element, m, w, its AleElem)`.
    pub fn packed_variable_elements<'a>(
        &'a self,
        lay: &'a Layout,
    ) -> impl Iterator<Item = (usize, usize, usize, &'a AleElem)> + 'a {
        lay.blocks.iter().zip(&self.blocks).flat_map(|(b, v)| {
            v.iter().map(move |ae| {
                (
                    b.elem_start as usize + ae.elem,
                    b.node_start as usize + ae.m,
                    b.node_start as usize + ae.w,
                    ae,
                )
            })
        })
    }

    /// How many of the next `left` steps (of `dt`, after step `step`) run on the
    /// current mesh: up to and including the first step after which some winch must
    /// remesh (or passes a limit), else all of them.
    pub fn steps_on_this_mesh(&self, step: u64, left: u64, dt: f64) -> u64 {
        let act = |k: u64| self.needs_action((step + k) as f64 * dt);
        if left == 0 || !self.winches.iter().all(|(w, _)| w.schedule.is_constant()) {
            return (1..=left).find(|&k| act(k)).unwrap_or(left);
        }
        // Constant rates: the paid-out length is monotone in the step, and the mesh is
        // kept where the variable element lies in a band and the drum holds the
        // length; a winch that is in range after the first step leaves it on one side
        // only, and stays out. So `act` is false up to a step and true from there on,
        // and a bisection finds that step (the one the scan above would find) with
        // log2(left) evaluations instead of one per step.
        if act(1) {
            return 1;
        }
        // act(lo) is false; hi is the first step that may act (left + 1: none).
        let (mut lo, mut hi) = (1, left + 1);
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if act(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi.min(left)
    }

    /// True when some winch must remesh (or passes a limit) at time `t`.
    pub fn needs_action(&self, t: f64) -> bool {
        self.winches
            .iter()
            .any(|(w, tr)| tr.needs_action(w.schedule.eval(t).dl))
    }

    /// Packs the edited description afresh; `rd`, `vd` the state in description order.
    fn rebuild(&mut self, rd: &[V], vd: &[V]) -> Result<(Layout, Vec<V>, Vec<V>), Error> {
        for (d, nd) in self.def.nodes.iter_mut().enumerate() {
            nd.position = rd[d].to_f64();
        }
        let (lay, pos, packed) = Layout::build_indexed(&self.def)?;
        let mut vp = vec![V::zero(); pos.len()];
        for (d, &i) in packed.iter().enumerate() {
            vp[i as usize] = vd[d];
        }
        let rp = pos.iter().map(|p| V::from_f64(*p)).collect();
        self.packed_of_def = packed;
        self.index(&lay);
        debug_assert!(lay
            .constraint_node
            .iter()
            .all(|&n| lay.node_constraint[n as usize] != NO_CONSTRAINT));
        Ok((lay, rp, vp))
    }

    /// Remeshes every winch cable at time `t`, moving the described nodes: `lay`, `r`,
    /// `v` (the packed layout and state) become the new ones; an error names the cable
    /// and the limit passed. Each changed cable that is a block of its own is spliced into the layout
    /// ([`Layout::splice_chain`]: nothing else is rebuilt, and the result equals a full
    /// [`Layout::build`]); otherwise the layout is rebuilt. Returns whether the mesh
    /// changed.
    pub fn remesh_in_place(
        &mut self,
        t: f64,
        lay: &mut Layout,
        r: &mut Vec<V>,
        v: &mut Vec<V>,
    ) -> Result<bool, Error> {
        // Where each winch cable's block and constraints are before the edit.
        let before: Vec<(usize, usize, Vec<u32>, bool)> = self
            .winches
            .iter()
            .map(|(w, _)| {
                let c = &lay.cables[w.cable];
                let first = c.nodes[0];
                let bi = lay.blocks.partition_point(|b| b.node_end <= first);
                let b = lay.blocks[bi];
                let alone = (b.node_end - b.node_start) as usize == c.nodes.len() && b.is_chain;
                let cons = [c.nodes[0], c.nodes[c.nodes.len() - 1]]
                    .iter()
                    .map(|&n| lay.node_constraint[n as usize])
                    .filter(|&k| k != NO_CONSTRAINT)
                    .collect();
                (w.cable, bi, cons, alone)
            })
            .collect();
        let n_before = lay.n_nodes();
        let Some((rd, vd)) = self.edit(t, r, v)? else {
            return Ok(false);
        };
        let changed: Vec<&(usize, usize, Vec<u32>, bool)> = before
            .iter()
            .filter(|(ci, ..)| self.last_changed.contains(ci))
            .collect();
        if changed.iter().any(|(.., alone)| !alone) {
            let (l, rp, vp) = self.rebuild(&rd, &vd)?;
            (*lay, *r, *v) = (l, rp, vp);
            return Ok(true);
        }
        // Later blocks first, so earlier blocks' indices stay valid.
        let mut order = changed;
        order.sort_by_key(|(_, bi, ..)| std::cmp::Reverse(*bi));
        for &&(ci, bi, ref cons, _) in &order {
            let c = &self.def.cables[ci];
            let one_def = ModelDef {
                env: self.def.env,
                line_types: vec![self.def.line_types[c.line_type].clone()],
                currents: vec![self.def.currents[c.current].clone()],
                nodes: c
                    .nodes
                    .iter()
                    .map(|&d| NodeDef {
                        position: rd[d].to_f64(),
                        ..self.def.nodes[d].clone()
                    })
                    .collect(),
                cables: vec![CableDef {
                    name: c.name.clone(),
                    line_type: 0,
                    nodes: (0..c.nodes.len()).collect(),
                    l0: c.l0.clone(),
                    current: 0,
                    output_positions: c.output_positions,
                    elem_lines: Vec::new(),
                }],
                // A winch cable has no bending stiffness (refused by the scenario).
                clamps: Vec::new(),
                joints: Vec::new(),
                screens: Default::default(),
            };
            let (one, _, _) = Layout::build_indexed(&one_def)?;
            let b = lay.blocks[bi];
            let (ns, ne) = (b.node_start as usize, b.node_end as usize);
            r.splice(ns..ne, c.nodes.iter().map(|&d| rd[d]));
            v.splice(ns..ne, c.nodes.iter().map(|&d| vd[d]));
            lay.splice_chain(bi, ci, &one, cons, c.line_type as u32, c.current as u32);
        }
        // Where each described node is now: cable nodes from the cables; loose nodes
        // (points on no cable) come after every cable's block and moved by the change
        // in the node count.
        let dn = lay.n_nodes() as i64 - n_before as i64;
        let mut on_cable = vec![false; self.def.nodes.len()];
        for (c, lc) in self.def.cables.iter().zip(&lay.cables) {
            for (&d, &p) in c.nodes.iter().zip(&lc.nodes) {
                self.packed_of_def[d] = p;
                on_cable[d] = true;
            }
        }
        for (d, p) in self.packed_of_def.iter_mut().enumerate() {
            if !on_cable[d] {
                *p = (*p as i64 + dn) as u32;
            }
        }
        for (d, nd) in self.def.nodes.iter_mut().enumerate() {
            nd.position = rd[d].to_f64();
        }
        self.index(lay);
        Ok(true)
    }

    /// Applies the remeshing rules of every winch at time `t` to the description;
    /// returns the state in description order (moved and extended like the
    /// description), or `None` when no mesh changed.
    #[allow(clippy::type_complexity)]
    fn edit(&mut self, t: f64, r: &[V], v: &[V]) -> Result<Option<(Vec<V>, Vec<V>)>, Error> {
        let mut plans = Vec::new();
        for (wi, (w, tr)) in self.winches.iter_mut().enumerate() {
            let pay = w.schedule.eval(t);
            if !tr.needs_action(pay.dl) {
                continue;
            }
            let ops = tr.remesh(pay.dl).map_err(|lim| Error::Winch {
                cable: self.def.cables[w.cable].name.clone(),
                time: t,
                message: lim.to_string(),
            })?;
            if !ops.is_empty() {
                plans.push((wi, ops, pay.rate));
            }
        }
        if plans.is_empty() {
            return Ok(None);
        }
        self.last_changed = plans.iter().map(|p| self.winches[p.0].0.cable).collect();
        // The state in description order.
        let mut rd: Vec<V> = self.packed_of_def.iter().map(|&i| r[i as usize]).collect();
        let mut vd: Vec<V> = self.packed_of_def.iter().map(|&i| v[i as usize]).collect();
        for (wi, ops, rate) in plans {
            let (w, tr) = &self.winches[wi];
            let ci = w.cable;
            for op in ops {
                let c = &self.def.cables[ci];
                let n = c.nodes.len();
                // Positions in the cable's node list of the winch node and of m.
                let (kw, km) = match w.end {
                    WinchEnd::Start => (0, 1),
                    WinchEnd::End => (n - 1, n - 2),
                };
                let (dw, dm) = (c.nodes[kw], c.nodes[km]);
                match op {
                    MeshOp::Insert { xi, l0_before } => {
                        let (rm, rw, vm, vw) = (rd[dm], rd[dw], vd[dm], vd[dw]);
                        let rn = rm + (rw - rm) * xi;
                        let vn = super::mass_flow::material_velocity(
                            xi, l0_before, rate, rm, rw, vm, vw,
                        );
                        let d = self.def.nodes.len();
                        self.def.nodes.push(NodeDef {
                            position: rn.to_f64(),
                            point: PointMass::default(),
                            route: None,
                            label: None,
                        });
                        rd.push(rn);
                        vd.push(vn);
                        self.packed_of_def.push(u32::MAX); // set by the caller
                        let l_var = l0_before - tr.l_std;
                        let c = &mut self.def.cables[ci];
                        match w.end {
                            WinchEnd::Start => {
                                c.nodes.insert(1, d);
                                c.l0[0] = l_var;
                                c.l0.insert(1, tr.l_std);
                            }
                            WinchEnd::End => {
                                c.nodes.insert(n - 1, d);
                                let last = c.l0.len() - 1;
                                c.l0[last] = tr.l_std;
                                c.l0.push(l_var);
                            }
                        }
                    }
                    MeshOp::Delete => {
                        let c = &mut self.def.cables[ci];
                        match w.end {
                            WinchEnd::Start => {
                                c.nodes.remove(1);
                                let merged = c.l0[0] + c.l0[1];
                                c.l0.remove(0);
                                c.l0[0] = merged;
                            }
                            WinchEnd::End => {
                                c.nodes.remove(n - 2);
                                let last = c.l0.pop().expect("two elements at least");
                                let k = c.l0.len() - 1;
                                c.l0[k] += last;
                            }
                        }
                        // Drop the described node, keeping the others in order (the
                        // constraints are numbered in description order: a rebuild
                        // then numbers them as before).
                        self.def.nodes.remove(dm);
                        rd.remove(dm);
                        vd.remove(dm);
                        self.packed_of_def.remove(dm);
                        for c in &mut self.def.cables {
                            for x in c.nodes.iter_mut().filter(|x| **x > dm) {
                                *x -= 1;
                            }
                        }
                    }
                }
            }
            // The description holds the tracker's variable length exactly.
            let c = &mut self.def.cables[ci];
            let kv = match w.end {
                WinchEnd::Start => 0,
                WinchEnd::End => c.l0.len() - 1,
            };
            c.l0[kv] = tr.base_l0;
        }
        Ok(Some((rd, vd)))
    }
}
