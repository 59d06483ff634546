// Shared structs, bindings and force functions of every cablesim compute stage.
//
// `gpu::shaders` prepends a header that defines the scalar type `R` (`f32` or
// `f64`: one source for both precisions) and the constants `PIO2_HI`, `PIO2_LO`
// (pi/2 split into two `R` values), then appends `step.wgsl` (one element and one
// node of a step, from the functions here), `waves.wgsl` and one stage file.
//
// Structs use scalar members only (plus `vec4<R>` in all-vector structs), never
// `vec3`: keep them in step with `src/gpu/layout.rs` (tests/gpu/layout.rs compares
// sizes and offsets through naga).
//
// Node positions are relative to their block's origin and stored as an unevaluated
// sum `r_hi + r_lo` (see `add_compensated`): in f32 an absolute coordinate near 100 m
// resolves only ~8e-6 m, which is a strain error of ~1e-6 on a 5 m element.

const NO_CONSTRAINT: u32 = 0xffffffffu;
// ElemParams.winch and NodeParams.winch of everything that is not a variable element
// of a winch cable (or one of its two nodes).
const NO_WINCH: u32 = 0xffffffffu;
// No bending hinge on this side of an element (its hinge row: see ElemParams).
const NO_HINGE: u32 = 0xffffffffu;
// No knot: a node of no screen-model net, or a knot's missing grid neighbour.
const NO_KNOT: u32 = 0xffffffffu;
const ROUTE_FIXED: u32 = 0u;
const ROUTE_LINE: u32 = 1u;
const ROUTE_CIRCLE: u32 = 2u;
const ROUTE_TABLE: u32 = 3u;
const ROUTE_BODY: u32 = 4u;
const FAIL_SPEED: u32 = 1u;
const FAIL_DISTANCE: u32 = 2u;
// Status.failed of a blow-up found by the fused kernel (see Status).
const FUSED_FAILED: u32 = 0x80000000u;

// Run constants. Rust: gpu::layout::{f32,f64}::Params.
struct Params {
    n_nodes: u32,
    n_elems: u32,
    n_routes: u32,
    // 1 when there is a seabed plane.
    seabed: u32,
    // Steps of this advance call before the current submission.
    step_base: u32,
    // Winch cables: rows of `payout` per step.
    n_winch: u32,
    // Steps of the current submission.
    n_steps: u32,
    // Bodies: rows of `body_rows` per step.
    n_bodies: u32,
    // Free and pinned bodies, and where their records start in `body_rows` (values of
    // R; shared/free_body.wgsl).
    n_free: u32,
    free_at: u32,
    // Line failures, and where their records start in `body_rows`.
    n_fail: u32,
    fail_at: u32,
    // 1 while the element pass runs for an evaluation: the elements' internal states
    // (viscoelastic lines) are not advanced then.
    evaluate: u32,
    pad_eval: u32,
    dt: R,
    alpha: R,
    beta: R,
    max_speed: R,
    max_distance: R,
    seabed_k: R,
    seabed_c: R,
    seabed_mu: R,
    seabed_v_eps: R,
    // The axial friction coefficient (seabed_mu is the transverse one; equal: isotropic).
    seabed_mu_axial: R,
    // 1.0, read at run time: keeps the compiler from folding compensated sums.
    one: R,
    // Gravity, m/s^2 (the dry weight of what is above the water surface).
    gravity: R,
    // Water density, kg/m^3 (free bodies' buoyancy and drag).
    water_density: R,
}

// The step within the current submission (a dynamic-offset uniform). Rust: StepInfo.
// `end`: the fused kernel steps `k .. end` (the host writes it at each dispatch's
// first step; the two-pass stages read `k` only).
struct StepInfo {
    k: u32,
    end: u32,
    pad1: u32,
    pad2: u32,
}

// Folded line constants (physics::Coefs). Rust: LineParams.
struct LineParams {
    ea: R,
    ea_c: R,
    drag_n: R,
    drag_t: R,
    froude_krylov: R,
    froude_krylov_t: R,
    mass: R,
    added_mass: R,
    added_mass_t: R,
    wet_weight_z: R,
    compression: R,
    // 1 + the index in current_ranges of the line's strain-tension curve (its rows in
    // current_pts: z the strain, ux the tension), 0 without one (physics::axial).
    table: R,
    // Viscoelastic lines (physics::visco; ea is the static stiffness): the dynamic
    // stiffness and its slope against the mean tension, the static branch's and the
    // dynamic spring's damping (ba_s = 0: not a viscoelastic line).
    ea_d: R,
    ea_d_slope: R,
    ba_s: R,
    ba_d: R,
}

// One element; its unstretched length is the compensated pair l0 + l0_lo (l0_lo is
// zero in f64). The variable element of a winch cable has winch = 2 x its winch
// index (+ 1 when the winch node is b) and takes its l0 from `payout`; every other
// element has NO_WINCH. Rust: ElemParams.
//
// A run with bending stiffness (BENDING in the header) has a second row per element,
// its *hinge row*, at elems[params.n_elems + e] (gpu::engine::install hinge_rows;
// shared/step.wgsl element_shear): `a` the far node of the element before it, whose
// hinge is at its node a (NO_HINGE: none; its own node a at a clamped end), `b` the
// far node of the element after it (hinge at its node b; its own node b at a clamped
// end), `line` and `current` the row of current_pts that holds the held direction
// of a clamped end a or b (in ux, uy, uz; NO_HINGE where that side is no clamp),
// `l0` and `l0_lo` the stiffness EI / lbar of the hinge at node a and at node b.
struct ElemParams {
    a: u32,
    b: u32,
    line: u32,
    current: u32,
    block: u32,
    winch: u32,
    l0: R,
    l0_lo: R,
    // The line's diameter, m (wetted_fraction).
    diameter: R,
}

// One node; its incidence entries are inc[inc_start..inc_end]. `winch` is the winch
// index of the two nodes of a variable element (m and w), else NO_WINCH.
// Rust: NodeParams.
struct NodeParams {
    inc_start: u32,
    inc_end: u32,
    constraint: u32,
    block: u32,
    current: u32,
    winch: u32,
    // A knot of a screen-model net: the first of its 8 grid neighbours' nodes in
    // `inc` (after the incidence entries; NO_KNOT where the grid ends), else NO_KNOT;
    // and the first of its net's 2 rows in `current_pts` (screen_coefs_at).
    screen: u32,
    screen_net: u32,
    point_mass: R,
    point_weight_z: R,
    point_drag: R,
    tributary: R,
    // What a point mass loses out of the water: its added mass Ca rho V (kg), the
    // mass of water it displaces rho V (kg), and how: the radius of the sphere of its
    // volume (m, point_wetted_fraction).
    point_added: R,
    point_displaced: R,
    point_radius: R,
}

// The variable element of one winch cable at one step (ALE-GLMF, crate::ale),
// evaluated on the host from the payout schedule exactly as the CPU path does:
// l0 + l0_lo = l0_base + (dL(t) - dL_base), the payout rate and acceleration, and
// the change (l0 - l0_base) / 2 of the tributary lengths of its two nodes. Row
// `step.k * params.n_winch + winch` of `payout`. Rust: Payout.
struct Payout {
    l0: R,
    l0_lo: R,
    rate: R,
    accel: R,
    trib: R,
}

