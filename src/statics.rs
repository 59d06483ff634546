//! Static equilibrium of the discrete model (docs/src/model/initial.md).
//!
//! A catenary or straight first guess is not an equilibrium of the lumped-mass chain;
//! [`relax`] moves the free nodes until the force the dynamic model computes on each of
//! them *at rest* vanishes, so that a line whose ends hold still stays still when the
//! solver starts.
//!
//! # The static force
//! The residual on a free node is exactly the force of the CPU stepper with every
//! velocity zero and `t = 0`, built from the same physics functions:
//! [`glmf_element_wet`] with zero node velocities (elastic axial force with the slack
//! rule, no internal damping since the strain rate is zero; half the element's weight
//! less the buoyancy of its share under the mean water level `z = 0`; normal and
//! tangential drag of the current at the element's midpoint on that share; no water
//! acceleration), the point mass's weight less the buoyancy of its share under water
//! and its drag in the current at the node on that share (docs/src/water_surface.md: a line
//! hung above the water starts from its true equilibrium, in air), and [`seabed_force`] with zero velocity (the elastic normal force; the
//! damping and the regularised friction vanish at rest). Nodes held by a route are
//! placed at `route.eval(0.0).r` and are not unknowns. Only the GLMF loads are used:
//! at rest in still water the older element frames are singular or equal to them.
//!
//! # The solver
//! Blocks (connected components, `Layout::blocks`) are independent and are solved in
//! parallel. Each is solved by Newton's method on the free nodes' positions:
//! * the stiffness `K = -dF/dr` is assembled from central finite differences of each
//!   element's static force with respect to its two end nodes (a 6x6 matrix per
//!   element, step `1e-6` of the element length) and of each node's own loads (point
//!   drag, seabed contact, near the seabed): general, drag and current profiles
//!   included. A slack element has no stiffness, so Newton's model would let a step
//!   stretch it without bound: it gets its taut axial stiffness `EA/l0 t t^T` in `K`
//!   (the Jacobian only; the residual, hence the solution, is unchanged);
//! * a chain block (`Block::is_chain`) gives a block-tridiagonal `K` (3x3 blocks),
//!   solved by the block Thomas algorithm in O(n); another block with at most
//!   [`RelaxOptions::max_dense_dof`] free coordinates is solved by a dense LU with
//!   partial pivoting (nalgebra); larger non-chain blocks use dynamic relaxation;
//! * globalisation: Levenberg-Marquardt, `(K + mu I) dr = F` with `mu = lambda k_ref`
//!   (`k_ref` the largest diagonal stiffness), which also regularises the singular
//!   directions (a slack line on a frictionless seabed). A step, capped at
//!   [`RelaxOptions::max_step`] mean element lengths per node, is accepted when the
//!   potential energy falls by at least `1e-4` of the decrease the quadratic model
//!   predicts, and `lambda` follows Nielsen's gain-ratio rule. The energy is the
//!   strain energy `1/2 EA l0 eps^2` of stretched elements, the seabed energy
//!   `1/2 K lt p^2`, and the work of the external loads (weights; drag frozen over a
//!   step). Without current it is convex in the node positions (a convex function of
//!   each element's length, which is convex in its end positions), so every accepted
//!   step is progress, whatever the active set of slack elements and contacts. Energy
//!   differences are formed from the step itself, accurate down to the round-off
//!   floor of the residual. Where drag makes the step no descent direction of the
//!   energy, a lower residual norm is accepted instead;
//! * a poor first guess (a straight, slack line; a flat net): when Newton has not
//!   converged after [`RelaxOptions::newton_first_pass`] iterations, it restarts from
//!   the first guess with every axial stiffness and the seabed stiffness scaled down
//!   so that the weight stretches the lines by about 20 % (slack and overstretch then
//!   cost little), and stiffens tenfold per stage, each stage starting from the last
//!   one's equilibrium, up to the true stiffness. Should that still fail, dynamic
//!   relaxation brings the block to [`RelaxOptions::dr_handoff`] of its load scale and
//!   Newton polishes it;
//! * dynamic relaxation: pseudo-dynamics with unit time step, fictitious masses from a
//!   Gershgorin bound of the stiffness (axial, geometric, and seabed where contact is
//!   near), so the explicit update is stable, and kinetic damping (velocities reset
//!   at each peak of the kinetic energy).
//!
//! # Convergence criterion
//! A block has converged when the largest residual force on any of its free nodes
//! (Euclidean norm, N) is at most
//! `max(rel_tol * load_scale, abs_tol, 8 eps r_max k_max)` where `load_scale` is the sum
//! of the magnitudes of the block's external loads at the first guess (element wet
//! weights and drag, point weights and drag: for a line in still water, its total wet
//! weight), `rel_tol = 1e-9` and `abs_tol = 1e-6 N` by default; the last term is the
//! round-off floor, `eps` the machine epsilon, `r_max` the largest coordinate magnitude
//! and `k_max` the largest element stiffness `EA/l0` or seabed stiffness `K lt` of the
//! block: a force below it cannot be resolved in f64 positions.

use crate::error::Error;
use crate::math::V3;
use crate::model::{Block, Layout, NO_CONSTRAINT};
use crate::physics::{
    glmf_element_wet, point_wetted_fraction, seabed_force, wetted_fraction, Coefs, ElementInput,
    SeabedCoefs,
};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use rayon::prelude::*;
use std::borrow::Cow;

type V = V3<f64>;
type M3 = Matrix3<f64>;

