//! The fast path of the CPU stepper for blocks that are one chain in node order
//! (mooring lines, towed cables: the common case).
//!
//! It runs the same two passes as the general path ([`super::passes`]), on the same
//! physics, but over structure-of-arrays scratch and without branches in the loops,
//! so the compiler vectorises them (4 lanes of f64 with AVX2, chosen at run time):
//! - the element pass reads node `k` and `k+1` for element `k` (no index arrays);
//! - element results are stored with a zero "ghost" element at each end, so node `i`
//!   always gathers padded elements `i` (element `i-1`, as its node b) and `i+1`
//!   (element `i`, as its node a);
//! - the 3x3 mass block `s I - a1 t1 t1^T - a2 t2 t2^T` of a chain node is solved in
//!   closed form (Woodbury identity: a 2x2 system instead of a 3x3 adjugate);
//! - the rare per-node extras (constrained nodes, point-mass drag) are fixed up after
//!   the vectorised loop, from short index lists.
//!
//! A test checks it against the general path (`tests/cpu/chain_kernel.rs`).

use super::passes::implicit_dt;
use super::water::{node_water, BlockWaves, Water};
use crate::ale::AleElem;
use crate::model::{Block, Current, Layout, NO_CONSTRAINT};
use crate::options::{Scheme, SolverOptions};
use crate::physics::{point_wetted_fraction, wetted_fraction};
use crate::step::{diverged, StepFailure};

mod net;
mod winch;
pub(crate) use net::{advance_net, advance_net_threaded, NetConsts, NetScratch};
use winch::{ale_constants, ale_mass_flow, ale_mass_flow_clear, ale_tension, AleScratch};

/// Per-block constants of a chain, built once.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChainConsts {
    n: usize,
    // Per element (length ne).
    l0: Vec<f64>,
    il0: Vec<f64>,
    ea: Vec<f64>,
    eac: Vec<f64>,
    comp: Vec<f64>,
    drag_n: Vec<f64>,
    drag_t: Vec<f64>,
    /// Half the element's weight less buoyancy (z), N.
    half_wz: Vec<f64>,
    /// Half the element's buoyancy `rho A g l0 / 2` (z), N, which its dry part loses.
    half_bz: Vec<f64>,
    /// Half the element's water-acceleration coefficient `(1 + Cm) rho A l0 / 2`, kg.
    half_fk: Vec<f64>,
    /// The element's diameter, m (its wetted fraction).
    diameter: Vec<f64>,
    /// Current profile per element.
    current: Vec<u32>,
    /// Line type per element (for the ALE variable element, evaluated apart).
    line: Vec<u32>,
    /// The block's current when every element shares one uniform current.
    uniform: Option<[f64; 3]>,
    // Per padded element (length ne + 2, ghosts zero).
    hm: Vec<f64>,
    ha: Vec<f64>,
    // Per node (length n).
    pm: Vec<f64>,
    pwz: Vec<f64>,
    /// `K lt`, `C lt`, `mu K lt` of the seabed per node.
    kl: Vec<f64>,
    cl: Vec<f64>,
    mukl: Vec<f64>,
    /// `(node, route index)` of constrained nodes.
    constrained: Vec<(usize, usize)>,
    /// `(node, 1/2 rho Cd A, current index, sphere radius)` of nodes with point drag.
    point_drag: Vec<(usize, f64, usize, f64)>,
    /// `(node, sphere radius, added mass, buoyancy, displaced mass)` of nodes whose
    /// point mass has a volume (what it loses out of the water, and its
    /// water-acceleration load `(1 + Ca) rho V a` in waves).
    point_volume: Vec<(usize, f64, f64, f64, f64)>,
    /// Tributary length per node (seabed contact), m.
    trib: Vec<f64>,
    /// Seabed `K`, `C`, `mu` (zero without a seabed).
    sb_k: f64,
    sb_c: f64,
    sb_mu: f64,
    zb: f64,
    friction: bool,
    v_eps: f64,
}

