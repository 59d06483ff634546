//! `src/study/run/sea_check.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::study_run_sea_check::study_field;

#[test]
fn member_fields_map_to_the_study_fields_of_their_sea_state() {
    let f = |s: &str| study_field(2, s);
    assert_eq!(
        f("environment.waves.trains[0].hs").unwrap(),
        "study.sea_states[2].hs"
    );
    assert_eq!(
        f("environment.waves.trains[0].tp").unwrap(),
        "study.sea_states[2].tp"
    );
    assert_eq!(
        f("environment.waves.trains[0].direction").unwrap(),
        "study.sea_states[2].heading"
    );
    assert_eq!(
        f("environment.waves.trains[0]").unwrap(),
        "study.sea_states[2]"
    );
    assert_eq!(
        f("environment.current").unwrap(),
        "study.sea_states[2].current_speed"
    );
    assert_eq!(f("environment.waves.seed").unwrap(), "study.sea_states[2]");
    assert_eq!(f("cables[0].length"), None);
    assert_eq!(f("environment.depth"), None);
}
