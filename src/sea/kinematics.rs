//! Airy (linear) kinematics of a sum of wave components: elevation, water velocity and
//! acceleration at a point, with Wheeler stretching (or the profile held at `z = 0`)
//! and the start-up ramp. Each function here has a WGSL twin of the same name in
//! `shaders/shared/waves.wgsl`.

pub use super::columns::{
    wave_kinematics_columns, wave_kinematics_rates_columns, ComponentColumns, KinematicsScratch,
};
use super::cut::{decay_cut_bounds, wave_decay_prefix};
use super::{poly, SeaState, Stretching, WaveComponent};
use std::f64::consts::{PI, TAU};

/// Elevation, velocity and acceleration of the water at one point and time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Kinematics {
    /// Surface elevation `eta` above the mean level at the point's `(x, y)`, m.
    pub eta: f64,
    /// Water velocity `u`, m/s.
    pub u: [f64; 3],
    /// Water acceleration `a = du/dt` (local, linear theory), m/s^2.
    pub a: [f64; 3],
}

/// One component prepared for evaluation (the layout of the WGSL `WaveComp`).
///
/// The depth decay of the velocity is `cosh(k (z + h)) / sinh(k h)` horizontally and
/// `sinh(k (z + h)) / sinh(k h)` vertically. Written with exponentials,
/// `(e^{k z} +- e^{-k (z + 2 h)}) / (1 - e^{-2 k h})`: for `-h <= z <= 0` both
/// exponents are `<= 0`, so nothing overflows however deep the water (the hyperbolic
/// form overflows once `k h > 710`), and infinite depth is the limit
/// `e^{-k (z + 2 h)} = 0`. The constant `1 / (1 - e^{-2 k h})` is folded into
/// `amp_u` and `amp_a` here, on the host, with `expm1` (exact in shallow water too).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PackedComponent {
    /// `k cos b`, rad/m.
    pub kx: f64,
    /// `k sin b`, rad/m.
    pub ky: f64,
    /// Wave number `k`, rad/m.
    pub k: f64,
    /// Angular frequency `w`, rad/s.
    pub omega: f64,
    /// Phase at the reference time, `(phi - w t_ref) mod 2 pi`, rad.
    pub phase_ref: f64,
    /// Amplitude `A`, m.
    pub amp: f64,
    /// `A w / (1 - e^{-2 k h})`, m/s.
    pub amp_u: f64,
    /// `A w^2 / (1 - e^{-2 k h})`, m/s^2.
    pub amp_a: f64,
    /// `cos b`.
    pub cos_b: f64,
    /// `sin b`.
    pub sin_b: f64,
    /// The decay cut's bounds on this component and all after it (sorted by `k`),
    /// over their limits ([`super::cut::decay_cut_bounds`]): the part independent of
    /// the node's speed.
    pub cut0: f64,
    /// The decay cut's factor of the node's speed, s/m.
    pub cut1: f64,
    /// The decay cut's factor of the ramp's rate, s.
    pub cut2: f64,
}

impl Default for PackedComponent {
    /// All zero but the cut's bounds, which are infinite (nothing is cut until
    /// [`super::cut::decay_cut_bounds`] sets them).
    fn default() -> Self {
        Self {
            kx: 0.0,
            ky: 0.0,
            k: 0.0,
            omega: 0.0,
            phase_ref: 0.0,
            amp: 0.0,
            amp_u: 0.0,
            amp_a: 0.0,
            cos_b: 0.0,
            sin_b: 0.0,
            cut0: f64::INFINITY,
            cut1: f64::INFINITY,
            cut2: f64::INFINITY,
        }
    }
}

/// A sea state ready for evaluation: components packed, phases referred to `t_ref`.
///
/// Phases are stored relative to a reference time so that the phase `w (t - t_ref)`
/// stays small: in f32 on the GPU, `w t` at `t` = 3 hours would carry 1e-3 rad of
/// rounding. The host moves `t_ref` forward ([`WaveField::rebase`]) as time goes on.
#[derive(Clone, Debug, PartialEq)]
pub struct WaveField {
    /// The components.
    pub comps: Vec<PackedComponent>,
    /// Water depth `h`, m (`f64::INFINITY` for deep water).
    pub depth: f64,
    /// How the profile is evaluated above the mean level.
    pub stretching: Stretching,
    /// Start-up ramp duration `T_r`, s (0: none).
    pub ramp_duration: f64,
    /// Reference time of the packed phases, s.
    pub t_ref: f64,
    /// The components as given (for rebasing).
    source: Vec<WaveComponent>,
    /// The cache tolerance the decay cut's bounds are for.
    tolerance: f64,
    /// `comps` as columns, what the CPU's sum reads.
    cols: ComponentColumns,
}