/// Options of [`relax`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelaxOptions {
    /// Newton iterations per solve at most (after the first pass, each stage of the
    /// stiffness continuation and the final polish may use as many).
    pub max_iterations: usize,
    /// Tolerance relative to the block's load scale (see the module doc).
    pub rel_tol: f64,
    /// Absolute tolerance floor, N.
    pub abs_tol: f64,
    /// Non-chain blocks with more free coordinates than this use dynamic relaxation
    /// instead of a dense Newton solve.
    pub max_dense_dof: usize,
    /// Largest displacement of any node in one Newton step, in mean element lengths of
    /// the block.
    pub max_step: f64,
    /// Newton iterations tried before falling back to dynamic relaxation (for chain and
    /// dense blocks); Newton then resumes from where dynamic relaxation stopped.
    pub newton_first_pass: usize,
    /// Residual, relative to the block's load scale, at which dynamic relaxation hands
    /// a chain or dense block back to Newton.
    pub dr_handoff: f64,
    /// Dynamic-relaxation iterations per block at most.
    pub dr_max_iterations: usize,
    /// Solve every block by dynamic relaxation alone (for comparisons and tests).
    pub force_dynamic_relaxation: bool,
    /// When true, a block that does not reach the tolerance makes [`relax`] fail (the
    /// positions are still left at the best state found); when false its report says
    /// `converged: false` and [`relax`] succeeds.
    pub require_convergence: bool,
}

impl Default for RelaxOptions {
    fn default() -> Self {
        Self {
            max_iterations: 200,
            rel_tol: 1e-9,
            abs_tol: 1e-6,
            max_dense_dof: 2000,
            max_step: 0.5,
            newton_first_pass: 30,
            dr_handoff: 1e-3,
            dr_max_iterations: 500_000,
            force_dynamic_relaxation: false,
            require_convergence: true,
        }
    }
}

/// How a block was solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Nothing to solve: every node is held by a route.
    Fixed,
    /// Newton's method with the block-tridiagonal (Thomas) solve of a chain.
    Chain,
    /// Newton's method with a dense LU.
    Dense,
    /// Dynamic relaxation with kinetic damping.
    DynamicRelaxation,
}

/// The outcome of one block.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockReport {
    /// Index into `Layout::blocks`.
    pub block: usize,
    /// Solver used.
    pub method: Method,
    /// Number of free (not route-held) nodes.
    pub free_nodes: usize,
    /// Newton iterations done.
    pub iterations: usize,
    /// Dynamic-relaxation iterations done.
    pub dr_iterations: usize,
    /// Largest residual force on a free node at the end, N.
    pub max_residual: f64,
    /// The tolerance the block was held to, N.
    pub tolerance: f64,
    /// Whether `max_residual <= tolerance`.
    pub converged: bool,
    /// Packed index of the node with the largest residual (none without free nodes).
    pub worst_node: Option<usize>,
}

/// The outcome of [`relax`].
#[derive(Clone, Debug, PartialEq)]
pub struct RelaxReport {
    /// One entry per block, in block order.
    pub blocks: Vec<BlockReport>,
    /// Largest residual force over all blocks, N.
    pub max_residual: f64,
    /// Most Newton iterations any block needed.
    pub iterations: usize,
    /// Most dynamic-relaxation iterations any block needed.
    pub dr_iterations: usize,
    /// Whether every block converged.
    pub converged: bool,
}

/// Moves the free nodes of every block to the static equilibrium of the discrete
/// model (see the module doc); route-held nodes are set to `route.eval(0.0).r`.
/// `positions` is in packed node order and is updated in place.
///
/// Errors: `positions` of the wrong length, a non-finite force, or (when
/// `opts.require_convergence`) a block that did not converge, naming its worst node's
/// cable and index, the residual and the tolerance.
pub fn relax(
    layout: &Layout,
    positions: &mut [[f64; 3]],
    opts: &RelaxOptions,
) -> Result<RelaxReport, Error> {
    relax_blocks(layout, positions, opts, &vec![true; layout.blocks.len()])
}

/// [`relax`] for the blocks where `which[block]` is true; the others keep their
/// positions (route-held nodes are still put at their t = 0 places) and are not reported.
pub fn relax_blocks(
    layout: &Layout,
    positions: &mut [[f64; 3]],
    opts: &RelaxOptions,
    which: &[bool],
) -> Result<RelaxReport, Error> {
    if positions.len() != layout.n_nodes() {
        return Err(Error::Statics(format!(
            "{} positions for {} nodes",
            positions.len(),
            layout.n_nodes()
        )));
    }
    for (c, &n) in layout.constraint_node.iter().enumerate() {
        positions[n as usize] = layout.routes[c].eval(0.0).r;
    }
    let coefs: Vec<Coefs<f64>> = layout.line_coefs.iter().map(Coefs::from_line).collect();
    let seabed = seabed_coefs(layout);
    // Disjoint per-block slices (blocks are contiguous, in node order).
    let mut parts = Vec::with_capacity(layout.blocks.len());
    let mut rest = &mut positions[..];
    let mut at = 0usize;
    for (bi, b) in layout.blocks.iter().enumerate() {
        let (n0, n1) = (b.node_start as usize, b.node_end as usize);
        let (_, tail) = rest.split_at_mut(n0 - at);
        let (mine, tail) = tail.split_at_mut(n1 - n0);
        if which.get(bi).copied().unwrap_or(false) {
            parts.push((bi, *b, mine));
        }
        rest = tail;
        at = n1;
    }
    let reports: Vec<Result<BlockReport, Error>> = parts
        .into_par_iter()
        .map(|(bi, b, pos)| {
            let sys = Sys::new(layout, &coefs, seabed, b);
            sys.solve(bi, pos, opts)
        })
        .collect();
    let mut blocks = Vec::with_capacity(reports.len());
    for r in reports {
        blocks.push(r?);
    }
    let report = RelaxReport {
        max_residual: blocks.iter().map(|b| b.max_residual).fold(0.0, f64::max),
        iterations: blocks.iter().map(|b| b.iterations).max().unwrap_or(0),
        dr_iterations: blocks.iter().map(|b| b.dr_iterations).max().unwrap_or(0),
        converged: blocks.iter().all(|b| b.converged),
        blocks,
    };
    if opts.require_convergence {
        if let Some(b) = report.blocks.iter().find(|b| !b.converged) {
            let place = match b.worst_node {
                Some(n) => {
                    let (cable, k) = layout.describe_node(n);
                    format!("cable '{cable}', node {k}")
                }
                None => "no free node".into(),
            };
            return Err(Error::Statics(format!(
                "block {} ({:?}) did not converge after {} iterations: residual {:.3e} N at {place} exceeds the tolerance {:.3e} N",
                b.block, b.method, b.iterations, b.max_residual, b.tolerance
            )));
        }
    }
    Ok(report)
}

