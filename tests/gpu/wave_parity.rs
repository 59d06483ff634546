//! The GPU path in waves against the CPU path: a 200-component JONSWAP sea on a line
//! whose fairlead circles through the surface (`surface::crossing_line`), both
//! kernels, f64 to round-off and f32 within the surface parity's tolerances. Both
//! paths use the per-node kinematics cache with the same refresh steps and weights.

use super::surface::crossing_line;
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::options::SolverOptions;
use cablesim::sea::cache::refresh_interval;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaSet, SeaState};

use super::common::*;

/// Hs 3 m, Tp 9 s, 200 components travelling along +x with 20 degrees of spreading
/// off it, in 30 m of water, no ramp (the waves act from the first step).
fn sea() -> SeaState {
    let depth = 30.0;
    let components = discretise(
        &Spectrum::Jonswap {
            hs: 3.0,
            tp: 9.0,
            gamma: 3.3,
        },
        &Discretisation {
            components: 200,
            direction: 0.35,
            spreading: None,
            seed: 11,
            stream: 0,
        },
        depth,
        9.81,
    );
    SeaState {
        components,
        ..SeaState::still(depth)
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The GPU path against the CPU path in [`sea`] on the crossing line; `banded`:
/// refreshed per depth band (`sea::bands`) on both, over two and a half of the
/// coarsest band's intervals (two of its refreshes), and the bands the nodes end in and
/// the breaches counted must be the same on both paths, with some nodes in a deeper
/// band than band 0.
fn parity(p: Precision, banded: bool) {
    let name = format!(
        "gpu_matches_cpu_in_waves{}_in_{}",
        if banded { "_per_depth_band" } else { "" },
        p.name()
    );
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let (lay, pos) = crossing_line();
    let opts = SolverOptions {
        dt: 2e-4,
        ..SolverOptions::default()
    };
    let sea = sea();
    let mut set = SeaSet::single(&sea);
    set.banded = banded;
    let plan = set.band_plan(0, opts.dt);
    let steps = if banded {
        assert!(plan.len() >= 2, "one band only: {plan:?}");
        (2.5 * plan.horizon() / opts.dt).ceil() as u64
    } else {
        3000u64
    };
    println!(
        "{name}: {} bands, tops {:?}, {steps} steps",
        plan.len(),
        plan.tops
    );
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.set_seas(&set, false);
    cpu.advance(steps).unwrap();
    let census = cpu.wave_band_census();
    if banded {
        println!("{name}: CPU bands {census:?}");
        assert!(
            census.nodes.len() >= 2 && census.nodes[0] < lay.n_nodes(),
            "no node in a deeper band: {census:?}"
        );
        // A normal run: no node beyond the margin, so no warning (tests/gpu/wave_breach.rs
        // forces one).
        assert_eq!(census.beyond_margin, 0, "{census:?}");
    }
    let cpu_r: Vec<[f64; 3]> = cpu.r.iter().map(|v| v.to_f64()).collect();
    let cpu_t = cpu.evaluate().unwrap().tension;
    // The same run in still water: the waves must move the line by far more than the
    // tolerances, or the comparison would not show that the GPU applies them.
    let mut still = CpuSolver::new(lay.clone(), &pos, opts);
    still.advance(steps).unwrap();
    let moved = still
        .r
        .iter()
        .zip(&cpu_r)
        .map(|(a, b)| dist(a.to_f64(), *b))
        .fold(0.0f64, f64::max);
    let above = cpu_r.iter().filter(|r| r[2] > 0.0).count();
    println!("{name}: waves move the line by up to {moved:.3e} m; {above} nodes in air");
    assert!(moved > 1e-3, "the waves barely move the line ({moved} m)");
    let length = 45.0;
    // The line's scale of tension for f32: the larger of its largest now and its
    // largest in still water (f32's tolerance is relative to the line's loads; the run may end
    // at a slack moment, whose largest tension is far under them: the banded run ends
    // after 2.5 coarsest intervals, at 2.05 s, with 30 N against 2.2 kN in still water).
    let tmax = cpu_t.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    let t_still = still
        .evaluate()
        .unwrap()
        .tension
        .iter()
        .fold(0.0f64, |m, t| m.max(t.abs()));
    let tscale = tmax.max(t_still);
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
        gpu.set_kernel(kernel).unwrap();
        gpu.set_seas(&set).unwrap();
        // Uneven calls: refreshes fall inside and at the edges of submissions.
        let mut done = 0;
        for n in [1u64, 999, 600, 1400].into_iter().cycle() {
            let n = n.min(steps - done);
            gpu.advance(n).unwrap();
            done += n;
            if done == steps {
                break;
            }
        }
        if banded {
            let g = gpu.wave_band_census().unwrap();
            assert_eq!(g, census, "{kernel:?}: bands on the GPU against the CPU");
        }
        let (r, _) = gpu.state().unwrap();
        let tension = gpu.evaluate().unwrap().tension;
        let dr = r
            .iter()
            .zip(&cpu_r)
            .map(|(a, b)| dist(*a, *b))
            .fold(0.0f64, f64::max);
        let dt = tension
            .iter()
            .zip(&cpu_t)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        println!(
            "{name} {kernel:?}: |dr| {dr:.3e} m, |dT| {dt:.3e} N (largest {tmax:.1} N, \
             in still water {t_still:.1} N)"
        );
        match p {
            Precision::F64 => {
                assert!(dr < 1e-9 * length, "{kernel:?}: |dr| {dr} m");
                assert!(dt < 1e-6 * tmax, "{kernel:?}: |dT| {dt} N");
            }
            Precision::F32 => {
                assert!(dr < 1e-4 * length, "{kernel:?}: |dr| {dr} m");
                // The tension's f32 difference follows the positions' (about 5.5e4 N
                // per m of |dr| on this line in both runs: 0.34 N at 6.2e-6 m after
                // 3,000 steps, 4.0 N at 7.0e-5 m after the banded run's 10,240, which
                // ends slack): the banded run, 3.4x as long, gets twice the share of
                // the line's scale. A band decided otherwise on the GPU moves nodes by
                // far more (the census is checked above; waves move the line by 0.4 m).
                let share = if banded { 2e-3 } else { 1e-3 };
                for (a, b) in tension.iter().zip(&cpu_t) {
                    assert!(
                        (a - b).abs() < 0.01 * b.abs() + share * tscale,
                        "{kernel:?}: tension {a} N against {b} N"
                    );
                }
            }
        }
    }
}

#[test]
fn gpu_matches_cpu_in_waves_in_f64() {
    parity(Precision::F64, false);
}

#[test]
fn gpu_matches_cpu_in_waves_in_f32() {
    parity(Precision::F32, false);
}

#[test]
fn gpu_matches_cpu_in_waves_per_depth_band_in_f64() {
    parity(Precision::F64, true);
}

#[test]
fn gpu_matches_cpu_in_waves_per_depth_band_in_f32() {
    parity(Precision::F32, true);
}

/// Output times in waves, GPU f64 against the CPU path, both kernels: evaluations (the
/// loads of a snapshot) at time 0 (where the evaluation does the cache's first
/// refresh), at every step around the cache's first two refresh times (where some
/// evaluations find the time past the cache and refresh it, as the next step would)
/// and at the end agree to the parity's tolerance (tensions within 1e-6 of the
/// largest, as `gpu_matches_cpu_in_waves_in_f64`; the nodes' forces, which carry the
/// water loads, within 1e-6 of the largest). The GPU run that evaluates ends where a
/// CPU run that never evaluates ends (outputs do not change the run), and the exact
/// sum's node forces at the CPU's states differ by more than that tolerance (the
/// comparison is of the cache's outputs, not of two exact sums).
#[test]
fn gpu_output_times_match_cpu_in_f64() {
    let name = "gpu_output_times_match_cpu_in_f64";
    let Some(ctx) = gpu_context(name, true) else {
        return;
    };
    let (lay, pos) = crossing_line();
    let opts = SolverOptions {
        dt: 2e-4,
        ..SolverOptions::default()
    };
    let sea = sea();
    let interval = refresh_interval(&sea.components, sea.cache_tolerance);
    let near = (interval / opts.dt).floor() as u64;
    let mut at = vec![0u64];
    at.extend(near - 2..=near + 3);
    at.extend(2 * near - 2..=2 * near + 3);
    at.push(3000);
    let steps = *at.last().unwrap();
    let mut quiet = CpuSolver::new(lay.clone(), &pos, opts);
    quiet.set_sea(&sea, false);
    quiet.advance(steps).unwrap();
    let length = 45.0;
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
        cpu.set_sea(&sea, false);
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, Precision::F64).unwrap();
        gpu.set_kernel(kernel).unwrap();
        gpu.set_sea(&sea).unwrap();
        // The largest differences relative to the largest value at the same time (the
        // line starts far from equilibrium: its loads fall by two orders of magnitude).
        let (mut worst_t, mut worst_f, mut exact_gap) = (0.0f64, 0.0f64, 0.0f64);
        for &k in &at {
            let n = k - cpu.steps();
            if n > 0 {
                cpu.advance(n).unwrap();
                gpu.advance(n).unwrap();
            }
            let exact = {
                let mut e = cpu.clone();
                e.set_sea(&sea, true);
                e.evaluate().unwrap()
            };
            let c = cpu.evaluate().unwrap();
            let g = gpu.evaluate().unwrap();
            let largest = |x: &[f64]| x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let tmax = largest(&c.tension);
            let dt: Vec<f64> = g
                .tension
                .iter()
                .zip(&c.tension)
                .map(|(a, b)| a - b)
                .collect();
            worst_t = worst_t.max(largest(&dt) / tmax);
            // The nodes' forces carry the water loads (the tensions do not).
            let fmax = largest(
                &c.force
                    .iter()
                    .map(|f| dist(*f, [0.0; 3]))
                    .collect::<Vec<_>>(),
            );
            let gap = |x: &[[f64; 3]]| {
                x.iter()
                    .zip(&c.force)
                    .fold(0.0f64, |m, (a, b)| m.max(dist(*a, *b)))
            };
            worst_f = worst_f.max(gap(&g.force) / fmax);
            exact_gap = exact_gap.max(gap(&exact.force) / fmax);
        }
        let (r, _) = gpu.state().unwrap();
        let dr = r
            .iter()
            .zip(&quiet.r)
            .map(|(a, b)| dist(*a, b.to_f64()))
            .fold(0.0f64, f64::max);
        println!(
            "{name} {kernel:?}: {} output times to step {steps} (refresh interval \
             {interval:.4} s), relative to the largest at each time: |dT| {worst_t:.3e}, \
             node force |dF| {worst_f:.3e}, exact sum against the cache {exact_gap:.3e}; \
             |dr| against a run without outputs {dr:.3e} m",
            at.len()
        );
        assert!(worst_t < 1e-6, "{kernel:?}: |dT| {worst_t} of the largest");
        assert!(worst_f < 1e-6, "{kernel:?}: |dF| {worst_f} of the largest");
        assert!(
            exact_gap > 1e-6,
            "{kernel:?}: the exact sum is within the tolerance too ({exact_gap})"
        );
        assert!(dr < 1e-9 * length, "{kernel:?}: |dr| {dr} m");
        for (a, b) in cpu.r.iter().zip(&quiet.r) {
            assert_eq!(a.to_f64(), b.to_f64(), "outputs changed the CPU run");
        }
    }
}

