//! The element pass of the chain fast path: per-element water velocity (currents,
//! waves), then the branch-free element loop ([`element_kernel`], shared with the
//! network path) writing unit tangents, tensions, half drag plus half weight less
//! buoyancy, and the wetted half added masses into the padded element columns.

use super::consts::ChainConsts;
use crate::cpu::water::node_water;
use crate::model::Current;
use crate::physics::wetted_fraction;

/// Element pass over SoA positions and velocities `p`, currents `u`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn elements<const WAVES: bool>(
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

/// Fills the per-element current (midpoint height) when the block's is not uniform.
#[inline(always)]
pub(super) fn currents(
    c: &ChainConsts,
    currents: &[Current],
    p: &[Vec<f64>; 6],
    u: &mut [Vec<f64>; 3],
) {
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
pub(super) fn add_waves(
    ne: usize,
    w: &[f64],
    u: &mut [Vec<f64>; 3],
    aw: &mut [Vec<f64>; 3],
    eta: &mut [f64],
) {
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
