//! The host's side of a layout: what is computed once per layout in f64 and does not
//! depend on the shader precision ([`Host`]: per-block origins, winch and body
//! indices), and the rows the host forms in f64 and uploads at each submission in the
//! shader precision: routes rebased to the submission's start ([`rebased_route`],
//! [`route_samples`]) and the bodies' rows ([`body_rows`]).
//!
//! Split out of `solver.rs` (one concept per file): these functions are also the
//! twins the GPU tests compare against (`tests/gpu/functions.rs`, `tests/gpu/bodies.rs`).

use super::layout::*;
use crate::ale::{AleElem, AleState};
use crate::body::{attachment, kinematics::mat_vec, Body};
use crate::error::Error;
use crate::model::{circle_basis, Layout, Route};
use std::f64::consts::PI;
use std::sync::Arc;

/// Node positions (absolute, m) and velocities (m/s), packed order.
pub type NodeStates = (Vec<[f64; 3]>, Vec<[f64; 3]>);

/// Precision-independent host data, computed once per layout.
#[derive(Clone)]
pub(super) struct Host {
    /// Per block: origin (absolute, m), a whole number of metres (exact in f32).
    pub(super) origin: Vec<[f64; 3]>,
    /// Per node: its block.
    pub(super) node_block: Vec<u32>,
    /// Per route: where its samples start in the `route_samples` buffer (tables only).
    pub(super) table_start: Vec<u32>,
    /// Per element: `ElemParams::winch`.
    pub(super) elem_winch: Vec<u32>,
    /// Per node: `NodeParams::winch`.
    pub(super) node_winch: Vec<u32>,
    /// The variable elements of the winch cables, in winch index order (the rows of
    /// the `payout` buffer).
    pub(super) winches: Vec<AleElem>,
    /// The bodies that ends are attached to (the columns of the `body_rows` buffer).
    pub(super) bodies: Vec<Arc<Body>>,
    /// Per route: its body's index in `bodies` (routes on prescribed bodies), or in
    /// `free` (routes on free and pinned bodies); else 0.
    pub(super) route_body: Vec<u32>,
    /// The free and pinned bodies (records in `body_rows` from `Params::free_at`).
    pub(super) free: Vec<FreeHost>,
}

/// A free or pinned body on the GPU path.
#[derive(Clone)]
pub(super) struct FreeHost {
    /// The body (its `Dynamic` motion holds the initial state).
    pub(super) body: Arc<Body>,
    /// The routes of its held nodes.
    pub(super) routes: Vec<u32>,
    /// A pinned body's column in the per-step rows (its pin's motion), else 0.
    pub(super) col: u32,
}

impl FreeHost {
    /// The initial reference point, absolute (what the records are relative to).
    pub(super) fn xr(&self) -> [f64; 3] {
        let d = self.body.dynamic().expect("a free body");
        let x = d.body.reference();
        [x.x, x.y, x.z]
    }
}

/// `ElemParams::winch` and `NodeParams::winch` of what is not a variable element.
pub(super) const NO_WINCH: u32 = u32::MAX;

