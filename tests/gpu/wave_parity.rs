//! The GPU path in waves against the CPU path: a 200-component JONSWAP sea on a line
//! whose fairlead circles through the surface (`surface::crossing_line`), both
//! kernels, f64 to round-off and f32 within the surface parity's tolerances. Both
//! paths use the per-node kinematics cache with the same refresh steps and weights.

use super::surface::crossing_line;
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::options::SolverOptions;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::SeaState;

use crate::common::*;

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

fn parity(p: Precision) {
    let name = format!("gpu_matches_cpu_in_waves_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let (lay, pos) = crossing_line();
    let opts = SolverOptions {
        dt: 2e-4,
        ..SolverOptions::default()
    };
    let sea = sea();
    let steps = 3000u64;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.set_sea(&sea, false);
    cpu.advance(steps).unwrap();
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
    let tmax = cpu_t.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
        gpu.set_kernel(kernel).unwrap();
        gpu.set_sea(&sea).unwrap();
        // Uneven calls: refreshes fall inside and at the edges of submissions.
        for n in [1u64, 999, 600, 1400] {
            gpu.advance(n).unwrap();
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
        println!("{name} {kernel:?}: |dr| {dr:.3e} m, |dT| {dt:.3e} N (largest {tmax:.1} N)");
        match p {
            Precision::F64 => {
                assert!(dr < 1e-9 * length, "{kernel:?}: |dr| {dr} m");
                assert!(dt < 1e-6 * tmax, "{kernel:?}: |dT| {dt} N");
            }
            Precision::F32 => {
                assert!(dr < 1e-4 * length, "{kernel:?}: |dr| {dr} m");
                for (a, b) in tension.iter().zip(&cpu_t) {
                    assert!(
                        (a - b).abs() < 0.01 * b.abs() + 1e-3 * tmax,
                        "{kernel:?}: tension {a} N against {b} N"
                    );
                }
            }
        }
    }
}

#[test]
fn gpu_matches_cpu_in_waves_in_f64() {
    parity(Precision::F64);
}

#[test]
fn gpu_matches_cpu_in_waves_in_f32() {
    parity(Precision::F32);
}

/// A scenario in a JONSWAP sea runs with `--backend gpu` (it used to be refused
/// there), and its end forces at the last output time match `--backend cpu` to
/// round-off in f64 (the same cache, the same refresh steps).
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
