//! The GPU stepper: the packed layout uploaded once, many steps per submission.
//!
//! With the fused kernel ([`GpuKernel::Fused`], chosen by [`fused_workgroup`] where it
//! applies) a submission is one dispatch of `fused_steps`, one workgroup per block,
//! looping over the submission's steps inside the shader (in waves, one dispatch from
//! each refresh of the kinematics cache to the next, the refresh a `wave_refresh`
//! dispatch of its own: see [`fused_segments`]). With the
//! two-pass kernel a step is two dispatches in one compute pass, `element_forces` then
//! `node_update` (wgpu orders the storage writes of one dispatch before the reads of the
//! next). Both read the step's route and payout rows the same way, so the rest of this
//! note holds for both.
//! [`STEPS_PER_SUBMISSION`] steps go into one command buffer; the step index reaches
//! the shaders through a dynamic-offset uniform (one 16-byte `StepInfo` per step,
//! written once; the fused kernel's end step is written at each of its dispatches'
//! first step), so nothing is written between steps. Before each submission the
//! routes are rebased to its start time (see [`RouteParams`]): the shaders evaluate
//! `r_d(t0 + tau)` with a small `tau`, which keeps f32 route positions and angles
//! accurate over long runs. Nothing is read back while stepping except, at the end of
//! an [`GpuSolver::advance`] call, the 16-byte status; state, tensions and reactions
//! come back only when asked for, through one staging buffer created once per layout.
//!
//! Winch cables: per submission the host also writes the `payout` rows (one [`Payout`]
//! per winch and step), and an `advance` call stops its submissions at each step after
//! which a winch cable must be remeshed, reads the state back, remeshes on the host
//! (`ale::AleState::remesh_in_place`, the CPU path's code), rebuilds the layout's buffers
//! and bind group (the pipelines stay) and uploads the state: see [`GpuSolver`].

use super::context::GpuContext;
use super::layout::*;
use super::shaders::{self, Stage};
use crate::ale::{AleElem, AleState, Winch};
use crate::body::{attachment, kinematics::mat_vec, Body};
use crate::error::Error;
use crate::math::V3;
use crate::model::{circle_basis, Layout, ModelDef, Route};
use crate::options::Precision;
use crate::options::{Formulation, Scheme, SolverOptions};
use crate::sea::cache::hermite_weights;
use crate::sea::kinematics::{wave_ramp, wave_ramp_rate, WaveField};
use crate::sea::schedule::{RefreshClock, RefreshPlan};
use crate::sea::{SeaSet, SeaState, Stretching, GPU_DEEP};
use crate::step::{diverged, Evaluation, StepFailure, WinchStatus};
use bytemuck::Zeroable;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::marker::PhantomData;
use std::sync::Arc;
use std::time::Instant;
use wgpu::util::DeviceExt;

/// `Status::failed` of a blow-up found by the fused kernel (WGSL `FUSED_FAILED`).
const FUSED_FAILED: u32 = 0x8000_0000;

/// Steps recorded in one command buffer (one submission).
pub const STEPS_PER_SUBMISSION: u32 = 512;

/// Invocations per workgroup of the two-pass stages (the shaders' `@workgroup_size`).
const WORKGROUP: u32 = 64;

/// The largest workgroup the fused kernel uses (nodes or elements of a block at most).
pub const MAX_FUSED_WORKGROUP: u32 = 256;

/// Bytes of workgroup memory the fused kernel needs per invocation at precision `p`:
/// a node state and an element's loads, 9 scalars each.
fn fused_bytes_per_lane(p: Precision) -> u32 {
    let r = match p {
        Precision::F32 => 4,
        Precision::F64 => 8,
    };
    2 * 9 * r
}

/// How [`GpuSolver::advance`] steps the layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GpuKernel {
    /// One workgroup per block advances it through a whole submission in one
    /// dispatch (`shaders/fused_chain.wgsl`), with the block's state in workgroup
    /// memory: for layouts whose blocks all have at most [`MAX_FUSED_WORKGROUP`]
    /// nodes and elements (and fit the adapter's workgroup memory), without winches.
    Fused,
    /// Two dispatches per step over the whole packed layout (`element_forces`, then
    /// `node_update`): any layout.
    TwoPass,
}

impl GpuKernel {
    /// `fused` or `two-pass`.
    pub fn name(self) -> &'static str {
        match self {
            GpuKernel::Fused => "fused",
            GpuKernel::TwoPass => "two-pass",
        }
    }
    /// Parses `fused | two-pass`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "fused" => Some(GpuKernel::Fused),
            "two-pass" => Some(GpuKernel::TwoPass),
            _ => None,
        }
    }
}

/// The fused kernel's workgroup size for this layout at precision `p` under `limits`,
/// or why the fused kernel cannot step it: the smallest multiple of 8 that holds the
/// nodes and the elements of every block, at most [`MAX_FUSED_WORKGROUP`] and what
/// the adapter's workgroup limits allow; no winch cables.
pub fn fused_workgroup(
    lay: &Layout,
    p: Precision,
    limits: &wgpu::Limits,
    winches: bool,
) -> Result<u32, String> {
    if winches {
        return Err("winch cables (their payout rows are per step and per dispatch)".into());
    }
    if lay.blocks.is_empty() {
        return Err("no blocks".into());
    }
    if lay.blocks.len() > limits.max_compute_workgroups_per_dimension as usize {
        return Err(format!(
            "{} blocks, more than the {} workgroups of one dispatch dimension",
            lay.blocks.len(),
            limits.max_compute_workgroups_per_dimension
        ));
    }
    let need = lay
        .blocks
        .iter()
        .map(|b| (b.node_end - b.node_start).max(b.elem_end - b.elem_start))
        .max()
        .unwrap_or(1);
    let per_lane = fused_bytes_per_lane(p);
    let cap = MAX_FUSED_WORKGROUP
        .min(limits.max_compute_invocations_per_workgroup)
        .min(limits.max_compute_workgroup_size_x)
        .min(limits.max_compute_workgroup_storage_size.saturating_sub(16) / per_lane / 8 * 8);
    // A multiple of 8 (a software adapter's SIMD width; a GPU runs whole warps anyway).
    let wg = need.max(1).div_ceil(8) * 8;
    if wg > cap {
        return Err(format!(
            "a block of {need} nodes or elements, more than the {cap} invocations the fused \
             kernel may use ({} bytes of workgroup memory each, {} available)",
            per_lane, limits.max_compute_workgroup_storage_size
        ));
    }
    Ok(wg)
}

/// The kernel the environment variable `CABLESIM_GPU_KERNEL` asks for (`fused`,
/// `two-pass`; unset, empty or `auto`: none).
fn kernel_from_env() -> Result<Option<GpuKernel>, Error> {
    match std::env::var("CABLESIM_GPU_KERNEL") {
        Err(_) => Ok(None),
        Ok(v) if v.is_empty() || v == "auto" => Ok(None),
        Ok(v) => GpuKernel::parse(&v).map(Some).ok_or_else(|| {
            Error::Gpu(format!(
                "CABLESIM_GPU_KERNEL={v}: expected fused, two-pass or auto"
            ))
        }),
    }
}

/// Node positions (absolute, m) and velocities (m/s), packed order.
pub type NodeStates = (Vec<[f64; 3]>, Vec<[f64; 3]>);

/// Precision-independent host data, computed once per layout.
#[derive(Clone)]
struct Host {
    /// Per block: origin (absolute, m), a whole number of metres (exact in f32).
    origin: Vec<[f64; 3]>,
    /// Per node: its block.
    node_block: Vec<u32>,
    /// Per route: where its samples start in the `route_samples` buffer (tables only).
    table_start: Vec<u32>,
    /// Per element: `ElemParams::winch`.
    elem_winch: Vec<u32>,
    /// Per node: `NodeParams::winch`.
    node_winch: Vec<u32>,
    /// The variable elements of the winch cables, in winch index order (the rows of
    /// the `payout` buffer).
    winches: Vec<AleElem>,
    /// The bodies that ends are attached to (the columns of the `body_rows` buffer).
    bodies: Vec<Arc<Body>>,
    /// Per route: its body's index in `bodies` (routes on bodies only; else 0).
    route_body: Vec<u32>,
}

/// `ElemParams::winch` and `NodeParams::winch` of what is not a variable element.
const NO_WINCH: u32 = u32::MAX;