impl Host {
    pub(super) fn new(
        lay: &Layout,
        positions: &[[f64; 3]],
        ale: Option<&AleState>,
    ) -> Result<Self, Error> {
        let mut origin = Vec::with_capacity(lay.blocks.len());
        let mut node_block = vec![0u32; lay.n_nodes()];
        for (bi, b) in lay.blocks.iter().enumerate() {
            let (n0, n1) = (b.node_start as usize, b.node_end as usize);
            let mut o = [0.0; 3];
            for p in &positions[n0..n1] {
                for d in 0..3 {
                    o[d] += p[d];
                }
            }
            let n = (n1 - n0).max(1) as f64;
            origin.push(o.map(|x| (x / n).round()));
            node_block[n0..n1].iter_mut().for_each(|x| *x = bi as u32);
        }
        let mut table_start = Vec::with_capacity(lay.routes.len());
        let mut next = 0u32;
        for r in &lay.routes {
            table_start.push(next);
            if let Route::Table { t, .. } = r {
                next += t.len() as u32;
            }
        }
        let mut bodies: Vec<Arc<Body>> = Vec::new();
        let mut route_body = vec![0u32; lay.routes.len()];
        let mut free: Vec<FreeHost> = Vec::new();
        for (c, r) in lay.routes.iter().enumerate() {
            if let Route::Body { body, .. } = r {
                if body.dynamic().is_some() {
                    route_body[c] = match free.iter().position(|f| Arc::ptr_eq(&f.body, body)) {
                        Some(i) => {
                            free[i].routes.push(c as u32);
                            i
                        }
                        None => {
                            free.push(FreeHost {
                                body: body.clone(),
                                routes: vec![c as u32],
                                col: 0,
                            });
                            free.len() - 1
                        }
                    } as u32;
                    continue;
                }
                route_body[c] = match bodies.iter().position(|b| Arc::ptr_eq(b, body)) {
                    Some(i) => i,
                    None => {
                        bodies.push(body.clone());
                        bodies.len() - 1
                    }
                } as u32;
            }
        }
        let mut elem_winch = vec![NO_WINCH; lay.n_elements()];
        let mut node_winch = vec![NO_WINCH; lay.n_nodes()];
        let mut winches = Vec::new();
        if let Some(ale) = ale {
            for (wi, (e, m, w, ae)) in ale.packed_variable_elements(lay).enumerate() {
                elem_winch[e] = 2 * wi as u32 + (lay.elem_b[e] as usize == w) as u32;
                for n in [m, w] {
                    if node_winch[n] != NO_WINCH {
                        let (cable, node) = lay.describe_node(n);
                        return Err(Error::GpuUnsupported(format!(
                            "node {node} of cable '{cable}' ends the variable elements of two winch cables"
                        )));
                    }
                    node_winch[n] = wi as u32;
                }
                winches.push(ae.clone());
            }
        }
        // A pinned body's pin motion goes in the per-step rows, as a column after the
        // prescribed bodies.
        for f in &mut free {
            if f.body.dynamic().expect("free").body.kind == crate::body::free::FreeKind::Pinned {
                f.col = bodies.len() as u32;
                bodies.push(f.body.clone());
            }
        }
        Ok(Self {
            origin,
            node_block,
            table_start,
            elem_winch,
            node_winch,
            winches,
            bodies,
            route_body,
            free,
        })
    }

    /// The origin of the block of the node route `c` drives.
    pub(super) fn route_origin(&self, lay: &Layout, c: usize) -> [f64; 3] {
        let n = lay.constraint_node[c] as usize;
        self.origin[self.node_block[n] as usize]
    }
}

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `x` as a compensated pair `(hi, lo)` of `R`: `hi + lo` is `x` to about twice the
/// precision of `R` (in f64, `lo` is zero).
pub(super) fn split<R: GpuReal>(x: f64) -> (R, R) {
    let hi = R::c(x);
    (hi, R::c(x - hi.f64()))
}

/// The samples of a table route relative to origin `o` (what [`rebased_route`]'s
/// `table_start` points at in the `route_samples` buffer); empty for other routes.
pub fn route_samples<R: GpuReal>(route: &Route, o: [f64; 3]) -> Vec<RouteSample<R>> {
    let Route::Table { t, p } = route else {
        return Vec::new();
    };
    t.iter()
        .zip(p)
        .map(|(&t, p)| {
            let mut s = RouteSample::<R>::default();
            (s.t_hi, s.t_lo) = split(t);
            (s.x_hi, s.x_lo) = split(p[0] - o[0]);
            (s.y_hi, s.y_lo) = split(p[1] - o[1]);
            (s.z_hi, s.z_lo) = split(p[2] - o[2]);
            s
        })
        .collect()
}

