//! How often a run's nodes were above the water surface: reads a scenario (its sea) and
//! the `positions.csv` of a run of it, and counts, for the nodes that came within
//! `above` m of the mean level (default -20: the design member's band 0 and its
//! fairleads), the output samples at which a node was over the elevation above it
//! (`z > eta`), and the least submergence `eta - z` seen. Why: the cache's factor near
//! the surface (benchmarks/history/BENCHMARKS-2026-12.md, "Why the surface needs 0.3 of the rule") matters where
//! the surface uncovers nodes.
//!
//! `target/release/examples/surface_count examples/study_design_check.toml o/positions.csv`
//!
//! Built with `cargo build --release --features bench --example surface_count`.

use cablesim::scenario::Scenario;
use cablesim::sea::kinematics::WaveField;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (scenario, positions) = match (args.get(1), args.get(2)) {
        (Some(s), Some(p)) => (s, p),
        _ => panic!("usage: surface_count SCENARIO.toml positions.csv [above]"),
    };
    let above: f64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(-20.0);
    let sc = Scenario::load(scenario).unwrap_or_else(|e| panic!("{scenario}: {e}"));
    let field = WaveField::new(&sc.sea);
    let mut reader =
        csv::Reader::from_path(positions).unwrap_or_else(|e| panic!("{positions}: {e}"));
    let (mut samples, mut uncovered, mut least) = (0u64, 0u64, f64::INFINITY);
    let mut highest = f64::NEG_INFINITY;
    for rec in reader.records() {
        let r = rec.unwrap();
        let num = |i: usize| r[i].parse::<f64>().unwrap();
        let (t, x, y, z) = (num(0), num(3), num(4), num(5));
        if z < above {
            continue;
        }
        samples += 1;
        highest = highest.max(z);
        let s = field.elevation(x, y, t) - z;
        least = least.min(s);
        uncovered += (s < 0.0) as u64;
    }
    println!(
        "node samples above {above} m: {samples}; highest node {highest:.2} m; over the surface \
         in {uncovered}; least submergence {least:.2} m"
    );
}