impl Host {
    fn new(lay: &Layout, positions: &[[f64; 3]], ale: Option<&AleState>) -> Result<Self, Error> {
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
        for (c, r) in lay.routes.iter().enumerate() {
            if let Route::Body { body, .. } = r {
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
        Ok(Self {
            origin,
            node_block,
            table_start,
            elem_winch,
            node_winch,
            winches,
            bodies,
            route_body,
        })
    }

    /// The origin of the block of the node route `c` drives.
    fn route_origin(&self, lay: &Layout, c: usize) -> [f64; 3] {
        let n = lay.constraint_node[c] as usize;
        self.origin[self.node_block[n] as usize]
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `x` as a compensated pair `(hi, lo)` of `R`: `hi + lo` is `x` to about twice the
/// precision of `R` (in f64, `lo` is zero).
fn split<R: GpuReal>(x: f64) -> (R, R) {
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

/// What the GPU solver does not do yet, or `None`.
pub fn unsupported(lay: &Layout, opts: &SolverOptions) -> Option<String> {
    if opts.formulation != Formulation::Glmf {
        return Some(format!(
            "the {} formulation (the GPU path is GLMF only)",
            opts.formulation.name()
        ));
    }
    if opts.scheme != Scheme::Symplectic {
        return Some(format!(
            "the {} scheme (the GPU path is symplectic Euler only so far)",
            opts.scheme.name()
        ));
    }
    // One invocation per node or element along x only, so far.
    let most = 65_535 * WORKGROUP as usize;
    if lay.n_nodes() > most || lay.n_elements() > most {
        return Some(format!(
            "more than {most} nodes or elements (one dispatch dimension)"
        ));
    }
    None
}

/// The device side of a solver at one precision.
trait Engine: Send {
    /// Runs `n` steps from step `step0`; `Some((step, node))` names the first blow-up
    /// (`step` counted from `step0`).
    fn advance(
        &mut self,
        lay: &Layout,
        host: &Host,
        step0: u64,
        n: u64,
    ) -> Result<Option<(u64, u32)>, Error>;
    /// Reads positions and velocities back (absolute positions).
    fn download(&mut self, host: &Host) -> Result<NodeStates, Error>;
    /// Writes positions and velocities.
    fn upload(&mut self, host: &Host, r: &[[f64; 3]], v: &[[f64; 3]]);
    /// Starts the waves' kinematics cache afresh at the next step (after the state was
    /// put back to an earlier time).
    fn restart_waves(&mut self);
    /// Loads, accelerations and reactions at step `step`.
    fn evaluate(&mut self, lay: &Layout, host: &Host, step: u64) -> Result<Evaluation, Error>;
    /// Where the host's time went in `advance` so far.
    fn timings(&self) -> GpuTimings;
    /// The kernel `advance` uses.
    fn kernel(&self) -> GpuKernel;
    /// Why the fused kernel cannot step the current layout, or `None`.
    fn fused_unavailable(&self) -> Option<&str>;
    /// Chooses the kernel (`Fused` only when available).
    fn set_kernel(&mut self, k: GpuKernel) -> Result<(), Error>;
    /// Runs in `seas` from now on (still water without components), keeping the state.
    fn set_seas(&mut self, lay: &Layout, host: &Host, seas: &SeaSet) -> Result<(), Error>;
    /// Replaces the layout (after a remeshing) with state `r`, `v`.
    fn install(
        &mut self,
        lay: &Layout,
        host: &Host,
        r: &[[f64; 3]],
        v: &[[f64; 3]],
    ) -> Result<(), Error>;
}

/// Where [`GpuSolver::advance`]'s wall time went, summed over its calls: recording the
/// command buffers on the host, submitting them, and waiting for the device at the end
/// of each call (the one read-back of the status). The device runs while the host
/// records the next submission, so `wait_seconds` is the device time the host could
/// not hide; on a software adapter (lavapipe) the "device" is the same CPU cores.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GpuTimings {
    /// Steps taken.
    pub steps: u64,
    /// Compute dispatches recorded (two per step on the two-pass path, one per
    /// submission on the fused path).
    pub dispatches: u64,
    /// Command buffers submitted.
    pub submissions: u64,
    /// Recording (route and parameter writes, encoding the dispatches), s.
    pub encode_seconds: f64,
    /// `Queue::submit`, s.
    pub submit_seconds: f64,
    /// Waiting for the device and reading the status back, s.
    pub wait_seconds: f64,
    /// All of `advance`, s.
    pub advance_seconds: f64,
}

struct Buffers {
    params: wgpu::Buffer,
    step: wgpu::Buffer,
    routes: wgpu::Buffer,
    state: wgpu::Buffer,
    elem_loads: wgpu::Buffer,
    node_out: wgpu::Buffer,
    reactions: wgpu::Buffer,
    status: wgpu::Buffer,
    payout: wgpu::Buffer,
    body_rows: wgpu::Buffer,
    wave_comps: wgpu::Buffer,
    wave_steps: wgpu::Buffer,
    staging: wgpu::Buffer,
}

/// Scalars per node and cache slot on the GPU: the values `eta, u, a` and their rates
/// along the node's path (`WAVE_CACHE_STRIDE` in `shaders/shared/waves.wgsl`); after
/// the two slots, three per node: its velocity at the last refresh.
const WAVE_CACHE_STRIDE: usize = 14;

/// The host's side of the waves' kinematics cache: the components (rebased at each
/// submission) and when the cache's two times are: the same [`RefreshClock`] as the
/// CPU path's `sea::cache::WaveCache`, on the same grid (`sea::schedule`), so that
/// both refresh at the same steps and interpolate with the same Hermite weights.
struct WaveSchedule {
    field: WaveField,
    /// Its first component in the components buffer.
    first: u32,
    /// The cache's times and refresh grid.
    clock: RefreshClock,
    /// Cache slot of the older values (0 or 1).
    slot0: u32,
}

impl WaveSchedule {
    fn new(sea: &SeaState, first: u32, plan: &RefreshPlan) -> Self {
        Self {
            field: WaveField::new(sea),
            first,
            clock: RefreshClock::on_grid(plan),
            slot0: 0,
        }
    }

    /// The row of constants every step shares.
    fn base<R: GpuReal>(&self) -> WaveStep<R> {
        WaveStep {
            n: self.field.comps.len() as u32,
            first: self.first,
            stretching: match self.field.stretching {
                Stretching::Wheeler => 0,
                Stretching::Constant => 1,
            },
            depth: R::c(if self.field.depth.is_finite() {
                self.field.depth
            } else {
                GPU_DEEP
            }),
            ..Default::default()
        }
    }

    /// The row of the step at time `t` (s; phases referred to `t_ref`), refreshing
    /// when the CPU path's cache would.
    fn step<R: GpuReal>(&mut self, t: f64, t_ref: f64) -> WaveStep<R> {
        let mut row = self.base::<R>();
        let ramp = self.field.ramp_duration;
        if let Some(tick) = self.clock.tick(t) {
            row.refresh = 1;
            row.track = 1;
            row.acc_rate = R::c(tick.acc_rate);
            if tick.restart {
                row.restart = 1;
                row.tau0 = R::c(t - t_ref);
                row.ramp0 = R::c(wave_ramp(t, ramp));
                row.ramp_rate0 = R::c(wave_ramp_rate(t, ramp));
            } else {
                self.slot0 = 1 - self.slot0;
            }
            let t1 = self.clock.t1;
            row.ahead = R::c(tick.ahead);
            row.tau1 = R::c(t1 - t_ref);
            row.ramp1 = R::c(wave_ramp(t1, ramp));
            row.ramp_rate1 = R::c(wave_ramp_rate(t1, ramp));
        }
        row.slot0 = self.slot0;
        row.slot1 = 1 - self.slot0;
        let (t0, t1) = (self.clock.t0, self.clock.t1);
        let delta = t1 - t0;
        let s = ((t - t0) / delta).clamp(0.0, 1.0);
        let w = hermite_weights(s, delta);
        (row.w0, row.w1, row.w2, row.w3) = (R::c(w[0]), R::c(w[1]), R::c(w[2]), R::c(w[3]));
        row
    }
}

/// The waves of a run: one schedule per sea (`sea::set`), their components back to
/// back in the components buffer, and `STEPS_PER_SUBMISSION` rows per sea in the rows
/// buffer (sea `q`'s at `q * STEPS_PER_SUBMISSION`). Each sea refreshes on its own
/// schedule, as its blocks' caches do on the CPU path.
struct SeaSchedules {
    /// Per sea: its schedule (`None`: still water, rows of zeros).
    seas: Vec<Option<WaveSchedule>>,
    /// Per cable: its sea (empty: all in sea 0).
    cable_sea: Vec<u32>,
    /// Components of every sea.
    n_comps: usize,
}

impl SeaSchedules {
    /// The schedules of `set`'s seas stepping by `dt` (each on its own
    /// [`SeaSet::plan`], as the CPU path's caches).
    fn new(set: &SeaSet, dt: f64) -> Self {
        let mut first = 0u32;
        let seas = set
            .seas
            .iter()
            .enumerate()
            .map(|(q, sea)| {
                (!sea.is_still()).then(|| {
                    let w = WaveSchedule::new(sea, first, &set.plan(q, dt));
                    first += sea.components.len() as u32;
                    w
                })
            })
            .collect();
        Self {
            seas,
            cable_sea: set.cable_sea.clone(),
            n_comps: first as usize,
        }
    }

    /// The first row of the sea of the block starting at packed node `n0`.
    fn block_rows(&self, lay: &Layout, n0: u32) -> u32 {
        let c = lay.node_cable.get(n0 as usize).copied().unwrap_or(0) as usize;
        self.cable_sea.get(c).copied().unwrap_or(0) * STEPS_PER_SUBMISSION
    }

    /// Starts every cache afresh (after a remesh, as the CPU path's caches do).
    fn restart(&mut self) {
        for w in self.seas.iter_mut().flatten() {
            w.clock.reset();
        }
    }
}

struct GpuEngine<R: GpuReal> {
    ctx: GpuContext,
    opts: SolverOptions,
    /// The layout's buffers (replaced at each remeshing).
    inst: Installed<R>,
    bgl: wgpu::BindGroupLayout,
    pipe_elem: wgpu::ComputePipeline,
    pipe_node: wgpu::ComputePipeline,
    pipe_eval: wgpu::ComputePipeline,
    pipe_refresh: wgpu::ComputePipeline,
    /// The waves (`None`: still water).
    waves: Option<SeaSchedules>,
    /// The fused kernel's pipeline and workgroup size, or why there is none.
    pipe_fused: Result<(wgpu::ComputePipeline, u32), String>,
    /// Whether `advance` uses the fused kernel.
    use_fused: bool,
    step_stride: u64,
    /// The time step in f64 (the shaders hold it in `R`; route times are formed in f64).
    dt64: f64,
    timings: GpuTimings,
    _r: PhantomData<R>,
}

/// Bytes of `v`, or of one zeroed element when `v` is empty (bindings may not be empty).
fn bytes_or_one<T: bytemuck::Pod>(v: &[T]) -> Vec<u8> {
    if v.is_empty() {
        vec![0u8; std::mem::size_of::<T>()]
    } else {
        bytemuck::cast_slice(v).to_vec()
    }
}

fn align_up(x: u64, a: u64) -> u64 {
    x.div_ceil(a) * a
}

/// Everything on the device that depends on the layout (rebuilt at each remeshing of
/// a winch cable); the pipelines do not.
struct Installed<R: GpuReal> {
    params: Params<R>,
    buf: Buffers,
    bind_group: wgpu::BindGroup,
    n_nodes: usize,
    n_elems: usize,
    n_routes: usize,
    n_blocks: usize,
    /// The most steps of one fused dispatch ([`fused_max_steps`]).
    fused_max_steps: u64,
}

impl<R: GpuReal> GpuEngine<R> {
    fn new(
        ctx: &GpuContext,
        lay: &Layout,
        host: &Host,
        positions: &[[f64; 3]],
        opts: &SolverOptions,
    ) -> Result<Self, Error> {
        let dev = &ctx.device;
        let step_stride = align_up(
            std::mem::size_of::<StepInfo>() as u64,
            ctx.limits.min_uniform_buffer_offset_alignment as u64,
        );
        let scope = dev.push_error_scope(wgpu::ErrorFilter::Validation);
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let mut entries = vec![storage(0, true)];
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: 1,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(16),
            },
            count: None,
        });
        entries.extend((2..=9).map(|b| storage(b, true)));
        entries.extend((10..=14).map(|b| storage(b, false)));
        entries.extend((15..=16).map(|b| storage(b, true)));
        // The wave components, bodies, the waves' cache and per-step rows.
        entries.push(storage(17, true));
        entries.push(storage(18, true));
        entries.push(storage(19, false));
        entries.push(storage(20, true));
        let bgl = dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cablesim"),
            entries: &entries,
        });
        let pl = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cablesim"),
            bind_group_layouts: &[Some(&bgl)],
            immediate_size: 0,
        });
        let precision = if R::WGSL == "f64" {
            Precision::F64
        } else {
            Precision::F32
        };
        let module = |stage: Stage| {
            dev.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(stage.file()),
                source: wgpu::ShaderSource::Wgsl(shaders::source(stage, precision).into()),
            })
        };
        let m_elem = module(Stage::ElementForces);
        let m_node = module(Stage::NodeUpdate);
        let pipeline = |m: &wgpu::ShaderModule, entry: &str| {
            dev.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pl),
                module: m,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let pipe_elem = pipeline(&m_elem, "element_forces");
        let pipe_node = pipeline(&m_node, "node_update");
        let pipe_eval = pipeline(&m_node, "node_evaluate");
        let pipe_refresh = pipeline(&m_node, "wave_refresh");
        let pipe_fused = fused_workgroup(lay, precision, &ctx.limits, !host.winches.is_empty())
            .map(|wg| {
                let m = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(Stage::FusedSteps.file()),
                    source: wgpu::ShaderSource::Wgsl(
                        shaders::source_with(Stage::FusedSteps, precision, wg).into(),
                    ),
                });
                (pipeline(&m, "fused_steps"), wg)
            });
        let use_fused = pipe_fused.is_ok();
        let inst = Self::build(ctx, &bgl, step_stride, lay, host, opts, None);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(Error::Gpu(format!(
                "building the {} pipelines: {e}",
                precision.name()
            )));
        }
        let mut engine = Self {
            ctx: ctx.clone(),
            opts: *opts,
            inst,
            bgl,
            pipe_elem,
            pipe_node,
            pipe_eval,
            pipe_refresh,
            waves: None,
            pipe_fused,
            use_fused,
            step_stride,
            dt64: opts.dt,
            timings: GpuTimings::default(),
            _r: PhantomData,
        };
        engine.upload(host, positions, &vec![[0.0; 3]; positions.len()]);
        engine.write_routes(lay, host, 0.0);
        Ok(engine)
    }

    /// Creates the layout's buffers and their bind group.
    fn build(
        ctx: &GpuContext,
        bgl: &wgpu::BindGroupLayout,
        step_stride: u64,
        lay: &Layout,
        host: &Host,
        opts: &SolverOptions,
        waves: Option<&SeaSchedules>,
    ) -> Installed<R> {
        let n_comps = waves.map_or(0, |w| w.n_comps);
        let n_seas = waves.map_or(1, |w| w.seas.len().max(1));
        let dev = &ctx.device;
        let env = &lay.env;
        let seabed = env.depth.is_finite();
        let n_winch = host.winches.len();
        let params = Params::<R> {
            n_nodes: lay.n_nodes() as u32,
            n_elems: lay.n_elements() as u32,
            n_routes: lay.routes.len() as u32,
            seabed: seabed as u32,
            step_base: 0,
            n_winch: n_winch as u32,
            n_steps: 0,
            n_bodies: host.bodies.len() as u32,
            dt: R::c(opts.dt),
            alpha: R::c(opts.baumgarte.alpha),
            beta: R::c(opts.baumgarte.beta),
            max_speed: R::c(opts.max_speed),
            max_distance: R::c(opts.max_distance),
            seabed_k: R::c(env.seabed.stiffness),
            seabed_c: R::c(env.seabed.damping),
            seabed_mu: R::c(env.seabed.friction),
            seabed_v_eps: R::c(env.seabed.friction_velocity),
            one: R::c(1.0),
            gravity: R::c(env.gravity),
        };
        let lines: Vec<LineParams<R>> = lay
            .line_coefs
            .iter()
            .map(|c| LineParams {
                ea: R::c(c.ea),
                ea_c: R::c(c.ea_c),
                drag_n: R::c(c.drag_n),
                drag_t: R::c(c.drag_t),
                froude_krylov: R::c(c.froude_krylov),
                mass: R::c(c.mass),
                added_mass: R::c(c.added_mass),
                wet_weight_z: R::c(c.wet_weight_z),
                compression: R::c(c.compression),
            })
            .collect();
        let elems: Vec<ElemParams<R>> = (0..lay.n_elements())
            .map(|e| ElemParams {
                a: lay.elem_a[e],
                b: lay.elem_b[e],
                line: lay.elem_line[e],
                current: lay.elem_current[e],
                block: host.node_block[lay.elem_a[e] as usize],
                winch: host.elem_winch[e],
                l0: split::<R>(lay.elem_l0[e]).0,
                l0_lo: split::<R>(lay.elem_l0[e]).1,
                diameter: R::c(lay.line_types[lay.elem_line[e] as usize].diameter),
            })
            .collect();
        let nodes: Vec<NodeParams<R>> = (0..lay.n_nodes())
            .map(|i| NodeParams {
                inc_start: lay.inc_start[i],
                inc_end: lay.inc_start[i + 1],
                constraint: lay.node_constraint[i],
                block: host.node_block[i],
                current: lay.node_current[i],
                winch: host.node_winch[i],
                point_mass: R::c(lay.node_point_mass[i]),
                point_weight_z: R::c(lay.node_point_weight_z[i]),
                point_drag: R::c(lay.node_point_drag[i]),
                tributary: R::c(lay.node_tributary[i]),
                point_added: R::c(lay.node_point_added[i]),
                point_displaced: R::c(lay.node_point_displaced[i]),
                point_radius: R::c(lay.node_point_radius[i]),
            })
            .collect();
        let blocks: Vec<BlockParams<R>> = host
            .origin
            .iter()
            .zip(&lay.blocks)
            .map(|(o, b)| BlockParams {
                ox: R::c(o[0]),
                oy: R::c(o[1]),
                oz: R::c(o[2]),
                zb: R::c(if seabed { -env.depth - o[2] } else { 0.0 }),
                node_start: b.node_start,
                node_end: b.node_end,
                elem_start: b.elem_start,
                elem_end: b.elem_end,
                wave_rows: waves.map_or(0, |w| w.block_rows(lay, b.node_start)),
                pad: 0,
            })
            .collect();
        let mut current_pts = Vec::new();
        let mut current_ranges = Vec::new();
        for c in &lay.currents {
            current_ranges.push(CurrentRange {
                start: current_pts.len() as u32,
                len: c.table.len() as u32,
            });
            for (z, u) in &c.table {
                current_pts.push(CurrentPoint {
                    z: R::c(*z),
                    ux: R::c(u[0]),
                    uy: R::c(u[1]),
                    uz: R::c(u[2]),
                });
            }
        }
        let n_nodes = lay.n_nodes();
        let n_elems = lay.n_elements();
        let n_routes = lay.routes.len();
        let n_blocks = lay.blocks.len();

        let mut steps = vec![0u8; (step_stride * STEPS_PER_SUBMISSION as u64) as usize];
        for k in 0..STEPS_PER_SUBMISSION as usize {
            let s = StepInfo {
                k: k as u32,
                ..Default::default()
            };
            let off = k * step_stride as usize;
            steps[off..off + 16].copy_from_slice(bytemuck::bytes_of(&s));
        }

        use wgpu::BufferUsages as U;
        let init = |label: &str, contents: &[u8], usage: U| {
            dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let ro = U::STORAGE;
        let rw = U::STORAGE | U::COPY_SRC | U::COPY_DST;
        let state_bytes = (n_nodes.max(1) * std::mem::size_of::<NodeState<R>>()) as u64;
        let loads_bytes = (n_elems.max(1) * std::mem::size_of::<ElemLoads<R>>()) as u64;
        let out_bytes = (n_nodes.max(1) * std::mem::size_of::<NodeOut<R>>()) as u64;
        let react_bytes = (n_routes.max(1) * std::mem::size_of::<[R; 4]>()) as u64;
        let payout_bytes = ((STEPS_PER_SUBMISSION as usize * n_winch).max(1)
            * std::mem::size_of::<Payout<R>>()) as u64;
        let body_bytes = ((STEPS_PER_SUBMISSION as usize * host.bodies.len()).max(1)
            * std::mem::size_of::<BodyRow<R>>()) as u64;
        let staging_bytes = [state_bytes, loads_bytes, out_bytes, react_bytes, 16]
            .iter()
            .map(|&b| align_up(b, 256))
            .sum();
        let zeros = |n: u64| vec![0u8; n as usize];
        let buf = Buffers {
            params: init("params", bytemuck::bytes_of(&params), ro | U::COPY_DST),
            step: init("step", &steps, U::UNIFORM | U::COPY_DST),
            routes: init(
                "routes",
                &bytes_or_one(&vec![RouteParams::<R>::zeroed(); n_routes]),
                ro | U::COPY_DST,
            ),
            state: init("state", &zeros(state_bytes), rw),
            elem_loads: init("elem_loads", &zeros(loads_bytes), rw),
            node_out: init("node_out", &zeros(out_bytes), rw),
            reactions: init("reactions", &zeros(react_bytes), rw),
            status: init("status", &zeros(16), rw),
            payout: init("payout", &zeros(payout_bytes), ro | U::COPY_DST),
            body_rows: init("body_rows", &zeros(body_bytes), ro | U::COPY_DST),
            wave_comps: init(
                "wave_comps",
                &zeros((n_comps.max(1) * std::mem::size_of::<WaveComp<R>>()) as u64),
                ro | U::COPY_DST,
            ),
            // Still water: rows of zeros (no components) are never rewritten.
            wave_steps: init(
                "wave_steps",
                &zeros(
                    (n_seas as u64 * STEPS_PER_SUBMISSION as u64)
                        * std::mem::size_of::<WaveStep<R>>() as u64,
                ),
                ro | U::COPY_DST,
            ),
            staging: dev.create_buffer(&wgpu::BufferDescriptor {
                label: Some("staging"),
                size: staging_bytes,
                usage: U::MAP_READ | U::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        let lines_b = init("lines", &bytes_or_one(&lines), ro);
        let elems_b = init("elems", &bytes_or_one(&elems), ro);
        let nodes_b = init("nodes", &bytes_or_one(&nodes), ro);
        let inc_b = init("inc", &bytes_or_one(&lay.inc), ro);
        let blocks_b = init("blocks", &bytes_or_one(&blocks), ro);
        let pts_b = init("current_pts", &bytes_or_one(&current_pts), ro);
        let ranges_b = init("current_ranges", &bytes_or_one(&current_ranges), ro);
        let samples: Vec<RouteSample<R>> = lay
            .routes
            .iter()
            .enumerate()
            .flat_map(|(c, r)| route_samples::<R>(r, host.route_origin(lay, c)))
            .collect();
        let samples_b = init("route_samples", &bytes_or_one(&samples), ro);
        // Two slots (t0, t1) of WAVE_CACHE_STRIDE values per node, then each node's
        // velocity at the last refresh; one value in still water.
        let cache_len = if n_comps == 0 {
            1
        } else {
            n_nodes * (2 * WAVE_CACHE_STRIDE + 3)
        };
        let cache_b = init(
            "wave_cache",
            &zeros((cache_len * std::mem::size_of::<R>()) as u64),
            U::STORAGE,
        );
        fn whole(binding: u32, b: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry {
                binding,
                resource: b.as_entire_binding(),
            }
        }
        let bind_group = dev.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cablesim"),
            layout: bgl,
            entries: &[
                whole(0, &buf.params),
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buf.step,
                        offset: 0,
                        size: wgpu::BufferSize::new(16),
                    }),
                },
                whole(2, &lines_b),
                whole(3, &elems_b),
                whole(4, &nodes_b),
                whole(5, &inc_b),
                whole(6, &buf.routes),
                whole(7, &blocks_b),
                whole(8, &pts_b),
                whole(9, &ranges_b),
                whole(10, &buf.state),
                whole(11, &buf.elem_loads),
                whole(12, &buf.node_out),
                whole(13, &buf.reactions),
                whole(14, &buf.status),
                whole(15, &samples_b),
                whole(16, &buf.payout),
                whole(17, &buf.wave_comps),
                whole(18, &buf.body_rows),
                whole(19, &cache_b),
                whole(20, &buf.wave_steps),
            ],
        });
        Installed {
            params,
            buf,
            bind_group,
            n_nodes,
            n_elems,
            n_routes,
            n_blocks,
            fused_max_steps: fused_max_steps(lay),
        }
    }

    /// Writes the `payout` rows of steps `step0 .. step0 + n` (rows `0 .. n`): the
    /// variable element of each winch cable at each step's time, from its schedule, in
    /// f64 exactly as the CPU path forms them (`ale::AleElem::l0`).
    fn write_payout(&self, host: &Host, step0: u64, n: u64) {
        if host.winches.is_empty() {
            return;
        }
        let mut rows = Vec::with_capacity(n as usize * host.winches.len());
        for k in 0..n {
            // Time from the step count, as the CPU path forms it.
            let t = (step0 + k) as f64 * self.dt64;
            for ae in &host.winches {
                let pay = ae.sched.eval(t);
                let l0 = ae.l0(pay.dl);
                let (hi, lo) = split::<R>(l0);
                rows.push(Payout::<R> {
                    l0: hi,
                    l0_lo: lo,
                    rate: R::c(pay.rate),
                    accel: R::c(pay.accel),
                    trib: R::c(0.5 * (l0 - ae.base_l0)),
                });
            }
        }
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.payout, 0, bytemuck::cast_slice(&rows));
    }

    /// Writes the `body_rows` of steps `step0 .. step0 + n` (rows `0 .. n`, one per
    /// body each), relative to each body's state at `step0` (the routes' rebase time).
    fn write_bodies(&self, host: &Host, step0: u64, n: u64) {
        if host.bodies.is_empty() {
            return;
        }
        let dt = self.dt64;
        // Bodies in parallel (a packed study has one per member); each row a function
        // of its time alone, so the rows do not depend on the thread count.
        let per_body: Vec<Vec<BodyRow<R>>> = host
            .bodies
            .par_iter()
            .map(|b| {
                body_rows(
                    b,
                    step0 as f64 * dt,
                    (0..n).map(|k| (step0 + k) as f64 * dt),
                )
            })
            .collect();
        let rows: Vec<BodyRow<R>> = (0..n as usize)
            .flat_map(|k| per_body.iter().map(move |b| b[k]))
            .collect();
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.body_rows, 0, bytemuck::cast_slice(&rows));
    }

    fn write_routes(&self, lay: &Layout, host: &Host, t0: f64) {
        if lay.routes.is_empty() {
            return;
        }
        let q: Vec<RouteParams<R>> = lay
            .routes
            .iter()
            .enumerate()
            .map(|(c, r)| {
                let mut q = rebased_route(
                    r,
                    lay.constraint_node[c],
                    t0,
                    host.route_origin(lay, c),
                    host.table_start[c],
                );
                q.body = host.route_body[c];
                q
            })
            .collect();
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.routes, 0, bytemuck::cast_slice(&q));
    }

    /// Rebases every sea's wave components to `t_ref` and writes them, back to back
    /// (waves only).
    fn write_wave_comps(&mut self, t_ref: f64) {
        let Some(w) = self.waves.as_mut() else {
            return;
        };
        let mut comps: Vec<WaveComp<R>> = Vec::with_capacity(w.n_comps);
        for sea in w.seas.iter_mut().flatten() {
            sea.field.rebase(t_ref);
            comps.extend(sea.field.comps.iter().map(WaveComp::from_packed));
        }
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.wave_comps, 0, bytemuck::cast_slice(&comps));
    }

    /// Writes the `wave_steps` rows of steps `step0 .. step0 + n` of every sea,
    /// components referred to the time of `step0`; returns which steps refresh the
    /// cache of some sea (none in still water).
    fn write_waves(&mut self, step0: u64, n: u64) -> Vec<bool> {
        if self.waves.is_none() {
            return vec![false; n as usize];
        }
        let dt = self.dt64;
        let t_ref = step0 as f64 * dt;
        self.write_wave_comps(t_ref);
        let w = self.waves.as_mut().expect("waves");
        let per = STEPS_PER_SUBMISSION as usize;
        let mut rows = vec![WaveStep::<R>::default(); w.seas.len() * per];
        let mut refresh = vec![false; n as usize];
        for (q, sea) in w.seas.iter_mut().enumerate() {
            let Some(sea) = sea else { continue };
            for k in 0..n as usize {
                let row = sea.step::<R>((step0 + k as u64) as f64 * dt, t_ref);
                refresh[k] |= row.refresh != 0;
                rows[q * per + k] = row;
            }
        }
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.wave_steps, 0, bytemuck::cast_slice(&rows));
        refresh
    }

    fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>, pipe: &wgpu::ComputePipeline, n: usize) {
        pass.set_pipeline(pipe);
        pass.dispatch_workgroups((n as u32).div_ceil(WORKGROUP).max(1), 1, 1);
    }

    /// Copies `(buffer, bytes)` pairs into the staging buffer, waits, and returns the
    /// bytes of each.
    fn read_back(&self, parts: &[(&wgpu::Buffer, u64)]) -> Result<Vec<Vec<u8>>, Error> {
        let ctx = &self.ctx;
        let mut enc = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("read_back"),
            });
        let mut offsets = Vec::new();
        let mut off = 0u64;
        for (b, n) in parts {
            enc.copy_buffer_to_buffer(b, 0, &self.inst.buf.staging, off, *n);
            offsets.push(off);
            off = align_up(off + n, 256);
        }
        ctx.queue.submit([enc.finish()]);
        let slice = self.inst.buf.staging.slice(0..off);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| Error::Gpu(format!("waiting for the device: {e}")))?;
        ctx.take_error()?;
        rx.recv()
            .map_err(|e| Error::Gpu(format!("read-back: {e}")))?
            .map_err(|e| Error::Gpu(format!("read-back: {e}")))?;
        let out = {
            let view = slice
                .get_mapped_range()
                .map_err(|e| Error::Gpu(format!("read-back: {e}")))?;
            parts
                .iter()
                .zip(&offsets)
                .map(|((_, n), &o)| view[o as usize..(o + n) as usize].to_vec())
                .collect()
        };
        self.inst.buf.staging.unmap();
        Ok(out)
    }
}