// A route rebased to the start of the submission and to the block origin:
// fixed: r = p; line: r = p + vel tau; circle/screw: r = p + e1 (cos(th) - c0)
// + e2 (sin(th) - s0) + vel tau with th = th0 + w tau, c0 = cos(th0), s0 = sin(th0)
// (e1, e2 scaled by the radius; `p` is the point on the circle at the rebase time,
// so only the displacement since then rounds in the shader). `p` is a
// compensated pair (p_hi + p_lo). table: samples route_samples[table_start ..
// table_start + table_len] interpolated at t = (t0_hi + t0_lo) + tau, the search
// starting at sample `cursor` (the number of samples at or before t0). body: a point
// fixed on body `body` (see body_point): `p` is the point at the rebase time, e1 =
// R(t0) at and e2 = at (its body coordinates). Rust: RouteParams.
struct RouteParams {
    p_hi_x: R,
    p_hi_y: R,
    p_hi_z: R,
    p_lo_x: R,
    p_lo_y: R,
    p_lo_z: R,
    vel_x: R,
    vel_y: R,
    vel_z: R,
    e1_x: R,
    e1_y: R,
    e1_z: R,
    e2_x: R,
    e2_y: R,
    e2_z: R,
    w: R,
    c0: R,
    s0: R,
    // Table: the rebase time, a compensated pair (absolute, s).
    t0_hi: R,
    t0_lo: R,
    kind: u32,
    node: u32,
    table_start: u32,
    table_len: u32,
    cursor: u32,
    body: u32,
}

// One body at step k of the submission, relative to its state at the rebase time t0
// (the host forms the differences in f64, so they are small and keep their precision):
// reference point displacement X(t) - X(t0), rotation change R(t) - R(t0) (rows),
// reference point velocity and acceleration, angular velocity and acceleration (global
// axes). Row `k * params.n_bodies + body` of `body_rows`. Rust: BodyRow.
struct BodyRow {
    dx: R,
    dy: R,
    dz: R,
    dr00: R,
    dr01: R,
    dr02: R,
    dr10: R,
    dr11: R,
    dr12: R,
    dr20: R,
    dr21: R,
    dr22: R,
    vx: R,
    vy: R,
    vz: R,
    ax: R,
    ay: R,
    az: R,
    wx: R,
    wy: R,
    wz: R,
    alx: R,
    aly: R,
    alz: R,
}

// One sample of a table route: time (absolute, s) and position (relative to the
// block origin, m), both as compensated pairs. Rust: RouteSample.
struct RouteSample {
    t_hi: R,
    t_lo: R,
    x_hi: R,
    y_hi: R,
    z_hi: R,
    x_lo: R,
    y_lo: R,
    z_lo: R,
}

// A block's origin (absolute, m), its seabed height relative to the origin, and its
// node and element ranges (what a workgroup of the fused kernel steps).
// Rust: BlockParams.
struct BlockParams {
    ox: R,
    oy: R,
    oz: R,
    zb: R,
    node_start: u32,
    node_end: u32,
    elem_start: u32,
    elem_end: u32,
    // The block's first WaveStep row (its sea's rows, shared/waves.wgsl).
    wave_rows: u32,
    pad: u32,
}

// One row of a current profile. Rust: CurrentPoint.
struct CurrentPoint {
    z: R,
    ux: R,
    uy: R,
    uz: R,
}

// The rows of one current profile. Rust: CurrentRange.
struct CurrentRange {
    start: u32,
    len: u32,
}

// Node state: position r_hi + r_lo (relative to the block origin) and velocity.
// Rust: NodeState.
struct NodeState {
    r_hi: vec4<R>,
    r_lo: vec4<R>,
    v: vec4<R>,
}

// What an element gives its nodes (physics::ElementLoads). Rust: ElemLoads.
struct ElemLoads {
    tx: R,
    ty: R,
    tz: R,
    tension: R,
    fx: R,
    fy: R,
    fz: R,
    half_mass: R,
    half_added: R,
    // The element's internal state (a viscoelastic line's static-branch strain): the
    // element pass reads it and writes it advanced by the step (not while evaluating).
    visco: R,
}

// Per node, written by the evaluate pass: total force and acceleration. While
// stepping, `force` of the two nodes of a variable element carries the mass-flow
// force of Eq. 39, written by the element pass and read by the node pass (the node
// pass cannot compute it: it would read the other node's state while that node's
// invocation overwrites it). Rust: NodeOut.
struct NodeOut {
    force: vec4<R>,
    acc: vec4<R>,
}

// First blow-up of an advance call. Rust: Status. The two-pass path sets `failed`
// to 1 and `step` to step_base + k of the failing step. The fused kernel sets
// `failed` to the largest `FUSED_FAILED | (0x7fff - k) << 16 | (0xffff - block)`
// (the earliest step of the submission, then the lowest block) and `step` to the
// submission's step_base; the host finds the node in the block.
struct Status {
    failed: atomic<u32>,
    step: atomic<u32>,
    node: u32,
    what: u32,
    // Waves: how many times a node was found more than the band margin above its
    // band's top in this advance call, and 0xffffffff less the earliest such step
    // (shared/waves.wgsl: wave_beyond_margin).
    beyond: atomic<u32>,
    beyond_step: atomic<u32>,
    // Waves: the entries on the refresh's work list (shared/waves.wgsl:
    // wave_due_push), 0 between refreshes.
    refresh_due: atomic<u32>,
}

@group(0) @binding(0) var<storage, read> params: Params;
@group(0) @binding(1) var<uniform> step: StepInfo;
@group(0) @binding(2) var<storage, read> lines: array<LineParams>;
@group(0) @binding(3) var<storage, read> elems: array<ElemParams>;
@group(0) @binding(4) var<storage, read> nodes: array<NodeParams>;
@group(0) @binding(5) var<storage, read> inc: array<u32>;
@group(0) @binding(6) var<storage, read> routes: array<RouteParams>;
@group(0) @binding(7) var<storage, read> blocks: array<BlockParams>;
@group(0) @binding(8) var<storage, read> current_pts: array<CurrentPoint>;
@group(0) @binding(9) var<storage, read> current_ranges: array<CurrentRange>;
@group(0) @binding(10) var<storage, read_write> state: array<NodeState>;
@group(0) @binding(11) var<storage, read_write> elem_loads: array<ElemLoads>;
@group(0) @binding(12) var<storage, read_write> node_out: array<NodeOut>;
@group(0) @binding(13) var<storage, read_write> reactions: array<vec4<R>>;
@group(0) @binding(14) var<storage, read_write> status: Status;
@group(0) @binding(15) var<storage, read> route_samples: array<RouteSample>;
@group(0) @binding(16) var<storage, read> payout: array<Payout>;
// The prescribed bodies' rows per step (BodyRow after BodyRow: body_row_at), then
// the free bodies' and line failures' records (shared/free_body.wgsl), as values.
@group(0) @binding(18) var<storage, read_write> body_rows: array<R>;

