//! The analytic elastic catenary (`cablesim::physics::catenary`): the solution against
//! the equations written out literally, closed forms, the inextensible limit, a sweep of
//! spans and rises, the errors, and the node positions of a cable's initial shape.
//! (Once unit tests in `src/physics/catenary.rs`: here they do not need the library
//! compiled a second time as a test harness.)

use cablesim::physics::catenary::*;

// The catenary example: chain-like line of the project's examples.
const EA: f64 = 6.2832e7;
fn w() -> f64 {
    wet_weight(5.0265, 0.04, 1025.0, 9.81)
}

/// The brief's equations written out literally (independently of the solver's
/// scaled form): residuals of XF and ZF, m.
fn literal_residuals(c: &Catenary) -> [f64; 2] {
    let (hf, vf, l, ea, w) = (c.hf, c.vf, c.length, c.ea, c.w);
    if c.seabed && vf < w * l {
        let lb = l - vf / w;
        let xf = lb + hf / w * (vf / hf).asinh() + hf * l / ea;
        let zf = hf / w * ((1.0 + (vf / hf).powi(2)).sqrt() - 1.0) + vf * vf / (2.0 * ea * w);
        [xf - c.xf, zf - c.zf]
    } else {
        let xf = hf / w * ((vf / hf).asinh() - ((vf - w * l) / hf).asinh()) + hf * l / ea;
        let zf = hf / w
            * ((1.0 + (vf / hf).powi(2)).sqrt() - (1.0 + ((vf - w * l) / hf).powi(2)).sqrt())
            + (vf * l - w * l * l / 2.0) / ea;
        [xf - c.xf, zf - c.zf]
    }
}

fn check_solution(c: &Catenary, tol: f64) {
    // The literal forms lose about eps * T / w to cancellation (very taut lines).
    let r = literal_residuals(c);
    let tol = tol + 64.0 * f64::EPSILON * c.fairlead_tension() / c.w;
    assert!(
        r[0].abs() < tol && r[1].abs() < tol,
        "residuals {r:?} for {c:?}"
    );
    // The profile ends at the fairlead.
    let p = c.position(c.length);
    assert!(
        (p[0] - c.xf).abs() < tol && (p[1] - c.zf).abs() < tol,
        "profile end {p:?} for {c:?}"
    );
    let t = c.fairlead_tension();
    assert!((t * t - (c.hf * c.hf + c.vf * c.vf)).abs() <= 1e-12 * t * t);
    assert!((c.tension(c.length) - t).abs() <= 1e-12 * t);
}

#[test]
fn mooring_line_with_grounded_part() {
    // The catenary example: L = 250 m, anchor 220 m away and 90 m below.
    let c = catenary(220.0, 90.0, 250.0, EA, w(), true).unwrap();
    check_solution(&c, 1e-9);
    assert!(c.grounded_length > 0.0 && c.grounded_length < 250.0);
    assert_eq!(c.va, 0.0);
    assert_eq!(c.ha, c.hf);
    // Vertical fairlead force = weight of the hanging part.
    assert!((c.vf - c.w * (c.length - c.grounded_length)).abs() < 1e-9 * c.vf);
    // Touchdown: the grounded part stretched by HF.
    assert!((c.touchdown - c.grounded_length * (1.0 + c.hf / EA)).abs() < 1e-9);
    // The profile is flat up to touchdown and leaves the seabed tangentially.
    let p = c.position(c.grounded_length);
    assert!(p[1].abs() < 1e-12 && (p[0] - c.touchdown).abs() < 1e-9);
    let q = c.position(c.grounded_length + 1e-3);
    assert!(q[1] > 0.0 && q[1] < 1e-6);
    // The profile has the unstretched-plus-stretch arclength: sum of chords over a
    // fine subdivision equals int (1 + T/EA) ds.
    let n = 20000;
    let (mut arc, mut stretched) = (0.0, 0.0);
    for k in 0..n {
        let (s0, s1) = (
            250.0 * k as f64 / n as f64,
            250.0 * (k + 1) as f64 / n as f64,
        );
        let (a, b) = (c.position(s0), c.position(s1));
        arc += (b[0] - a[0]).hypot(b[1] - a[1]);
        stretched += (s1 - s0) * (1.0 + c.tension(0.5 * (s0 + s1)) / EA);
    }
    assert!((arc - stretched).abs() < 1e-6, "{arc} vs {stretched}");
}

#[test]
fn long_grounded_portion() {
    // 330 m of line over a 300 m span, 50 m deep: most of it on the seabed.
    let c = catenary(300.0, 50.0, 330.0, EA, w(), true).unwrap();
    check_solution(&c, 1e-9);
    assert!(c.grounded_length > 200.0, "{c:?}");
    // Closed-form check of the inextensible limit of the hanging part: with
    // a = HF/w, the hanging part spans zf = a (cosh(x_s/a) - 1).
    let a = c.hf / c.w;
    let hang = c.length - c.grounded_length;
    // Suspended length from the touchdown: s = a sinh(x/a) (inextensible part).
    let xs = a * (hang / a).asinh();
    let z_inext = a * ((xs / a).cosh() - 1.0);
    assert!((z_inext - 50.0).abs() < 0.05, "{z_inext}");
}