/// The fused kernel's dispatches of a submission, as step ranges `a .. b`: a new one
/// starts at every step that refreshes the waves' cache (`refresh[k]`), after a
/// `wave_refresh` dispatch, and after at most `max_len` steps. Why: on llvmpipe
/// (lavapipe) all the loops of a shader invocation share one budget of 65535
/// iterations, after which each loop stops after one iteration without a word
/// (`shaders/fused_chain.wgsl`). The refresh's sums over the wave components spent it
/// within a submission, so the fused kernel does not refresh; `max_len`
/// ([`fused_max_steps`]) keeps the loops of its steps within it.
fn fused_segments(refresh: &[bool], max_len: u64) -> Vec<(u64, u64)> {
    let n = refresh.len() as u64;
    let max_len = max_len.max(1);
    let mut segs = Vec::new();
    let mut a = 0;
    for k in 1..=n {
        if k == n || refresh[k as usize] || k - a == max_len {
            segs.push((a, k));
            a = k;
        }
    }
    segs
}

/// The most steps one fused dispatch may take on this layout: half of llvmpipe's
/// budget of 65535 loop iterations per shader invocation over an upper bound of one
/// step's iterations (the step loop, a node's incidence list, the linear search of the
/// longest current profile, the binary search of the longest route table). 512 steps
/// (a whole submission) fit unless a current profile has more than some 50 points.
fn fused_max_steps(lay: &Layout) -> u64 {
    const LOOP_BUDGET: u64 = 65535 / 2;
    let incidence = lay
        .inc_start
        .windows(2)
        .map(|w| w[1] - w[0])
        .max()
        .unwrap_or(0) as u64;
    let profile = lay
        .currents
        .iter()
        .map(|c| c.table.len())
        .max()
        .unwrap_or(0) as u64;
    let table = lay
        .routes
        .iter()
        .map(|r| match r {
            Route::Table { t, .. } => t.len(),
            _ => 0,
        })
        .max()
        .unwrap_or(0) as u64;
    let search = 64 - table.leading_zeros() as u64 + 1;
    let per_step = 1 + incidence + profile + search;
    (LOOP_BUDGET / per_step).max(1)
}

