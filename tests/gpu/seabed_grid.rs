//! A seabed grid on the GPU path: a chain falling onto a 4 degree slope (with friction,
//! from a straight start) run by the GPU in f64 (two-pass and fused kernels) against
//! the CPU reference, to round-off; in f32 within the f32 path's usual agreement.

use super::common::*;
use super::compare::{RoundOff, Snapshot};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::model::Layout;
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;

/// A 500 m chain from an anchor on a plane seabed rising at 4 degrees along x (a 4 x 3
/// grid, sheared a little along y so that both slopes are non-zero) to a fairlead 470 m
/// away, started straight, with friction.
fn sloped_layout() -> (Layout, Vec<[f64; 3]>) {
    let dir = std::env::temp_dir().join(format!("cablesim_gpu_slope_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let t = 4f64.to_radians().tan();
    let xs = [-50.0, 150.0, 350.0, 600.0];
    let ys = [-50.0, 0.0, 50.0];
    let mut grid = "4 3\n-50 150 350 600\n-50 0 50\n".to_string();
    for x in xs {
        for y in ys {
            grid += &format!("{x} {y} {:.17e}\n", -100.0 + x * t + 0.01 * y);
        }
    }
    std::fs::write(dir.join("slope.txt"), grid).unwrap();
    let text = r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0

[environment]
seabed_file = "slope.txt"

[environment.seabed]
stiffness = 3.0e6
damping = 3.0e4
friction = 0.3

[[line_types]]
name = "chain"
diameter = 0.1
mass_per_length = 100.0
ea = 7.5e8
damping = 1.0e-3
cn = 2.4
ct = 0.4
cm = 1.0

[[cables]]
name = "line1"
line_type = "chain"
length = 500.0
segments = 25
start = { fixed = [0.0, 0.0, -100.0] }
end = { fixed = [470.0, 5.0, -10.0] }
initial = "straight"
"#;
    let sc = Scenario::parse(text, &dir.join("slope.toml")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    Layout::build(&sc.model).unwrap()
}

#[test]
fn gpu_matches_cpu_on_a_seabed_grid() {
    let name = "gpu_matches_cpu_on_a_seabed_grid";
    let Some(ctx) = gpu_context(name, true) else {
        return;
    };
    let (lay, pos) = sloped_layout();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = 4000u64;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.advance(steps).unwrap();
    let c = Snapshot::cpu("CPU f64", &mut cpu);
    // The line has fallen onto the slope: some nodes touch it, and slide on it.
    let g = lay.env.seabed.grid.unwrap();
    let grounded =
        c.r.iter()
            .filter(|p| p[2] < g.height(p[0], p[1]) + 0.01)
            .count();
    assert!(grounded >= 5, "{grounded} nodes on the seabed");
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    let ea = lay.line_coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
    let bounds = RoundOff::new(&lay, &c, steps, f64::EPSILON, ea, l0_min, 2.0 / bound.dt);
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, Precision::F64).unwrap();
        gpu.set_kernel(kernel).unwrap();
        for n in [1u64, 1499, 2500] {
            gpu.advance(n).unwrap();
        }
        let s = Snapshot::gpu(format!("GPU f64 {}", kernel.name()), &mut gpu);
        let d = bounds.check(name, &lay, &s, &c);
        eprintln!(
            "{name}: {}: {grounded} nodes grounded; {}",
            kernel.name(),
            d.report(&lay)
        );
    }
    // f32: the same fall, to within 1 cm (the f32 path's rounding over 4000 steps).
    let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, Precision::F32).unwrap();
    gpu.advance(steps).unwrap();
    let s = Snapshot::gpu("GPU f32", &mut gpu);
    let worst =
        s.r.iter()
            .zip(&c.r)
            .map(|(a, b)| dist(*a, *b))
            .fold(0.0, f64::max);
    eprintln!("{name}: f32 against CPU f64: largest position difference {worst:.3e} m");
    assert!(worst < 0.01, "f32: {worst} m");
}
