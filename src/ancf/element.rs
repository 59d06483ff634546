//! Loads of one ANCF cable element, integrated by Gauss quadrature (paper Eqs. 40-44,
//! 47, 49-50; the choices are listed in the module doc of [`crate::ancf`]).
//!
//! The element's 12 coordinates are `[r_a, r'_a, r_b, r'_b]`, read as four 3-vectors
//! `q_k`; its generalized force is four 3-vectors `Q_k`, and the force vector
//! acting on coordinate `q_k` from a load `f` per unit unstretched length is
//! `int S_k f dx`.

use super::shape::{gauss_legendre, hermite, AleShapeAt, ShapeAt};
use crate::math::V3;
use crate::model::Current;
use crate::physics::{froude_krylov, seabed_force, Coefs, SeabedCoefs};

type V = V3<f64>;

/// Line constants of the ANCF element: the GLMF constants plus bending.
#[derive(Clone, Copy, Debug, Default)]
pub struct AncfCoefs {
    /// The GLMF line constants (drag, added mass, weight, `EA`, `EA c`, slack rule).
    pub line: Coefs<f64>,
    /// Bending stiffness `EI`, N m^2.
    pub ei: f64,
    /// `EI c`, N m^2 s (bending damping with the same time constant as the axial).
    pub ei_c: f64,
}

/// One quadrature point of an element: where, how much, and the shape functions there.
#[derive(Clone, Copy, Debug, Default)]
pub struct GaussPoint {
    /// `xi = x / L` in `(0, 1)`.
    pub xi: f64,
    /// Quadrature weight times the element length, m.
    pub dx: f64,
    /// Shape functions and derivatives at `xi`.
    pub shape: ShapeAt,
}

/// The `n`-point Gauss rule of an element of length `l` (m).
pub fn gauss_points(l: f64, n: usize) -> Vec<GaussPoint> {
    let (xs, ws) = gauss_legendre(n);
    xs.iter()
        .zip(&ws)
        .map(|(&xi, &w)| GaussPoint {
            xi,
            dx: w * l,
            shape: hermite(l, xi),
        })
        .collect()
}

/// Water and seabed as the element sees them.
#[derive(Clone, Copy, Debug)]
pub struct ElementEnv<'a> {
    /// Current profile.
    pub current: &'a Current,
    /// The current's value when it is uniform (skips the profile lookup).
    pub uniform_current: Option<V>,
    /// Water acceleration `a_w`, m/s^2 (uniform).
    pub water_accel: V,
    /// Seabed, when there is one.
    pub seabed: Option<SeabedCoefs<f64>>,
}

/// Kinematics at one point of an element.
#[derive(Clone, Copy, Debug, Default)]
pub struct PointKinematics {
    /// Position `r`, m.
    pub r: V,
    /// Velocity, m/s.
    pub rd: V,
    /// Slope `r' = dr/dx` (unit length in the unstretched state).
    pub r1: V,
    /// Slope rate, 1/s.
    pub r1d: V,
    /// `r'' = d^2 r/dx^2`, 1/m.
    pub r2: V,
    /// Rate of `r''`, 1/(m s).
    pub r2d: V,
}

#[inline(always)]
fn vec_at(q: &[f64], k: usize) -> V {
    V::new(q[3 * k], q[3 * k + 1], q[3 * k + 2])
}

/// Interpolates positions, slopes, curvature vectors and their rates at one point from
/// the element coordinates `q` and rates `qd` (12 each).
#[inline(always)]
pub fn kinematics(sh: &ShapeAt, q: &[f64], qd: &[f64]) -> PointKinematics {
    let mut p = PointKinematics::default();
    for k in 0..4 {
        let (x, xd) = (vec_at(q, k), vec_at(qd, k));
        p.r += x * sh.s[k];
        p.rd += xd * sh.s[k];
        p.r1 += x * sh.ds[k];
        p.r1d += xd * sh.ds[k];
        p.r2 += x * sh.dds[k];
        p.r2d += xd * sh.dds[k];
    }
    p
}

