//! How often the waves' kinematics cache refreshes in a packed GPU study, and so how
//! many fused-kernel dispatches a step costs (BENCHMARKS.md, "The design-check study on
//! the GPU path"):
//!
//! `target/release/examples/study_refresh_schedule examples/study_design_check.toml 0.006666666666666667 1620000`
//!
//! (arguments: a study file, the step in s (the design check's auto step, 1/150 s), the
//! steps to follow: here the 3 hours; optionally a factor on every interval, e.g. 2.35
//! for what the cubic Hermite cache of branch `herm` gives). For every member it
//! builds the member's sea as the study does (its sea state's JONSWAP train, 200
//! components, seeded with the member's wave seed, in the base scenario's depth) and
//! prints the cache's refresh interval (`sea::cache::refresh_interval` at the default
//! tolerance 1e-3). Then it follows the refresh schedule of every member's sea step by
//! step, as `gpu::solver::WaveSchedule::step` does (a refresh when the step's time
//! leaves `[t0, t1]`), and counts the steps at which *some* sea refreshes: in waves the
//! solver starts a new fused dispatch (after a `wave_refresh` dispatch) at each such
//! step (`gpu::solver::fused_segments`), so the count is the number of dispatch pairs
//! for the packed batch of the first `n` members, for several `n`.
//!
//! The base scenario is assumed to be the design check's (320 m of water, g = 9.81,
//! no `cache_tolerance`, long-crested); the example checks the depth it reads.

use cablesim::sea::cache::refresh_interval;
use cablesim::sea::irregular::{discretise, Discretisation, DEFAULT_COMPONENTS};
use cablesim::sea::spectrum::{dnv_peak_factor, Spectrum};
use cablesim::study::definition::StudyFile;
use cablesim::study::members::members;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: study_refresh_schedule STUDY DT STEPS");
    let dt: f64 = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(6.6667e-3);
    let steps: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(9000);
    let factor: f64 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(1.0);
    let file = StudyFile::load(path).expect("study file");
    let depth = 320.0;
    assert!(
        file.scenario_text.contains("depth = 320.0"),
        "this example assumes the design check's 320 m of water"
    );
    let def = &file.def;
    let mut intervals = Vec::new();
    for m in members(def) {
        let s = &def.sea_states[m.sea_state];
        let gamma = s.gamma.unwrap_or_else(|| dnv_peak_factor(s.hs, s.tp));
        let spectrum = Spectrum::Jonswap {
            hs: s.hs,
            tp: s.tp,
            gamma,
        };
        let d = Discretisation {
            components: DEFAULT_COMPONENTS,
            direction: s.heading.to_radians(),
            spreading: None,
            seed: m.wave_seed,
            stream: 0,
        };
        let comps = discretise(&spectrum, &d, depth, 9.81);
        intervals.push((m.sea_state, factor * refresh_interval(&comps, 1e-3)));
    }
    for (q, s) in def.sea_states.iter().enumerate() {
        let iv: Vec<f64> = intervals
            .iter()
            .filter(|(k, _)| *k == q)
            .map(|(_, i)| *i)
            .collect();
        let lo = iv.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = iv.iter().cloned().fold(0.0, f64::max);
        let mean = iv.iter().sum::<f64>() / iv.len() as f64;
        println!(
            "sea state {q} ({}): {} members, refresh interval {:.4} s (min {:.4}, max {:.4}): \
             a refresh every {:.2} steps of {dt} s",
            s.name.as_deref().unwrap_or(""),
            iv.len(),
            mean,
            lo,
            hi,
            mean / dt
        );
    }
    // Each member's schedule, step by step (WaveSchedule::step: t0, t1 = t0 + interval,
    // a refresh at the first step whose time leaves [t0, t1]).
    let n = intervals.len();
    let mut refreshes_of = vec![0usize; n];
    let mut any_upto: Vec<usize> = Vec::new(); // per batch size in `sizes`
    let sizes: Vec<usize> = [1, 3, 10, 30, 100, 300, 1000, 3000]
        .into_iter()
        .filter(|&k| k <= n)
        .chain((!matches!(n, 1 | 3 | 10 | 30 | 100 | 300 | 1000 | 3000)).then_some(n))
        .collect();
    any_upto.resize(sizes.len(), 0);
    let mut t0 = vec![0.0f64; n];
    let mut t1 = vec![0.0f64; n];
    let mut started = vec![false; n];
    for k in 0..steps {
        let t = k as f64 * dt;
        let mut first_refresh: Option<usize> = None;
        for i in 0..n {
            let iv = intervals[i].1;
            let covered = t1[i] > t0[i] && t >= t0[i] && t <= t1[i];
            if !covered {
                if !started[i] || t < t0[i] || t > t1[i] + iv {
                    t0[i] = t;
                    started[i] = true;
                } else {
                    t0[i] = t1[i];
                }
                t1[i] = t0[i] + iv;
                refreshes_of[i] += 1;
                first_refresh.get_or_insert(i);
            }
        }
        if let Some(i) = first_refresh {
            for (c, &size) in any_upto.iter_mut().zip(&sizes) {
                if i < size {
                    *c += 1;
                }
            }
        }
    }
    let per_member = refreshes_of.iter().sum::<usize>() as f64 / n as f64;
    println!(
        "{steps} steps: a member's sea refreshes at {:.4} of the steps (mean over members)",
        per_member / steps as f64
    );
    for (c, size) in any_upto.iter().zip(&sizes) {
        println!(
            "batch of the first {size} members: some sea refreshes at {c} of {steps} steps \
             ({:.4}): {:.2} steps per fused dispatch",
            *c as f64 / steps as f64,
            steps as f64 / *c as f64
        );
    }
}
