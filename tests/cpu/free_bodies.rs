//! Free and pinned bodies on the CPU path, with their lines: a subsurface buoy on three
//! lines released off its equilibrium settles where it is in equilibrium (the same pose
//! from two releases, on the axis of symmetry, the lines' force balancing its net
//! buoyancy), the body's properties through a scenario, what the GPU path refuses and
//! the errors of bad input.

use cablesim::scenario::Scenario;
use std::path::Path;

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

/// A buoy (3 m^3, 2000 kg) on three taut ropes (clear of the seabed) to anchors 60 m
/// away in 50 m of water.
fn buoy(offset: [f64; 3], angles: [f64; 3], duration: f64) -> String {
    let mut s = format!(
        r#"
[simulation]
duration = {duration}
output_interval = 1.0
backend = "cpu"

[environment]
depth = 50.0

[[line_types]]
name = "chain"
diameter = 0.05
mass_per_length = 2.5
ea = 1.0e7
damping = 2.0e-3
cn = 1.2
ct = 0.2
cm = 1.0

[[bodies]]
name = "buoy"
motion = "free"
initial = "pose"
reference = [0.0, 0.0, -20.0]
offset = [{}, {}, {}]
angles = [{}, {}, {}]
mass = 2000.0
cg = [0.0, 0.0, -0.5]
inertia = [2000.0, 2000.0, 3000.0]
volume = 3.0
ca = [1.0, 1.0, 1.0]
drag_area = [2.0, 2.0, 2.0]
damping = [[1500.0, 0, 0, 0, 0, 0], [0, 1500.0, 0, 0, 0, 0], [0, 0, 3000.0, 0, 0, 0], [0, 0, 0, 2.0e4, 0, 0], [0, 0, 0, 0, 2.0e4, 0], [0, 0, 0, 0, 0, 500.0]]
"#,
        offset[0], offset[1], offset[2], angles[0], angles[1], angles[2]
    );
    for k in 0..3 {
        let a = (120.0 * k as f64).to_radians();
        let (c, sn) = (a.cos(), a.sin());
        s += &format!(
            r#"
[[cables]]
name = "leg{k}"
line_type = "chain"
length = 68.0
segments = 20
initial = "catenary"
start = {{ fixed = [{}, {}, -50.0] }}
end = {{ body = "buoy", at = [{}, {}, -1.0] }}
"#,
            60.0 * c,
            60.0 * sn,
            1.5 * c,
            1.5 * sn
        );
    }
    s
}

