//! The node pass of the chain fast path: each node gathers its two padded elements,
//! adds its point weight, seabed load (damping and friction implicit in the symplectic
//! scheme) and the few per-node extra forces (point drag, a point's water acceleration,
//! winch mass flow), and solves its 3x3 mass block in closed form ([`node_kernel`]);
//! constrained nodes take their route's acceleration afterwards. Also the per-stage
//! masses ([`Masses`]) and the point-mass helpers that the network path shares.

use super::consts::ChainConsts;
use super::winch::{ale_mass_flow, ale_mass_flow_clear, AleScratch};
use crate::cpu::passes::implicit_dt;
use crate::cpu::water::node_water;
use crate::model::Layout;
use crate::options::SolverOptions;
use crate::physics::point_wetted_fraction;

/// Solves the chain node's mass block `D - a1 t1 t1^T - a2 t2 t2^T` for `f`, with
/// `D = diag(d)`: the scalar mass `s` on the diagonal plus the seabed's implicit damping
/// `dt c` (Woodbury identity with a diagonal `D`: a 2x2 system, written so that `a = 0`
/// of a ghost element needs no division by it).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn solve_mass(d: [f64; 3], a1: f64, a2: f64, t1: [f64; 3], t2: [f64; 3], f: [f64; 3]) -> [f64; 3] {
    let id = [1.0 / d[0], 1.0 / d[1], 1.0 / d[2]];
    let (u1, u2) = (
        [t1[0] * id[0], t1[1] * id[1], t1[2] * id[2]],
        [t2[0] * id[0], t2[1] * id[1], t2[2] * id[2]],
    );
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (w1, w2) = (dot(u1, f), dot(u2, f));
    let (g11, g22, g12) = (dot(u1, t1), dot(u2, t2), dot(u1, t2));
    // (I - A G) c = A w with A = diag(a1, a2), G = U^T D^-1 U.
    let (m11, m22) = (1.0 - a1 * g11, 1.0 - a2 * g22);
    let (m12, m21) = (-a1 * g12, -a2 * g12);
    let idet = 1.0 / (m11 * m22 - m12 * m21);
    let (aw1, aw2) = (a1 * w1, a2 * w2);
    let c1 = (m22 * aw1 - m12 * aw2) * idet;
    let c2 = (m11 * aw2 - m21 * aw1) * idet;
    [
        (f[0] + c1 * t1[0] + c2 * t2[0]) * id[0],
        (f[1] + c1 * t1[1] + c2 * t2[1]) * id[1],
        (f[2] + c1 * t1[2] + c2 * t2[2]) * id[2],
    ]
}

/// The seabed's damping slopes `(c_h, c_z)` on a chain node penetrating by `pen` and
/// sliding at `(vx, vy)` (physics::seabed_damping): `C lt` normal, and the regularised
/// friction's `mu K lt pen / max(|v_h|, v_eps)`; zero off the seabed.
#[inline(always)]
fn contact_slopes<const FRICTION: bool>(
    pen: f64,
    vx: f64,
    vy: f64,
    cl: f64,
    mukl: f64,
    v_eps: f64,
) -> (f64, f64) {
    let on = pen > 0.0;
    let cz = if on { cl } else { 0.0 };
    let ch = if FRICTION && on {
        mukl * pen / (vx * vx + vy * vy).sqrt().max(v_eps)
    } else {
        0.0
    };
    (ch, cz)
}

/// The seabed's load on a node penetrating by `pen` with velocity `v` (`kl`, `cl`,
/// `mukl` its `K lt`, `C lt`, `mu K lt`): `([-c_h vx, -c_h vy, K lt pen - c_z vz], c_h,
/// c_z)` on the seabed (the friction terms only with `FRICTION`), zero off it.
#[inline(always)]
pub(super) fn seabed_load<const FRICTION: bool>(
    pen: f64,
    v: [f64; 3],
    kl: f64,
    cl: f64,
    mukl: f64,
    v_eps: f64,
) -> ([f64; 3], f64, f64) {
    let on = pen > 0.0;
    let (ch, cz) = contact_slopes::<FRICTION>(pen, v[0], v[1], cl, mukl, v_eps);
    let gz = if on { kl * pen - cz * v[2] } else { 0.0 };
    ([-(ch * v[0]), -(ch * v[1]), gz], ch, cz)
}