// ---- Small math ----

// Symmetric 3x3 matrix (math::Sym3).
struct Sym3 {
    xx: R,
    yy: R,
    zz: R,
    xy: R,
    xz: R,
    yz: R,
}

fn sym3_scalar(s: R) -> Sym3 {
    return Sym3(s, s, s, R(0.0), R(0.0), R(0.0));
}

// m + s I + a (I - t t^T): a lumped element's half mass along its tangent and what its
// normal plane has more (physics::ElementLoads).
fn sym3_add_element(m: Sym3, s: R, a: R, t: vec3<R>) -> Sym3 {
    var o = m;
    o.xx += s;
    o.yy += s;
    o.zz += s;
    o.xx += a - a * t.x * t.x;
    o.yy += a - a * t.y * t.y;
    o.zz += a - a * t.z * t.z;
    o.xy -= a * t.x * t.y;
    o.xz -= a * t.x * t.z;
    o.yz -= a * t.y * t.z;
    return o;
}

fn sym3_mul(m: Sym3, v: vec3<R>) -> vec3<R> {
    return vec3<R>(
        m.xx * v.x + m.xy * v.y + m.xz * v.z,
        m.xy * v.x + m.yy * v.y + m.yz * v.z,
        m.xz * v.x + m.yz * v.y + m.zz * v.z,
    );
}

// Solves m x = b by the adjugate (math::Sym3::solve).
fn sym3_solve(m: Sym3, b: vec3<R>) -> vec3<R> {
    let c_xx = m.yy * m.zz - m.yz * m.yz;
    let c_xy = m.xz * m.yz - m.xy * m.zz;
    let c_xz = m.xy * m.yz - m.xz * m.yy;
    let c_yy = m.xx * m.zz - m.xz * m.xz;
    let c_yz = m.xy * m.xz - m.xx * m.yz;
    let c_zz = m.xx * m.yy - m.xy * m.xy;
    let det = m.xx * c_xx + m.xy * c_xy + m.xz * c_xz;
    let inv = R(1.0) / det;
    return vec3<R>(
        (c_xx * b.x + c_xy * b.y + c_xz * b.z) * inv,
        (c_xy * b.x + c_yy * b.y + c_yz * b.z) * inv,
        (c_xz * b.x + c_yz * b.y + c_zz * b.z) * inv,
    );
}

fn norm3(v: vec3<R>) -> R {
    return sqrt(dot(v, v));
}

// (sin x, cos x) for |x| up to a few turns, in either precision: WGSL's sin and cos
// are not defined for f64 (GLSL.std.450 has no double trigonometry). Reduction by
// pi/2 (split in two parts), then the Taylor series to x^15 / x^16 on
// |y| <= pi/4, whose truncation error (below 5e-17) is under an f64 ulp.
fn sin_cos(x: R) -> vec2<R> {
    let q = floor(x / (PIO2_HI + PIO2_LO) + R(0.5));
    let y = (x - q * PIO2_HI) - q * PIO2_LO;
    let y2 = y * y;
    let s = y * (R(1.0) + y2 * (R(-1.0 / 6.0) + y2 * (R(1.0 / 120.0) + y2 * (R(-1.0 / 5040.0)
        + y2 * (R(1.0 / 362880.0) + y2 * (R(-1.0 / 39916800.0) + y2 * (R(1.0 / 6227020800.0)
        + y2 * R(-1.0 / 1307674368000.0))))))));
    let c = R(1.0) + y2 * (R(-0.5) + y2 * (R(1.0 / 24.0) + y2 * (R(-1.0 / 720.0)
        + y2 * (R(1.0 / 40320.0) + y2 * (R(-1.0 / 3628800.0) + y2 * (R(1.0 / 479001600.0)
        + y2 * (R(-1.0 / 87178291200.0) + y2 * R(1.0 / 20922789888000.0))))))));
    let quadrant = ((i32(q) % 4) + 4) % 4;
    switch quadrant {
        case 0: { return vec2<R>(s, c); }
        case 1: { return vec2<R>(c, -s); }
        case 2: { return vec2<R>(-s, -c); }
        default: { return vec2<R>(-c, s); }
    }
}

// `x`, opaque to the compiler: a select on a run-time condition (`params.one` is 1.0),
// so that a product passed through it is rounded to `R` and used as such, not
// contracted into an fma with the addition that consumes it (Mesa's NIR fuses
// multiply-adds and reassociates multiplications by `params.one`, so `(a * b) * one`
// is not enough; a select it leaves alone).
fn opaque(x: R) -> R {
    return select(R(0.0), x, params.one > R(0.5));
}

fn opaque3(x: vec3<R>) -> vec3<R> {
    return select(vec3<R>(R(0.0)), x, params.one > R(0.5));
}

// Adds `d` to the compensated value `hi + lo` (Knuth's two-sum, then a renormalising
// fast two-sum), returning the new (hi, lo). `params.one` is 1.0 at run time; the
// multiplications keep compilers from rewriting `(hi + d) - hi` as `d` (NIR applies
// such inexact algebra unless it cannot see through the operands). Pass a product
// `d` through `opaque3` first.
fn add_compensated(hi: vec3<R>, lo: vec3<R>, d: vec3<R>) -> array<vec3<R>, 2> {
    let s = (hi + d) * params.one;
    let bb = s - hi;
    let err = (hi - (s - bb)) + (d - bb);
    let l = lo + err;
    let h = (s + l) * params.one;
    return array<vec3<R>, 2>(h, l - (h - s));
}

// (s, e) with s + e = a + b exactly (Knuth's two-sum; `params.one` as above).
fn two_sum(a: R, b: R) -> vec2<R> {
    let s = (a + b) * params.one;
    let bb = (s - a) * params.one;
    return vec2<R>(s, (a - (s - bb)) + (b - bb));
}

// (p, e) with p + e = a * a exactly: Veltkamp's split into halves whose products are
// exact (`SPLITTER` = 2^12 + 1 in f32, 2^27 + 1 in f64), then Dekker's product. No
// fma needed, and contracting the error term into fmas leaves it exact. The product
// `p` goes through `opaque` so that it cannot be contracted into the addition that
// consumes it (an fma there adds the exact square, not `p`, and the two-sums
// downstream miss the difference: lavapipe does this).
fn two_square(a: R) -> vec2<R> {
    let c = (SPLITTER * a) * params.one;
    let hi = c - (c - a) * params.one;
    let lo = a - hi;
    let p = opaque(a * a);
    return vec2<R>(p, ((hi * hi - p) + R(2.0) * hi * lo) + lo * lo);
}