/// A scenario in a JONSWAP sea runs with `--backend gpu` (it used to be refused
/// there), and its end forces at the last output time match `--backend cpu` to
/// round-off in f64 (the same cache, the same refresh steps, per depth band on both
/// paths by default: `sea::bands`).
#[test]
fn wave_scenario_runs_on_the_gpu() {
    let Some(ctx) = gpu_context("wave_scenario_runs_on_the_gpu", true) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string("examples/catenary.toml")
        .unwrap()
        .replace(
            "[environment.seabed]",
            "[environment.waves]\n\n[[environment.waves.trains]]\ntype = \"jonswap\"\n\
             hs = 4.0\ntp = 10.0\ndirection = 20.0\n\n[environment.seabed]",
        );
    assert!(text.contains("jonswap"));
    let scen = dir.path().join("waves.toml");
    std::fs::write(&scen, text).unwrap();
    let env = format!("{:?}", ctx.info.backend).to_lowercase();
    let run = |backend: &str| {
        let out = dir.path().join(format!("out-{backend}"));
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_cablesim"))
            .arg("run")
            .arg(&scen)
            .args(["--out", out.to_str().unwrap(), "-q", "--duration", "2"])
            .args(["--backend", backend, "--precision", "f64"])
            .env("WGPU_BACKEND", &env)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "{backend}: {err}");
        let csv = std::fs::read_to_string(out.join("end_forces.csv")).unwrap();
        let last: Vec<Vec<f64>> = csv
            .lines()
            .rev()
            .take(2)
            .map(|l| l.split(',').filter_map(|x| x.parse().ok()).collect())
            .collect();
        last
    };
    let gpu = run("gpu");
    let cpu = run("cpu");
    let still = {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_cablesim"))
            .arg("run")
            .arg("examples/catenary.toml")
            .args(["--out", dir.path().join("still").to_str().unwrap(), "-q"])
            .args(["--duration", "2", "--backend", "cpu"])
            .output()
            .unwrap();
        assert!(o.status.success());
        std::fs::read_to_string(dir.path().join("still/end_forces.csv")).unwrap()
    };
    let still_end: Vec<f64> = still
        .lines()
        .last()
        .unwrap()
        .split(',')
        .filter_map(|x| x.parse().ok())
        .collect();
    println!("waves: gpu {gpu:?}\n       cpu {cpu:?}\nstill water {still_end:?}");
    for (g, c) in gpu.iter().zip(&cpu) {
        let n = c.iter().map(|x| x * x).sum::<f64>().sqrt();
        for (a, b) in g.iter().zip(c) {
            assert!((a - b).abs() < 1e-8 * n, "GPU {g:?} against CPU {c:?}");
        }
    }
    // The waves changed the fairlead force (the comparison is not of still water).
    let dz = (cpu[0].last().unwrap() - still_end.last().unwrap()).abs();
    assert!(
        dz > 1.0,
        "the waves changed the fairlead force by {dz} N only"
    );
}