/// Node pass: accelerations of every node into `a`, with constraints fixed up
/// afterwards. `p` is the state the element pass used. The few nodes with extra forces
/// (point drag, a point's water-acceleration load, mass flow) have them added to their
/// force before the solve, as on the general path.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn nodes<const FRICTION: bool>(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    time: f64,
    p: &[Vec<f64>; 6],
    tv: &[Vec<f64>; 3],
    ten: &[f64],
    fv: &[Vec<f64>; 3],
    m: &Masses,
    asc: &AleScratch,
    xf: &mut [Vec<f64>; 3],
    a: &mut [Vec<f64>; 3],
) {
    // Winch cables: the mass-flow forces of Eq. 39 on the variable element's free nodes
    // (crate::ale; a held winch node's acceleration is its route's).
    let mut extra = ale_mass_flow(asc, p, xf);
    let mut add = |xf: &mut [Vec<f64>; 3], i: usize, f: [f64; 3]| {
        for (x, fq) in xf.iter_mut().zip(f) {
            x[i] += fq;
        }
        extra = true;
    };
    for pd in &c.point_drag {
        let i = pd.0;
        let f = point_drag_force(lay, pd, p[2][i], [p[3][i], p[4][i], p[5][i]], m.eta[i], m.w);
        add(xf, i, f);
    }
    if !m.w.is_empty() {
        for pv in &c.point_volume {
            let i = pv.0;
            add(xf, i, point_water_accel_force(pv, p[2][i], m.eta[i], m.w));
        }
    }
    let [ax, ay, az] = a;
    // The symplectic scheme takes the seabed's damping implicitly (passes::implicit_dt).
    let h = implicit_dt(opts);
    macro_rules! kernel_of {
        ($extra:literal, $seabed:literal) => {
            node_kernel::<FRICTION, $extra, $seabed>(
                c, h, &p[2], &p[3], &p[4], &p[5], &tv[0], &tv[1], &tv[2], ten, &fv[0], &fv[1],
                &fv[2], &xf[0], &xf[1], &xf[2], m.pm, m.pwz, m.hm, m.ha, m.kl, m.cl, m.mukl, ax,
                ay, az,
            )
        };
    }
    // Without a seabed (friction needs one) the node loop skips the contact terms.
    let seabed = FRICTION || c.zb.is_finite();
    macro_rules! kernel {
        ($extra:literal) => {
            if seabed {
                kernel_of!($extra, true)
            } else {
                kernel_of!($extra, false)
            }
        };
    }
    if extra {
        kernel!(true);
        ale_mass_flow_clear(asc, xf);
        for i in c
            .point_drag
            .iter()
            .map(|pd| pd.0)
            .chain(c.point_volume.iter().map(|pv| pv.0))
        {
            for x in xf.iter_mut() {
                x[i] = 0.0;
            }
        }
    } else {
        kernel!(false);
    }
    for &(i, ri) in &c.constrained {
        let d = route_accel(lay, opts, time, ri, |q| (p[q][i], p[3 + q][i]));
        for (q, aq) in a.iter_mut().enumerate() {
            aq[i] = d[q];
        }
    }
}

/// Point-mass drag on node `pd.0` (a `point_drag` entry) at height `z`, velocity `v`,
/// under surface `eta`, on the wet share of the point; `w` the per-node water values
/// (empty in still water).
#[inline(always)]
pub(super) fn point_drag_force(
    lay: &Layout,
    &(i, pd, ci, radius): &(usize, f64, usize, f64),
    z: f64,
    v: [f64; 3],
    eta: f64,
    w: &[f64],
) -> [f64; 3] {
    let wet = point_wetted_fraction(eta - z, radius);
    let mut u = lay.currents[ci].at::<f64>(z).to_f64();
    if !w.is_empty() {
        let (_, uw, _) = node_water(w, i);
        u = [u[0] + uw[0], u[1] + uw[1], u[2] + uw[2]];
    }
    let r = [u[0] - v[0], u[1] - v[1], u[2] - v[2]];
    let k = pd * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt() * wet;
    [r[0] * k, r[1] * k, r[2] * k]
}

/// Waves: the water-acceleration load `(1 + Ca) rho V a` of the wet share of the point
/// of node `pv.0` (a `point_volume` entry) at height `z` under surface `eta`; `w` the
/// per-node water values (not empty).
#[inline(always)]
pub(super) fn point_water_accel_force(
    &(i, radius, added, _, displaced): &(usize, f64, f64, f64, f64),
    z: f64,
    eta: f64,
    w: &[f64],
) -> [f64; 3] {
    let (_, _, aw) = node_water(w, i);
    let k = (displaced + added) * point_wetted_fraction(eta - z, radius);
    [aw[0] * k, aw[1] * k, aw[2] * k]
}

/// The Baumgarte acceleration of a node held on route `route` at `time`; `state(q)` is
/// its position and velocity along axis `q`.
#[inline(always)]
pub(super) fn route_accel(
    lay: &Layout,
    opts: &SolverOptions,
    time: f64,
    route: usize,
    state: impl Fn(usize) -> (f64, f64),
) -> [f64; 3] {
    let d = lay.routes[route].eval(time);
    let bg = opts.baumgarte;
    std::array::from_fn(|q| {
        let (r, v) = state(q);
        d.a[q] - bg.beta * (v - d.v[q]) - bg.alpha * (r - d.r[q])
    })
}

