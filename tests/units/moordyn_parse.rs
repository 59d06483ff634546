//! `src/moordyn/parse.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::moordyn::parse::*;

#[test]
fn header_phrases_pick_their_sections() {
    assert_eq!(kind_of("---- LINE TYPES ----"), Kind::LineTypes);
    assert_eq!(kind_of("---- LINE DICTIONARY ----"), Kind::LineTypes);
    assert_eq!(kind_of("---- LINE PROPERTIES ----"), Kind::Lines);
    assert_eq!(kind_of("---- Lines ----"), Kind::Lines);
    assert_eq!(kind_of("--- CONNECTION PROPERTIES ---"), Kind::Points);
    assert_eq!(kind_of("--- NODE PROPERTIES ---"), Kind::Points);
    assert_eq!(kind_of("--- ROD TYPES ---"), Kind::Other("ROD TYPES"));
    assert_eq!(kind_of("--- RODS ---"), Kind::Other("RODS"));
    assert_eq!(kind_of("---- SOLVER OPTIONS ----"), Kind::Options);
    assert_eq!(kind_of("---- OUTPUTS ----"), Kind::Outputs);
    assert_eq!(kind_of("---- MoorDyn Input File ----"), Kind::Unknown);
    assert_eq!(kind_of("---- need this line ----"), Kind::Unknown);
}

#[test]
fn comments_and_blank_rows_are_skipped() {
    assert_eq!(fields("  1  Fixed  0 # anchor"), vec!["1", "Fixed", "0"]);
    assert!(fields("   # only a note").is_empty());
}