/// Runs scenario `text` in `dir` and returns the last row of `bodies.csv`.
fn last_body_row(dir: &Path, text: &str) -> Vec<f64> {
    write(dir, "s.toml", text);
    let sc = Scenario::load(&dir.join("s.toml")).unwrap();
    let out = dir.join("out");
    cablesim::sim::run(
        &sc,
        &cablesim::sim::RunOptions {
            out_dir: out.clone(),
            overrides: Default::default(),
            progress: false,
        },
    )
    .unwrap();
    let csv = std::fs::read_to_string(out.join("bodies.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz,vx,vy,vz,wx,wy,wz"
    );
    let last = lines.last().unwrap();
    last.split(',')
        .map(|x| x.parse().unwrap_or(f64::NAN))
        .collect()
}

#[test]
fn a_buoy_on_three_lines_settles_at_its_equilibrium() {
    let dir = tempfile::tempdir().unwrap();
    let a = last_body_row(dir.path(), &buoy([4.0, 0.0, 0.0], [0.0; 3], 200.0));
    let dir2 = tempfile::tempdir().unwrap();
    let b = last_body_row(
        dir2.path(),
        &buoy([0.0, -3.0, 2.0], [6.0, -4.0, 10.0], 200.0),
    );
    // At rest.
    for row in [&a, &b] {
        for k in 14..20 {
            assert!(row[k].abs() < 1e-3, "still moving: {row:?}");
        }
    }
    // On the axis of symmetry, level, and with no yaw.
    for row in [&a, &b] {
        assert!(row[2].abs() < 0.01 && row[3].abs() < 0.01, "{row:?}");
        for k in 5..8 {
            assert!(row[k].abs() < 0.05, "angle {k}: {row:?}");
        }
    }
    // The same pose from both releases (within 1 cm and 0.01 degrees).
    for k in 2..8 {
        assert!(
            (a[k] - b[k]).abs() < 0.01,
            "column {k}: {} vs {}",
            a[k],
            b[k]
        );
    }
    // The lines' force balances the net buoyancy (the held end nodes' weight is in
    // the lines' force).
    let (rho, g) = (1025.0, 9.81);
    let net = (rho * 3.0 - 2000.0) * g;
    assert!(
        (a[10] + net).abs() < 1e-3 * net,
        "lines {} N against net buoyancy {net} N",
        a[10]
    );
    assert!(a[8].abs() < 1e-3 * net && a[9].abs() < 1e-3 * net);
    // It rose from -20 m: the lines hold it against its net buoyancy.
    assert!(a[4] > -20.0 && a[4] < -1.0, "z {}", a[4]);
}

#[test]
fn the_gpu_path_refuses_a_stiffness_matrix_by_name_and_auto_falls_back() {
    // The GPU path runs free bodies (tests/gpu/free_bodies.rs) but for a 6x6
    // stiffness matrix and a table of loads: refused by name, and `auto` runs them on
    // the CPU.
    let dir = tempfile::tempdir().unwrap();
    let stiff = "stiffness = [[1.0e3, 0, 0, 0, 0, 0], [0, 1.0e3, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]\n";
    let text = buoy([1.0, 0.0, 0.0], [0.0; 3], 2.0)
        .replace("backend = \"cpu\"", "backend = \"gpu\"")
        .replace("volume = 3.0\n", &format!("volume = 3.0\n{stiff}"));
    assert!(text.contains("stiffness"));
    write(dir.path(), "s.toml", &text);
    let sc = Scenario::load(&dir.path().join("s.toml")).unwrap();
    let e = cablesim::sim::run(
        &sc,
        &cablesim::sim::RunOptions {
            out_dir: dir.path().join("out"),
            overrides: Default::default(),
            progress: false,
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("stiffness matrix") && e.contains("buoy"), "{e}");
    let text = text.replace("backend = \"gpu\"", "backend = \"auto\"");
    write(dir.path(), "s.toml", &text);
    let sc = Scenario::load(&dir.path().join("s.toml")).unwrap();
    cablesim::sim::run(
        &sc,
        &cablesim::sim::RunOptions {
            out_dir: dir.path().join("out2"),
            overrides: Default::default(),
            progress: false,
        },
    )
    .unwrap();
}

fn error_of(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "s.toml", text);
    Scenario::load(&dir.path().join("s.toml"))
        .unwrap_err()
        .to_string()
}

#[test]
fn bad_free_body_input_names_the_key_and_value() {
    let base = buoy([0.0; 3], [0.0; 3], 1.0);
    let e = error_of(&base.replace("mass = 2000.0", "mass = 0.0"));
    assert!(
        e.contains("bodies[0] (\"buoy\").mass") && e.contains("positive"),
        "{e}"
    );
    let e = error_of(&base.replace(
        "inertia = [2000.0, 2000.0, 3000.0]",
        "inertia = [2000.0, -2000.0, 3000.0]",
    ));
    assert!(e.contains(".inertia") && e.contains("negative"), "{e}");
    let e = error_of(&base.replace(
        "inertia = [2000.0, 2000.0, 3000.0]",
        "inertia = [[2000.0, 5.0, 0.0], [0.0, 2000.0, 0.0], [0.0, 0.0, 3000.0]]",
    ));
    assert!(e.contains(".inertia") && e.contains("symmetric"), "{e}");
    let e = error_of(&base.replace("volume = 3.0", "volume = nan"));
    assert!(e.contains(".volume"), "{e}");
    let e = error_of(&base.replace("motion = \"free\"", "motion = \"floating\""));
    assert!(e.contains(".motion") && e.contains("floating"), "{e}");
    let e = error_of(&base.replace("mass = 2000.0\n", ""));
    assert!(e.contains(".mass") && e.contains("missing"), "{e}");
    // A prescribed body with a key of the free ones.
    let e = error_of(&base.replace("motion = \"free\"\n", ""));
    assert!(
        e.contains("motion = \\\"free\\\"") || e.contains("motion = \"free\""),
        "{e}"
    );
}

/// Runs scenario `text` in `dir` and returns the output directory.
fn run_in(dir: &Path, text: &str) -> std::path::PathBuf {
    write(dir, "s.toml", text);
    let sc = Scenario::load(&dir.join("s.toml")).unwrap();
    let out = dir.join("out");
    cablesim::sim::run(
        &sc,
        &cablesim::sim::RunOptions {
            out_dir: out.clone(),
            overrides: Default::default(),
            progress: false,
        },
    )
    .unwrap();
    out
}

const ROPE: &str = r#"
[simulation]
duration = 8.0
output_interval = 0.5
backend = "cpu"

[output]
positions = "all"

[[line_types]]
name = "rope"
diameter = 0.02
mass_per_length = 1.0
ea = 2.0e6
damping = 1.0e-3
cn = 1.2
ct = 0.01
cm = 1.0
"#;

fn failures_of(out: &Path) -> Vec<serde_json::Value> {
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    s["failures"].as_array().cloned().unwrap_or_default()
}

#[test]
fn an_end_fails_at_its_time_and_falls_free() {
    let dir = tempfile::tempdir().unwrap();
    let text = format!(
        r#"{ROPE}
[[cables]]
name = "span"
line_type = "rope"
length = 10.0
segments = 10
start = {{ fixed = [0.0, 0.0, -10.0] }}
end = {{ fixed = [10.0, 0.0, -10.0], mass = 50.0, fail_time = 2.0 }}
"#
    );
    let out = run_in(dir.path(), &text);
    let f = failures_of(&out);
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0]["cable"], "span");
    assert_eq!(f[0]["end"], "end");
    assert_eq!(f[0]["trigger"], "time");
    let t = f[0]["time"].as_f64().unwrap();
    assert!((2.0..2.01).contains(&t), "fired at {t}");
    // The end node (node 10) held until 2 s, then falls with its 50 kg clump.
    let pos = std::fs::read_to_string(out.join("positions.csv")).unwrap();
    let end_z = |time: f64| -> f64 {
        pos.lines()
            .skip(1)
            .map(|l| l.split(',').collect::<Vec<_>>())
            .find(|v| v[0].parse::<f64>().unwrap() == time && v[2] == "10")
            .map(|v| v[5].parse().unwrap())
            .unwrap()
    };
    assert!((end_z(2.0) + 10.0).abs() < 1e-6, "{}", end_z(2.0));
    assert!(end_z(8.0) < -12.0, "the freed end fell: z {}", end_z(8.0));
    // Held before it failed.
    assert!((end_z(1.0) + 10.0).abs() < 1e-6, "{}", end_z(1.0));
}

