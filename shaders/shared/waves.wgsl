// Wave kinematics: the WGSL twins of src/sea/kinematics.rs and src/sea/cache.rs (same
// names, same formulas; tests/gpu_waves.rs compares each with its Rust twin).
//
// Appended after the prelude (it uses `R`, `PIO2_HI`, `PIO2_LO`, `sin_cos` and
// `params`). Buffers: the components, `WaveComp` per component
// (`sea::kinematics::PackedComponent`, four vec4, sorted by k, phases referred to a reference
// time `t_ref` chosen by the host: the solver rebases them at each submission), at
// group 0, binding 17; the solver's per-node cache at binding 19 and its per-step rows
// at binding 20 (see the end of this file).
//
// Conventions: mean level z = 0, z up; eta = A cos(theta), theta = k (x cos b + y sin b)
// - w t + phi, b the direction of travel from +x towards +y. Infinite depth comes as
// `sea::GPU_DEEP` (1e30 m).

// One component in the buffer: four vec4 (sea::kinematics::PackedComponent's thirteen
// scalars, `k` twice), grouped by the loops that read them, so that a loop loads one
// vec4 where it loaded up to four scalars: on a software adapter (lavapipe) every
// storage load is a loop over the SIMD lanes. The elevation pass reads `phase` and
// `amps`, the decay pass `phase`, `amps` and `dir`, the decay cut's bisection `cut`
// (wave_comp, wave_comp_cut). Rust: gpu::layout::WaveComp.
struct WaveComp {
    // kx, ky, the phase at the reference time, omega.
    phase: vec4<R>,
    // The amplitude A, amp_u, amp_a, k.
    amps: vec4<R>,
    // cos b, sin b, 0, 0.
    dir: vec4<R>,
    // k and the decay cut's bounds on this component and all after it (sea::cut).
    cut: vec4<R>,
}

// A component's values as the sums use them, read from the buffer by wave_comp.
struct WaveCompVals {
    kx: R,
    ky: R,
    k: R,
    omega: R,
    phase_ref: R,
    amp: R,
    amp_u: R,
    amp_a: R,
    cos_b: R,
    sin_b: R,
}

// A component's decay cut, read by wave_comp_cut.
struct WaveCompCut {
    k: R,
    cut0: R,
    cut1: R,
    cut2: R,
}

struct WaveKin {
    eta: R,
    u: vec3<R>,
    a: vec3<R>,
}

const WAVE_WHEELER: u32 = 0u;
const WAVE_CONSTANT: u32 = 1u;

@group(0) @binding(17) var<storage, read> wave_comps: array<WaveComp>;

// Component j's values: one vec4 load per group a caller uses (the others are dead
// code, which the compiler drops).
fn wave_comp(j: u32) -> WaveCompVals {
    let p = wave_comps[j].phase;
    let a = wave_comps[j].amps;
    let d = wave_comps[j].dir;
    return WaveCompVals(p.x, p.y, a.w, p.w, p.z, a.x, a.y, a.z, d.x, d.y);
}

// Component j's decay cut: one vec4 load.
fn wave_comp_cut(j: u32) -> WaveCompCut {
    let c = wave_comps[j].cut;
    return WaveCompCut(c.x, c.y, c.z, c.w);
}

// exp(x) for x <= 0 in the shader's own arithmetic (WGSL has no f64 exp): Cody-Waite
// reduction x = n ln2 + r, |r| <= ln2 / 2, with ln2 split so that n * LN2_HI is exact
// in f32 and f64 (LN2_HI has 16 significant bits), Taylor to r^13 (truncation below
// 1e-17), then the factor 2^n by `ldexp`.
//
// `ldexp` gives the bits the loop before it gave (0.5^-n by repeated squaring, then
// p * 0.5^-n; branch `hgpuref`, BENCHMARKS.md "The seabed term and ldexp in the GPU
// refresh"): a power of two 2^n, n >= R_LEAST_EXP2 (the least subnormal's exponent),
// is exact, so both are p * 2^n rounded once (the loop's partial products are powers
// of two, exact down to 2^R_LEAST_EXP2; `ldexp` is the correctly rounded p * 2^n).
// Below it the loop's 0.5^-n was 0 (2^(R_LEAST_EXP2 - 1) is a tie that rounds to even,
// 0), where `ldexp` of p > 1 would round up to the least subnormal: hence the test on
// n, which also stands for the old test x < -745 (there n <= -1075). A device that
// flushes subnormals flushes both the same way. The loop ran as many times as the
// bits of -n (on lavapipe a loop runs as long as its slowest lane).
const WAVE_LN2_HI: R = 0.693145751953125;
const WAVE_LN2_LO: R = 1.4286068203094172321e-06;

fn wave_exp(x: R) -> R {
    let n = floor(x * R(1.4426950408889634) + R(0.5));
    if n < R_LEAST_EXP2 {
        return R(0.0);
    }
    let r = (x - n * WAVE_LN2_HI) - n * WAVE_LN2_LO;
    let p = R(1.0) + r * (R(1.0) + r * (R(1.0 / 2.0) + r * (R(1.0 / 6.0) + r * (R(1.0 / 24.0)
        + r * (R(1.0 / 120.0) + r * (R(1.0 / 720.0) + r * (R(1.0 / 5040.0) + r * (R(1.0 / 40320.0)
        + r * (R(1.0 / 362880.0) + r * (R(1.0 / 3628800.0) + r * (R(1.0 / 39916800.0)
        + r * (R(1.0 / 479001600.0) + r * R(1.0 / 6227020800.0)))))))))))));
    // n <= 0 in the domain x <= 0 (x > ln2 / 2 is no use here: the loop returned p).
    return ldexp(p, i32(n));
}