impl ChainConsts {
    /// Folds the layout's constants for chain block `b`.
    pub(crate) fn new(lay: &Layout, b: &Block) -> Self {
        let n0 = b.node_start as usize;
        let n = (b.node_end - b.node_start) as usize;
        let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
        let ne = e1 - e0;
        let env = &lay.env;
        let mut c = ChainConsts {
            n,
            ..Default::default()
        };
        c.hm = vec![0.0; ne + 2];
        c.ha = vec![0.0; ne + 2];
        for (k, e) in (e0..e1).enumerate() {
            let lc = &lay.line_coefs[lay.elem_line[e] as usize];
            let l0 = lay.elem_l0[e];
            c.l0.push(l0);
            c.il0.push(1.0 / l0);
            c.ea.push(lc.ea);
            c.eac.push(lc.ea_c);
            c.comp.push(lc.compression);
            c.drag_n.push(lc.drag_n);
            c.drag_t.push(lc.drag_t);
            c.half_wz.push(0.5 * lc.wet_weight_z * l0);
            c.half_bz
                .push(0.5 * (lc.wet_weight_z + lc.mass * env.gravity) * l0);
            c.half_fk.push(0.5 * lc.froude_krylov * l0);
            c.diameter
                .push(lay.line_types[lay.elem_line[e] as usize].diameter);
            c.current.push(lay.elem_current[e]);
            c.line.push(lay.elem_line[e]);
            c.hm[k + 1] = 0.5 * lc.mass * l0;
            c.ha[k + 1] = 0.5 * lc.added_mass * l0;
        }
        let first = c.current.first().copied().unwrap_or(0);
        if c.current.iter().all(|&x| x == first) && lay.currents[first as usize].table.len() <= 1 {
            c.uniform = Some(lay.currents[first as usize].at::<f64>(0.0).to_f64());
        }
        let has_seabed = env.depth.is_finite();
        for li in 0..n {
            let i = n0 + li;
            c.pm.push(lay.node_point_mass[i]);
            c.pwz.push(lay.node_point_weight_z[i]);
            let lt = if has_seabed {
                lay.node_tributary[i]
            } else {
                0.0
            };
            c.trib.push(lt);
            c.kl.push(env.seabed.stiffness * lt);
            c.cl.push(env.seabed.damping * lt);
            c.mukl.push(env.seabed.friction * env.seabed.stiffness * lt);
            let k = lay.node_constraint[i];
            if k != NO_CONSTRAINT {
                c.constrained.push((li, k as usize));
            }
            if lay.node_point_drag[i] > 0.0 {
                c.point_drag.push((
                    li,
                    lay.node_point_drag[i],
                    lay.node_current[i] as usize,
                    lay.node_point_radius[i],
                ));
            }
            if lay.node_point_radius[i] > 0.0 {
                c.point_volume.push((
                    li,
                    lay.node_point_radius[i],
                    lay.node_point_added[i],
                    lay.node_point_displaced[i] * env.gravity,
                    lay.node_point_displaced[i],
                ));
            }
        }
        if has_seabed {
            (c.sb_k, c.sb_c, c.sb_mu) = (
                env.seabed.stiffness,
                env.seabed.damping,
                env.seabed.friction,
            );
        }
        c.zb = if has_seabed {
            -env.depth
        } else {
            f64::NEG_INFINITY
        };
        c.friction = has_seabed && env.seabed.friction > 0.0;
        c.v_eps = env.seabed.friction_velocity;
        c
    }
}