#[test]
fn an_end_fails_when_its_tension_first_reaches_the_threshold() {
    let dir = tempfile::tempdir().unwrap();
    // Pulled away at 1 m/s from 15 m to beyond its 20 m length.
    let text = format!(
        r#"{ROPE}
[[cables]]
name = "pulled"
line_type = "rope"
length = 20.0
segments = 10
start = {{ fixed = [0.0, 0.0, -10.0] }}
end = {{ route = "line", start = [15.0, 0.0, -10.0], velocity = [1.0, 0.0, 0.0], fail_tension = 1.0e4 }}
"#
    );
    let out = run_in(dir.path(), &text);
    let f = failures_of(&out);
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0]["trigger"], "tension");
    let (t, tension) = (
        f[0]["time"].as_f64().unwrap(),
        f[0]["tension"].as_f64().unwrap(),
    );
    assert!((1.0e4..1.05e4).contains(&tension), "tension {tension}");
    // The line is taut once the ends are 20 m apart, and 1e4 N is 10 cm more.
    assert!(t > 5.0 && t < 5.5, "fired at {t}");
}

#[test]
fn a_buoy_drifts_away_from_a_failed_leg() {
    let dir = tempfile::tempdir().unwrap();
    let text = buoy([0.0; 3], [0.0; 3], 60.0).replace(
        "end = { body = \"buoy\", at = [1.5, 0, -1.0] }",
        "end = { body = \"buoy\", at = [1.5, 0, -1.0], fail_time = 5.0 }",
    );
    assert!(text.contains("fail_time"), "the replacement matched");
    let out = run_in(dir.path(), &text);
    let f = failures_of(&out);
    assert_eq!(f.len(), 1);
    assert_eq!(f[0]["cable"], "leg0");
    let csv = std::fs::read_to_string(out.join("bodies.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    // Leg 0 held it towards +x: without it the other two pull it to -x.
    let at = |t: f64| rows.iter().find(|r| r[0] == t).unwrap();
    assert!(at(5.0)[2].abs() < 0.05, "{:?}", at(5.0));
    assert!(at(60.0)[2] < -1.0, "x {}", at(60.0)[2]);
    assert!(at(60.0)[3].abs() < 0.05, "y {}", at(60.0)[3]);
}

#[test]
fn bad_failure_input_names_the_key() {
    let e = error_of(&format!(
        r#"{ROPE}
[[cables]]
name = "c"
line_type = "rope"
length = 10.0
segments = 2
start = {{ fixed = [0.0, 0.0, -10.0] }}
end = {{ fixed = [5.0, 0.0, -10.0], fail_tension = 0.0 }}
"#
    ));
    assert!(
        e.contains("cables[0] (\"c\").end.fail_tension") && e.contains("positive"),
        "{e}"
    );
    let e = error_of(&format!(
        r#"{ROPE}
[[cables]]
name = "c"
line_type = "rope"
length = 10.0
segments = 2
start = {{ fixed = [0.0, 0.0, -10.0] }}
end = {{ free = [5.0, 0.0, -10.0], fail_time = 1.0 }}
"#
    ));
    assert!(e.contains("end.fail_time") && e.contains("free end"), "{e}");
    let e = error_of(&format!(
        r#"{ROPE}
[[cables]]
name = "c"
line_type = "rope"
length = 10.0
segments = 2
start = {{ fixed = [0.0, 0.0, -10.0] }}
end = {{ fixed = [5.0, 0.0, -10.0], fail_time = -1.0 }}
"#
    ));
    assert!(e.contains("end.fail_time") && e.contains("negative"), "{e}");
}

#[test]
fn a_pinned_body_swings_about_its_pin_with_its_line() {
    // A pinned body (centre of gravity 2 m below the pin) with a line and a clump
    // hanging from a point 1 m out, released rolled 10 degrees: the reference point
    // stays at the pin, the roll swings back through zero and decays.
    let dir = tempfile::tempdir().unwrap();
    let text = format!(
        r#"{ROPE}
[[bodies]]
name = "arm"
motion = "pinned"
reference = [0.0, 0.0, -5.0]
angles = [10.0, 0.0, 0.0]
mass = 500.0
cg = [0.0, 0.0, -2.0]
inertia = [100.0, 100.0, 100.0]
rotational_drag = [50.0, 50.0, 50.0]

[[cables]]
name = "hang"
line_type = "rope"
length = 5.0
segments = 5
start = {{ body = "arm", at = [0.0, 1.0, -0.5] }}
end = {{ free = [0.0, 1.0, -10.5], mass = 20.0 }}
"#
    )
    .replace("duration = 8.0", "duration = 20.0");
    let out = run_in(dir.path(), &text);
    let csv = std::fs::read_to_string(out.join("bodies.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    let mut crossed = false;
    for r in &rows {
        assert!(
            r[2].abs() < 1e-9 && r[3].abs() < 1e-9 && (r[4] + 5.0).abs() < 1e-9,
            "the pin moved: {r:?}"
        );
        assert!(r[14].abs() < 1e-9 && r[15].abs() < 1e-9 && r[16].abs() < 1e-9);
        crossed |= r[5] < -1.0;
    }
    assert!(crossed, "the roll swings through zero");
    let last = rows.last().unwrap();
    assert!(last[5].abs() < 5.0, "decaying: roll {}", last[5]);
}

/// The free bodies' units (each body with the blocks of its lines, stepped several
/// steps a call on the chain fast path, `CpuSolver::advance_units`) step as the
/// general passes do, one step a call: the buoy on three legs (one failing at a time)
/// and the pinned arm with its rope, joined here by a tie line between the two bodies
/// (one unit of two bodies and five blocks) and, apart, the rope's own unit. Nodes
/// and bodies within round-off of each other after 1 s, the failures at the same step.
#[test]
fn free_bodies_step_on_the_chain_path_as_on_the_general_passes() {
    use cablesim::cpu::CpuSolver;
    use cablesim::options::SolverOptions;
    let dir = tempfile::tempdir().unwrap();
    let mut text = super::common::free_bodies::buoy_and_arm(1.0, 0.4, 1.0e9);
    text += r#"
[[cables]]
name = "tie"
line_type = "rope"
length = 33.0
segments = 10
start = { body = "buoy", at = [0.0, 0.0, 0.5] }
end = { body = "arm", at = [0.0, 0.0, -1.0] }
"#;
    write(dir.path(), "s.toml", &text);
    let sc = Scenario::load(dir.path().join("s.toml")).unwrap();
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let steps = (1.0 / opts.dt).round() as u64;
    let run = |chain: bool| {
        let mut s = CpuSolver::new(lay.clone(), &pos, opts);
        s.use_chain_kernel = chain;
        s.set_failures(&sc.failures).unwrap();
        let mut done = 0;
        for n in [1u64, 700, 299, 1000].iter().cycle() {
            let n = (*n).min(steps - done);
            if n == 0 {
                break;
            }
            s.advance(n).unwrap();
            done += n;
        }
        s
    };
    let (a, b) = (run(true), run(false));
    let (fa, fb) = (a.failure_events(), b.failure_events());
    assert_eq!(fa.len(), 1, "{fa:?}");
    assert_eq!(fa.len(), fb.len());
    for (x, y) in fa.iter().zip(&fb) {
        assert_eq!((&x.cable, x.time), (&y.cable, y.time));
        assert!(
            (x.tension - y.tension).abs() <= 1e-9 * y.tension,
            "{x:?} {y:?}"
        );
    }
    let worst =
        a.r.iter()
            .zip(&b.r)
            .map(|(x, y)| (*x - *y).norm())
            .fold(0.0, f64::max);
    eprintln!("free bodies, chain path against general passes: nodes within {worst:.3e} m");
    assert!(worst < 1e-7, "nodes apart by {worst:e} m");
    let (ba, bb) = (a.dynamic_bodies(), b.dynamic_bodies());
    assert_eq!(ba.len(), 2);
    let start = CpuSolver::new(lay.clone(), &pos, opts).dynamic_bodies();
    let k = ba.iter().position(|b| b.body.name == "buoy").unwrap();
    let moved = (ba[k].state.x - start[k].state.x).norm();
    assert!(moved > 0.1, "the buoy should move off its start: {moved} m");
    for (x, y) in ba.iter().zip(&bb) {
        let d = (x.state.x - y.state.x).norm();
        let da = (0..3)
            .map(|k| (x.angles[k] - y.angles[k]).abs())
            .fold(0.0, f64::max);
        assert!(
            d < 1e-7 && da < 1e-7,
            "body '{}': {d:e} m, {da:e} rad",
            x.body.name
        );
    }
}

/// The buoy's reference point and angles, and every node, after `steps` steps of `dt`
/// in `scheme` from the start of scenario `text`, sampled every `every` steps (the
/// body's reference point).
fn run_scheme(
    text: &str,
    scheme: cablesim::options::Scheme,
    dt: f64,
    steps: u64,
    every: u64,
) -> (Vec<[f64; 3]>, Vec<f64>) {
    use cablesim::cpu::CpuSolver;
    use cablesim::options::SolverOptions;
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "s.toml", text);
    let sc = Scenario::load(dir.path().join("s.toml")).unwrap();
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let opts = SolverOptions {
        dt,
        scheme,
        ..Default::default()
    };
    let mut s = CpuSolver::new(lay, &pos, opts);
    s.set_failures(&sc.failures).unwrap();
    let mut track = Vec::new();
    let mut done = 0;
    while done < steps {
        let n = every.min(steps - done);
        s.advance(n).unwrap();
        done += n;
        let b = &s.dynamic_bodies()[0];
        track.push([b.state.x.x, b.state.x.y, b.state.x.z]);
    }
    let b = &s.dynamic_bodies()[0];
    let mut last: Vec<f64> = vec![b.state.x.x, b.state.x.y, b.state.x.z];
    last.extend(b.angles);
    for r in &s.r {
        last.extend([r.x, r.y, r.z]);
    }
    (track, last)
}

/// The stable step of scenario `text` in `scheme`.
fn stable_dt(text: &str, scheme: cablesim::options::Scheme) -> f64 {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "s.toml", text);
    let sc = Scenario::load(dir.path().join("s.toml")).unwrap();
    let (lay, _, _) = cablesim::sim::prepare(&sc).unwrap();
    cablesim::stability::stable_step(&lay, scheme, Default::default()).dt
}

/// RK4 and symplectic Euler step the moored buoy's free decay alike: the buoy released
/// 2.3 m and 13 degrees off its equilibrium, 8 s of its motion (the body and its lines
/// in the same Runge-Kutta stages) within 0.5 % of the initial offset of each other.
#[test]
fn rk4_and_symplectic_agree_on_a_moored_buoy_decay() {
    use cablesim::options::Scheme;
    let text = buoy([2.0, -1.0, 0.5], [6.0, -4.0, 10.0], 8.0);
    let dt = 0.8 * stable_dt(&text, Scheme::Symplectic).min(stable_dt(&text, Scheme::Rk4));
    let steps = (8.0 / dt).round() as u64;
    let every = steps / 32;
    let (a, _) = run_scheme(&text, Scheme::Symplectic, dt, steps, every);
    let (b, _) = run_scheme(&text, Scheme::Rk4, dt, steps, every);
    let offset = (4.0f64 + 1.0 + 0.25).sqrt();
    let dist =
        |x: &[f64; 3], y: &[f64; 3]| (0..3).map(|k| (x[k] - y[k]).powi(2)).sum::<f64>().sqrt();
    let moved = a.iter().map(|x| dist(x, &a[0])).fold(0.0, f64::max);
    assert!(moved > 0.3 * offset, "the buoy barely moves: {moved} m");
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| dist(x, y))
        .fold(0.0, f64::max);
    eprintln!("moored buoy decay, RK4 against symplectic (dt {dt:.3e} s): {worst:.3e} m apart at most, moved {moved:.3} m");
    assert!(worst < 5e-3 * offset, "RK4 and symplectic {worst} m apart");
}

/// The buoy of [`buoy`] on three taut legs to anchors 15 m from its axis, 1 m over the
/// seabed (no contact, no slack element), released off its equilibrium; without
/// quadratic drag, so that the loads are smooth (a quadratic drag `|u| u` is only once
/// differentiable where the relative velocity passes zero, which every node's does as
/// it swings: with the drag the differences fall by 2 to 4 per halving, in RK4 too).
fn taut_buoy() -> String {
    let text = buoy([0.5, -0.3, 0.2], [3.0, -2.0, 5.0], 1.0)
        .replace("cn = 1.2\nct = 0.2", "cn = 0.0\nct = 0.0")
        .replace("drag_area = [2.0, 2.0, 2.0]", "drag_area = [0.0, 0.0, 0.0]");
    let mut s = text[..text.find("[[cables]]").unwrap()].to_string();
    for k in 0..3 {
        let a = (120.0 * k as f64).to_radians();
        let (c, sn) = (a.cos(), a.sin());
        s += &format!(
            r#"
[[cables]]
name = "leg{k}"
line_type = "chain"
length = 31.07
segments = 12
start = {{ fixed = [{}, {}, -49.0] }}
end = {{ body = "buoy", at = [{}, {}, -1.0] }}
"#,
            15.0 * c,
            15.0 * sn,
            1.5 * c,
            1.5 * sn
        );
    }
    s
}

/// The order of the Runge-Kutta schemes with a free body: the taut buoy and its lines
/// over 0.4 s at steps dt, dt/2, dt/4; the differences between successive halvings fall by
/// 2^4 in RK4 (between 12 and 20 here) and 2^2 in RK2 (between 3 and 5), over the
/// body's pose and every node.
#[test]
fn rk_schemes_with_a_free_body_converge_at_their_order() {
    use cablesim::options::Scheme;
    let text = taut_buoy();
    let dt = 0.5 * stable_dt(&text, Scheme::Rk2).min(stable_dt(&text, Scheme::Rk4));
    let t = 0.4;
    for (scheme, lo, hi) in [(Scheme::Rk4, 12.0, 20.0), (Scheme::Rk2, 3.0, 5.0)] {
        let finals: Vec<Vec<f64>> = [1u64, 2, 4]
            .iter()
            .map(|&m| {
                let h = dt / m as f64;
                let steps = (t / h).round() as u64;
                run_scheme(&text, scheme, t / steps as f64, steps, steps).1
            })
            .collect();
        let diff = |x: &[f64], y: &[f64]| {
            x.iter()
                .zip(y)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        let (d1, d2) = (diff(&finals[0], &finals[1]), diff(&finals[1], &finals[2]));
        let ratio = d1 / d2;
        eprintln!("{scheme:?} with a free body: differences {d1:.3e}, {d2:.3e}, ratio {ratio:.2}");
        assert!(
            d2 > 0.0 && (lo..hi).contains(&ratio),
            "{scheme:?}: ratio {ratio} ({d1:e}, {d2:e})"
        );
    }
}

/// The buoy and the pinned arm of the shared set-up under RK4 and RK2 through a
/// scenario file (`scheme`): the failures fire (by time and by tension) as under the
/// symplectic scheme, and the arm's roll 1 s later agrees within 0.2 degrees.
#[test]
fn rk_schemes_run_free_and_pinned_bodies_with_failures() {
    let dir = tempfile::tempdir().unwrap();
    let base = super::common::free_bodies::buoy_and_arm(1.5, 0.3, 330.0);
    let mut rolls = Vec::new();
    for scheme in ["symplectic", "rk4", "rk2"] {
        let text = base.replace(
            "backend = \"cpu\"",
            &format!("backend = \"cpu\"\nscheme = \"{scheme}\""),
        );
        let sub = dir.path().join(scheme);
        std::fs::create_dir_all(&sub).unwrap();
        let out = run_in(&sub, &text);
        let f = failures_of(&out);
        assert_eq!(f.len(), 2, "{scheme}: {f:?}");
        let csv = std::fs::read_to_string(out.join("bodies.csv")).unwrap();
        let last = csv
            .lines()
            .filter(|l| l.contains(",arm,"))
            .last()
            .unwrap()
            .to_string();
        let roll: f64 = last.split(',').nth(5).unwrap().parse().unwrap();
        rolls.push(roll);
    }
    eprintln!("arm roll at the end: symplectic, RK4, RK2: {rolls:?}");
    for r in &rolls[1..] {
        assert!((r - rolls[0]).abs() < 0.2, "rolls {rolls:?}");
    }
    assert!(
        (rolls[0] - 10.0).abs() > 0.5,
        "the arm should swing: {rolls:?}"
    );
}
