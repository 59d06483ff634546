//! How often the waves' kinematics cache refreshes in a packed GPU study, and so how
//! many fused-kernel dispatches a step costs (benchmarks/history/BENCHMARKS-2026-12.md, "The design-check study on
//! the GPU path"):
//!
//! `target/release/examples/study_refresh_schedule examples/study_design_check.toml 0.006666666666666667 1620000`
//!
//! (arguments: a study file, the step in s (the design check's auto step, 1/150 s), the
//! steps to follow: here the 3 hours; optionally the reach of each sea state's nodes,
//! m, comma-separated, as `cablesim run` logs it ("nodes reach z = ..."; default:
//! unknown, the rule at the mean level)). For every member it builds the member's sea
//! as the study does (its sea state's JONSWAP train, 200 components, seeded with the
//! member's wave seed, in the base scenario's depth) and its refresh plan
//! (`sea::schedule::refresh_plan` at the default tolerance 1e-3). Then it follows every
//! member's refresh schedule step by step with the solvers' own clock
//! (`sea::schedule::RefreshClock`), twice: on the common grid of the plan (what the
//! solvers do) and, for comparison, at the plan's unrounded interval from the first
//! step (what they did before the grid), and counts the steps at which *some* sea
//! refreshes: in waves the GPU path starts a new fused dispatch (after a
//! `wave_refresh` dispatch) at each such step (`gpu::wave_schedule::fused_segments`), so the
//! count is the number of dispatch pairs for the packed batch of the first `n`
//! members, for several `n`.
//!
//! The base scenario is assumed to be the design check's (320 m of water, g = 9.81,
//! no `cache_tolerance`, long-crested); the example checks the depth it reads.
//!
//! Built with `cargo build --release --features bench --example study_refresh_schedule`: the
//! examples/*.rs are behind the `bench` feature, so `cargo test` does not build them.

use cablesim::sea::irregular::{discretise, Discretisation, DEFAULT_COMPONENTS};
use cablesim::sea::schedule::{refresh_plan, RefreshClock, RefreshPlan};
use cablesim::sea::spectrum::{dnv_peak_factor, Spectrum};
use cablesim::sea::SeaState;
use cablesim::study::definition::StudyFile;
use cablesim::study::members::members;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: study_refresh_schedule STUDY DT STEPS [REACH,REACH,...]");
    let dt: f64 = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(6.6667e-3);
    let steps: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(9000);
    let reach: Vec<f64> = args
        .get(4)
        .map(|s| s.split(',').map(|x| x.parse().expect("reach, m")).collect())
        .unwrap_or_default();
    let file = StudyFile::load(path).expect("study file");
    let depth = 320.0;
    assert!(
        file.scenario_text.contains("depth = 320.0"),
        "this example assumes the design check's 320 m of water"
    );
    let def = &file.def;
    let mut plans: Vec<(usize, RefreshPlan)> = Vec::new();
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
        let sea = SeaState {
            components: discretise(&spectrum, &d, depth, 9.81),
            ..SeaState::still(depth)
        };
        let z = reach.get(m.sea_state).copied().unwrap_or(f64::INFINITY);
        plans.push((m.sea_state, refresh_plan(&sea, z, dt)));
    }
    for (q, s) in def.sea_states.iter().enumerate() {
        let ps: Vec<&RefreshPlan> = plans
            .iter()
            .filter(|(k, _)| *k == q)
            .map(|(_, p)| p)
            .collect();
        let un: Vec<f64> = ps.iter().map(|p| p.unrounded).collect();
        let lo = un.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = un.iter().cloned().fold(0.0, f64::max);
        let mean = un.iter().sum::<f64>() / un.len() as f64;
        let mut grid: Vec<u64> = ps.iter().map(|p| p.steps).collect();
        grid.sort();
        grid.dedup();
        println!(
            "sea state {q} ({}): {} members, reach {:.2} m, factor {}, interval {:.4} s \
             (min {:.4}, max {:.4}): {:.2} steps of {dt} s; on the grid: every {grid:?} steps",
            s.name.as_deref().unwrap_or(""),
            ps.len(),
            ps[0].reach,
            ps[0].factor,
            mean,
            lo,
            hi,
            mean / dt
        );
    }
    let n = plans.len();
    let sizes: Vec<usize> = [1, 3, 10, 30, 100, 300, 1000, 3000]
        .into_iter()
        .filter(|&k| k <= n)
        .chain((!matches!(n, 1 | 3 | 10 | 30 | 100 | 300 | 1000 | 3000)).then_some(n))
        .collect();
    for (label, on_grid) in [("on the grid", true), ("unrounded, not on a grid", false)] {
        let mut clocks: Vec<RefreshClock> = plans
            .iter()
            .map(|(_, p)| {
                if on_grid {
                    RefreshClock::on_grid(p)
                } else {
                    RefreshClock::free(p.unrounded)
                }
            })
            .collect();
        let mut refreshes_of = vec![0usize; n];
        let mut any_upto = vec![0usize; sizes.len()];
        for k in 0..steps {
            let t = k as f64 * dt;
            let mut first_refresh: Option<usize> = None;
            for (i, c) in clocks.iter_mut().enumerate() {
                if c.tick(t).is_some() {
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
            "{label}: {steps} steps: a member's sea refreshes at {:.4} of the steps (mean \
             over members)",
            per_member / steps as f64
        );
        for (c, size) in any_upto.iter().zip(&sizes) {
            println!(
                "  batch of the first {size} members: some sea refreshes at {c} of {steps} \
                 steps ({:.4}): {:.2} steps per fused dispatch",
                *c as f64 / steps as f64,
                steps as f64 / *c as f64
            );
        }
    }
}
