//! The network path's node pass over one tile of nodes: the point loads, the node loop
//! (each node's slots summed in incidence order, the seabed, the 3x3 solve; vectorised
//! over nodes), held nodes' routes, then the symplectic update and the limits check in
//! one loop, which also finds whether the tile's nodes end the step at or below still
//! water's surface (the tile's flag, which spares the element pass its test of a run:
//! [`super::NetScratch::under`]).

use super::super::consts::ChainConsts;
use super::super::nodes::{
    point_drag_force, point_surface_at, point_water_accel_force, route_accel, seabed_load,
};
use super::{loads_len, NetConsts, Work, COLS, CS, NT};
use crate::cpu::passes::implicit_dt;
use crate::math::{Sym3, V3};
use crate::model::Layout;
use crate::options::SolverOptions;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

/// The entries of `list` (sorted by node, its first field) whose node is in `nr`.
fn listed<'a, T>(list: &'a [T], node: impl Fn(&T) -> usize, nr: &Range<usize>) -> &'a [T] {
    let lo = list.partition_point(|p| node(p) < nr.start);
    let hi = list.partition_point(|p| node(p) < nr.end);
    &list[lo..hi]
}

/// [`node_pass`] with the block's friction flag (`nc.c.friction`) turned into its
/// constant: the one place that chooses between the two, for the one-thread steps
/// ([`super::advance_net`]) and the threaded ones. A macro, not an `#[inline(always)]`
/// function over `node_pass`: both inline to the same arithmetic, but the function
/// made LLVM lay out the rest of the step (the element code around it) otherwise, 1.4 %
/// more instructions a node-step of the net cage (callgrind), the macro none.
/// `node_pass_either!(nc, lay, opts, time, dt, nr, x, eta, w, sum, g, under)`.
macro_rules! node_pass_either {
    ($nc:expr, $($arg:expr),+ $(,)?) => {
        if $nc.c.friction {
            node_pass::<true>($nc, $($arg),+)
        } else {
            node_pass::<false>($nc, $($arg),+)
        }
    };
}
pub(super) use node_pass_either;

/// The node pass over the nodes `nr` of one tile (`x`: their state, updated in place
/// by a symplectic step of `dt`), reading what the elements add to them from the
/// tile's buffer `sum` (`super::Loads`); `eta`, `w` over the whole block. Sets `under`
/// (the tile's flag of [`super::NetScratch::under`]) to whether every new `z` is at or
/// below zero. Returns the block-local index of the first node whose new state is over
/// the limits.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn node_pass<const FRICTION: bool>(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    time: f64,
    dt: f64,
    nr: Range<usize>,
    x: [&mut [f64]; 6],
    eta: &[f64],
    w: &[f64],
    sum: &[f64],
    g: &mut Work,
    under: &AtomicBool,
) -> Option<usize> {
    let c = &nc.c;
    let n0 = nr.start;
    let len = nr.len();
    let point_drag = listed(&c.point_drag, |p| p.0, &nr);
    let point_volume = listed(&c.point_volume, |p| p.0, &nr);
    // Point masses and weights: the constants, or where a point has a volume, a copy
    // with the surface's share of it at the listed nodes.
    let (pm, pwz) = if point_volume.is_empty() {
        (&c.pm[nr.clone()], &c.pwz[nr.clone()])
    } else {
        g.pm[..len].copy_from_slice(&c.pm[nr.clone()]);
        g.pwz[..len].copy_from_slice(&c.pwz[nr.clone()]);
        for pv in point_volume {
            let i = pv.0;
            (g.pm[i - n0], g.pwz[i - n0]) = point_surface_at(c, pv, eta[i] - x[2][i - n0]);
        }
        (&g.pm[..len], &g.pwz[..len])
    };
    for pd in point_drag {
        let j = pd.0 - n0;
        let v = [x[3][j], x[4][j], x[5][j]];
        let f = point_drag_force(lay, pd, x[2][j], v, eta[pd.0], w);
        for (e, fq) in g.ex.iter_mut().zip(f) {
            e[j] += fq;
        }
    }
    // Screen-model nets: each knot's share of its panels' loads (super::Work::screen).
    let screen = listed(&g.screen, |p| p.0, &nr);
    for &(i, f) in screen {
        for (e, fq) in g.ex.iter_mut().zip(f) {
            e[i - n0] += fq;
        }
    }
    if !w.is_empty() {
        for pv in point_volume {
            let j = pv.0 - n0;
            let f = point_water_accel_force(pv, x[2][j], eta[pv.0], w);
            for (e, fq) in g.ex.iter_mut().zip(f) {
                e[j] += fq;
            }
        }
    }
    assert_eq!(sum.len(), loads_len(1, nc.width));
    let h = implicit_dt(opts);
    // Each its own parameter: the kernel's stores need no run-time overlap checks.
    let [ax, ay, az] = g.acc.each_mut().map(|q| &mut q[..]);
    macro_rules! kernel {
        ($width:literal) => {
            node_kernel::<$width, FRICTION>(
                c,
                h,
                sum,
                nr.clone(),
                [&x[2][..], &x[3][..], &x[4][..], &x[5][..]],
                pm,
                pwz,
                [&g.ex[0][..len], &g.ex[1][..len], &g.ex[2][..len]],
                [&c.kl[nr.clone()], &c.cl[nr.clone()], &c.mukl[nr.clone()]],
                ax,
                ay,
                az,
            )
        };
    }
    if nc.width == 4 {
        kernel!(4)
    } else {
        kernel!(8)
    }
    // The point loads back to zero for the next tile.
    for &i in point_drag
        .iter()
        .map(|p| &p.0)
        .chain(point_volume.iter().map(|p| &p.0))
        .chain(screen.iter().map(|p| &p.0))
    {
        for q in 0..3 {
            g.ex[q][i - n0] = 0.0;
        }
    }
    for &(i, ri) in listed(&c.constrained, |p| p.0, &nr) {
        let j = i - n0;
        let d = route_accel(lay, opts, time, ri, |q| (x[q][j], x[3 + q][j]));
        for (a, dq) in g.acc.iter_mut().zip(d) {
            a[j] = dq;
        }
    }
    let [px, py, pz, vx, vy, vz] = x;
    let [ax, ay, az] = g.acc.each_ref().map(|q| &q[..]);
    let (rmax, vmax) = (opts.max_distance, opts.max_speed);
    let (bad, above) = update_over(px, py, pz, vx, vy, vz, ax, ay, az, dt, rmax, vmax);
    // Read by the next step's element pass (after the barriers when threaded).
    under.store(above == 0, Ordering::Relaxed);
    if bad == 0 {
        return None;
    }
    first_bad([&*px, &*py, &*pz, &*vx, &*vy, &*vz], opts)
}

