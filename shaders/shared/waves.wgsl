// Wave kinematics: the WGSL twins of src/sea/kinematics.rs and src/sea/cache.rs (same
// names, same formulas; tests/gpu_waves.rs compares each with its Rust twin).
//
// Appended after the prelude (it uses `R`, `PIO2_HI`, `PIO2_LO`, `sin_cos` and
// `params`). Buffers: the components, `WaveComp` per component
// (`sea::kinematics::PackedComponent`, ten scalars, phases referred to a reference
// time `t_ref` chosen by the host: the solver rebases them at each submission), at
// group 0, binding 17; the solver's per-node cache at binding 19 and its per-step rows
// at binding 20 (see the end of this file).
//
// Conventions: mean level z = 0, z up; eta = A cos(theta), theta = k (x cos b + y sin b)
// - w t + phi, b the direction of travel from +x towards +y. Infinite depth comes as
// `sea::GPU_DEEP` (1e30 m).

struct WaveComp {
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

struct WaveKin {
    eta: R,
    u: vec3<R>,
    a: vec3<R>,
}

const WAVE_WHEELER: u32 = 0u;
const WAVE_CONSTANT: u32 = 1u;

@group(0) @binding(17) var<storage, read> wave_comps: array<WaveComp>;

// exp(x) for x <= 0 in the shader's own arithmetic (WGSL has no f64 exp): Cody-Waite
// reduction x = n ln2 + r, |r| <= ln2 / 2, with ln2 split so that n * LN2_HI is exact
// in f32 and f64 (LN2_HI has 16 significant bits), Taylor to r^13 (truncation below
// 1e-17), then the factor 2^n by repeated squaring of 1/2.
const WAVE_LN2_HI: R = 0.693145751953125;
const WAVE_LN2_LO: R = 1.4286068203094172321e-06;

fn wave_exp(x: R) -> R {
    if x < R(-745.0) {
        return R(0.0);
    }
    let n = floor(x * R(1.4426950408889634) + R(0.5));
    let r = (x - n * WAVE_LN2_HI) - n * WAVE_LN2_LO;
    let p = R(1.0) + r * (R(1.0) + r * (R(1.0 / 2.0) + r * (R(1.0 / 6.0) + r * (R(1.0 / 24.0)
        + r * (R(1.0 / 120.0) + r * (R(1.0 / 720.0) + r * (R(1.0 / 5040.0) + r * (R(1.0 / 40320.0)
        + r * (R(1.0 / 362880.0) + r * (R(1.0 / 3628800.0) + r * (R(1.0 / 39916800.0)
        + r * (R(1.0 / 479001600.0) + r * R(1.0 / 6227020800.0)))))))))))));
    var m = u32(-n);
    var s = R(1.0);
    var b = R(0.5);
    loop {
        if m == 0u {
            break;
        }
        if (m & 1u) == 1u {
            s = s * b;
        }
        b = b * b;
        m = m >> 1u;
    }
    return p * s;
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

// Phase of a component at (x, y), tau = t - t_ref after its reference time.
fn wave_theta(c: WaveComp, x: R, y: R, tau: R) -> R {
    return c.kx * x + c.ky * y + c.phase_ref - c.omega * tau;
}

// sum A cos(theta) over the n components from `first`, no ramp.
fn wave_elevation_sum(first: u32, n: u32, x: R, y: R, tau: R) -> R {
    var eta = R(0.0);
    for (var j = first; j < first + n; j++) {
        let c = wave_comps[j];
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

// (e^{k zs} + e^{-k (zs + 2 h)}, e^{k zs} - e^{-k (zs + 2 h)}): the depth decay
// (cosh, sinh)(k (zs + h)) / sinh(k h) times 1 - e^{-2 k h}, without overflow.
fn wave_depth_decay(k: R, zs: R, depth: R) -> vec2<R> {
    let e1 = wave_exp(k * zs);
    let e2 = wave_exp(-k * (zs + R(2.0) * depth));
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
        let c = wave_comps[j];
        let sc = sin_cos(wave_theta(c, p.x, p.y, tau));
        let d = wave_depth_decay(c.k, zs, depth);
        let uh = c.amp_u * d.x * sc.y;
        let ah = c.amp_a * d.x * sc.x;
        u += vec3<R>(uh * c.cos_b, uh * c.sin_b, c.amp_u * d.y * sc.x);
        a += vec3<R>(ah * c.cos_b, ah * c.sin_b, -c.amp_a * d.y * sc.y);
    }
    return WaveKin(eta, r * u, r * a);
}

// The cache's interpolation (1 - s) v0 + s v1 between refresh times (s in [0, 1]).
fn wave_cache_lerp(v0: WaveKin, v1: WaveKin, s: R) -> WaveKin {
    let q = R(1.0) - s;
    return WaveKin(q * v0.eta + s * v1.eta, q * v0.u + s * v1.u, q * v0.a + s * v1.a);
}

// ---- The solver's per-node kinematics cache (sea::cache::WaveCache, the CPU path's
// cpu::water::BlockWaves): values at two refresh times t0, t1 per node, interpolated
// between them at every step. The host decides when a refresh is due, exactly as the
// CPU path does, and writes one WaveStep row per step of a submission and sea: the rows
// of sea q are q * STEPS_PER_SUBMISSION + k, and a block reads its sea's from
// `BlockParams::wave_rows` (a packed run's members each in their own sea, sea::set). ----

// One step of a submission in one sea. Rust: gpu::layout::WaveStep.
struct WaveStep {
    // Cache slots of the t0 values and of the t1 values (0 or 1; 2: the evaluation's
    // own slot, so that an output-time evaluation leaves the run's cache alone).
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
    pad: u32,
    // Interpolation weight of this step's time, (t - t0) / (t1 - t0) in [0, 1].
    s: R,
    // Refresh: t - t_ref (s) and the ramp factor at the step's time t (restart only).
    tau0: R,
    ramp0: R,
    // Refresh: t1 - t_ref (s) and the ramp factor at t1.
    tau1: R,
    ramp1: R,
    // Refresh: t1 - t, s (the t1 values are evaluated at x + v (t1 - t)).
    ahead: R,
    // Water depth, m (sea::GPU_DEEP for deep water).
    depth: R,
}

// Seven scalars per node and slot: eta, u, a (m, m/s, m/s^2); three slots.
@group(0) @binding(19) var<storage, read_write> wave_cache: array<R>;
@group(0) @binding(20) var<storage, read> wave_steps: array<WaveStep>;

fn wave_cache_load(slot: u32, i: u32) -> WaveKin {
    let o = (slot * params.n_nodes + i) * 7u;
    return WaveKin(
        wave_cache[o],
        vec3<R>(wave_cache[o + 1u], wave_cache[o + 2u], wave_cache[o + 3u]),
        vec3<R>(wave_cache[o + 4u], wave_cache[o + 5u], wave_cache[o + 6u]),
    );
}

fn wave_cache_store(slot: u32, i: u32, w: WaveKin) {
    let o = (slot * params.n_nodes + i) * 7u;
    wave_cache[o] = w.eta;
    wave_cache[o + 1u] = w.u.x;
    wave_cache[o + 2u] = w.u.y;
    wave_cache[o + 3u] = w.u.z;
    wave_cache[o + 4u] = w.a.x;
    wave_cache[o + 5u] = w.a.y;
    wave_cache[o + 6u] = w.a.z;
}

// The row of step k of the submission for the sea of node i's block.
fn node_wave_step(i: u32, k: u32) -> WaveStep {
    return wave_steps[blocks[nodes[i].block].wave_rows + k];
}

// Node i's elevation, wave velocity and wave acceleration at step k of the
// submission (all zero in still water). CPU twin: cpu::water::BlockWaves::fill.
fn node_waves(i: u32, k: u32) -> WaveKin {
    let ws = node_wave_step(i, k);
    if ws.n == 0u {
        return WaveKin(R(0.0), vec3<R>(R(0.0)), vec3<R>(R(0.0)));
    }
    return wave_cache_lerp(wave_cache_load(ws.slot0, i), wave_cache_load(ws.slot1, i), ws.s);
}

// The refresh of node i at step k, at absolute position p (m) with velocity v (m/s):
// on a restart the t0 values at p, then the t1 values at the predicted position
// p + v (t1 - t); nothing when the node's sea does not refresh at this step. CPU twin:
// sea::cache::WaveCache::refresh_if_due.
fn wave_refresh_node(i: u32, k: u32, p: vec3<R>, v: vec3<R>) {
    let ws = node_wave_step(i, k);
    if ws.refresh == 0u {
        return;
    }
    if ws.restart != 0u {
        wave_cache_store(ws.slot0, i, wave_kinematics_tau(ws.first, ws.n, ws.depth, ws.stretching, ws.ramp0, p, ws.tau0));
    }
    wave_cache_store(ws.slot1, i, wave_kinematics_tau(ws.first, ws.n, ws.depth, ws.stretching, ws.ramp1, p + v * ws.ahead, ws.tau1));
}
