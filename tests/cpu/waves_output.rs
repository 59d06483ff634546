//! Output times in waves: an evaluation (a snapshot's loads) sees the kinematics the
//! steps integrate, the cache interpolated at the current time, within the cache's
//! tolerance of the exact component sum, and taking outputs does not change the run.

use super::waves_steppers::{jonswap, moored_rope};
use cablesim::cpu::CpuSolver;
use cablesim::options::SolverOptions;
use cablesim::sea::cache::refresh_interval;
use cablesim::step::Evaluation;

const DT: f64 = 2e-4;

fn norm(f: [f64; 3]) -> f64 {
    (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The moored rope of `waves_steppers` in its 200-component JONSWAP sea, through the
/// kinematics cache.
fn cached_rope() -> CpuSolver {
    let (lay, pos) = moored_rope();
    let opts = SolverOptions {
        dt: DT,
        ..SolverOptions::default()
    };
    let mut s = CpuSolver::new(lay, &pos, opts);
    s.set_sea(&jonswap(), false);
    s
}

/// The evaluation of a copy of `s` in exact mode: the component sum at every node at
/// the same state and time.
fn exact_evaluation(s: &CpuSolver) -> Evaluation {
    let mut e = s.clone();
    e.set_sea(&jonswap(), true);
    e.evaluate().unwrap()
}

/// At output times every 0.5 s over 20 s (the ramp, then the sea in full) the
/// fairlead force from the cache is within 1e-3 of the largest fairlead force of the
/// exact sum at the same state (the tolerance the cached run keeps against the exact
/// run: `waves_steppers`), and differs from it (the output is the cache's, not the
/// exact sum's); the tensions, which depend on the state alone, are the same.
#[test]
fn output_loads_from_the_cache_are_within_its_tolerance_of_the_exact_sum() {
    let mut s = cached_rope();
    let every = (0.5 / DT).round() as u64;
    let (mut d_force, mut fmax) = (0.0f64, 0.0f64);
    for _ in 0..40 {
        s.advance(every).unwrap();
        let exact = exact_evaluation(&s);
        let cached = s.evaluate().unwrap();
        fmax = fmax.max(norm(exact.reaction[1]));
        d_force = d_force.max(norm(sub(cached.reaction[1], exact.reaction[1])));
        assert_eq!(cached.tension, exact.tension);
    }
    println!(
        "outputs from the cache against the exact sum: fairlead force {d_force:.3e} N of a \
         largest {fmax:.1} N ({:.2e})",
        d_force / fmax
    );
    assert!(d_force < 1e-3 * fmax, "fairlead force off by {d_force} N");
    assert!(
        d_force > 1e-9 * fmax,
        "the output equals the exact sum's ({d_force} N): is it the cache's?"
    );
}

/// The accelerations an evaluation reports are those the next step integrates: after
/// `evaluate` at step `n`, one symplectic Euler step gives `v_{n+1} = v_n + a_n dt` at
/// every free node off the seabed (on it, the step takes the seabed's damping
/// implicitly), to round-off. Checked at time 0 (where the evaluation does the cache's
/// first refresh) and, past the ramp, at every step over two refresh intervals (so
/// some evaluations find the time past the cache's newer time and refresh it as the
/// step would), where the exact sum's accelerations differ by far more. And the run
/// that evaluates ends bit for bit where one that never does ends.
#[test]
fn output_loads_are_the_ones_the_step_integrates() {
    let mut s = cached_rope();
    let mut quiet = s.clone();
    let lay = s.layout().clone();
    let depth = lay.env.depth;
    let interval = refresh_interval(&jonswap().components, jonswap().cache_tolerance);
    let settle = (5.0 / DT).round() as u64;
    let steps = (2.2 * interval / DT).ceil() as u64;
    let (mut worst, mut worst_exact, mut amax) = (0.0f64, 0.0f64, 0.0f64);
    let mut checked = 0;
    for k in 0..=steps {
        let exact = exact_evaluation(&s);
        let ev = s.evaluate().unwrap();
        let v0: Vec<[f64; 3]> = s.v.iter().map(|v| v.to_f64()).collect();
        s.advance(1).unwrap();
        for (i, &v0_i) in v0.iter().enumerate() {
            let free = lay.node_constraint[i] == cablesim::model::NO_CONSTRAINT;
            if !free || s.r[i].z < -depth + 0.5 {
                continue;
            }
            let a_step = sub(s.v[i].to_f64(), v0_i).map(|x| x / DT);
            worst = worst.max(norm(sub(ev.acc[i], a_step)));
            amax = amax.max(norm(a_step));
            if k > 0 {
                worst_exact = worst_exact.max(norm(sub(exact.acc[i], a_step)));
            }
            checked += 1;
        }
        if k == 0 {
            s.advance(settle - 1).unwrap();
        }
    }
    quiet.advance(settle + steps).unwrap();
    println!(
        "{steps} steps from {:.1} s ({interval:.4} s refresh interval), {checked} \
         node-steps: the evaluation's acceleration against the step's {worst:.3e} m/s^2, \
         the exact sum's {worst_exact:.3e} m/s^2, largest {amax:.3e} m/s^2",
        settle as f64 * DT
    );
    assert!(checked > 0);
    assert!(
        worst < 1e-9 * amax,
        "the evaluation is not what the step integrates: {worst} m/s^2"
    );
    assert!(
        worst_exact > 1e3 * worst,
        "the exact sum would pass too ({worst_exact} m/s^2): the check is vacuous"
    );
    assert_eq!(s.steps(), quiet.steps());
    for (a, b) in s.r.iter().zip(&quiet.r) {
        assert_eq!(a.to_f64(), b.to_f64(), "outputs changed the run");
    }
}