/// The static force (every velocity zero, `t = 0`) on every node, N, in packed order:
/// the residual that [`relax`] drives to zero on free nodes. On a route-held node it is
/// the force the cable exerts on its support at rest (the reaction `F_k - M_k a_k` of
/// a node at rest on a fixed route, docs/src/model/constraints.md, "End forces").
pub fn static_forces(layout: &Layout, positions: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let coefs: Vec<Coefs<f64>> = layout.line_coefs.iter().map(Coefs::from_line).collect();
    let seabed = seabed_coefs(layout);
    let mut out = vec![[0.0; 3]; layout.n_nodes()];
    for b in &layout.blocks {
        let sys = Sys::new(layout, &coefs, seabed, *b);
        let (n0, n1) = (b.node_start as usize, b.node_end as usize);
        let r: Vec<V> = positions[n0..n1].iter().map(|p| V::from_f64(*p)).collect();
        let mut f = vec![V::zero(); r.len()];
        sys.residual(&r, &mut f);
        for (o, fi) in out[n0..n1].iter_mut().zip(&f) {
            *o = fi.to_f64();
        }
    }
    out
}

fn seabed_coefs(layout: &Layout) -> SeabedCoefs<f64> {
    let e = &layout.env;
    SeabedCoefs {
        z: -e.depth,
        k: e.seabed.stiffness,
        c: e.seabed.damping,
        mu: e.seabed.friction,
        v_eps: e.seabed.friction_velocity,
    }
}

/// One block's static problem.
struct Sys<'a> {
    lay: &'a Layout,
    coefs: Cow<'a, [Coefs<f64>]>,
    seabed: SeabedCoefs<f64>,
    block: Block,
    n0: usize,
    nn: usize,
    e0: usize,
    e1: usize,
    /// Per block-local node: not held by a route.
    free: Vec<bool>,
}

impl<'a> Sys<'a> {
    fn new(
        lay: &'a Layout,
        coefs: &'a [Coefs<f64>],
        seabed: SeabedCoefs<f64>,
        block: Block,
    ) -> Self {
        let (n0, n1) = (block.node_start as usize, block.node_end as usize);
        Self {
            lay,
            coefs: Cow::Borrowed(coefs),
            seabed,
            block,
            n0,
            nn: n1 - n0,
            e0: block.elem_start as usize,
            e1: block.elem_end as usize,
            free: (n0..n1)
                .map(|i| lay.node_constraint[i] == NO_CONSTRAINT)
                .collect(),
        }
    }