/// Route `route` of node `node` rebased to time `t0` and origin `o`: what the shaders'
/// `route_eval(q, tau)` turns into the target at `t0 + tau`, relative to `o`. A table
/// route's samples ([`route_samples`]) start at `table_start` in the samples buffer.
/// A point on a body holds the point at `t0`, `R(t0) at` and `at` (`body` is left 0
/// for the caller to set); the shaders' `body_point` adds the motion since `t0` from
/// the body's row of the step ([`body_rows`]).
pub fn rebased_route<R: GpuReal>(
    route: &Route,
    node: u32,
    t0: f64,
    o: [f64; 3],
    table_start: u32,
) -> RouteParams<R> {
    let mut q = RouteParams::<R> {
        node,
        ..Default::default()
    };
    if let Route::Table { t, .. } = route {
        q.kind = 3;
        q.table_start = table_start;
        q.table_len = t.len() as u32;
        q.cursor = t.partition_point(|&x| x <= t0) as u32;
        (q.t0_hi, q.t0_lo) = split(t0);
        return q;
    }
    if let Route::Body { body, at } = route {
        if let Some(d) = body.dynamic() {
            // A free or pinned body: `p` is its initial reference point, the body's
            // row holds its displacement since then and its whole rotation (e1 = 0).
            q.kind = 5;
            let x = d.body.reference();
            let p = sub([x.x, x.y, x.z], o);
            (q.p_hi_x, q.p_lo_x) = split(p[0]);
            (q.p_hi_y, q.p_lo_y) = split(p[1]);
            (q.p_hi_z, q.p_lo_z) = split(p[2]);
            (q.e2_x, q.e2_y, q.e2_z) = (R::c(at[0]), R::c(at[1]), R::c(at[2]));
            return q;
        }
        q.kind = 4;
        let s = body.state(t0);
        let p = sub(attachment(&s, *at).r, o);
        (q.p_hi_x, q.p_lo_x) = split(p[0]);
        (q.p_hi_y, q.p_lo_y) = split(p[1]);
        (q.p_hi_z, q.p_lo_z) = split(p[2]);
        let q0 = mat_vec(&s.rot, *at);
        (q.e1_x, q.e1_y, q.e1_z) = (R::c(q0.x), R::c(q0.y), R::c(q0.z));
        (q.e2_x, q.e2_y, q.e2_z) = (R::c(at[0]), R::c(at[1]), R::c(at[2]));
        return q;
    }
    let (p, vel) = match route {
        Route::Fixed { position } => {
            q.kind = 0;
            (sub(*position, o), [0.0; 3])
        }
        Route::Line { start, velocity } => {
            q.kind = 1;
            let p = [0, 1, 2].map(|d| start[d] + velocity[d] * t0);
            (sub(p, o), *velocity)
        }
        Route::Circle {
            center,
            radius,
            period,
            axis,
            phase,
            advance,
        } => {
            q.kind = 2;
            let w = 2.0 * PI / period;
            let adv = advance / period;
            let (e1, e2) = circle_basis(*axis);
            q.e1_x = R::c(radius * e1[0]);
            q.e1_y = R::c(radius * e1[1]);
            q.e1_z = R::c(radius * e1[2]);
            q.e2_x = R::c(radius * e2[0]);
            q.e2_y = R::c(radius * e2[1]);
            q.e2_z = R::c(radius * e2[2]);
            q.w = R::c(w);
            let th0 = (w * t0 + phase).rem_euclid(2.0 * PI);
            let (s0, c0) = th0.sin_cos();
            q.c0 = R::c(c0);
            q.s0 = R::c(s0);
            // The point on the circle at t0, in f64: the shader adds the displacement.
            let p = [0, 1, 2]
                .map(|d| center[d] + axis[d] * adv * t0 + radius * (c0 * e1[d] + s0 * e2[d]));
            (sub(p, o), axis.map(|a| a * adv))
        }
        Route::Table { .. } | Route::Body { .. } => unreachable!("handled above"),
    };
    (q.p_hi_x, q.p_lo_x) = split(p[0]);
    (q.p_hi_y, q.p_lo_y) = split(p[1]);
    (q.p_hi_z, q.p_lo_z) = split(p[2]);
    q.vel_x = R::c(vel[0]);
    q.vel_y = R::c(vel[1]);
    q.vel_z = R::c(vel[2]);
    q
}

