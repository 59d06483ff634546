//! `src/gpu/wave_schedule.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::gpu::solver::STEPS_PER_SUBMISSION;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::{dnv_peak_factor, Spectrum};
use cablesim::sea::{SeaSet, SeaState};
use cablesim::testing::gpu_wave_schedule::{fused_segments, SeaSchedules};

/// A packed study's seas on the common refresh grid (`sea::schedule`): the three
/// sea states of `examples/study_design_check.toml` (refreshes every 16, 24 and 32
/// steps of 1/150 s at the mean level), ten seeds each. Submission by submission as
/// `write_waves` forms them, the fused dispatch is cut only at the refresh steps
/// of the shortest interval's family and of the threes' (the union of every 16th
/// and every 24th step: one in twelve), not at most steps as when each sea kept
/// its own unrounded interval.
#[test]
fn packed_seas_on_the_grid_cut_the_fused_dispatch_rarely() {
    let dt = 1.0 / 150.0;
    let mut seas = Vec::new();
    for (hs, tp, gamma) in [
        (4.0, 9.0, dnv_peak_factor(4.0, 9.0)),
        (9.0, 13.0, 2.5),
        (13.0, 15.5, 3.3),
    ] {
        for seed in 0..10 {
            let d = Discretisation {
                components: 200,
                direction: 0.0,
                spreading: None,
                seed,
                stream: 0,
            };
            seas.push(SeaState {
                components: discretise(&Spectrum::Jonswap { hs, tp, gamma }, &d, 320.0, 9.81),
                ..SeaState::still(320.0)
            });
        }
    }
    let set = SeaSet {
        cable_sea: (0..seas.len() as u32).collect(),
        seas,
        reach: Vec::new(),
        banded: false,
    };
    let mut steps: Vec<u64> = (0..set.seas.len()).map(|q| set.plan(q, dt).steps).collect();
    steps.sort();
    steps.dedup();
    assert_eq!(steps, vec![16, 24, 32]);
    let mut w = SeaSchedules::new(&set, dt);
    let (n, per) = (48 * 512u64, STEPS_PER_SUBMISSION as u64);
    let (mut segments, mut refreshes) = (0usize, 0u64);
    for step0 in (0..n).step_by(per as usize) {
        let (_, refresh) = w.rows::<f64>(per as usize, |k| (step0 + k as u64) as f64 * dt, 0.0);
        for (k, &r) in refresh.iter().enumerate() {
            let i = step0 + k as u64;
            let want =
                i == 0 || (i > 1 && ((i - 1).is_multiple_of(16) || (i - 1).is_multiple_of(24)));
            assert_eq!(r, want, "step {i}");
        }
        refreshes += refresh.iter().filter(|&&r| r).count() as u64;
        segments += fused_segments(&refresh, 512).len();
    }
    // One in twelve steps refreshes (16 and 24 meet every 48), and a segment
    // starts at each of them or at a submission's first step.
    let m = n - 2;
    assert_eq!(refreshes, 1 + m / 16 + m / 24 - m / 48);
    assert!(segments as u64 <= refreshes + n / per, "{segments}");
    assert!(segments as u64 >= refreshes, "{segments}");
}

#[test]
fn fused_segments_cut_at_refresh_steps_and_at_the_longest() {
    assert_eq!(fused_segments(&[false; 5], 512), vec![(0, 5)]);
    let r = [true, false, false, true, false, true];
    assert_eq!(fused_segments(&r, 512), vec![(0, 3), (3, 5), (5, 6)]);
    assert_eq!(fused_segments(&[false, true], 512), vec![(0, 1), (1, 2)]);
    assert_eq!(fused_segments(&[false; 5], 2), vec![(0, 2), (2, 4), (4, 5)]);
    assert_eq!(fused_segments(&r, 2), vec![(0, 2), (2, 3), (3, 5), (5, 6)]);
}
