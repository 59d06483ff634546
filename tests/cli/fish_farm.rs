//! The fish-farm cage (examples/fish_farm.toml, docs/src/cage.md): a short run of the
//! example at two current speeds and in still water; the cage's keys' errors and the
//! collar's flotation warning.

use cablesim::output::MemorySink;
use cablesim::scenario::Scenario;
use cablesim::{Overrides, Simulation};
use std::f64::consts::PI;
use std::path::Path;

const EXAMPLE: &str = "examples/fish_farm.toml";

fn example() -> String {
    std::fs::read_to_string(EXAMPLE).unwrap()
}

/// The example with a uniform current of `u` m/s along +x.
fn with_current(u: f64) -> String {
    let text = example();
    assert!(text.contains("current = [0.5, 0.0, 0.0]"));
    text.replace(
        "current = [0.5, 0.0, 0.0]",
        &format!("current = [{u}, 0.0, 0.0]"),
    )
}

fn run(text: &str, duration: f64) -> MemorySink {
    let overrides = Overrides {
        duration: Some(duration),
        ..Default::default()
    };
    let mut sim = Simulation::from_toml(text, EXAMPLE, &overrides).unwrap();
    let mut sink = MemorySink::new();
    sim.run(&mut sink, |_| {}).unwrap();
    sink
}

/// The mean over the frames from `t0` on of `f` of the cage's row.
fn mean_after(sink: &MemorySink, t0: f64, f: impl Fn(&cablesim::output::NetState) -> f64) -> f64 {
    let v: Vec<f64> = sink
        .frames
        .iter()
        .filter(|s| s.time >= t0)
        .map(|s| {
            assert_eq!(s.nets.len(), 1);
            f(&s.nets[0])
        })
        .collect();
    assert!(!v.is_empty());
    v.iter().sum::<f64>() / v.len() as f64
}

/// In current the cage deflects: the volume it encloses falls as the current rises, and
/// the drag on its net grows; at the start (the cage as generated) the ratio is 1. The
/// runs are short (16 s) and the cage not settled (docs/src/cage.md, "A current
/// sweep"): what is asserted is the order, at the same time after the start.
#[test]
fn fish_farm_volume_falls_with_current_speed() {
    let (t, t0) = (16.0, 10.0);
    let slow = run(&with_current(0.2), t);
    let fast = run(&with_current(0.6), t);
    for s in [&slow, &fast] {
        let first = &s.frames[0].nets[0];
        assert!(
            (first.volume_ratio - 1.0).abs() < 1e-9,
            "{}",
            first.volume_ratio
        );
    }
    let (v_slow, v_fast) = (
        mean_after(&slow, t0, |n| n.volume_ratio),
        mean_after(&fast, t0, |n| n.volume_ratio),
    );
    let (d_slow, d_fast) = (
        mean_after(&slow, t0, |n| n.force[0].hypot(n.force[1])),
        mean_after(&fast, t0, |n| n.force[0].hypot(n.force[1])),
    );
    eprintln!("volume ratio {v_slow} at 0.2 m/s, {v_fast} at 0.6 m/s; drag {d_slow} N, {d_fast} N");
    assert!(
        v_fast < v_slow && v_slow < 1.0,
        "volume ratios {v_slow}, {v_fast}"
    );
    assert!(v_fast > 0.3, "{v_fast}");
    // The drag grows with the speed (about as its square, less as the net yields).
    assert!(
        d_fast > 3.0 * d_slow && d_slow > 0.0,
        "drag {d_slow} N, {d_fast} N"
    );
    // Along the current.
    let fx = mean_after(&fast, t0, |n| n.force[0]);
    assert!(fx > 0.99 * d_fast, "{fx} of {d_fast}");
}