impl ChainConsts {
    /// Makes `self` a copy of `o`, reusing `self`'s arrays (a run of steps of a winch
    /// cable edits a working copy of its block's constants).
    fn copy_from(&mut self, o: &ChainConsts) {
        let ChainConsts {
            n,
            l0,
            il0,
            ea,
            eac,
            comp,
            drag_n,
            drag_t,
            half_wz,
            half_bz,
            half_fk,
            diameter,
            current,
            line,
            uniform,
            hm,
            ha,
            pm,
            pwz,
            kl,
            cl,
            mukl,
            constrained,
            point_drag,
            point_volume,
            trib,
            sb_k,
            sb_c,
            sb_mu,
            zb,
            friction,
            v_eps,
        } = self;
        *n = o.n;
        for (d, s) in [
            (l0, &o.l0),
            (il0, &o.il0),
            (ea, &o.ea),
            (eac, &o.eac),
            (comp, &o.comp),
            (drag_n, &o.drag_n),
            (drag_t, &o.drag_t),
            (half_wz, &o.half_wz),
            (half_bz, &o.half_bz),
            (half_fk, &o.half_fk),
            (diameter, &o.diameter),
            (hm, &o.hm),
            (ha, &o.ha),
            (pm, &o.pm),
            (pwz, &o.pwz),
            (kl, &o.kl),
            (cl, &o.cl),
            (mukl, &o.mukl),
            (trib, &o.trib),
        ] {
            d.clone_from(s);
        }
        current.clone_from(&o.current);
        line.clone_from(&o.line);
        *uniform = o.uniform;
        constrained.clone_from(&o.constrained);
        point_drag.clone_from(&o.point_drag);
        point_volume.clone_from(&o.point_volume);
        (*sb_k, *sb_c, *sb_mu, *zb, *friction, *v_eps) =
            (o.sb_k, o.sb_c, o.sb_mu, o.zb, o.friction, o.v_eps);
    }

    /// Re-reads the constraint numbers of block `b` of `lay` (the same chain as the one
    /// these constants were made for, possibly renumbered by a rebuild).
    pub(crate) fn refresh_constraints(&mut self, lay: &Layout, b: &Block) {
        debug_assert_eq!(self.n, (b.node_end - b.node_start) as usize);
        self.constrained.clear();
        for li in 0..self.n {
            let k = lay.node_constraint[b.node_start as usize + li];
            if k != NO_CONSTRAINT {
                self.constrained.push((li, k as usize));
            }
        }
    }
}

/// Structure-of-arrays state and scratch of one chain, reused across blocks.
#[derive(Default)]
pub(crate) struct ChainScratch {
    x: [Vec<f64>; 6],
    // Stage state and accumulators of the Runge-Kutta schemes.
    xs: [Vec<f64>; 6],
    x0: [Vec<f64>; 6],
    sum: [Vec<f64>; 6],
    a: [Vec<f64>; 3],
    w: Work,
    /// Winch cables: the working copy of the block's constants that the variable
    /// elements change every stage, and what the run keeps about them.
    wc: ChainConsts,
    ale: AleScratch,
}

/// What one evaluation writes.
#[derive(Default)]
struct Work {
    // Per-element water velocity (current, plus waves) and wave acceleration.
    u: [Vec<f64>; 3],
    aw: [Vec<f64>; 3],
    // Surface elevation over each node, m (zero in still water).
    eta: Vec<f64>,
    // Padded element results; `haw` the half normal added masses times the elements'
    // wetted fractions.
    t: [Vec<f64>; 3],
    ten: Vec<f64>,
    f: [Vec<f64>; 3],
    haw: Vec<f64>,
    // Per node: point mass and point weight less buoyancy, less what a point mass
    // partly out of the water loses.
    pm: Vec<f64>,
    pwz: Vec<f64>,
    // Per node: the extra forces (point drag, water acceleration of a point, mass flow)
    // that the node loop adds before its solve; zero but at the few nodes that have them.
    xf: [Vec<f64>; 3],
}

fn resize(v: &mut [Vec<f64>], n: usize) {
    for x in v {
        x.clear();
        x.resize(n, 0.0);
    }
}

