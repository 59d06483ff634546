//! Criterion benches: node-steps per second of the CPU reference path.
//!
//! `cargo bench --bench lib` ; criterion reports throughput in "elem/s", which here
//! means node-steps per second (nodes x steps / wall time).

mod common;

use cablesim::cpu::CpuSolver;
use cablesim::options::{Scheme, SolverOptions};
use common::fleet;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

fn bench_cpu(c: &mut Criterion) {
    let mut g = c.benchmark_group("cpu_step");
    g.sample_size(10);
    for scheme in [Scheme::Symplectic, Scheme::Rk2, Scheme::Rk4] {
        for &(n_cables, segments) in &[(1usize, 50usize), (100, 50), (1000, 100)] {
            let (lay, pos) = fleet(n_cables, segments);
            let nodes = lay.n_nodes() as u64;
            let steps = (2_000_000 / nodes).clamp(1, 1000);
            let mut s = CpuSolver::new(
                lay,
                &pos,
                SolverOptions {
                    dt: 1e-4,
                    scheme,
                    ..Default::default()
                },
            );
            g.throughput(Throughput::Elements(nodes * steps));
            g.bench_with_input(
                BenchmarkId::new(scheme.name(), format!("{n_cables}x{}", segments + 1)),
                &steps,
                |b, &steps| b.iter(|| s.advance(steps).unwrap()),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, bench_cpu);
criterion_main!(benches);
