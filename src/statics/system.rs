//! One block's static problem: its loads, potential energy, residual and stiffness.

use super::{M3, V};
use crate::model::{block_hinges, Block, Hinge, Layout, NO_CONSTRAINT, NO_ELEM};
use crate::physics::{
    bending_energy, bending_hinge, glmf_element_wet, point_wetted_fraction, seabed_force,
    seabed_height, seabed_slope_force, tabulated_slope, tabulated_tension, tabulated_work,
    wetted_fraction, Coefs, ElementInput, ElementLoads, SeabedCoefs,
};
use nalgebra::Vector3;
use std::borrow::Cow;

/// One block's static problem.
pub(super) struct Sys<'a> {
    pub(super) lay: &'a Layout,
    pub(super) coefs: Cow<'a, [Coefs<f64>]>,
    pub(super) seabed: SeabedCoefs<f64>,
    pub(super) block: Block,
    pub(super) n0: usize,
    pub(super) nn: usize,
    pub(super) e0: usize,
    pub(super) e1: usize,
    /// Per block-local node: not held by a route.
    pub(super) free: Vec<bool>,
    /// The factor on the tabulated strain-tension curves (continuation; 1 otherwise).
    pub(super) curve_scale: f64,
    /// The block's bending hinges (`Layout::hinges`).
    pub(super) hinges: &'a [Hinge],
}

