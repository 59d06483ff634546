//! Free and pinned bodies under the Runge-Kutta schemes (RK2, RK4): each unit of
//! bodies and the blocks holding nodes on them (`super::super::free::Unit`) steps
//! through the same stages, the bodies' states (centre of gravity, its velocity, the
//! attitude quaternion, the angular velocity) in the stage buffers beside the nodes'
//! (docs/src/bodies.md, "Time schemes").
//!
//! At each stage the held nodes are placed on their bodies' points of the stage's
//! body state, the blocks' accelerations are evaluated there (the general passes), and
//! each held node's force and mass block is lumped into its body, as in the symplectic
//! step: the bodies' rates come from the same stage as the lines'. At the step's end the
//! held nodes go to their bodies' points again.

use super::super::free::{current_at, fluid_of};
use super::super::passes::{block_accelerations, fill_water, implicit_dt, Ctx};
use super::super::water::Water;
use super::CpuSolver;
use crate::body::attachment;
use crate::body::free::{FreeBody, Lump, Rates};
use crate::error::Error;
use crate::math::{Sym3, V3};
use crate::options::Scheme;
use crate::step::{blow_up, StepFailure};

type V = V3<f64>;

/// One block's stage buffers.
struct Stages {
    bi: usize,
    n0: usize,
    n1: usize,
    e0: usize,
    e1: usize,
    r0: Vec<V>,
    v0: Vec<V>,
    rs: Vec<V>,
    vs: Vec<V>,
    sr: Vec<V>,
    sv: Vec<V>,
    acc: Vec<V>,
    x0: Vec<f64>,
    xs: Vec<f64>,
    xsum: Vec<f64>,
}

/// A scheme's stages as `(time, weight, next)` in fractions of the step: the stage's
/// time, its rates' weight in the step's sum, and how far along its rates the next
/// stage's state lies from the step's start; and the weights' divisor.
pub(crate) fn rk_tableau(scheme: Scheme) -> Option<(&'static [(f64, f64, f64)], f64)> {
    match scheme {
        Scheme::Symplectic => None,
        // The midpoint rule, as the lines' RK2.
        Scheme::Rk2 => Some((&[(0.0, 0.0, 0.5), (0.5, 1.0, 0.0)], 1.0)),
        Scheme::Rk4 => Some((
            &[
                (0.0, 1.0, 0.5),
                (0.5, 2.0, 0.5),
                (0.5, 2.0, 1.0),
                (1.0, 1.0, 0.0),
            ],
            6.0,
        )),
    }
}

