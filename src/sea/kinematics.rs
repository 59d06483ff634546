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
#[inline]
pub fn wave_depth_decay(k: f64, zs: f64, depth: f64) -> (f64, f64) {
    let e1 = poly::exp_neg(k * zs);
    let e2 = poly::exp_neg(-k * (zs + 2.0 * depth));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sea::dispersion::wave_number;

    const G: f64 = 9.81;

    fn comp(amplitude: f64, period: f64, depth: f64, direction: f64, phase: f64) -> WaveComponent {
        let omega = TAU / period;
        WaveComponent {
            amplitude,
            omega,
            k: wave_number(omega, depth, G),
            direction,
            phase,
        }
    }

    fn sea(components: Vec<WaveComponent>, depth: f64, stretching: Stretching) -> SeaState {
        SeaState {
            components,
            depth,
            stretching,
            ramp_duration: 0.0,
            ..SeaState::still(depth)
        }
    }

    /// One component against the textbook closed form with hyperbolic functions, at
    /// points below the mean level in finite depth, and the sum of two components is
    /// the sum of each.
    #[test]
    fn matches_the_closed_form_below_the_mean_level() {
        let h = 60.0;
        let c1 = comp(1.5, 9.0, h, 0.4, 0.7);
        let c2 = comp(0.6, 5.0, h, -1.1, 2.0);
        let both = WaveField::new(&sea(vec![c1, c2], h, Stretching::Constant));
        let closed = |c: &WaveComponent, p: [f64; 3], t: f64| {
            let th = c.theta(p[0], p[1], t);
            let ch = (c.k * (p[2] + h)).cosh() / (c.k * h).sinh();
            let sh = (c.k * (p[2] + h)).sinh() / (c.k * h).sinh();
            let (cb, sb) = (c.direction.cos(), c.direction.sin());
            let uh = c.amplitude * c.omega * ch * th.cos();
            let ah = c.amplitude * c.omega * c.omega * ch * th.sin();
            let w2 = c.omega * c.omega;
            (
                c.amplitude * th.cos(),
                [uh * cb, uh * sb, c.amplitude * c.omega * sh * th.sin()],
                [ah * cb, ah * sb, -c.amplitude * w2 * sh * th.cos()],
            )
        };
        for (i, &p) in [[0.0, 0.0, -1.0], [13.0, -40.0, -20.0], [-7.0, 3.0, -59.0]]
            .iter()
            .enumerate()
        {
            let t = 3.7 * i as f64 + 0.3;
            let k = both.kinematics(p, t);
            let (e1, u1, a1) = closed(&c1, p, t);
            let (e2, u2, a2) = closed(&c2, p, t);
            assert!((k.eta - (e1 + e2)).abs() < 1e-12, "{} {}", k.eta, e1 + e2);
            for d in 0..3 {
                assert!((k.u[d] - (u1[d] + u2[d])).abs() < 1e-12, "u[{d}] at {p:?}");
                assert!((k.a[d] - (a1[d] + a2[d])).abs() < 1e-12, "a[{d}] at {p:?}");
            }
        }
    }

    /// Deep water: the decay is `e^{k z}` and nothing overflows at `k h` of thousands
    /// (where `cosh(k h)` is infinite in f64); finite but very deep water gives the
    /// same as infinite depth.
    #[test]
    fn deep_water_does_not_overflow() {
        let c = comp(2.0, 4.0, 5000.0, 0.0, 0.0);
        assert!(c.k * 5000.0 > 1000.0);
        let deep = WaveField::new(&sea(vec![c], f64::INFINITY, Stretching::Constant));
        let finite = WaveField::new(&sea(vec![c], 5000.0, Stretching::Constant));
        for &z in &[0.0, -3.0, -30.0, -4999.0] {
            let p = [1.0, 2.0, z];
            let (kd, kf) = (deep.kinematics(p, 1.3), finite.kinematics(p, 1.3));
            let th = c.theta(1.0, 2.0, 1.3);
            let decay = (c.k * z).exp();
            let ux = c.amplitude * c.omega * decay * th.cos();
            let uz = c.amplitude * c.omega * decay * th.sin();
            assert!(
                (kd.u[0] - ux).abs() <= 1e-14 * c.amplitude * c.omega,
                "z = {z}"
            );
            assert!(
                (kd.u[2] - uz).abs() <= 1e-14 * c.amplitude * c.omega,
                "z = {z}"
            );
            for d in 0..3 {
                assert!(kf.u[d].is_finite() && kf.a[d].is_finite());
                assert!((kf.u[d] - kd.u[d]).abs() <= 1e-14 * c.amplitude * c.omega);
            }
        }
    }

    /// Wheeler stretching: at the instantaneous surface `z = eta` the kinematics are
    /// the mean-level values of the unstretched profile, above the mean level
    /// (crest) and below it (trough); at the seabed they are the seabed values.
    #[test]
    fn wheeler_gives_the_surface_value_at_the_surface() {
        let h = 30.0;
        let comps = vec![comp(1.2, 8.0, h, 0.3, 0.0), comp(0.5, 6.0, h, 1.0, 1.0)];
        let wheeler = WaveField::new(&sea(comps.clone(), h, Stretching::Wheeler));
        let held = WaveField::new(&sea(comps, h, Stretching::Constant));
        let mut crest = false;
        let mut trough = false;
        for i in 0..40 {
            let (x, y, t) = (3.0 * i as f64, -2.0 * i as f64, 0.7 * i as f64);
            let eta = wheeler.elevation(x, y, t);
            crest |= eta > 0.3;
            trough |= eta < -0.3;
            let at_surface = wheeler.kinematics([x, y, eta], t);
            let mean_level = held.kinematics([x, y, 0.0], t);
            for d in 0..3 {
                assert!((at_surface.u[d] - mean_level.u[d]).abs() < 1e-12);
                assert!((at_surface.a[d] - mean_level.a[d]).abs() < 1e-12);
            }
            let bed_w = wheeler.kinematics([x, y, -h], t);
            let bed = held.kinematics([x, y, -h], t);
            assert!(bed.u[2].abs() < 1e-12, "no flow through the seabed");
            assert!((bed_w.u[0] - bed.u[0]).abs() < 1e-12);
            // Half-way down the stretched column is the unstretched mid-depth value.
            let mid_w = wheeler.kinematics([x, y, (eta - h) / 2.0], t);
            let mid = held.kinematics([x, y, -h / 2.0], t);
            assert!((mid_w.u[0] - mid.u[0]).abs() < 1e-12);
            // In air: the surface value.
            let air = wheeler.kinematics([x, y, eta + 5.0], t);
            assert!((air.u[0] - at_surface.u[0]).abs() < 1e-12);
        }
        assert!(crest && trough, "the test must visit crests and troughs");
    }

    /// The profile held at `z = 0`: above the mean level the value at `z = 0`, below it
    /// the unstretched profile (different from Wheeler's below a crest).
    #[test]
    fn constant_option_holds_the_mean_level_profile() {
        let h = 30.0;
        let c = comp(1.0, 7.0, h, 0.0, 0.0);
        let held = WaveField::new(&sea(vec![c], h, Stretching::Constant));
        let wheeler = WaveField::new(&sea(vec![c], h, Stretching::Wheeler));
        // Under a crest (theta = 0 at x = 0, t = 0).
        let k0 = held.kinematics([0.0, 0.0, 0.0], 0.0);
        let k_up = held.kinematics([0.0, 0.0, 0.8], 0.0);
        assert_eq!(k0.u, k_up.u);
        let below = held.kinematics([0.0, 0.0, -5.0], 0.0);
        let below_w = wheeler.kinematics([0.0, 0.0, -5.0], 0.0);
        assert!(
            below_w.u[0] < below.u[0],
            "Wheeler evaluates lower under a crest"
        );
    }

    /// The ramp: zero at the start, half at `T_r / 2`, full from `T_r` on, and it
    /// scales elevation, velocity and acceleration alike; `T_r = 0` is no ramp.
    #[test]
    fn ramp_scales_everything() {
        assert_eq!(wave_ramp(0.0, 20.0), 0.0);
        assert_eq!(wave_ramp(-1.0, 20.0), 0.0);
        assert!((wave_ramp(10.0, 20.0) - 0.5).abs() < 1e-15);
        assert!((wave_ramp(5.0, 20.0) - 0.5 * (1.0 - (PI / 4.0).cos())).abs() < 1e-15);
        assert_eq!(wave_ramp(20.0, 20.0), 1.0);
        assert_eq!(wave_ramp(0.0, 0.0), 1.0);
        let h = 50.0;
        let c = comp(1.0, 8.0, h, 0.2, 0.4);
        let mut s = sea(vec![c], h, Stretching::Constant);
        let full = WaveField::new(&s);
        s.ramp_duration = 20.0;
        let ramped = WaveField::new(&s);
        let p = [4.0, 1.0, -3.0];
        for &t in &[0.0, 2.0, 7.5, 19.0, 25.0] {
            let (a, b) = (full.kinematics(p, t), ramped.kinematics(p, t));
            let r = wave_ramp(t, 20.0);
            assert!((b.eta - r * a.eta).abs() < 1e-14);
            for d in 0..3 {
                assert!((b.u[d] - r * a.u[d]).abs() < 1e-14);
                assert!((b.a[d] - r * a.a[d]).abs() < 1e-14);
            }
        }
    }

    /// Rebasing the phases to another reference time changes nothing beyond round-off.
    #[test]
    fn rebasing_keeps_the_field() {
        let h = 80.0;
        let comps = vec![comp(1.0, 8.0, h, 0.2, 0.4), comp(0.3, 3.0, h, 2.0, 5.0)];
        let f0 = WaveField::new(&sea(comps, h, Stretching::Wheeler));
        let mut f1 = f0.clone();
        f1.rebase(10_000.0);
        let p = [12.0, -4.0, -2.0];
        let (a, b) = (f0.kinematics(p, 10_003.0), f1.kinematics(p, 10_003.0));
        assert!((a.eta - b.eta).abs() < 1e-10);
        assert!((a.u[0] - b.u[0]).abs() < 1e-10);
    }

    /// The rates of [`wave_kinematics_rates_tau`] against a central finite difference of
    /// the values along a moving path `p(t) = p0 + v t`: Wheeler and constant
    /// stretching, finite and infinite depth, deep down, just under the surface and in
    /// air, at full height and inside the ramp; and its values are those of
    /// [`wave_kinematics_tau`].
    #[test]
    fn rates_match_a_finite_difference_along_the_path() {
        let cases: [(f64, Stretching, f64); 4] = [
            (30.0, Stretching::Wheeler, 0.0),
            (30.0, Stretching::Constant, 0.0),
            (f64::INFINITY, Stretching::Wheeler, 0.0),
            (30.0, Stretching::Wheeler, 20.0),
        ];
        let v = [1.3, -0.7, 0.9];
        for (h, stretching, ramp) in cases {
            let hd = if h.is_finite() { h } else { 200.0 };
            let comps = vec![
                comp(1.2, 9.0, hd, 0.3, 0.1),
                comp(0.6, 5.0, hd, -0.8, 2.0),
                comp(0.25, 3.0, hd, 1.9, 4.0),
            ];
            let mut sea = sea(comps, h, stretching);
            sea.ramp_duration = ramp;
            let f = WaveField::new(&sea);
            let t = if ramp > 0.0 { 5.3 } else { 12.7 };
            let eta0 = f.elevation(4.0, -2.0, t);
            // Deep down, 2 m under the surface, and 3 m in air.
            for z in [-22.0, eta0 - 2.0, eta0 + 3.0] {
                let p0 = [4.0 - v[0] * t, -2.0 - v[1] * t, z - v[2] * t];
                let at = |t: f64| {
                    let p = [0, 1, 2].map(|d| p0[d] + v[d] * t);
                    (p, wave_ramp(t, ramp))
                };
                let (p, r) = at(t);
                let (val, rate) = wave_kinematics_rates_tau(
                    &f.comps,
                    h,
                    stretching,
                    r,
                    wave_ramp_rate(t, ramp),
                    p,
                    v,
                    t,
                );
                let plain = wave_kinematics_tau(&f.comps, h, stretching, r, p, t);
                assert!((val.eta - plain.eta).abs() < 1e-13);
                for d in 0..3 {
                    assert!((val.u[d] - plain.u[d]).abs() < 1e-13);
                    assert!((val.a[d] - plain.a[d]).abs() < 1e-13);
                }
                let dt = 1e-4;
                let ((pp, rp), (pm, rm)) = (at(t + dt), at(t - dt));
                let kp = wave_kinematics_tau(&f.comps, h, stretching, rp, pp, t + dt);
                let km = wave_kinematics_tau(&f.comps, h, stretching, rm, pm, t - dt);
                let fd = |a: f64, b: f64| (a - b) / (2.0 * dt);
                let norm = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
                let what = format!("h {h}, {stretching:?}, ramp {ramp}, z {z:.2}");
                let e = fd(kp.eta, km.eta);
                assert!(
                    (e - rate.eta).abs() <= 1e-7 * rate.eta.abs().max(0.1),
                    "eta rate {} against {e}: {what}",
                    rate.eta
                );
                let (su, sa) = (norm(rate.u), norm(rate.a));
                assert!(su > 1e-3 && sa > 1e-3, "{what}: rates too small to test");
                for d in 0..3 {
                    let (eu, ea) = (fd(kp.u[d], km.u[d]), fd(kp.a[d], km.a[d]));
                    assert!(
                        (eu - rate.u[d]).abs() <= 1e-7 * su,
                        "u[{d}] rate {} against {eu}: {what}",
                        rate.u[d]
                    );
                    assert!(
                        (ea - rate.a[d]).abs() <= 1e-7 * sa,
                        "a[{d}] rate {} against {ea}: {what}",
                        rate.a[d]
                    );
                }
            }
        }
    }

    /// The ramp's rate is the derivative of the ramp (central difference), 0 outside
    /// the ramp and without one.
    #[test]
    fn ramp_rate_is_the_ramps_derivative() {
        let tr = 20.0;
        for &t in &[0.5, 5.0, 10.0, 17.3, 19.9] {
            let h = 1e-5;
            let fd = (wave_ramp(t + h, tr) - wave_ramp(t - h, tr)) / (2.0 * h);
            assert!((wave_ramp_rate(t, tr) - fd).abs() < 1e-9, "t = {t}");
        }
        assert_eq!(wave_ramp_rate(-1.0, tr), 0.0);
        assert_eq!(wave_ramp_rate(25.0, tr), 0.0);
        assert_eq!(wave_ramp_rate(3.0, 0.0), 0.0);
    }
}