// The stretch `|d| - l0` of an element whose node-a-to-b vector is the compensated
// `d_hi + d_lo` and whose unstretched length is `l0_hi + l0_lo`, accurate relative to
// the stretch itself: `(|d|^2 - l0^2) / (|d| + l0)` with the numerator summed from
// exact squares by two-sums, so the cancellation of `|d|^2` against `l0^2` loses
// nothing. Plain `|d| - l0` in f32 knows the stretch only to `2^-24 l0`, a tension
// only to `EA 2^-24`: 4 N on a steel wire, 50 N on a chain, and that noise, fed back
// every step, rings the axial modes to tenths of a percent of the tension.
fn element_stretch(d_hi: vec3<R>, d_lo: vec3<R>, l0_hi: R, l0_lo: R) -> R {
    let x = two_square(d_hi.x);
    let y = two_square(d_hi.y);
    let z = two_square(d_hi.z);
    let l0sq = two_square(l0_hi);
    let s1 = two_sum(x.x, y.x);
    let s2 = two_sum(s1.x, z.x);
    let s3 = two_sum(s2.x, -l0sq.x);
    let small = (s1.y + s2.y) + (x.y + y.y + z.y - l0sq.y)
        + R(2.0) * (dot(d_hi, d_lo) - l0_hi * l0_lo);
    let num = s3.x + (s3.y + small);
    return num / (norm3(d_hi + d_lo) + (l0_hi + l0_lo));
}

// ---- Environment ----

// Current of profile `ci` at absolute height `z` (model::Current::at).
fn current_at(ci: u32, z: R) -> vec3<R> {
    let rg = current_ranges[ci];
    if rg.len == 0u {
        return vec3<R>(R(0.0), R(0.0), R(0.0));
    }
    let first = current_pts[rg.start];
    if rg.len == 1u || z <= first.z {
        return vec3<R>(first.ux, first.uy, first.uz);
    }
    let last = current_pts[rg.start + rg.len - 1u];
    if z >= last.z {
        return vec3<R>(last.ux, last.uy, last.uz);
    }
    var i = 1u;
    while current_pts[rg.start + i].z < z {
        i += 1u;
    }
    let p0 = current_pts[rg.start + i - 1u];
    let p1 = current_pts[rg.start + i];
    let s = (z - p0.z) / (p1.z - p0.z);
    return vec3<R>(p0.ux + s * (p1.ux - p0.ux), p0.uy + s * (p1.uy - p0.uy), p0.uz + s * (p1.uz - p0.uz));
}

// ---- Physics (twins of src/physics) ----

// Tension of a tabulated strain-tension curve at strain `eps` (physics::tabulated_tension):
// the rows `rg` of current_pts, z the strain and ux the tension; zero at and below zero
// strain, linear from (0, 0) to the first row and between rows, the last segment's
// slope past the last row.
fn tabulated_tension(rg: CurrentRange, eps: R) -> R {
    if !(eps > R(0.0)) {
        return R(0.0);
    }
    let first = current_pts[rg.start];
    var x0 = R(0.0);
    var y0 = R(0.0);
    var x1 = first.z;
    var y1 = first.ux;
    if eps > first.z {
        var i = 1u;
        while i + 1u < rg.len && current_pts[rg.start + i].z < eps {
            i += 1u;
        }
        let p0 = current_pts[rg.start + i - 1u];
        let p1 = current_pts[rg.start + i];
        x0 = p0.z;
        y0 = p0.ux;
        x1 = p1.z;
        y1 = p1.ux;
    }
    return y0 + (eps - x0) * ((y1 - y0) / (x1 - x0));
}

// The dynamic stiffness of a viscoelastic line at static-branch strain `s`
// (physics::visco_dynamic_stiffness): `kd` when constant (`slope` 0) or in
// compression, else the larger root for the mean tension K1 s.
fn visco_dynamic_stiffness(ks: R, kd: R, slope: R, s: R) -> R {
    if slope == R(0.0) || s < R(0.0) {
        return kd;
    }
    let q = ks * (R(1.0) + slope * s);
    let d = kd - q;
    return R(0.5) * (kd + q + sqrt(d * d + R(4.0) * kd * ks * slope * s));
}

// The axial force and the state's rate (x, y) of a viscoelastic element at strain
// `eps`, strain rate `epsdot` and state `s` (physics::visco_tension): the static
// branch K1 with c1 in series with the dynamic spring K2 with c2.
fn visco_tension(ks: R, kd: R, slope: R, c1: R, c2: R, eps: R, epsdot: R, s: R) -> vec2<R> {
    let k2 = visco_dynamic_stiffness(ks, kd, slope, s);
    let k1 = k2 * ks / (k2 - ks);
    let rate = (k2 * eps - (k1 + k2) * s + c2 * epsdot) / (c1 + c2);
    var elastic = R(0.0);
    if eps > R(0.0) {
        elastic = k1 * s;
    }
    return vec2<R>(elastic + c1 * rate, rate);
}

// Fraction of a straight element of diameter `d` under water from the submergences
// (surface elevation minus height, m) of its two nodes (physics::wetted_fraction):
// the section's share `clamp(1 + s / d, 0, 1)` averaged along the element.
fn wetted_fraction(sa: R, sb: R, d: R) -> R {
    if sa >= R(0.0) && sb >= R(0.0) {
        return R(1.0);
    }
    if sa <= -d && sb <= -d {
        return R(0.0);
    }
    if d <= R(0.0) {
        return (max(sa, R(0.0)) + max(sb, R(0.0))) / (abs(sa) + abs(sb));
    }
    let ua = R(1.0) + sa / d;
    let ub = R(1.0) + sb / d;
    let lo = min(ua, ub);
    let hi = max(ua, ub);
    if hi <= lo {
        return clamp(lo, R(0.0), R(1.0));
    }
    let a = max(lo, R(0.0));
    let b = min(hi, R(1.0));
    let w0 = max(b - a, R(0.0));
    let w1 = max(hi - max(lo, R(1.0)), R(0.0));
    return (w0 * (R(0.5) * (a + b)) + w1) / (hi - lo);
}

// Fraction of a point mass's volume under water, the point taken as a sphere of
// radius `radius` whose centre is submerged by `s` (physics::point_wetted_fraction).
fn point_wetted_fraction(s: R, radius: R) -> R {
    if radius <= R(0.0) {
        return select(R(0.0), R(1.0), s >= R(0.0));
    }
    let x = clamp((s + radius) / (radius + radius), R(0.0), R(1.0));
    return x * x * (R(3.0) - x - x);
}

// What an element contributes to its two nodes (physics::ElementLoads).
struct Element {
    t: vec3<R>,
    tension: R,
    f_half: vec3<R>,
    half_mass: R,
    half_added: R,
}

// Axial force from the stretch `l - l0` and the stretch rate (physics::axial_force).
fn axial_force(c: LineParams, stretch: R, l0: R, t: vec3<R>, dv: vec3<R>) -> R {
    let eps = stretch / l0;
    let epsdot = dot(t, dv) / l0;
    let k = select(c.compression, R(1.0), eps > R(0.0));
    return c.ea * eps * k + c.ea_c * epsdot;
}