/// The symplectic update of a tile's nodes (`v += a dt`, then `p += v dt`, per
/// coordinate), the count of nodes whose new state is non-finite or over the limits
/// (`rmax` on each coordinate, `vmax` on each velocity component), and the count of
/// those whose new `z` is not at or below zero (still water's surface), in one loop:
/// the new state is checked while still in registers. Every array its own parameter:
/// no run-time overlap checks before the vector loop.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn update_over(
    px: &mut [f64],
    py: &mut [f64],
    pz: &mut [f64],
    vx: &mut [f64],
    vy: &mut [f64],
    vz: &mut [f64],
    ax: &[f64],
    ay: &[f64],
    az: &[f64],
    dt: f64,
    rmax: f64,
    vmax: f64,
) -> (usize, usize) {
    let n = px.len();
    let (py, pz, vx, vy, vz) = (
        &mut py[..n],
        &mut pz[..n],
        &mut vx[..n],
        &mut vy[..n],
        &mut vz[..n],
    );
    let (ax, ay, az) = (&ax[..n], &ay[..n], &az[..n]);
    let (mut bad, mut above) = (0usize, 0usize);
    for i in 0..n {
        vx[i] += ax[i] * dt;
        px[i] += vx[i] * dt;
        vy[i] += ay[i] * dt;
        py[i] += vy[i] * dt;
        vz[i] += az[i] * dt;
        pz[i] += vz[i] * dt;
        // `&`, not `&&`: no short circuit, so the loop vectorises. NaN fails every `<`.
        let ok = (px[i].abs() < rmax)
            & (py[i].abs() < rmax)
            & (pz[i].abs() < rmax)
            & (vx[i].abs() < vmax)
            & (vy[i].abs() < vmax)
            & (vz[i].abs() < vmax);
        bad += (!ok) as usize;
        above += (!(pz[i] <= 0.0)) as usize;
    }
    (bad, above)
}

