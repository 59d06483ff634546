//! Nonlinear axial stiffness and cables of several sections on the GPU path against
//! the CPU reference: a polyester line with a strain-tension curve released from a
//! stretched straight start (strains over several rows of its curve, and slack where
//! it rebounds) and a chain - polyester - chain cable falling from a straight start,
//! stepped on the CPU (f64, general passes) and on the GPU (two-pass and fused kernels,
//! f64 and f32). Contract: the round-off bound of `compare` in f64; in f32 the f32
//! contract of `f32_vs_f64` (nodes within 1e-4 of the cable's length, tensions within
//! 1% plus 0.1% of the cable's largest).

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
ea_curve = [[0.005, 1.0e5], [0.01, 3.0e5], [0.02, 9.0e5], [0.03, 1.8e6], [0.05, 4.0e6]]
damping = 0.002

[[line_types]]
name = "chain"
diameter = 0.12
mass_per_length = 100.0
ea = 1.0e9
damping = 0.0005

[[cables]]
name = "rope"
line_type = "polyester"
length = 490.0
segments = 30
start = { fixed = [0.0, 0.0, -600.0] }
end = { fixed = [400.0, 0.0, -300.0] }

[[cables]]
name = "mooring"
start = { fixed = [1000.0, 0.0, -900.0] }
end = { fixed = [1500.0, 0.0, -100.0] }
sections = [
    { line_type = "chain", length = 100.0, segments = 10 },
    { line_type = "polyester", length = 800.0, segments = 20 },
    { line_type = "chain", length = 50.0, segments = 5 },
]
"#;

fn gpu_run(
    ctx: &cablesim::gpu::GpuContext,
    lay: &cablesim::model::Layout,
    pos: &[[f64; 3]],
    opts: SolverOptions,
    p: Precision,
    kernel: GpuKernel,
    steps: u64,
) -> Snapshot {
    let mut gpu = GpuSolver::new(ctx, lay.clone(), pos, opts, p).unwrap();
    gpu.set_kernel(kernel).unwrap();
    for n in [1u64, 499, steps - 500] {
        gpu.advance(n).unwrap();
    }
    Snapshot::gpu(format!("GPU {} {}", p.name(), kernel.name()), &mut gpu)
}

fn compare(p: Precision) {
    let name = format!(
        "tabulated_and_sectioned_lines_gpu_match_cpu_in_{}",
        p.name()
    );
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let sc = Scenario::parse(SCENARIO, Path::new("/tmp/axial_gpu.toml")).unwrap();
    let (lay, pos) = cablesim::model::Layout::build(&sc.model).unwrap();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = 2000;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.advance(steps).unwrap();
    let reference = Snapshot::cpu("CPU f64", &mut cpu);
    // It does what it is meant to: the rope's strains run past its curve's second row,
    // and the cable of sections moves.
    let rope_eps = lay.cables[0]
        .elements
        .iter()
        .map(|&e| {
            let (a, b) = (
                lay.elem_a[e as usize] as usize,
                lay.elem_b[e as usize] as usize,
            );
            super::compare::dist(reference.r[a], reference.r[b]) / lay.elem_l0[e as usize] - 1.0
        })
        .fold(0.0, f64::max);
    assert!(rope_eps > 0.01, "{name}: largest rope strain {rope_eps}");
    let moved = lay.cables[1]
        .nodes
        .iter()
        .map(|&n| super::compare::dist(reference.r[n as usize], pos[n as usize]))
        .fold(0.0, f64::max);
    assert!(moved > 0.1, "{name}: the sectioned cable moved {moved} m");
    let eps = match p {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    };
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    let ea = lay.line_coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let g = gpu_run(&ctx, &lay, &pos, opts, p, kernel, steps);
        match p {
            Precision::F64 => {
                let bounds =
                    RoundOff::new(&lay, &reference, steps, eps, ea, l0_min, 2.0 / bound.dt);
                let d = bounds.check(&name, &lay, &g, &reference);
                eprintln!("{name} ({}): {}", kernel.name(), d.report(&lay));
            }
            Precision::F32 => {
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
fn tabulated_and_sectioned_lines_gpu_match_cpu_in_f64() {
    compare(Precision::F64);
}

#[test]
fn tabulated_and_sectioned_lines_gpu_match_cpu_in_f32() {
    compare(Precision::F32);
}
