//! The general passes of the CPU reference path over any graph (see the module doc of
//! `cpu`): the element pass, the node pass, and the time schemes over one block, with
//! the block's connectivity behind [`Topo`].

use super::screen::screen_block_forces;
use super::water::{node_water, BlockWaves, Water};
use crate::ale::{mass_flow_forces, AleElem};
use crate::math::{Sym3, V3};
use crate::model::{block_hinges, Block, Hinge, Layout, NO_CONSTRAINT, NO_ELEM};
use crate::options::{Formulation, Scheme, SolverOptions};
use crate::physics::frames::{frame_element, frenet_virtual_node};
use crate::physics::{
    bending_hinge, glmf_element_wet, point_wetted_fraction, seabed_damping, seabed_force,
    seabed_friction_axis, seabed_height, seabed_slope_damping, seabed_slope_force,
    seabed_slope_normal, tabulated_tension, visco_tension, wetted_fraction, Coefs, ElementInput,
    ElementLoads, SeabedCoefs,
};
use crate::step::{blow_up, StepFailure};

type V = V3<f64>;

/// Per-node scratch of the Runge-Kutta schemes.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct NodeScratch {
    r0: V,
    v0: V,
    sr: V,
    sv: V,
    acc: V,
}

/// Read-only context of the passes.
pub(super) struct Ctx<'a> {
    pub(super) lay: &'a Layout,
    pub(super) coefs: &'a [Coefs<f64>],
    pub(super) seabed: SeabedCoefs<f64>,
    pub(super) opts: SolverOptions,
    pub(super) elem_in_cable: &'a [u32],
    /// Per current profile: its value when uniform (looked up without a table walk).
    pub(super) uniform_current: &'a [Option<V>],
    /// Gravity, m/s^2 (the dry weight of what is above the water surface).
    pub(super) gravity: f64,
    /// The step with which the seabed's damping terms are taken implicitly in the
    /// node solve, `(M + h diag(c)) a = F` (the symplectic scheme: `h = dt`); 0 for
    /// the explicit acceleration (Runge-Kutta stages, evaluation).
    pub(super) implicit_dt: f64,
    /// Per route: the target of a node held on a free body, read in place of the
    /// route (empty without free bodies: `super::free`).
    pub(super) targets: &'a [Option<crate::model::RouteState>],
    /// Every bending hinge of the layout (`Layout::hinges`), ordered by anchor.
    pub(super) hinges: &'a [Hinge],
}

/// How a block's elements and nodes are connected, in block-local indices.
///
/// Two implementations share the passes: [`ChainTopo`] for a block that is one chain
/// in node order (element `k` joins nodes `k` and `k+1`: no index arrays read at all),
/// and [`GeneralTopo`] for networks (element ends and incidence lists from the layout).
/// Gathers are iterators (one loop body), not callbacks, so they inline.
pub(super) trait Topo {
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
pub(super) struct ChainInc {
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
pub(super) struct GeneralTopo<'a> {
    pub(super) lay: &'a Layout,
    pub(super) n0: usize,
    pub(super) e0: usize,
}

/// Incidence of a node from the layout's lists.
pub(super) struct GeneralInc<'a> {
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
pub(super) fn element_input<T: Topo>(
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

/// Pass 1 over one block: element loads. `r`, `v`, `out` are block-local slices, and
/// so is `x`, the elements' internal states (viscoelastic lines: `physics::visco`;
/// empty in a run without them), whose rates the pass leaves in `out[k].rate`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn element_pass<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    ale: &[AleElem],
    r: &[V],
    v: &[V],
    x: &[f64],
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
            // Tabulated strain-tension curves (physics::axial): the elastic part from the
            // curve, the damping as before. Skipped whole where no line type has one.
            if lay.line_types.iter().any(|lt| lt.ea_curve.is_some()) {
                tabulated_pass(ctx, topo, r, v, l0s, lines, out);
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
    if !x.is_empty() {
        visco_pass(ctx, topo, r, v, x, l0s, lines, out);
    }
    if !ctx.hinges.is_empty() {
        bending_pass(ctx, topo, e0, r, out);
    }
    Ok(())
}

/// Replaces the tension of every element of a viscoelastic line by the model's
/// (`physics::visco`) at its state `x[k]`, and leaves the state's rate in `rate`
/// (winch cables of such a line are refused where the scenario is read).
#[cold]
#[allow(clippy::too_many_arguments)]
fn visco_pass<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    r: &[V],
    v: &[V],
    x: &[f64],
    l0s: &[f64],
    lines: &[u32],
    out: &mut [ElementLoads<f64>],
) {
    let lay = ctx.lay;
    for (k, o) in out.iter_mut().enumerate() {
        let lt = &lay.line_types[lines[k] as usize];
        let Some(vm) = lt.viscoelastic else {
            continue;
        };
        let (a, bn) = topo.ends(k);
        let l0 = l0s[k];
        let eps = (r[bn] - r[a]).norm() / l0 - 1.0;
        let epsdot = o.t.dot(v[bn] - v[a]) / l0;
        let (ten, rate) = visco_tension(
            lt.ea,
            vm.ea_dynamic,
            vm.ea_dynamic_slope,
            vm.ba_static,
            vm.ba_dynamic,
            eps,
            epsdot,
            x[k],
        );
        o.tension = ten;
        o.rate = rate;
    }
}

/// Replaces the tension of every element of a tabulated line by the curve's (winch
/// cables of a tabulated line are refused where the scenario is read).
#[cold]
fn tabulated_pass<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    r: &[V],
    v: &[V],
    l0s: &[f64],
    lines: &[u32],
    out: &mut [ElementLoads<f64>],
) {
    let lay = ctx.lay;
    for (k, o) in out.iter_mut().enumerate() {
        let line = lines[k] as usize;
        let Some(rows) = lay.line_types[line].ea_curve.as_deref() else {
            continue;
        };
        let (a, bn) = topo.ends(k);
        let l = (r[bn] - r[a]).norm();
        let l0 = l0s[k];
        let c = &ctx.coefs[line];
        let eps = l / l0 - 1.0;
        let epsdot = o.t.dot(v[bn] - v[a]) / l0;
        o.tension = tabulated_tension(rows, eps) + c.ea_c * epsdot;
    }
}