/// Element pass over SoA positions and velocities `p`, currents `u`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn elements<const WAVES: bool>(
    c: &ChainConsts,
    p: &[Vec<f64>; 6],
    u: &[Vec<f64>; 3],
    aw: &[Vec<f64>; 3],
    eta: &[f64],
    t: &mut [Vec<f64>; 3],
    ten: &mut [f64],
    f: &mut [Vec<f64>; 3],
    haw: &mut [f64],
) {
    let ne = c.l0.len();
    let [tx, ty, tz] = t;
    let [fx, fy, fz] = f;
    // Every node at or below the surface (the common case: a line in still water, or
    // deep in waves) makes every wetted fraction exactly 1 (`wetted_fraction`'s first
    // case), so the loop without it gives the same bits, and stays vectorised.
    let submerged = eta[..ne + 1]
        .iter()
        .zip(&p[2][..ne + 1])
        .fold(true, |all, (e, z)| all & (e - z >= 0.0));
    macro_rules! kernel {
        ($submerged:literal) => {
            element_kernel::<WAVES, $submerged>(
                [
                    &p[0][..ne],
                    &p[1][..ne],
                    &p[2][..ne],
                    &p[3][..ne],
                    &p[4][..ne],
                    &p[5][..ne],
                    &eta[..ne],
                ],
                [
                    &p[0][1..ne + 1],
                    &p[1][1..ne + 1],
                    &p[2][1..ne + 1],
                    &p[3][1..ne + 1],
                    &p[4][1..ne + 1],
                    &p[5][1..ne + 1],
                    &eta[1..ne + 1],
                ],
                &u[0][..ne],
                &u[1][..ne],
                &u[2][..ne],
                &aw[0][..ne],
                &aw[1][..ne],
                &aw[2][..ne],
                c,
                0,
                &mut tx[1..ne + 1],
                &mut ty[1..ne + 1],
                &mut tz[1..ne + 1],
                &mut ten[1..ne + 1],
                &mut fx[1..ne + 1],
                &mut fy[1..ne + 1],
                &mut fz[1..ne + 1],
                &mut haw[1..ne + 1],
            )
        };
    }
    if submerged {
        kernel!(true)
    } else {
        kernel!(false)
    }
}

