//! `src/sea/schedule.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::cache::{hermite_rule_interval, HERMITE_INTERVAL_FACTOR};
use cablesim::sea::dispersion::wave_number;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::schedule::*;
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::SeaState;

fn sea(hs: f64, tp: f64, seed: u64) -> SeaState {
    let d = Discretisation {
        components: 200,
        direction: 0.0,
        spreading: None,
        seed,
        stream: 0,
    };
    let spectrum = Spectrum::Jonswap { hs, tp, gamma: 2.5 };
    SeaState {
        components: discretise(&spectrum, &d, 320.0, 9.81),
        ..SeaState::still(320.0)
    }
}

/// At the mean level the plan is the old rule times 0.3; deeper the interval
/// grows and the rule with decayed amplitudes is not longer than the rule of the
/// longest component alone; deep enough under the troughs the factor is the
/// submerged one. The grid rounds down to the ladder `2^m, 3 2^m` of the step.
#[test]
fn the_plan_grows_with_depth_and_rounds_down_to_the_grid() {
    let s = sea(9.0, 13.0, 3);
    let dt = 1.0 / 150.0;
    let top = refresh_plan(&s, f64::INFINITY, dt);
    let rule = hermite_rule_interval(&s.components, 1e-3);
    assert_eq!(top.unrounded, HERMITE_INTERVAL_FACTOR * rule);
    assert!(!top.submerged);
    // Hs 9 m: the trough 1.2 Hs.
    assert!((top.trough + 1.2 * 9.0).abs() < 0.2, "{}", top.trough);
    let mut last = top.unrounded;
    for reach in [-2.0, -10.0, -20.0, -40.0] {
        let p = refresh_plan(&s, reach, dt);
        assert!(p.unrounded >= last, "{reach}: {} < {last}", p.unrounded);
        assert!(p.interval <= p.unrounded && 1.5 * p.interval > p.unrounded);
        let odd = p.steps >> p.steps.trailing_zeros();
        assert!(odd == 1 || odd == 3, "{}", p.steps);
        assert_eq!(p.interval, p.steps as f64 * dt);
        assert_eq!(p.submerged, reach <= p.trough - SURFACE_MARGIN);
        last = p.unrounded;
    }
    let deep = refresh_plan(&s, -40.0, dt);
    assert!(deep.submerged && deep.factor == SUBMERGED_FACTOR);
    let wmin = s
        .components
        .iter()
        .map(|c| c.omega)
        .fold(f64::MAX, f64::min);
    assert!(deep.unrounded <= SUBMERGED_FACTOR * (384e-3f64).powf(0.25) / wmin);
    assert_eq!(grid_steps(f64::INFINITY, dt), u64::MAX);
    assert_eq!(grid_steps(0.5 * dt, dt), 1);
    assert_eq!(grid_steps(8.0 * dt, dt), 8);
    assert_eq!(grid_steps(7.9 * dt, dt), 6);
    assert_eq!(grid_steps(5.9 * dt, dt), 4);
    assert_eq!(grid_steps(2.9 * dt, dt), 2);
    assert_eq!(grid_steps(3.0 * dt, dt), 3);
    assert_eq!(grid_steps(26.4 * dt, dt), 24);
    assert_eq!(grid_steps(31.5 * dt, dt), 24);
    assert_eq!(grid_steps(33.0 * dt, dt), 32);
}

/// The decay is 1 at the mean level, `e^{k z}` in deep water and the cosh ratio in
/// finite depth.
#[test]
fn depth_decay_is_the_horizontal_profile() {
    let k = wave_number(0.8, 50.0, 9.81);
    assert!((depth_decay(k, 0.0, 50.0) - 1.0).abs() < 1e-15);
    let want = (k * (50.0 - 10.0)).cosh() / (k * 50.0).cosh();
    assert!((depth_decay(k, -10.0, 50.0) - want).abs() < 1e-12);
    assert!((depth_decay(0.1, -10.0, f64::INFINITY) - (-1.0f64).exp()).abs() < 1e-15);
}

/// Seas with different intervals on the grid of one step refresh at nested steps:
/// when one's steps per refresh divide the other's (both powers of two, or both
/// three times one), every step at which the longer-interval clock refreshes is one
/// at which the shorter one does; and each refreshes every `steps` steps.
#[test]
fn clocks_on_the_grid_nest() {
    let dt = 1.0 / 150.0;
    let seas = [
        (sea(4.0, 9.0, 1), f64::INFINITY),
        (sea(4.0, 9.0, 1), -12.0),
        (sea(9.0, 13.0, 2), f64::INFINITY),
        (sea(13.0, 15.5, 3), f64::INFINITY),
    ];
    let plans: Vec<RefreshPlan> = seas
        .iter()
        .map(|(s, reach)| refresh_plan(s, *reach, dt))
        .collect();
    let mut clocks: Vec<RefreshClock> = plans.iter().map(RefreshClock::on_grid).collect();
    let n_steps = 100_000u64;
    let mut at: Vec<Vec<u64>> = vec![Vec::new(); plans.len()];
    for n in 0..n_steps {
        let t = n as f64 * dt;
        for (q, c) in clocks.iter_mut().enumerate() {
            if c.tick(t).is_some() {
                at[q].push(n);
            }
        }
    }
    let mut nested = 0;
    for (a, pa) in plans.iter().enumerate() {
        // The first refresh at step 0, then one step past each grid time.
        let want: Vec<u64> = std::iter::once(0)
            .chain((1..).map(|j| j * pa.steps + 1).take_while(|&n| n < n_steps))
            .collect();
        assert_eq!(at[a], want, "sea {a}: {pa:?}");
        for (b, pb) in plans.iter().enumerate() {
            if pa.steps < pb.steps && pb.steps % pa.steps == 0 {
                nested += 1;
                assert!(at[b].iter().all(|n| at[a].binary_search(n).is_ok()));
            }
        }
    }
    let steps: Vec<u64> = plans.iter().map(|p| p.steps).collect();
    assert!(nested >= 1, "no nested pair: {steps:?}");
}

/// A restart off the grid goes to the next grid time, then on along the grid.
#[test]
fn a_restart_joins_the_grid() {
    let dt = 0.01;
    let plan = RefreshPlan {
        steps: 8,
        interval: 0.08,
        dt,
        ..refresh_plan(&SeaState::still(10.0), f64::INFINITY, dt)
    };
    let mut c = RefreshClock::on_grid(&plan);
    let t = 13.0 * dt;
    let tick = c.tick(t).unwrap();
    assert!(tick.restart && tick.acc_rate == 0.0);
    assert_eq!((c.t0, c.t1), (t, 16.0 * dt));
    assert!(c.tick(16.0 * dt).is_none());
    let tick = c.tick(17.0 * dt).unwrap();
    assert!(!tick.restart);
    assert_eq!((c.t0, c.t1), (16.0 * dt, 24.0 * dt));
    assert!((tick.acc_rate - 1.0 / (4.0 * dt)).abs() < 1e-9);
    c.reset();
    assert!(c.tick(17.0 * dt).unwrap().restart);
}