// The GLMF loads of an element with node-a-to-b vector `d` and stretch `|d| - l0`,
// wholly under water (physics::glmf_element).
fn glmf_element(c: LineParams, d: vec3<R>, stretch: R, va: vec3<R>, vb: vec3<R>, l0: R, u: vec3<R>, aw: vec3<R>) -> Element {
    return glmf_element_wet(c, d, stretch, va, vb, l0, u, aw, R(1.0), R(0.0));
}

// The water-acceleration load on `vol_l0` metres of unstretched line with tangent `t`
// in water accelerating at `aw` (physics::froude_krylov): `(1 + Cm) rho A P aw` across
// and `(1 + Cat) rho A (t . aw) t` along the line, per metre.
fn froude_krylov(c: LineParams, t: vec3<R>, aw: vec3<R>, vol_l0: R) -> vec3<R> {
    let at = dot(t, aw);
    let awn = aw - t * at;
    return awn * (c.froude_krylov * vol_l0) + t * (c.froude_krylov_t * vol_l0 * at);
}

// The GLMF loads of an element of which the fraction `wet` is under water, in gravity
// `g` (physics::glmf_element_wet): tension with slack and damping; normal and
// tangential drag on the relative current `u - (va + vb) / 2`, the water-acceleration
// load of `aw` (froude_krylov) and the added masses, normal and tangential, each times
// `wet`; the weight less the buoyancy of the wet share, `wet_weight_z - (1 - wet) rho
// A g` per length with `rho A g = wet_weight_z + mass g`. The mass block is
// `half_mass I + half_added (I - t t^T)`: half the mass along the tangent, and what
// the normal plane has more.
fn glmf_element_wet(c: LineParams, d: vec3<R>, stretch: R, va: vec3<R>, vb: vec3<R>, l0: R, u: vec3<R>, aw: vec3<R>, wet: R, g: R) -> Element {
    let l = norm3(d);
    let t = d / l;
    let tension = axial_force(c, stretch, l0, t, vb - va);
    let vrel = u - (va + vb) * R(0.5);
    let vt = dot(t, vrel);
    let vn = vrel - t * vt;
    let drag_n = vn * (c.drag_n * l * norm3(vn) * wet);
    let drag_t = t * (c.drag_t * l * abs(vt) * vt * wet);
    let fk = froude_krylov(c, t, aw, l0 * wet);
    let buoyancy_z = c.wet_weight_z + c.mass * g;
    let w = vec3<R>(R(0.0), R(0.0), (c.wet_weight_z - (R(1.0) - wet) * buoyancy_z) * l0);
    let total = drag_n + drag_t + fk + w;
    let half_mass = (c.mass + c.added_mass_t * wet) * l0 * R(0.5);
    let half_added = (c.added_mass - c.added_mass_t) * l0 * R(0.5) * wet;
    return Element(t, tension, total * R(0.5), half_mass, half_added);
}

// ---- Bending (physics::bending; docs/src/model/bending.md) ----

// atan(x) for 0 <= x <= 1 in either precision (WGSL has no f64 atan): above 0.66
// reduced by atan(x) = pi/4 + atan((x - 1) / (x + 1)), then Cephes' rational
// approximation x + x^3 P(x^2) / Q(x^2) on |x| <= 0.66 (within an f64 ulp).
fn bending_atan(x0: R) -> R {
    var x = x0;
    var y = R(0.0);
    var lo = R(0.0);
    if x > R(0.66) {
        y = R(0.5) * PIO2_HI;
        lo = R(0.5) * PIO2_LO;
        x = (x - R(1.0)) / (x + R(1.0));
    }
    let z = x * x;
    let p = (((R(-8.750608600031904122785e-1) * z + R(-1.615753718733365076637e1)) * z
        + R(-7.500855792314704667340e1)) * z + R(-1.228866684490136173410e2)) * z
        + R(-6.485021904942025371773e1);
    let q = ((((z + R(2.485846490142306297962e1)) * z + R(1.650270098316988542046e2)) * z
        + R(4.328810604912902668951e2)) * z + R(4.853903996359136964868e2)) * z
        + R(1.945506571482613964425e2);
    return y + ((x * (z * p / q) + x) + lo);
}

// atan2(s, c) for s >= 0 (an angle in [0, pi]) from bending_atan.
fn bending_atan2(s: R, c: R) -> R {
    if c >= s {
        return bending_atan(s / c);
    }
    if -c >= s {
        return (R(2.0) * PIO2_HI - bending_atan(s / -c)) + R(2.0) * PIO2_LO;
    }
    let t = c / s;
    let a = select(-bending_atan(-t), bending_atan(t), t >= R(0.0));
    return (PIO2_HI - a) + PIO2_LO;
}

// The angle phi between unit tangents q1, q2 and phi / sin(phi) (1 at phi = 0, by its
// series below sin(phi) = 1e-4) (physics::bending_angle).
fn bending_angle(q1: vec3<R>, q2: vec3<R>) -> vec2<R> {
    let c = dot(q1, q2);
    let s = norm3(cross(q1, q2));
    let phi = bending_atan2(s, c);
    var g: R;
    if s < R(1e-4) {
        g = R(1.0) + phi * phi / R(6.0);
    } else {
        g = phi / s;
    }
    return vec2<R>(phi, g);
}

// The forces of a bending hinge of stiffness k = EI / lbar between the element before
// it (unit tangent q1, length l1) and the one after it (q2, l2): on the far node of
// the element before (f1, index 0) and on the far node of the element after (f2,
// index 1); the hinge's own node takes -(f1 + f2) (physics::bending_hinge).
fn bending_hinge(q1: vec3<R>, l1: R, q2: vec3<R>, l2: R, k: R) -> array<vec3<R>, 2> {
    let c = dot(q1, q2);
    let g = bending_angle(q1, q2).y;
    let kg = k * g;
    let f1 = (q2 - q1 * c) * (-kg / l1);
    let f2 = (q1 - q2 * c) * (kg / l2);
    return array<vec3<R>, 2>(f1, f2);
}

// The energy k phi^2 / 2 of a hinge of stiffness k = EI / lbar (physics::bending_energy).
fn bending_energy(q1: vec3<R>, q2: vec3<R>, k: R) -> R {
    let phi = bending_angle(q1, q2).x;
    return R(0.5) * k * phi * phi;
}

// Seabed contact on a node penetrating by `pen` (seabed z minus node z, m) with
// tributary length `lt`, moving at `v` (physics::seabed_force).
fn seabed_force(pen: R, lt: R, v: vec3<R>) -> vec3<R> {
    if !(pen > R(0.0)) {
        return vec3<R>(R(0.0), R(0.0), R(0.0));
    }
    let fz = params.seabed_k * lt * pen - params.seabed_c * lt * v.z;
    var f = vec3<R>(R(0.0), R(0.0), fz);
    if params.seabed_mu > R(0.0) {
        let fnorm = params.seabed_k * lt * pen;
        let vh = vec3<R>(v.x, v.y, R(0.0));
        let speed = max(norm3(vh), params.seabed_v_eps);
        f += vh * (-params.seabed_mu * fnorm / speed);
    }
    return f;
}