/// The bending hinges of the block of elements `e0..e0 + out.len()`: each hinge's
/// forces ([`bending_hinge`]) added to the shear of the elements beside it, after
/// the element loop has left every element's tangent in `out`.
#[inline(always)]
pub(super) fn bending_pass<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    e0: usize,
    r: &[V],
    out: &mut [ElementLoads<f64>],
) {
    let len = |k: usize| {
        let (a, b) = topo.ends(k);
        (r[b] - r[a]).norm()
    };
    for h in block_hinges(ctx.hinges, e0, e0 + out.len()) {
        let p = (h.prev != NO_ELEM).then(|| h.prev as usize - e0);
        let n = (h.next != NO_ELEM).then(|| h.next as usize - e0);
        let dir = V::from_f64(h.dir);
        let (q1, l1) = p.map_or((dir, 1.0), |p| (out[p].t, len(p)));
        let (q2, l2) = n.map_or((dir, 1.0), |n| (out[n].t, len(n)));
        let (f1, f2) = bending_hinge(q1, l1, q2, l2, h.k);
        // f1 acts on node a of the element before (which receives -shear), f2 on
        // node b of the element after (which receives +shear).
        if let Some(p) = p {
            out[p].shear -= f1;
        }
        if let Some(n) = n {
            out[n].shear += f2;
        }
    }
}

