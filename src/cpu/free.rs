//! Free and pinned bodies on the CPU path: stepped with their lines in the same
//! symplectic Euler step (docs/src/bodies.md, "Free bodies").
//!
//! A step: every block's passes at the state of step `n` (the blocks with nodes held on
//! a free body take the general passes, whose element loads the body reads), each held
//! node's force and mass block at that state lumped into its body ([`Lump`]), the body
//! advanced, and its held nodes placed rigidly at its points. The held nodes' route
//! targets are the body's points now ([`FreeRun::targets`], read by the node pass in
//! place of the route), so an output-time evaluation reports their reactions against
//! the body's own motion.

use crate::body::free::{Fluid, FreeBody, FreeKind, Lump, Pin};
use crate::body::kinematics::attachment;
use crate::body::Body;
use crate::math::{Sym3, V3};
use crate::model::{Layout, Route, RouteState};
use std::sync::Arc;

type V = V3<f64>;

/// A node held on a free body.
#[derive(Clone, Debug)]
pub(crate) struct Held {
    /// Packed node.
    pub node: usize,
    /// Route (constraint) index.
    pub route: usize,
    /// Body coordinates, m.
    pub at: [f64; 3],
}

/// One free or pinned body in a run.
#[derive(Clone, Debug)]
pub(crate) struct FreeEntry {
    /// The body as the layout's routes share it (name, pose, pinned translation).
    pub body: Arc<Body>,
    /// Its state.
    pub state: FreeBody,
    /// Its held nodes.
    pub held: Vec<Held>,
}

/// The free and pinned bodies of a run and what the passes read of them.
#[derive(Clone, Debug)]
pub(crate) struct FreeRun {
    /// The bodies.
    pub bodies: Vec<FreeEntry>,
    /// Per route: the target of a node held on a free body (its body's point now);
    /// `None` for the other routes.
    pub targets: Vec<Option<RouteState>>,
    /// Per block: whether it has a node held on a free body.
    pub touched: Vec<bool>,
    /// Per block: its held nodes, block-local, and their routes.
    pub held_local: Vec<Vec<(usize, usize)>>,
    /// The bodies and blocks that step together: each unit is a connected group of
    /// free bodies and the blocks holding nodes on them (a body's lines; a line between
    /// two bodies joins them), stepped step by step apart from the other units.
    pub units: Vec<Unit>,
    /// Per block: the unit it is in (`None`: no node of it was ever held on a free
    /// body; kept when a failure lets a node go).
    pub unit_of: Vec<Option<usize>>,
}

/// Free bodies and blocks that step together ([`FreeRun::units`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Unit {
    /// Its blocks, in order.
    pub blocks: Vec<usize>,
    /// Its bodies (indices into [`FreeRun::bodies`]).
    pub bodies: Vec<usize>,
}