    /// The same block with every axial stiffness and the seabed stiffness scaled by `s`
    /// (continuation).
    fn softened(&self, s: f64) -> Sys<'a> {
        let coefs = self
            .coefs
            .iter()
            .map(|c| Coefs {
                ea: c.ea * s,
                ea_c: c.ea_c * s,
                ..*c
            })
            .collect::<Vec<_>>();
        Sys {
            lay: self.lay,
            coefs: Cow::Owned(coefs),
            seabed: SeabedCoefs {
                k: self.seabed.k * s,
                ..self.seabed
            },
            block: self.block,
            n0: self.n0,
            nn: self.nn,
            e0: self.e0,
            e1: self.e1,
            free: self.free.clone(),
        }
    }

    /// Block-local end nodes of packed element `e`.
    #[inline]
    fn ends(&self, e: usize) -> (usize, usize) {
        (
            self.lay.elem_a[e] as usize - self.n0,
            self.lay.elem_b[e] as usize - self.n0,
        )
    }

    /// Static forces of packed element `e` on its nodes a and b.
    #[inline]
    fn element(&self, e: usize, ra: V, rb: V) -> (V, V) {
        let lay = self.lay;
        let current = lay.currents[lay.elem_current[e] as usize].at(0.5 * (ra.z + rb.z));
        let input = ElementInput {
            ra,
            rb,
            va: V::zero(),
            vb: V::zero(),
            l0: lay.elem_l0[e],
            current,
            water_accel: V::zero(),
        };
        // Still water at the mean level: the part above z = 0 is in air.
        let line = lay.elem_line[e] as usize;
        let wet = wetted_fraction(-ra.z, -rb.z, lay.line_types[line].diameter);
        let c = &self.coefs[line];
        let el = glmf_element_wet(c, &input, wet, lay.env.gravity);
        (el.f_half + el.t * el.tension, el.f_half - el.t * el.tension)
    }

    /// The point loads of packed node `i`: weight less the buoyancy of the share of
    /// the point under the mean water level, drag in the current on that share.
    #[inline]
    fn point(&self, i: usize, r: V) -> V {
        let lay = self.lay;
        let wet = point_wetted_fraction(-r.z, lay.node_point_radius[i]);
        let buoyancy = lay.node_point_displaced[i] * lay.env.gravity;
        let mut f = V::new(
            0.0,
            0.0,
            lay.node_point_weight_z[i] - (1.0 - wet) * buoyancy,
        );
        let pd = lay.node_point_drag[i];
        if pd > 0.0 {
            let u = lay.currents[lay.node_current[i] as usize].at(r.z);
            f += u * (pd * u.norm() * wet);
        }
        f
    }

    /// Static loads of packed node `i`'s own: point loads and seabed contact.
    #[inline]
    fn node(&self, i: usize, r: V) -> V {
        self.point(i, r) + seabed_force(&self.seabed, self.lay.node_tributary[i], r, V::zero())
    }

    /// The external loads at `r` that [`Self::energy_change`] holds fixed over a step:
    /// per element (in element order) its weight and drag, per node its point loads.
    fn frozen_loads(&self, r: &[V]) -> (Vec<V>, Vec<V>) {
        let ext = (self.e0..self.e1)
            .map(|e| {
                let (a, b) = self.ends(e);
                let (fa, fb) = self.element(e, r[a], r[b]);
                fa + fb // the tension cancels
            })
            .collect();
        let own = (0..self.nn)
            .map(|li| self.point(self.n0 + li, r[li]))
            .collect();
        (ext, own)
    }

    /// Change of the potential energy from `r` to `r + dx` (`dx` zero on held nodes):
    /// elastic strain energy `1/2 EA l0 eps^2` (stretched elements, or all for a rod),
    /// seabed energy `1/2 K lt p^2` (`p` the penetration), and the work of the external
    /// loads `ext`, `own` held at their values at `r` (weights are constant; drag
    /// depends on the shape and is frozen over one step, so this is exact without
    /// current). Every difference is formed from `dx` itself rather than by subtracting
    /// two energies, so it stays accurate as the step shrinks near convergence.
    fn energy_change(&self, r: &[V], dx: &[V], ext: &[V], own: &[V]) -> f64 {
        let lay = self.lay;
        let mut de = 0.0;
        for e in self.e0..self.e1 {
            let (a, b) = self.ends(e);
            let c = &self.coefs[lay.elem_line[e] as usize];
            let l0 = lay.elem_l0[e];
            let d0 = r[b] - r[a];
            let dd = dx[b] - dx[a];
            let d1 = d0 + dd;
            let (la, lb) = (d0.norm(), d1.norm());
            // lb - la = (lb^2 - la^2) / (la + lb), lb^2 - la^2 = dd . (d0 + d1).
            let dl = dd.dot(d0 + d1) / (la + lb);
            let (ea, eb) = (la / l0 - 1.0, lb / l0 - 1.0);
            let rod = c.compression > 0.0;
            let (pa, pb) = if rod {
                (ea, eb)
            } else {
                (ea.max(0.0), eb.max(0.0))
            };
            let dp = if rod || (ea > 0.0 && eb > 0.0) {
                dl / l0
            } else {
                pb - pa
            };
            de += 0.5 * c.ea * l0 * dp * (pa + pb);
            de -= ext[e - self.e0].dot((dx[a] + dx[b]) * 0.5);
        }
        for li in 0..self.nn {
            if !self.free[li] {
                continue;
            }
            de -= own[li].dot(dx[li]);
            let (za, zb) = (r[li].z, r[li].z + dx[li].z);
            let (pa, pb) = ((self.seabed.z - za).max(0.0), (self.seabed.z - zb).max(0.0));
            if pa > 0.0 || pb > 0.0 {
                let dp = if pa > 0.0 && pb > 0.0 {
                    -dx[li].z
                } else {
                    pb - pa
                };
                let k = self.seabed.k * lay.node_tributary[self.n0 + li];
                de += 0.5 * k * dp * (pa + pb);
            }
        }
        de
    }

    /// Static force on every node of the block (block-local `r` and `f`).
    fn residual(&self, r: &[V], f: &mut [V]) {
        for (li, fi) in f.iter_mut().enumerate() {
            *fi = self.node(self.n0 + li, r[li]);
        }
        for e in self.e0..self.e1 {
            let (a, b) = self.ends(e);
            let (fa, fb) = self.element(e, r[a], r[b]);
            f[a] += fa;
            f[b] += fb;
        }
    }

    /// Largest free-node force magnitude and its block-local node, and the sum of
    /// squares over free nodes.
    fn measure(&self, f: &[V]) -> (f64, Option<usize>, f64) {
        let (mut fmax, mut worst, mut sum) = (0.0f64, None, 0.0);
        for (li, fi) in f.iter().enumerate() {
            if !self.free[li] {
                continue;
            }
            let n2 = fi.norm2();
            // Written so that NaN propagates into the result.
            if n2.is_nan() || n2.sqrt() > fmax {
                fmax = n2.sqrt();
                worst = Some(li);
            }
            sum += n2;
        }
        (fmax, worst, sum)
    }

    /// Sum of the magnitudes of the external loads at `r`, and the largest stiffness.
    fn scales(&self, r: &[V]) -> (f64, f64) {
        let lay = self.lay;
        let mut load = 0.0;
        let mut kmax = 0.0f64;
        for (li, ri) in r.iter().enumerate() {
            let i = self.n0 + li;
            load += self.point(i, *ri).norm();
            kmax = kmax.max(self.seabed.k * lay.node_tributary[i]);
        }
        for e in self.e0..self.e1 {
            let (a, b) = self.ends(e);
            let (fa, fb) = self.element(e, r[a], r[b]);
            // The tension cancels in the sum: what is left is the external load.
            load += (fa + fb).norm();
            let c = &self.coefs[lay.elem_line[e] as usize];
            kmax = kmax.max(c.ea / lay.elem_l0[e]);
        }
        (load, kmax)
    }

    /// Stiffness `K = -dF/dr` by central differences, handed out as 3x3 blocks
    /// `(row node, column node, block)` in block-local indices.
    fn stiffness(&self, r: &[V], mut add: impl FnMut(usize, usize, &M3)) {
        let vec3 = |v: V| Vector3::new(v.x, v.y, v.z);
        for e in self.e0..self.e1 {
            let (a, b) = self.ends(e);
            let (ra, rb) = (r[a], r[b]);
            let h = 1e-6 * (rb - ra).norm().max(self.lay.elem_l0[e]);
            // Columns of dF/dr: F = (f_a, f_b), r = (r_a, r_b).
            let mut kk = [[M3::zeros(); 2]; 2]; // kk[row node][column node]
            for k in 0..6 {
                let (mut p, mut m) = ([ra, rb], [ra, rb]);
                let x = *comp(&mut p[k / 3], k % 3);
                let (xp, xm) = (x + h, x - h);
                *comp(&mut p[k / 3], k % 3) = xp;
                *comp(&mut m[k / 3], k % 3) = xm;
                let (fap, fbp) = self.element(e, p[0], p[1]);
                let (fam, fbm) = self.element(e, m[0], m[1]);
                let inv = -1.0 / (xp - xm);
                kk[0][k / 3].set_column(k % 3, &(vec3(fap - fam) * inv));
                kk[1][k / 3].set_column(k % 3, &(vec3(fbp - fbm) * inv));
            }
            // A slack element has no stiffness, and Newton's model would let the step
            // stretch it without limit: give it its taut axial stiffness in the
            // Jacobian only (the residual, hence the solution, is unchanged).
            let c = &self.coefs[self.lay.elem_line[e] as usize];
            let d = rb - ra;
            let l = d.norm();
            let l0 = self.lay.elem_l0[e];
            if c.compression == 0.0 && l < l0 && l > 0.0 {
                let t = vec3(d / l);
                let ks = t * t.transpose() * (c.ea / l0);
                kk[0][0] += ks;
                kk[1][1] += ks;
                kk[0][1] -= ks;
                kk[1][0] -= ks;
            }
            add(a, a, &kk[0][0]);
            add(a, b, &kk[0][1]);
            add(b, a, &kk[1][0]);
            add(b, b, &kk[1][1]);
        }
        for (li, &ri) in r.iter().enumerate() {
            if !self.free[li] {
                continue;
            }
            let i = self.n0 + li;
            let lay = self.lay;
            // Only the seabed, a current profile and the water surface (a point mass
            // crossing it) make a node's own loads vary.
            let near_seabed = ri.z < self.seabed.z + 1.0;
            let profile = lay.node_point_drag[i] > 0.0
                && lay.currents[lay.node_current[i] as usize].table.len() > 1;
            let has_point = lay.node_point_displaced[i] > 0.0 || lay.node_point_drag[i] > 0.0;
            let near_surface = has_point && ri.z.abs() < lay.node_point_radius[i] + 1.0;
            if !(near_seabed || profile || near_surface) {
                continue;
            }
            let h = 1e-6 * lay.node_tributary[i].max(1e-3);
            let mut kn = M3::zeros();
            for k in 0..3 {
                let (mut p, mut m) = (ri, ri);
                let x = *comp(&mut p, k);
                let (xp, xm) = (x + h, x - h);
                *comp(&mut p, k) = xp;
                *comp(&mut m, k) = xm;
                let df = self.node(i, p) - self.node(i, m);
                kn.set_column(k, &(vec3(df) * (-1.0 / (xp - xm))));
            }
            add(li, li, &kn);
        }
    }

    /// True when some node at `r` (block-local) is close enough to the mean water
    /// level for the surface to change a load: within a diameter of its lines or the
    /// radius of its point mass below it, or above it.
    fn near_surface(&self, r: &[V]) -> bool {
        let lay = self.lay;
        let band = (self.e0..self.e1)
            .map(|e| lay.line_types[lay.elem_line[e] as usize].diameter)
            .fold(0.0f64, f64::max);
        r.iter()
            .enumerate()
            .any(|(li, p)| p.z > -band.max(lay.node_point_radius[self.n0 + li]) - 1e-9)
    }

    /// Mean unstretched element length (1 m without elements).
    fn mean_l0(&self) -> f64 {
        if self.e1 > self.e0 {
            self.lay.elem_l0[self.e0..self.e1].iter().sum::<f64>() / (self.e1 - self.e0) as f64
        } else {
            1.0
        }
    }

    /// Solves the block in place (`pos` block-local).
    fn solve(
        &self,
        bi: usize,
        pos: &mut [[f64; 3]],
        opts: &RelaxOptions,
    ) -> Result<BlockReport, Error> {
        let mut r: Vec<V> = pos.iter().map(|p| V::from_f64(*p)).collect();
        let n_free = self.free.iter().filter(|&&f| f).count();
        let (load, kmax) = self.scales(&r);
        let rmax = r.iter().map(|p| p.max_abs()).fold(0.0, f64::max);
        let tol = (opts.rel_tol * load)
            .max(opts.abs_tol)
            .max(8.0 * f64::EPSILON * rmax * kmax);
        let method = if n_free == 0 {
            Method::Fixed
        } else if opts.force_dynamic_relaxation {
            Method::DynamicRelaxation
        } else if self.block.is_chain {
            Method::Chain
        } else if 3 * n_free <= opts.max_dense_dof {
            Method::Dense
        } else {
            Method::DynamicRelaxation
        };
        let (mut iterations, mut dr_iterations) = (0, 0);
        match method {
            Method::Fixed => {}
            Method::Chain | Method::Dense => {
                let guess = r.clone();
                let first = opts.max_iterations.min(opts.newton_first_pass);
                let (its, mut fmax) = self.newton(&mut r, method, tol, kmax, first, opts);
                iterations = its;
                if fmax > tol {
                    // A poor first guess (slack lines): continuation in the axial
                    // stiffness from the first guess. Soft enough that the weight
                    // stretches the lines by some 20 %, slack and overstretch cost little
                    // and Newton finds the sagged shape; then ten times stiffer per
                    // stage, each stage starting from the last one's equilibrium.
                    r.copy_from_slice(&guess);
                    let ea_max = self.coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
                    let mut s = (load / (0.2 * ea_max)).min(1.0);
                    loop {
                        let (its, fm) = if s >= 1.0 {
                            self.newton(&mut r, method, tol, kmax, opts.max_iterations, opts)
                        } else {
                            let soft = self.softened(s);
                            let stage_tol = (1e-6 * load).max(tol);
                            soft.newton(
                                &mut r,
                                method,
                                stage_tol,
                                kmax * s,
                                opts.max_iterations,
                                opts,
                            )
                        };
                        iterations += its;
                        fmax = fm;
                        log::debug!(
                            "relax block {bi}: stiffness x {s:.3e}, {its} Newton iterations, residual {fm:.3e} N"
                        );
                        if s >= 1.0 {
                            break;
                        }
                        s = (s * 10.0).min(1.0);
                    }
                }
                if fmax > tol {
                    // Far from equilibrium (slack lines, contact changing): let dynamic
                    // relaxation bring the block close, then polish with Newton.
                    let handoff = (opts.dr_handoff * load).max(tol);
                    dr_iterations = self.dynamic_relaxation(&mut r, handoff, opts);
                    log::debug!("relax block {bi}: dynamic relaxation, {dr_iterations} iterations");
                    let (its, _) =
                        self.newton(&mut r, method, tol, kmax, opts.max_iterations, opts);
                    iterations += its;
                }
            }
            Method::DynamicRelaxation => {
                dr_iterations = self.dynamic_relaxation(&mut r, tol, opts);
            }
        }
        let mut f = vec![V::zero(); self.nn];
        self.residual(&r, &mut f);
        let (fmax, worst, _) = self.measure(&f);
        if !fmax.is_finite() {
            let (cable, k) = self.lay.describe_node(self.n0 + worst.unwrap_or_default());
            return Err(Error::Statics(format!(
                "non-finite static force at cable '{cable}', node {k} (a zero-length element?)"
            )));
        }
        for (p, ri) in pos.iter_mut().zip(&r) {
            *p = ri.to_f64();
        }
        Ok(BlockReport {
            block: bi,
            method,
            free_nodes: n_free,
            iterations,
            dr_iterations,
            max_residual: fmax,
            tolerance: tol,
            converged: fmax <= tol,
            worst_node: worst.map(|w| self.n0 + w),
        })
    }

    /// Newton's method with a Levenberg-Marquardt shift (module doc). Returns the
    /// iterations done and the final largest residual.
    fn newton(
        &self,
        r: &mut [V],
        method: Method,
        tol: f64,
        kmax: f64,
        max_iterations: usize,
        opts: &RelaxOptions,
    ) -> (usize, f64) {
        let nn = self.nn;
        let max_len = opts.max_step * self.mean_l0();
        let mut lin = match method {
            Method::Chain => Lin::chain(nn),
            _ => Lin::dense(&self.free),
        };
        let mut f = vec![V::zero(); nn];
        let mut ft = vec![V::zero(); nn];
        let mut trial = r.to_vec();
        self.residual(r, &mut f);
        let (mut fmax, _, mut merit) = self.measure(&f);
        // Shift relative to the stiffness scale, and its growth factor (Nielsen).
        let mut lambda: f64 = 1e-9;
        let mut nu = 2.0;
        const LAMBDA_MIN: f64 = 1e-12;
        for it in 0..max_iterations {
            if fmax <= tol {
                return (it, fmax);
            }
            lin.clear();
            self.stiffness(r, |i, j, m| {
                if self.free[i] && self.free[j] {
                    lin.add(i, j, m)
                }
            });
            // Slack lines have no stiffness at all: then the block's largest element
            // or seabed stiffness sets the scale of the shift.
            let kref = lin
                .diag_max(&self.free)
                .max(1e-3 * kmax)
                .max(f64::MIN_POSITIVE);
            let (ext, own) = self.frozen_loads(r);
            let mut accepted = false;
            for _attempt in 0..60 {
                let Some(mut dx) = lin.solve(lambda * kref, &f, &self.free) else {
                    lambda *= nu;
                    nu *= 2.0;
                    continue;
                };
                let big = dx.iter().map(|d| d.norm()).fold(0.0, f64::max);
                if big > max_len {
                    let s = max_len / big;
                    dx.iter_mut().for_each(|d| *d = *d * s);
                }
                // Decrease of the potential energy predicted by the quadratic model
                // (K and the frozen loads), and the actual one.
                let g0 = self.work(&f, &dx);
                let kd = lin.mul(&dx, &self.free);
                let pred = g0 - 0.5 * self.work(&kd, &dx);
                for li in 0..nn {
                    trial[li] = r[li] + dx[li];
                }
                self.residual(&trial, &mut ft);
                let (tmax, _, tmerit) = self.measure(&ft);
                let ok = if pred > 0.0 && g0 > 0.0 {
                    // The external loads averaged over the step's two ends (trapezoid):
                    // the buoyancy of what crosses the water surface changes along the
                    // step, and its work must be counted to second order like the
                    // elastic energy's, or steps near the surface are wrongly refused.
                    // Blocks wholly under water keep the loads at `r`.
                    let rho = if self.near_surface(r) || self.near_surface(&trial) {
                        let (ext1, own1) = self.frozen_loads(&trial);
                        let avg = |a: &[V], b: &[V]| -> Vec<V> {
                            a.iter().zip(b).map(|(x, y)| (*x + *y) * 0.5).collect()
                        };
                        let (ext_m, own_m) = (avg(&ext, &ext1), avg(&own, &own1));
                        -self.energy_change(r, &dx, &ext_m, &own_m) / pred
                    } else {
                        -self.energy_change(r, &dx, &ext, &own) / pred
                    };
                    if rho > 1e-4 {
                        lambda *= (1.0 / 3.0f64).max(1.0 - (2.0 * rho - 1.0).powi(3));
                        lambda = lambda.max(LAMBDA_MIN);
                        nu = 2.0;
                        true
                    } else {
                        false
                    }
                } else {
                    // Not a descent direction of the energy (drag): a lower residual.
                    tmerit < merit
                };
                if ok && tmax.is_finite() {
                    r.copy_from_slice(&trial);
                    std::mem::swap(&mut f, &mut ft);
                    fmax = tmax;
                    merit = tmerit;
                    accepted = true;
                    break;
                }
                lambda *= nu;
                nu *= 2.0;
            }
            log::trace!("relax: iteration {it}, residual {fmax:.3e} N, lambda {lambda:.1e}");
            if !accepted {
                return (it, fmax); // stalled: no step lowers the energy (or the residual)
            }
        }
        (max_iterations, fmax)
    }

    /// `sum_free f_i . dx_i`.
    fn work(&self, f: &[V], dx: &[V]) -> f64 {
        f.iter()
            .zip(dx)
            .zip(&self.free)
            .filter(|(_, &fr)| fr)
            .map(|((fi, di), _)| fi.dot(*di))
            .sum()
    }

    /// Dynamic relaxation: pseudo-dynamics `m_i a_i = F_i` with unit time step,
    /// fictitious masses from the Gershgorin bound of the stiffness (so the explicit
    /// scheme is stable), and kinetic damping (velocities reset at each peak of the
    /// kinetic energy). Returns the iterations done.
    fn dynamic_relaxation(&self, r: &mut [V], tol: f64, opts: &RelaxOptions) -> usize {
        let nn = self.nn;
        let lay = self.lay;
        let mut v = vec![V::zero(); nn];
        let mut m = vec![0.0; nn];
        let mut f = vec![V::zero(); nn];
        let near = 0.5 * self.mean_l0();
        let masses = |r: &[V], m: &mut [f64]| {
            for (li, mi) in m.iter_mut().enumerate() {
                // Seabed stiffness only where contact is near: elsewhere it would only
                // slow the node down.
                *mi = if r[li].z < self.seabed.z + near {
                    self.seabed.k * lay.node_tributary[self.n0 + li]
                } else {
                    0.0
                };
            }
            for e in self.e0..self.e1 {
                let (a, b) = self.ends(e);
                let c = &self.coefs[lay.elem_line[e] as usize];
                let l = (r[b] - r[a]).norm();
                let l0 = lay.elem_l0[e];
                let t = c.ea * (l / l0 - 1.0).max(0.0);
                // Element stiffness EA/l0 t t^T + T/l P: eigenvalues at most this.
                let k = c.ea / l0 + t / l;
                m[a] += k;
                m[b] += k;
            }
            for mi in m.iter_mut() {
                // Gershgorin: |lambda| <= 2 sum_e k_e + k_seabed <= 2 m, so omega dt
                // <= sqrt(2) < 2 with dt = 1; the margin covers the drag terms.
                *mi = (*mi).max(f64::MIN_POSITIVE) * 1.2;
            }
        };
        let mut ke_prev = 0.0;
        for it in 0..opts.dr_max_iterations {
            if it % 10 == 0 {
                masses(r, &mut m);
            }
            self.residual(r, &mut f);
            let (fmax, _, _) = self.measure(&f);
            if fmax <= tol || !fmax.is_finite() {
                return it;
            }
            let mut ke = 0.0;
            for li in 0..nn {
                if self.free[li] {
                    v[li] += f[li] / m[li];
                    ke += m[li] * v[li].norm2();
                }
            }
            if ke < ke_prev {
                // Past a peak of kinetic energy: stop, and start again from rest.
                v.iter_mut().for_each(|x| *x = V::zero());
                ke_prev = 0.0;
                continue;
            }
            ke_prev = ke;
            for li in 0..nn {
                if self.free[li] {
                    r[li] += v[li];
                }
            }
        }
        opts.dr_max_iterations
    }
}

