//! `src/ale/schedule.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::ale_schedule::*;

#[test]
fn rates_integrate_exactly() {
    let s = PayoutSchedule::rates(&[(0.0, 0.0), (10.0, 1.0), (20.0, 1.0), (20.0, -1.0)]).unwrap();
    let p = s.eval(5.0);
    assert!((p.dl - 1.25).abs() < 1e-12 && (p.rate - 0.5).abs() < 1e-12);
    assert!((p.accel - 0.1).abs() < 1e-12);
    let p = s.eval(15.0);
    assert!((p.dl - 10.0).abs() < 1e-12 && p.rate == 1.0 && p.accel == 0.0);
    let p = s.eval(25.0);
    assert!((p.dl - 10.0).abs() < 1e-12 && p.rate == -1.0, "{p:?}");
    // Derivatives agree with finite differences.
    for &t in &[3.0, 12.0, 30.0] {
        let h = 1e-5;
        let fd = (s.eval(t + h).dl - s.eval(t - h).dl) / (2.0 * h);
        assert!((fd - s.eval(t).rate).abs() < 1e-8);
    }
    assert_eq!(
        PayoutSchedule::rates(&[(0.0, 0.0)]).unwrap().eval(7.0).dl,
        0.0
    );
}

#[test]
fn table_interpolates_and_holds() {
    let s = PayoutSchedule::table(&[(0.0, 10.0), (10.0, 20.0), (20.0, 15.0)]).unwrap();
    assert_eq!(s.table_length_at_zero(), Some(10.0));
    let p = s.eval(5.0);
    assert_eq!((p.dl, p.rate), (5.0, 1.0));
    assert_eq!(s.eval(15.0).rate, -0.5);
    assert_eq!(s.eval(30.0).dl, 5.0);
    assert_eq!(s.eval(30.0).rate, 0.0);
}