/// The node's mass block at position `r` under surface elevation `eta`: point mass,
/// half masses and half normal added masses.
#[inline(always)]
pub(super) fn node_mass<T: Topo>(
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
/// Baumgarte-constrained). `r`, `v`, `elems` are block-local, `li` block-local too;
/// `screen` the block's screen-net knot forces (empty without screen nets).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn node_accel<T: Topo>(
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
    screen: &[(usize, V)],
) -> (V, V, Sym3<f64>) {
    let wn = (!w.is_empty()).then(|| node_water(w, li));
    node_accel_of(ctx, topo, b, li, r[li], v[li], t, wn, elems, |trib, f| {
        // Screen-model nets: the knot's share of its panels' loads
        // (super::screen::screen_block_forces, sorted by node).
        if !screen.is_empty() {
            if let Ok(j) = screen.binary_search_by_key(&li, |p| p.0) {
                *f += screen[j].1;
            }
        }
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
pub(super) fn node_accel_of<T: Topo>(
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
        f += el.f_half + (el.t * el.tension - el.shear) * sign;
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
    // A seabed grid: contact along the local normal (its height and slopes looked up
    // once per node and stage).
    let slope = lay
        .env
        .seabed
        .grid
        .map(|g| seabed_height(&g.packed[..], ri.x, ri.y));
    f += match slope {
        None => seabed_force(&ctx.seabed, trib, ri, vi),
        Some(g) => seabed_slope_force(&ctx.seabed, trib, ri, vi, g),
    };
    // Friction split along and across the line: the axial part `-d (v.q) q` on a node
    // of one or two elements (a net's knot has no line direction: isotropic, mu_t).
    let mut axis = (V::zero(), 0.0);
    if ctx.seabed.mu_axial != ctx.seabed.mu {
        let mut t = V::zero();
        let mut n_inc = 0;
        for (e, _) in topo.incident(li) {
            t += elems[e].t;
            n_inc += 1;
        }
        if n_inc <= 2 {
            let (n, fnorm) = match slope {
                None => (
                    V::new(0.0, 0.0, 1.0),
                    ctx.seabed.k * trib * (ctx.seabed.z - ri.z),
                ),
                Some(g) => {
                    let n = seabed_slope_normal(g);
                    (n, ctx.seabed.k * trib * (g.x - ri.z) * n.z)
                }
            };
            axis = seabed_friction_axis(&ctx.seabed, fnorm, n, vi, t);
            f -= axis.0 * (axis.1 * vi.dot(axis.0));
        }
    }
    let c = lay.node_constraint[i];
    let a = if c == NO_CONSTRAINT {
        if ctx.implicit_dt > 0.0 {
            // The seabed's damping taken implicitly (linearised at this state), so it
            // does not bound the step: (M + dt diag(c)) a = F, or on a sloped seabed
            // (M + dt (c_t I + (c_n - c_t) n n^T)) a = F.
            let mut mi = m;
            match slope {
                None => {
                    let cd = seabed_damping(&ctx.seabed, trib, ri, vi) * ctx.implicit_dt;
                    mi.xx += cd.x;
                    mi.yy += cd.y;
                    mi.zz += cd.z;
                }
                Some(g) => {
                    let (cn, ct) = seabed_slope_damping(&ctx.seabed, trib, ri, vi, g);
                    let (cn, ct) = (cn * ctx.implicit_dt, ct * ctx.implicit_dt);
                    mi.xx += cn;
                    mi.yy += cn;
                    mi.zz += cn;
                    mi.add_normal_projection(ct - cn, seabed_slope_normal(g));
                }
            }
            if axis.1 != 0.0 {
                // The axial friction's slope: + dt d q q^T.
                let (q, d) = (axis.0, axis.1 * ctx.implicit_dt);
                mi.xx += d * q.x * q.x;
                mi.yy += d * q.y * q.y;
                mi.zz += d * q.z * q.z;
                mi.xy += d * q.x * q.y;
                mi.xz += d * q.x * q.z;
                mi.yz += d * q.y * q.z;
            }
            mi.solve(f)
        } else {
            m.solve(f)
        }
    } else {
        let d = match ctx.targets.get(c as usize) {
            Some(Some(d)) => *d,
            _ => lay.routes[c as usize].eval(t),
        };
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
pub(super) fn check(ctx: &Ctx, r: V, v: V) -> Option<String> {
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
    x: &[f64],
    t: f64,
    w: &[f64],
    elems: &mut [ElementLoads<f64>],
    mut store: impl FnMut(usize, V),
) -> Result<(), StepFailure> {
    accelerations_of(ctx, topo, b, ale, r, v, x, t, w, elems, |li, a, _, _| {
        store(li, a)
    })
}

/// [`accelerations`], handing each node's force and mass block too.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn accelerations_of<T: Topo>(
    ctx: &Ctx,
    topo: &T,
    b: &Block,
    ale: &[AleElem],
    r: &[V],
    v: &[V],
    x: &[f64],
    t: f64,
    w: &[f64],
    elems: &mut [ElementLoads<f64>],
    mut store: impl FnMut(usize, V, V, Sym3<f64>),
) -> Result<(), StepFailure> {
    element_pass(ctx, topo, b, ale, r, v, x, t, w, elems)?;
    let mut screen = Vec::new();
    if ctx.lay.block_has_screen(b) {
        screen_block_forces(ctx.lay, b.node_start as usize, r, v, w, &mut screen);
    }
    for li in 0..r.len() {
        let (a, f, m) = node_accel(ctx, topo, b, ale, li, r, v, t, w, elems, &screen);
        store(li, a, f, m);
    }
    Ok(())
}

/// [`accelerations`] of a block at state `(r, v, x)` through its own topology, handing
/// each node's acceleration, force and mass block to `store` (the free bodies' stages
/// under the Runge-Kutta schemes: `super::solver`'s `free_rk`).
#[allow(clippy::too_many_arguments)]
pub(super) fn block_accelerations(
    ctx: &Ctx,
    b: &Block,
    r: &[V],
    v: &[V],
    x: &[f64],
    t: f64,
    w: &[f64],
    elems: &mut [ElementLoads<f64>],
    mut store: impl FnMut(usize, V, V, Sym3<f64>),
) -> Result<(), StepFailure> {
    if b.is_chain {
        let topo = ChainTopo { n_nodes: r.len() };
        accelerations_of(ctx, &topo, b, &[], r, v, x, t, w, elems, &mut store)
    } else {
        let topo = GeneralTopo {
            lay: ctx.lay,
            n0: b.node_start as usize,
            e0: b.elem_start as usize,
        };
        accelerations_of(ctx, &topo, b, &[], r, v, x, t, w, elems, &mut store)
    }
}

/// Advances one block by `nsteps` steps starting at step number `step0`, with the
/// chain fast path where the block is one chain in node order. `x` holds the block's
/// elements' internal states (empty without viscoelastic lines), advanced by the same
/// scheme as the nodes.
#[allow(clippy::too_many_arguments)]
pub(super) fn advance_block(
    ctx: &Ctx,
    b: &Block,
    ale: &[AleElem],
    r: &mut [V],
    v: &mut [V],
    x: &mut [f64],
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
            ctx, &topo, b, ale, r, v, x, s, elems, rs, vs, waves, wbuf, step0, dt, nsteps,
        )
    } else {
        let topo = GeneralTopo {
            lay: ctx.lay,
            n0: b.node_start as usize,
            e0: b.elem_start as usize,
        };
        advance_block_in(
            ctx, &topo, b, ale, r, v, x, s, elems, rs, vs, waves, wbuf, step0, dt, nsteps,
        )
    }
}

/// Fills `buf` with the block's water values at `t` for nodes at `r`, `v` (left empty
/// in still water).
#[inline(always)]
pub(super) fn fill_water(
    waves: &mut Option<&mut BlockWaves>,
    t: f64,
    r: &[V],
    v: &[V],
    buf: &mut Water,
) {
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
    x: &mut [f64],
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
    let has_screen = ctx.lay.block_has_screen(b);
    let mut screen = Vec::new();
    rs.resize(n, V::zero());
    vs.resize(n, V::zero());
    let diverged = |li: usize, t: f64, what: String| StepFailure::Diverged {
        node: n0 + li,
        time: t,
        what,
    };
    // The elements' internal states of the Runge-Kutta stages: the stage's state, the
    // state at the step's start, the weighted sum of the rates (empty without).
    let ne = x.len();
    let (mut xs, mut x0, mut xsum) = (x.to_vec(), vec![0.0; ne], vec![0.0; ne]);
    for k in 0..nsteps {
        // Time from the step count, not by accumulation: output times stay exact.
        let t = (step0 + k) as f64 * dt;
        match ctx.opts.scheme {
            Scheme::Symplectic => {
                fill_water(&mut waves, t, r, v, wbuf);
                element_pass(ctx, topo, b, ale, r, v, x, t, wbuf, elems)?;
                // The internal states by explicit Euler, from this step's rates.
                for (xk, el) in x.iter_mut().zip(elems.iter()) {
                    *xk += el.rate * dt;
                }
                if has_screen {
                    screen_block_forces(ctx.lay, n0, r, v, wbuf, &mut screen);
                }
                // The element pass (and the screen loads) have read every position and
                // velocity of this step, so each node can be updated as soon as its
                // acceleration is known.
                for li in 0..n {
                    let (a, _, _) =
                        node_accel(ctx, topo, b, ale, li, r, v, t, wbuf, elems, &screen);
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
                accelerations(ctx, topo, b, ale, r, v, x, t, wbuf, elems, |li, a| {
                    s[li].acc = a
                })?;
                for li in 0..n {
                    rs[li] = r[li] + v[li] * h;
                    vs[li] = v[li] + s[li].acc * h;
                }
                for k in 0..ne {
                    xs[k] = x[k] + elems[k].rate * h;
                }
                fill_water(&mut waves, t + h, rs, vs, wbuf);
                accelerations(
                    ctx,
                    topo,
                    b,
                    ale,
                    rs,
                    vs,
                    &xs,
                    t + h,
                    wbuf,
                    elems,
                    |li, a| s[li].acc = a,
                )?;
                for k in 0..ne {
                    x[k] += elems[k].rate * dt;
                }
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
                x0.copy_from_slice(x);
                xs.copy_from_slice(x);
                xsum.fill(0.0);
                for (stage, (tau, w, next)) in
                    [(0.0, 1.0, h), (h, 2.0, h), (h, 2.0, dt), (dt, 1.0, 0.0)]
                        .into_iter()
                        .enumerate()
                {
                    fill_water(&mut waves, t + tau, rs, vs, wbuf);
                    accelerations(
                        ctx,
                        topo,
                        b,
                        ale,
                        rs,
                        vs,
                        &xs,
                        t + tau,
                        wbuf,
                        elems,
                        |li, a| s[li].acc = a,
                    )?;
                    for k in 0..ne {
                        xsum[k] += elems[k].rate * w;
                        if stage < 3 {
                            xs[k] = x0[k] + elems[k].rate * next;
                        }
                    }
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
                for k in 0..ne {
                    x[k] = x0[k] + xsum[k] * (dt / 6.0);
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