/// Component `k` of `v`.
fn comp(v: &mut V, k: usize) -> &mut f64 {
    match k {
        0 => &mut v.x,
        1 => &mut v.y,
        _ => &mut v.z,
    }
}

/// The linear system of one Newton step: block-tridiagonal or dense.
enum Lin {
    /// Diagonal, upper (row i, column i+1) and lower (row i, column i-1) 3x3 blocks.
    Chain { d: Vec<M3>, u: Vec<M3>, l: Vec<M3> },
    /// Dense matrix over the free coordinates; `dof[i]` is node i's first row
    /// (`usize::MAX` for held nodes).
    Dense { k: DMatrix<f64>, dof: Vec<usize> },
}

impl Lin {
    fn chain(n: usize) -> Self {
        Lin::Chain {
            d: vec![M3::zeros(); n],
            u: vec![M3::zeros(); n],
            l: vec![M3::zeros(); n],
        }
    }

    fn dense(free: &[bool]) -> Self {
        let mut dof = vec![usize::MAX; free.len()];
        let mut n = 0;
        for (i, &fr) in free.iter().enumerate() {
            if fr {
                dof[i] = n;
                n += 3;
            }
        }
        Lin::Dense {
            k: DMatrix::zeros(n, n),
            dof,
        }
    }

