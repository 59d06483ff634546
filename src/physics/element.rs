//! GLMF element loads (docs/src/model/glmf.md, paper Eq. 10, 20 and 40).
//!
//! Everything is expressed in the global frame through the tangent `t` and the
//! normal-plane projection `P = I - t t^T`; no element frame is built, so the only
//! singular configuration is a zero-length element.

use crate::math::{Real, V3};
use crate::model::LineCoefs;

/// Line constants in the precision of the computation.
#[derive(Clone, Copy, Debug, Default)]
pub struct Coefs<T> {
    /// `EA`, N.
    pub ea: T,
    /// `EA c`, N s.
    pub ea_c: T,
    /// `1/2 rho Cn d`, kg/m^2.
    pub drag_n: T,
    /// `1/2 rho Ct pi d`, kg/m^2.
    pub drag_t: T,
    /// `(1 + Cm) rho A`, kg/m.
    pub froude_krylov: T,
    /// `(1 + Cat) rho A`, kg/m.
    pub froude_krylov_t: T,
    /// `mbar`, kg/m.
    pub mass: T,
    /// `Cm rho A`, kg/m.
    pub added_mass: T,
    /// `Cat rho A`, kg/m.
    pub added_mass_t: T,
    /// z component of weight less buoyancy per length, N/m.
    pub wet_weight_z: T,
    /// 1 when the elastic force acts in compression, else 0.
    pub compression: T,
}

impl<T: Real> Coefs<T> {
    /// Converts the folded `f64` constants.
    pub fn from_line(c: &LineCoefs) -> Self {
        Self {
            ea: T::c(c.ea),
            ea_c: T::c(c.ea_c),
            drag_n: T::c(c.drag_n),
            drag_t: T::c(c.drag_t),
            froude_krylov: T::c(c.froude_krylov),
            froude_krylov_t: T::c(c.froude_krylov_t),
            mass: T::c(c.mass),
            added_mass: T::c(c.added_mass),
            added_mass_t: T::c(c.added_mass_t),
            wet_weight_z: T::c(c.wet_weight_z),
            compression: T::c(c.compression),
        }
    }
}

/// Kinematics of one element: its two nodes' states and the water at its midpoint.
#[derive(Clone, Copy, Debug)]
pub struct ElementInput<T> {
    /// Position of node a, m.
    pub ra: V3<T>,
    /// Position of node b, m.
    pub rb: V3<T>,
    /// Velocity of node a, m/s.
    pub va: V3<T>,
    /// Velocity of node b, m/s.
    pub vb: V3<T>,
    /// Unstretched length `l0`, m.
    pub l0: T,
    /// Current at the midpoint, m/s.
    pub current: V3<T>,
    /// Water acceleration at the midpoint, m/s^2.
    pub water_accel: V3<T>,
}

/// What an element contributes to its two nodes.
///
/// Node a receives `f_half + tension t - shear`, node b `f_half - tension t + shear`
/// (`shear` from the bending hinges, zero without them); each receives the
/// mass block `half_mass I + half_added (I - t t^T)`: `half_mass` is the element's half
/// mass along its tangent (material plus tangential added mass), `half_added` what its
/// normal plane has more (normal less tangential added mass), so that the block is
/// `(mbar l0 I + Cm rho A l0 wet P + Cat rho A l0 wet t t^T) / 2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ElementLoads<T> {
    /// Unit tangent `t = (r_b - r_a) / l`.
    pub t: V3<T>,
    /// Axial force `EA max(eps, 0) + EA c epsdot`, N (positive in tension).
    pub tension: T,
    /// Half of the external load `F_dn + F_dt + F_a + W`, N.
    pub f_half: V3<T>,
    /// Half of `(mbar + Cat rho A wet) l0`, kg: the mass along the tangent.
    pub half_mass: T,
    /// Half of `(Cm - Cat) rho A l0 wet`, kg: what the normal plane has more (negative
    /// when `Cat > Cm`).
    pub half_added: T,
    /// The bending shear of the element (`super::bending`), N: node b receives
    /// `+shear`, node a `-shear` (zero without bending stiffness).
    pub shear: V3<T>,
    /// The rate of the element's internal state: a viscoelastic line's `sdot`
    /// (`super::visco`), 1/s; zero for every other line.
    pub rate: T,
}

/// External load parts of an element, kept apart for the frame comparisons and tests.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExternalLoads<T> {
    /// Normal drag `F_dn`, N.
    pub drag_n: V3<T>,
    /// Tangential drag `F_dt`, N.
    pub drag_t: V3<T>,
    /// Water-acceleration load `F_a` (Froude-Krylov and added mass, across and along
    /// the element), N.
    pub froude_krylov: V3<T>,
    /// Weight less buoyancy `W`, N.
    pub wet_weight: V3<T>,
}

impl<T: Real> ExternalLoads<T> {
    /// Sum of the parts.
    #[inline(always)]
    pub fn total(&self) -> V3<T> {
        self.drag_n + self.drag_t + self.froude_krylov + self.wet_weight
    }
}