/// In still water the collar floats where its buoyancy carries its load: the hand
/// calculation of docs/src/cage.md, from the example's numbers (the lengths and line
/// types as the scenario builds them), with the bridles' pull read from the run.
#[test]
fn fish_farm_collar_floats_at_its_freeboard() {
    let text = with_current(0.0);
    let sc = Scenario::parse(&text, Path::new(EXAMPLE)).unwrap();
    let m = &sc.model;
    let (g, rho) = (m.env.gravity, m.env.water_density);
    let lt = |name: &str| m.line_types.iter().find(|l| l.name == name).unwrap();
    // Sum of unstretched lengths of the cables whose names start with `prefix`.
    let length = |prefix: &str| -> f64 {
        m.cables
            .iter()
            .filter(|c| c.name.starts_with(prefix))
            .map(|c| c.l0.iter().sum::<f64>())
            .sum()
    };
    let wet = |name: &str| {
        let l = lt(name);
        (l.mass_per_length - rho * PI * l.diameter.powi(2) / 4.0) * g
    };
    // The collar: 400 mm pipe, 24 mm wall, HDPE 950 kg/m^3.
    let (d, t) = (0.4f64, 0.024);
    let m_collar = 950.0 * PI / 4.0 * (d * d - (d - 2.0 * t).powi(2));
    let l_collar = length("cage.collar.");
    // 32 knots, 2 elements between two: the 64-gon of radius 10 m.
    assert!((l_collar - 64.0 * 2.0 * 10.0 * (PI / 64.0).sin()).abs() < 1e-6);
    // The sinker tube: 250 mm, 23 mm wall, flooded, 15 kg/m of ballast.
    let (dt, tt) = (0.25f64, 0.023);
    let bore = PI / 4.0 * (dt - 2.0 * tt).powi(2);
    let m_tube = 950.0 * PI / 4.0 * (dt * dt - (dt - 2.0 * tt).powi(2)) + 15.0 + rho * bore;
    let w_tube = (m_tube - rho * PI * dt * dt / 4.0) * g * length("cage.tube.");
    let twines = length("cage.h") + length("cage.v");
    // The top row's twines lie along the collar's node line, above the water: their
    // weight in air, not in water.
    let top_row = length("cage.h0.");
    let net = lt("net");
    let load = m_collar * g * l_collar
        + w_tube
        + wet("chain13") * length("cage.chain.")
        + wet("net") * twines
        + (net.mass_per_length * g - wet("net")) * top_row;
    let capacity = rho * g * PI * d * d / 4.0 * l_collar;
    let sink = run(&text, 14.0);
    let t0 = 8.0;
    // The bridles pull the collar down: their start ends are on it.
    let pull = {
        let f: Vec<f64> = sink
            .frames
            .iter()
            .filter(|s| s.time >= t0)
            .map(|s| {
                s.cables
                    .iter()
                    .filter(|c| c.name.starts_with("bridle_"))
                    .map(|c| -c.end_forces.start[2])
                    .sum::<f64>()
            })
            .collect();
        f.iter().sum::<f64>() / f.len() as f64
    };
    assert!(pull > 0.0, "{pull}");
    let freeboard = d * (1.0 - (load + pull) / capacity);
    let z = mean_after(&sink, t0, |n| n.collar_z);
    eprintln!("collar at {z} m, hand calculation {freeboard} m (load {load} N, bridles {pull} N, buoyancy {capacity} N)");
    assert!(
        (z - freeboard).abs() < 0.005,
        "collar at {z} m, the hand calculation {freeboard} m (load {load} N, bridles {pull} N, \
         buoyancy {capacity} N)"
    );
    // And the cage keeps its shape in still water.
    let v = mean_after(&sink, t0, |n| n.volume_ratio);
    assert!(v > 0.95 && v < 1.02, "{v}");
}

/// The cage's keys: what is wrong is named.
#[test]
fn fish_farm_bad_cage_keys() {
    let bad = |from: &str, to: &str, field: &str, what: &str| {
        let text = example();
        assert!(text.contains(from), "{from}");
        let e = Scenario::parse(&text.replacen(from, to, 1), Path::new(EXAMPLE))
            .unwrap_err()
            .to_string();
        assert!(e.contains(field) && e.contains(what), "{e}");
    };
    bad(
        "chain_length = 2.0",
        "chain_length = 2.0\nradius = 13.0",
        "nets[0] (\"cage\").sinker_tube.radius",
        "more than the chains' length",
    );
    bad(
        "free = [7.0710678, 7.0710678, 0.25]",
        "free = [7.0710678, 9.0, 0.25]",
        "nets[0] (\"cage\").collar.points[0]",
        "from the nearest top knot",
    );
    bad(
        "shape = \"cylinder\"",
        "shape = \"panel\"",
        "nets[0] (\"cage\").collar",
        "needs shape = \"cylinder\"",
    );
    bad(
        "wall = 0.024",
        "wall = 0.3",
        "nets[0] (\"cage\").collar.pipe.wall",
        "thicker than half the diameter",
    );
    bad(
        "points = [\"bridle_ne\"",
        "points = [\"nowhere\"",
        "nets[0] (\"cage\").collar.points[0]",
        "no point named \"nowhere\"",
    );
}

/// A collar too small for what hangs from it: a warning with the freeboard.
#[test]
fn fish_farm_collar_that_cannot_float_warns() {
    let sinks = example().replace(
        "diameter = 0.4, wall = 0.024",
        "diameter = 0.12, wall = 0.008",
    );
    let (sc, warnings) =
        cablesim::scenario::collect_warnings(|| Scenario::parse(&sinks, Path::new(EXAMPLE)));
    sc.unwrap();
    let w = warnings
        .iter()
        .find(|w| w.contains("cannot float"))
        .unwrap_or_else(|| panic!("{warnings:?}"));
    assert!(
        w.contains("nets[0] (\"cage\").collar") && w.contains("freeboard -"),
        "{w}"
    );
    // The example's collar floats with reserve: no such warning.
    let (sc, warnings) =
        cablesim::scenario::collect_warnings(|| Scenario::parse(&example(), Path::new(EXAMPLE)));
    sc.unwrap();
    assert!(
        !warnings.iter().any(|w| w.contains("collar")),
        "{warnings:?}"
    );
}