    fn clear(&mut self) {
        match self {
            Lin::Chain { d, u, l } => {
                for x in d.iter_mut().chain(u.iter_mut()).chain(l.iter_mut()) {
                    *x = M3::zeros();
                }
            }
            Lin::Dense { k, .. } => k.fill(0.0),
        }
    }

    /// Adds a block at (row node i, column node j); both free.
    fn add(&mut self, i: usize, j: usize, m: &M3) {
        match self {
            Lin::Chain { d, u, l } => {
                if i == j {
                    d[i] += m;
                } else if j == i + 1 {
                    u[i] += m;
                } else if i == j + 1 {
                    l[i] += m;
                } else {
                    unreachable!("a chain couples neighbours only");
                }
            }
            Lin::Dense { k, dof } => {
                let (r0, c0) = (dof[i], dof[j]);
                let mut view = k.fixed_view_mut::<3, 3>(r0, c0);
                view += m;
            }
        }
    }

    /// Largest diagonal entry over free nodes.
    fn diag_max(&self, free: &[bool]) -> f64 {
        let mut best = 0.0f64;
        for (i, &fr) in free.iter().enumerate() {
            if !fr {
                continue;
            }
            for c in 0..3 {
                let x = match self {
                    Lin::Chain { d, .. } => d[i][(c, c)],
                    Lin::Dense { k, dof } => k[(dof[i] + c, dof[i] + c)],
                };
                best = best.max(x.abs());
            }
        }
        best
    }

