//! Free and pinned bodies and line failures on the GPU, against the CPU path
//! (`shaders/shared/free_body.wgsl`; the CPU path: `cpu::free`, `body::free`).
//!
//! 1. A subsurface buoy on three lines (6 DOF, added mass, linear damping, quadratic
//!    drag, released off its equilibrium, tilted and yawed) together with a pinned
//!    body swinging about its pin with a hanging line, in one run (two free bodies
//!    and six blocks per dispatch); one of the buoy's legs fails at a time, and the
//!    pinned body's line fails when its tension first reaches a threshold. GPU
//!    against CPU with the harness of `compare`: f64, both kernels, within the
//!    round-off contract (`10 N eps L` in position after `N` steps, and what follows
//!    for velocities, tensions and reactions); f32, both kernels, nodes within 1e-4 of
//!    the cable's length. The bodies' states (reference point, attitude) and the
//!    failures (step, tension) are compared too.
//! 2. A scenario with a free buoy and a failure through `cablesim::sim::run` on the
//!    GPU: `bodies.csv` and `summary.json`'s failures as the CPU path writes them.

use super::common::free_bodies::buoy_and_arm as scenario;
use super::common::*;
use super::compare::*;
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuContext, GpuKernel, GpuSolver, Precision};
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use std::path::Path;

fn load(dir: &Path, text: &str) -> Scenario {
    std::fs::write(dir.join("s.toml"), text).unwrap();
    Scenario::load(dir.join("s.toml")).unwrap()
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Advances in uneven calls (the failures are read back and rewritten at each).
fn advance_unevenly(steps: u64, mut f: impl FnMut(u64)) {
    let mut done = 0;
    for n in [1u64, 700, 299, 1000].iter().cycle() {
        let n = (*n).min(steps - done);
        if n == 0 {
            break;
        }
        f(n);
        done += n;
    }
}

fn parity(p: Precision) {
    let name = format!("gpu_runs_free_bodies_and_failures_like_cpu_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // Leg 0 fails at 0.4 s; the rope fails at 330 N as it snaps taut under its
    // falling clump (about 0.25 s).
    let sc = load(dir.path(), &scenario(1.0, 0.4, 330.0));
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = (1.0 / opts.dt).round() as u64;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.set_failures(&sc.failures).unwrap();
    advance_unevenly(steps, |n| cpu.advance(n).unwrap());
    let c = Snapshot::cpu("CPU f64", &mut cpu);
    let cpu_fail = cpu.failure_events();
    assert_eq!(
        cpu_fail.len(),
        2,
        "{name}: both failures fire: {cpu_fail:?}"
    );
    let cpu_bodies = cpu.dynamic_bodies();
    // The bodies moved by far more than any tolerance below.
    let b0 = &cpu_bodies[0].state;
    assert!(
        dist(b0.x.to_f64(), [0.0, 0.0, -20.0]) > 0.5,
        "{name}: the buoy should move"
    );
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    let ea = lay.line_coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
    let lengths = cable_lengths(&lay);
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let label = format!("GPU {} {}", p.name(), kernel.name());
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
        gpu.set_kernel(kernel).unwrap();
        gpu.set_failures(&sc.failures).unwrap();
        advance_unevenly(steps, |n| gpu.advance(n).unwrap());
        let g = Snapshot::gpu(&label, &mut gpu);
        // The failures: the same step, the same trigger, the tension within the
        // tension tolerance below.
        let gpu_fail = gpu.failure_events();
        assert_eq!(
            gpu_fail.len(),
            cpu_fail.len(),
            "{name} {label}: {gpu_fail:?}"
        );
        for (a, b) in gpu_fail.iter().zip(&cpu_fail) {
            assert_eq!(
                (&a.cable, &a.end, &a.trigger),
                (&b.cable, &b.end, &b.trigger)
            );
            assert!(
                (a.time - b.time).abs() < 0.5 * opts.dt,
                "{name} {label}: {a:?} against {b:?}"
            );
            let tol = if p == Precision::F64 { 1e-6 } else { 1e-3 } * b.tension;
            assert!(
                (a.tension - b.tension).abs() <= tol,
                "{name} {label}: {a:?} against {b:?}"
            );
        }
        let gb = gpu.dynamic_bodies();
        assert_eq!(gb.len(), cpu_bodies.len());
        let check = Check::new(&name, &lay, &g, &c);
        match p {
            Precision::F64 => {
                let bounds =
                    RoundOff::new(&lay, &c, steps, f64::EPSILON, ea, l0_min, 2.0 / bound.dt);
                let d = bounds.check(&name, &lay, &g, &c);
                eprintln!("{name} ({label}): {}", d.report(&lay));
                for (a, b) in gb.iter().zip(&cpu_bodies) {
                    let dx = dist(a.state.x.to_f64(), b.state.x.to_f64());
                    let da = (0..3)
                        .map(|k| (a.angles[k] - b.angles[k]).abs())
                        .fold(0.0, f64::max);
                    eprintln!(
                        "{name} ({label}): body '{}': |dx| {dx:.3e} m, |dangle| {da:.3e} rad",
                        b.body.name
                    );
                    assert!(
                        dx <= bounds.r,
                        "{name} ({label}): body '{}' off by {dx:e} m",
                        b.body.name
                    );
                    assert!(
                        da <= bounds.r,
                        "{name} ({label}): body '{}' turned by {da:e} rad",
                        b.body.name
                    );
                }
            }
            Precision::F32 => {
                let worst = nodes_within_length(&check, &g.r, &c.r, 1e-4);
                eprintln!("{name} ({label}): nodes within {worst:.3e} of their cable's length");
                let lmin = lengths.iter().cloned().fold(f64::INFINITY, f64::min);
                for (a, b) in gb.iter().zip(&cpu_bodies) {
                    let dx = dist(a.state.x.to_f64(), b.state.x.to_f64());
                    eprintln!("{name} ({label}): body '{}': |dx| {dx:.3e} m", b.body.name);
                    assert!(
                        dx <= 1e-4 * lmin,
                        "{name} ({label}): body '{}' off by {dx:e} m",
                        b.body.name
                    );
                }
            }
        }
    }
}

#[test]
fn gpu_runs_free_bodies_and_failures_like_cpu_in_f64() {
    parity(Precision::F64);
}

#[test]
fn gpu_runs_free_bodies_and_failures_like_cpu_in_f32() {
    parity(Precision::F32);
}

fn run_on(sc: &Scenario, out: &Path, backend: cablesim::scenario::Backend) {
    cablesim::sim::run(
        sc,
        &cablesim::sim::RunOptions {
            out_dir: out.to_path_buf(),
            overrides: cablesim::sim::Overrides {
                backend: Some(backend),
                precision: Some(Precision::F64),
                ..Default::default()
            },
            progress: false,
        },
    )
    .unwrap();
}

fn rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect()
}