/// Decodes read-back bytes (the staging copy is not aligned for `T`).
fn decode<T: bytemuck::Pod>(b: &[u8]) -> Vec<T> {
    b.chunks_exact(std::mem::size_of::<T>())
        .map(bytemuck::pod_read_unaligned)
        .collect()
}

fn v3<R: GpuReal>(a: &[R]) -> [f64; 3] {
    [a[0].f64(), a[1].f64(), a[2].f64()]
}

impl<R: GpuReal> Engine for GpuEngine<R> {
    fn advance(
        &mut self,
        lay: &Layout,
        host: &Host,
        step0: u64,
        n: u64,
    ) -> Result<Option<(u64, u32)>, Error> {
        let ctx = &self.ctx.clone();
        ctx.queue.write_buffer(
            &self.inst.buf.status,
            0,
            bytemuck::bytes_of(&Status::default()),
        );
        let dt64 = self.dt64;
        let mut done = 0u64;
        let t_start = Instant::now();
        while done < n {
            let chunk = (n - done).min(STEPS_PER_SUBMISSION as u64);
            let t_enc = Instant::now();
            self.write_routes(lay, host, (step0 + done) as f64 * dt64);
            self.write_payout(host, step0 + done, chunk);
            self.write_bodies(host, step0 + done, chunk);
            let refresh = self.write_waves(step0 + done, chunk);
            self.inst.params.step_base = done as u32;
            self.inst.params.n_steps = chunk as u32;
            ctx.queue.write_buffer(
                &self.inst.buf.params,
                0,
                bytemuck::bytes_of(&self.inst.params),
            );
            let mut enc = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("steps"),
                });
            {
                let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("step"),
                    timestamp_writes: None,
                });
                match (&self.pipe_fused, self.use_fused) {
                    (Ok((pipe, _)), true) => {
                        // One workgroup per block, stepping from one refresh of the
                        // waves' cache to the next (all `chunk` steps in still water).
                        for (a, b) in fused_segments(&refresh, self.inst.fused_max_steps) {
                            let off = a * self.step_stride;
                            let info = StepInfo {
                                k: a as u32,
                                end: b as u32,
                                ..Default::default()
                            };
                            ctx.queue.write_buffer(
                                &self.inst.buf.step,
                                off,
                                bytemuck::bytes_of(&info),
                            );
                            pass.set_bind_group(0, &self.inst.bind_group, &[off as u32]);
                            if refresh[a as usize] {
                                self.dispatch(&mut pass, &self.pipe_refresh, self.inst.n_nodes);
                                self.timings.dispatches += 1;
                            }
                            pass.set_pipeline(pipe);
                            pass.dispatch_workgroups(self.inst.n_blocks as u32, 1, 1);
                            self.timings.dispatches += 1;
                        }
                    }
                    _ => {
                        for k in 0..chunk {
                            let off = (k * self.step_stride) as u32;
                            pass.set_bind_group(0, &self.inst.bind_group, &[off]);
                            if refresh[k as usize] {
                                self.dispatch(&mut pass, &self.pipe_refresh, self.inst.n_nodes);
                                self.timings.dispatches += 1;
                            }
                            self.dispatch(&mut pass, &self.pipe_elem, self.inst.n_elems);
                            self.dispatch(&mut pass, &self.pipe_node, self.inst.n_nodes);
                        }
                        self.timings.dispatches += 2 * chunk;
                    }
                }
            }
            let cb = enc.finish();
            self.timings.encode_seconds += t_enc.elapsed().as_secs_f64();
            let t_sub = Instant::now();
            ctx.queue.submit([cb]);
            self.timings.submit_seconds += t_sub.elapsed().as_secs_f64();
            self.timings.submissions += 1;
            done += chunk;
        }
        let t_wait = Instant::now();
        let out = self.read_back(&[(&self.inst.buf.status, 16)])?;
        self.timings.wait_seconds += t_wait.elapsed().as_secs_f64();
        self.timings.advance_seconds += t_start.elapsed().as_secs_f64();
        self.timings.steps += n;
        let st: Status = bytemuck::pod_read_unaligned(&out[0][..16]);
        if st.failed & FUSED_FAILED == 0 {
            return Ok((st.failed != 0).then_some((st.step as u64, st.node)));
        }
        // The fused kernel: the earliest failing step of the failing submission and
        // its block; the block stopped there, so its failing node is the first whose
        // state fails the check.
        let k = 0x7fff - ((st.failed >> 16) & 0x7fff);
        let b = &lay.blocks[(0xffff - (st.failed & 0xffff)) as usize];
        let (r, v) = self.download(host)?;
        let bad = |i: usize| {
            !(r[i].iter().all(|x| x.abs() < self.opts.max_distance)
                && v[i].iter().all(|x| x.abs() < self.opts.max_speed))
        };
        let node = (b.node_start..b.node_end)
            .find(|&i| bad(i as usize))
            .unwrap_or(b.node_start);
        Ok(Some((st.step as u64 + k as u64, node)))
    }

    fn timings(&self) -> GpuTimings {
        self.timings
    }

    fn kernel(&self) -> GpuKernel {
        if self.use_fused && self.pipe_fused.is_ok() {
            GpuKernel::Fused
        } else {
            GpuKernel::TwoPass
        }
    }

    fn fused_unavailable(&self) -> Option<&str> {
        self.pipe_fused.as_ref().err().map(|s| s.as_str())
    }

    fn set_kernel(&mut self, k: GpuKernel) -> Result<(), Error> {
        if k == GpuKernel::Fused {
            if let Err(why) = &self.pipe_fused {
                return Err(Error::GpuUnsupported(format!("the fused kernel: {why}")));
            }
        }
        self.use_fused = k == GpuKernel::Fused;
        Ok(())
    }

    fn install(
        &mut self,
        lay: &Layout,
        host: &Host,
        r: &[[f64; 3]],
        v: &[[f64; 3]],
    ) -> Result<(), Error> {
        let scope = self
            .ctx
            .device
            .push_error_scope(wgpu::ErrorFilter::Validation);
        // A new mesh starts the waves' cache afresh (as the CPU path's does).
        if let Some(w) = self.waves.as_mut() {
            w.restart();
        }
        self.inst = Self::build(
            &self.ctx,
            &self.bgl,
            self.step_stride,
            lay,
            host,
            &self.opts,
            self.waves.as_ref(),
        );
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(Error::Gpu(format!("rebuilding the buffers: {e}")));
        }
        self.upload(host, r, v);
        Ok(())
    }

    fn set_seas(&mut self, lay: &Layout, host: &Host, seas: &SeaSet) -> Result<(), Error> {
        self.waves = (!seas.is_still()).then(|| SeaSchedules::new(seas, self.dt64));
        let scope = self
            .ctx
            .device
            .push_error_scope(wgpu::ErrorFilter::Validation);
        let new = Self::build(
            &self.ctx,
            &self.bgl,
            self.step_stride,
            lay,
            host,
            &self.opts,
            self.waves.as_ref(),
        );
        let old = std::mem::replace(&mut self.inst, new);
        // The state moves over bit for bit (no round trip through f64 positions).
        let bytes = (self.inst.n_nodes.max(1) * std::mem::size_of::<NodeState<R>>()) as u64;
        let mut enc = self
            .ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("set_sea"),
            });
        enc.copy_buffer_to_buffer(&old.buf.state, 0, &self.inst.buf.state, 0, bytes);
        self.ctx.queue.submit([enc.finish()]);
        self.write_routes(lay, host, 0.0);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(Error::Gpu(format!("installing the waves: {e}")));
        }
        Ok(())
    }

    fn download(&mut self, host: &Host) -> Result<NodeStates, Error> {
        let bytes = (self.inst.n_nodes * std::mem::size_of::<NodeState<R>>()) as u64;
        let out = self.read_back(&[(&self.inst.buf.state, bytes.max(4))])?;
        let st: Vec<NodeState<R>> = decode(&out[0][..bytes as usize]);
        let mut r = Vec::with_capacity(self.inst.n_nodes);
        let mut v = Vec::with_capacity(self.inst.n_nodes);
        for (i, s) in st.iter().enumerate() {
            let o = host.origin[host.node_block[i] as usize];
            let (h, l) = (v3(&s.r_hi), v3(&s.r_lo));
            r.push([0, 1, 2].map(|d| o[d] + (h[d] + l[d])));
            v.push(v3(&s.v));
        }
        Ok((r, v))
    }

    fn restart_waves(&mut self) {
        if let Some(w) = self.waves.as_mut() {
            w.restart();
        }
    }

    fn upload(&mut self, host: &Host, r: &[[f64; 3]], v: &[[f64; 3]]) {
        let st: Vec<NodeState<R>> = (0..self.inst.n_nodes)
            .map(|i| {
                let o = host.origin[host.node_block[i] as usize];
                let mut s = NodeState::<R>::default();
                for d in 0..3 {
                    (s.r_hi[d], s.r_lo[d]) = split(r[i][d] - o[d]);
                    s.v[d] = R::c(v[i][d]);
                }
                s
            })
            .collect();
        if !st.is_empty() {
            self.ctx
                .queue
                .write_buffer(&self.inst.buf.state, 0, bytemuck::cast_slice(&st));
        }
    }

    fn evaluate(&mut self, lay: &Layout, host: &Host, step: u64) -> Result<Evaluation, Error> {
        let ctx = &self.ctx.clone();
        self.write_routes(lay, host, step as f64 * self.dt64);
        self.write_payout(host, step, 1);
        self.write_bodies(host, step, 1);
        let t = step as f64 * self.dt64;
        // The components referred to `t`, as the next submission's (it starts at this
        // step), and each sea's row of the step at `t`: the cache interpolated at `t`,
        // refreshed first (the refresh dispatch below) where that step would refresh it,
        // which then finds it covering its time (the CPU path's rule:
        // `cpu::water::BlockWaves::cover`).
        self.write_wave_comps(t);
        if let Some(w) = self.waves.as_mut() {
            let per = STEPS_PER_SUBMISSION as usize;
            let mut rows = vec![WaveStep::<R>::default(); w.seas.len() * per];
            for (q, sea) in w.seas.iter_mut().enumerate() {
                if let Some(sea) = sea {
                    rows[q * per] = sea.step::<R>(t, t);
                }
            }
            ctx.queue
                .write_buffer(&self.inst.buf.wave_steps, 0, bytemuck::cast_slice(&rows));
        }
        self.inst.params.step_base = 0;
        ctx.queue.write_buffer(
            &self.inst.buf.params,
            0,
            bytemuck::bytes_of(&self.inst.params),
        );
        let mut enc = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("evaluate"),
            });
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("evaluate"),
                timestamp_writes: None,
            });
            pass.set_bind_group(0, &self.inst.bind_group, &[0]);
            if self.waves.is_some() {
                self.dispatch(&mut pass, &self.pipe_refresh, self.inst.n_nodes);
            }
            self.dispatch(&mut pass, &self.pipe_elem, self.inst.n_elems);
            self.dispatch(&mut pass, &self.pipe_eval, self.inst.n_nodes);
        }
        ctx.queue.submit([enc.finish()]);
        let loads_bytes = (self.inst.n_elems * std::mem::size_of::<ElemLoads<R>>()) as u64;
        let out_bytes = (self.inst.n_nodes * std::mem::size_of::<NodeOut<R>>()) as u64;
        let react_bytes = (self.inst.n_routes * std::mem::size_of::<[R; 4]>()) as u64;
        let out = self.read_back(&[
            (&self.inst.buf.elem_loads, loads_bytes.max(4)),
            (&self.inst.buf.node_out, out_bytes.max(4)),
            (&self.inst.buf.reactions, react_bytes.max(4)),
        ])?;
        let loads: Vec<ElemLoads<R>> = decode(&out[0][..loads_bytes as usize]);
        let nout: Vec<NodeOut<R>> = decode(&out[1][..out_bytes as usize]);
        let react: Vec<[R; 4]> = decode(&out[2][..react_bytes as usize]);
        Ok(Evaluation {
            acc: nout.iter().map(|o| v3(&o.acc)).collect(),
            force: nout.iter().map(|o| v3(&o.force)).collect(),
            tension: loads.iter().map(|l| l.tension.f64()).collect(),
            reaction: react.iter().map(|x| v3(x)).collect(),
            elements: loads
                .iter()
                .map(|l| crate::physics::ElementLoads {
                    t: crate::math::V3::new(l.tx.f64(), l.ty.f64(), l.tz.f64()),
                    tension: l.tension.f64(),
                    f_half: crate::math::V3::new(l.fx.f64(), l.fy.f64(), l.fz.f64()),
                    half_mass: l.half_mass.f64(),
                    half_added: l.half_added.f64(),
                })
                .collect(),
        })
    }
}

