//! `src/study/sampling.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::study::channel_stats::ChannelStats;
use cablesim::study::channels::ModelChannels;
use cablesim::study::channels::{resolve, CableChannels};
use cablesim::study::sampling::*;
use std::path::Path;

#[test]
fn each_channel_reads_its_own_owner_and_quantity() {
    let model = ModelChannels {
        cables: vec![
            CableChannels {
                name: "a".into(),
                line_type: "chain".into(),
                elements: 3,
            },
            CableChannels {
                name: "b".into(),
                line_type: "chain".into(),
                elements: 2,
            },
        ],
        bodies: vec!["hull".into(), "buoy".into()],
        body_references: vec![[0.0; 3], [10.0, 0.0, -5.0]],
        free_bodies: vec![false, true],
    };
    let entries: Vec<String> = [
        "b.tension_max",
        "a.start_force",
        "b.end_force",
        "a.tension[2]",
        "buoy.fz",
        "hull.my",
        "buoy.offset",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let channels = resolve(Path::new("s"), "study.channels", &entries, &model).unwrap();
    let sampler = Sampler::new(&channels, &model);
    let ta = [10.0, 30.0, 20.0];
    let tb = [5.0, 7.0];
    let cables = [
        CableSnapshot {
            tensions: &ta,
            start_force: [3.0, 0.0, 4.0],
            end_force: [0.0; 3],
        },
        CableSnapshot {
            tensions: &tb,
            start_force: [0.0; 3],
            end_force: [0.0, 6.0, 8.0],
        },
    ];
    let bodies = [
        BodySnapshot {
            force: [0.0; 3],
            moment: [1.0, 2.0, 3.0],
            position: Some([0.5, 0.0, 0.0]),
        },
        BodySnapshot {
            force: [4.0, 5.0, -6.0],
            moment: [0.0; 3],
            // 3 m along x and 4 m along y from its reference, 1 m up: 5 m in plan.
            position: Some([13.0, 4.0, -4.0]),
        },
    ];
    let got: Vec<Option<f64>> = (0..channels.len())
        .map(|i| sampler.value(i, &cables, &bodies))
        .collect();
    assert_eq!(
        got,
        [
            Some(7.0),
            Some(5.0),
            Some(10.0),
            Some(20.0),
            Some(-6.0),
            Some(2.0),
            Some(5.0)
        ]
    );
    // A body not in the snapshot has no offset (rather than one from the origin).
    let absent = [
        bodies[0],
        BodySnapshot {
            position: None,
            ..bodies[1]
        },
    ];
    assert_eq!(sampler.value(6, &cables, &absent), None);
    // `default` adds the free body's offset (not the prescribed hull's).
    let d = resolve(
        Path::new("s"),
        "study.channels",
        &["default".to_string()],
        &model,
    )
    .unwrap();
    let names: Vec<String> = d.iter().map(|c| c.name()).collect();
    assert!(names.contains(&"buoy.offset".to_string()), "{names:?}");
    assert!(!names.contains(&"hull.offset".to_string()), "{names:?}");
    // A hauled-in element gives no sample instead of a wrong one.
    let short = [
        CableSnapshot {
            tensions: &ta[..2],
            ..cables[0]
        },
        cables[1],
    ];
    assert_eq!(sampler.value(3, &short, &bodies), None);
    let mut stats = vec![ChannelStats::new(0.0); channels.len()];
    sampler.record(&mut stats, 1.0, &short, &bodies);
    assert_eq!(stats[3].count(), 0);
    assert_eq!(stats[0].max().unwrap().value, 7.0);
}