impl WaveField {
    /// Packs `sea` with phases referred to `t_ref = 0`.
    pub fn new(sea: &SeaState) -> Self {
        let mut f = Self {
            comps: Vec::new(),
            cols: ComponentColumns::default(),
            depth: sea.depth,
            stretching: sea.stretching,
            ramp_duration: sea.ramp_duration,
            t_ref: 0.0,
            source: sea.components.clone(),
            tolerance: sea.cache_tolerance,
        };
        f.rebase(0.0);
        f
    }

    /// Refers the packed phases to `t_ref` (does not change any result beyond
    /// round-off). The packed components are sorted by wave number, ascending (the
    /// order both the CPU and the GPU sum in: the decay cut of [`super::cut`] drops a
    /// suffix of the shortest waves).
    pub fn rebase(&mut self, t_ref: f64) {
        self.t_ref = t_ref;
        let h = self.depth;
        self.comps = self
            .source
            .iter()
            .map(|c| {
                // 1 - e^{-2 k h}, exact for small k h; 1 in deep water.
                let den = -(-2.0 * c.k * h).exp_m1();
                let (sin_b, cos_b) = c.direction.sin_cos();
                PackedComponent {
                    kx: c.k * cos_b,
                    ky: c.k * sin_b,
                    k: c.k,
                    omega: c.omega,
                    phase_ref: (c.phase - c.omega * t_ref).rem_euclid(TAU),
                    amp: c.amplitude,
                    amp_u: c.amplitude * c.omega / den,
                    amp_a: c.amplitude * c.omega * c.omega / den,
                    cos_b,
                    sin_b,
                    ..Default::default()
                }
            })
            .collect();
        // Stable: equal wave numbers keep the sea's order.
        self.comps.sort_by(|a, b| a.k.total_cmp(&b.k));
        decay_cut_bounds(&mut self.comps, self.tolerance);
        self.cols = ComponentColumns::new(&self.comps);
    }

    /// Elevation `eta` at `(x, y)` and time `t`, ramp included, m.
    pub fn elevation(&self, x: f64, y: f64, t: f64) -> f64 {
        wave_ramp(t, self.ramp_duration) * wave_elevation_sum(&self.comps, x, y, t - self.t_ref)
    }

    /// Elevation, velocity and acceleration at `p` and time `t`, ramp included.
    pub fn kinematics(&self, p: [f64; 3], t: f64) -> Kinematics {
        self.kinematics_with(p, t, &mut KinematicsScratch::default())
    }

    /// [`Self::kinematics`] with working columns `scratch` (for loops over many
    /// points: allocated once).
    pub fn kinematics_with(
        &self,
        p: [f64; 3],
        t: f64,
        scratch: &mut KinematicsScratch,
    ) -> Kinematics {
        wave_kinematics_columns(
            &self.cols,
            self.depth,
            self.stretching,
            wave_ramp(t, self.ramp_duration),
            p,
            t - self.t_ref,
            scratch,
        )
    }

    /// The values of [`Self::kinematics_with`] and their rates along a path through `p`
    /// with velocity `v`, m/s (see [`wave_kinematics_rates_tau`]): `(values, rates)`.
    pub fn kinematics_rates_with(
        &self,
        p: [f64; 3],
        v: [f64; 3],
        t: f64,
        scratch: &mut KinematicsScratch,
    ) -> (Kinematics, Kinematics) {
        wave_kinematics_rates_columns(
            &self.cols,
            self.depth,
            self.stretching,
            wave_ramp(t, self.ramp_duration),
            wave_ramp_rate(t, self.ramp_duration),
            p,
            v,
            t - self.t_ref,
            scratch,
        )
    }
}

/// The start-up ramp `0.5 (1 - cos(pi t / T_r))` for `0 <= t < T_r`, 0 before, 1
/// after (and always 1 when `T_r <= 0`), computed as `sin^2(pi t / (2 T_r))`.
pub fn wave_ramp(t: f64, ramp_duration: f64) -> f64 {
    if ramp_duration <= 0.0 || t >= ramp_duration {
        1.0
    } else if t <= 0.0 {
        0.0
    } else {
        // 0.5 (1 - cos x) = sin^2(x / 2), without the cancellation near t = 0.
        (0.5 * PI * t / ramp_duration).sin().powi(2)
    }
}

/// The time derivative of [`wave_ramp`]: `(pi / (2 T_r)) sin(pi t / T_r)` on
/// `0 < t < T_r`, 0 elsewhere (and 0 when `T_r <= 0`).
pub fn wave_ramp_rate(t: f64, ramp_duration: f64) -> f64 {
    if ramp_duration <= 0.0 || t <= 0.0 || t >= ramp_duration {
        0.0
    } else {
        0.5 * PI / ramp_duration * (PI * t / ramp_duration).sin()
    }
}

