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
//! [`glmf_element_wet`](crate::physics::glmf_element_wet) with zero node velocities (elastic axial force with the slack
//! rule, no internal damping since the strain rate is zero; half the element's weight
//! less the buoyancy of its share under the mean water level `z = 0`; normal and
//! tangential drag of the current at the element's midpoint on that share; no water
//! acceleration), the point mass's weight less the buoyancy of its share under water
//! and its drag in the current at the node on that share (docs/src/water_surface.md: a line
//! hung above the water starts from its true equilibrium, in air), and [`seabed_force`](crate::physics::seabed_force) with zero velocity (the elastic normal force; the
//! damping and the regularised friction vanish at rest). Nodes held by a route are
//! placed at `route.eval(0.0).r` and are not unknowns. Only the GLMF loads are used:
//! at rest in still water the older element frames are singular or equal to them.
//!
//! # The solver
//! Blocks (connected components, `Layout::blocks`) are independent and are solved in
//! parallel. Each is solved by Newton's method on the free nodes' positions:
//! * the stiffness `K = -dF/dr` is assembled per element from its axial force written
//!   out, `dT/dl t t^T + T/l (I - t t^T)`, and from central finite differences of its
//!   external loads (weight at the water surface, drag) with respect to its two end
//!   nodes (step `1e-6` of the element length), and from differences of each node's
//!   own loads (point drag, seabed contact, near the seabed): general, drag and current
//!   profiles included. The axial part is not differenced: for a near-inextensible
//!   line the tension's round-off over the difference step swamps the geometric
//!   stiffness `T/l` (docs/src/model/initial.md). A slack element has no stiffness, so
//!   Newton's model would let a step stretch it without bound: it gets its taut axial
//!   stiffness `EA/l0 t t^T` in `K` (the Jacobian only; the residual, hence the
//!   solution, is unchanged);
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
use crate::model::Layout;
use crate::physics::{Coefs, SeabedCoefs};
use rayon::prelude::*;

pub mod bodies;
mod dynamic;
mod linear;
mod newton;
mod system;

use system::Sys;

type V = V3<f64>;
type M3 = nalgebra::Matrix3<f64>;

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
    relax_blocks_held(layout, positions, opts, which)
}

/// [`relax_blocks`] with the route-held nodes left where `positions` has them (the
/// nodes held on a free body, placed by the body statics).
pub(crate) fn relax_blocks_held(
    layout: &Layout,
    positions: &mut [[f64; 3]],
    opts: &RelaxOptions,
    which: &[bool],
) -> Result<RelaxReport, Error> {
    let coefs: Vec<Coefs<f64>> = layout.line_coefs.iter().map(Coefs::from_line).collect();
    let seabed = seabed_coefs(layout);
    let hinges = layout.hinges();
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
            let sys = Sys::new(layout, &coefs, seabed, b, &hinges);
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
    let hinges = layout.hinges();
    let mut out = vec![[0.0; 3]; layout.n_nodes()];
    for b in &layout.blocks {
        let sys = Sys::new(layout, &coefs, seabed, *b, &hinges);
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
        mu_axial: e.seabed.mu_axial(),
        v_eps: e.seabed.friction_velocity,
    }
}