/// Axial force from stretch and stretch rate (paper Eq. 10 with the damping of Eq. 40).
#[inline(always)]
pub fn axial_force<T: Real>(c: &Coefs<T>, l: T, l0: T, t: V3<T>, dv: V3<T>) -> T {
    let eps = l / l0 - T::one();
    let epsdot = t.dot(dv) / l0;
    // Slack: the elastic part vanishes in compression unless the line is a rod.
    let elastic = c.ea
        * eps
        * if eps > T::zero() {
            T::one()
        } else {
            c.compression
        };
    elastic + c.ea_c * epsdot
}

/// GLMF external loads of an element with tangent `t` and current length `l`, wholly
/// under water.
#[inline(always)]
pub fn glmf_external<T: Real>(
    c: &Coefs<T>,
    e: &ElementInput<T>,
    t: V3<T>,
    l: T,
) -> ExternalLoads<T> {
    glmf_external_wet(c, e, t, l, T::one(), T::zero())
}

/// GLMF external loads of an element with tangent `t` and current length `l` of which
/// the fraction `wet` (see [`super::surface::wetted_fraction`]) is under water, in
/// gravity `gravity` (m/s^2). The water-acceleration load is [`froude_krylov`]'s.
/// Every water term (drag, the water-acceleration load, buoyancy) is taken times `wet`; the weight is `(mbar - wet rho A) l0 g`, written as
/// the wet weight less the buoyancy `(1 - wet) rho A g l0` of the dry part, with
/// `rho A g = wet_weight_z + mbar g`. At `wet = 1` every product is by one and the
/// subtraction is of zero, so a submerged element's loads are bit for bit those of
/// [`glmf_external`].
#[inline(always)]
pub fn glmf_external_wet<T: Real>(
    c: &Coefs<T>,
    e: &ElementInput<T>,
    t: V3<T>,
    l: T,
    wet: T,
    gravity: T,
) -> ExternalLoads<T> {
    let half = T::c(0.5);
    let vrel = e.current - (e.va + e.vb) * half;
    let vt = t.dot(vrel);
    let vn = vrel - t * vt; // P v_rel
    let buoyancy_z = c.wet_weight_z + c.mass * gravity;
    let weight_z = c.wet_weight_z - (T::one() - wet) * buoyancy_z;
    ExternalLoads {
        drag_n: vn * (c.drag_n * l * vn.norm() * wet),
        drag_t: t * (c.drag_t * l * vt.abs() * vt * wet),
        froude_krylov: froude_krylov(c, t, e.water_accel, e.l0 * wet),
        wet_weight: V3::new(T::zero(), T::zero(), weight_z * e.l0),
    }
}

/// The water-acceleration load on `vol_l0` metres of unstretched line with tangent `t`
/// in water accelerating at `aw` (its wetted length `l0 wet`): the undisturbed
/// pressure gradient `rho A a_w` on the displaced volume in every direction plus the
/// added masses, `(1 + Cm) rho A P a_w` across and `(1 + Cat) rho A (t . a_w) t`
/// along the line, per metre.
#[inline(always)]
pub fn froude_krylov<T: Real>(c: &Coefs<T>, t: V3<T>, aw: V3<T>, vol_l0: T) -> V3<T> {
    let at = t.dot(aw);
    let aw_n = aw - t * at; // P a_w
    aw_n * (c.froude_krylov * vol_l0) + t * (c.froude_krylov_t * vol_l0 * at)
}

/// The GLMF loads of one element wholly under water. A zero-length element gives
/// non-finite output, which the steppers' blow-up check reports with the element's
/// cable and time.
#[inline(always)]
pub fn glmf_element<T: Real>(c: &Coefs<T>, e: &ElementInput<T>) -> ElementLoads<T> {
    glmf_element_wet(c, e, T::one(), T::zero())
}

/// The GLMF loads of one element of which the fraction `wet` is under water (see
/// [`glmf_external_wet`]); its added masses, normal and tangential, are taken times
/// `wet` too. At `wet = 1` this is [`glmf_element`] bit for bit.
#[inline(always)]
pub fn glmf_element_wet<T: Real>(
    c: &Coefs<T>,
    e: &ElementInput<T>,
    wet: T,
    gravity: T,
) -> ElementLoads<T> {
    let d = e.rb - e.ra;
    let l = d.norm();
    let t = d / l;
    let tension = axial_force(c, l, e.l0, t, e.vb - e.va);
    let ext = glmf_external_wet(c, e, t, l, wet, gravity);
    let half = T::c(0.5);
    ElementLoads {
        t,
        tension,
        f_half: ext.total() * half,
        half_mass: (c.mass + c.added_mass_t * wet) * e.l0 * half,
        half_added: (c.added_mass - c.added_mass_t) * e.l0 * half * wet,
        shear: V3::zero(),
        rate: T::zero(),
    }
}