/// The element loop over elements `e0..e0 + tx.len()` of the block's constants `c`.
/// Every array is its own parameter: `&mut [f64]` parameters are known not to alias,
/// which is what lets the compiler vectorise the loop (arrays reached through one
/// `&mut [Vec<f64>; 3]` would need run-time overlap checks). `a` and `b` are the
/// elements' end nodes, `[x, y, z, vx, vy, vz, eta]` per element (for a chain, the
/// node arrays and the same shifted by one; for a network, gathered by index).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn element_kernel<const WAVES: bool, const SUBMERGED: bool>(
    a: [&[f64]; 7],
    b: [&[f64]; 7],
    ux: &[f64],
    uy: &[f64],
    uz: &[f64],
    awx: &[f64],
    awy: &[f64],
    awz: &[f64],
    c: &ChainConsts,
    e0: usize,
    tx: &mut [f64],
    ty: &mut [f64],
    tz: &mut [f64],
    ten: &mut [f64],
    fx: &mut [f64],
    fy: &mut [f64],
    fz: &mut [f64],
    haw: &mut [f64],
) {
    let ne = tx.len();
    // Slices cut one by one: `array::map` here is a call per stage (not inlined).
    let [xa, ya, za, vxa, vya, vza, eta_a] = a;
    let [xb, yb, zb, vxb, vyb, vzb, eta_b] = b;
    let (xa, ya, za, vxa, vya, vza, eta_a) = (
        &xa[..ne],
        &ya[..ne],
        &za[..ne],
        &vxa[..ne],
        &vya[..ne],
        &vza[..ne],
        &eta_a[..ne],
    );
    let (xb, yb, zb, vxb, vyb, vzb, eta_b) = (
        &xb[..ne],
        &yb[..ne],
        &zb[..ne],
        &vxb[..ne],
        &vyb[..ne],
        &vzb[..ne],
        &eta_b[..ne],
    );
    let (ux, uy, uz) = (&ux[..ne], &uy[..ne], &uz[..ne]);
    let haw = &mut haw[..ne];
    let e1 = e0 + ne;
    let (hb, ha) = (&c.half_bz[e0..e1], &c.ha[e0 + 1..e1 + 1]);
    let (awx, awy, awz, hfk) = (&awx[..ne], &awy[..ne], &awz[..ne], &c.half_fk[e0..e1]);
    let diam = &c.diameter[e0..e1];
    let (ty, tz, ten, fx, fy, fz) = (
        &mut ty[..ne],
        &mut tz[..ne],
        &mut ten[..ne],
        &mut fx[..ne],
        &mut fy[..ne],
        &mut fz[..ne],
    );
    let (il0, ea, eac, comp) = (
        &c.il0[e0..e1],
        &c.ea[e0..e1],
        &c.eac[e0..e1],
        &c.comp[e0..e1],
    );
    let (dn, dt, hw) = (&c.drag_n[e0..e1], &c.drag_t[e0..e1], &c.half_wz[e0..e1]);
    for k in 0..ne {
        let (dx, dy, dz) = (xb[k] - xa[k], yb[k] - ya[k], zb[k] - za[k]);
        let l = (dx * dx + dy * dy + dz * dz).sqrt();
        let il = 1.0 / l;
        let (ex, ey, ez) = (dx * il, dy * il, dz * il);
        let eps = l * il0[k] - 1.0;
        let epsdot =
            (ex * (vxb[k] - vxa[k]) + ey * (vyb[k] - vya[k]) + ez * (vzb[k] - vza[k])) * il0[k];
        // Slack: the elastic part vanishes in compression unless the line is a rod.
        let elastic = ea[k] * eps * if eps > 0.0 { 1.0 } else { comp[k] };
        let tension = elastic + eac[k] * epsdot;
        let rx = ux[k] - 0.5 * (vxa[k] + vxb[k]);
        let ry = uy[k] - 0.5 * (vya[k] + vyb[k]);
        let rz = uz[k] - 0.5 * (vza[k] + vzb[k]);
        let vt = ex * rx + ey * ry + ez * rz;
        let (nx, ny, nz) = (rx - ex * vt, ry - ey * vt, rz - ez * vt);
        // Water terms times the wetted fraction; the dry part loses its buoyancy.
        let wet = if SUBMERGED {
            1.0
        } else {
            wetted_fraction(eta_a[k] - za[k], eta_b[k] - zb[k], diam[k])
        };
        let kn = dn[k] * l * (nx * nx + ny * ny + nz * nz).sqrt() * wet;
        let kt = dt[k] * l * vt.abs() * vt * wet;
        // Half of drag, plus half the weight less buoyancy (no water acceleration yet).
        fx[k] = 0.5 * (nx * kn + ex * kt);
        fy[k] = 0.5 * (ny * kn + ey * kt);
        fz[k] = 0.5 * (nz * kn + ez * kt) + (hw[k] - (1.0 - wet) * hb[k]);
        if WAVES {
            // Froude-Krylov and added mass on the normal wave acceleration P a_w.
            let an = ex * awx[k] + ey * awy[k] + ez * awz[k];
            let kf = hfk[k] * wet;
            fx[k] += kf * (awx[k] - ex * an);
            fy[k] += kf * (awy[k] - ey * an);
            fz[k] += kf * (awz[k] - ez * an);
        }
        haw[k] = ha[k] * wet;
        tx[k] = ex;
        ty[k] = ey;
        tz[k] = ez;
        ten[k] = tension;
    }
}

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
fn nodes<const FRICTION: bool>(
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

/// The node loop (see [`element_kernel`] for why every array is a parameter).
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

/// The symplectic Euler update `v += a dt`, then `x += v dt`, of the first `n` nodes
/// of the SoA state `x`, and the number of them whose new state is non-finite or over
/// the limits ([`count_bad`]'s test), in one loop.
#[inline(always)]
fn symplectic_update(
    x: &mut [Vec<f64>; 6],
    a: &[Vec<f64>; 3],
    n: usize,
    dt: f64,
    vmax: f64,
    rmax: f64,
) -> usize {
    let [px, py, pz, vx, vy, vz] = x;
    let (px, py, pz) = (&mut px[..n], &mut py[..n], &mut pz[..n]);
    let (vx, vy, vz) = (&mut vx[..n], &mut vy[..n], &mut vz[..n]);
    let (ax, ay, az) = (&a[0][..n], &a[1][..n], &a[2][..n]);
    let mut bad = 0usize;
    for i in 0..n {
        vx[i] += ax[i] * dt;
        vy[i] += ay[i] * dt;
        vz[i] += az[i] * dt;
        px[i] += vx[i] * dt;
        py[i] += vy[i] * dt;
        pz[i] += vz[i] * dt;
        // `&`, not `&&`: no short circuit, so the loop vectorises. NaN fails every `<`.
        let ok = (px[i].abs() < rmax)
            & (py[i].abs() < rmax)
            & (pz[i].abs() < rmax)
            & (vx[i].abs() < vmax)
            & (vy[i].abs() < vmax)
            & (vz[i].abs() < vmax);
        bad += (!ok) as usize;
    }
    bad
}

/// `x += v h` elementwise.
#[inline(always)]
fn axpy(x: &mut [f64], v: &[f64], h: f64) {
    let v = &v[..x.len()];
    for i in 0..x.len() {
        x[i] += v[i] * h;
    }
}

/// `out = x + v h` elementwise.
#[inline(always)]
fn xpvh(out: &mut [f64], x: &[f64], v: &[f64], h: f64) {
    let (x, v) = (&x[..out.len()], &v[..out.len()]);
    for i in 0..out.len() {
        out[i] = x[i] + v[i] * h;
    }
}

/// The per-stage masses and seabed constants: the point masses and weights and the
/// added masses follow the water surface, the ALE variable element changes its half
/// masses and its nodes' seabed constants; otherwise they are the block's constants.
struct Masses<'a> {
    /// Surface elevation over each node, m.
    eta: &'a [f64],
    /// Per-node water values in waves (`cpu::water`), empty in still water.
    w: &'a [f64],
    pm: &'a [f64],
    pwz: &'a [f64],
    hm: &'a [f64],
    ha: &'a [f64],
    kl: &'a [f64],
    cl: &'a [f64],
    mukl: &'a [f64],
}

