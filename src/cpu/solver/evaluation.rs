//! What a [`CpuSolver`] reports at an output time without stepping: the loads,
//! accelerations and reactions of the current state ([`CpuSolver::evaluate`]), and the
//! kinetic and strain energies (diagnostics of the energy tests).

use super::CpuSolver;
use crate::cpu::passes::{element_pass, node_accel, node_mass, Ctx, GeneralTopo};
use crate::cpu::water::node_water;
use crate::error::Error;
use crate::model::NO_CONSTRAINT;
use crate::options::{Formulation, SolverOptions};
use crate::physics::ElementLoads;
use crate::step::Evaluation;

impl CpuSolver {
    /// Evaluates loads, accelerations and reactions at the current state, with the
    /// water the next step starts from: each block's kinematics cache interpolated at
    /// the current time (refreshed first where that step would refresh it), or the
    /// exact sum in exact mode. So the loads reported are those the solver integrates,
    /// within the cache's tolerance of the exact sum, and outputs do not change the run.
    pub fn evaluate(&mut self) -> Result<Evaluation, Error> {
        self.evaluate_keeping(None)
    }

    /// [`Self::evaluate`], keeping the loads of the elements `picked` (ascending) only,
    /// or of every element (`None`): the outputs read a few elements' loads (the cables'
    /// end elements, the nets' twines), and a fleet's full copy would cost 104 bytes an
    /// element at every output time. Tensions are kept for every element.
    pub fn evaluate_keeping(&mut self, picked: Option<Vec<u32>>) -> Result<Evaluation, Error> {
        self.cover_waves_now();
        let ctx = self.ctx();
        let lay = &self.layout;
        // With picks: the accelerations of the picked elements' end nodes only, and no
        // node forces (the outputs read neither elsewhere).
        let picked_nodes: Vec<u32> = match &picked {
            Some(p) => {
                let mut n: Vec<u32> = p
                    .iter()
                    .flat_map(|&e| [lay.elem_a[e as usize], lay.elem_b[e as usize]])
                    .collect();
                n.sort_unstable();
                n.dedup();
                n
            }
            None => Vec::new(),
        };
        let full = picked.is_none();
        let mut ev = Evaluation {
            acc: vec![
                [0.0; 3];
                if full {
                    lay.n_nodes()
                } else {
                    picked_nodes.len()
                }
            ],
            force: vec![[0.0; 3]; if full { lay.n_nodes() } else { 0 }],
            tension: vec![0.0; lay.n_elements()],
            reaction: vec![[0.0; 3]; lay.routes.len()],
            elements: Vec::with_capacity(picked.as_ref().map_or(0, |p| p.len())),
            picked: None,
            picked_nodes: Vec::new(),
        };
        let mut next_node = 0;
        // One block's element loads at a time (every element's, without picks).
        let mut elems = vec![
            ElementLoads::default();
            if picked.is_some() {
                lay.blocks
                    .iter()
                    .map(|b| (b.elem_end - b.elem_start) as usize)
                    .max()
                    .unwrap_or(0)
            } else {
                lay.n_elements()
            }
        ];
        let mut next_pick = 0;
        for (bi, b) in lay.blocks.iter().enumerate() {
            let ale = self.ale_block(bi);
            let (n0, n1) = (b.node_start as usize, b.node_end as usize);
            let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
            let topo = GeneralTopo { lay, n0, e0 };
            let w = self.water_now(bi, n0, n1);
            // The block's loads sit at `base..` of `elems`.
            let base = if picked.is_some() { 0 } else { e0 };
            let elems = &mut elems[base..base + (e1 - e0)];
            element_pass(
                &ctx,
                &topo,
                b,
                ale,
                &self.r[n0..n1],
                &self.v[n0..n1],
                self.visco_block(e0, e1),
                self.t,
                &w,
                elems,
            )
            .map_err(|f| self.name_failure(f))?;
            let mut screen = Vec::new();
            if lay.block_has_screen(b) {
                crate::cpu::screen::screen_block_forces(
                    lay,
                    n0,
                    &self.r[n0..n1],
                    &self.v[n0..n1],
                    &w,
                    &mut screen,
                );
            }
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
                    elems,
                    &screen,
                );
                if full {
                    ev.acc[i] = a.to_f64();
                    ev.force[i] = f.to_f64();
                } else if picked_nodes.get(next_node) == Some(&(i as u32)) {
                    ev.acc[next_node] = a.to_f64();
                    next_node += 1;
                }
                let c = lay.node_constraint[i];
                if c != NO_CONSTRAINT {
                    ev.reaction[c as usize] = (f - m.mul_vec(a)).to_f64();
                }
            }
            for (k, el) in elems.iter().enumerate() {
                ev.tension[e0 + k] = el.tension;
            }
            if let Some(p) = &picked {
                while next_pick < p.len() && (p[next_pick] as usize) < e1 {
                    ev.elements.push(elems[p[next_pick] as usize - e0]);
                    next_pick += 1;
                }
            }
        }
        match picked {
            Some(p) => {
                ev.picked = Some(p);
                ev.picked_nodes = picked_nodes;
            }
            None => ev.elements = elems,
        }
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
            let w = self.water_exact_now(n0, n1);
            let _ = element_pass(
                &ctx,
                &topo,
                b,
                ale,
                &self.r[n0..n1],
                &self.v[n0..n1],
                self.visco_block(e0, e1),
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

    /// Elastic strain energy `sum 1/2 EA l0 eps^2` over stretched elements (a tabulated
    /// line's `l0 int T deps`), and the bending energy `k phi^2 / 2` of the bending
    /// hinges, J.
    pub fn strain_energy(&self) -> f64 {
        let lay = &self.layout;
        let l0s = self.element_l0();
        let tangent = |e: u32, dir: [f64; 3]| {
            if e == crate::model::NO_ELEM {
                crate::math::V3::<f64>::from_f64(dir)
            } else {
                let e = e as usize;
                let d = self.r[lay.elem_b[e] as usize] - self.r[lay.elem_a[e] as usize];
                d / d.norm()
            }
        };
        let bending: f64 = self
            .hinges
            .iter()
            .map(|h| {
                crate::physics::bending_energy(tangent(h.prev, h.dir), tangent(h.next, h.dir), h.k)
            })
            .sum();
        bending
            + (0..lay.n_elements())
                .map(|e| {
                    let l =
                        (self.r[lay.elem_b[e] as usize] - self.r[lay.elem_a[e] as usize]).norm();
                    let l0 = l0s[e];
                    let c = &self.coefs[lay.elem_line[e] as usize];
                    let eps = l / l0 - 1.0;
                    let line = &lay.line_types[lay.elem_line[e] as usize];
                    if let Some(rows) = line.ea_curve.as_deref() {
                        // The curve's work from zero strain.
                        l0 * crate::physics::tabulated_work(rows, 0.0, eps)
                    } else if eps > 0.0 || c.compression > 0.0 {
                        0.5 * c.ea * l0 * eps * eps
                    } else {
                        0.0
                    }
                })
                .sum::<f64>()
    }
}
