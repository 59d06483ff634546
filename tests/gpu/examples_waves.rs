//! Parity under waves on every example: each `examples/*.toml`, in its own sea or, where
//! it has no wave train, in a short regular sea added here ([`with_sea`]), runs a short
//! time on the CPU and on the GPU in f64 (both through `Simulation`, the GPU at the
//! CPU's step; lavapipe in CI) and the node positions are compared. Chains agree to
//! round-off: within `1e-9` of their cable's length. Nets in waves are chaotic (slack
//! twines turn round-off into visible differences within seconds: `net_cage_waves`
//! moves by 2e-2 of its length in 30 s for a 5e-14 change of the step), so theirs is
//! compared with the CPU's own envelope, the same CPU run with the step changed by
//! `1e-13` of itself: the GPU within ten times that, plus `1e-9` of the net's size. So
//! are the chains listed in [`AMPLIFIES`], whose own envelope is asserted to be above
//! the chains' `1e-9` (the CPU cannot meet it against itself): the paper's Case 1
//! (`case1_screw`), a cable released straight and vertical in a 1 m/s current with a
//! free end, amplifies round-off about 1e10-fold in its first second, in still water as
//! in waves (the CPU against itself: 2.6e-3 m of 200 m in still water, 5.7e-3 m in
//! waves); Case 2 on its screw route (`case2_screw`), to 2e-8 of its length in 1 s. (The other chains' envelopes are no measure of chaos: a changed
//! step moves the waves cache's refresh steps and a winch's remeshing steps, which
//! changes the fleets by up to 1e-3 of a length; their GPU runs, at the CPU's own
//! step, keep to round-off.) The sea's start-up ramp is removed (the waves act in full from the first
//! step, or a short run would hardly see them; where the sea is added, every line type
//! gets a tangential added mass too), and for the examples that keep to
//! round-off a still-water run of the same example must differ from the waves' by far
//! more than the tolerance (the comparison shows that both paths apply the waves).

use super::common::*;
use cablesim::gpu::Precision;
use cablesim::options::{Backend, Overrides};
use cablesim::scenario::Scenario;
use cablesim::sim::Simulation;
use std::path::{Path, PathBuf};

/// The chains whose dynamics amplify round-off, compared as the nets are.
const AMPLIFIES: [&str; 2] = ["case1_screw.toml", "case2_screw.toml"];

/// Simulated time of each run, s: 1 s, 0.2 s for the examples of more than 3000 nodes
/// (the net cage, the winch fleet) and 0.05 s for those of more than 20,000 (the fleet
/// of 716 lines), whose steps take lavapipe longest.
fn duration(sc: &Scenario) -> f64 {
    match sc.model.nodes.len() {
        n if n > 20_000 => 0.05,
        n if n > 3000 => 0.2,
        _ => 1.0,
    }
}

/// Every example scenario, in name order.
fn examples() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    v.sort();
    v
}

/// The example's text with a wave train where it has none: a regular wave 2 m high of
/// 8 s travelling 30 degrees off +x (a study's base scenario has its sea's settings but
/// no train; the still-water examples have neither); and then a tangential added mass
/// on every line type (`cat = 0.7`), so that the comparison covers it on every path
/// (chains, nets, winch cables).
fn with_sea(text: &str) -> (String, bool) {
    if text.contains("[[environment.waves.trains]]") {
        return (text.to_string(), false);
    }
    let mut t = text.replace("[[line_types]]\n", "[[line_types]]\ncat = 0.7\n");
    if !t.contains("[environment.waves]") {
        t.push_str("\n[environment.waves]\nramp = 0.0\n");
    }
    t.push_str(
        "\n[[environment.waves.trains]]\ntype = \"regular\"\nheight = 2.0\nperiod = 8.0\ndirection = 30.0\n",
    );
    (t, true)
}