// The start-up ramp 0.5 (1 - cos(pi t / T_r)) on [0, T_r), 0 before, 1 after (and
// always 1 when T_r <= 0), computed as sin^2(pi t / (2 T_r)).
fn wave_ramp(t: R, ramp_duration: R) -> R {
    if ramp_duration <= R(0.0) || t >= ramp_duration {
        return R(1.0);
    }
    if t <= R(0.0) {
        return R(0.0);
    }
    // 0.5 (1 - cos x) = sin^2(x / 2), without the cancellation near t = 0.
    let s = sin_cos((PIO2_HI + PIO2_LO) * t / ramp_duration).x;
    return s * s;
}

// The ramp's time derivative (pi / (2 T_r)) sin(pi t / T_r) on (0, T_r), 0 elsewhere
// (and always 0 when T_r <= 0).
fn wave_ramp_rate(t: R, ramp_duration: R) -> R {
    if ramp_duration <= R(0.0) || t >= ramp_duration || t <= R(0.0) {
        return R(0.0);
    }
    let c = (PIO2_HI + PIO2_LO) / ramp_duration;
    return c * sin_cos(R(2.0) * c * t).x;
}

// Phase of a component at (x, y), tau = t - t_ref after its reference time.
fn wave_theta(c: WaveCompVals, x: R, y: R, tau: R) -> R {
    return c.kx * x + c.ky * y + c.phase_ref - c.omega * tau;
}

// sum A cos(theta) over the n components from `first`, no ramp.
fn wave_elevation_sum(first: u32, n: u32, x: R, y: R, tau: R) -> R {
    var eta = R(0.0);
    for (var j = first; j < first + n; j++) {
        let c = wave_comp(j);
        eta += c.amp * sin_cos(wave_theta(c, x, y, tau)).y;
    }
    return eta;
}

// The depth in [-h, 0] at which the profile is evaluated (Wheeler: (z - eta) /
// (1 + eta / h); constant: z), clamped so that air gets the surface value.
fn wave_eval_depth(z: R, eta: R, depth: R, stretching: u32) -> R {
    var zs = z;
    if stretching == WAVE_WHEELER {
        zs = (z - eta) / (R(1.0) + eta / depth);
    }
    return max(min(zs, R(0.0)), -depth);
}

// The time derivative of wave_eval_depth along a path with vertical velocity vz under
// an elevation changing at eta_rate (both along the path): Wheeler
// (vz - eta_rate (1 + zs / h)) / (1 + eta / h), constant vz, and 0 where the clamp to
// [-h, 0] holds the depth (a point in air or under the seabed).
fn wave_eval_depth_rate(z: R, eta: R, depth: R, stretching: u32, vz: R, eta_rate: R) -> R {
    var zs = z;
    var rate = vz;
    if stretching == WAVE_WHEELER {
        let d = R(1.0) + eta / depth;
        zs = (z - eta) / d;
        rate = (vz - eta_rate * (R(1.0) + zs / depth)) / d;
    }
    if zs > R(0.0) || zs < -depth {
        return R(0.0);
    }
    return rate;
}

// (e^{k zs} + e^{-k (zs + 2 h)}, e^{k zs} - e^{-k (zs + 2 h)}): the depth decay
// (cosh, sinh)(k (zs + h)) / sinh(k h) times 1 - e^{-2 k h}, without overflow.
//
// The seabed's reflection e2 is left out (0) where 2 k (zs + h) > 39, as on the CPU
// (sea::columns): then e2 / e1 = e^{-2 k (zs + h)} < e^{-39} < 1.2e-17, below half an
// ulp of e1 even where e1 is a power of two (the gap below it is 2^-53 e1 in f64, the
// half of that 5.6e-17 e1; f32's 3e-8 e1), so e1 + e2 and e1 - e2 round to e1 exactly,
// the bits of e1 +- 0. The margin (4.8x in f64) covers the rounding of the exponents
// (|x| eps, 1e-13 relative at k (zs + 2 h) = 640) and of wave_exp (a few ulps). A NaN
// fails the test and keeps e2, as before; zs + h >= 0 (wave_eval_depth's clamp).
fn wave_depth_decay(k: R, zs: R, depth: R) -> vec2<R> {
    let e1 = wave_exp(k * zs);
    var e2 = R(0.0);
    if !(R(2.0) * k * (zs + depth) > R(39.0)) {
        e2 = wave_exp(-k * (zs + R(2.0) * depth));
    }
    return vec2<R>(e1 + e2, e1 - e2);
}

// Elevation, velocity and acceleration of the first n components at p and time t
// (phases referred to t_ref), ramp included.
fn wave_kinematics_at(n: u32, depth: R, stretching: u32, ramp_duration: R, p: vec3<R>, t: R, t_ref: R) -> WaveKin {
    return wave_kinematics_tau(0u, n, depth, stretching, wave_ramp(t, ramp_duration), p, t - t_ref);
}

// The same for the n components from `first` (one sea of a packed run, sea::set), at
// tau = t - t_ref after the reference time, with the ramp factor r given (the solver
// forms both on the host in f64: an absolute time in f32 would carry 1e-3 s of
// rounding after three hours).
fn wave_kinematics_tau(first: u32, n: u32, depth: R, stretching: u32, r: R, p: vec3<R>, tau: R) -> WaveKin {
    let eta = r * wave_elevation_sum(first, n, p.x, p.y, tau);
    let zs = wave_eval_depth(p.z, eta, depth, stretching);
    var u = vec3<R>(R(0.0));
    var a = vec3<R>(R(0.0));
    for (var j = first; j < first + n; j++) {
        let c = wave_comp(j);
        let sc = sin_cos(wave_theta(c, p.x, p.y, tau));
        let d = wave_depth_decay(c.k, zs, depth);
        let uh = c.amp_u * d.x * sc.y;
        let ah = c.amp_a * d.x * sc.x;
        u += vec3<R>(uh * c.cos_b, uh * c.sin_b, c.amp_u * d.y * sc.x);
        a += vec3<R>(ah * c.cos_b, ah * c.sin_b, -c.amp_a * d.y * sc.y);
    }
    return WaveKin(eta, r * u, r * a);
}

