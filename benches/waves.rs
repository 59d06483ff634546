//! Criterion bench: the cost of a CPU step in waves against a step in still water.
//!
//! `cargo bench --bench waves` ; throughput in node-steps per second. The sea is a
//! 200-component JONSWAP (Hs 4 m, Tp 9 s) in 100 m of water, through the kinematics
//! cache at its default tolerance (1e-3); the goal is at most 1.5x the still-water
//! step's time. `jonswap200` plans the cache's refresh as a `cablesim run` does (the
//! sea's reach from the fleet's ends, a refresh interval per depth band: `sea::bands`);
//! `jonswap200_one_band` refreshes every node at the interval of the mean level, as a
//! run did before the plan knew the nodes' depths (kept to show what the bands save).

mod common;

use cablesim::cpu::CpuSolver;
use cablesim::options::{Scheme, SolverOptions};
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaSet, SeaState, Stretching};
use cablesim::sim::reach::sea_reach;
use common::fleet;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

fn jonswap(depth: f64) -> SeaState {
    let spectrum = Spectrum::Jonswap {
        hs: 4.0,
        tp: 9.0,
        gamma: 3.3,
    };
    let d = Discretisation {
        components: 200,
        direction: 0.0,
        spreading: None,
        seed: 1,
        stream: 0,
    };
    SeaState {
        components: discretise(&spectrum, &d, depth, 9.81),
        depth,
        stretching: Stretching::Wheeler,
        ramp_duration: 0.0,
        cache_tolerance: 1e-3,
    }
}

fn bench_waves(c: &mut Criterion) {
    let mut g = c.benchmark_group("cpu_step_sea");
    g.sample_size(10);
    for &(n_cables, segments) in &[(1usize, 50usize), (100, 50)] {
        for (label, sea, banded) in [
            ("still", None, false),
            ("jonswap200", Some(jonswap(100.0)), true),
            ("jonswap200_one_band", Some(jonswap(100.0)), false),
        ] {
            let (lay, pos) = fleet(n_cables, segments);
            let nodes = lay.n_nodes() as u64;
            // Long enough runs that the cache's refreshes (every few hundred steps)
            // are counted at their share.
            let steps = (4_000_000 / nodes).clamp(2000, 20_000);
            let mut s = CpuSolver::new(
                lay.clone(),
                &pos,
                SolverOptions {
                    dt: 1e-4,
                    scheme: Scheme::Symplectic,
                    ..Default::default()
                },
            );
            if let Some(sea) = &sea {
                let mut set = SeaSet::single(sea);
                if banded {
                    // The ends are held still, so the reach does not depend on how
                    // long criterion runs; an hour covers every iteration.
                    set.reach = sea_reach(&lay, &pos, &set, 3600.0);
                    set.banded = true;
                }
                s.set_seas(&set, false);
            }
            g.throughput(Throughput::Elements(nodes * steps));
            g.bench_with_input(
                BenchmarkId::new(label, format!("{n_cables}x{}", segments + 1)),
                &steps,
                |b, &steps| b.iter(|| s.advance(steps).unwrap()),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, bench_waves);
criterion_main!(benches);