/// The example's text with the waves' ramp removed (`ramp = 0.0` in
/// `[environment.waves]`) and, with `still`, its waves removed too.
fn edited(text: &str, still: bool) -> String {
    let mut out = String::new();
    let mut in_waves = false;
    let mut skipping = false;
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with('[') {
            in_waves = t.starts_with("[environment.waves]");
            skipping = still && t.starts_with("[[environment.waves.");
        }
        if still && (in_waves || skipping) {
            continue;
        }
        if in_waves && t.starts_with("ramp") {
            out.push_str("ramp = 0.0\n");
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// Every node's position of a run of `sc` to [`duration`] with `o`, cable by cable.
fn run(sc: &Scenario, o: Overrides) -> (f64, Vec<Vec<[f64; 3]>>) {
    let t = duration(sc);
    let o = Overrides {
        duration: Some(1.0),
        ..o
    };
    let mut sim = Simulation::new(sc.clone(), &o).unwrap();
    sim.advance_to(t).unwrap();
    let snap = sim.snapshot().unwrap();
    assert!(
        (snap.time - t).abs() < 2.0 * sim.dt(),
        "stopped at {}",
        snap.time
    );
    (
        sim.dt(),
        snap.cables.into_iter().map(|c| c.positions).collect(),
    )
}

/// The largest distance between two runs' nodes, relative to each cable's length
/// (`scale` per cable), and where.
fn worst(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>], scale: &[f64]) -> (f64, usize, usize) {
    let mut w = (0.0, 0, 0);
    for (ci, (ca, cb)) in a.iter().zip(b).enumerate() {
        assert_eq!(ca.len(), cb.len());
        for (k, (p, q)) in ca.iter().zip(cb).enumerate() {
            let d = dist(*p, *q) / scale[ci];
            if d > w.0 {
                w = (d, ci, k);
            }
        }
    }
    w
}

#[test]
fn gpu_matches_cpu_in_f64_on_every_example_with_waves() {
    let name = "gpu_matches_cpu_in_f64_on_every_example_with_waves";
    let Some(_ctx) = gpu_context(name, true) else {
        return;
    };
    let examples = examples();
    assert!(examples.len() >= 16, "{examples:?}");
    for path in examples {
        let (text, added) = with_sea(&std::fs::read_to_string(&path).unwrap());
        let sc = Scenario::parse(&edited(&text, false), &path).unwrap();
        assert!(!sc.sea.is_still(), "{}: no waves", path.display());
        let net = text.contains("[[nets]]");
        let lengths: Vec<f64> = sc.model.cables.iter().map(|c| c.l0.iter().sum()).collect();
        // A net's nodes against the net's size (its longest twine line), a chain's
        // against its cable's length.
        let size = lengths.iter().fold(0.0f64, |m, &l| m.max(l));
        let scale: Vec<f64> = if net {
            vec![size; lengths.len()]
        } else {
            lengths
        };
        let cpu_o = Overrides {
            backend: Some(Backend::Cpu),
            ..Overrides::default()
        };
        let t0 = std::time::Instant::now();
        let (dt, cpu) = run(&sc, cpu_o.clone());
        let t_cpu = t0.elapsed().as_secs_f64();
        let t0 = std::time::Instant::now();
        let (_, gpu) = run(
            &sc,
            Overrides {
                backend: Some(Backend::Gpu),
                precision: Some(Precision::F64),
                dt: Some(dt),
                ..Overrides::default()
            },
        );
        let t_gpu = t0.elapsed().as_secs_f64();
        let still = Scenario::parse(&edited(&text, true), &path).unwrap();
        assert!(still.sea.is_still());
        let (_, calm) = run(
            &still,
            Overrides {
                dt: Some(dt),
                ..cpu_o.clone()
            },
        );
        let (d, ci, k) = worst(&gpu, &cpu, &scale);
        let (waves, _, _) = worst(&calm, &cpu, &scale);
        let (_, nudged) = run(
            &sc,
            Overrides {
                dt: Some(dt * (1.0 + 1e-13)),
                ..cpu_o.clone()
            },
        );
        let (envelope, _, _) = worst(&nudged, &cpu, &scale);
        let ex = path.file_name().unwrap().to_string_lossy().into_owned();
        let chaotic = net || AMPLIFIES.contains(&ex.as_str());
        if AMPLIFIES.contains(&ex.as_str()) {
            assert!(
                envelope > 1e-9,
                "{ex}: its own envelope is only {envelope:e}"
            );
        }
        let tol = if chaotic {
            10.0 * envelope + 1e-9
        } else {
            1e-9
        };
        println!(
            "{ex}{}: dt {dt:.3e} s, GPU - CPU {d:.2e} (cable {ci}, node {k}), the CPU's own \
             envelope {envelope:.2e}, waves against still water {waves:.2e}, tolerance \
             {tol:.1e} (relative to length); CPU {t_cpu:.1} s, GPU {t_gpu:.1} s",
            if added { " (a sea added)" } else { "" }
        );
        assert!(
            d <= tol,
            "{ex}: the GPU differs from the CPU by {d:e} of the length at cable {ci}, node {k}"
        );
        assert!(
            chaotic || waves > 1e3 * tol,
            "{ex}: the waves move the nodes by only {waves:e} of the length"
        );
    }
}
