//! `src/body/rao.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::body::kinematics::Dofs;
use cablesim::body::rao::*;
use cablesim::sea::WaveComponent;
use std::f64::consts::PI;

fn table() -> RaoTable {
    // Two frequencies, four headings; heave amplitude and phase vary with both.
    let omega = vec![0.5, 1.0];
    let heading: Vec<f64> = [0.0f64, 90.0, 180.0, 270.0]
        .iter()
        .map(|d| d.to_radians())
        .collect();
    let mut values = Vec::new();
    for i in 0..2 {
        for j in 0..4 {
            let mut r = [(0.0, 0.0); 6];
            r[2] = (
                1.0 - 0.4 * i as f64 + 0.1 * j as f64,
                (10.0 * j as f64 + 170.0 * i as f64).to_radians(),
            );
            values.push(r);
        }
    }
    RaoTable::new(omega, heading, values)
}

#[test]
fn grid_points_are_exact_and_between_them_linear() {
    let t = table();
    let (a, p) = t.at(1.0, 90f64.to_radians())[2];
    assert!((a - 0.7).abs() < 1e-15 && (p - 180f64.to_radians()).abs() < 1e-12);
    // Halfway in frequency at heading 0: amplitude 0.8, phase 85 deg.
    let (a, p) = t.at(0.75, 0.0)[2];
    assert!((a - 0.8).abs() < 1e-15 && (p - 85f64.to_radians()).abs() < 1e-12);
    // Across the wrap: 315 deg is halfway between 270 (0.3 + 1) and 360 (= 0).
    let (a, _) = t.at(0.5, 315f64.to_radians())[2];
    assert!((a - 1.15).abs() < 1e-12);
    // -45 deg is the same heading.
    assert_eq!(
        t.at(0.5, -45f64.to_radians()),
        t.at(0.5, 315f64.to_radians())
    );
    // Held outside the frequency range.
    assert_eq!(t.at(0.1, 0.3), t.at(0.5, 0.3));
    assert_eq!(t.at(9.0, 0.3), t.at(1.0, 0.3));
}

#[test]
fn phases_take_the_shorter_arc() {
    let r = |p: f64| {
        let mut x = [(1.0, 0.0); 6];
        x[0].1 = p.to_radians();
        x
    };
    let t = RaoTable::new(vec![1.0, 2.0], vec![0.0], vec![r(170.0), r(-170.0)]);
    let p = t.at(1.5, 0.0)[0].1;
    assert!((wrap_pi(p) - PI).abs() < 1e-12, "{p}");
}

#[test]
fn motion_leads_the_elevation_by_its_phase() {
    // One component, heave RAO 0.8 m/m with a 30 deg lead: heave peaks 30 deg of
    // the period before the crest passes the reference point.
    let mut v = [(0.0, 0.0); 6];
    v[2] = (0.8, 30f64.to_radians());
    let rao = RaoTable::new(vec![0.6], vec![0.0], vec![v]);
    let wc = WaveComponent {
        amplitude: 1.5,
        omega: 0.6,
        k: 0.6 * 0.6 / 9.81,
        direction: 0.4,
        phase: 1.1,
    };
    let (x, y) = (30.0, -20.0);
    let m = RaoMotion::new(&rao, &[wc], x, y, 0.0, 0.0);
    // The crest passes (x, y) when theta = 0 (mod 2 pi).
    let t_crest = wc.theta(x, y, 0.0) / wc.omega;
    let t_peak = t_crest - 30f64.to_radians() / wc.omega;
    let d = m.eval_exact(t_peak);
    assert!((d.q[2] - 1.2).abs() < 1e-12, "{}", d.q[2]);
    assert!(d.qd[2].abs() < 1e-12);
    assert!((d.qdd[2] + 1.2 * 0.36).abs() < 1e-12);
    // Interpolated between knots: within the tolerance of the amplitude (one
    // component: the error of the acceleration is at most `(w dt_b)^4 / 384` of
    // its amplitude, the rule's tolerance, and so are the others').
    let d = m.eval(t_peak);
    let tol = RAO_KNOT_TOLERANCE * 1.2;
    assert!((d.q[2] - 1.2).abs() < tol, "{}", d.q[2]);
    assert!(d.qd[2].abs() < tol * 0.6);
    assert!((d.qdd[2] + 1.2 * 0.36).abs() < tol * 0.36);
    // One component: `w dt_b = (384 eps)^(1/4)`.
    let wdt = wc.omega * m.knot_interval();
    assert!((wdt - (384.0 * RAO_KNOT_TOLERANCE).powf(0.25)).abs() < 1e-12);
}