/// The GPU solver: the same packed model and options as [`crate::cpu::CpuSolver`],
/// stepped by WGSL compute shaders at f32 or f64.
///
/// Winch cables (ALE-GLMF, [`crate::ale`]; [`GpuSolver::with_winches`]) step inside
/// the same submissions as every other cable: the variable element's `l0_v(t)`, payout
/// rate and acceleration of each step are written by the host per submission (one
/// small row per winch and step, from the schedule, in f64 as the CPU path forms them),
/// and the shaders apply the variable `l0` (its mass, weight, added mass, stretch and
/// tributary lengths), the ALE strain-rate damping and the mass-flow forces of Eq. 39.
/// The schedule fixes in advance the step at which a cable must be remeshed, so an
/// [`GpuSolver::advance`] call ends its submissions exactly there, reads the state
/// back, remeshes on the host with the CPU path's code (`WinchTracker` and the same
/// node insertion or deletion, spliced into the host's packed layout), uploads the
/// layout's buffers (the pipelines are kept), and goes on: one round trip per remeshing, every `l_s / Ldot`
/// seconds, none per step.
pub struct GpuSolver {
    /// The packed model (the current mesh, with winches).
    layout: Layout,
    /// Options (GLMF, symplectic Euler; see [`unsupported`]).
    opts: SolverOptions,
    /// Shader precision.
    precision: Precision,
    /// Simulated time, s.
    t: f64,
    /// Number of steps taken.
    steps: u64,
    /// Node-steps taken: nodes times steps, summed over the meshes a run went through.
    node_steps: u64,
    /// Remeshings of winch cables so far (each one state read-back and re-upload).
    remeshes: u64,
    device: String,
    host: Host,
    engine: Box<dyn Engine>,
    /// Winch cables, if any.
    ale: Option<Box<AleState>>,
}

