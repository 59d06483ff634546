//! Bending stiffness on the GPU path against the CPU reference
//! (docs/src/model/bending.md): MoorDyn's test beam (10 m, EI 1e7 N m^2, in air)
//! pinned at both ends, clamped at one end (a cantilever) and clamped at both ends
//! along tilted directions, each released straight in gravity so that it swings
//! about its bent shape; and a hanging cable with bending stiffness in water, read
//! from a scenario file, its top driven round a circle through a current, an end mass
//! below. Stepped on the CPU (f64, general passes) and on the GPU (two-pass and fused
//! kernels, f64 and f32). Contract: the round-off bound of `compare` in f64; in f32
//! the f32 contract of `f32_vs_f64` (nodes within 1e-4 of the cable's length, end
//! forces within 1% plus 0.1% of the cable's larger one). Each case first shows that its
//! bending matters: the same run without `EI` ends elsewhere by far more than the
//! tolerances.

use super::common::*;
use super::compare::{end_forces, nodes_within_length, Check, Place, RoundOff, Snapshot};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::model::{Clamp, Environment, Layout, LineType, ModelDef, PointMass, Route, Seabed};
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use std::path::Path;

const L: f64 = 10.0;
const Z0: f64 = 10.0;

/// MoorDyn's test beam, in air.
fn beam(n: usize, pinned_b: bool, clamps: &[(bool, [f64; 3])]) -> ModelDef {
    let env = Environment {
        gravity: 9.80665,
        water_density: 0.0,
        depth: f64::INFINITY,
        seabed: Seabed::default(),
    };
    let lt = LineType {
        name: "beam".into(),
        diameter: 0.05,
        mass_per_length: 100.0,
        ea: 1e8,
        damping: 1e-4,
        cn: 0.0,
        ct: 0.0,
        cm: 0.0,
        cat: 0.0,
        ei: 1e7,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    let (a, b) = ([0.0, 0.0, Z0], [L, 0.0, Z0]);
    let mut def = straight_cable(
        env,
        lt,
        a,
        b,
        L,
        n,
        Some(Route::Fixed { position: a }),
        pinned_b.then_some(Route::Fixed { position: b }),
        PointMass::default(),
        [0.0; 3],
    );
    for &(end_b, t) in clamps {
        let k = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
        def.clamps.push(Clamp {
            cable: 0,
            end_b,
            tangent: t.map(|x| x / k),
        });
    }
    def
}

/// A hanging cable with bending stiffness (a power cable's numbers) in 60 m of water:
/// its top driven round a circle, a 300 kg mass on its free lower end, a current.
const HANGING: &str = r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0
backend = "cpu"

[environment]
depth = 60.0
current = [0.8, 0.2, 0.0]

[[line_types]]
name = "power_cable"
diameter = 0.12
mass_per_length = 30.0
ea = 1.0e8
ei = 1.0e5
damping = 1.0e-3
cn = 1.2
ct = 0.01
cm = 1.0

[[cables]]
name = "riser"
line_type = "power_cable"
length = 40.0
segments = 20
start = { route = "circle", center = [0.0, 0.0, -5.0], diameter = 6.0, period = 8.0 }
end = { free = [3.0, 0.0, -45.0], mass = 300.0, volume = 0.04, drag_area = 0.3, added_mass = 0.5 }
initial = "straight"
"#;

fn hanging() -> ModelDef {
    Scenario::parse(HANGING, Path::new("/tmp/bending_gpu.toml"))
        .unwrap()
        .model
}

fn gpu_run(
    ctx: &cablesim::gpu::GpuContext,
    lay: &Layout,
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

fn cpu_run(lay: &Layout, pos: &[[f64; 3]], opts: SolverOptions, steps: u64) -> Snapshot {
    let mut cpu = CpuSolver::new(lay.clone(), pos, opts);
    cpu.advance(steps).unwrap();
    Snapshot::cpu("CPU f64", &mut cpu)
}

fn compare(p: Precision) {
    let name = format!("bending_gpu_matches_cpu_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let cases: Vec<(&str, ModelDef)> = vec![
        ("pinned beam", beam(20, true, &[])),
        ("cantilever", beam(20, false, &[(false, [1.0, 0.0, 0.0])])),
        (
            "beam clamped at both ends",
            beam(
                16,
                true,
                &[(false, [1.0, 0.2, 0.3]), (true, [1.0, -0.1, -0.4])],
            ),
        ),
        ("hanging cable", hanging()),
    ];
    let eps = match p {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    };
    let steps = 2000;
    for (case, def) in cases {
        let (lay, pos) = Layout::build(&def).unwrap();
        assert!(!lay.hinges().is_empty(), "{case}: no hinges");
        assert_eq!(cablesim::gpu::solver::unsupported_bending(&lay), None);
        let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
        let opts = SolverOptions {
            dt: 0.8 * bound.dt,
            ..Default::default()
        };
        let reference = cpu_run(&lay, &pos, opts, steps);
        let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
        let ea = lay.line_coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
        let length: f64 = lay.elem_l0.iter().sum();
        // Bending matters here: without it the same run ends far away.
        let mut flat = def.clone();
        flat.line_types[0].ei = 0.0;
        flat.clamps.clear();
        let (lay0, _) = Layout::build(&flat).unwrap();
        let plain = cpu_run(&lay0, &pos, opts, steps);
        let moved = reference
            .r
            .iter()
            .zip(&plain.r)
            .map(|(a, b)| super::compare::dist(*a, *b))
            .fold(0.0, f64::max);
        eprintln!("{name}, {case}: {steps} steps of {:.3e} s; without EI the nodes end up to {moved:.3e} m away", opts.dt);
        assert!(
            moved > 1e-3 * length,
            "{case}: bending moved the nodes {moved} m only"
        );
        for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
            let g = gpu_run(&ctx, &lay, &pos, opts, p, kernel, steps);
            let label = format!("{name}, {case}");
            match p {
                Precision::F64 => {
                    let bounds =
                        RoundOff::new(&lay, &reference, steps, eps, ea, l0_min, 2.0 / bound.dt);
                    let d = bounds.check(&label, &lay, &g, &reference);
                    eprintln!("{label} ({}): {}", kernel.name(), d.report(&lay));
                }
                Precision::F32 => {
                    let check = Check::new(&label, &lay, &g, &reference);
                    let r = nodes_within_length(&check, &g.r, &reference.r, 1e-4);
                    // The end forces (what end_forces.csv reports): the supports'
                    // reactions, where the bending shear is most of the load.
                    let (fg, fc) = (end_forces(&lay, &g.eval), end_forces(&lay, &reference.eval));
                    let fmax = fc
                        .iter()
                        .map(|f| super::compare::norm(*f))
                        .fold(0.0, f64::max);
                    let f = check.within("end forces", "N", Place::CableEnd, &fg, &fc, |k| {
                        0.01 * super::compare::norm(fc[k]) + 1e-3 * fmax
                    });
                    eprintln!(
                        "{label} ({}): positions within {r:.2e} of the length, end forces {:.2e} N of {fmax:.3e} N",
                        kernel.name(),
                        f.map_or(0.0, |f| f.diff)
                    );
                }
            }
        }
    }
}

#[test]
fn bending_gpu_matches_cpu_in_f64() {
    compare(Precision::F64);
}

#[test]
fn bending_gpu_matches_cpu_in_f32() {
    compare(Precision::F32);
}
