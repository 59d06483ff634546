//! `src/scenario/numbers.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::scenario_numbers::*;
use std::path::Path;

#[test]
fn numbers_in_messages_are_short() {
    assert_eq!(show(9.81), "9.81");
    assert_eq!(show(-1e160), "-1e160");
    assert_eq!(show(2.5e-200), "2.5e-200");
    assert_eq!(show(0.0), "0");
    let e = non_negative(Path::new("m.toml"), "environment.gravity", -1e160).unwrap_err();
    let text = e.to_string();
    assert!(text.ends_with("must not be negative, got -1e160"), "{text}");
}
