//! `src/sea/bands.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::bands::*;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::schedule::refresh_plan;
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::SeaState;

fn sea(hs: f64, tp: f64) -> SeaState {
    let d = Discretisation {
        components: 200,
        direction: 0.0,
        spreading: None,
        seed: 3,
        stream: 0,
    };
    SeaState {
        components: discretise(&Spectrum::Jonswap { hs, tp, gamma: 2.5 }, &d, 320.0, 9.81),
        ..SeaState::still(320.0)
    }
}

/// Band 0 is the sea's plan; each deeper band doubles the steps and its top is the
/// highest height whose planned interval reaches them: just above the top the
/// interval is short of them, at the top it is not; tops decrease.
#[test]
fn band_tops_are_where_the_interval_reaches_the_rung() {
    let s = sea(9.0, 13.0);
    let dt = 1.0 / 150.0;
    let p = band_plan(&s, 2.0, dt);
    assert_eq!(p.base, refresh_plan(&s, 2.0, dt));
    assert!(p.len() >= 3, "{p:?}");
    assert_eq!(p.tops[0], f64::INFINITY);
    for m in 1..p.len() {
        assert_eq!(p.steps[m], p.steps[0] << m);
        assert!(p.tops[m] < p.tops[m - 1]);
        let need = p.band(m).interval;
        assert!(band_interval(&s, p.tops[m]) >= need);
        assert!(band_interval(&s, p.tops[m] + 0.01) < need);
        assert!(band_interval(&s, p.tops[m]) >= refresh_plan(&s, p.tops[m], dt).unrounded);
    }
    assert_eq!(p.horizon(), p.band(p.len() - 1).interval);
    let still = band_plan(&SeaState::still(50.0), 0.0, dt);
    assert_eq!(still.len(), 1);
}

/// The decision: the deepest band whose top the node's bound over that band's
/// look-ahead (band 0's given, 1 s here, doubled per band) stays under; a node moving (up,
/// or down: it may come back up within the interval) or accelerating goes
/// shallower; only the bands given (those refreshing at the decision) are tried.
#[test]
fn the_band_decision_keeps_the_bound_under_the_top() {
    let tops = [f64::INFINITY, -20.0, -60.0, -150.0];
    // At rest the interval does not matter: the margin alone.
    assert_eq!(wave_band(-300.0, 0.0, 0.0, 1.0, 2.0, &tops), 3);
    assert_eq!(wave_band(-151.5, 0.0, 0.0, 1.0, 2.0, &tops), 2);
    assert_eq!(wave_band(-152.5, 0.0, 0.0, 1.0, 2.0, &tops), 3);
    assert_eq!(wave_band(-70.0, 0.0, 0.0, 1.0, 2.0, &tops), 2);
    assert_eq!(wave_band(-21.0, 0.0, 0.0, 1.0, 2.0, &tops), 0);
    // Moving at 2.5 m/s: over band 2's 4 s it rises 10 m, to -58 m with the margin
    // (over -60: not band 2); over band 1's 2 s, 5 m, to -63 m (band 1).
    assert_eq!(wave_band(-70.0, 2.5, 0.0, 1.0, 2.0, &tops), 1);
    assert_eq!(wave_band(-70.0, -2.5, 0.0, 1.0, 2.0, &tops), 1);
    // 1.5 m/s: 6 m over 4 s, to -62 m: band 2.
    assert_eq!(wave_band(-70.0, -1.5, 0.0, 1.0, 2.0, &tops), 2);
    assert_eq!(wave_band(-70.0, 0.0, -1.5, 1.0, 2.0, &tops), 1);
    // The same node deep enough for band 3 at rest, but moving: band 3's 8 s carry
    // it 12 m up to -146 m (over -150), band 2's 4 s 6 m: band 2.
    assert_eq!(wave_band(-160.0, 1.5, 0.0, 1.0, 2.0, &tops), 2);
    // Near the top of band 1 and heaving: over band 1's 2 s it stays under -20 m,
    // where looking 8 s ahead (band 0's look-ahead 4 s) it would not.
    assert_eq!(wave_band(-25.0, 1.0, 0.0, 1.0, 2.0, &tops), 1);
    assert_eq!(wave_band(-25.0, 1.0, 0.0, 4.0, 2.0, &tops), 0);
    // Only the bands refreshing at the decision: bands 0 to 1 here.
    assert_eq!(wave_band(-300.0, 0.0, 0.0, 1.0, 2.0, &tops[..2]), 1);
    assert_eq!(wave_band(-300.0, 0.0, 0.0, 1.0, 2.0, &tops[..1]), 0);
    assert_eq!(wave_band(-5.0, 0.0, 0.0, 1.0, 2.0, &[f64::INFINITY]), 0);
}