/// The node loop (see [`super::elements::element_kernel`] for why every array is a parameter).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn node_kernel<const FRICTION: bool, const EXTRA: bool, const SEABED: bool>(
    c: &ChainConsts,
    h: f64,
    z: &[f64],
    vx: &[f64],
    vy: &[f64],
    vz: &[f64],
    tx: &[f64],
    ty: &[f64],
    tz: &[f64],
    tn: &[f64],
    fx: &[f64],
    fy: &[f64],
    fz: &[f64],
    xfx: &[f64],
    xfy: &[f64],
    xfz: &[f64],
    pm: &[f64],
    pwz: &[f64],
    hm: &[f64],
    ha: &[f64],
    kl: &[f64],
    cl: &[f64],
    mukl: &[f64],
    ax: &mut [f64],
    ay: &mut [f64],
    az: &mut [f64],
) {
    let n = c.n;
    let (z, vx, vy, vz) = (&z[..n], &vx[..n], &vy[..n], &vz[..n]);
    let (tx, ty, tz, tn) = (&tx[..n + 1], &ty[..n + 1], &tz[..n + 1], &tn[..n + 1]);
    let (fx, fy, fz) = (&fx[..n + 1], &fy[..n + 1], &fz[..n + 1]);
    let (xfx, xfy, xfz) = (&xfx[..n], &xfy[..n], &xfz[..n]);
    let (hm, ha) = (&hm[..n + 1], &ha[..n + 1]);
    let (pm, pwz, kl, cl, mukl) = (&pm[..n], &pwz[..n], &kl[..n], &cl[..n], &mukl[..n]);
    let (ax, ay, az) = (&mut ax[..n], &mut ay[..n], &mut az[..n]);
    let (zb, v_eps) = (c.zb, c.v_eps);
    for i in 0..n {
        // Padded element i is element i-1 (this node is its b end: -T t), i+1 is element i.
        let (j, k) = (i, i + 1);
        let mut gx = fx[j] + fx[k] - tn[j] * tx[j] + tn[k] * tx[k];
        let mut gy = fy[j] + fy[k] - tn[j] * ty[j] + tn[k] * ty[k];
        let mut gz = fz[j] + fz[k] - tn[j] * tz[j] + tn[k] * tz[k] + pwz[i];
        if EXTRA {
            gx += xfx[i];
            gy += xfy[i];
            gz += xfz[i];
        }
        let s = pm[i] + hm[j] + hm[k] + ha[j] + ha[k];
        // Seabed damping and friction implicit: (M + h diag(c_h, c_h, c_z)) a = F.
        // Without a seabed the diagonal is `s` (what `s + h 0` is, bit for bit).
        let d = if SEABED {
            let (sb, ch, cz) = seabed_load::<FRICTION>(
                zb - z[i],
                [vx[i], vy[i], vz[i]],
                kl[i],
                cl[i],
                mukl[i],
                v_eps,
            );
            gz += sb[2];
            if FRICTION {
                gx += sb[0];
                gy += sb[1];
            }
            [s + h * ch, s + h * ch, s + h * cz]
        } else {
            [s, s, s]
        };
        let acc = solve_mass(
            d,
            ha[j],
            ha[k],
            [tx[j], ty[j], tz[j]],
            [tx[k], ty[k], tz[k]],
            [gx, gy, gz],
        );
        ax[i] = acc[0];
        ay[i] = acc[1];
        az[i] = acc[2];
    }
}

/// The per-stage masses and seabed constants: the point masses and weights and the
/// added masses follow the water surface, the ALE variable element changes its half
/// masses and its nodes' seabed constants; otherwise they are the block's constants.
pub(super) struct Masses<'a> {
    /// Surface elevation over each node, m.
    pub(super) eta: &'a [f64],
    /// Per-node water values in waves (`cpu::water`), empty in still water.
    pub(super) w: &'a [f64],
    pub(super) pm: &'a [f64],
    pub(super) pwz: &'a [f64],
    pub(super) hm: &'a [f64],
    pub(super) ha: &'a [f64],
    pub(super) kl: &'a [f64],
    pub(super) cl: &'a [f64],
    pub(super) mukl: &'a [f64],
}

/// The point masses and weights of the nodes whose point has a volume, less what the
/// share of it out of the water loses (its added mass and buoyancy). Under water
/// `dry` is 0 and the block's constants stand bit for bit.
#[inline(always)]
pub(super) fn point_surface(
    c: &ChainConsts,
    p: &[Vec<f64>; 6],
    eta: &[f64],
    pm: &mut [f64],
    pwz: &mut [f64],
) {
    for pv in &c.point_volume {
        let i = pv.0;
        (pm[i], pwz[i]) = point_surface_at(c, pv, eta[i] - p[2][i]);
    }
}

/// The point mass and weight of node `pv.0` (a `point_volume` entry) whose point is
/// `depth` under the surface, less what its share out of the water loses.
#[inline(always)]
pub(super) fn point_surface_at(
    c: &ChainConsts,
    &(i, radius, added, buoyancy, _): &(usize, f64, f64, f64, f64),
    depth: f64,
) -> (f64, f64) {
    let dry = 1.0 - point_wetted_fraction(depth, radius);
    (c.pm[i] - dry * added, c.pwz[i] - dry * buoyancy)
}