#[test]
fn knots_are_exact_and_the_interpolant_is_a_function_of_t_alone() {
    let mut v = [(0.0, 0.0); 6];
    v[0] = (0.5, 0.3);
    v[5] = (0.01, -1.0);
    let rao = RaoTable::new(vec![0.4, 1.2], vec![0.0], vec![v, v]);
    let wave = |a: f64, w: f64, p: f64| WaveComponent {
        amplitude: a,
        omega: w,
        k: w * w / 9.81,
        direction: 0.0,
        phase: p,
    };
    let waves = [
        wave(1.0, 0.5, 0.1),
        wave(0.3, 0.9, 2.0),
        wave(0.1, 1.1, 4.0),
    ];
    let m = RaoMotion::new(&rao, &waves, 5.0, 1.0, 0.0, 0.0);
    let dt = m.knot_interval();
    assert!(dt.is_finite() && dt > 0.0);
    // At a knot, the exact sum.
    assert_eq!(m.eval(7.0 * dt), m.eval_exact(7.0 * dt));
    // Asked in another order, or by a clone with an empty cache: the same bits.
    let ts: Vec<f64> = (0..200).map(|i| 0.37 * i as f64).collect();
    let fwd: Vec<Dofs> = ts.iter().map(|&t| m.eval(t)).collect();
    let other = m.clone();
    for (i, &t) in ts.iter().enumerate().rev() {
        assert_eq!(other.eval(t), fwd[i]);
    }
}

#[test]
fn ramp_derivatives_are_consistent() {
    let mut v = [(0.0, 0.0); 6];
    v[4] = (0.02, 0.5);
    let rao = RaoTable::new(vec![0.8], vec![0.0], vec![v]);
    let wc = WaveComponent {
        amplitude: 2.0,
        omega: 0.8,
        k: 0.8 * 0.8 / 9.81,
        direction: 0.0,
        phase: 0.2,
    };
    let m = RaoMotion::new(&rao, &[wc], 0.0, 0.0, 0.0, 10.0);
    assert_eq!(m.eval(0.0).q[4], 0.0);
    let h = 1e-4;
    // The exact sum, ramped: the ramp's product rule.
    for &t in &[2.0, 7.5, 12.0] {
        let (a, b, c) = (m.eval_exact(t - h), m.eval_exact(t), m.eval_exact(t + h));
        assert!(((c.q[4] - a.q[4]) / (2.0 * h) - b.qd[4]).abs() < 1e-9);
        assert!(((c.qd[4] - a.qd[4]) / (2.0 * h) - b.qdd[4]).abs() < 1e-9);
    }
    // Between knots the same ramp on the interpolated motion: within the knots'
    // tolerance of the amplitude (0.04 rad; rates and accelerations times w, w^2,
    // plus the ramp's rates on the smaller ones).
    let tol = RAO_KNOT_TOLERANCE * 0.04 * 2.0;
    for i in 0..400 {
        let t = 0.0371 * i as f64;
        let (e, g) = (m.eval_exact(t), m.eval(t));
        assert!((e.q[4] - g.q[4]).abs() < tol, "t {t}");
        assert!((e.qd[4] - g.qd[4]).abs() < tol * 0.8, "t {t}");
        assert!((e.qdd[4] - g.qdd[4]).abs() < tol * 0.64, "t {t}");
    }
    assert_eq!(m.eval(0.0).q[4], 0.0);
}
