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
    assert_eq!(cpu.frames.len(), gpu.frames.len());
    let last = &cpu.frames.last().unwrap().nets[0];
    // The cage moved: the comparison is of a deformed, loaded cage.
    assert!((last.volume_ratio - 1.0).abs() > 1e-6 && last.force[0] > 100.0, "{last:?}");
    for (a, b) in cpu.frames.iter().zip(&gpu.frames) {
        let (a, b) = (&a.nets[0], &b.nets[0]);
        assert_eq!(a.name, b.name);
        let rel = |x: f64, y: f64, s: f64| (x - y).abs() / s;
        let drag = a.force[0].hypot(a.force[1]).max(1.0);
        assert!(rel(a.volume, b.volume, a.volume) < 1e-9, "{a:?} {b:?}");
        assert!(rel(a.force[0], b.force[0], drag) < 1e-6, "{a:?} {b:?}");
        assert!(rel(a.force[1], b.force[1], drag) < 1e-6, "{a:?} {b:?}");
        assert!((a.collar_z - b.collar_z).abs() < 1e-9, "{a:?} {b:?}");
        assert_eq!(a.current, b.current);
    }
}
