// Wave kinematics: the WGSL twins of src/sea/kinematics.rs and src/sea/cache.rs (same
// names, same formulas; tests/gpu_waves.rs compares each with its Rust twin).
//
// Appended after the prelude (it uses `R`, `PIO2_HI`, `PIO2_LO` and `sin_cos`).
// Buffers: the components, `WaveComp` per component (`sea::kinematics::PackedComponent`,
// ten scalars, phases referred to a reference time `t_ref` chosen by the host), at
// group 0, binding 17. Nothing else is bound here: a stage that uses the waves passes
// the number of components, depth, stretching and ramp as arguments, and owns the
// cache's storage (seven scalars per node and time: eta, u, a).
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

// sum A cos(theta) over the first n components, no ramp.
fn wave_elevation_sum(n: u32, x: R, y: R, tau: R) -> R {
    var eta = R(0.0);
    for (var j = 0u; j < n; j++) {
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
    let r = wave_ramp(t, ramp_duration);
    let tau = t - t_ref;
    let eta = r * wave_elevation_sum(n, p.x, p.y, tau);
    let zs = wave_eval_depth(p.z, eta, depth, stretching);
    var u = vec3<R>(R(0.0));
    var a = vec3<R>(R(0.0));
    for (var j = 0u; j < n; j++) {
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