#[test]
fn fully_suspended_symmetric() {
    // Both ends at the same height, no seabed: VF = VA in magnitude = wL/2.
    let c = catenary(80.0, 0.0, 100.0, EA, w(), false).unwrap();
    check_solution(&c, 1e-9);
    assert!((c.vf - 0.5 * c.w * c.length).abs() < 1e-9 * c.vf);
    assert!((c.va + 0.5 * c.w * c.length).abs() < 1e-9 * c.vf);
    // The lowest point is at mid-length, the profile is symmetric.
    let mid = c.position(50.0);
    assert!((mid[0] - 40.0).abs() < 1e-9);
    for s in [10.0, 25.0, 40.0] {
        let (p, q) = (c.position(s), c.position(100.0 - s));
        assert!((p[0] + q[0] - 80.0).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9);
    }
    // Sag against the inextensible closed form: L = 2 a sinh(X/(2a)).
    let a = c.hf / c.w;
    let l_inext = 2.0 * a * (40.0 / a).sinh();
    assert!((l_inext - 100.0).abs() < 0.01, "{l_inext}");
}

#[test]
fn inextensible_limit() {
    // Parametrise an inextensible catenary z = a (cosh((x - x0)/a) - cosh(x0/a)):
    // choose a and x0, derive span, rise and length, and recover HF = w a.
    let w = w();
    for &(a, x0, span) in &[
        (50.0f64, -20.0f64, 100.0f64),
        (200.0, 30.0, 150.0),
        (10.0, 5.0, 40.0),
    ] {
        let zf = a * (((span - x0) / a).cosh() - (-x0 / a).cosh());
        let len = a * (((span - x0) / a).sinh() - (-x0 / a).sinh());
        let c = catenary(span, zf, len, 1e15, w, false).unwrap();
        check_solution(&c, 1e-7);
        assert!((c.hf - w * a).abs() < 1e-6 * w * a, "{} vs {}", c.hf, w * a);
        // VF = w a sinh((span - x0)/a).
        let vf = w * a * ((span - x0) / a).sinh();
        assert!((c.vf - vf).abs() < 1e-6 * vf.abs().max(w * a));
        // And EA = infinity itself works for a slack line.
        let c2 = catenary(span, zf, len, f64::INFINITY, w, false).unwrap();
        assert!((c2.hf - w * a).abs() < 1e-9 * w * a);
    }
}

#[test]
fn taut_line_stretches() {
    // Ends 1 % farther apart than the unstretched length.
    let l = 100.0;
    let c = catenary(101.0 * 0.8, 101.0 * 0.6, l, EA, w(), true).unwrap();
    check_solution(&c, 1e-9);
    assert_eq!(c.grounded_length, 0.0);
    assert!(c.va > 0.0);
    // Tension about EA * 1 %.
    let t = c.fairlead_tension();
    assert!((t / (0.01 * EA) - 1.0).abs() < 0.02, "{t}");
}

#[test]
fn nearly_vertical_and_vertical_lines() {
    let w = w();
    // Exactly vertical, taut.
    let c = catenary(0.0, 100.5, 100.0, EA, w, false).unwrap();
    assert_eq!(c.hf, 0.0);
    let p = c.position(100.0);
    assert!(p[0] == 0.0 && (p[1] - 100.5).abs() < 1e-9);
    assert!((c.vf - c.va - w * 100.0).abs() < 1e-9 * c.vf);
    // Nearly vertical: continuous with it.
    let c2 = catenary(1e-6, 100.5, 100.0, EA, w, false).unwrap();
    check_solution(&c2, 1e-9);
    assert!((c2.vf - c.vf).abs() < 1e-6 * c.vf, "{} {}", c2.vf, c.vf);
    // Vertical above a seabed anchor with surplus line: slack on the seabed, the
    // hanging part weighs VF.
    let c3 = catenary(0.0, 60.0, 100.0, EA, w, true).unwrap();
    assert!(c3.is_slack());
    assert!((c3.position(100.0)[1] - 60.0).abs() < 1e-9);
    assert!(c3.grounded_length > 40.0 && c3.grounded_length < 40.01);
    // Small span over the seabed: slack until the grounded part is straight.
    let c4 = catenary(10.0, 60.0, 100.0, EA, w, true).unwrap();
    assert!(c4.is_slack());
    let p = c4.position(100.0);
    assert!((p[0] - 10.0).abs() < 1e-9 && (p[1] - 60.0).abs() < 1e-9);
    // And with the grounded part just taut it is a normal catenary.
    let c5 = catenary(45.0, 60.0, 100.0, EA, w, true).unwrap();
    assert!(!c5.is_slack() && c5.hf > 0.0);
    check_solution(&c5, 1e-9);
    // Folded vertical line (no seabed): ends at the same point.
    let c6 = catenary(0.0, 0.0, 100.0, EA, w, false).unwrap();
    let lowest = c6.position(50.0);
    assert!(lowest[1] < -49.0);
    assert!(c6.position(100.0)[1].abs() < 1e-9);
}