impl FreeRun {
    /// The free and pinned bodies of `lay`, at their initial state; `None` when it
    /// has none.
    pub fn new(lay: &Layout) -> Option<Self> {
        let mut bodies: Vec<FreeEntry> = Vec::new();
        for (c, r) in lay.routes.iter().enumerate() {
            let Route::Body { body, at } = r else {
                continue;
            };
            let Some(d) = body.dynamic() else {
                continue;
            };
            let held = Held {
                node: lay.constraint_node[c] as usize,
                route: c,
                at: *at,
            };
            match bodies.iter_mut().find(|e| Arc::ptr_eq(&e.body, body)) {
                Some(e) => e.held.push(held),
                None => bodies.push(FreeEntry {
                    body: body.clone(),
                    state: d.body.clone(),
                    held: vec![held],
                }),
            }
        }
        if bodies.is_empty() {
            return None;
        }
        let nb = lay.blocks.len();
        let mut touched = vec![false; nb];
        let mut held_local = vec![Vec::new(); nb];
        // Units: a union-find over blocks, each body joining the blocks it holds.
        let mut parent: Vec<usize> = (0..nb).collect();
        fn root(p: &mut [usize], mut i: usize) -> usize {
            while p[i] != i {
                p[i] = p[p[i]];
                i = p[i];
            }
            i
        }
        let mut body_block = Vec::with_capacity(bodies.len());
        for e in &bodies {
            let mut first = None;
            for h in &e.held {
                let bi = lay
                    .blocks
                    .partition_point(|b| (b.node_end as usize) <= h.node);
                touched[bi] = true;
                held_local[bi].push((h.node - lay.blocks[bi].node_start as usize, h.route));
                match first {
                    None => first = Some(bi),
                    Some(f) => {
                        let (a, b) = (root(&mut parent, f), root(&mut parent, bi));
                        parent[a] = b;
                    }
                }
            }
            body_block.push(first);
        }
        let mut unit_of = vec![None; nb];
        let mut units: Vec<Unit> = Vec::new();
        for bi in (0..nb).filter(|&bi| touched[bi]) {
            let r = root(&mut parent, bi);
            let u = match unit_of[r] {
                Some(u) => u,
                None => {
                    units.push(Unit::default());
                    unit_of[r] = Some(units.len() - 1);
                    units.len() - 1
                }
            };
            units[u].blocks.push(bi);
        }
        for bi in (0..nb).filter(|&bi| touched[bi]) {
            let r = root(&mut parent, bi);
            unit_of[bi] = unit_of[r];
        }
        for (k, first) in body_block.iter().enumerate() {
            // A body holding nothing steps with the first unit (or alone, in a unit of
            // no blocks).
            match first.and_then(|bi| unit_of[bi]) {
                Some(u) => units[u].bodies.push(k),
                None => units.push(Unit {
                    blocks: Vec::new(),
                    bodies: vec![k],
                }),
            }
        }
        let mut run = Self {
            bodies,
            targets: vec![None; lay.routes.len()],
            touched,
            held_local,
            units,
            unit_of,
        };
        run.refresh_targets();
        Some(run)
    }

    /// Sets every held node's target to its body's point now.
    pub fn refresh_targets(&mut self) {
        for e in &self.bodies {
            let s = e.state.body_state();
            for h in &e.held {
                self.targets[h.route] = Some(attachment(&s, h.at));
            }
        }
    }

    /// Advances every body by `dt` from `t` with the held nodes' forces and mass
    /// blocks `lumps` (packed node, force, mass block), places the held nodes on
    /// their points in `r`, `v`, and refreshes the targets. `Err` names the body.
    pub fn step(
        &mut self,
        lay: &Layout,
        t: f64,
        dt: f64,
        lumps: &[(usize, V, Sym3<f64>)],
        r: &mut [V],
        v: &mut [V],
    ) -> Result<(), String> {
        // Sorted by node: each held node's lump found by bisection (a fleet's bodies
        // hold thousands of nodes).
        let mut lumps = lumps.to_vec();
        lumps.sort_unstable_by_key(|l| l.0);
        let lump = |node: usize| {
            lumps
                .binary_search_by_key(&node, |l| l.0)
                .ok()
                .map(|k| (lumps[k].1, lumps[k].2))
        };
        let mut ls = Vec::new();
        for e in &mut self.bodies {
            e.step(lay, t, dt, lump, |i| r[i], &mut ls)?;
            for (h, p) in e.points() {
                r[h.node] = V::from_f64(p.r);
                v[h.node] = V::from_f64(p.v);
                self.targets[h.route] = Some(p);
            }
        }
        Ok(())
    }
}