/// Axial strain `eps0 = (r'.r' - 1)/2`, its rate, and the axial stress resultant
/// `N = EA g(eps0) eps0 + EA c eps0dot` (per unit unstretched slope: the force vector
/// across a section is `N r'`, its magnitude, the tension, `N |r'|`). `g` is the slack
/// rule: 1 in tension, `compression` (0 or 1) otherwise.
#[inline(always)]
pub fn axial(c: &Coefs<f64>, p: &PointKinematics) -> (f64, f64, f64) {
    let eps0 = 0.5 * (p.r1.norm2() - 1.0);
    let eps0d = p.r1.dot(p.r1d);
    let gate = if eps0 > 0.0 { 1.0 } else { c.compression };
    (eps0, eps0d, c.ea * gate * eps0 + c.ea_c * eps0d)
}

/// Curvature `kappa = |r'' x r'| / |r'|^3` and the two vectors giving its gradient:
/// `d kappa / d q_k = S_k' g1 - S_k'' g2`, so `kappadot = g1.r1d - g2.r2d`. At zero
/// curvature the gradient is taken as zero (the elastic force `EI kappa dkappa/dq` is
/// continuous there; only the damping term's direction is undefined).
#[inline(always)]
pub fn curvature(p: &PointKinematics) -> (f64, V, V) {
    let c = p.r2.cross(p.r1);
    let cn = c.norm();
    let l1 = p.r1.norm();
    let inv3 = 1.0 / (l1 * l1 * l1);
    let kappa = cn * inv3;
    if cn == 0.0 {
        return (0.0, V::zero(), V::zero());
    }
    let ch = c / cn;
    let g1 = ch.cross(p.r2) * inv3 - p.r1 * (3.0 * kappa / (l1 * l1));
    let g2 = ch.cross(p.r1) * inv3;
    (kappa, g1, g2)
}

/// External load per unit unstretched length at a point (paper Eqs. 42 and 49-50):
/// normal and tangential drag on the relative velocity (on the stretched length, as the
/// GLMF's `l`), the water-acceleration load, weight less buoyancy, seabed contact.
#[inline(always)]
pub fn external_load(c: &Coefs<f64>, env: &ElementEnv, p: &PointKinematics) -> V {
    let u = match env.uniform_current {
        Some(u) => u,
        None => env.current.at(p.r.z),
    };
    let vrel = u - p.rd;
    let stretch = p.r1.norm();
    let t = p.r1 / stretch;
    let vt = t.dot(vrel);
    let vn = vrel - t * vt; // P v_rel
    let mut f = vn * (c.drag_n * stretch * vn.norm())
        + t * (c.drag_t * stretch * vt.abs() * vt)
        + froude_krylov(c, t, env.water_accel, 1.0);
    f.z += c.wet_weight_z;
    if let Some(s) = &env.seabed {
        // Eq. 49: the nodal law with unit tributary length is the law per metre.
        f += seabed_force(s, 1.0, p.r, p.rd);
    }
    f
}

/// The ALE terms of the variable (winch) element of an ALE-ANCF cable at one
/// evaluation (see [`AleShapeAt`]): the element's length changes at `ldot` (the payout
/// rate) and `lddot`.
#[derive(Clone, Copy, Debug)]
pub struct AleLoad<'a> {
    /// [`AleShapeAt`] at each Gauss point of the element.
    pub shapes: &'a [AleShapeAt],
    /// `dl/dt`, m/s.
    pub ldot: f64,
    /// `d2l/dt2`, m/s^2.
    pub lddot: f64,
}

