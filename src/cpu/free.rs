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

use crate::body::free::{Fluid, FreeBody, FreeKind, Lump};
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
    /// Per block: the block-local indices of its held nodes.
    pub held_local: Vec<Vec<usize>>,
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
        let mut touched = vec![false; lay.blocks.len()];
        let mut held_local = vec![Vec::new(); lay.blocks.len()];
        for e in &bodies {
            for h in &e.held {
                let bi = lay
                    .blocks
                    .partition_point(|b| (b.node_end as usize) <= h.node);
                touched[bi] = true;
                held_local[bi].push(h.node - lay.blocks[bi].node_start as usize);
            }
        }
        let mut run = Self {
            bodies,
            targets: vec![None; lay.routes.len()],
            touched,
            held_local,
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
        let fluid = Fluid {
            rho: lay.env.water_density,
            g: lay.env.gravity,
        };
        for e in &mut self.bodies {
            let mut ls = Vec::with_capacity(e.held.len());
            for h in &e.held {
                // The force and mass of each held node (the passes' values at step n).
                let Some((_, f, m)) = lumps.iter().find(|l| l.0 == h.node) else {
                    return Err(format!(
                        "body '{}': no load for its node {}",
                        e.body.name, h.node
                    ));
                };
                ls.push(Lump {
                    r: r[h.node].to_f64(),
                    m: [[m.xx, m.xy, m.xz], [m.xy, m.yy, m.yz], [m.xz, m.yz, m.zz]],
                    f: f.to_f64(),
                });
            }
            let x = e.state.reference();
            let u = lay
                .currents
                .first()
                .map_or([0.0; 3], |c| c.at(x.z).to_f64());
            let (pin, pin_next) = match e.state.kind {
                FreeKind::Free => (None, None),
                FreeKind::Pinned => (Some(e.body.pin(t)), Some(e.body.pin(t + dt))),
            };
            e.state
                .step(t, dt, fluid, u, &ls, pin, pin_next)
                .map_err(|m| format!("body '{}': {m}", e.body.name))?;
            let s = e.state.body_state();
            for h in &e.held {
                let p = attachment(&s, h.at);
                r[h.node] = V::from_f64(p.r);
                v[h.node] = V::from_f64(p.v);
                self.targets[h.route] = Some(p);
            }
        }
        Ok(())
    }
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
        self.held_local[bi].retain(|&x| x != li);
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