    /// `K x` on the free nodes (zero on held nodes).
    fn mul(&self, x: &[V], free: &[bool]) -> Vec<V> {
        let n = x.len();
        let v3 = |v: V| Vector3::new(v.x, v.y, v.z);
        let back = |v: Vector3<f64>| V::new(v[0], v[1], v[2]);
        let mut out = vec![V::zero(); n];
        match self {
            Lin::Chain { d, u, l } => {
                for i in 0..n {
                    if !free[i] {
                        continue;
                    }
                    let mut y = d[i] * v3(x[i]);
                    if i + 1 < n {
                        y += u[i] * v3(x[i + 1]);
                    }
                    if i > 0 {
                        y += l[i] * v3(x[i - 1]);
                    }
                    out[i] = back(y);
                }
            }
            Lin::Dense { k, dof } => {
                let mut xv = DVector::zeros(k.nrows());
                for (i, &di) in dof.iter().enumerate() {
                    if di != usize::MAX {
                        xv.fixed_rows_mut::<3>(di).copy_from(&v3(x[i]));
                    }
                }
                let y = k * xv;
                for (i, &di) in dof.iter().enumerate() {
                    if di != usize::MAX {
                        out[i] = V::new(y[di], y[di + 1], y[di + 2]);
                    }
                }
            }
        }
        out
    }

