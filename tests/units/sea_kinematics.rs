//! `src/sea/kinematics.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::dispersion::wave_number;
use cablesim::sea::kinematics::*;
use cablesim::sea::{SeaState, Stretching, WaveComponent};
use std::f64::consts::{PI, TAU};

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
