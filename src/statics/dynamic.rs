//! Dynamic relaxation with kinetic damping, for blocks too large for a dense solve.

use super::system::Sys;
use super::{RelaxOptions, V};

impl Sys<'_> {
    /// Dynamic relaxation: pseudo-dynamics `m_i a_i = F_i` with unit time step,
    /// fictitious masses from the Gershgorin bound of the stiffness (so the explicit
    /// scheme is stable), and kinetic damping (velocities reset at each peak of the
    /// kinetic energy). Returns the iterations done.
    pub(super) fn dynamic_relaxation(&self, r: &mut [V], tol: f64, opts: &RelaxOptions) -> usize {
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
                *mi = if r[li].z < self.seabed_z(r[li]) + near {
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
            // Bending hinges: the Gershgorin bound of crate::stability's, 2 k s |b_i|
            // on each of a hinge's nodes.
            for h in self.hinges {
                let fs = self.hinge_forces(h, r);
                let mut s = 0.0;
                for e in [h.prev, h.next] {
                    if e != crate::model::NO_ELEM {
                        let (a, b) = self.ends(e as usize);
                        s += 1.0 / (r[b] - r[a]).norm();
                    }
                }
                for (li, _) in fs {
                    m[li] += 2.0 * h.k * s * s;
                }
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
