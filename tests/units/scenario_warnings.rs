//! `src/scenario/warnings.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::scenario_warnings::*;

#[test]
fn collected_warnings_are_kept_in_order_and_nested_calls_keep_their_own() {
    let (((), inner), outer) = collect_warnings(|| {
        warn("a".into());
        let inner = collect_warnings(|| warn("b".into()));
        warn("c".into());
        inner
    });
    assert_eq!(inner, vec!["b".to_string()]);
    assert_eq!(outer, vec!["a".to_string(), "c".to_string()]);
    // Outside, nothing is collected any more.
    assert!(SINK.with(|s| s.borrow().is_none()));
}
