//! `src/ale/winch.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::ale::PayoutSchedule;
use cablesim::testing::ale_winch::*;
use std::sync::Arc;

#[test]
fn tracker_keeps_the_variable_element_in_band() {
    let w = Winch {
        cable: 0,
        end: WinchEnd::Start,
        schedule: Arc::new(PayoutSchedule::constant(1.0).unwrap()),
        drum_length: 100.0,
        element_length: 2.0,
    };
    let mut tr = WinchTracker::new(&w, &[2.0; 5], 0.0);
    for k in 1..=500 {
        let dl = 0.1 * k as f64;
        tr.remesh(dl).unwrap();
        let l = tr.variable_l0(dl);
        assert!((1.0..=3.0).contains(&l), "{l}");
        let total: f64 = tr.fixed.iter().sum::<f64>() + l;
        assert!((total - tr.deployed(dl)).abs() < 1e-9);
    }
    assert!(matches!(tr.remesh(95.0), Err(WinchLimit::Drum { .. })));
}
