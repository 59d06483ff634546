//! `src/model/route.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::model_route::*;

#[test]
fn circle_velocity_and_acceleration_are_derivatives() {
    let r = Route::Circle {
        center: [1.0, 2.0, -3.0],
        radius: 20.0,
        period: 62.8,
        axis: [0.0, 0.0, -1.0],
        phase: 0.3,
        advance: 62.8,
    };
    let h = 1e-4;
    for &t in &[0.0, 7.0, 100.0] {
        let (a, b, c) = (r.eval(t - h), r.eval(t), r.eval(t + h));
        for k in 0..3 {
            let v = (c.r[k] - a.r[k]) / (2.0 * h);
            let acc = (c.r[k] - 2.0 * b.r[k] + a.r[k]) / (h * h);
            assert!((v - b.v[k]).abs() < 1e-6, "v {k}: {v} vs {}", b.v[k]);
            assert!((acc - b.a[k]).abs() < 1e-3, "a {k}: {acc} vs {}", b.a[k]);
        }
        // Distance from the (advancing) axis is the radius.
    }
    let s = r.eval(0.0);
    let d = ((s.r[0] - 1.0).powi(2) + (s.r[1] - 2.0).powi(2)).sqrt();
    assert!((d - 20.0).abs() < 1e-12);
    // One revolution advances 62.8 m along -z.
    let s1 = r.eval(62.8);
    assert!((s1.r[2] - (s.r[2] - 62.8)).abs() < 1e-9);
}

#[test]
fn table_interpolates_and_holds() {
    let r = Route::Table {
        t: vec![0.0, 10.0],
        p: vec![[0.0, 0.0, 0.0], [10.0, 0.0, -5.0]],
    };
    let s = r.eval(5.0);
    assert_eq!(s.r, [5.0, 0.0, -2.5]);
    assert_eq!(s.v, [1.0, 0.0, -0.5]);
    assert_eq!(r.eval(20.0).r, [10.0, 0.0, -5.0]);
    assert_eq!(r.eval(20.0).v, [0.0; 3]);
    assert_eq!(r.eval(-1.0).r, [0.0; 3]);
}