/// The point masses and weights of the nodes whose point has a volume, less what the
/// share of it out of the water loses (its added mass and buoyancy). Under water
/// `dry` is 0 and the block's constants stand bit for bit.
#[inline(always)]
fn point_surface(c: &ChainConsts, p: &[Vec<f64>; 6], eta: &[f64], pm: &mut [f64], pwz: &mut [f64]) {
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

/// Fills the per-element current (midpoint height) when the block's is not uniform.
#[inline(always)]
fn currents(c: &ChainConsts, currents: &[Current], p: &[Vec<f64>; 6], u: &mut [Vec<f64>; 3]) {
    let ne = c.l0.len();
    if let Some(un) = c.uniform {
        for (q, uq) in u.iter_mut().enumerate() {
            uq[..ne].fill(un[q]);
        }
        return;
    }
    for k in 0..ne {
        let v = currents[c.current[k] as usize]
            .at::<f64>(0.5 * (p[2][k] + p[2][k + 1]))
            .to_f64();
        for q in 0..3 {
            u[q][k] = v[q];
        }
    }
}

/// Waves: adds the mean of each element's two nodes' wave velocities to its water
/// velocity `u`, writes the mean of their wave accelerations to `aw`, and each node's
/// surface elevation to `eta`, from the per-node water values `w`.
#[inline(always)]
fn add_waves(ne: usize, w: &[f64], u: &mut [Vec<f64>; 3], aw: &mut [Vec<f64>; 3], eta: &mut [f64]) {
    for (i, e) in eta.iter_mut().enumerate() {
        *e = node_water(w, i).0;
    }
    for k in 0..ne {
        let (_, ua, aa) = node_water(w, k);
        let (_, ub, ab) = node_water(w, k + 1);
        for q in 0..3 {
            u[q][k] += 0.5 * (ua[q] + ub[q]);
            aw[q][k] = 0.5 * (aa[q] + ab[q]);
        }
    }
}

/// Counts nodes whose new state is non-finite or over the limits.
#[inline(always)]
fn count_bad(p: &[Vec<f64>; 6], n: usize, vmax: f64, rmax: f64) -> usize {
    let mut bad = 0usize;
    let p: [&[f64]; 6] = [
        &p[0][..n],
        &p[1][..n],
        &p[2][..n],
        &p[3][..n],
        &p[4][..n],
        &p[5][..n],
    ];
    #[allow(clippy::needless_range_loop)] // six arrays indexed together
    for i in 0..n {
        // `&`, not `&&`: no short circuit, so the loop vectorises. NaN fails every `<`.
        let ok = (p[0][i].abs() < rmax)
            & (p[1][i].abs() < rmax)
            & (p[2][i].abs() < rmax)
            & (p[3][i].abs() < vmax)
            & (p[4][i].abs() < vmax)
            & (p[5][i].abs() < vmax);
        bad += (!ok) as usize;
    }
    bad
}

/// Advances a chain block; `r`, `v` are its AoS state (block-local).
#[allow(clippy::too_many_arguments)]
pub(crate) fn advance_chain(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            return unsafe {
                advance_chain_avx2(
                    c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps,
                )
            };
        }
    }
    advance_chain_body(
        c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps,
    )
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn advance_chain_avx2(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    advance_chain_body(
        c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps,
    )
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn advance_chain_body(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    if c.friction {
        advance_chain_scheme::<true>(
            c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps,
        )
    } else {
        advance_chain_scheme::<false>(
            c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps,
        )
    }
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn advance_chain_scheme<const FRICTION: bool>(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    let n = c.n;
    let ne = c.l0.len();
    let mut waves = waves;
    if waves.is_none() {
        wbuf.clear();
    }
    resize(&mut sc.x, n);
    resize(&mut sc.a, n);
    resize(&mut sc.w.t, ne + 2);
    resize(&mut sc.w.f, ne + 2);
    sc.w.ten.clear();
    sc.w.ten.resize(ne + 2, 0.0);
    resize(&mut sc.w.u, ne);
    resize(&mut sc.w.aw, ne);
    sc.w.eta.clear();
    sc.w.eta.resize(n, 0.0);
    sc.w.haw.clear();
    sc.w.haw.resize(ne + 2, 0.0);
    sc.w.pm.clone_from(&c.pm);
    sc.w.pwz.clone_from(&c.pwz);
    if opts.scheme != Scheme::Symplectic {
        resize(&mut sc.xs, n);
        resize(&mut sc.x0, n);
        resize(&mut sc.sum, n);
    }
    for i in 0..n {
        sc.x[0][i] = r[i].x;
        sc.x[1][i] = r[i].y;
        sc.x[2][i] = r[i].z;
        sc.x[3][i] = v[i].x;
        sc.x[4][i] = v[i].y;
        sc.x[5][i] = v[i].z;
    }
    resize(&mut sc.w.xf, n);
    if c.uniform.is_some() && waves.is_none() {
        currents(c, &lay.currents, &sc.x, &mut sc.w.u);
    }
    // Always: the scratch may hold the previous block's variable elements.
    sc.ale.prepare(c, lay, ale);
    if !ale.is_empty() {
        sc.wc.copy_from(c);
    }
    let ChainScratch {
        x,
        xs,
        x0,
        sum,
        a,
        w: wk,
        wc,
        ale: asc,
    } = sc;
    // A function, not a closure: closures are not inlined into the AVX2 caller and
    // would be compiled for the baseline target.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn eval<const FRICTION: bool>(
        c: &ChainConsts,
        wc: &mut ChainConsts,
        asc: &mut AleScratch,
        lay: &Layout,
        opts: &SolverOptions,
        ale: &[AleElem],
        state: &[Vec<f64>; 6],
        time: f64,
        waves: &mut Option<&mut BlockWaves>,
        wbuf: &mut Water,
        sc: &mut Work,
        a: &mut [Vec<f64>; 3],
    ) {
        let Work {
            u,
            aw,
            eta,
            t,
            ten,
            f,
            haw,
            pm,
            pwz,
            xf,
        } = sc;
        // Winch cables: the variable elements' constants at this time.
        let c = if ale.is_empty() {
            c
        } else {
            ale_constants(asc, time, wc);
            &*wc
        };
        // A uniform current in still water was filled once for the run.
        if c.uniform.is_none() || waves.is_some() {
            currents(c, &lay.currents, state, u);
        }
        if let Some(wb) = waves.as_deref_mut() {
            let st = |i: usize| {
                (
                    [state[0][i], state[1][i], state[2][i]],
                    [state[3][i], state[4][i], state[5][i]],
                )
            };
            if wb.exact() {
                wb.fill(time, c.n, st, wbuf);
                add_waves(c.l0.len(), wbuf, u, aw, eta);
            } else {
                // The per-node values are needed only by the point masses' loads
                // (`nodes`); the elements read the cache's columns.
                if !c.point_drag.is_empty() || !c.point_volume.is_empty() {
                    wb.fill(time, c.n, st, wbuf);
                }
                wb.fill_chain(time, c.n, st, eta, u, aw);
            }
            elements::<true>(c, state, u, aw, eta, t, ten, f, haw);
        } else {
            elements::<false>(c, state, u, aw, eta, t, ten, f, haw);
        }
        ale_tension(asc, state, ten);
        point_surface(c, state, eta, pm, pwz);
        let m = Masses {
            eta,
            w: wbuf,
            pm,
            pwz,
            hm: &c.hm,
            ha: haw,
            kl: &c.kl,
            cl: &c.cl,
            mukl: &c.mukl,
        };
        nodes::<FRICTION>(c, lay, opts, time, state, t, ten, f, &m, asc, xf, a);
    }
    let mut result = Ok(());
    let mut bad = 0;
    for k in 0..nsteps {
        let time = (step0 + k) as f64 * dt;
        match opts.scheme {
            Scheme::Symplectic => {
                eval::<FRICTION>(c, wc, asc, lay, opts, ale, x, time, &mut waves, wbuf, wk, a);
                bad = symplectic_update(x, a, n, dt, opts.max_speed, opts.max_distance);
            }
            Scheme::Rk2 => {
                let h = 0.5 * dt;
                eval::<FRICTION>(c, wc, asc, lay, opts, ale, x, time, &mut waves, wbuf, wk, a);
                for q in 0..3 {
                    xpvh(&mut xs[q][..n], &x[q], &x[3 + q], h);
                    xpvh(&mut xs[3 + q][..n], &x[3 + q], &a[q], h);
                }
                eval::<FRICTION>(
                    c,
                    wc,
                    asc,
                    lay,
                    opts,
                    ale,
                    xs,
                    time + h,
                    &mut waves,
                    wbuf,
                    wk,
                    a,
                );
                let (pos, vel) = x.split_at_mut(3);
                for q in 0..3 {
                    axpy(&mut pos[q][..n], &xs[3 + q], dt);
                    axpy(&mut vel[q][..n], &a[q], dt);
                }
            }
            Scheme::Rk4 => {
                let h = 0.5 * dt;
                for q in 0..6 {
                    x0[q].copy_from_slice(&x[q]);
                    xs[q].copy_from_slice(&x[q]);
                    sum[q].fill(0.0);
                }
                for (stage, (tau, w, next)) in
                    [(0.0, 1.0, h), (h, 2.0, h), (h, 2.0, dt), (dt, 1.0, 0.0)]
                        .into_iter()
                        .enumerate()
                {
                    eval::<FRICTION>(
                        c,
                        wc,
                        asc,
                        lay,
                        opts,
                        ale,
                        xs,
                        time + tau,
                        &mut waves,
                        wbuf,
                        wk,
                        a,
                    );
                    let (spos, svel) = xs.split_at_mut(3);
                    for q in 0..3 {
                        axpy(&mut sum[q][..n], &svel[q], w);
                        axpy(&mut sum[3 + q][..n], &a[q], w);
                        if stage < 3 {
                            xpvh(&mut spos[q][..n], &x0[q], &svel[q], next);
                            xpvh(&mut svel[q][..n], &x0[3 + q], &a[q], next);
                        }
                    }
                }
                for q in 0..6 {
                    xpvh(&mut x[q][..n], &x0[q], &sum[q], dt / 6.0);
                }
            }
        }
        if opts.scheme != Scheme::Symplectic {
            bad = count_bad(x, n, opts.max_speed, opts.max_distance);
        }
        if bad > 0 {
            let i = (0..n)
                .find(|&i| {
                    !(x[0][i].abs() < opts.max_distance
                        && x[1][i].abs() < opts.max_distance
                        && x[2][i].abs() < opts.max_distance
                        && x[3][i].abs() < opts.max_speed
                        && x[4][i].abs() < opts.max_speed
                        && x[5][i].abs() < opts.max_speed)
                })
                .unwrap_or(0);
            result = Err((i, time + dt));
            break;
        }
    }
    for i in 0..n {
        r[i] = crate::math::V3::new(x[0][i], x[1][i], x[2][i]);
        v[i] = crate::math::V3::new(x[3][i], x[4][i], x[5][i]);
    }
    result.map_err(|(i, time)| diverged(opts, r[i], v[i], n0 + i, time))
}