/// Adds the convective (ALE) parts of the material rates to `p` (velocity, slope rate,
/// rate of `r''`) and returns the convective acceleration `rddot_p` (Eq. 36).
#[inline(always)]
pub fn ale_kinematics(
    al: &AleShapeAt,
    ldot: f64,
    lddot: f64,
    q: &[f64],
    qd: &[f64],
    p: &mut PointKinematics,
) -> V {
    let (mut dq, mut dqd, mut d2q, mut d1, mut d2) =
        (V::zero(), V::zero(), V::zero(), V::zero(), V::zero());
    for k in 0..4 {
        let (x, xd) = (vec_at(q, k), vec_at(qd, k));
        dq += x * al.d[k];
        dqd += xd * al.d[k];
        d2q += x * al.d2[k];
        d1 += x * al.d_ds[k];
        d2 += x * al.d_dds[k];
    }
    p.rd += dq * ldot;
    p.r1d += d1 * ldot;
    p.r2d += d2 * ldot;
    dqd * (2.0 * ldot) + dq * lddot + d2q * (ldot * ldot)
}

/// Adds the element's generalized force (internal and external) at coordinates `q`
/// and rates `qd` to `f` (12 entries each). When `tangents` is given it receives the
/// unit tangent at each Gauss point (for the normal added mass).
///
/// With `ale` (the variable element of an ALE-ANCF cable) the velocity, strain rate
/// and curvature rate are the material ones (convective parts included: drag and
/// damping see the material, not the mesh), and the mass-flow force
/// `-int mbar S_k rddot_p dx` of Eq. 39 is added, with the cable's own `mbar` (the
/// reading of Eq. 39's density argued in [`crate::ale`]).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn element_forces(
    c: &AncfCoefs,
    gps: &[GaussPoint],
    env: &ElementEnv,
    q: &[f64],
    qd: &[f64],
    f: &mut [f64],
    mut tangents: Option<&mut [V]>,
    ale: Option<&AleLoad>,
) {
    let mut acc = [V::zero(); 4];
    for (g, gp) in gps.iter().enumerate() {
        let sh = &gp.shape;
        let mut p = kinematics(sh, q, qd);
        let mut flow = V::zero();
        if let Some(a) = ale {
            let rpp = ale_kinematics(&a.shapes[g], a.ldot, a.lddot, q, qd, &mut p);
            flow = rpp * (-c.line.mass);
        }
        let (_, _, n) = axial(&c.line, &p);
        let fe = (external_load(&c.line, env, &p) + flow) * gp.dx;
        let ax = p.r1 * (n * gp.dx);
        let (mut bm, mut g1, mut g2) = (0.0, V::zero(), V::zero());
        if c.ei > 0.0 {
            let (kappa, a, b) = curvature(&p);
            let kd = a.dot(p.r1d) - b.dot(p.r2d);
            bm = (c.ei * kappa + c.ei_c * kd) * gp.dx;
            g1 = a;
            g2 = b;
        }
        for (k, a) in acc.iter_mut().enumerate() {
            *a += fe * sh.s[k] - ax * sh.ds[k] - (g1 * sh.ds[k] - g2 * sh.dds[k]) * bm;
        }
        if let Some(ts) = tangents.as_deref_mut() {
            ts[g] = p.r1 / p.r1.norm();
        }
    }
    for k in 0..4 {
        f[3 * k] += acc[k].x;
        f[3 * k + 1] += acc[k].y;
        f[3 * k + 2] += acc[k].z;
    }
}

/// Strain energy of the element, J: `int (EA/2 g eps0^2 + EI/2 kappa^2) dx` by the same
/// quadrature as the forces (whose elastic parts are its exact gradient).
pub fn strain_energy(c: &AncfCoefs, gps: &[GaussPoint], q: &[f64]) -> f64 {
    let zero = [0.0; 12];
    gps.iter()
        .map(|gp| {
            let p = kinematics(&gp.shape, q, &zero);
            let eps0 = 0.5 * (p.r1.norm2() - 1.0);
            let gate = if eps0 > 0.0 { 1.0 } else { c.line.compression };
            let (kappa, _, _) = curvature(&p);
            gp.dx * (0.5 * c.line.ea * gate * eps0 * eps0 + 0.5 * c.ei * kappa * kappa)
        })
        .sum()
}