/// The rows of `body` at times `times` (s) relative to its state at the rebase time
/// `t0` (what the shaders' `body_point` reads): the reference point's displacement
/// and the change of the rotation since `t0`, formed in f64 so that only small
/// numbers are rounded to `R`, and the velocities and accelerations at each time.
pub fn body_rows<R: GpuReal>(
    body: &Body,
    t0: f64,
    times: impl Iterator<Item = f64>,
) -> Vec<BodyRow<R>> {
    let s0 = body.state(t0);
    times
        .map(|t| {
            let s = body.evaluate(t);
            let d = s.x - s0.x;
            let dr = |i: usize, j: usize| R::c(s.rot[i][j] - s0.rot[i][j]);
            BodyRow {
                dx: R::c(d.x),
                dy: R::c(d.y),
                dz: R::c(d.z),
                dr00: dr(0, 0),
                dr01: dr(0, 1),
                dr02: dr(0, 2),
                dr10: dr(1, 0),
                dr11: dr(1, 1),
                dr12: dr(1, 2),
                dr20: dr(2, 0),
                dr21: dr(2, 1),
                dr22: dr(2, 2),
                vx: R::c(s.v.x),
                vy: R::c(s.v.y),
                vz: R::c(s.v.z),
                ax: R::c(s.a.x),
                ay: R::c(s.a.y),
                az: R::c(s.a.z),
                wx: R::c(s.omega.x),
                wy: R::c(s.omega.y),
                wz: R::c(s.omega.z),
                alx: R::c(s.alpha.x),
                aly: R::c(s.alpha.y),
                alz: R::c(s.alpha.z),
            }
        })
        .collect()
}

/// Values of `R` per free body record (shaders/shared/free_body.wgsl: FREE_STRIDE).
pub const FREE_STRIDE: usize = 168;
/// Values of `R` per line failure record (FAIL_STRIDE).
pub const FAIL_STRIDE: usize = 12;

/// The row (a [`BodyRow`]) of free body `f` in state `b`: its reference point's
/// displacement since `xr`, its rotation, the reference point's velocity and
/// acceleration, its angular velocity and acceleration (what `free_body_step` writes).
fn free_row(b: &crate::body::free::FreeBody, xr: [f64; 3]) -> [f64; 24] {
    let s = b.body_state();
    let mut row = [0.0; 24];
    for d in 0..3 {
        row[d] = s.x.to_f64()[d] - xr[d];
        row[12 + d] = s.v.to_f64()[d];
        row[15 + d] = s.a.to_f64()[d];
        row[18 + d] = s.omega.to_f64()[d];
        row[21 + d] = s.alpha.to_f64()[d];
        for j in 0..3 {
            row[3 + 3 * d + j] = s.rot[d][j];
        }
    }
    row
}

