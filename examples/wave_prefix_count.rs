//! How many components the refresh's decay pass sums per depth band on a member's
//! actual depths (benchmarks/history/BENCHMARKS-2026-12.md, "The GPU step in waves", the counted part): the
//! scenario run on the CPU path, and at each sample time every node's band and the
//! prefix its refresh would sum at its state then (`CpuSolver::wave_decay_prefixes`:
//! `sea::cut::wave_decay_prefix`, the Rust twin of the shader's), averaged per band
//! over the samples. The elevation pass sums every component whatever the depth. Also
//! per band the mean number of prefix components whose seabed term the refresh leaves
//! out (`2 k (zs + h) > 39` at the node's state: one `wave_exp` in `wave_depth_decay`
//! instead of two, branch `hgpuref`).
//!
//! `target/release/examples/wave_prefix_count examples/study_design_check.toml 10 200 1`
//!
//! (arguments: a scenario, the first and last sample time and the spacing, s). Prints
//! per band the mean number of nodes, the mean prefix and its range, the mean number
//! of those without the seabed term, as lines scripts/gpu_wave_counts.py can take.
//!
//! Built with `cargo build --release --features bench --example wave_prefix_count`: the
//! examples/*.rs are behind the `bench` feature, so `cargo test` does not build them.

use cablesim::options::Backend;
use cablesim::{Overrides, Simulation};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: wave_prefix_count SCENARIO [FIRST LAST EVERY]");
    let num = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().expect("a time, s"));
    let (first, last, every) = (num(2, 10.0), num(3, 200.0), num(4, 1.0));
    let ov = Overrides {
        backend: Some(Backend::Cpu),
        duration: Some(last),
        ..Default::default()
    };
    let mut sim = Simulation::from_file(path, &ov).expect("scenario");
    let n_comps = sim
        .scenario()
        .sea_set()
        .seas
        .iter()
        .map(|s| s.components.len())
        .max();
    // Per band: node samples, the sum of their prefixes, the least and the most, the
    // sum of the prefix components without the seabed term.
    let mut per: Vec<(u64, u64, usize, usize, u64)> = Vec::new();
    let mut samples = 0u64;
    let mut t = first;
    while t <= last + 1e-9 {
        sim.advance_to(t).expect("run");
        let cpu = sim.cpu_solver().expect("the CPU path");
        for (b, m, skip) in cpu.wave_decay_prefixes() {
            if per.len() <= b {
                per.resize(b + 1, (0, 0, usize::MAX, 0, 0));
            }
            let e = &mut per[b];
            e.0 += 1;
            e.1 += m as u64;
            e.2 = e.2.min(m);
            e.3 = e.3.max(m);
            e.4 += skip as u64;
        }
        samples += 1;
        t += every;
    }
    println!(
        "{path}: {samples} samples from {first} s to {last} s every {every} s; \
         components {n_comps:?} (the elevation pass sums them all)"
    );
    println!(
        "| band | nodes (mean) | decay prefix (mean) | least | most | of it without the seabed term (mean) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    let mut nodes = Vec::new();
    let mut prefix = Vec::new();
    let mut seabed_skip = Vec::new();
    for (b, &(n, sum, lo, hi, skip)) in per.iter().enumerate() {
        if n == 0 {
            println!("| {b} | 0 | | | | |");
            continue;
        }
        let mean = sum as f64 / n as f64;
        let skip = skip as f64 / n as f64;
        println!(
            "| {b} | {:.1} | {mean:.1} | {lo} | {hi} | {skip:.1} |",
            n as f64 / samples as f64
        );
        nodes.push(format!("{b}: {:.1}", n as f64 / samples as f64));
        prefix.push(format!("{b}: {mean:.1}"));
        seabed_skip.push(format!("{b}: {skip:.1}"));
    }
    println!("nodes = {{{}}}", nodes.join(", "));
    println!("prefix = {{{}}}", prefix.join(", "));
    println!("seabed_skip = {{{}}}", seabed_skip.join(", "));
}