#[test]
fn sweep_converges_everywhere() {
    // A grid of spans and rises, with and without seabed, stiff and soft lines.
    let w = w();
    let l = 100.0;
    let mut max_it = 0;
    for &ea in &[1e4, 1e6, EA, 1e12] {
        for i in 0..=24 {
            for k in 0..=24 {
                let xf = 1.3 * l * i as f64 / 24.0;
                let zf = 1.3 * l * k as f64 / 24.0;
                for seabed in [false, true] {
                    match catenary(xf, zf, l, ea, w, seabed) {
                        Ok(c) => {
                            assert!(c.iterations < 50, "{c:?}");
                            max_it = max_it.max(c.iterations);
                            let tol = 1e-8 * l;
                            if c.hf > 0.0 {
                                check_solution(&c, tol);
                            } else {
                                let p = c.position(l);
                                assert!(
                                    (p[0] - xf).abs() < tol && (p[1] - zf).abs() < tol,
                                    "{p:?} for {c:?}"
                                );
                            }
                        }
                        Err(e) => {
                            // Only "too far apart" may fail.
                            assert!(
                                e.contains("too far apart") && xf.hypot(zf) > l,
                                "xf {xf} zf {zf} ea {ea} seabed {seabed}: {e}"
                            );
                        }
                    }
                }
            }
        }
    }
    eprintln!("most Newton iterations over the sweep: {max_it}");
}

#[test]
fn errors_are_reported() {
    assert!(catenary(10.0, 10.0, 100.0, EA, -1.0, false)
        .unwrap_err()
        .contains("wet weight"));
    assert!(catenary(10.0, 10.0, 100.0, EA, 0.0, false).is_err());
    assert!(catenary(-1.0, 10.0, 100.0, EA, 1.0, false).is_err());
    assert!(catenary(10.0, 10.0, 0.0, EA, 1.0, false).is_err());
    assert!(catenary(10.0, -5.0, 100.0, EA, 1.0, true).is_err());
    assert!(catenary(200.0, 0.0, 100.0, f64::INFINITY, 1.0, false)
        .unwrap_err()
        .contains("inextensible"));
    assert!(catenary(300.0, 0.0, 100.0, 1e3, 1.0, false)
        .unwrap_err()
        .contains("too far apart"));
}

#[test]
fn positions_follow_the_catenary() {
    let w = w();
    let a = [-220.0, 0.0, -100.0];
    let b = [0.0, 0.0, -10.0];
    let pts = catenary_positions(a, b, 250.0, 50, EA, w, -100.0);
    assert_eq!(pts.len(), 51);
    assert_eq!(pts[0], a);
    assert_eq!(pts[50], b);
    // Reversed ends give the same points in reverse order.
    let rev = catenary_positions(b, a, 250.0, 50, EA, w, -100.0);
    for k in 0..=50 {
        for j in 0..3 {
            assert!((pts[k][j] - rev[50 - k][j]).abs() < 1e-9);
        }
    }
    // Grounded nodes lie on the seabed; chords are no longer than L/n stretched.
    let c = catenary(220.0, 90.0, 250.0, EA, w, true).unwrap();
    let tmax = c.fairlead_tension();
    for k in 0..50 {
        let d: f64 = (0..3)
            .map(|j| (pts[k + 1][j] - pts[k][j]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(d <= 5.0 * (1.0 + tmax / EA) + 1e-9);
    }
    assert!(pts[5][2] == -100.0);
    // A rotated plane: the line stays in the vertical plane through its ends.
    let b2 = [0.0, 100.0, -10.0];
    let a2 = [0.0, -120.0, -100.0];
    let p2 = catenary_positions(a2, b2, 250.0, 25, EA, w, -100.0);
    assert!(p2.iter().all(|p| p[0].abs() < 1e-12));
    // Buoyant: straight.
    let s = catenary_positions(a, b, 250.0, 10, EA, -5.0, -100.0);
    assert_eq!(s, straight_positions(a, b, 10));
    // Slack on the seabed: no zero-length element.
    let p3 = catenary_positions(
        [0.0, 0.0, -100.0],
        [0.0, 0.0, -40.0],
        100.0,
        20,
        EA,
        w,
        -100.0,
    );
    for k in 0..20 {
        let d: f64 = (0..3)
            .map(|j| (p3[k + 1][j] - p3[k][j]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(d > 4.0, "element {k} has length {d}");
    }
}