    /// Solves `(K + mu I) dx = f` on the free nodes; held nodes get `dx = 0`. `None`
    /// when the matrix is singular.
    fn solve(&self, mu: f64, f: &[V], free: &[bool]) -> Option<Vec<V>> {
        let n = f.len();
        let shift = M3::identity() * mu;
        match self {
            Lin::Chain { d, u, l } => {
                // Block Thomas: forward elimination, then back substitution.
                let mut dinv = vec![M3::zeros(); n];
                let mut bp = vec![Vector3::zeros(); n];
                for i in 0..n {
                    let (mut di, mut bi) = if free[i] {
                        (d[i] + shift, Vector3::new(f[i].x, f[i].y, f[i].z))
                    } else {
                        (M3::identity(), Vector3::zeros())
                    };
                    if i > 0 {
                        let m = l[i] * dinv[i - 1];
                        di -= m * u[i - 1];
                        bi -= m * bp[i - 1];
                    }
                    dinv[i] = di.try_inverse()?;
                    bp[i] = bi;
                }
                let mut x = vec![Vector3::zeros(); n];
                x[n - 1] = dinv[n - 1] * bp[n - 1];
                for i in (0..n - 1).rev() {
                    x[i] = dinv[i] * (bp[i] - u[i] * x[i + 1]);
                }
                let out: Vec<V> = x.iter().map(|v| V::new(v[0], v[1], v[2])).collect();
                out.iter().all(|v| v.is_finite()).then_some(out)
            }
            Lin::Dense { k, dof } => {
                let m = k.nrows();
                let mut a = k.clone();
                for c in 0..m {
                    a[(c, c)] += mu;
                }
                let mut rhs = DVector::zeros(m);
                for (i, &di) in dof.iter().enumerate() {
                    if di != usize::MAX {
                        rhs[di] = f[i].x;
                        rhs[di + 1] = f[i].y;
                        rhs[di + 2] = f[i].z;
                    }
                }
                let x = a.lu().solve(&rhs)?;
                let out: Vec<V> = dof
                    .iter()
                    .map(|&di| {
                        if di == usize::MAX {
                            V::zero()
                        } else {
                            V::new(x[di], x[di + 1], x[di + 2])
                        }
                    })
                    .collect();
                out.iter().all(|v| v.is_finite()).then_some(out)
            }
        }
    }
}
