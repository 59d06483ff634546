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

/// Bending stiffness on the chain fast path: one mooring line of 51 nodes (the
/// fleet's wire), without `EI` and with a steel wire's (`E pi d^4 / 64`, 2.5e4 N m^2),
/// symplectic, one thread; and the same line with `EI` on the general passes (what a
/// line with bending took before the fast path had it).
fn bench_bending(c: &mut Criterion) {
    let mut g = c.benchmark_group("cpu_bending");
    g.sample_size(10);
    let (lay0, pos) = fleet(1, 50);
    let mut bent = lay0.clone();
    for lt in &mut bent.line_types {
        lt.ei = 2.5e4;
    }
    let nodes = lay0.n_nodes() as u64;
    let steps = 20_000;
    for (name, lay, fast) in [
        ("no_ei", lay0, true),
        ("ei", bent.clone(), true),
        ("ei_general_path", bent, false),
    ] {
        let mut s = CpuSolver::new(
            lay,
            &pos,
            SolverOptions {
                dt: 1e-4,
                ..Default::default()
            },
        );
        s.use_chain_kernel = fast;
        g.throughput(Throughput::Elements(nodes * steps));
        g.bench_with_input(BenchmarkId::new(name, nodes), &steps, |b, &steps| {
            b.iter(|| s.advance(steps).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench_cpu, bench_bending);
criterion_main!(benches);