impl FreeEntry {
    /// Each held node and its point on the body now (where it goes after a step, and
    /// its target from then on).
    pub fn points(&self) -> impl Iterator<Item = (&Held, RouteState)> + '_ {
        let s = self.state.body_state();
        self.held.iter().map(move |h| (h, attachment(&s, h.at)))
    }

    /// Advances the body by `dt` from `t`: `lump(node)` gives each held node's force
    /// and mass block at the step's start, `pos(node)` its position. The held nodes
    /// go to [`Self::points`] then. `Err` names the body.
    pub fn step(
        &mut self,
        lay: &Layout,
        t: f64,
        dt: f64,
        lump: impl Fn(usize) -> Option<(V, Sym3<f64>)>,
        pos: impl Fn(usize) -> V,
        ls: &mut Vec<Lump>,
    ) -> Result<(), String> {
        let fluid = Fluid {
            rho: lay.env.water_density,
            g: lay.env.gravity,
        };
        ls.clear();
        for h in &self.held {
            // The force and mass of each held node (the passes' values at step n).
            let Some((f, m)) = lump(h.node) else {
                return Err(format!(
                    "body '{}': no load for its node {}",
                    self.body.name, h.node
                ));
            };
            ls.push(Lump {
                r: pos(h.node).to_f64(),
                m: [[m.xx, m.xy, m.xz], [m.xy, m.yy, m.yz], [m.xz, m.yz, m.zz]],
                f: f.to_f64(),
            });
        }
        let u = current_at(lay, &self.state);
        let (pin, pin_next) = (self.pin(t), self.pin(t + dt));
        self.state
            .step(t, dt, fluid, u, ls, pin, pin_next)
            .map_err(|m| format!("body '{}': {m}", self.body.name))
    }

    /// A pinned body's pin at time `t` (`None` for a free body).
    pub fn pin(&self, t: f64) -> Option<Pin> {
        match self.state.kind {
            FreeKind::Free => None,
            FreeKind::Pinned => Some(self.body.pin(t)),
        }
    }
}

/// The water and gravity of the layout.
pub(crate) fn fluid_of(lay: &Layout) -> Fluid {
    Fluid {
        rho: lay.env.water_density,
        g: lay.env.gravity,
    }
}

/// The current at body `b`'s reference point (the layout's first profile).
pub(crate) fn current_at(lay: &Layout, b: &FreeBody) -> [f64; 3] {
    let x = b.reference();
    lay.currents
        .first()
        .map_or([0.0; 3], |c| c.at(x.z).to_f64())
}

impl FreeRun {
    /// Lets node `node` go (its cable end failed): it is no longer held on a body.
    pub fn release(&mut self, node: usize, lay: &Layout) {
        for e in &mut self.bodies {
            for h in e.held.iter().filter(|h| h.node == node) {
                self.targets[h.route] = None;
            }
            e.held.retain(|h| h.node != node);
        }
        let bi = lay
            .blocks
            .partition_point(|b| (b.node_end as usize) <= node);
        let li = node - lay.blocks[bi].node_start as usize;
        self.held_local[bi].retain(|x| x.0 != li);
        self.touched[bi] = !self.held_local[bi].is_empty();
    }
}

/// A cable end that may fail, and whether it has.
#[derive(Clone, Debug)]
pub(crate) struct Failure {
    /// What the scenario asked.
    pub spec: crate::model::EndFailure,
    /// Packed node of the end.
    pub node: usize,
    /// Packed element at the end.
    pub elem: usize,
    /// When and how it failed.
    pub fired: Option<crate::model::FailureEvent>,
}

/// The elastic tension of element `e` at positions `r`, N: `EA` times its strain (a
/// tabulated line's curve), zero in slack.
pub(crate) fn end_tension(lay: &Layout, r: &[V], e: usize) -> f64 {
    let (a, b) = (lay.elem_a[e] as usize, lay.elem_b[e] as usize);
    let l = (r[b] - r[a]).norm();
    let l0 = lay.elem_l0[e];
    let line = lay.elem_line[e] as usize;
    if let Some(rows) = lay.line_types[line].ea_curve.as_deref() {
        return crate::physics::tabulated_tension(rows, l / l0 - 1.0);
    }
    let ea = lay.line_coefs[line].ea;
    (ea * (l - l0) / l0).max(0.0)
}
