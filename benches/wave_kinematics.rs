//! Criterion benches of the wave kinematics: the exact sum over a 200-component
//! JONSWAP sea at one node (what a refresh of the cache costs per node) against the
//! cache's interpolation at one node (what every step costs per node).
//!
//! `cargo bench --bench wave_kinematics`; "elem/s" means node evaluations per second. A node-step
//! in waves costs one interpolation plus `1 / (refresh interval / dt)` exact sums; the
//! refresh interval is printed.

use cablesim::sea::cache::{evaluate_nodes, refresh_interval, WaveCache, CACHE_STRIDE};
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::kinematics::WaveField;
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::SeaState;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

fn sea() -> SeaState {
    let comps = discretise(
        &Spectrum::Jonswap {
            hs: 6.0,
            tp: 10.0,
            gamma: 3.3,
        },
        &Discretisation {
            components: 200,
            direction: 0.0,
            spreading: None,
            seed: 1,
            stream: 0,
        },
        150.0,
        9.81,
    );
    SeaState {
        components: comps,
        ..SeaState::still(150.0)
    }
}

fn bench_waves(c: &mut Criterion) {
    let sea = sea();
    eprintln!(
        "refresh interval for Hs 6 m, Tp 10 s, 200 components, tolerance 1e-3: {:.4} s",
        refresh_interval(&sea.components, sea.cache_tolerance)
    );
    let n = 1000;
    let pos: Vec<f64> = (0..n)
        .flat_map(|i| [i as f64 * 0.5, 0.0, -150.0 + 0.15 * i as f64])
        .collect();
    let field = WaveField::new(&sea);
    let mut out = vec![0.0; n * CACHE_STRIDE];
    let mut g = c.benchmark_group("waves");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("exact_sum_200_components_per_node", |b| {
        b.iter(|| evaluate_nodes(&field, &pos, 12.3, &mut out))
    });
    let mut cache = WaveCache::new(&sea, n);
    let vel = vec![0.0; 3 * n];
    cache.refresh_if_due(12.3, &pos, &vel);
    let t = 0.5 * (cache.t0 + cache.t1);
    g.bench_function("cache_interpolation_per_node", |b| {
        b.iter(|| cache.interpolate(t, &mut out))
    });
    g.finish();
}

criterion_group!(benches, bench_waves);
criterion_main!(benches);
