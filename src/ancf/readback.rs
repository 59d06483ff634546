//! What users read back from an ANCF cable: kinematics, curvature and tension at
//! any arc length, node section forces, end forces on supports, energies.

use super::band::BW;
use super::cable::AncfCable;
use super::element::{ale_kinematics, element_forces, kinematics, strain_energy, PointKinematics};
use super::shape::{ale_shape, hermite};
use crate::error::Error;
use crate::math::V3;

type V = V3<f64>;

/// Kinetic, strain and potential energy of a cable, J.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AncfEnergy {
    /// `1/2 qd^T M qd` with the consistent mass (and point masses).
    pub kinetic: f64,
    /// Axial and bending strain energy.
    pub strain: f64,
    /// Potential of the weights and applied forces, `-Q_const . q`.
    pub potential: f64,
}

impl AncfEnergy {
    /// The sum.
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.potential
    }
}
impl AncfCable {
    /// Kinematics at unstretched arc length `s` from node 0 (clamped to the cable):
    /// material velocity and rates (convective parts included on a winch's variable
    /// element).
    #[doc(hidden)]
    pub fn point_at(&self, s: f64) -> PointKinematics {
        let lens = self.m.lens_at(self.t);
        let mut e = 0;
        let mut x = s.max(0.0);
        while e + 1 < lens.len() && x > lens[e] {
            x -= lens[e];
            e += 1;
        }
        let l = lens[e];
        let xi = (x / l).clamp(0.0, 1.0);
        let sh = hermite(l, xi);
        let (q, qd) = (&self.q[6 * e..6 * e + 12], &self.qd[6 * e..6 * e + 12]);
        let mut p = kinematics(&sh, q, qd);
        if let (Some(a), Some(now)) = (&self.m.ale, self.m.ale_now(self.t)) {
            if now.elem == e {
                let al = ale_shape(l, xi, a.at_start, &sh);
                ale_kinematics(&al, now.ldot, now.lddot, q, qd, &mut p);
            }
        }
        p
    }

    /// Position at unstretched arc length `s` from the start, m.
    pub fn position_at(&self, s: f64) -> [f64; 3] {
        self.point_at(s).r.to_f64()
    }

    /// Velocity at unstretched arc length `s` from the start, m/s (of the material
    /// there).
    pub fn velocity_at(&self, s: f64) -> [f64; 3] {
        self.point_at(s).rd.to_f64()
    }

    /// Axial force (tension) at unstretched arc length `s`, N: `|r'| EA (g eps0 + c
    /// eps0dot)`, the magnitude of the force `N r'` across the section (bending shear
    /// not included). The strain of a stiff line oscillates along a cubic element, so
    /// this pointwise value converges slowly (about 0.3 % of the tension with 16
    /// elements on a 1000 m catenary); [`AncfCable::node_tensions`] is the accurate one
    /// (1e-6 there).
    pub fn tension_at(&self, s: f64) -> f64 {
        let p = self.point_at(s);
        let (_, _, n) = super::element::axial(&self.m.coefs.line, &p);
        n * p.r1.norm()
    }

    /// Curvature at unstretched arc length `s`, 1/m.
    pub fn curvature_at(&self, s: f64) -> f64 {
        super::element::curvature(&self.point_at(s)).0
    }

    // ------------------------------------------------------------------ evaluation

