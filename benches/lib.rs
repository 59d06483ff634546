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

/// The net cage of `examples/net_cage.toml` (128 x 32 knots, one element a twine, in
/// still water with a 0.3 m/s current) stepped with Morison twines and with the screen
/// model (Kristiansen and Faltinsen, Cheng's wake), on the network fast path, one
/// thread: the screen model's cost per node-step (docs/src/model/screen.md).
fn bench_net_screen(c: &mut Criterion) {
    use cablesim::model::{
        add_net, Current, Environment, Layout, LineType, ModelDef, NetShape, NetSpec, PointMass,
        ScreenModel, ScreenNet, WakeModel,
    };
    let mut g = c.benchmark_group("net_cage");
    g.sample_size(10);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for screen in [false, true] {
        let mut def = ModelDef {
            env: Environment::default(),
            line_types: vec![LineType {
                name: "twine".into(),
                diameter: 0.012,
                mass_per_length: 0.15,
                ea: 5.0e4,
                damping: 1e-4,
                cn: 1.2,
                ct: 0.01,
                cm: 1.0,
                cat: 0.0,
                ei: 0.0,
                allow_compression: false,
                ea_curve: None,
                viscoelastic: None,
            }],
            currents: vec![Current::uniform([0.3, 0.0, 0.0])],
            ..Default::default()
        };
        add_net(
            &mut def,
            &NetSpec {
                name: "cage".into(),
                line_type: 0,
                current: 0,
                shape: NetShape::Cylinder {
                    around: 128,
                    rows: 32,
                    radius: 10.0,
                    depth: 8.0,
                    top: [0.0, 0.0, -0.5],
                },
                segments: 1,
                sinker: PointMass {
                    mass: 20.0,
                    volume: 0.0025,
                    drag_area: 0.02,
                    added_mass_coef: 0.0,
                },
                output_positions: false,
                screen: screen.then_some(ScreenNet {
                    model: ScreenModel::KristiansenFaltinsen,
                    solidity: 0.2,
                    twine_diameter: 2e-3,
                    viscosity: 1e-6,
                    wake: WakeModel::Cheng,
                    axis: [0.0, 0.0],
                }),
            },
        )
        .unwrap();
        let (lay, pos) = Layout::build(&def).unwrap();
        let nodes = lay.n_nodes() as u64;
        let steps = 200;
        let mut s = CpuSolver::new(
            lay,
            &pos,
            SolverOptions {
                dt: 2e-4,
                ..Default::default()
            },
        );
        g.throughput(Throughput::Elements(nodes * steps));
        let name = if screen { "screen" } else { "morison" };
        g.bench_function(name, |b| {
            b.iter(|| pool.install(|| s.advance(steps).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, bench_cpu, bench_bending, bench_net_screen);
criterion_main!(benches);