/// The free bodies' records (from [`Params::free_at`]) in states `states` (one per
/// `host.free`), then their held routes' lists; `list_at` is the value offset of the
/// lists in `body_rows`.
pub(super) fn free_records<R: GpuReal>(
    host: &Host,
    states: &[crate::body::free::FreeBody],
    list_at: usize,
) -> Vec<R> {
    use crate::body::free::FreeKind;
    let n = host.free.len();
    let mut out = vec![0.0f64; n * FREE_STRIDE];
    let mut lists: Vec<f64> = Vec::new();
    let mut hi_lo: Vec<(usize, f64)> = Vec::new();
    for (i, (f, b)) in host.free.iter().zip(states).enumerate() {
        let o = i * FREE_STRIDE;
        let init = &f.body.dynamic().expect("free").body;
        let xr = f.xr();
        let sp = &b.spec;
        out[o..o + 24].copy_from_slice(&free_row(b, xr));
        let s = o + 24;
        // The centre of gravity's displacement since its initial position, split
        // into a compensated pair below.
        for d in 0..3 {
            hi_lo.push((s + d, b.x_g[d] - init.x_g[d]));
            out[s + 6 + d] = b.v_g[d];
            out[s + 13 + d] = b.w[d];
            out[s + 16 + d] = b.last_acc.0[d];
            out[s + 19 + d] = b.last_acc.1[d];
        }
        let q = b.q.quaternion();
        out[s + 9] = q.i;
        out[s + 10] = q.j;
        out[s + 11] = q.k;
        out[s + 12] = q.w;
        let c = o + 48;
        out[c] = (b.kind == FreeKind::Pinned) as u8 as f64;
        out[c + 1] = f.col as f64;
        out[c + 2] = sp.mass;
        out[c + 3..c + 6].copy_from_slice(&sp.cg);
        for r in 0..3 {
            out[c + 6 + 3 * r..c + 9 + 3 * r].copy_from_slice(&sp.inertia[r]);
        }
        out[c + 15] = sp.volume;
        out[c + 16..c + 19].copy_from_slice(&sp.cb);
        out[c + 19] = sp.waterplane_area;
        out[c + 20..c + 22].copy_from_slice(&sp.waterplane_inertia);
        for r in 0..6 {
            out[c + 22 + 6 * r..c + 28 + 6 * r].copy_from_slice(&sp.added_mass[r]);
            out[c + 64 + 6 * r..c + 70 + 6 * r].copy_from_slice(&sp.damping[r]);
        }
        out[c + 58..c + 61].copy_from_slice(&sp.drag_area);
        out[c + 61..c + 64].copy_from_slice(&sp.rotational_drag);
        out[c + 100..c + 103].copy_from_slice(&sp.force);
        out[c + 103..c + 106].copy_from_slice(&sp.moment);
        for d in 0..3 {
            out[c + 106 + d] = init.x_g[d] - xr[d];
            out[c + 109 + d] = xr[d];
        }
        out[c + 112] = xr[2] - b.x0[2];
        out[c + 113] = (list_at + lists.len()) as f64;
        out[c + 114] = f.routes.len() as f64;
        lists.extend(f.routes.iter().map(|&r| r as f64));
    }
    let mut v: Vec<R> = out.iter().map(|&x| R::c(x)).collect();
    for (at, x) in hi_lo {
        let (h, l) = split::<R>(x);
        v[at] = h;
        v[at + 3] = l;
    }
    v.extend(lists.iter().map(|&x| R::c(x)));
    v
}

/// Free body `f`'s state from its record `rec` (FREE_STRIDE values read back), in f64.
pub(super) fn free_state_of<R: GpuReal>(f: &FreeHost, rec: &[R]) -> crate::body::free::FreeBody {
    use nalgebra::{Quaternion, UnitQuaternion, Vector3};
    let init = &f.body.dynamic().expect("free").body;
    let mut b = init.clone();
    let x = |j: usize| rec[j].f64();
    let s = 24;
    b.x_g = init.x_g + Vector3::new(x(s) + x(s + 3), x(s + 1) + x(s + 4), x(s + 2) + x(s + 5));
    b.v_g = Vector3::new(x(s + 6), x(s + 7), x(s + 8));
    b.q = UnitQuaternion::new_normalize(Quaternion::new(x(s + 12), x(s + 9), x(s + 10), x(s + 11)));
    b.w = Vector3::new(x(s + 13), x(s + 14), x(s + 15));
    b.last_acc = (
        Vector3::new(x(s + 16), x(s + 17), x(s + 18)),
        Vector3::new(x(s + 19), x(s + 20), x(s + 21)),
    );
    b
}

/// The per-step row of pinned body `body` at `t`: its pin's displacement since `xr`,
/// velocity and acceleration.
pub(super) fn pin_row<R: GpuReal>(body: &Body, xr: [f64; 3], t: f64) -> BodyRow<R> {
    let p = body.pin(t);
    BodyRow {
        dx: R::c(p.x[0] - xr[0]),
        dy: R::c(p.x[1] - xr[1]),
        dz: R::c(p.x[2] - xr[2]),
        vx: R::c(p.v[0]),
        vy: R::c(p.v[1]),
        vz: R::c(p.v[2]),
        ax: R::c(p.a[0]),
        ay: R::c(p.a[1]),
        az: R::c(p.a[2]),
        ..Default::default()
    }
}

/// `ElemParams` fields of a hinge row's side without a hinge (WGSL `NO_HINGE`).
pub const NO_HINGE: u32 = u32::MAX;