    /// Section force at every node, N: the force the cable beyond the node (towards the
    /// end) exerts on the cable before it, `T t` for a line in tension. It is taken from
    /// the elements' consistent nodal forces, `-(Q_e - M_e a_e)` over the node's position
    /// coordinates (internal, external and inertial forces of the adjacent element,
    /// averaged over the two elements at an interior node), the same construction as the
    /// end reactions: in a converged static state these are the element's exact
    /// equilibrium with its loads, and far more accurate than the tension from the strain
    /// at a point ([`AncfCable::tension_at`]), which oscillates along stiff elements.
    pub fn node_section_forces(&mut self) -> Result<Vec<[f64; 3]>, Error> {
        let (q, qd, t) = (self.q.clone(), self.qd.clone(), self.t);
        self.m
            .accelerations(&q, &qd, t, &mut self.ws)
            .map_err(|e| self.m.diverged(0, t, e))?;
        let n_el = self.m.n_el;
        let env = self.m.env();
        let c = &self.m.coefs.line;
        let now = self.m.ale_now(t);
        let mut out = vec![V::zero(); n_el + 1];
        let mut count = vec![0.0; n_el + 1];
        for e in 0..n_el {
            let b = 6 * e;
            let mut f = [0.0; 12];
            let (gps, ale) = self.m.element_rule(e, &now);
            element_forces(
                &self.m.coefs,
                gps,
                &env,
                &q[b..b + 12],
                &qd[b..b + 12],
                &mut f,
                Some(&mut self.ws.tangents[..]),
                ale.as_ref(),
            );
            // Consistent inertia forces (M_e a_e) on the element's two position coordinates.
            let acc = &self.ws.acc[b..b + 12];
            let (mut ia, mut ib) = (V::zero(), V::zero());
            for (gp, tg) in gps.iter().zip(&self.ws.tangents) {
                let sh = &gp.shape;
                let a = kinematics(sh, acc, &[0.0; 12]).r;
                let ma = a * (c.mass + self.m.added_iso) - *tg * (self.m.added * tg.dot(a));
                ia += ma * (gp.dx * sh.s[0]);
                ib += ma * (gp.dx * sh.s[2]);
            }
            let fa = V::new(f[0], f[1], f[2]) - ia;
            let fb = V::new(f[6], f[7], f[8]) - ib;
            // The element pulls its end b back with -T t: the section force is -fb.
            out[e + 1] -= fb;
            out[e] += fa;
            count[e] += 1.0;
            count[e + 1] += 1.0;
        }
        Ok(out
            .iter()
            .zip(&count)
            .map(|(v, n)| (*v / *n).to_f64())
            .collect())
    }

    /// Tension at every node, N: the magnitude of [`AncfCable::node_section_forces`].
    pub fn node_tensions(&mut self) -> Result<Vec<f64>, Error> {
        Ok(self
            .node_section_forces()?
            .iter()
            .map(|f| V::from_f64(*f).norm())
            .collect())
    }

    /// The force each supported end (one on a route) exerts on its support at the
    /// current state, `F_k - (M a)_k` over the end's position coordinates, N
    /// (docs/src/model/constraints.md, "End forces"); `None` for an end without a route.
    pub fn end_forces(&mut self) -> Result<[Option<[f64; 3]>; 2], Error> {
        let (q, qd, t) = (self.q.clone(), self.qd.clone(), self.t);
        self.m
            .accelerations(&q, &qd, t, &mut self.ws)
            .map_err(|e| self.m.diverged(0, t, e))?;
        let mfull = if self.m.mass_varies() {
            &self.ws.m
        } else {
            &self.m.mass_base
        };
        let mut out = [None, None];
        for (k, sup) in self.m.supported.iter().enumerate() {
            if let Some(node) = sup {
                let mut r = [0.0; 3];
                for (a, ra) in r.iter_mut().enumerate() {
                    let i = 6 * node + a;
                    let j0 = i.saturating_sub(BW);
                    let j1 = (i + BW).min(q.len() - 1);
                    let ma: f64 = (j0..=j1).map(|j| mfull.get(i, j) * self.ws.acc[j]).sum();
                    *ra = self.ws.f[i] - ma;
                }
                out[k] = Some(r);
            }
        }
        Ok(out)
    }

    /// Kinetic, strain and potential energy at the current state (the potential counts
    /// weights and applied forces; drag, seabed and damping are not conservative).
    pub fn energy(&mut self) -> AncfEnergy {
        let mfull = if self.m.mass_varies() {
            let (q, qd, t) = (self.q.clone(), self.qd.clone(), self.t);
            self.m.forces(&q, &qd, t, &mut self.ws, true);
            &self.ws.m
        } else {
            &self.m.mass_base
        };
        let mut mv = vec![0.0; self.q.len()];
        mfull.mul_vec(&self.qd, &mut mv);
        let kinetic = 0.5 * mv.iter().zip(&self.qd).map(|(a, b)| a * b).sum::<f64>();
        let now = self.m.ale_now(self.t);
        let strain = (0..self.m.n_el)
            .map(|e| {
                let (gps, _) = self.m.element_rule(e, &now);
                strain_energy(&self.m.coefs, gps, &self.q[6 * e..6 * e + 12])
            })
            .sum();
        let potential = -self
            .m
            .const_force
            .iter()
            .zip(&self.q)
            .map(|(f, q)| f * q)
            .sum::<f64>();
        AncfEnergy {
            kinetic,
            strain,
            potential,
        }
    }
}