// The contact's damping slopes (c_h, c_h, c_z), N s/m, on a node penetrating by `pen`
// with tributary length `lt`, moving at `v` (physics::seabed_damping): C lt normal, and
// the regularised friction's mu F_N / max(|v_h|, v_eps); zero above the seabed.
// node_advance takes them implicitly, so they do not bound the step.
fn seabed_damping(pen: R, lt: R, v: vec3<R>) -> vec3<R> {
    if !(pen > R(0.0)) {
        return vec3<R>(R(0.0), R(0.0), R(0.0));
    }
    let cz = params.seabed_c * lt;
    var ch = R(0.0);
    if params.seabed_mu > R(0.0) {
        let fnorm = params.seabed_k * lt * pen;
        let speed = max(norm3(vec3<R>(v.x, v.y, R(0.0))), params.seabed_v_eps);
        ch = params.seabed_mu * fnorm / speed;
    }
    return vec3<R>(ch, ch, cz);
}

// The seabed grid's k-th packed value ([nx, ny, x.., y.., z..], physics::seabed_height),
// four to a row of `current_pts` from the range `current_ranges[params.seabed - 2u]`
// (params.seabed: 0 no seabed, 1 the plane, 2 + i the grid in range i).
fn seabed_grid_value(k: u32) -> R {
    let p = current_pts[current_ranges[params.seabed - 2u].start + k / 4u];
    switch k % 4u {
        case 0u: { return p.z; }
        case 1u: { return p.ux; }
        case 2u: { return p.uy; }
        default: { return p.uz; }
    }
}

