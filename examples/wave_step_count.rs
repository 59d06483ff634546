//! A fixed number of CPU steps of the `benches/waves.rs` fleet, in still water or in
//! its 200-component JONSWAP sea, for load-independent instruction counts:
//!
//! `valgrind --tool=callgrind target/release/examples/wave_step_count still 1 20000`
//! and the same with `waves` (arguments: sea, cables, steps). The difference of the
//! two counts over the node-steps is the cost of the waves. `waves` plans the cache's
//! refresh as a CPU run does (the sea's reach from the fleet's ends, refresh per depth
//! band: `sea::bands`); `waves-flat` refreshes every node at the interval of the
//! mean level, as before the plan knew the nodes' depth.
//!
//! Built with `cargo build --release --features bench --example wave_step_count`: the
//! examples/*.rs are behind the `bench` feature, so `cargo test` does not build them.

#[path = "../benches/common/mod.rs"]
mod common;

use cablesim::cpu::CpuSolver;
use cablesim::options::{Scheme, SolverOptions};
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaSet, SeaState, Stretching};
use cablesim::sim::reach::sea_reach;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map(String::as_str).unwrap_or("still");
    let waves = mode.starts_with("waves");
    let cables: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let steps: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(20_000);
    let (lay, pos) = common::fleet(cables, 50);
    let mut s = CpuSolver::new(
        lay.clone(),
        &pos,
        SolverOptions {
            dt: 1e-4,
            scheme: Scheme::Symplectic,
            ..Default::default()
        },
    );
    if waves {
        let depth = 100.0;
        let d = Discretisation {
            components: 200,
            direction: 0.0,
            spreading: None,
            seed: 1,
            stream: 0,
        };
        let spectrum = Spectrum::Jonswap {
            hs: 4.0,
            tp: 9.0,
            gamma: 3.3,
        };
        let sea = SeaState {
            components: discretise(&spectrum, &d, depth, 9.81),
            depth,
            stretching: Stretching::Wheeler,
            ramp_duration: 0.0,
            cache_tolerance: 1e-3,
        };
        if mode == "waves-flat" {
            s.set_sea(&sea, false);
        } else {
            let mut set = SeaSet::single(&sea);
            set.reach = sea_reach(&lay, &pos, &set, steps as f64 * 1e-4);
            set.banded = true;
            s.set_seas(&set, false);
        }
    }
    s.advance(steps).unwrap();
    println!("{steps} steps, {mode}");
}