impl GpuSolver {
    /// The packed model (the current mesh, with winches).
    pub fn layout(&self) -> &Layout {
        &self.layout
    }
    /// The options it steps with.
    pub fn opts(&self) -> &SolverOptions {
        &self.opts
    }
    /// Shader precision.
    pub fn precision(&self) -> Precision {
        self.precision
    }
    /// Simulated time, s.
    pub fn t(&self) -> f64 {
        self.t
    }
    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// Node-steps taken: nodes times steps, summed over the meshes a run went through.
    pub fn node_steps(&self) -> u64 {
        self.node_steps
    }
    /// Remeshings of winch cables so far (each one state read-back and re-upload).
    pub fn remeshes(&self) -> u64 {
        self.remeshes
    }

    /// Uploads the model, at rest at `positions` (packed order), `t = 0`.
    pub fn new(
        ctx: &GpuContext,
        layout: Layout,
        positions: &[[f64; 3]],
        opts: SolverOptions,
        precision: Precision,
    ) -> Result<Self, Error> {
        Self::build(ctx, layout, positions, opts, precision, None)
    }

    /// Uploads the model of `def`, at rest at `positions` (packed order of
    /// `Layout::build(&def)`), `t = 0`, whose cables listed in `winches` pay out or
    /// haul in (ALE-GLMF), as [`crate::cpu::CpuSolver::with_winches`] does on the CPU.
    pub fn with_winches(
        ctx: &GpuContext,
        def: ModelDef,
        winches: Vec<Winch>,
        positions: &[[f64; 3]],
        opts: SolverOptions,
        precision: Precision,
    ) -> Result<Self, Error> {
        if winches.is_empty() {
            let (lay, _) = Layout::build(&def)?;
            return Self::new(ctx, lay, positions, opts, precision);
        }
        if let Some(what) = unsupported_winches(&def, &winches) {
            return Err(Error::GpuUnsupported(what));
        }
        let (lay, pos0, packed) = Layout::build_indexed(&def)?;
        if pos0.len() != positions.len() {
            return Err(Error::Model(format!(
                "{} initial positions for {} nodes",
                positions.len(),
                pos0.len()
            )));
        }
        let mut ale = AleState::new(def, winches, packed)?;
        ale.index(&lay);
        Self::build(ctx, lay, positions, opts, precision, Some(Box::new(ale)))
    }