impl<'a> Sys<'a> {
    pub(super) fn new(
        lay: &'a Layout,
        coefs: &'a [Coefs<f64>],
        seabed: SeabedCoefs<f64>,
        block: Block,
        all_hinges: &'a [Hinge],
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
            curve_scale: 1.0,
            hinges: block_hinges(
                all_hinges,
                block.elem_start as usize,
                block.elem_end as usize,
            ),
        }
    }

    /// The same block with every axial stiffness and the seabed stiffness scaled by `s`
    /// (continuation).
    pub(super) fn softened(&self, s: f64) -> Sys<'a> {
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
            curve_scale: self.curve_scale * s,
            hinges: self.hinges,
        }
    }

    /// Block-local end nodes of packed element `e`.
    #[inline]
    pub(super) fn ends(&self, e: usize) -> (usize, usize) {
        (
            self.lay.elem_a[e] as usize - self.n0,
            self.lay.elem_b[e] as usize - self.n0,
        )
    }

    /// Static forces of packed element `e` on its nodes a and b.
    #[inline]
    pub(super) fn element(&self, e: usize, ra: V, rb: V) -> (V, V) {
        let el = self.element_loads(e, ra, rb);
        (el.f_half + el.t * el.tension, el.f_half - el.t * el.tension)
    }

    /// The GLMF loads of packed element `e` at rest with ends `ra`, `rb`.
    #[inline]
    pub(super) fn element_loads(&self, e: usize, ra: V, rb: V) -> ElementLoads<f64> {
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
        let mut el = glmf_element_wet(c, &input, wet, lay.env.gravity);
        if let Some(rows) = self.curve(e) {
            // At rest: the curve's tension, no damping.
            let eps = (rb - ra).norm() / input.l0 - 1.0;
            el.tension = self.curve_scale * tabulated_tension(rows, eps);
        }
        el
    }

    /// The strain-tension curve of packed element `e`'s line type, if it has one.
    #[inline]
    pub(super) fn curve(&self, e: usize) -> Option<&'a [[f64; 2]]> {
        self.lay.line_types[self.lay.elem_line[e] as usize]
            .ea_curve
            .as_deref()
    }

    /// The point loads of packed node `i`: weight less the buoyancy of the share of
    /// the point under the mean water level, drag in the current on that share.
    #[inline]
    pub(super) fn point(&self, i: usize, r: V) -> V {
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
    pub(super) fn node(&self, i: usize, r: V) -> V {
        self.point(i, r) + self.contact(i, r)
    }

    /// Seabed contact on packed node `i` at rest at `r`: on the plane, or along the
    /// local normal of the seabed grid.
    #[inline]
    pub(super) fn contact(&self, i: usize, r: V) -> V {
        let lt = self.lay.node_tributary[i];
        match self.lay.env.seabed.grid {
            None => seabed_force(&self.seabed, lt, r, V::zero()),
            Some(g) => {
                let h = seabed_height(&g.packed[..], r.x, r.y);
                seabed_slope_force(&self.seabed, lt, r, V::zero(), h)
            }
        }
    }

    /// The seabed's height under `r`: the plane's, or the grid's at `r`'s `x`, `y`.
    #[inline]
    pub(super) fn seabed_z(&self, r: V) -> f64 {
        match self.lay.env.seabed.grid {
            None => self.seabed.z,
            Some(g) => seabed_height(&g.packed[..], r.x, r.y).x,
        }
    }

    /// The external loads at `r` that [`Self::energy_change`] holds fixed over a step:
    /// per element (in element order) its weight and drag, per node its point loads.
    pub(super) fn frozen_loads(&self, r: &[V]) -> (Vec<V>, Vec<V>) {
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
    pub(super) fn energy_change(&self, r: &[V], dx: &[V], ext: &[V], own: &[V]) -> f64 {
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
            de += match self.curve(e) {
                // The curve's work from strain `ea` to `eb`, from the increment itself.
                Some(rows) => self.curve_scale * l0 * tabulated_work(rows, ea, dl / l0),
                None => 0.5 * c.ea * l0 * dp * (pa + pb),
            };
            de -= ext[e - self.e0].dot((dx[a] + dx[b]) * 0.5);
        }
        if !self.hinges.is_empty() {
            let r1: Vec<V> = r.iter().zip(dx).map(|(p, d)| *p + *d).collect();
            for h in self.hinges {
                de += self.hinge_energy(h, &r1) - self.hinge_energy(h, r);
            }
        }
        for li in 0..self.nn {
            if !self.free[li] {
                continue;
            }
            de -= own[li].dot(dx[li]);
            if let Some(g) = lay.env.seabed.grid {
                // A seabed grid: the energy 1/2 K lt p^2 of the penetration along the
                // local normal, p = (z_b - z) n_z, at both ends of the step.
                let k = self.seabed.k * lay.node_tributary[self.n0 + li];
                let pen = |x: V| {
                    let h = seabed_height(&g.packed[..], x.x, x.y);
                    (h.x - x.z).max(0.0) / (1.0 + h.y * h.y + h.z * h.z).sqrt()
                };
                let (pa, pb) = (pen(r[li]), pen(r[li] + dx[li]));
                de += 0.5 * k * (pb - pa) * (pa + pb);
                continue;
            }
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
    pub(super) fn residual(&self, r: &[V], f: &mut [V]) {
        for (li, fi) in f.iter_mut().enumerate() {
            *fi = self.node(self.n0 + li, r[li]);
        }
        for e in self.e0..self.e1 {
            let (a, b) = self.ends(e);
            let (fa, fb) = self.element(e, r[a], r[b]);
            f[a] += fa;
            f[b] += fb;
        }
        for h in self.hinges {
            for (li, fh) in self.hinge_forces(h, r) {
                f[li] += fh;
            }
        }
    }

    /// The side of hinge `h` on packed element `e` (or its held direction where `e` is
    /// [`NO_ELEM`]): unit tangent, length, block-local far node (the node not at the
    /// hinge) and hinge node; `last` says whether `e` ends at the hinge.
    fn hinge_side(
        &self,
        h: &Hinge,
        e: u32,
        r: &[V],
        last: bool,
    ) -> (V, f64, Option<usize>, Option<usize>) {
        if e == NO_ELEM {
            return (V::from_f64(h.dir), 1.0, None, None);
        }
        let (a, b) = self.ends(e as usize);
        let d = r[b] - r[a];
        let l = d.norm();
        if last {
            (d / l, l, Some(a), Some(b))
        } else {
            (d / l, l, Some(b), Some(a))
        }
    }

    /// The bending forces of hinge `h` at `r`: (block-local node, force) for its far
    /// node before, its own node and its far node after (a held side left out).
    pub(super) fn hinge_forces(&self, h: &Hinge, r: &[V]) -> Vec<(usize, V)> {
        let (q1, l1, far1, mid1) = self.hinge_side(h, h.prev, r, true);
        let (q2, l2, far2, mid2) = self.hinge_side(h, h.next, r, false);
        let (mut f1, mut f2) = bending_hinge(q1, l1, q2, l2, h.k);
        let mut out = Vec::with_capacity(3);
        match far1 {
            Some(a) => out.push((a, f1)),
            None => f1 = V::zero(),
        }
        match far2 {
            Some(b) => out.push((b, f2)),
            None => f2 = V::zero(),
        }
        if let Some(m) = mid1.or(mid2) {
            out.push((m, -(f1 + f2)));
        }
        out
    }

    /// The bending energy of hinge `h` at `r`, J.
    pub(super) fn hinge_energy(&self, h: &Hinge, r: &[V]) -> f64 {
        let (q1, ..) = self.hinge_side(h, h.prev, r, true);
        let (q2, ..) = self.hinge_side(h, h.next, r, false);
        bending_energy(q1, q2, h.k)
    }

    /// What makes the static force at block-local node `li` (state `r`) not a finite
    /// magnitude, in words for an error: the first of its position, an element of its
    /// (zero length, tension, distributed loads), its point loads and its seabed contact
    /// found out of range, with the values; else the sum of them that overflows.
    pub(super) fn why_not_finite(&self, r: &[V], li: usize) -> String {
        let bad = |v: V| !v.norm2().is_finite();
        let i = self.n0 + li;
        if bad(r[li]) {
            return format!(
                "its position {:?} m is not finite, or its square overflows f64",
                r[li].to_f64()
            );
        }
        for e in self.e0..self.e1 {
            let (a, b) = self.ends(e);
            if a != li && b != li {
                continue;
            }
            let (cable, k) = self.lay.describe_element(e);
            let el = format!("element {k} of cable '{cable}'");
            let other = if a == li { b } else { a };
            if bad(r[other]) {
                return format!(
                    "the other node of {el} is at {:?} m, not finite or with a square that overflows f64",
                    r[other].to_f64()
                );
            }
            if (r[b] - r[a]).norm2() == 0.0 {
                return format!(
                    "{el} has zero length (both its nodes at {:?} m): no direction for its tension",
                    r[li].to_f64()
                );
            }
            let loads = self.element_loads(e, r[a], r[b]);
            if !(loads.tension * loads.tension).is_finite() {
                return format!(
                    "the tension of {el} is {:e} N (unstretched length {:e} m, stretched {:e} m), whose square overflows f64",
                    loads.tension,
                    self.lay.elem_l0[e],
                    (r[b] - r[a]).norm()
                );
            }
            if bad(loads.f_half) {
                return format!(
                    "the weight, buoyancy or drag on {el} is {:?} N, whose square overflows f64",
                    (loads.f_half * 2.0).to_f64()
                );
            }
        }
        let point = self.point(i, r[li]);
        if bad(point) {
            return format!(
                "its point load (weight, buoyancy, drag of a point mass) is {:?} N, whose square overflows f64",
                point.to_f64()
            );
        }
        let contact = self.contact(i, r[li]);
        if bad(contact) {
            return format!(
                "its seabed contact force is {:?} N, whose square overflows f64",
                contact.to_f64()
            );
        }
        "the sum of its loads overflows f64".into()
    }

    /// Largest free-node force magnitude and its block-local node, and the sum of
    /// squares over free nodes.
    pub(super) fn measure(&self, f: &[V]) -> (f64, Option<usize>, f64) {
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
    pub(super) fn scales(&self, r: &[V]) -> (f64, f64) {
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
    pub(super) fn stiffness(&self, r: &[V], mut add: impl FnMut(usize, usize, &M3)) {
        let vec3 = |v: V| Vector3::new(v.x, v.y, v.z);
        for e in self.e0..self.e1 {
            let (a, b) = self.ends(e);
            let (ra, rb) = (r[a], r[b]);
            // The axial force's stiffness is written out, not differenced: for a
            // near-inextensible line (EA/l0 ~ 1e11 N/m) the round-off of the tension,
            // EA/l0 times that of the length (eps |r|), divided by a difference step
            // swamps the geometric stiffness T/l of the catenary's shape, and Newton's
            // model fails. G = dT/dl t t^T + T/l (I - t t^T), with dT/dl as in
            // `axial_force` (EA/l0 taut, compression EA/l0 for a rod shortened, none
            // for a slack line).
            let c = &self.coefs[self.lay.elem_line[e] as usize];
            let d = rb - ra;
            let l = d.norm();
            let l0 = self.lay.elem_l0[e];
            let mut g = M3::zeros();
            if l > 0.0 {
                let t = vec3(d / l);
                let tt = t * t.transpose();
                let eps = l / l0 - 1.0;
                let (k_ax, tension) = if let Some(rows) = self.curve(e) {
                    (
                        self.curve_scale * tabulated_slope(rows, eps) / l0,
                        self.curve_scale * tabulated_tension(rows, eps),
                    )
                } else if eps > 0.0 {
                    (c.ea / l0, c.ea * eps)
                } else {
                    (c.ea * c.compression / l0, c.ea * eps * c.compression)
                };
                g = tt * k_ax + (M3::identity() - tt) * (tension / l);
                // A slack element has no stiffness, and Newton's model would let the
                // step stretch it without limit: give it its taut axial stiffness in
                // the Jacobian only (the residual, hence the solution, is unchanged).
                if c.compression == 0.0 && l < l0 {
                    g += tt * (c.ea / l0);
                }
            }
            let mut kk = [[g, -g], [-g, g]]; // kk[row node][column node]
                                             // The external loads (weight, buoyancy at the surface, drag: the same
                                             // half on each end) by central differences.
            let h = 1e-6 * l.max(l0);
            for k in 0..6 {
                let (mut p, mut m) = ([ra, rb], [ra, rb]);
                let x = *comp(&mut p[k / 3], k % 3);
                let (xp, xm) = (x + h, x - h);
                *comp(&mut p[k / 3], k % 3) = xp;
                *comp(&mut m[k / 3], k % 3) = xm;
                let fp = self.element_loads(e, p[0], p[1]).f_half;
                let fm = self.element_loads(e, m[0], m[1]).f_half;
                let col = vec3(fp - fm) * (-1.0 / (xp - xm));
                if col != Vector3::zeros() {
                    let mut c0 = kk[0][k / 3].column_mut(k % 3);
                    c0 += col;
                    let mut c1 = kk[1][k / 3].column_mut(k % 3);
                    c1 += col;
                }
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
            let near_seabed = ri.z < self.seabed_z(ri) + 1.0;
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
        // Bending hinges: central differences of each hinge's forces with respect to
        // its nodes (at most three, the held ones left out).
        for h in self.hinges {
            let nodes: Vec<usize> = self.hinge_forces(h, r).iter().map(|x| x.0).collect();
            let mut p = r.to_vec();
            for &j in &nodes {
                let hstep = 1e-6 * self.mean_l0();
                for k in 0..3 {
                    let x = *comp(&mut p[j], k);
                    *comp(&mut p[j], k) = x + hstep;
                    let fp = self.hinge_forces(h, &p);
                    *comp(&mut p[j], k) = x - hstep;
                    let fm = self.hinge_forces(h, &p);
                    *comp(&mut p[j], k) = x;
                    for ((i, a), (_, b)) in fp.iter().zip(&fm) {
                        let mut blk = M3::zeros();
                        blk.set_column(k, &(vec3(*a - *b) * (-1.0 / (2.0 * hstep))));
                        add(*i, j, &blk);
                    }
                }
            }
        }
    }

    /// True when some node at `r` (block-local) is close enough to the mean water
    /// level for the surface to change a load: within a diameter of its lines or the
    /// radius of its point mass below it, or above it.
    pub(super) fn near_surface(&self, r: &[V]) -> bool {
        let lay = self.lay;
        let band = (self.e0..self.e1)
            .map(|e| lay.line_types[lay.elem_line[e] as usize].diameter)
            .fold(0.0f64, f64::max);
        r.iter()
            .enumerate()
            .any(|(li, p)| p.z > -band.max(lay.node_point_radius[self.n0 + li]) - 1e-9)
    }

    /// Mean unstretched element length (1 m without elements).
    pub(super) fn mean_l0(&self) -> f64 {
        if self.e1 > self.e0 {
            self.lay.elem_l0[self.e0..self.e1].iter().sum::<f64>() / (self.e1 - self.e0) as f64
        } else {
            1.0
        }
    }
}

/// Component `k` of `v`.
pub(super) fn comp(v: &mut V, k: usize) -> &mut f64 {
    match k {
        0 => &mut v.x,
        1 => &mut v.y,
        _ => &mut v.z,
    }
}