/// The first node whose state is non-finite or over the limits (searched only once
/// [`update_over`] has counted one).
#[cold]
fn first_bad(x: [&[f64]; 6], opts: &SolverOptions) -> Option<usize> {
    let (rmax, vmax) = (opts.max_distance, opts.max_speed);
    let n = x[0].len();
    let [px, py, pz, vx, vy, vz] = x.map(|q| &q[..n]);
    (0..n).find(|&i| {
        !(px[i].abs() < rmax
            && py[i].abs() < rmax
            && pz[i].abs() < rmax
            && vx[i].abs() < vmax
            && vy[i].abs() < vmax
            && vz[i].abs() < vmax)
    })
}

/// The node loop over the nodes `nr` of one tile (their state, point and seabed values
/// from 0): per node, the sum over its `W` slots in the tile's buffer `sum`
/// ([`Loads`]) of what the incident elements add to its force and mass block (the
/// general path's order: point, then each incident element, then point loads, then
/// the seabed), the seabed's damping taken implicitly with step `h`, and the 3x3
/// solve, 4 nodes at a time.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn node_kernel<const W: usize, const FRICTION: bool>(
    c: &ChainConsts,
    h: f64,
    sum: &[f64],
    nr: Range<usize>,
    state: [&[f64]; 4],
    pm: &[f64],
    pwz: &[f64],
    ex: [&[f64]; 3],
    seabed: [&[f64]; 3],
    ax: &mut [f64],
    ay: &mut [f64],
    az: &mut [f64],
) {
    let (zb, v_eps) = (c.zb, c.v_eps);
    let per_tile = W * COLS * CS;
    let mut i = nr.start;
    assert!(nr.is_empty() || (nr.end - 1) / NT == nr.start / NT);
    while i < nr.end {
        // Nodes `i .. i + len` of tile `i / NT`, from its node `j0`.
        let (j0, len) = (i % NT, (nr.end - i).min(NT - i % NT));
        let tile = &sum[..per_tile];
        // Column `q` of slot `s`: `col[q][s]`, all at fixed offsets from the tile.
        // Filled by loops, not `std::array::from_fn`: whether its closures inline
        // depends on how the crate falls into codegen units, and where they did not
        // (main after the merges of 2026-12-02 night) the loop reloaded the columns
        // from a stack array: 13% more instructions on the net cage.
        let mut col: [[&[f64]; W]; COLS] = [[&[]; W]; COLS];
        for (q, c) in col.iter_mut().enumerate() {
            for (s, c) in c.iter_mut().enumerate() {
                *c = &tile[(COLS * s + q) * CS + j0..][..len];
            }
        }
        let tr = i - nr.start..i - nr.start + len;
        let [z, vx, vy, vz] = state.map(|q| &q[tr.clone()]);
        let (pm, pwz) = (&pm[tr.clone()], &pwz[tr.clone()]);
        let [exx, exy, exz] = ex.map(|q| &q[tr.clone()]);
        let [kl, cl, mukl] = seabed.map(|q| &q[tr.clone()]);
        let (ax, ay, az) = (
            &mut ax[tr.clone()],
            &mut ay[tr.clone()],
            &mut az[tr.clone()],
        );
        for k in 0..len {
            // Mass block `xx, yy, zz, xy, xz, yz` and force, summed entry by entry in
            // slot order (the general path's order).
            let mut sm = [pm[k], pm[k], pm[k], 0.0, 0.0, 0.0];
            let mut sf = [0.0, 0.0, pwz[k]];
            for s in 0..W {
                for (q, v) in sm.iter_mut().enumerate() {
                    *v += col[q][s][k];
                }
                for (q, v) in sf.iter_mut().enumerate() {
                    *v += col[6 + q][s][k];
                }
            }
            let mut m = Sym3 {
                xx: sm[0],
                yy: sm[1],
                zz: sm[2],
                xy: sm[3],
                xz: sm[4],
                yz: sm[5],
            };
            let mut g = V3::new(sf[0], sf[1], sf[2]);
            g += V3::new(exx[k], exy[k], exz[k]);
            let (sb, ch, cz) = seabed_load::<FRICTION>(
                zb - z[k],
                [vx[k], vy[k], vz[k]],
                kl[k],
                cl[k],
                mukl[k],
                v_eps,
            );
            g.z += sb[2];
            if FRICTION {
                g.x += sb[0];
                g.y += sb[1];
            }
            m.xx += h * ch;
            m.yy += h * ch;
            m.zz += h * cz;
            let a = m.solve(g);
            ax[k] = a.x;
            ay[k] = a.y;
            az[k] = a.z;
        }
        i += len;
    }
}