impl CpuSolver {
    /// Steps the free bodies' units `nsteps` steps from step `step0` in the run's
    /// Runge-Kutta scheme (the general passes for their blocks). The blocks outside the
    /// units are not touched, nor the step count.
    pub(super) fn advance_units_rk(&mut self, step0: u64, nsteps: u64) -> Result<(), Error> {
        let dt = self.opts.dt;
        // The units' blocks take the general passes: their element loads.
        self.general_buffers();
        let (tableau, div) = rk_tableau(self.opts.scheme).expect("a Runge-Kutta scheme");
        let seabed = self.ctx().seabed;
        let res = (|| -> Result<(), Failed> {
            let free = self.free.as_deref_mut().expect("free bodies");
            let lay = &self.layout;
            let fluid = fluid_of(lay);
            let body_err = |m: String, t: f64| {
                Failed::Body(Error::Diverged {
                    cable: m,
                    node: 0,
                    time: t,
                    what: "a free body's state".into(),
                })
            };
            let mut wbuf = Water::new();
            let mut lumps: Vec<(usize, V, Sym3<f64>)> = Vec::new();
            let mut ls: Vec<Lump> = Vec::new();
            for u in 0..free.units.len() {
                let unit = free.units[u].clone();
                let mut blks: Vec<Stages> = unit
                    .blocks
                    .iter()
                    .map(|&bi| {
                        let b = lay.blocks[bi];
                        let (n0, n1) = (b.node_start as usize, b.node_end as usize);
                        let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
                        let nx = if self.visco.is_empty() { 0 } else { e1 - e0 };
                        Stages {
                            bi,
                            n0,
                            n1,
                            e0,
                            e1,
                            r0: vec![V::zero(); n1 - n0],
                            v0: vec![V::zero(); n1 - n0],
                            rs: vec![V::zero(); n1 - n0],
                            vs: vec![V::zero(); n1 - n0],
                            sr: vec![V::zero(); n1 - n0],
                            sv: vec![V::zero(); n1 - n0],
                            acc: vec![V::zero(); n1 - n0],
                            x0: vec![0.0; nx],
                            xs: vec![0.0; nx],
                            xsum: vec![0.0; nx],
                        }
                    })
                    .collect();
                for k in 0..nsteps {
                    let t = (step0 + k) as f64 * dt;
                    for s in &mut blks {
                        s.r0.copy_from_slice(&self.r[s.n0..s.n1]);
                        s.v0.copy_from_slice(&self.v[s.n0..s.n1]);
                        s.rs.copy_from_slice(&s.r0);
                        s.vs.copy_from_slice(&s.v0);
                        s.sr.fill(V::zero());
                        s.sv.fill(V::zero());
                        if !s.x0.is_empty() {
                            s.x0.copy_from_slice(&self.visco[s.e0..s.e1]);
                            s.xs.copy_from_slice(&s.x0);
                            s.xsum.fill(0.0);
                        }
                    }
                    let body0: Vec<FreeBody> = unit
                        .bodies
                        .iter()
                        .map(|&ib| free.bodies[ib].state.clone())
                        .collect();
                    let mut stage_b = body0.clone();
                    let mut sums = vec![Rates::default(); body0.len()];
                    let mut first_acc = Vec::with_capacity(body0.len());
                    for (si, &(tau, w, next)) in tableau.iter().enumerate() {
                        let last = si + 1 == tableau.len();
                        let ts = t + tau * dt;
                        // The held nodes on their bodies' points at this stage.
                        for (j, &ib) in unit.bodies.iter().enumerate() {
                            let st = stage_b[j].body_state();
                            for h in &free.bodies[ib].held {
                                free.targets[h.route] = Some(attachment(&st, h.at));
                            }
                        }
                        lumps.clear();
                        for s in &mut blks {
                            let held = &free.held_local[s.bi];
                            for &(li, route) in held {
                                let p = free.targets[route].expect("a held node's target");
                                s.rs[li] = V::from_f64(p.r);
                                s.vs[li] = V::from_f64(p.v);
                            }
                            let ctx = Ctx {
                                lay,
                                coefs: &self.coefs,
                                seabed,
                                opts: self.opts,
                                elem_in_cable: &self.elem_in_cable,
                                uniform_current: &self.uniform_current,
                                gravity: lay.env.gravity,
                                implicit_dt: implicit_dt(&self.opts),
                                targets: &free.targets,
                                hinges: &self.hinges,
                            };
                            let b = lay.blocks[s.bi];
                            let mut waves = self.wave_blocks.get_mut(s.bi);
                            if waves.is_none() {
                                wbuf.clear();
                            }
                            fill_water(&mut waves, ts, &s.rs, &s.vs, &mut wbuf);
                            let (acc, n0) = (&mut s.acc, s.n0);
                            block_accelerations(
                                &ctx,
                                &b,
                                &s.rs,
                                &s.vs,
                                &s.xs,
                                ts,
                                &wbuf,
                                &mut self.elems[s.e0..s.e1],
                                |li, a, f, m| {
                                    acc[li] = a;
                                    if held.iter().any(|x| x.0 == li) {
                                        lumps.push((n0 + li, f, m));
                                    }
                                },
                            )
                            .map_err(Failed::Step)?;
                            // The next stage's nodes and internal states.
                            let els = &self.elems[s.e0..s.e1];
                            for (x, el) in s.xsum.iter_mut().zip(els) {
                                *x += el.rate * w;
                            }
                            if !last {
                                for ((xs, x0), el) in s.xs.iter_mut().zip(&s.x0).zip(els) {
                                    *xs = x0 + el.rate * (next * dt);
                                }
                            }
                            for li in 0..s.rs.len() {
                                s.sr[li] += s.vs[li] * w;
                                s.sv[li] += s.acc[li] * w;
                                if !last {
                                    s.rs[li] = s.r0[li] + s.vs[li] * (next * dt);
                                    s.vs[li] = s.v0[li] + s.acc[li] * (next * dt);
                                }
                            }
                        }
                        lumps.sort_unstable_by_key(|l| l.0);
                        // The bodies' rates at this stage, and their next stage.
                        for (j, &ib) in unit.bodies.iter().enumerate() {
                            let e = &free.bodies[ib];
                            ls.clear();
                            for h in &e.held {
                                let Ok(q) = lumps.binary_search_by_key(&h.node, |l| l.0) else {
                                    return Err(body_err(
                                        format!(
                                            "body '{}': no load for its node {}",
                                            e.body.name, h.node
                                        ),
                                        ts,
                                    ));
                                };
                                let (_, f, m) = lumps[q];
                                let rp = free.targets[h.route].expect("a held node's target").r;
                                ls.push(Lump {
                                    r: rp,
                                    m: [[m.xx, m.xy, m.xz], [m.xy, m.yy, m.yz], [m.xz, m.yz, m.zz]],
                                    f: f.to_f64(),
                                });
                            }
                            let u = current_at(lay, &stage_b[j]);
                            let kr =
                                stage_b[j]
                                    .rates(ts, fluid, u, &ls, e.pin(ts))
                                    .map_err(|m| {
                                        body_err(format!("body '{}': {m}", e.body.name), ts)
                                    })?;
                            if si == 0 {
                                first_acc.push(stage_b[j].last_acc);
                            }
                            sums[j].add_scaled(&kr, w);
                            if !last {
                                let tn = t + next * dt;
                                stage_b[j] =
                                    body0[j].advanced(&kr, next * dt, e.pin(tn)).map_err(|m| {
                                        body_err(format!("body '{}': {m}", e.body.name), tn)
                                    })?;
                            }
                        }
                    }
                    // The step's end: the weighted sums.
                    let h = dt / div;
                    for (j, &ib) in unit.bodies.iter().enumerate() {
                        let e = &mut free.bodies[ib];
                        let mut nb =
                            body0[j].advanced(&sums[j], h, e.pin(t + dt)).map_err(|m| {
                                body_err(format!("body '{}': {m}", e.body.name), t + dt)
                            })?;
                        nb.last_acc = first_acc[j];
                        e.state = nb;
                    }
                    for s in &mut blks {
                        for li in 0..s.r0.len() {
                            let (rn, vn) = (s.r0[li] + s.sr[li] * h, s.v0[li] + s.sv[li] * h);
                            self.r[s.n0 + li] = rn;
                            self.v[s.n0 + li] = vn;
                            if let Some(what) = blow_up(&self.opts, rn, vn) {
                                return Err(Failed::Step(StepFailure::Diverged {
                                    node: s.n0 + li,
                                    time: t + dt,
                                    what,
                                }));
                            }
                        }
                        if !s.x0.is_empty() {
                            for (i, x) in self.visco[s.e0..s.e1].iter_mut().enumerate() {
                                *x = s.x0[i] + s.xsum[i] * h;
                            }
                        }
                    }
                    // The held nodes on their bodies' points at the step's end.
                    for &ib in &unit.bodies {
                        let e = &free.bodies[ib];
                        for (hd, p) in e.points() {
                            self.r[hd.node] = V::from_f64(p.r);
                            self.v[hd.node] = V::from_f64(p.v);
                            free.targets[hd.route] = Some(p);
                        }
                    }
                }
            }
            Ok(())
        })();
        res.map_err(|f| match f {
            Failed::Step(s) => self.name_failure(s),
            Failed::Body(e) => e,
        })
    }
}

/// Why a unit's step stopped.
enum Failed {
    Step(StepFailure),
    Body(Error),
}