#[test]
fn a_scenario_with_free_bodies_and_failures_writes_the_same_outputs_on_the_gpu() {
    let name = "a_scenario_with_free_bodies_and_failures_writes_the_same_outputs_on_the_gpu";
    let Some(_ctx): Option<GpuContext> = gpu_context(name, true) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let sc = load(dir.path(), &scenario(0.75, 0.3, 330.0));
    run_on(
        &sc,
        &dir.path().join("cpu"),
        cablesim::scenario::Backend::Cpu,
    );
    run_on(
        &sc,
        &dir.path().join("gpu"),
        cablesim::scenario::Backend::Gpu,
    );
    let (a, b) = (
        rows(&dir.path().join("cpu/bodies.csv")),
        rows(&dir.path().join("gpu/bodies.csv")),
    );
    assert_eq!(a.len(), b.len());
    assert!(a.len() >= 6, "{} rows", a.len());
    let mut worst = 0.0f64;
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x[0], y[0]);
        // Pose (x, y, z, roll, pitch, yaw) and velocities.
        for k in (2..8).chain(14..20) {
            worst = worst.max((x[k] - y[k]).abs());
            assert!(
                (x[k] - y[k]).abs() < 1e-6,
                "{name}: column {k}: {x:?} against {y:?}"
            );
        }
    }
    eprintln!("{name}: bodies.csv within {worst:.3e}");
    let failures = |d: &str| -> Vec<serde_json::Value> {
        let s: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join(d).join("summary.json")).unwrap(),
        )
        .unwrap();
        s["failures"].as_array().cloned().unwrap_or_default()
    };
    let (fa, fb) = (failures("cpu"), failures("gpu"));
    // Leg 0 by time (the rope may fail too: the run's initial relaxation leaves its
    // clump off its rest, as on both paths).
    assert!(
        fa.iter()
            .any(|f| f["cable"] == "leg0" && f["trigger"] == "time"),
        "{fa:?}"
    );
    assert_eq!(fa.len(), fb.len(), "{fa:?} against {fb:?}");
    for (x, y) in fa.iter().zip(&fb) {
        assert_eq!(x["cable"], y["cable"]);
        assert_eq!(x["end"], y["end"]);
        assert_eq!(x["trigger"], y["trigger"]);
        assert_eq!(x["time"], y["time"]);
        let (tx, ty) = (
            x["tension"].as_f64().unwrap(),
            y["tension"].as_f64().unwrap(),
        );
        assert!((tx - ty).abs() < 1e-6 * tx, "{x} against {y}");
    }
}