    fn build(
        ctx: &GpuContext,
        layout: Layout,
        positions: &[[f64; 3]],
        opts: SolverOptions,
        precision: Precision,
        ale: Option<Box<AleState>>,
    ) -> Result<Self, Error> {
        if let Some(what) = unsupported(&layout, &opts) {
            return Err(Error::GpuUnsupported(what));
        }
        if !ctx.supports(precision) {
            return Err(Error::NoAdapter(format!(
                "{} has no SHADER_F64: f64 shaders cannot run (use --precision f32)",
                ctx.describe()
            )));
        }
        let host = Host::new(&layout, positions, ale.as_deref())?;
        let engine: Box<dyn Engine> = match precision {
            Precision::F32 => Box::new(GpuEngine::<f32>::new(
                ctx, &layout, &host, positions, &opts,
            )?),
            Precision::F64 => Box::new(GpuEngine::<f64>::new(
                ctx, &layout, &host, positions, &opts,
            )?),
        };
        let mut engine = engine;
        if let Some(k) = kernel_from_env()? {
            engine.set_kernel(k)?;
        }
        Ok(Self {
            layout,
            opts,
            precision,
            t: 0.0,
            steps: 0,
            node_steps: 0,
            remeshes: 0,
            device: ctx.describe(),
            host,
            engine,
            ale,
        })
    }

    /// The adapter it runs on.
    pub fn device(&self) -> &str {
        &self.device
    }

    /// Where the wall time of [`Self::advance`] went so far (host recording, submission,
    /// waiting for the device).
    pub fn timings(&self) -> GpuTimings {
        self.engine.timings()
    }

    /// The kernel [`Self::advance`] uses: [`GpuKernel::Fused`] where it applies
    /// ([`fused_workgroup`]), unless [`Self::set_kernel`] or the environment variable
    /// `CABLESIM_GPU_KERNEL=two-pass` asked for the two-pass path.
    pub fn kernel(&self) -> GpuKernel {
        self.engine.kernel()
    }

    /// Why the fused kernel cannot step this layout on this adapter, or `None`.
    pub fn fused_unavailable(&self) -> Option<&str> {
        self.engine.fused_unavailable()
    }

    /// Chooses the kernel of later [`Self::advance`] calls (both step the same
    /// physics; results agree to round-off). Asking for [`GpuKernel::Fused`] where it
    /// does not apply is an error.
    pub fn set_kernel(&mut self, k: GpuKernel) -> Result<(), Error> {
        self.engine.set_kernel(k)
    }

    /// Where each winch cable stands now (empty without winches).
    pub fn winch_status(&self) -> Vec<WinchStatus> {
        self.ale
            .as_deref()
            .map_or_else(Vec::new, |a| a.status(self.t))
    }

    /// Advances `nsteps` steps of `opts.dt`, in submissions of
    /// [`STEPS_PER_SUBMISSION`] steps, then reads the 16-byte status. On a blow-up the
    /// state stays where it failed and the error names the cable, node and time, as on
    /// the CPU. With winches, the submissions end at each step after which a winch
    /// cable must be remeshed (known in advance from the schedules); the state is read
    /// back, remeshed on the host as on the CPU path, and uploaded with the new layout.
    pub fn advance(&mut self, nsteps: u64) -> Result<(), Error> {
        if self.ale.is_none() {
            return self.advance_fixed(nsteps);
        }
        let dt = self.opts.dt;
        let mut left = nsteps;
        while left > 0 {
            let ale = self.ale.as_deref().expect("winches");
            let k = ale.steps_on_this_mesh(self.steps, left, dt);
            self.advance_fixed(k)?;
            left -= k;
            if self.ale.as_deref().expect("winches").needs_action(self.t) {
                self.remesh()?;
            }
        }
        Ok(())
    }

    /// Reads the state back, remeshes the winch cables at the current time and
    /// installs the new layout and state.
    fn remesh(&mut self) -> Result<(), Error> {
        let (r, v) = self.engine.download(&self.host)?;
        let mut r: Vec<V3<f64>> = r.iter().map(|p| V3::from_f64(*p)).collect();
        let mut v: Vec<V3<f64>> = v.iter().map(|p| V3::from_f64(*p)).collect();
        let ale = self.ale.as_deref_mut().expect("winches");
        // The host's layout is spliced in place where it can be (as on the CPU path);
        // the device buffers are uploaded whole.
        if ale.remesh_in_place(self.t, &mut self.layout, &mut r, &mut v)? {
            let r: Vec<[f64; 3]> = r.iter().map(|x| x.to_f64()).collect();
            let v: Vec<[f64; 3]> = v.iter().map(|x| x.to_f64()).collect();
            self.host = Host::new(&self.layout, &r, Some(ale))?;
            self.engine.install(&self.layout, &self.host, &r, &v)?;
            self.remeshes += 1;
        }
        Ok(())
    }

    /// Advances `nsteps` steps on the current mesh.
    fn advance_fixed(&mut self, nsteps: u64) -> Result<(), Error> {
        if nsteps == 0 {
            return Ok(());
        }
        let step0 = self.steps;
        let failed = self
            .engine
            .advance(&self.layout, &self.host, step0, nsteps)?;
        self.steps += nsteps;
        self.node_steps += nsteps * self.layout.n_nodes() as u64;
        self.t = self.steps as f64 * self.opts.dt;
        if let Some((k, node)) = failed {
            let (r, v) = self.engine.download(&self.host)?;
            let i = node as usize;
            let time = (step0 + k + 1) as f64 * self.opts.dt;
            let f = diverged(&self.opts, V3::from_f64(r[i]), V3::from_f64(v[i]), i, time);
            if let StepFailure::Diverged { node, time, what } = f {
                let (cable, node) = self.layout.describe_node(node);
                return Err(Error::Diverged {
                    cable,
                    node,
                    time,
                    what: format!("{what} (GPU, {})", self.precision.name()),
                });
            }
        }
        Ok(())
    }

