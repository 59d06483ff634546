//! The GPU path's host rows of an RAO body alone, for load-independent instruction
//! counts (benchmarks/history/BENCHMARKS-2026-12.md, "RAO body motion between knots"): the design-check platform
//! (`examples/study_design_check.toml`: the synthetic RAO table in the 200-component
//! JONSWAP sea) through `gpu::solver::body_rows`, the function `write_bodies` calls per
//! member and submission, in submissions of 75 steps (an output interval of 0.5 s at the
//! design check's step of 1/150 s), from t = 0:
//!
//! `valgrind --tool=callgrind target/release/examples/body_rows_count rows 15000`
//!
//! (arguments: `rows` (the rows as `write_bodies` forms them) or `exact` (the exact
//! sum over the components at every step, `RaoMotion::eval_exact`, with the same rigid
//! body state: what every row cost before the knots), and the steps; the difference of
//! two counts over the difference of their steps is the cost per member-step, the
//! scenario's loading cancelling out).
//!
//! Built with `cargo build --release --features bench --example body_rows_count`: the
//! examples/*.rs are behind the `bench` feature, so `cargo test` does not build them.

use cablesim::body::{kinematics::body_state, Body, Motion};
use cablesim::gpu::solver::body_rows;
use cablesim::model::Route;
use cablesim::scenario::Scenario;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let exact = args.get(1).map(String::as_str) == Some("exact");
    let steps: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(15000);
    let sc =
        Scenario::load("examples/study_design_check.toml").expect("run from the repository root");
    let body: std::sync::Arc<Body> = sc
        .model
        .nodes
        .iter()
        .find_map(|n| match &n.route {
            Some(Route::Body { body, .. }) => Some(body.clone()),
            _ => None,
        })
        .expect("a cable end on the platform");
    let Motion::Rao(m) = &body.motion else {
        panic!("the platform moves by RAOs")
    };
    let dt = 1.0 / 150.0;
    let per = 75;
    let mut check = 0.0f64;
    let mut step0 = 0;
    while step0 < steps {
        let n = per.min(steps - step0);
        let times = (0..n).map(|k| (step0 + k) as f64 * dt);
        if exact {
            for t in times {
                check += body_state(&body.pose, &m.eval_exact(t)).x.z;
            }
        } else {
            let rows = body_rows::<f32>(&body, step0 as f64 * dt, times);
            check += rows.iter().map(|r| r.dz as f64).sum::<f64>();
        }
        step0 += n;
    }
    println!(
        "{steps} steps, {}: checksum {check:.6e}, knot interval {:.4} s",
        if exact { "exact" } else { "rows" },
        m.knot_interval()
    );
}
