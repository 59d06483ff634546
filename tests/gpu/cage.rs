//! A fish-farm cage's outputs on both paths: `nets.csv`'s volume, drag and collar height
//! are formed from the state each backend reads back, so the GPU's (f64, at the CPU's
//! step) match the CPU's. The collar and the sinker tube here have no bending (line
//! types of `ei = 0`), which the GPU path runs.

use super::common::*;
use cablesim::gpu::Precision;
use cablesim::options::{Backend, Overrides};
use cablesim::output::MemorySink;
use cablesim::sim::Simulation;

const CAGE: &str = r#"
[simulation]
duration = 0.6
dt = "auto"
output_interval = 0.2

[environment]
depth = 40.0
current = [0.5, 0.2, 0.0]

[[line_types]]
name = "net"
diameter = 0.03
mass_per_length = 0.76
ea = 2.0e5
damping = 1.0e-3
cn = 5.8

[[line_types]]
name = "ring"
diameter = 0.4
mass_per_length = 27.0
ea = 2.8e7

[[line_types]]
name = "tube"
diameter = 0.25
mass_per_length = 64.0
ea = 1.6e7

[[line_types]]
name = "chain"
diameter = 0.023
mass_per_length = 3.4
ea = 1.4e7

[[nets]]
name = "cage"
line_type = "net"
shape = "cylinder"
knots = [16, 5]
size = [6.0, 5.0]
top = [0.0, 0.0, 0.25]

[nets.collar]
line_type = "ring"
segments = 2

[nets.sinker_tube]
line_type = "tube"
chain_line_type = "chain"
chain_length = 1.5
every = 2
"#;

fn run(o: Overrides) -> (f64, MemorySink) {
    let mut sim = Simulation::from_toml(CAGE, "cage.toml", &o).unwrap();
    let mut sink = MemorySink::new();
    sim.run(&mut sink, |_| {}).unwrap();
    (sim.dt(), sink)
}

#[test]
fn cage_outputs_match_on_both_paths() {
    let name = "cage_outputs_match_on_both_paths";
    let Some(_ctx) = gpu_context(name, true) else {
        return;
    };
    let (dt, cpu) = run(Overrides {
        backend: Some(Backend::Cpu),
        ..Overrides::default()
    });
    let (_, gpu) = run(Overrides {
        backend: Some(Backend::Gpu),
        precision: Some(Precision::F64),
        dt: Some(dt),
        ..Overrides::default()
    });
    // Nets amplify round-off (slack twines: tests/gpu/examples_waves.rs): the CPU's
    // own envelope is the same run with the step changed by 1e-13 of itself.
    let (_, nudged) = run(Overrides {
        backend: Some(Backend::Cpu),
        dt: Some(dt * (1.0 + 1e-13)),
        ..Overrides::default()
    });
    assert_eq!(cpu.frames.len(), gpu.frames.len());
    let last = &cpu.frames.last().unwrap().nets[0];
    // The cage moved: the comparison is of a deformed, loaded cage.
    assert!(
        (last.volume_ratio - 1.0).abs() > 1e-6 && last.force[0] > 100.0,
        "{last:?}"
    );
    // The largest differences of volume (relative), drag (relative to the drag) and
    // collar height (m) between two runs.
    let diff = |x: &MemorySink, y: &MemorySink| -> [f64; 3] {
        let mut d = [0.0f64; 3];
        for (a, b) in x.frames.iter().zip(&y.frames) {
            let (a, b) = (&a.nets[0], &b.nets[0]);
            assert_eq!((&a.name, a.current), (&b.name, b.current));
            let drag = a.force[0].hypot(a.force[1]).max(1.0);
            d[0] = d[0].max((a.volume - b.volume).abs() / a.volume);
            d[1] = d[1].max((a.force[0] - b.force[0]).hypot(a.force[1] - b.force[1]) / drag);
            d[2] = d[2].max((a.collar_z - b.collar_z).abs());
        }
        d
    };
    let (g, e) = (diff(&gpu, &cpu), diff(&nudged, &cpu));
    eprintln!("GPU against CPU: {g:?}; the CPU's envelope: {e:?}");
    for k in 0..3 {
        assert!(g[k] <= 10.0 * e[k] + 1e-9, "{k}: GPU {g:?}, envelope {e:?}");
    }
    // And the outputs are no accident of the state: the frames differ from each other.
    let (f1, f2) = (&cpu.frames[1].nets[0], &cpu.frames[2].nets[0]);
    assert!(
        (f1.force[0] - f2.force[0]).abs() > 1e3 * g[1] * f2.force[0].abs(),
        "{f1:?} {f2:?}"
    );
}