    /// Runs in the sea state `sea` from now on (still water when it has no
    /// components), as [`crate::cpu::CpuSolver`]'s stepper does with its kinematics
    /// cache: the same refresh times, the same interpolation, the same loads.
    pub fn set_sea(&mut self, sea: &SeaState) -> Result<(), Error> {
        self.set_seas(&SeaSet::single(sea))
    }

    /// [`GpuSolver::set_sea`] with a sea per cable (a packed model's members,
    /// `sea::set`): each block reads its cable's sea, refreshed on that sea's own
    /// schedule, as [`crate::cpu::CpuSolver::set_seas`] does.
    pub fn set_seas(&mut self, seas: &SeaSet) -> Result<(), Error> {
        self.engine.set_seas(&self.layout, &self.host, seas)
    }

    /// Reads back node positions (absolute, m) and velocities (m/s), packed order.
    pub fn state(&mut self) -> Result<NodeStates, Error> {
        self.engine.download(&self.host)
    }

    /// The state now, to go back to with [`GpuSolver::restore`] (read back from the
    /// device). With winches it also keeps the host's side of the mesh (layout, host
    /// data, winch state), since a remeshing after it replaces them.
    pub fn checkpoint(&mut self) -> Result<GpuCheckpoint, Error> {
        let (r, v) = self.engine.download(&self.host)?;
        let mesh = self.ale.as_ref().map(|ale| {
            Box::new(SavedMesh {
                layout: self.layout.clone(),
                host: self.host.clone(),
                ale: ale.clone(),
                remeshes: self.remeshes,
            })
        });
        Ok(GpuCheckpoint {
            steps: self.steps,
            node_steps: self.node_steps,
            r,
            v,
            mesh,
        })
    }

    /// Goes back to the state `cp`, taken from this solver. Where a winch cable was
    /// remeshed since, the saved layout is installed again (as a remeshing installs
    /// its new one); an error there is the device's, when rebuilding the buffers.
    pub fn restore(&mut self, cp: &GpuCheckpoint) -> Result<(), Error> {
        if let Some(m) = &cp.mesh {
            if m.remeshes != self.remeshes {
                self.engine.install(&m.layout, &m.host, &cp.r, &cp.v)?;
                self.layout.clone_from(&m.layout);
                self.host = m.host.clone();
            }
            self.ale = Some(m.ale.clone());
            self.remeshes = m.remeshes;
        }
        self.steps = cp.steps;
        self.node_steps = cp.node_steps;
        self.t = self.steps as f64 * self.opts.dt;
        self.engine.upload(&self.host, &cp.r, &cp.v);
        // The cache holds values for times ahead of the state now: it starts afresh
        // (so a replay agrees with the first pass within the cache's tolerance).
        self.engine.restart_waves();
        Ok(())
    }

    /// Replaces node positions and velocities (packed order). The waves' cache starts
    /// afresh (it holds values along the nodes' old paths): the next step or
    /// evaluation evaluates the sum at the state set.
    pub fn set_state(&mut self, r: &[[f64; 3]], v: &[[f64; 3]]) {
        assert_eq!(r.len(), self.layout.n_nodes());
        assert_eq!(v.len(), self.layout.n_nodes());
        self.engine.upload(&self.host, r, v);
        self.engine.restart_waves();
    }

    /// Loads, accelerations and reactions at the current state, evaluated on the GPU
    /// (an `element_forces` and a `node_evaluate` dispatch) and read back. A winch
    /// cable's variable element is evaluated at the current time. In waves, with the
    /// kinematics the next step starts from: the cache interpolated at the current
    /// time, refreshed first (a `wave_refresh` dispatch) where that step would refresh
    /// it, as on the CPU path ([`crate::cpu::CpuSolver::evaluate`]).
    pub fn evaluate(&mut self) -> Result<Evaluation, Error> {
        self.engine.evaluate(&self.layout, &self.host, self.steps)
    }
}

/// A GPU run's state at one step ([`GpuSolver::checkpoint`]).
pub struct GpuCheckpoint {
    /// Steps taken.
    pub steps: u64,
    node_steps: u64,
    r: Vec<[f64; 3]>,
    v: Vec<[f64; 3]>,
    /// With winches: the mesh then.
    mesh: Option<Box<SavedMesh>>,
}

/// The host's side of a winch run's mesh at a checkpoint.
struct SavedMesh {
    layout: Layout,
    host: Host,
    ale: Box<AleState>,
    /// [`GpuSolver::remeshes`] then: the device holds another layout where it differs.
    remeshes: u64,
}

/// What the GPU path cannot do with these winches, or `None`: two winch cables that
/// share a node (a node of both variable elements after remeshing would need two
/// mass-flow forces; the CPU path runs them).
pub fn unsupported_winches(def: &ModelDef, winches: &[Winch]) -> Option<String> {
    let mut owner: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    for w in winches {
        let c = def.cables.get(w.cable)?;
        for &n in &c.nodes {
            if let Some(&o) = owner.get(&n) {
                if o != w.cable {
                    return Some(format!(
                        "winch cables '{}' and '{}' sharing a node (ALE-GLMF on the GPU)",
                        def.cables[o].name, c.name
                    ));
                }
            }
            owner.insert(n, w.cable);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::{fused_segments, SeaSchedules, STEPS_PER_SUBMISSION};
    use crate::sea::irregular::{discretise, Discretisation};
    use crate::sea::spectrum::{dnv_peak_factor, Spectrum};
    use crate::sea::{SeaSet, SeaState};

    /// A packed study's seas on the common refresh grid (`sea::schedule`): the three
    /// sea states of `examples/study_design_check.toml` (refreshes every 16, 24 and 32
    /// steps of 1/150 s at the mean level), ten seeds each. Submission by submission as
    /// `write_waves` forms them, the fused dispatch is cut only at the refresh steps
    /// of the shortest interval's family and of the threes' (the union of every 16th
    /// and every 24th step: one in twelve), not at most steps as when each sea kept
    /// its own unrounded interval.
    #[test]
    fn packed_seas_on_the_grid_cut_the_fused_dispatch_rarely() {
        let dt = 1.0 / 150.0;
        let mut seas = Vec::new();
        for (hs, tp, gamma) in [
            (4.0, 9.0, dnv_peak_factor(4.0, 9.0)),
            (9.0, 13.0, 2.5),
            (13.0, 15.5, 3.3),
        ] {
            for seed in 0..10 {
                let d = Discretisation {
                    components: 200,
                    direction: 0.0,
                    spreading: None,
                    seed,
                    stream: 0,
                };
                seas.push(SeaState {
                    components: discretise(&Spectrum::Jonswap { hs, tp, gamma }, &d, 320.0, 9.81),
                    ..SeaState::still(320.0)
                });
            }
        }
        let set = SeaSet {
            cable_sea: (0..seas.len() as u32).collect(),
            seas,
            reach: Vec::new(),
        };
        let mut steps: Vec<u64> = (0..set.seas.len()).map(|q| set.plan(q, dt).steps).collect();
        steps.sort();
        steps.dedup();
        assert_eq!(steps, vec![16, 24, 32]);
        let mut w = SeaSchedules::new(&set, dt);
        let (n, per) = (48 * 512u64, STEPS_PER_SUBMISSION as u64);
        let (mut segments, mut refreshes) = (0usize, 0u64);
        for step0 in (0..n).step_by(per as usize) {
            let refresh: Vec<bool> = (0..per)
                .map(|k| {
                    let t = (step0 + k) as f64 * dt;
                    w.seas
                        .iter_mut()
                        .flatten()
                        .fold(false, |any, s| s.step::<f64>(t, 0.0).refresh != 0 || any)
                })
                .collect();
            for (k, &r) in refresh.iter().enumerate() {
                let i = step0 + k as u64;
                let want = i == 0 || (i > 1 && ((i - 1) % 16 == 0 || (i - 1) % 24 == 0));
                assert_eq!(r, want, "step {i}");
            }
            refreshes += refresh.iter().filter(|&&r| r).count() as u64;
            segments += fused_segments(&refresh, 512).len();
        }
        // One in twelve steps refreshes (16 and 24 meet every 48), and a segment
        // starts at each of them or at a submission's first step.
        let m = n - 2;
        assert_eq!(refreshes, 1 + m / 16 + m / 24 - m / 48);
        assert!(segments as u64 <= refreshes + n / per, "{segments}");
        assert!(segments as u64 >= refreshes, "{segments}");
    }

    #[test]
    fn fused_segments_cut_at_refresh_steps_and_at_the_longest() {
        assert_eq!(fused_segments(&[false; 5], 512), vec![(0, 5)]);
        let r = [true, false, false, true, false, true];
        assert_eq!(fused_segments(&r, 512), vec![(0, 3), (3, 5), (5, 6)]);
        assert_eq!(fused_segments(&[false, true], 512), vec![(0, 1), (1, 2)]);
        assert_eq!(fused_segments(&[false; 5], 2), vec![(0, 2), (2, 4), (4, 5)]);
        assert_eq!(fused_segments(&r, 2), vec![(0, 2), (2, 3), (3, 5), (5, 6)]);
    }
}
