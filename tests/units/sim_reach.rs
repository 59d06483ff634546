//! `src/sim/reach.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::model::Route;
use cablesim::output::Snapshot;
use cablesim::output::{CableState, EndForces};
use cablesim::sea::SeaSet;
use cablesim::sea::{SeaState, WaveComponent};
use cablesim::sim::reach::*;
use std::f64::consts::TAU;

fn cable(name: &str, z: &[f64]) -> CableState {
    CableState {
        name: name.into(),
        output_positions: false,
        positions: z.iter().map(|&z| [0.0, 0.0, z]).collect(),
        velocities: vec![[0.0; 3]; z.len()],
        tensions: Vec::new(),
        end_forces: EndForces {
            start: [0.0; 3],
            end: [0.0; 3],
        },
        winch: None,
    }
}

/// The watch finds the first node above its sea's reach (cables in still water
/// are not watched), and none when all stay under.
#[test]
fn the_watch_finds_a_node_above_the_reach() {
    let wave = SeaState {
        components: vec![WaveComponent {
            amplitude: 1.0,
            omega: 0.6,
            k: 0.6 * 0.6 / 9.81,
            direction: 0.0,
            phase: 0.0,
        }],
        ..SeaState::still(100.0)
    };
    let seas = SeaSet {
        seas: vec![wave, SeaState::still(100.0)],
        cable_sea: vec![0, 0, 1],
        reach: vec![-10.0, f64::INFINITY],
        banded: false,
    };
    let mut w = ReachWatch::new(&seas, 3).expect("a watch in waves");
    let snap = |z1: f64| Snapshot {
        time: 1.0,
        steps: 10,
        cables: vec![
            cable("a", &[-30.0, -12.0]),
            cable("b", &[-30.0, z1, -11.0]),
            cable("c", &[5.0]),
        ],
        bodies: Vec::new(),
        points: Vec::new(),
        nets: Vec::new(),
    };
    assert_eq!(w.breach(&snap(-10.5)), None);
    assert_eq!(w.breach(&snap(-9.0)), Some((1, 1, -9.0)));
    w.check(&snap(-9.0));
    assert!(w.warned);
    assert!(ReachWatch::new(&SeaSet::single(&SeaState::still(1.0)), 1).is_none());
}

/// A fixed end reaches its own height; an end on a vertical circle at least the
/// circle's top and no more than the sampling's allowance above it; a table at
/// least its highest row.
#[test]
fn route_tops_bound_the_ends_heights() {
    let fixed = Route::Fixed {
        position: [1.0, 2.0, -18.0],
    };
    let (r, period) = (3.0, 7.3);
    let circle = Route::Circle {
        center: [0.0, 0.0, -20.0],
        radius: r,
        period,
        axis: [0.0, 1.0, 0.0],
        phase: 0.4,
        advance: 0.0,
    };
    let table = Route::Table {
        t: vec![0.0, 10.0, 20.0],
        p: vec![[0.0, 0.0, -5.0], [0.0, 0.0, -2.5], [0.0, 0.0, -6.0]],
    };
    let tops = route_tops(&[&fixed, &circle, &table], 100.0);
    assert_eq!(tops[0], -18.0);
    let w = TAU / period;
    let h = ROUTE_SAMPLE;
    assert!(tops[1] >= -20.0 + r, "{}", tops[1]);
    assert!(tops[1] <= -20.0 + r + r * w * h / 2.0 + r * w * w * h * h / 8.0);
    // The highest row, raised by at most the steeper slope's half sample.
    assert!(
        tops[2] >= -2.5 && tops[2] <= -2.5 + 0.35 * h / 2.0 + 1e-12,
        "{}",
        tops[2]
    );
}
