//! Seabed friction split along and across the line on the GPU path: a chain falling
//! from a straight start onto the seabed plane and onto a sloped seabed grid, with
//! `friction_axial` and `friction_transverse` apart, run by the GPU in f64 (two-pass
//! and fused kernels) against the CPU reference (general passes), to round-off; in
//! f32 within the f32 path's usual agreement.

use super::common::*;
use super::compare::{RoundOff, Snapshot};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::model::Layout;
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;

/// A 500 m chain from an anchor at x = 0 to a fairlead 470 m away (5 m aside, so the
/// line crosses the seabed obliquely), started straight; on the plane `z = -100` or on
/// a grid rising 4 degrees along x (sheared a little along y).
fn layout(grid: bool, friction: &str) -> (Layout, Vec<[f64; 3]>) {
    let dir = std::env::temp_dir().join(format!(
        "cablesim_gpu_fric_{grid}_{}_{}",
        friction.len(),
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let (bed, zf) = if grid {
        let t = 4f64.to_radians().tan();
        let xs = [-50.0, 150.0, 350.0, 600.0];
        let ys = [-50.0, 0.0, 50.0];
        let mut g = "4 3\n-50 150 350 600\n-50 0 50\n".to_string();
        for x in xs {
            for y in ys {
                g += &format!("{x} {y} {:.17e}\n", -100.0 + x * t + 0.01 * y);
            }
        }
        std::fs::write(dir.join("slope.txt"), g).unwrap();
        ("seabed_file = \"slope.txt\"", -10.0)
    } else {
        ("depth = 100.0", -40.0)
    };
    let text = format!(
        r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0

[environment]
{bed}

[environment.seabed]
stiffness = 3.0e6
damping = 3.0e4
{friction}

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
start = {{ fixed = [0.0, 0.0, -100.0] }}
end = {{ fixed = [470.0, 5.0, {zf:e}] }}
initial = "straight"
"#
    );
    let sc = Scenario::parse(&text, &dir.join("fric.toml")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    Layout::build(&sc.model).unwrap()
}

#[test]
fn gpu_matches_cpu_with_split_seabed_friction() {
    let name = "gpu_matches_cpu_with_split_seabed_friction";
    let Some(ctx) = gpu_context(name, true) else {
        return;
    };
    let steps = 4000u64;
    for grid in [false, true] {
        let (lay, pos) = layout(grid, "friction_axial = 0.1\nfriction_transverse = 0.8");
        assert!(lay.env.seabed.split_friction());
        let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
        let opts = SolverOptions {
            dt: 0.8 * bound.dt,
            ..Default::default()
        };
        let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
        cpu.advance(steps).unwrap();
        let c = Snapshot::cpu("CPU f64", &mut cpu);
        // The split matters here: the same fall with one coefficient ends elsewhere.
        let (lay_iso, _) = layout(grid, "friction = 0.8");
        let mut iso = CpuSolver::new(lay_iso, &pos, opts);
        iso.advance(steps).unwrap();
        let ci = Snapshot::cpu("CPU f64 isotropic", &mut iso);
        let apart =
            c.r.iter()
                .zip(&ci.r)
                .map(|(a, b)| dist(*a, *b))
                .fold(0.0, f64::max);
        eprintln!("{name}: grid {grid}: split against isotropic friction: {apart:.3e} m apart");
        assert!(apart > 1e-3, "the split changed nothing ({apart} m)");
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
            eprintln!("{name}: grid {grid}: {}: {}", kernel.name(), d.report(&lay));
        }
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, Precision::F32).unwrap();
        gpu.advance(steps).unwrap();
        let s = Snapshot::gpu("GPU f32", &mut gpu);
        let worst =
            s.r.iter()
                .zip(&c.r)
                .map(|(a, b)| dist(*a, *b))
                .fold(0.0, f64::max);
        eprintln!(
            "{name}: grid {grid}: f32 against CPU f64: largest position difference {worst:.3e} m"
        );
        assert!(worst < 0.01, "f32: {worst} m");
    }
}
