//! A winch run that blows up on the GPU after a remeshing inside the output interval:
//! the run goes back to the checkpoint at the interval's start (the mesh, payout and
//! state of then), installs that mesh again and replays to the step before the failure,
//! so the summary and the last frame hold the state at that step, as on the CPU path.

use super::common::{dist, gpu_context};
use cablesim::gpu::Precision;
use cablesim::options::{Backend, Overrides};
use cablesim::output::Summary;
use cablesim::scenario::Scenario;
use cablesim::{Error, MemorySink, Simulation};
use std::path::Path;

/// `examples/winch_deploy.toml` with 8 segments (a node is inserted at about 7.1 s),
/// one output interval of 10 s, and a speed limit that the clump passes at about
/// 7.2 s, after that insertion: a blow-up inside the first interval.
fn winch_blow_up() -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/winch_deploy.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text
        .replace(
            "output_interval = 1.0",
            "output_interval = 10.0\nmax_speed = 0.36",
        )
        .replace("segments = 4 ", "segments = 8 ");
    assert!(
        text.contains("max_speed") && text.contains("segments = 8 "),
        "the example changed"
    );
    Scenario::parse(&text, &path).unwrap()
}

/// Runs it on `backend`: the failure's time, the summary, and the last frame's
/// `(time, steps, positions)`.
fn run(backend: Backend) -> (f64, Summary, (f64, u64, Vec<[f64; 3]>)) {
    let o = Overrides {
        backend: Some(backend),
        precision: Some(Precision::F64),
        ..Overrides::default()
    };
    let mut sim = Simulation::new(winch_blow_up(), &o).unwrap();
    let mut sink = MemorySink::new();
    let t_fail = match sim.run_until(&mut sink, |_| {}, || false) {
        Err(Error::Diverged { time, .. }) => time,
        other => panic!("{backend:?}: expected a blow-up, got {other:?}"),
    };
    let s = sink.summary.expect("a summary");
    let last = sink.frames.last().expect("frames");
    let frame = (last.time, last.steps, last.cables[0].positions.clone());
    (t_fail, s, frame)
}

#[test]
fn a_winch_blow_up_on_the_gpu_leaves_the_state_at_the_step_before_as_on_the_cpu() {
    let name = "a_winch_blow_up_on_the_gpu_leaves_the_state_at_the_step_before_as_on_the_cpu";
    if gpu_context(name, true).is_none() {
        return;
    }
    let (tc, cpu, (_, _, rc_last)) = run(Backend::Cpu);
    let (tg, gpu, (tl, nl, rl)) = run(Backend::Gpu);
    assert_eq!((cpu.backend.as_str(), gpu.backend.as_str()), ("cpu", "gpu"));
    let dt = gpu.dt;
    println!(
        "{name}: fails at t = {tg} s on the GPU, {tc} s on the CPU; summaries at {} and {} s",
        gpu.simulated_time, cpu.simulated_time
    );
    // The same failure within a step, inside the first output interval and after the
    // cable was remeshed in it (so the replay went back to the earlier mesh).
    assert!((tg - tc).abs() <= dt * 1.0001, "GPU at {tg}, CPU at {tc}");
    assert!(
        tg < 10.0,
        "the failure at {tg} s is not inside the first interval"
    );
    let (wc, wg) = (
        cpu.cables[0].winch.as_ref().unwrap(),
        gpu.cables[0].winch.as_ref().unwrap(),
    );
    assert_eq!(wg.nodes_inserted, 1, "{wg:?}");
    assert_eq!(
        (wg.elements, wg.nodes_inserted, wg.nodes_deleted),
        (wc.elements, wc.nodes_inserted, wc.nodes_deleted)
    );
    // The summary's time and steps are the step before the failure, not the end of
    // the interval where stepping stopped.
    assert_eq!(gpu.status, "diverged");
    assert!((gpu.simulated_time - gpu.steps as f64 * dt).abs() < 1e-9);
    assert!(
        (tg - gpu.simulated_time - dt).abs() < 1e-9,
        "failure at {tg}, summary at {}",
        gpu.simulated_time
    );
    // The state is that step's: where the CPU is at the same step, the positions agree
    // far closer than one step's motion of the clump (0.36 m/s x dt = 1.2e-4 m).
    if gpu.steps == cpu.steps {
        let (rg, rc) = (&rl, &rc_last);
        assert_eq!(rg.len(), rc.len());
        let d = rg
            .iter()
            .zip(rc)
            .map(|(a, b)| dist(*a, *b))
            .fold(0.0, f64::max);
        println!("{name}: positions within {d:.2e} m of the CPU's");
        assert!(d < 1e-6, "positions {d} m from the CPU's at the same step");
        assert!(
            (wg.deployed_length - wc.deployed_length).abs() < 1e-9,
            "{wg:?} vs {wc:?}"
        );
    }
    // The last frame (the final state) stands there too.
    assert_eq!((tl, nl), (gpu.simulated_time, gpu.steps));
}