// One axis of the seabed grid (`n` ticks from packed value `off`): the cell, the
// fraction across it and 1 / its width, or 0 outside (physics::seabed_axis).
fn seabed_axis(off: u32, n: u32, x: R) -> vec3<R> {
    if n < 2u || x <= seabed_grid_value(off) {
        return vec3<R>(R(0.0), R(0.0), R(0.0));
    }
    if x >= seabed_grid_value(off + n - 1u) {
        return vec3<R>(R(n - 2u), R(1.0), R(0.0));
    }
    var lo = 0u;
    var hi = n - 1u;
    while hi - lo > 1u {
        let mid = (lo + hi) / 2u;
        if seabed_grid_value(off + mid) <= x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let x0 = seabed_grid_value(off + lo);
    let inv = R(1.0) / (seabed_grid_value(off + hi) - x0);
    return vec3<R>(R(lo), (x - x0) * inv, inv);
}

// The seabed grid at absolute (x, y): (z_b, dz_b/dx, dz_b/dy), bilinear, the edge values
// continued flat outside (physics::seabed_height).
fn seabed_height(x: R, y: R) -> vec3<R> {
    let nx = u32(seabed_grid_value(0u));
    let ny = u32(seabed_grid_value(1u));
    let ax = seabed_axis(2u, nx, x);
    let ay = seabed_axis(2u + nx, ny, y);
    let i = u32(ax.x);
    let j = u32(ay.x);
    let z0 = 2u + nx + ny;
    let i1 = select(i, i + 1u, nx > 1u);
    let j1 = select(j, j + 1u, ny > 1u);
    let z00 = seabed_grid_value(z0 + i * ny + j);
    let z01 = seabed_grid_value(z0 + i * ny + j1);
    let z10 = seabed_grid_value(z0 + i1 * ny + j);
    let z11 = seabed_grid_value(z0 + i1 * ny + j1);
    let fx = ax.y;
    let fy = ay.y;
    let zy0 = z00 + (z10 - z00) * fx;
    let zy1 = z01 + (z11 - z01) * fx;
    let z = zy0 + (zy1 - zy0) * fy;
    let dzdx = ((z10 - z00) * (R(1.0) - fy) + (z11 - z01) * fy) * ax.z;
    let dzdy = (zy1 - zy0) * ay.z;
    return vec3<R>(z, dzdx, dzdy);
}

// The seabed's upward unit normal where its slopes are (g.y, g.z)
// (physics::seabed_slope_normal).
fn seabed_slope_normal(g: vec3<R>) -> vec3<R> {
    let nz = R(1.0) / sqrt(R(1.0) + g.y * g.y + g.z * g.z);
    return vec3<R>(-g.y * nz, -g.z * nz, nz);
}

// Contact with the seabed grid on a node `gap` below it (z_b - z, m), tributary length
// `lt`, moving at `v`, the grid's height and slopes there `g` (seabed_height): along
// the normal n, K lt gap n_z n - C lt (v.n) n, and the regularised friction on the
// sliding velocity v - (v.n) n (physics::seabed_slope_force).
fn seabed_slope_force(gap: R, lt: R, v: vec3<R>, g: vec3<R>) -> vec3<R> {
    if !(gap > R(0.0)) {
        return vec3<R>(R(0.0), R(0.0), R(0.0));
    }
    let n = seabed_slope_normal(g);
    let fnorm = params.seabed_k * lt * gap * n.z;
    let vn = dot(v, n);
    var f = n * (fnorm - params.seabed_c * lt * vn);
    if params.seabed_mu > R(0.0) {
        let vt = v - n * vn;
        let speed = max(norm3(vt), params.seabed_v_eps);
        f += vt * (-params.seabed_mu * fnorm / speed);
    }
    return f;
}

// The damping slopes (c_n, c_t) of seabed_slope_force (physics::seabed_slope_damping):
// node_advance adds dt (c_t I + (c_n - c_t) n n^T) to the mass block.
fn seabed_slope_damping(gap: R, lt: R, v: vec3<R>, g: vec3<R>) -> vec2<R> {
    if !(gap > R(0.0)) {
        return vec2<R>(R(0.0), R(0.0));
    }
    let n = seabed_slope_normal(g);
    var ct = R(0.0);
    if params.seabed_mu > R(0.0) {
        let fnorm = params.seabed_k * lt * gap * n.z;
        let vt = v - n * dot(v, n);
        ct = params.seabed_mu * fnorm / max(norm3(vt), params.seabed_v_eps);
    }
    return vec2<R>(params.seabed_c * lt, ct);
}

// Target position (relative to the origin, as a compensated pair r_hi + r_lo),
// velocity and acceleration of a route at `tau` seconds after the rebase time.
struct RouteState {
    r_hi: vec3<R>,
    r_lo: vec3<R>,
    v: vec3<R>,
    a: vec3<R>,
}

// `t - t_j` for table sample `j` (index within the table) at `tau` after the rebase.
fn table_dt(q: RouteParams, j: u32, tau: R) -> R {
    let s = route_samples[q.table_start + j];
    return ((q.t0_hi - s.t_hi) + (q.t0_lo - s.t_lo)) + tau;
}

fn sample_hi(j: u32) -> vec3<R> {
    let s = route_samples[j];
    return vec3<R>(s.x_hi, s.y_hi, s.z_hi);
}

fn sample_lo(j: u32) -> vec3<R> {
    let s = route_samples[j];
    return vec3<R>(s.x_lo, s.y_lo, s.z_lo);
}

// A table route (model::Route::Table): linear between samples, held at the first and
// last samples outside the table's span (velocity zero there). The segment is found by
// binary search from the cursor, as `partition_point(t_j <= t)` on the CPU.
fn table_eval(q: RouteParams, tau: R) -> RouteState {
    let zero = vec3<R>(R(0.0), R(0.0), R(0.0));
    let n = q.table_len;
    let b = q.table_start;
    if n == 1u || table_dt(q, 0u, tau) <= R(0.0) {
        return RouteState(sample_hi(b), sample_lo(b), zero, zero);
    }
    if table_dt(q, n - 1u, tau) >= R(0.0) {
        return RouteState(sample_hi(b + n - 1u), sample_lo(b + n - 1u), zero, zero);
    }
    // The first sample after t lies in [lo, hi]; sample n - 1 is after t.
    var lo = clamp(q.cursor, 1u, n - 1u);
    var hi = n - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if table_dt(q, mid, tau) >= R(0.0) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    let s0 = route_samples[b + lo - 1u];
    let s1 = route_samples[b + lo];
    let h = (s1.t_hi - s0.t_hi) + (s1.t_lo - s0.t_lo);
    let u = table_dt(q, lo - 1u, tau);
    let p0_hi = vec3<R>(s0.x_hi, s0.y_hi, s0.z_hi);
    let p0_lo = vec3<R>(s0.x_lo, s0.y_lo, s0.z_lo);
    let dp = (vec3<R>(s1.x_hi, s1.y_hi, s1.z_hi) - p0_hi) + (vec3<R>(s1.x_lo, s1.y_lo, s1.z_lo) - p0_lo);
    return RouteState(p0_hi, p0_lo + dp * (u / h), dp / h, zero);
}

fn route_eval(q: RouteParams, tau: R) -> RouteState {
    if q.kind == ROUTE_TABLE {
        return table_eval(q, tau);
    }
    let p_hi = vec3<R>(q.p_hi_x, q.p_hi_y, q.p_hi_z);
    let p_lo = vec3<R>(q.p_lo_x, q.p_lo_y, q.p_lo_z);
    let vel = vec3<R>(q.vel_x, q.vel_y, q.vel_z);
    let zero = vec3<R>(R(0.0), R(0.0), R(0.0));
    if q.kind == ROUTE_FIXED {
        return RouteState(p_hi, p_lo, zero, zero);
    }
    if q.kind == ROUTE_LINE {
        return RouteState(p_hi, p_lo + vel * tau, vel, zero);
    }
    let e1 = vec3<R>(q.e1_x, q.e1_y, q.e1_z);
    let e2 = vec3<R>(q.e2_x, q.e2_y, q.e2_z);
    // Angle addition from the rebase angle: cos(th0 + phi) - c0 = c0 (cos phi - 1)
    // - s0 sin phi, with cos phi - 1 = -2 sin^2(phi / 2) (no cancellation), so the
    // displacement rounds relative to its own size, not to the radius.
    let phi = q.w * tau;
    let sc = sin_cos(phi);
    let half = sin_cos(phi * R(0.5));
    let cm1 = R(-2.0) * half.x * half.x;
    let dc = q.c0 * cm1 - q.s0 * sc.x;
    let ds = q.s0 * cm1 + q.c0 * sc.x;
    let c = q.c0 + dc;
    let s = q.s0 + ds;
    let radial = e1 * c + e2 * s;
    return RouteState(
        p_hi,
        p_lo + (e1 * dc + e2 * ds) + vel * tau,
        (e2 * c - e1 * s) * q.w + vel,
        -radial * (q.w * q.w),
    );
}

// A point fixed on a body (route kind ROUTE_BODY) from the route `q` rebased to t0 and
// the body's row `b` of this step: with q_at = R(t) at = e1 + dR at,
// r = p + dX + dR at, v = V + w x q_at, a = A + alpha x q_at + w x (w x q_at)
// (rigid-body kinematics; only the small displacement since t0 rounds in the shader).
// Rust twin: body::kinematics::attachment.
fn body_point(q: RouteParams, b: BodyRow) -> RouteState {
    let at = vec3<R>(q.e2_x, q.e2_y, q.e2_z);
    let dq = vec3<R>(
        b.dr00 * at.x + b.dr01 * at.y + b.dr02 * at.z,
        b.dr10 * at.x + b.dr11 * at.y + b.dr12 * at.z,
        b.dr20 * at.x + b.dr21 * at.y + b.dr22 * at.z,
    );
    let qa = vec3<R>(q.e1_x, q.e1_y, q.e1_z) + dq;
    let w = vec3<R>(b.wx, b.wy, b.wz);
    let al = vec3<R>(b.alx, b.aly, b.alz);
    return RouteState(
        vec3<R>(q.p_hi_x, q.p_hi_y, q.p_hi_z),
        vec3<R>(q.p_lo_x, q.p_lo_y, q.p_lo_z) + (vec3<R>(b.dx, b.dy, b.dz) + dq),
        vec3<R>(b.vx, b.vy, b.vz) + cross(w, qa),
        vec3<R>(b.ax, b.ay, b.az) + cross(al, qa) + cross(w, cross(w, qa)),
    );
}

// The target of constraint `c` at `tau` into the submission, step `k` of it (a body's
// row is per step).
fn constraint_target(c: u32, tau: R, k: u32) -> RouteState {
    let q = routes[c];
    if q.kind == ROUTE_BODY {
        return body_point(q, body_row_at((k * params.n_bodies + q.body) * 24u));
    }
    if q.kind == ROUTE_FREE {
        // A point on a free or pinned body: its row as the body stage left it.
        return body_point(q, body_row_at(params.free_at + q.body * FREE_STRIDE + FREE_ROW));
    }
    return route_eval(q, tau);
}


// ---- Screen-model net loads (Rust twins: physics::screen; docs/src/model/screen.md).

// One screen net's constants (Rust: physics::ScreenCoefs): coefficient set (0
// Aarsnes, 1 Loland, 2 Kristiansen-Faltinsen), wake rule (0 none, 1 Loland, 2 Cheng),
// solidity, the twines' Reynolds number per unit speed d_w / (nu (1 - Sn)), half the
// water density, and the vertical axis whose downstream side is in the wake
// (relative to the block origin).
struct ScreenCoefs {
    model: u32,
    wake: u32,
    sn: R,
    re_scale: R,
    half_rho: R,
    axis_x: R,
    axis_y: R,
}

// The twine's (circular cylinder's) drag coefficient at Reynolds number re: the
// degree-7 polynomial in log10(Re), re-centred at 2.5, log10(Re) held to [1, 4].
fn screen_cylinder_cd(re: R) -> R {
    let y = screen_log10(min(max(re, R(10.0)), R(1.0e4))) - R(2.5);
    var p = R(0.12479);
    p = p * y + R(-0.265115);
    p = p * y + R(-0.3477225);
    p = p * y + R(0.83019125);
    p = p * y + R(0.220573125);
    p = p * y + R(-0.4381015625);
    p = p * y + R(-0.39100046875);
    p = p * y + R(1.244830859375);
    return p;
}

// log10(x) for x in [10, 1e4] (no library logarithm in f64): x = 2^k m by five exact
// divisions by powers of two, m in (1/sqrt 2, sqrt 2], then ln m = 2 atanh(z),
// z = (m - 1) / (m + 1), by its series to z^21. No loop (a loop's iterations count
// against lavapipe's budget in the fused kernel).
fn screen_log10(x: R) -> R {
    let sqrt2 = R(1.41421356237309504880);
    var m = x;
    var k = R(0.0);
    if m > R(256.0) * sqrt2 { m = m / R(256.0); k += R(8.0); }
    if m > R(16.0) * sqrt2 { m = m / R(16.0); k += R(4.0); }
    if m > R(4.0) * sqrt2 { m = m / R(4.0); k += R(2.0); }
    if m > R(2.0) * sqrt2 { m = m / R(2.0); k += R(1.0); }
    if m > R(1.0) * sqrt2 { m = m / R(2.0); k += R(1.0); }
    let z = (m - R(1.0)) / (m + R(1.0));
    let w = z * z;
    var a = R(1.0) / R(21.0);
    a = a * w + R(1.0) / R(19.0);
    a = a * w + R(1.0) / R(17.0);
    a = a * w + R(1.0) / R(15.0);
    a = a * w + R(1.0) / R(13.0);
    a = a * w + R(1.0) / R(11.0);
    a = a * w + R(1.0) / R(9.0);
    a = a * w + R(1.0) / R(7.0);
    a = a * w + R(1.0) / R(5.0);
    a = a * w + R(1.0) / R(3.0);
    a = a * w + R(1.0);
    let ln = k * R(0.69314718055994530942) + R(2.0) * z * a;
    return ln * R(0.43429448190325182765);
}

// (C_D, g) of coefficient set `model` for solidity sn, twine Reynolds number re and
// c = cos(theta) (theta between the panel normal and the flow); C_L = g sin(2 theta).
fn screen_coefficients(model: u32, sn: R, re: R, c: R) -> vec2<R> {
    let s2 = sn * sn;
    let s3 = sn * sn * sn;
    if model == 0u {
        let cd = R(0.04) + (R(-0.04) + sn - R(1.24) * s2 + R(13.7) * s3) * c;
        let g = R(0.57) * sn - R(3.54) * s2 + R(10.1) * s3;
        return vec2<R>(cd, g);
    } else if model == 1u {
        let cd = R(0.04) + (R(-0.04) + R(0.33) * sn + R(6.54) * s2 - R(4.88) * s3) * c;
        let g = R(-0.05) * sn + R(2.3) * s2 - R(1.76) * s3;
        return vec2<R>(cd, g);
    }
    let cdc = screen_cylinder_cd(re);
    let q = R(1.0) - sn;
    let cd0 = cdc * sn * (R(2.0) - sn) / (R(2.0) * q * q);
    let cn45 = cdc * sn / (R(2.0) * q * q);
    let cl45 = R(3.14159265358979323846) * cn45 / (R(8.0) + cn45);
    let cl0 = (R(0.5) * cd0 - cl45) * R(0.70710678118654752440);
    let cd = cd0 * (R(0.9) * c + R(0.1) * (R(4.0) * c * c * c - R(3.0) * c));
    let g = cl0 * (R(1.0) + R(0.2) * (R(2.0) * c * c - R(1.0)));
    return vec2<R>(cd, g);
}

// The flow-reduction factor behind the net (0 to 1) for a panel whose normal makes
// c = cos(theta) with the flow, twine Reynolds number re.
fn screen_wake_factor(co: ScreenCoefs, re: R, c: R) -> R {
    var r = R(1.0);
    if co.wake == 1u {
        r = R(1.0) - R(0.46) * screen_coefficients(co.model, co.sn, re, R(1.0)).x;
    } else if co.wake == 2u {
        r = (c + R(0.05) - R(0.38) * co.sn) / (c + R(0.05));
    }
    return min(max(r, R(0.0)), R(1.0));
}

// The screen-model force on the panel with corners p0..p3 (in order around it),
// corner velocities v0..v3, in water moving at u at its centre: drag along the
// relative flow, lift across it towards the side the panel faces, the flow slowed
// by the wake factor where the panel is downstream of the axis.
fn screen_panel_force(co: ScreenCoefs, p0: vec3<R>, p1: vec3<R>, p2: vec3<R>, p3: vec3<R>,
        v0: vec3<R>, v1: vec3<R>, v2: vec3<R>, v3: vec3<R>, u: vec3<R>) -> vec3<R> {
    let zero = vec3<R>(R(0.0), R(0.0), R(0.0));
    let vbar = (v0 + v1 + v2 + v3) * R(0.25);
    let nv = cross(p2 - p0, p3 - p1) * R(0.5);
    let area = norm3(nv);
    if area <= R(0.0) {
        return zero;
    }
    let n = nv * (R(1.0) / area);
    var w = u;
    if co.wake != 0u {
        let cx = (p0.x + p1.x + p2.x + p3.x) * R(0.25);
        let cy = (p0.y + p1.y + p2.y + p3.y) * R(0.25);
        if (cx - co.axis_x) * u.x + (cy - co.axis_y) * u.y > R(0.0) {
            let u0 = u - vbar;
            let s0 = norm3(u0);
            if s0 > R(0.0) {
                let c0 = min(abs(dot(n, u0)) / s0, R(1.0));
                w = u * screen_wake_factor(co, co.re_scale * s0, c0);
            }
        }
    }
    let ur = w - vbar;
    let s = norm3(ur);
    if s <= R(0.0) {
        return zero;
    }
    let nu = dot(n, ur);
    let c = min(abs(nu) / s, R(1.0));
    let nd = select(n, -n, nu < R(0.0));
    let k = screen_coefficients(co.model, co.sn, co.re_scale * s, c);
    let lift = (nd * (s * s) - ur * (s * c)) * (R(2.0) * c * k.y);
    return (ur * (k.x * s) + lift) * (co.half_rho * area);
}

// The axial part of the seabed friction (physics::seabed_friction_axis): a node of a line
// with tangent `t` (the sum of its elements' unit tangents), elastic normal force
// `fnorm` along the seabed's unit normal `n`, moving at `v`: (q, d) with q the line's
// unit direction within the seabed plane and d = (mu_a - mu_t) F_N / max(|v_t|, v_eps);
// the friction gains -d (v.q) q and the implicit damping d q q^T. Zero off the seabed
// or where the line stands normal to it.
fn seabed_friction_axis(fnorm: R, n: vec3<R>, v: vec3<R>, t: vec3<R>) -> vec4<R> {
    if !(fnorm > R(0.0)) {
        return vec4<R>(R(0.0));
    }
    let qp = t - n * dot(t, n);
    let ql = norm3(qp);
    if !(ql > R(1e-4) * norm3(t)) {
        return vec4<R>(R(0.0));
    }
    let q = qp * (R(1.0) / ql);
    let vt = v - n * dot(v, n);
    let d = (params.seabed_mu_axial - params.seabed_mu) * fnorm / max(norm3(vt), params.seabed_v_eps);
    return vec4<R>(q, d);
}