/// The bending hinges of a layout ([`Layout::hinges`]) as the shaders read them: per
/// element its *hinge row* (an [`ElemParams`] at `elems[n_elems + e]`, read by
/// `shaders/shared/step.wgsl` `element_shear`) and the held directions of clamped
/// ends (rows of `current_pts` from `clamp_row0` on). In a hinge row `a` is the far
/// node of the element before (the hinge at its node a; its own node a at a clamp),
/// `b` the far node of the element after (the hinge at its node b), `line` and
/// `current` the clamp rows of its ends a and b, `l0` and `l0_lo` the two hinges'
/// stiffness `EI / lbar`; [`NO_HINGE`] where a side has none.
///
/// Each element computes its own shear from these (a gather, no atomics): both
/// hinges beside it are evaluated by both their elements. So a hinge must join the
/// node b of its element before to the node a of its element after (as `Hinge`
/// says), and an element can have one hinge at each end: a hinge across two cables
/// that meet end to start fits, one that meets end to end or start to start, or a
/// third hinge at one element end (three cables bending through one point), does not
/// (the error says which).
#[derive(Clone, Debug, Default)]
pub struct HingeRows {
    /// Per element: `(far node a, far node b, clamp a, clamp b, k a, k b)`.
    pub rows: Vec<(u32, u32, u32, u32, f64, f64)>,
    /// The held directions of clamped ends, in clamp row order.
    pub clamps: Vec<[f64; 3]>,
}

impl HingeRows {
    /// The hinge rows of `lay`, clamp rows numbered from `clamp_row0`, or why the
    /// shaders cannot hold its hinges.
    pub fn new(lay: &Layout, clamp_row0: u32) -> Result<Self, String> {
        let n = lay.n_elements();
        let mut rows = vec![(NO_HINGE, NO_HINGE, NO_HINGE, NO_HINGE, 0.0, 0.0); n];
        let mut clamps = Vec::new();
        let name = |e: u32| {
            let c = &lay.cables[lay.elem_cable[e as usize] as usize];
            let j = c.elements.iter().position(|&x| x == e).unwrap_or(0);
            format!("cable '{}' element {j}", c.name)
        };
        for h in lay.hinges() {
            let (p, q) = (h.prev, h.next);
            let none = crate::model::NO_ELEM;
            if p != none && q != none && lay.elem_b[p as usize] != lay.elem_a[q as usize] {
                return Err(format!(
                    "a bending hinge between {} and {} that do not meet end to start \
                     (the GPU path's hinge rows hold that form only)",
                    name(p),
                    name(q)
                ));
            }
            let mut clamp = || {
                clamps.push(h.dir);
                clamp_row0 + clamps.len() as u32 - 1
            };
            if q != none {
                let r = &mut rows[q as usize];
                if r.0 != NO_HINGE {
                    return Err(format!(
                        "two bending hinges at the start of {} (the GPU path holds one \
                         hinge at each element end)",
                        name(q)
                    ));
                }
                if p != none {
                    r.0 = lay.elem_a[p as usize];
                } else {
                    r.0 = lay.elem_a[q as usize];
                    r.2 = clamp();
                }
                r.4 = h.k;
            }
            if p != none {
                let r = &mut rows[p as usize];
                if r.1 != NO_HINGE {
                    return Err(format!(
                        "two bending hinges at the end of {} (the GPU path holds one \
                         hinge at each element end)",
                        name(p)
                    ));
                }
                if q != none {
                    r.1 = lay.elem_b[q as usize];
                } else {
                    r.1 = lay.elem_b[p as usize];
                    r.3 = clamp();
                }
                r.5 = h.k;
            }
        }
        Ok(Self { rows, clamps })
    }

    /// The rows as `ElemParams` in precision `R`.
    pub fn params<R: GpuReal>(&self) -> Vec<ElemParams<R>> {
        self.rows
            .iter()
            .map(|&(a, b, ca, cb, ka, kb)| ElemParams {
                a,
                b,
                line: ca,
                current: cb,
                block: 0,
                winch: NO_WINCH,
                l0: R::c(ka),
                l0_lo: R::c(kb),
                diameter: R::c(0.0),
            })
            .collect()
    }
}
