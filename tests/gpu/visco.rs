//! Viscoelastic fibre ropes on the GPU path against the CPU reference: a rope of
//! constant dynamic stiffness released from a taut straight start (it sags and rings)
//! and one of load-dependent dynamic stiffness falling from a straight start between
//! ends closer than its length, stepped on the CPU (f64, general passes) and on the
//! GPU (two-pass and fused kernels, f64 and f32), with an evaluation between the
//! submissions (which must not advance the elements' states). Contract: the round-off
//! bound of `compare` in f64, and the elements' states within 1e-9 of their largest;
//! in f32 nodes within 1e-4 of the cable's length, tensions within 1% plus 0.1% of the
//! cable's largest, states within 1% of their largest.

use super::common::*;
use super::compare::{nodes_within_length, Check, Place, RoundOff, Snapshot};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use std::path::Path;

const SCENARIO: &str = r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0
backend = "cpu"

[environment]
gravity = 9.81
water_density = 1025.0
depth = 1000.0

[[line_types]]
name = "polyester"
diameter = 0.15
mass_per_length = 40.0
ea = 2.0e7
ea_dynamic = 6.0e7
ba_static = 2.0e7
ba_dynamic = 2.0e5

[[line_types]]
name = "nylon"
diameter = 0.12
mass_per_length = 12.0
ea = 5.0e6
ea_dynamic = 8.0e6
ea_dynamic_slope = 30.0
ba_static = 3.0e6

[[cables]]
name = "taut"
line_type = "polyester"
length = 300.0
segments = 20
start = { fixed = [0.0, 0.0, -500.0] }
end = { fixed = [303.0, 0.0, -500.0] }

[[cables]]
name = "falling"
line_type = "nylon"
length = 200.0
segments = 16
start = { fixed = [1000.0, 0.0, -300.0] }
end = { fixed = [1150.0, 0.0, -250.0] }
"#;

fn gpu_run(
    ctx: &cablesim::gpu::GpuContext,
    lay: &cablesim::model::Layout,
    pos: &[[f64; 3]],
    opts: SolverOptions,
    p: Precision,
    kernel: GpuKernel,
    steps: u64,
) -> (Snapshot, Vec<f64>) {
    let mut gpu = GpuSolver::new(ctx, lay.clone(), pos, opts, p).unwrap();
    gpu.set_kernel(kernel).unwrap();
    for n in [1u64, 499, steps - 500] {
        gpu.advance(n).unwrap();
        // An evaluation between submissions leaves the states as they are.
        let _ = gpu.evaluate().unwrap();
    }
    let x = gpu.visco_states().unwrap();
    (
        Snapshot::gpu(format!("GPU {} {}", p.name(), kernel.name()), &mut gpu),
        x,
    )
}

fn compare(p: Precision) {
    let name = format!("viscoelastic_ropes_gpu_match_cpu_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let sc = Scenario::parse(SCENARIO, Path::new("/tmp/visco_gpu.toml")).unwrap();
    let (lay, pos) = cablesim::model::Layout::build(&sc.model).unwrap();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = 2000;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    for n in [1u64, 499, steps - 500] {
        cpu.advance(n).unwrap();
        let _ = cpu.evaluate().unwrap();
    }
    let x_cpu = cpu.visco_states().to_vec();
    let reference = Snapshot::cpu("CPU f64", &mut cpu);
    // It does what it is meant to: the states moved off their start (the taut rope
    // relaxed, the falling one loaded), and the ropes moved.
    let x0 = cablesim::physics::visco::visco_rest_states(&lay, |e| {
        let (a, b) = (lay.elem_a[e] as usize, lay.elem_b[e] as usize);
        super::compare::dist(pos[a], pos[b])
    });
    let xmax = x_cpu.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let changed = x_cpu
        .iter()
        .zip(&x0)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        xmax > 1e-3 && changed > 1e-3,
        "{name}: states {xmax}, changed {changed}"
    );
    for c in &lay.cables {
        let moved = c
            .nodes
            .iter()
            .map(|&n| super::compare::dist(reference.r[n as usize], pos[n as usize]))
            .fold(0.0, f64::max);
        assert!(moved > 0.1, "{name}: cable {} moved {moved} m", c.name);
    }
    let eps = match p {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    };
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    // The stiffest a rope element gets (its high-frequency stiffness).
    let ea = lay
        .line_types
        .iter()
        .map(|lt| match lt.viscoelastic {
            Some(v) => {
                let k2 = cablesim::physics::visco::visco_step_stiffness(
                    lt.ea,
                    v.ea_dynamic,
                    v.ea_dynamic_slope,
                );
                k2.max(k2 * lt.ea / (k2 - lt.ea))
            }
            None => lt.ea,
        })
        .fold(0.0, f64::max);
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let (g, x_gpu) = gpu_run(&ctx, &lay, &pos, opts, p, kernel, steps);
        let dx = x_gpu
            .iter()
            .zip(&x_cpu)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        eprintln!(
            "{name} ({}): states within {dx:.3e} (largest {xmax:.3e})",
            kernel.name()
        );
        match p {
            Precision::F64 => {
                assert!(
                    dx < 1e-9 * xmax,
                    "{name} ({}): states differ by {dx}",
                    kernel.name()
                );
                let bounds =
                    RoundOff::new(&lay, &reference, steps, eps, ea, l0_min, 2.0 / bound.dt);
                let d = bounds.check(&name, &lay, &g, &reference);
                eprintln!("{name} ({}): {}", kernel.name(), d.report(&lay));
            }
            Precision::F32 => {
                assert!(
                    dx < 1e-2 * xmax,
                    "{name} ({}): states differ by {dx}",
                    kernel.name()
                );
                let check = Check::new(&name, &lay, &g, &reference);
                nodes_within_length(&check, &g.r, &reference.r, 1e-4);
                let tmax: Vec<f64> = lay
                    .cables
                    .iter()
                    .map(|c| {
                        c.elements
                            .iter()
                            .map(|&e| reference.eval.tension[e as usize].abs())
                            .fold(0.0, f64::max)
                    })
                    .collect();
                check.within(
                    "tensions",
                    "N",
                    Place::Element,
                    &g.eval.tension,
                    &reference.eval.tension,
                    |e| {
                        0.01 * reference.eval.tension[e].abs()
                            + 1e-3 * tmax[lay.elem_cable[e] as usize]
                    },
                );
            }
        }
    }
}

#[test]
fn viscoelastic_ropes_gpu_match_cpu_in_f64() {
    compare(Precision::F64);
}

#[test]
fn viscoelastic_ropes_gpu_match_cpu_in_f32() {
    compare(Precision::F32);
}
