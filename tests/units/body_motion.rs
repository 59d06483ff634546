//! `src/body/motion.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::body::motion::*;

#[test]
fn spline_passes_through_samples_and_is_twice_continuous() {
    let t = [0.0, 0.5, 1.7, 2.0, 3.3, 4.0];
    let y = [1.0, -2.0, 0.5, 0.7, 3.0, -1.0];
    let s = Spline::new(&t, &y);
    for i in 0..t.len() - 1 {
        let (a, _, _) = s.eval_segment(&t, i, t[i]);
        let (b, _, _) = s.eval_segment(&t, i, t[i + 1]);
        assert!((a - y[i]).abs() < 1e-13 && (b - y[i + 1]).abs() < 1e-13);
    }
    for i in 1..t.len() - 1 {
        let l = s.eval_segment(&t, i - 1, t[i]);
        let r = s.eval_segment(&t, i, t[i]);
        assert!((l.1 - r.1).abs() < 1e-12, "slope jumps at {i}");
        assert!((l.2 - r.2).abs() < 1e-12, "curvature jumps at {i}");
    }
    // Natural ends.
    assert_eq!(s.eval_segment(&t, 0, 0.0).2, 0.0);
    assert!(s.eval_segment(&t, 4, 4.0).2.abs() < 1e-13);
}

#[test]
fn spline_converges_at_fourth_order_on_a_smooth_motion() {
    // Interior error of sin(t) sampled every h falls ~16x when h halves.
    let err = |n: usize| {
        let t: Vec<f64> = (0..=n).map(|i| 10.0 * i as f64 / n as f64).collect();
        let y: Vec<f64> = t.iter().map(|x| x.sin()).collect();
        let s = Spline::new(&t, &y);
        let mut e: f64 = 0.0;
        for i in n / 4..3 * n / 4 {
            let x = 0.5 * (t[i] + t[i + 1]);
            e = e.max((s.eval_segment(&t, i, x).0 - x.sin()).abs());
        }
        e
    };
    let (e1, e2) = (err(40), err(80));
    assert!(e1 / e2 > 12.0 && e1 / e2 < 20.0, "{e1} {e2}");
}

#[test]
fn table_holds_outside_and_unwraps_yaw() {
    let rows = [
        [0.0, 0.0, 0.0, 0.0, 0.0, 170.0],
        [1.0, 0.0, 0.0, 0.0, 0.0, -170.0],
        [2.0, 0.0, 0.0, 0.0, 0.0, -150.0],
    ];
    let m = MotionTable::new(vec![0.0, 1.0, 2.0], &rows);
    // -170 follows 170 as 190: the yaw goes on increasing.
    assert!((m.eval(1.0).q[5] - 190f64.to_radians()).abs() < 1e-12);
    assert!(m.eval(0.5).qd[5] > 0.0);
    let after = m.eval(5.0);
    assert_eq!(after.q[0], 2.0);
    assert_eq!(after.qd, [0.0; 6]);
    assert_eq!(m.eval(-1.0).q[5], 170f64.to_radians());
}
