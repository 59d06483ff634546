//! `src/study/channels.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::error::Error;
use cablesim::study::channels::*;
use std::path::Path;

fn model() -> ModelChannels {
    ModelChannels {
        cables: vec![
            CableChannels {
                name: "a.1".into(),
                line_type: "chain".into(),
                elements: 3,
            },
            CableChannels {
                name: "b".into(),
                line_type: "rope".into(),
                elements: 2,
            },
        ],
        bodies: vec!["ship".into()],
        ..Default::default()
    }
}

fn names(entries: &[&str]) -> Result<Vec<String>, Error> {
    let e: Vec<String> = entries.iter().map(|s| s.to_string()).collect();
    resolve(Path::new("s.toml"), "study.channels", &e, &model())
        .map(|v| v.iter().map(Channel::name).collect())
}

#[test]
fn default_and_requests_expand_in_order_once() {
    assert_eq!(
        names(&[
            "default",
            "a.1.tension_max",
            "b.tension[*]",
            "ship.fz",
            "a.1.tension[2]"
        ])
        .unwrap(),
        [
            "a.1.tension_max",
            "b.tension_max",
            "a.1.start_force",
            "b.start_force",
            "a.1.end_force",
            "b.end_force",
            "b.tension[0]",
            "b.tension[1]",
            "ship.fz",
            "a.1.tension[2]",
        ]
    );
    let r = resolve(
        Path::new("s.toml"),
        "study.channels",
        &["a.1.end_force".to_string()],
        &model(),
    )
    .unwrap();
    assert_eq!(r[0].line_type.as_deref(), Some("chain"));
}

#[test]
fn unknown_channels_are_errors_naming_the_entry() {
    let msg = |e: &[&str]| names(e).unwrap_err().to_string();
    let m = msg(&["default", "c.tension_max"]);
    assert!(m.starts_with("s.toml: study.channels[1]: "), "{m}");
    assert!(m.contains("no cable named \"c\""), "{m}");
    let m = msg(&["b.tenson_max"]);
    assert!(m.contains("unknown quantity \"tenson_max\""), "{m}");
    let m = msg(&["b.tension[2]"]);
    assert!(m.contains("has 2 elements"), "{m}");
    let m = msg(&["ship.tension_max"]);
    assert!(m.contains("it is a body"), "{m}");
    let m = msg(&["b.fx"]);
    assert!(m.contains("no body named \"b\""), "{m}");
    let m = msg(&["tension_max"]);
    assert!(m.contains("OWNER.QUANTITY"), "{m}");
    let m = msg(&["b.tension[x]"]);
    assert!(m.contains("an index from 0"), "{m}");
}