/// Phase `theta` of a packed component at `(x, y)`, `tau = t - t_ref` after its
/// reference time.
#[inline]
pub fn wave_theta(c: &PackedComponent, x: f64, y: f64, tau: f64) -> f64 {
    c.kx * x + c.ky * y + c.phase_ref - c.omega * tau
}

/// `sum A cos(theta)`, no ramp.
pub fn wave_elevation_sum(comps: &[PackedComponent], x: f64, y: f64, tau: f64) -> f64 {
    comps
        .iter()
        .map(|c| c.amp * poly::sin_cos(wave_theta(c, x, y, tau)).1)
        .sum()
}

/// The depth at which the linear profile is evaluated for a point at height `z` under
/// the elevation `eta`, in `[-h, 0]`.
///
/// Wheeler: `z_s = h (z - eta) / (h + eta)` maps the water column `[-h, eta]` onto
/// `[-h, 0]`, so the surface gets the mean-level value; written `(z - eta) / (1 + eta /
/// h)` it is also right for infinite depth. Constant: the profile at `z` below the
/// mean level and held at its `z = 0` value above. Either way a point above the
/// surface (in air) gets the surface value (its water loads are scaled by its wetted
/// fraction, which is 0 there), and a point below the seabed the seabed value.
pub fn wave_eval_depth(z: f64, eta: f64, depth: f64, stretching: Stretching) -> f64 {
    let zs = match stretching {
        Stretching::Wheeler => (z - eta) / (1.0 + eta / depth),
        Stretching::Constant => z,
    };
    zs.min(0.0).max(-depth)
}

/// The numerators of the depth decay at evaluation depth `zs` (`-h <= zs <= 0`):
/// `(e^{k zs} + e^{-k (zs + 2 h)}, e^{k zs} - e^{-k (zs + 2 h)})`, i.e.
/// `(cosh, sinh)(k (zs + h)) / sinh(k h)` times `1 - e^{-2 k h}`.
///
/// The seabed's term `e^{-k (zs + 2 h)}` is left out where `2 k (zs + h) > 39`, as in
/// [`wave_kinematics_columns`] and the WGSL twin: it is then under `1.2e-17` of
/// `e^{k zs}`, below half an ulp, so the sums are the same bits without it.
#[inline]
pub fn wave_depth_decay(k: f64, zs: f64, depth: f64) -> (f64, f64) {
    let e1 = poly::exp_neg(k * zs);
    let e2 = if 2.0 * k * (zs + depth) > 39.0 {
        0.0
    } else {
        poly::exp_neg(-k * (zs + 2.0 * depth))
    };
    (e1 + e2, e1 - e2)
}

/// Elevation, velocity and acceleration of the sum of `comps` at `p` and time `t`
/// (phases referred to `t_ref`), with the ramp of duration `ramp_duration`.
///
/// The same sums as the WGSL twin, arranged for the CPU in [`wave_kinematics_columns`]
/// (this packs the components into columns first; [`WaveField::kinematics`] keeps
/// them packed).
pub fn wave_kinematics_at(
    comps: &[PackedComponent],
    depth: f64,
    stretching: Stretching,
    ramp_duration: f64,
    p: [f64; 3],
    t: f64,
    t_ref: f64,
) -> Kinematics {
    wave_kinematics_tau(
        comps,
        depth,
        stretching,
        wave_ramp(t, ramp_duration),
        p,
        t - t_ref,
    )
}

/// [`wave_kinematics_at`] at `tau = t - t_ref` after the reference time, with the
/// ramp factor `r` given (the GPU solver forms both on the host in f64).
pub fn wave_kinematics_tau(
    comps: &[PackedComponent],
    depth: f64,
    stretching: Stretching,
    r: f64,
    p: [f64; 3],
    tau: f64,
) -> Kinematics {
    let cols = ComponentColumns::new(comps);
    let mut scratch = KinematicsScratch::default();
    wave_kinematics_columns(&cols, depth, stretching, r, p, tau, &mut scratch)
}

/// The time derivative of the evaluation depth [`wave_eval_depth`] along a path with
/// vertical velocity `vz` under an elevation changing at `eta_rate` (both along the
/// path): Wheeler `(vz - eta_rate (1 + zs / h)) / (1 + eta / h)`, constant `vz`, and 0
/// where the clamp to `[-h, 0]` holds the depth (a point in air or under the seabed).
pub fn wave_eval_depth_rate(
    z: f64,
    eta: f64,
    depth: f64,
    stretching: Stretching,
    vz: f64,
    eta_rate: f64,
) -> f64 {
    let (zs, rate) = match stretching {
        Stretching::Wheeler => {
            let d = 1.0 + eta / depth;
            let zs = (z - eta) / d;
            (zs, (vz - eta_rate * (1.0 + zs / depth)) / d)
        }
        Stretching::Constant => (z, vz),
    };
    if zs > 0.0 || zs < -depth {
        0.0
    } else {
        rate
    }
}