// The decay cut (Rust twin: sea::cut::wave_decay_prefix): how many of the n components
// from `first` (sorted by k) a node at evaluation depth zs <= 0 needs in its decay pass,
// for a speed s = |v_h| + |zs'| and a ramp rate r_rate: the smallest m whose bound on
// the components from m on is at most 1, by bisection.
fn wave_decay_prefix(first: u32, n: u32, zs: R, s: R, r_rate: R) -> u32 {
    var lo = 0u;
    var hi = n;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        let c = wave_comp_cut(first + mid);
        let bound = wave_exp(c.k * zs) * (c.cut0 + c.cut1 * s + c.cut2 * abs(r_rate));
        if bound <= R(1.0) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// Values and their rates along a path.
struct WaveKinRates {
    val: WaveKin,
    rate: WaveKin,
}

// wave_kinematics_tau and the time derivatives of its values along the path of a
// point at p moving with velocity v (the cache's interpolant takes both at each end):
// the phases' rate is the Doppler-shifted kx vx + ky vy - w, the evaluation depth's is
// wave_eval_depth_rate's, d/dzs (ch, sh) = k (sh, ch), and the ramp's rate r_rate
// multiplies the unramped sums.
fn wave_kinematics_rates_tau(first: u32, n: u32, depth: R, stretching: u32, r: R, r_rate: R, p: vec3<R>, v: vec3<R>, tau: R) -> WaveKinRates {
    // The elevation and its rate (unramped sums), which set the evaluation depth.
    var se = R(0.0);
    var sed = R(0.0);
    for (var j = first; j < first + n; j++) {
        let c = wave_comp(j);
        let sc = sin_cos(wave_theta(c, p.x, p.y, tau));
        se += c.amp * sc.y;
        sed -= c.amp * sc.x * (c.kx * v.x + c.ky * v.y - c.omega);
    }
    let eta = r * se;
    let eta_rate = r * sed + r_rate * se;
    let zs = wave_eval_depth(p.z, eta, depth, stretching);
    let zs_rate = wave_eval_depth_rate(p.z, eta, depth, stretching, v.z, eta_rate);
    // The decay pass over the prefix the node needs (sea::cut).
    let m = wave_decay_prefix(first, n, zs, length(v.xy) + abs(zs_rate), r_rate);
    var u = vec3<R>(R(0.0));
    var a = vec3<R>(R(0.0));
    var du = vec3<R>(R(0.0));
    var da = vec3<R>(R(0.0));
    for (var j = first; j < first + m; j++) {
        let c = wave_comp(j);
        let d = wave_depth_decay(c.k, zs, depth);
        // A component decayed below 1e-30 (e^{k zs} = (ch + sh) / 2: short waves deep
        // down) contributes 0, as in the CPU's sums; its phase is not needed.
        if d.x + d.y < R(2e-30) {
            continue;
        }
        let sc = sin_cos(wave_theta(c, p.x, p.y, tau));
        let th_rate = c.kx * v.x + c.ky * v.y - c.omega;
        // d/dt of (ch, sh): k (sh, ch) zs_rate.
        let kz = c.k * zs_rate;
        let ch_cos = d.x * sc.y;
        let ch_sin = d.x * sc.x;
        let uh = c.amp_u * ch_cos;
        let ah = c.amp_a * ch_sin;
        u += vec3<R>(uh * c.cos_b, uh * c.sin_b, c.amp_u * d.y * sc.x);
        a += vec3<R>(ah * c.cos_b, ah * c.sin_b, -c.amp_a * d.y * sc.y);
        let duh = c.amp_u * (kz * d.y * sc.y - ch_sin * th_rate);
        let dah = c.amp_a * (kz * d.y * sc.x + ch_cos * th_rate);
        du += vec3<R>(duh * c.cos_b, duh * c.sin_b, c.amp_u * (kz * d.x * sc.x + d.y * sc.y * th_rate));
        da += vec3<R>(dah * c.cos_b, dah * c.sin_b, -c.amp_a * (kz * d.x * sc.y - d.y * sc.x * th_rate));
    }
    return WaveKinRates(
        WaveKin(eta, r * u, r * a),
        WaveKin(eta_rate, r * du + r_rate * u, r * da + r_rate * a),
    );
}

// The cache's cubic Hermite interpolation between refresh times t0, t1 from the
// values v0, v1 and rates d0, d1 there: w = [h00, Delta h10, h01, Delta h11] of
// s = (t - t0) / Delta, Delta = t1 - t0 (the host forms them in f64:
// sea::cache::hermite_weights).
fn wave_cache_hermite(v0: WaveKin, d0: WaveKin, v1: WaveKin, d1: WaveKin, w: vec4<R>) -> WaveKin {
    return WaveKin(
        w.x * v0.eta + w.y * d0.eta + w.z * v1.eta + w.w * d1.eta,
        w.x * v0.u + w.y * d0.u + w.z * v1.u + w.w * d1.u,
        w.x * v0.a + w.y * d0.a + w.z * v1.a + w.w * d1.a,
    );
}

// ---- The solver's per-node kinematics cache (sea::cache::WaveCache, the CPU path's
// cpu::water::BlockWaves): values and their rates along each node's path at two
// refresh times t0, t1 per node, interpolated between them (cubic Hermite) at every
// step. The host decides when a refresh is due, exactly as the CPU path does, and
// writes one WaveStep row per step of a submission, sea and depth band (sea::bands):
// band m's row of step k of a sea is m * band_rows + k after the sea's first, and a
// block reads its sea's from `BlockParams::wave_rows` (a packed run's members each in
// their own sea, sea::set); each node reads its band's (its band in the cache). ----

// One step of a submission in one sea. Rust: gpu::layout::WaveStep.
struct WaveStep {
    // The Hermite weights of this step's time, [h00, Delta h10, h01, Delta h11]
    // (wave_cache_hermite): a vec4, one load (on a software adapter, lavapipe, a loop
    // over the lanes per load, which every element of the step runs: wave_band_weights),
    // first in the row so that it is aligned at both precisions.
    w: vec4<R>,
    // Cache slots of the t0 values and of the t1 values (0 and 1: a refresh copies a
    // node's t1 values to slot 0).
    slot0: u32,
    slot1: u32,
    // 1 when the t0 values are evaluated afresh at this step (first step, or a jump
    // in time), else 0.
    restart: u32,
    // 1 when this step refreshes the cache before its element pass.
    refresh: u32,
    // Number of components (0: still water, nothing read).
    n: u32,
    // WAVE_WHEELER or WAVE_CONSTANT.
    stretching: u32,
    // The sea's first component in wave_comps (the seas' components are back to back).
    first: u32,
    // 1 when the refresh records each node's velocity for the next refresh's estimate
    // of its acceleration.
    track: u32,
    // The sea's number of depth bands (sea::bands); band m's row of a step is m *
    // band_rows rows after band 0's.
    n_bands: u32,
    band_rows: u32,
    // How many bands this step's decision is among: M + 1, M > 0 the coarsest band
    // that refreshes (so every band up to it does), not a restart; a node of one of
    // those bands is decided anew among them (wave_band). 0: no decision.
    decide: u32,
    // 1 when this step counts the nodes above their band's top: band 0 refreshes,
    // not a restart, more than one band.
    watch: u32,
    // Unused: the row's size a multiple of vec4<f64>'s alignment (32 bytes).
    pad0: u32,
    pad1: u32,
    pad2: u32,
    pad3: u32,
    // Refresh: t - t_ref (s), the ramp factor and its rate (1/s) at the step's time t
    // (restart only).
    tau0: R,
    ramp0: R,
    ramp_rate0: R,
    // Refresh: t1 - t_ref (s), the ramp factor and its rate at t1.
    tau1: R,
    ramp1: R,
    ramp_rate1: R,
    // Refresh: t1 - t, s (the t1 values are evaluated at x + v (t1 - t) + acc (t1 - t)^2 / 2
    // with velocity v + acc (t1 - t)).
    ahead: R,
    // Refresh: 1 / (t - the previous refresh's time), 1/s, 0 on a restart: the node's
    // acceleration acc is estimated as (v - v at the previous refresh) times it.
    acc_rate: R,
    // Water depth, m (sea::GPU_DEEP for deep water).
    depth: R,
    // How far ahead a decision into band 0 looks, s (sea::bands::BAND_LOOK_AHEAD band 0
    // intervals); into band m, 2^m times it (wave_band).
    look0: R,
    // The tops of bands 1 to 6, m (band 0's is infinite; sea::bands::MAX_BANDS at
    // most 7).
    top1: R,
    top2: R,
    top3: R,
    top4: R,
    top5: R,
    top6: R,
}

// The tops of bands 1 to 6 of a step row, m (wave_band's `tops`).
fn wave_step_tops(ws: WaveStep) -> array<R, 6> {
    return array<R, 6>(ws.top1, ws.top2, ws.top3, ws.top4, ws.top5, ws.top6);
}

// Fourteen scalars per node and slot: eta, u, a (m, m/s, m/s^2), then their rates
// along the node's path (m/s, m/s^2, m/s^3); two slots (slot 0 the values at the
// node's band's t0, slot 1 at its t1: a refresh copies slot 1 to slot 0, as the CPU
// cache does, since the bands' refreshes differ from node to node); then three per
// node: the node's velocity at the last refresh (m/s); then one per node: its depth
// band (a small whole number, exact in R); then one per node: how many times it was
// found above its band's top (sea::cache::WaveCache::breaches, summed by the host);
// then WAVE_ELEM_STRIDE per element: its band or mark (wave_elem_form, below; its
// midpoint cache is in wave_elems, as vec4 rows); then four per node: its breaches
// beyond the margin (wave_beyond_at); then the refresh's work list, two entries of
// WAVE_DUE_STRIDE per node at most (wave_due_at).
const WAVE_CACHE_STRIDE: u32 = 14u;
@group(0) @binding(19) var<storage, read_write> wave_cache: array<R>;
@group(0) @binding(20) var<storage, read> wave_steps: array<WaveStep>;
// The elements' midpoint cache, WAVE_ELEM_ROWS rows per element (wave_elem_rows_at),
// as vec4 rows: on a software adapter (lavapipe) a storage load is a loop over the
// SIMD lanes, one loop per load whatever its width, so the step reads an entry's 32
// scalars in 8 loads instead of 32.
@group(0) @binding(21) var<storage, read_write> wave_elems: array<vec4<R>>;

fn wave_cache_load7(o: u32) -> WaveKin {
    return WaveKin(
        wave_cache[o],
        vec3<R>(wave_cache[o + 1u], wave_cache[o + 2u], wave_cache[o + 3u]),
        vec3<R>(wave_cache[o + 4u], wave_cache[o + 5u], wave_cache[o + 6u]),
    );
}

fn wave_cache_store7(o: u32, w: WaveKin) {
    wave_cache[o] = w.eta;
    wave_cache[o + 1u] = w.u.x;
    wave_cache[o + 2u] = w.u.y;
    wave_cache[o + 3u] = w.u.z;
    wave_cache[o + 4u] = w.a.x;
    wave_cache[o + 5u] = w.a.y;
    wave_cache[o + 6u] = w.a.z;
}

fn wave_cache_store(slot: u32, i: u32, w: WaveKinRates) {
    let o = (slot * params.n_nodes + i) * WAVE_CACHE_STRIDE;
    wave_cache_store7(o, w.val);
    wave_cache_store7(o + 7u, w.rate);
}

// The band of a node at height z (m) with vertical velocity vz (m/s) and
// acceleration estimate az (m/s^2), among bands 0 to n_bands - 1 (those refreshing at
// the decision): the deepest band m whose top is not under z + |vz| L_m + |az| L_m^2 / 2
// + margin, L_m = look0 2^m the look-ahead of band m (BAND_LOOK_AHEAD times its own
// interval; the node stays in m until m's next refresh). `tops` are the tops of bands 1 to 6 (band 0's is infinite). The
// bound grows with m and the tops fall: the search stops at the first band that does
// not pass. Rust twin: sea::bands::wave_band (its `tops[m]` is this `tops[m - 1]`,
// its tops' length this `n_bands`).
fn wave_band(z: R, vz: R, az: R, look0: R, margin: R, tops_in: array<R, 6>, n_bands: u32) -> u32 {
    // A local copy: indexed at run time.
    var tops = tops_in;
    var b = 0u;
    var h = look0;
    loop {
        if b + 1u >= n_bands || b >= 6u {
            break;
        }
        // Band b + 1's look-ahead: a doubling, exact in any precision.
        h = h + h;
        let bound = z + abs(vz) * h + R(0.5) * abs(az) * h * h + margin;
        if !(bound <= tops[b]) {
            break;
        }
        b = b + 1u;
    }
    return b;
}

// Added to a node's bound in the band decision, m (sea::bands::BAND_MARGIN).
const WAVE_BAND_MARGIN: R = 2.0;

// Where node i's band is in the cache.
fn wave_band_at(i: u32) -> u32 {
    return (2u * WAVE_CACHE_STRIDE + 3u) * params.n_nodes + i;
}

// The row of step k of the submission for band b of the sea of node i's block. One
// row read whatever b (band 0's is b * band_rows = 0 rows on), not one per branch: on a
// software adapter (lavapipe) an `if` runs both sides, loads included, so a branch
// for band 0 read every field the caller uses twice.
fn wave_band_step(i: u32, b: u32, k: u32) -> WaveStep {
    let r = blocks[nodes[i].block].wave_rows + k;
    return wave_steps[r + b * wave_steps[r].band_rows];
}

// Node i's elevation, wave velocity and wave acceleration at step k of the
// submission (all zero in still water), interpolated with its band's weights. CPU
// twin: cpu::water::BlockWaves::fill.
fn node_waves(i: u32, k: u32) -> WaveKin {
    let r = blocks[nodes[i].block].wave_rows + k;
    var ws = wave_steps[r];
    if ws.n == 0u {
        return WaveKin(R(0.0), vec3<R>(R(0.0)), vec3<R>(R(0.0)));
    }
    // Still water has no band entries: read only past the test above.
    let b = u32(wave_cache[wave_band_at(i)]);
    if b != 0u {
        ws = wave_steps[r + b * ws.band_rows];
    }
    let o0 = (ws.slot0 * params.n_nodes + i) * WAVE_CACHE_STRIDE;
    let o1 = (ws.slot1 * params.n_nodes + i) * WAVE_CACHE_STRIDE;
    return wave_cache_hermite(
        wave_cache_load7(o0),
        wave_cache_load7(o0 + 7u),
        wave_cache_load7(o1),
        wave_cache_load7(o1 + 7u),
        ws.w,
    );
}

// ---- The per-element midpoint cache (the CPU path's chain columns,
// cpu::water::BlockWaves::fill_chain): per element, formed when either of its nodes
// refreshes, the surface over each of its two nodes and the mean of their wave
// velocity and acceleration, values and rates at both cache times (4 x 8 scalars), so
// that the element pass interpolates 32 scalars instead of reading both nodes' 56.
// Interpolation is linear in the cached values, so this is the same value up to
// round-off. The element's nodes share a band but for the few elements across a band
// top, whose two nodes interpolate with different weights: those are marked with
// both bands (WAVE_ELEM_MIXED), keep node a's values and both surfaces in their entry
// and node b's velocity and acceleration after it (elem_waves). The entries are
// vec4 rows of their own buffer (wave_elems): the step's loads of an entry are 8
// rows, and 6 more for node b's values, where scalars took 32 and 24 loads; on a
// software adapter each load is a loop over the lanes whatever its width. The
// element's band (or mark) stays a scalar of the cache (wave_elem_at), so that a GPU
// reads no more bytes than the 33 scalars it read before. ----

// An element's waves: the surface over nodes a and b, the mean wave velocity and
// acceleration of the two (m, m/s, m/s^2; or their rates).
struct WaveMid {
    eta_a: R,
    eta_b: R,
    u: vec3<R>,
    a: vec3<R>,
}

// One band marker per element, after the nodes' part of the cache.
const WAVE_ELEM_STRIDE: u32 = 1u;
// Rows of an element's entry in wave_elems: the four sides (values at t0, rates at
// t0, values at t1, rates at t1) of two rows each, (eta_a, u) and (eta_b, a)
// (wave_mid_load); then, for an element across a band top only, node b's velocity
// and acceleration on the four sides, 24 scalars in six rows (wave_mixed_b_load).
const WAVE_ELEM_ROWS: u32 = 14u;
// The band marker of an element whose nodes are in different bands is at least this:
// WAVE_ELEM_MIXED + 8 bb + ba for node a in band ba and node b in band bb (small whole
// numbers, exact in R; a band is below 8: sea::bands::MAX_BANDS).
const WAVE_ELEM_MIXED: u32 = 8u;

// The element part of node a's and node b's cache entries (one side: values or rates
// at one time). Rust twin: sea::cache::wave_cache_midpoint.
fn wave_cache_midpoint(a: WaveKin, b: WaveKin) -> WaveMid {
    return WaveMid(a.eta, b.eta, R(0.5) * (a.u + b.u), R(0.5) * (a.a + b.a));
}

// wave_cache_hermite over the element's eight scalars (Rust twin:
// sea::cache::wave_cache_hermite over slices of eight).
fn wave_mid_hermite(v0: WaveMid, d0: WaveMid, v1: WaveMid, d1: WaveMid, w: vec4<R>) -> WaveMid {
    return WaveMid(
        w.x * v0.eta_a + w.y * d0.eta_a + w.z * v1.eta_a + w.w * d1.eta_a,
        w.x * v0.eta_b + w.y * d0.eta_b + w.z * v1.eta_b + w.w * d1.eta_b,
        w.x * v0.u + w.y * d0.u + w.z * v1.u + w.w * d1.u,
        w.x * v0.a + w.y * d0.a + w.z * v1.a + w.w * d1.a,
    );
}

// Where element e's band (or mark) is in the cache (after the nodes' 2 x 14 + 5 per
// node).
fn wave_elem_at(e: u32) -> u32 {
    return (2u * WAVE_CACHE_STRIDE + 5u) * params.n_nodes + e * WAVE_ELEM_STRIDE;
}

// Where element e's entry starts in wave_elems.
fn wave_elem_rows_at(e: u32) -> u32 {
    return e * WAVE_ELEM_ROWS;
}

// One side of an entry from its two rows at q: (eta_a, u) and (eta_b, a).
fn wave_mid_load(q: u32) -> WaveMid {
    let x = wave_elems[q];
    let y = wave_elems[q + 1u];
    return WaveMid(x.x, y.x, x.yzw, y.yzw);
}

fn wave_mid_store(q: u32, m: WaveMid) {
    wave_elems[q] = vec4<R>(m.eta_a, m.u);
    wave_elems[q + 1u] = vec4<R>(m.eta_b, m.a);
}

// Node b's velocity and acceleration on the four sides of an element across a band
// top (values at t0, rates at t0, values at t1, rates at t1), 24 scalars packed in
// the six rows from q (the surfaces are in the entry's sides: wave_mixed_side).
fn wave_mixed_b_store(q: u32, s0: WaveKin, s1: WaveKin, s2: WaveKin, s3: WaveKin) {
    wave_elems[q] = vec4<R>(s0.u, s0.a.x);
    wave_elems[q + 1u] = vec4<R>(s0.a.yz, s1.u.xy);
    wave_elems[q + 2u] = vec4<R>(s1.u.z, s1.a);
    wave_elems[q + 3u] = vec4<R>(s2.u, s2.a.x);
    wave_elems[q + 4u] = vec4<R>(s2.a.yz, s3.u.xy);
    wave_elems[q + 5u] = vec4<R>(s3.u.z, s3.a);
}

// The four sides wave_mixed_b_store packed, their surfaces zero (the caller uses
// only the velocity and acceleration).
fn wave_mixed_b_load(q: u32) -> array<WaveKin, 4> {
    let x0 = wave_elems[q];
    let x1 = wave_elems[q + 1u];
    let x2 = wave_elems[q + 2u];
    let x3 = wave_elems[q + 3u];
    let x4 = wave_elems[q + 4u];
    let x5 = wave_elems[q + 5u];
    let z = R(0.0);
    return array<WaveKin, 4>(
        WaveKin(z, x0.xyz, vec3<R>(x0.w, x1.xy)),
        WaveKin(z, vec3<R>(x1.zw, x2.x), x2.yzw),
        WaveKin(z, x3.xyz, vec3<R>(x3.w, x4.xy)),
        WaveKin(z, vec3<R>(x4.zw, x5.x), x5.yzw),
    );
}

// Node a's side and node b's surface on that side as an element entry stores them
// for an element across a band top (wave_elem_form): node a's own velocity and
// acceleration, not the mean, which the step forms after interpolating each node
// with its own band's weights (elem_waves).
fn wave_mixed_side(a: WaveKin, b: WaveKin) -> WaveMid {
    return WaveMid(a.eta, b.eta, a.u, a.a);
}

// Forms element e's entry at step k, after the nodes' refresh (wave_refresh_node)
// and only where one of its nodes' bands refreshed at this step (a node changes band
// only at a refresh of its old and its new band): its band and, per side, the surface over
// its nodes and the mean of their velocity and acceleration; or, for an element whose
// nodes' bands differ, the mark WAVE_ELEM_MIXED + 8 bb + ba and per side node a's
// values and node b's surface (wave_mixed_side), then node b's velocity and
// acceleration on the four sides (wave_mixed_b_store): the same values the step
// would read from the nodes' cache, which changes only at a refresh of node b's band,
// when this entry is formed again. CPU twin:
// cpu::water::ChainColumns::form (which, with several bands, puts every node in the
// power basis of one time instead of marking the mixed elements).
fn wave_elem_form(e: u32, k: u32) {
    let ep = elems[e];
    if wave_steps[blocks[ep.block].wave_rows + k].n == 0u {
        return;
    }
    let ba = u32(wave_cache[wave_band_at(ep.a)]);
    let bb = u32(wave_cache[wave_band_at(ep.b)]);
    let wa = wave_band_step(ep.a, ba, k);
    let wb = wave_band_step(ep.b, bb, k);
    if wa.refresh == 0u && wb.refresh == 0u {
        return;
    }
    let o = wave_elem_at(e);
    let q = wave_elem_rows_at(e);
    let oa0 = (wa.slot0 * params.n_nodes + ep.a) * WAVE_CACHE_STRIDE;
    let oa1 = (wa.slot1 * params.n_nodes + ep.a) * WAVE_CACHE_STRIDE;
    let ob0 = (wa.slot0 * params.n_nodes + ep.b) * WAVE_CACHE_STRIDE;
    let ob1 = (wa.slot1 * params.n_nodes + ep.b) * WAVE_CACHE_STRIDE;
    // Both kinds of entry from the same loads and stores, the kind selected: on a
    // software adapter an `if` per kind ran both kinds' loads and stores. Node b's
    // velocity and acceleration rows only for a mixed element, the only kind whose
    // step reads them (elem_waves): on a GPU the other elements skip the 24 stores.
    let mixed = ba != bb;
    wave_cache[o] = R(select(ba, WAVE_ELEM_MIXED + 8u * bb + ba, mixed));
    let b0 = wave_cache_load7(ob0);
    let b1 = wave_cache_load7(ob0 + 7u);
    let b2 = wave_cache_load7(ob1);
    let b3 = wave_cache_load7(ob1 + 7u);
    wave_mid_store(q, wave_elem_side(wave_cache_load7(oa0), b0, mixed));
    wave_mid_store(q + 2u, wave_elem_side(wave_cache_load7(oa0 + 7u), b1, mixed));
    wave_mid_store(q + 4u, wave_elem_side(wave_cache_load7(oa1), b2, mixed));
    wave_mid_store(q + 6u, wave_elem_side(wave_cache_load7(oa1 + 7u), b3, mixed));
    if mixed {
        wave_mixed_b_store(q + 8u, b0, b1, b2, b3);
    }
}

// One side of an element's entry from its nodes' a and b: wave_mixed_side for an
// element across a band top, else wave_cache_midpoint (the same values either way as
// when each had its own branch).
fn wave_elem_side(a: WaveKin, b: WaveKin, mixed: bool) -> WaveMid {
    let m = wave_cache_midpoint(a, b);
    let x = wave_mixed_side(a, b);
    return WaveMid(m.eta_a, m.eta_b, select(m.u, x.u, mixed), select(m.a, x.a, mixed));
}

// Where a block's sea's rows are at one step: `r` the row of band 0 at that step
// (BlockParams::wave_rows + k), `band_rows` the rows from one band to the next, the
// cache slots of the t0 and t1 values, and whether the sea has waves (`n != 0`). All
// but `r` are the same in every row of a sea in a submission
// (gpu::wave_schedule::WaveSchedule::base), so the fused kernel reads them once per
// dispatch (wave_sea_rows) and moves `r` along with its step: on a software adapter
// (lavapipe) every storage load is a loop over the SIMD lanes.
struct SeaRows {
    r: u32,
    band_rows: u32,
    slot0: u32,
    slot1: u32,
    waves: bool,
}

// The rows of step k of the sea whose band 0 starts at row `wave_rows`.
fn wave_sea_rows(wave_rows: u32, k: u32) -> SeaRows {
    let r = wave_rows + k;
    let n = wave_steps[r].n;
    return SeaRows(r, wave_steps[r].band_rows, wave_steps[r].slot0, wave_steps[r].slot1, n != 0u);
}

// The Hermite weights of band b's row at rows `sr`.
fn wave_band_weights(sr: SeaRows, b: u32) -> vec4<R> {
    let r = sr.r + b * sr.band_rows;
    return wave_steps[r].w;
}

// Element e's waves at rows `sr` of a sea with waves (the caller checks): its entry
// interpolated with its band's weights; for an element across a band top, node a's
// values from the entry with node a's band's weights, node b's surface from the
// entry and its velocity and acceleration from the entry's last six rows (copies of
// the nodes' cache: wave_elem_form) with node b's band's weights, then their mean, as
// wave_cache_midpoint of the two nodes' interpolations (the same arithmetic on the
// same values, so the same bits). Both cases share the entry's 8 row loads: on a
// software adapter (lavapipe) an `if` costs the code of both sides, loads included,
// so every element runs the 6 rows of node b too (24 scalar loads of the nodes' cache
// before). CPU twin: cpu::water::BlockWaves::fill_chain.
fn elem_waves(e: u32, sr: SeaRows) -> WaveMid {
    let mark = u32(wave_cache[wave_elem_at(e)]);
    let mixed = mark >= WAVE_ELEM_MIXED;
    let ba = select(mark, (mark - WAVE_ELEM_MIXED) % 8u, mixed);
    let q = wave_elem_rows_at(e);
    let v0 = wave_mid_load(q);
    let d0 = wave_mid_load(q + 2u);
    let v1 = wave_mid_load(q + 4u);
    let d1 = wave_mid_load(q + 6u);
    var m = wave_mid_hermite(v0, d0, v1, d1, wave_band_weights(sr, ba));
    if mixed {
        let wb = wave_band_weights(sr, (mark - WAVE_ELEM_MIXED) / 8u);
        m.eta_b = wb.x * v0.eta_b + wb.y * d0.eta_b + wb.z * v1.eta_b + wb.w * d1.eta_b;
        let s = wave_mixed_b_load(q + 8u);
        let b = wave_cache_hermite(s[0], s[1], s[2], s[3], wb);
        m.u = R(0.5) * (m.u + b.u);
        m.a = R(0.5) * (m.a + b.a);
    }
    return m;
}

// Where node i's record of its breaches beyond the margin is in the cache, after the
// elements' part: how many, then the height and the band's top (m) of its first one
// and its step within its `advance` call (small whole numbers, exact in R).
fn wave_beyond_at(i: u32) -> u32 {
    return wave_elem_at(params.n_elems) + 4u * i;
}

// Node i at height z, more than WAVE_BAND_MARGIN above the top `top` of its band at
// step k of the submission: counted in its record (the first one's height, top and
// step kept) and in the status (how many, and the earliest step of the advance call),
// from which the host warns as the CPU path does (sea::bands::warn_beyond_margin).
fn wave_beyond_margin(i: u32, k: u32, z: R, top: R) {
    let o = wave_beyond_at(i);
    if wave_cache[o] == R(0.0) {
        wave_cache[o + 1u] = z;
        wave_cache[o + 2u] = top;
        wave_cache[o + 3u] = R(params.step_base + k);
    }
    wave_cache[o] = wave_cache[o] + R(1.0);
    atomicAdd(&status.beyond, 1u);
    atomicMax(&status.beyond_step, 0xffffffffu - (params.step_base + k));
}

// ---- The refresh's work list. A refresh runs in two passes: the first
// (wave_refresh_node, over every node) decides, copies and tracks, and puts each
// evaluation a node needs on this list; the second (wave_refresh_due_entry, over it)
// evaluates. Why: at most refreshes only band 0's nodes are due (about one per chain,
// spread over the layout), and a SIMD group (llvmpipe's 4-8 lanes, a GPU's warp) runs
// the 200-component sums once per group with any lane due: over the list the due
// nodes sit side by side in a few groups. Each evaluation is the same call with the
// same arguments as in one pass, so the same bits whatever the list's order. ----

// Per entry: the node, which evaluation (0: the t0 values of a restart, 1: the t1
// values), then the position (m) and velocity (m/s) to evaluate at. At most two
// entries per node (a restart), after the nodes' beyond-margin records.
const WAVE_DUE_STRIDE: u32 = 8u;

fn wave_due_at(n: u32) -> u32 {
    return wave_beyond_at(params.n_nodes) + WAVE_DUE_STRIDE * n;
}

// Appends node i's evaluation `which` at p along v (small whole numbers stored in R:
// the host keeps node indices below 2^24, exact in f32).
fn wave_due_push(i: u32, which: u32, p: vec3<R>, v: vec3<R>) {
    let o = wave_due_at(atomicAdd(&status.refresh_due, 1u));
    wave_cache[o] = R(i);
    wave_cache[o + 1u] = R(which);
    wave_cache[o + 2u] = p.x;
    wave_cache[o + 3u] = p.y;
    wave_cache[o + 4u] = p.z;
    wave_cache[o + 5u] = v.x;
    wave_cache[o + 6u] = v.y;
    wave_cache[o + 7u] = v.z;
}

// Entry n of the list at step k, if there is one: its node's values and rates in the
// slot of the evaluation (t0 of a restart: slot0 at tau0 with ramp0; t1: slot1 at
// tau1 with ramp1) of the node's band's row (the band the first pass set). One call
// of wave_kinematics_rates_tau with its arguments selected, not one per branch: on a
// software adapter an `if` runs both sides.
fn wave_refresh_due_entry(n: u32, k: u32) {
    if n >= atomicLoad(&status.refresh_due) {
        return;
    }
    let o = wave_due_at(n);
    let i = u32(wave_cache[o]);
    let t1 = wave_cache[o + 1u] != R(0.0);
    let p = vec3<R>(wave_cache[o + 2u], wave_cache[o + 3u], wave_cache[o + 4u]);
    let v = vec3<R>(wave_cache[o + 5u], wave_cache[o + 6u], wave_cache[o + 7u]);
    let ws = wave_band_step(i, u32(wave_cache[wave_band_at(i)]), k);
    let slot = select(ws.slot0, ws.slot1, t1);
    let ramp = select(ws.ramp0, ws.ramp1, t1);
    let ramp_rate = select(ws.ramp_rate0, ws.ramp_rate1, t1);
    let tau = select(ws.tau0, ws.tau1, t1);
    wave_cache_store(slot, i, wave_kinematics_rates_tau(ws.first, ws.n, ws.depth, ws.stretching, ramp, ramp_rate, p, v, tau));
}

// The first pass of the refresh of node i at step k, at absolute position p (m) with
// velocity v (m/s), when the node's band refreshes at this step (nothing otherwise:
// the node keeps its cache): on a restart the t0 values and rates at p along v (on
// the work list) and the node back in band 0; else the t1 values and rates become
// the t0 ones, and at a band decision (bands 0 to decide - 1 refresh, its own among
// them) the node goes to the band `wave_band` gives among those; then the t1 values
// and rates of its band (on the work list) at the predicted
// position p + v h + acc h^2 / 2 along v + acc h (h = t1 - t, acc the velocity change
// since the previous refresh over its time, 0 on a restart). At a refresh of band 0
// a node above its band's top is counted. CPU twin (both passes):
// sea::cache::WaveCache::refresh_if_due.
fn wave_refresh_node(i: u32, k: u32, p: vec3<R>, v: vec3<R>) {
    let ab = wave_band_at(i);
    let old = u32(wave_cache[ab]);
    let wo = wave_band_step(i, old, k);
    if wo.watch != 0u {
        var tops = wave_step_tops(wo);
        if old > 0u && p.z > tops[old - 1u] {
            let bi = ab + params.n_nodes;
            wave_cache[bi] = wave_cache[bi] + R(1.0);
            if p.z - tops[old - 1u] > WAVE_BAND_MARGIN {
                wave_beyond_margin(i, k, p.z, tops[old - 1u]);
            }
        }
    }
    if wo.refresh == 0u {
        return;
    }
    let ov = (2u * params.n_nodes * WAVE_CACHE_STRIDE) + 3u * i;
    var acc = vec3<R>(R(0.0));
    if wo.acc_rate != R(0.0) {
        acc = (v - vec3<R>(wave_cache[ov], wave_cache[ov + 1u], wave_cache[ov + 2u])) * wo.acc_rate;
    }
    var band = old;
    if wo.restart != 0u {
        band = 0u;
    } else if wo.decide != 0u {
        // The node's band refreshes (above), so it is among the `decide` bands.
        band = wave_band(p.z, v.z, acc.z, wo.look0, WAVE_BAND_MARGIN, wave_step_tops(wo), min(wo.decide, wo.n_bands));
    }
    wave_cache[ab] = R(band);
    let ws = wave_band_step(i, band, k);
    if ws.refresh == 0u {
        return;
    }
    if ws.restart != 0u {
        wave_due_push(i, 0u, p, v);
    } else {
        let o0 = (ws.slot0 * params.n_nodes + i) * WAVE_CACHE_STRIDE;
        let o1 = (ws.slot1 * params.n_nodes + i) * WAVE_CACHE_STRIDE;
        for (var j = 0u; j < WAVE_CACHE_STRIDE; j = j + 1u) {
            wave_cache[o0 + j] = wave_cache[o1 + j];
        }
    }
    if ws.track != 0u {
        wave_cache[ov] = v.x;
        wave_cache[ov + 1u] = v.y;
        wave_cache[ov + 2u] = v.z;
    }
    let h = ws.ahead;
    let p1 = p + v * h + R(0.5) * acc * h * h;
    let v1 = v + acc * h;
    wave_due_push(i, 1u, p1, v1);
}
