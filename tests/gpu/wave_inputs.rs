//! Measured and tabulated seas on the GPU: a scenario whose waves are a table of
//! components (a CSV file) and a basin record decomposed by FFT runs on the GPU in f64
//! as on the CPU, to round-off (the `compare` harness), on both kernels; and a sea a
//! software adapter cannot loop over is refused with the reason.

use super::common::*;
use super::compare::{dist, RoundOff, Snapshot};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use cablesim::sea::{SeaSet, SeaState, WaveComponent};

const SCENARIO: &str = r#"
[simulation]
duration = 10.0
output_interval = 1.0

[environment]
depth = 40.0

[environment.waves]

[[environment.waves.trains]]
type = "components"
file = "waves.csv"

[[environment.waves.trains]]
type = "record"
file = "basin.csv"
reference = [10.0, 5.0]
direction = 20.0

[[line_types]]
name = "rope"
diameter = 0.05
mass_per_length = 3.0
ea = 5.0e6
cn = 1.2
ct = 0.01
cm = 1.0

[[cables]]
name = "riser"
line_type = "rope"
length = 62.0
segments = 30
start = { fixed = [-50.0, 0.0, -40.0] }
end = { fixed = [0.0, 0.0, -3.0] }
"#;

/// The scenario in a folder with its two wave files: 40 components (Hz, with
/// directions) and a 100 s basin record every 0.25 s.
fn scenario() -> Scenario {
    let dir = tempfile::tempdir().unwrap();
    let mut table = String::from("frequency,amplitude,phase,direction\n");
    for j in 0..40 {
        let f = 0.06 + 0.004 * j as f64;
        table += &format!(
            "{f},{},{},{}\n",
            0.02 + 0.002 * (j % 7) as f64,
            37.0 * j as f64,
            -30.0 + 1.5 * j as f64
        );
    }
    let mut record = String::from("t,eta\n");
    for i in 0..400 {
        let t = 0.25 * i as f64;
        record += &format!(
            "{t},{}\n",
            0.4 * (0.7 * t + 0.3).cos() + 0.25 * (1.05 * t).sin() + 0.05 * (2.3 * t).cos()
        );
    }
    std::fs::write(dir.path().join("waves.csv"), table).unwrap();
    std::fs::write(dir.path().join("basin.csv"), record).unwrap();
    let path = dir.path().join("riser.toml");
    std::fs::write(&path, SCENARIO).unwrap();
    Scenario::load(&path).unwrap()
}

#[test]
fn gpu_f64_runs_a_component_table_and_a_basin_record_like_the_cpu() {
    let name = "gpu_f64_runs_a_component_table_and_a_basin_record_like_the_cpu";
    let Some(ctx) = gpu_context(name, true) else {
        return;
    };
    let sc = scenario();
    assert_eq!(sc.sea.components.len(), 40 + 200);
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let opts = SolverOptions {
        dt: 2e-4,
        ..SolverOptions::default()
    };
    let steps = 3000u64;
    let set = SeaSet::single(&sc.sea);
    let omega = 2.0 / cablesim::stability::stable_step(&lay, opts.scheme, opts.baumgarte).dt;
    let l0_min = lay.elem_l0.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.set_seas(&set, false);
    cpu.advance(steps).unwrap();
    let c = Snapshot::cpu("CPU f64", &mut cpu);
    // The waves must move the line by far more than the tolerance.
    let mut still = CpuSolver::new(lay.clone(), &pos, opts);
    still.advance(steps).unwrap();
    let moved = still
        .r
        .iter()
        .zip(&c.r)
        .map(|(a, b)| dist(a.to_f64(), *b))
        .fold(0.0f64, f64::max);
    assert!(moved > 1e-3, "the waves barely move the line ({moved} m)");
    let bounds = RoundOff::new(&lay, &c, steps, f64::EPSILON, 5.0e6, l0_min, omega);
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, Precision::F64).unwrap();
        gpu.set_kernel(kernel).unwrap();
        gpu.set_seas(&set).unwrap();
        let mut done = 0;
        for n in [1u64, 999, 600, 1400].into_iter().cycle() {
            let n = n.min(steps - done);
            gpu.advance(n).unwrap();
            done += n;
            if done == steps {
                break;
            }
        }
        let g = Snapshot::gpu(format!("GPU f64 {}", kernel.name()), &mut gpu);
        let d = bounds.check(&format!("{name} ({})", kernel.name()), &lay, &g, &c);
        eprintln!(
            "{name} ({}): waves move the line by {moved:.3e} m; {}",
            kernel.name(),
            d.report(&lay)
        );
    }
}

#[test]
fn a_sea_beyond_a_software_adapters_loop_budget_is_refused() {
    let name = "a_sea_beyond_a_software_adapters_loop_budget_is_refused";
    let Some(ctx) = gpu_context(name, false) else {
        return;
    };
    if ctx.info.device_type != wgpu::DeviceType::Cpu {
        eprintln!(
            "{name}: {} is not a software adapter: nothing to refuse",
            ctx.describe()
        );
        return;
    }
    let (lay, pos) = {
        let sc = scenario();
        let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
        (lay, pos)
    };
    let sea = |n: usize| SeaState {
        components: (0..n)
            .map(|j| {
                let omega = 0.3 + 1e-4 * j as f64;
                WaveComponent {
                    amplitude: 1e-4,
                    omega,
                    k: omega * omega / 9.81,
                    direction: 0.0,
                    phase: 0.0,
                }
            })
            .collect(),
        ..SeaState::still(40.0)
    };
    let n = cablesim::gpu::SOFTWARE_MAX_COMPONENTS;
    let mut gpu = GpuSolver::new(
        &ctx,
        lay.clone(),
        &pos,
        SolverOptions::default(),
        Precision::F32,
    )
    .unwrap();
    let e = gpu.set_sea(&sea(n + 1)).unwrap_err().to_string();
    assert!(
        e.contains("software adapter") && e.contains("65,535"),
        "{e}"
    );
    gpu.set_sea(&sea(n)).unwrap();
}
