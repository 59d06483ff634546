//! The node pass of the chain fast path: each node gathers its two padded elements,
//! adds its point weight, seabed load (damping and friction implicit in the symplectic
//! scheme) and the few per-node extra forces (point drag, a point's water acceleration,
//! winch mass flow), and solves its 3x3 mass block in closed form ([`node_kernel`]);
//! constrained nodes take their route's acceleration afterwards. Also the per-stage
//! masses ([`Masses`]) and the point-mass helpers that the network path shares.

use super::consts::ChainConsts;
use super::lanes::{chunks_for, col, keep_chunks, lanes, lanes_next, ColumnsView, Stride, KEEP};
use super::winch::{ale_mass_flow, extra_forces_clear, AleScratch};
use crate::cpu::passes::implicit_dt;
use crate::cpu::water::node_water;
use crate::math::{Sym3, V3};
use crate::model::{Layout, RouteState};
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

/// [`solve_mass`] where `D = s I` (no seabed) and `t1`, `t2` are unit tangents (or
/// zero, with `a = 0`, for a ghost element): then `G = [[1, g], [g, 1]] / s` with
/// `g = t1 . t2`, so the 2x2 system is `(s I - A T) c = A U^T f`, and the result
/// `(det f + c1 t1 + c2 t2) / (s det)` with `c` unscaled: three dot products and one
/// division instead of five and two. The same solution to round-off (`t . t` is 1 to
/// a few ulp); `det >= s (s - a1 - a2) > 0` as the original's.
#[inline(always)]
fn solve_mass_iso(s: f64, a1: f64, a2: f64, t1: [f64; 3], t2: [f64; 3], f: [f64; 3]) -> [f64; 3] {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (w1, w2, g) = (dot(t1, f), dot(t2, f), dot(t1, t2));
    let (m11, m22) = (s - a1, s - a2);
    let (a1g, a2g) = (a1 * g, a2 * g);
    let det = m11 * m22 - a1g * a2g;
    let (aw1, aw2) = (a1 * w1, a2 * w2);
    let c1 = m22 * aw1 + a1g * aw2;
    let c2 = m11 * aw2 + a2g * aw1;
    let r = 1.0 / (s * det);
    [
        (f[0] * det + c1 * t1[0] + c2 * t2[0]) * r,
        (f[1] * det + c1 * t1[1] + c2 * t2[1]) * r,
        (f[2] * det + c1 * t1[2] + c2 * t2[2]) * r,
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
    // Computed off the seabed too, then dropped: no branch, so the loops vectorise.
    let ch = if FRICTION {
        let ch = mukl * pen / (vx * vx + vy * vy).sqrt().max(v_eps);
        if on {
            ch
        } else {
            0.0
        }
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

/// Node pass: accelerations of every node into the block's `col::AX` columns, with
/// constraints fixed up afterwards, from its element results, point masses and extra
/// forces (module [`super::lanes`]'s `col`). `p` is the state the element pass used.
/// The few nodes with extra forces (point drag, a point's water-acceleration load,
/// mass flow) have them added to their force before the solve, as on the general path.
///
/// Nodes held on a free body (`held`: block-local node and its target, the body's
/// point now) take the target's acceleration as a route's; with `lumps`, each one's
/// force and mass block ([`held_load`]) is pushed there (block-local node first), for
/// its body to lump in (`cpu::free`).
///
/// # Safety
/// Every column of `c`, `p`, `m` and `wv` has at least
/// [`super::lanes::padded_len`]`(c.n)` entries, no slice of `wv`'s columns lives
/// during the call, `L` is 4 or 8, and every node of `held` is below `c.n`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) unsafe fn nodes<const FRICTION: bool, const L: usize, St: Stride>(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    time: f64,
    p: &[Vec<f64>; 6],
    m: &Masses,
    asc: &AleScratch,
    wv: &ColumnsView<'_, St>,
    held: &[(usize, RouteState)],
    lumps: Option<&mut Vec<(usize, V3<f64>, Sym3<f64>)>>,
) {
    // SAFETY (every use): the nodes of `c`'s lists and of the variable elements
    // (checked by `AleScratch::prepare`) are below `c.n`, and the caller's columns
    // are longer.
    macro_rules! get {
        ($col:expr, $i:expr) => {
            unsafe { *$col.get_unchecked($i) }
        };
    }
    macro_rules! set {
        ($col:expr, $i:expr) => {
            unsafe { $col.get_unchecked_mut($i) }
        };
    }
    // Bending: every node's hinge forces into the extra forces' columns (`=`; what
    // follows adds to them), from the tangents the element pass left.
    let bend = c.bend.is_some();
    if let Some(bd) = c.bend.as_deref() {
        // SAFETY: the caller's columns; a block with bending has the bending columns
        // (`advance_chain`), and `bd.kh` is padded with the rest.
        unsafe { super::bending::bending_forces(c.n, bd, p, wv) };
    }
    // SAFETY: the extra forces' columns, not reached otherwise until the node loop.
    let mut xf: [&mut [f64]; 3] = unsafe {
        [
            wv.col_mut(col::XFX),
            wv.col_mut(col::XFX + 1),
            wv.col_mut(col::XFX + 2),
        ]
    };
    // Winch cables: the mass-flow forces of Eq. 39 on the variable element's free nodes
    // (crate::ale; a held winch node's acceleration is its route's).
    // SAFETY: as above.
    let mut extra = unsafe { ale_mass_flow(asc, p, &mut xf) } || bend;
    let mut add = |xf: &mut [&mut [f64]; 3], i: usize, f: [f64; 3]| {
        for (x, fq) in xf.iter_mut().zip(f) {
            *set!(x, i) += fq;
        }
        extra = true;
    };
    for pd in &c.point_drag {
        let i = pd.0;
        let v = [get!(p[3], i), get!(p[4], i), get!(p[5], i)];
        let f = point_drag_force(lay, pd, get!(p[2], i), v, get!(m.eta, i), m.w);
        add(&mut xf, i, f);
    }
    if !m.w.is_empty() {
        for pv in &c.point_volume {
            let i = pv.0;
            add(
                &mut xf,
                i,
                point_water_accel_force(pv, get!(p[2], i), get!(m.eta, i), m.w),
            );
        }
    }
    // The symplectic scheme takes the seabed's damping implicitly (passes::implicit_dt).
    let h = implicit_dt(opts);
    // SAFETY: the caller's columns, as this function's.
    macro_rules! kernel_of {
        ($extra:literal, $seabed:literal) => {
            unsafe { node_kernel::<FRICTION, $extra, $seabed, L, St>(c, h, p, m, wv) }
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
        if let Some(out) = lumps {
            for &(i, _) in held {
                // SAFETY: as this function's; the extra forces are still in their columns.
                out.push(unsafe { held_load::<FRICTION, St>(c, i, p, m, wv) });
            }
        }
        // SAFETY: the extra forces' columns, not reached otherwise after the node loop.
        let mut xf: [&mut [f64]; 3] = unsafe {
            [
                wv.col_mut(col::XFX),
                wv.col_mut(col::XFX + 1),
                wv.col_mut(col::XFX + 2),
            ]
        };
        // SAFETY: as above (the nodes checked by `AleScratch::prepare`).
        unsafe { extra_forces_clear(asc, &mut xf) };
    } else {
        kernel!(false);
        if let Some(out) = lumps {
            for &(i, _) in held {
                // SAFETY: as this function's.
                out.push(unsafe { held_load::<FRICTION, St>(c, i, p, m, wv) });
            }
        }
    }
    for &(i, ri) in &c.constrained {
        // Held on a free body: its target below.
        if held.iter().any(|h| h.0 == i) {
            continue;
        }
        let d = route_accel(lay, opts, time, ri, |q| (get!(p[q], i), get!(p[3 + q], i)));
        for (q, dq) in d.into_iter().enumerate() {
            // SAFETY: an acceleration column, not reached otherwise here.
            let aq = unsafe { wv.col_mut(col::AX + q) };
            *set!(aq, i) = dq;
        }
    }
    // Held on a free body: the body's point now is the target (in place of the route).
    for (i, d) in held {
        let i = *i;
        let d = target_accel(opts, d, |q| (get!(p[q], i), get!(p[3 + q], i)));
        for (q, dq) in d.into_iter().enumerate() {
            // SAFETY: an acceleration column, not reached otherwise here.
            let aq = unsafe { wv.col_mut(col::AX + q) };
            *set!(aq, i) = dq;
        }
    }
}

/// The force on chain node `i` from everything but its constraint (its two padded
/// elements' tensions and loads, its point's weight and extra forces, the seabed's load
/// with its damping explicit) and its mass block (half masses, added masses, point
/// mass): what the node loop solves, as the general path's `node_accel_of` forms them,
/// for a node held on a free body. Returns `(i, force, mass block)`.
///
/// # Safety
/// As [`nodes`], `i < c.n`, after the element pass and before the extra forces are
/// cleared.
#[inline(never)]
unsafe fn held_load<const FRICTION: bool, St: Stride>(
    c: &ChainConsts,
    i: usize,
    p: &[Vec<f64>; 6],
    m: &Masses,
    wv: &ColumnsView<'_, St>,
) -> (usize, V3<f64>, Sym3<f64>) {
    use col::{FX, PM, PWZ, TEN, TX, XFX};
    // SAFETY: the caller's columns; padded elements `i` and `i + 1` exist.
    let at = |q: usize, k: usize| unsafe { *wv.col(q).get_unchecked(k) };
    let (j, k) = (i, i + 1);
    let tj = [at(TX, j), at(TX + 1, j), at(TX + 2, j)];
    let tk = [at(TX, k), at(TX + 1, k), at(TX + 2, k)];
    let (tnj, tnk) = (at(TEN, j), at(TEN, k));
    let mut g = [0.0; 3];
    for q in 0..3 {
        g[q] = at(FX + q, j) + at(FX + q, k) - tnj * tj[q] + tnk * tk[q] + at(XFX + q, i);
    }
    g[2] += at(PWZ, i);
    if FRICTION || c.zb.is_finite() {
        let (sb, _, _) = seabed_load::<FRICTION>(
            c.zb - p[2][i],
            [p[3][i], p[4][i], p[5][i]],
            m.kl[i],
            m.cl[i],
            m.mukl[i],
            c.v_eps,
        );
        for q in 0..3 {
            g[q] += sb[q];
        }
    }
    let (haj, hak) = (m.ha[j], m.ha[k]);
    let mut mm = Sym3::scalar(at(PM, i) + m.hm[j] + m.hm[k] + haj + hak);
    // `s I - a t t^T` for each element: `add_normal_projection` less its `a I`.
    for (a, t) in [(haj, tj), (hak, tk)] {
        mm.xx -= a * t[0] * t[0];
        mm.yy -= a * t[1] * t[1];
        mm.zz -= a * t[2] * t[2];
        mm.xy -= a * t[0] * t[1];
        mm.xz -= a * t[0] * t[2];
        mm.yz -= a * t[1] * t[2];
    }
    (i, V3::new(g[0], g[1], g[2]), mm)
}

/// The Baumgarte acceleration of a node held on target `d`; `state(q)` is its
/// position and velocity along axis `q`.
#[inline(always)]
pub(super) fn target_accel(
    opts: &SolverOptions,
    d: &RouteState,
    state: impl Fn(usize) -> (f64, f64),
) -> [f64; 3] {
    let bg = opts.baumgarte;
    let axis = |q: usize| {
        let (r, v) = state(q);
        d.a[q] - bg.beta * (v - d.v[q]) - bg.alpha * (r - d.r[q])
    };
    [axis(0), axis(1), axis(2)]
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
    // Wholly under water the wetted fraction is exactly 1 (`point_wetted_fraction`).
    let wet = if radius >= 0.0 && eta - z >= radius {
        1.0
    } else {
        point_wetted_fraction(eta - z, radius)
    };
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
    let d = lay.routes[route].eval_inline(time);
    let bg = opts.baumgarte;
    // Written out, not `std::array::from_fn` (see `net::node_pass`'s columns).
    let axis = |q: usize| {
        let (r, v) = state(q);
        d.a[q] - bg.beta * (v - d.v[q]) - bg.alpha * (r - d.r[q])
    };
    [axis(0), axis(1), axis(2)]
}

/// The node loop over `nc` whole chunks of nodes of the padded columns (module
/// [`super::lanes`]): node `i` gathers padded elements `i` and `i + 1`. The padding
/// nodes' accelerations are set to zero.
///
/// # Safety
/// As [`nodes`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn node_kernel<
    const FRICTION: bool,
    const EXTRA: bool,
    const SEABED: bool,
    const L: usize,
    St: Stride,
>(
    c: &ChainConsts,
    h: f64,
    p: &[Vec<f64>; 6],
    m: &Masses,
    wv: &ColumnsView<'_, St>,
) {
    let nc = chunks_for::<L>(c.n);
    // SAFETY (every use): the caller's columns hold `padded_len(c.n) >= nc * L + 1`
    // entries.
    macro_rules! at {
        ($s:expr) => {
            unsafe { lanes::<L>($s, nc) }
        };
    }
    macro_rules! next {
        ($s:expr) => {
            unsafe { lanes_next::<L>($s, nc) }
        };
    }
    // The block's columns: one base register, constant displacements with a fixed
    // stride. SAFETY (every use): as above; the accelerations are the only columns
    // written, and not read.
    macro_rules! bat {
        ($q:expr) => {
            unsafe { wv.lanes::<L>($q, 0, nc) }
        };
    }
    macro_rules! bnext {
        ($q:expr) => {
            unsafe { wv.lanes::<L>($q, 1, nc) }
        };
    }
    macro_rules! bout {
        ($q:expr) => {
            unsafe { wv.lanes_mut::<L>($q, 0, nc) }
        };
    }
    use col::{AX, FX, PM, PWZ, TEN, TX, XFX};
    let (z, vx, vy, vz) = (at!(&p[2]), at!(&p[3]), at!(&p[4]), at!(&p[5]));
    let (txj, tyj, tzj, tnj) = (bat!(TX), bat!(TX + 1), bat!(TX + 2), bat!(TEN));
    let (txk, tyk, tzk, tnk) = (bnext!(TX), bnext!(TX + 1), bnext!(TX + 2), bnext!(TEN));
    let (fxj, fyj, fzj) = (bat!(FX), bat!(FX + 1), bat!(FX + 2));
    let (fxk, fyk, fzk) = (bnext!(FX), bnext!(FX + 1), bnext!(FX + 2));
    let (xfx, xfy, xfz) = (bat!(XFX), bat!(XFX + 1), bat!(XFX + 2));
    let (hmj, hmk, haj, hak) = (at!(m.hm), next!(m.hm), at!(m.ha), next!(m.ha));
    let (pm, pwz, kl, cl, mukl) = (bat!(PM), bat!(PWZ), at!(m.kl), at!(m.cl), at!(m.mukl));
    let (ax, ay, az) = (bout!(AX), bout!(AX + 1), bout!(AX + 2));
    let (zb, v_eps) = (c.zb, c.v_eps);
    for i in 0..nc {
        keep_chunks();
        // Every input into locals first, then every output: no overlap to check.
        let (z, vx, vy, vz) = (z[i], vx[i], vy[i], vz[i]);
        let (txj, tyj, tzj, tnj) = (txj[i], tyj[i], tzj[i], tnj[i]);
        let (txk, tyk, tzk, tnk) = (txk[i], tyk[i], tzk[i], tnk[i]);
        let (fxj, fyj, fzj, fxk, fyk, fzk) = (fxj[i], fyj[i], fzj[i], fxk[i], fyk[i], fzk[i]);
        let (xfx, xfy, xfz) = (xfx[i], xfy[i], xfz[i]);
        let (hmj, hmk, haj, hak) = (hmj[i], hmk[i], haj[i], hak[i]);
        let (pm, pwz, kl, cl, mukl) = (pm[i], pwz[i], kl[i], cl[i], mukl[i]);
        let mut o = [[0.0; L]; 3];
        for l in 0..L {
            // Padded element i is element i-1 (this node is its b end: -T t), i+1 is
            // element i.
            let (tj, tk) = ([txj[l], tyj[l], tzj[l]], [txk[l], tyk[l], tzk[l]]);
            let (fj, fk) = ([fxj[l], fyj[l], fzj[l]], [fxk[l], fyk[l], fzk[l]]);
            let (tnj, tnk) = (tnj[l], tnk[l]);
            let mut g = [
                fj[0] + fk[0] - tnj * tj[0] + tnk * tk[0],
                fj[1] + fk[1] - tnj * tj[1] + tnk * tk[1],
                fj[2] + fk[2] - tnj * tj[2] + tnk * tk[2],
            ];
            g[2] += pwz[l];
            if EXTRA {
                g[0] += xfx[l];
                g[1] += xfy[l];
                g[2] += xfz[l];
            }
            let s = pm[l] + hmj[l] + hmk[l] + haj[l] + hak[l];
            // Seabed damping and friction implicit: (M + h diag(c_h, c_h, c_z)) a = F.
            // Without a seabed the diagonal is `s`: the shorter solve of a scalar one.
            let acc = if SEABED {
                let (sb, ch, cz) = seabed_load::<FRICTION>(
                    zb - z[l],
                    [vx[l], vy[l], vz[l]],
                    kl[l],
                    cl[l],
                    mukl[l],
                    v_eps,
                );
                g[2] += sb[2];
                if FRICTION {
                    g[0] += sb[0];
                    g[1] += sb[1];
                }
                let d = [s + h * ch, s + h * ch, s + h * cz];
                solve_mass(d, haj[l], hak[l], tj, tk, g)
            } else {
                solve_mass_iso(s, haj[l], hak[l], tj, tk, g)
            };
            [o[0][l], o[1][l], o[2][l]] = acc;
        }
        [ax[i], ay[i], az[i]] = o;
    }
    // The padding nodes stay at rest at zero (the symplectic update's check reads them;
    // their solve divides by a zero mass, and they gather the padding elements' NaN
    // tangents). They are the last chunk's lanes from `c.n` on: one AND a column on
    // that chunk with the lanes' bits (`KEEP`), `+0.0` as before, in vector code.
    if nc > 0 {
        let j = nc - 1;
        // The last chunk holds 1 to `L` nodes (`nc = chunks_for::<L>(c.n)`), and
        // `L <= MAX_LANES`.
        let k = c.n - j * L;
        debug_assert!((1..=L).contains(&k));
        // SAFETY: `k <= L <= MAX_LANES`, a row of the table, whose first `L` entries
        // are an `[u64; L]`.
        let keep = unsafe { &*KEEP.get_unchecked(k).as_ptr().cast::<[u64; L]>() };
        // Every input into locals first, then every output.
        let (x, y, z) = (ax[j], ay[j], az[j]);
        [ax[j], ay[j], az[j]] = [
            keep_lanes(x, keep),
            keep_lanes(y, keep),
            keep_lanes(z, keep),
        ];
    }
}

/// `v`'s lanes ANDed with `keep`'s bits (module [`super::lanes`]'s `KEEP`). A
/// function, not a closure: closures are not inlined into the AVX2 caller.
#[inline(always)]
fn keep_lanes<const L: usize>(v: [f64; L], keep: &[u64; L]) -> [f64; L] {
    let mut o = [0.0; L];
    for l in 0..L {
        o[l] = f64::from_bits(v[l].to_bits() & keep[l]);
    }
    o
}

/// The per-stage masses and seabed constants: the point masses and weights and the
/// added masses follow the water surface, the ALE variable element changes its half
/// masses and its nodes' seabed constants; otherwise they are the block's constants.
pub(super) struct Masses<'a> {
    /// Surface elevation over each node, m.
    pub(super) eta: &'a [f64],
    /// Per-node water values in waves (`cpu::water`), empty in still water.
    pub(super) w: &'a [f64],
    pub(super) hm: &'a [f64],
    pub(super) ha: &'a [f64],
    pub(super) kl: &'a [f64],
    pub(super) cl: &'a [f64],
    pub(super) mukl: &'a [f64],
}

/// The point masses and weights of the nodes whose point has a volume, less what the
/// share of it out of the water loses (its added mass and buoyancy). Under water
/// `dry` is 0 and the block's constants stand bit for bit.
///
/// # Safety
/// Every column of `c`, `p` and `eta`, `pm` and `pwz` has at least `c.n` entries (the
/// points' nodes are nodes of the block, as `nodes` relies on too): read and written
/// without bounds checks (about 10 instructions a step of Case 2 with its end mass).
#[inline(always)]
pub(super) unsafe fn point_surface(
    c: &ChainConsts,
    p: &[Vec<f64>; 6],
    eta: &[f64],
    pm: &mut [f64],
    pwz: &mut [f64],
) {
    for pv in &c.point_volume {
        let i = pv.0;
        debug_assert!(i < c.n);
        // SAFETY (every use): `i` is a node of the block, as the contract says.
        let depth = unsafe { *eta.get_unchecked(i) - *p[2].get_unchecked(i) };
        // `point_surface_at` with the block's own constants read unchecked.
        let radius = pv.1;
        let v = if radius >= 0.0 && depth >= radius {
            unsafe { (*c.pm.get_unchecked(i), *c.pwz.get_unchecked(i)) }
        } else {
            point_surface_at(c, pv, depth)
        };
        unsafe { (*pm.get_unchecked_mut(i), *pwz.get_unchecked_mut(i)) = v };
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
    // Wholly under water the wetted fraction is exactly 1 and `dry` 0, so the
    // block's constants stand bit for bit: no need to evaluate it.
    if radius >= 0.0 && depth >= radius {
        return (c.pm[i], c.pwz[i]);
    }
    let dry = 1.0 - point_wetted_fraction(depth, radius);
    (c.pm[i] - dry * added, c.pwz[i] - dry * buoyancy)
}