/// [`wave_kinematics_tau`] and the rates of the same values along a path through `p`
/// with velocity `v` (m/s): `d/dt` of `eta`, `u` and `a` seen by a point moving at `v`,
/// with the ramp factor `r` and its rate `r_rate` ([`wave_ramp_rate`]) given. Returns
/// `(values, rates)`; the rates as a [`Kinematics`] (`eta` rate, m/s; `u` rate, m/s^2;
/// `a` rate, m/s^3).
///
/// One component at a time, the reference (and the WGSL twin's arrangement): with
/// `theta' = kx vx + ky vy - w` (the Doppler-shifted frequency) and `zs'` from
/// [`wave_eval_depth_rate`], `d/dt [ch cos] = k sh zs' cos - ch sin theta'` and the like
/// (`d ch / dzs = k sh`, `d sh / dzs = k ch`). Each rate sum is times `r`, plus `r_rate`
/// times the unramped value sum. A component whose decay `e^{k zs}` is under `1e-30`
/// contributes 0 to the velocity and acceleration and their rates, as in
/// [`wave_kinematics_columns`]. The decay pass sums only the prefix of `comps` that
/// [`wave_decay_prefix`] keeps (the decay cut of [`super::cut`]: `comps` sorted by
/// `k`, with their cut bounds set; with the default infinite bounds nothing is cut),
/// so the values' `u` and `a` are those of [`wave_kinematics_tau`] within the cut's
/// bound.
#[allow(clippy::too_many_arguments)]
pub fn wave_kinematics_rates_tau(
    comps: &[PackedComponent],
    depth: f64,
    stretching: Stretching,
    r: f64,
    r_rate: f64,
    p: [f64; 3],
    v: [f64; 3],
    tau: f64,
) -> (Kinematics, Kinematics) {
    let (mut se, mut se_rate) = (0.0, 0.0);
    for c in comps {
        let (s, co) = poly::sin_cos(wave_theta(c, p[0], p[1], tau));
        let theta_rate = c.kx * v[0] + c.ky * v[1] - c.omega;
        se += c.amp * co;
        se_rate -= c.amp * s * theta_rate;
    }
    let eta = r * se;
    let eta_rate = r * se_rate + r_rate * se;
    let zs = wave_eval_depth(p[2], eta, depth, stretching);
    let zs_rate = wave_eval_depth_rate(p[2], eta, depth, stretching, v[2], eta_rate);
    // The decay cut: the components the node needs (sorted by k, a prefix).
    let speed = v[0].hypot(v[1]) + zs_rate.abs();
    let m = wave_decay_prefix(comps, zs, speed, r_rate);
    // Unramped sums: u, a (a_z without its sign) and their rates.
    let (mut u, mut a, mut du, mut da) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
    for c in &comps[..m] {
        let (ch, sh) = wave_depth_decay(c.k, zs, depth);
        if poly::exp_neg(c.k * zs) < 1e-30 {
            continue;
        }
        let (s, co) = poly::sin_cos(wave_theta(c, p[0], p[1], tau));
        let theta_rate = c.kx * v[0] + c.ky * v[1] - c.omega;
        let kz = c.k * zs_rate;
        let (cc, ss, cs, sc) = (ch * co, sh * s, ch * s, sh * co);
        let (uh, uh_rate) = (c.amp_u * cc, c.amp_u * (kz * sc - cs * theta_rate));
        let (ah, ah_rate) = (c.amp_a * cs, c.amp_a * (kz * ss + cc * theta_rate));
        u[0] += uh * c.cos_b;
        u[1] += uh * c.sin_b;
        u[2] += c.amp_u * ss;
        a[0] += ah * c.cos_b;
        a[1] += ah * c.sin_b;
        a[2] += c.amp_a * sc;
        du[0] += uh_rate * c.cos_b;
        du[1] += uh_rate * c.sin_b;
        du[2] += c.amp_u * (kz * cs + sc * theta_rate);
        da[0] += ah_rate * c.cos_b;
        da[1] += ah_rate * c.sin_b;
        da[2] += c.amp_a * (kz * cc - ss * theta_rate);
    }
    a[2] = -a[2];
    da[2] = -da[2];
    let values = Kinematics {
        eta,
        u: u.map(|x| r * x),
        a: a.map(|x| r * x),
    };
    let rate = |x: [f64; 3], dx: [f64; 3]| [0, 1, 2].map(|d| r * dx[d] + r_rate * x[d]);
    let rates = Kinematics {
        eta: eta_rate,
        u: rate(u, du),
        a: rate(a, da),
    };
    (values, rates)
}
