//! The static equilibrium of free and pinned bodies with their lines
//! (`statics::bodies`, `initial = "equilibrium"`): a buoy on one weightless vertical
//! line against the closed form; the buoy on three lines against the pose it settles
//! at when released and run until at rest; a pinned arm's roll against its moment
//! balance; and `initial = "pose"` holding the body where the file puts it.

use cablesim::scenario::Scenario;
use std::path::Path;

fn rows(dir: &Path, text: &str) -> Vec<Vec<f64>> {
    std::fs::write(dir.join("s.toml"), text).unwrap();
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
    csv.lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect()
}

const RHO: f64 = 1025.0;
const G: f64 = 9.81;

/// A 3 m^3, 2000 kg buoy (centre of gravity and of buoyancy at its reference point)
/// on one vertical line of 45 m whose mass equals the water it displaces (no wet
/// weight), from an anchor at (0, 0, -50), held at (0, 0, -1) in body coordinates.
fn one_line(initial: &str, duration: f64) -> String {
    let d: f64 = 0.05;
    let m = RHO * std::f64::consts::PI * d * d / 4.0;
    format!(
        r#"
[simulation]
duration = {duration}
output_interval = {duration}
backend = "cpu"

[environment]
depth = 50.0
water_density = {RHO}
gravity = {G}

[[line_types]]
name = "rope"
diameter = {d}
mass_per_length = {m}
ea = 1.0e7
damping = 2.0e-3
cn = 1.2
ct = 0.2
cm = 1.0

[[bodies]]
name = "buoy"
motion = "free"
initial = "{initial}"
reference = [0.0, 0.0, -4.0]
offset = [2.0, -1.5, 1.0]
angles = [6.0, -5.0, 0.0]
mass = 2000.0
inertia = [2000.0, 2000.0, 3000.0]
volume = 3.0
ca = [1.0, 1.0, 1.0]
drag_area = [2.0, 2.0, 2.0]

[[cables]]
name = "tether"
line_type = "rope"
length = 45.0
segments = 15
initial = "catenary"
start = {{ fixed = [0.0, 0.0, -50.0] }}
end = {{ body = "buoy", at = [0.0, 0.0, -1.0] }}
"#
    )
}

#[test]
fn a_buoy_on_a_weightless_line_rests_where_the_closed_form_puts_it() {
    let dir = tempfile::tempdir().unwrap();
    let r = rows(dir.path(), &one_line("equilibrium", 0.1));
    let first = &r[0];
    // The line's tension is the net buoyancy; it stretches by T L0 / EA and stands
    // vertical under the buoy, which hangs level above it.
    let t = (RHO * 3.0 - 2000.0) * G;
    let z = -50.0 + 45.0 * (1.0 + t / 1.0e7) + 1.0;
    assert!(first[2].abs() < 1e-5 && first[3].abs() < 1e-5, "{first:?}");
    assert!((first[4] - z).abs() < 1e-6, "z {} against {z}", first[4]);
    assert!(first[5].abs() < 1e-4 && first[6].abs() < 1e-4, "{first:?}");
    // The line's pull on the body is the net buoyancy, straight down.
    assert!(
        (first[10] + t).abs() < 1e-6 * t,
        "fz {} against {t}",
        first[10]
    );
    // And it stays there: after 0.1 s nothing moves (a force of 1 N left on the body
    // would give it 2e-5 m/s by then).
    let last = r.last().unwrap();
    assert!(last[0] > 0.09, "{last:?}");
    for k in 14..20 {
        assert!(last[k].abs() < 1e-6, "moving: {last:?}");
    }
}

#[test]
fn initial_pose_holds_the_body_where_the_file_puts_it() {
    let dir = tempfile::tempdir().unwrap();
    let r = rows(dir.path(), &one_line("pose", 0.001));
    let first = &r[0];
    assert!((first[2] - 2.0).abs() < 1e-3 && (first[3] + 1.5).abs() < 1e-3);
    assert!(
        (first[5] - 6.0).abs() < 0.05 && (first[6] + 5.0).abs() < 0.05,
        "{first:?}"
    );
}

/// The buoy of tests/cpu/free_bodies.rs on three ropes to anchors 60 m away.
fn three_lines(initial: &str, duration: f64) -> String {
    let mut s = format!(
        r#"
[simulation]
duration = {duration}
output_interval = {duration}
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
initial = "{initial}"
reference = [0.0, 0.0, -20.0]
offset = [3.0, -2.0, 1.0]
angles = [4.0, -3.0, 5.0]
mass = 2000.0
cg = [0.3, 0.0, -0.5]
inertia = [2000.0, 2000.0, 3000.0]
volume = 3.0
ca = [1.0, 1.0, 1.0]
drag_area = [2.0, 2.0, 2.0]
force = [800.0, 300.0, 0.0]
damping = [[1500.0, 0, 0, 0, 0, 0], [0, 1500.0, 0, 0, 0, 0], [0, 0, 3000.0, 0, 0, 0], [0, 0, 0, 2.0e4, 0, 0], [0, 0, 0, 0, 2.0e4, 0], [0, 0, 0, 0, 0, 500.0]]
"#
    );
    for k in 0..3 {
        let a = (120.0 * k as f64).to_radians();
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
            60.0 * a.cos(),
            60.0 * a.sin(),
            1.5 * a.cos(),
            1.5 * a.sin()
        );
    }
    s
}

#[test]
fn the_statics_finds_the_pose_a_released_buoy_settles_at() {
    // An eccentric centre of gravity and a side force: an equilibrium off the axis,
    // heeled and turned. The statics' pose at t = 0 against the last row of a run
    // released from the file's pose (damped, 250 s).
    let dir = tempfile::tempdir().unwrap();
    let s = rows(dir.path(), &three_lines("equilibrium", 0.1));
    let dir2 = tempfile::tempdir().unwrap();
    let d = rows(dir2.path(), &three_lines("pose", 250.0));
    let (a, b) = (&s[0], d.last().unwrap());
    let a_later = s.last().unwrap();
    for k in 14..20 {
        assert!(
            b[k].abs() < 1e-4,
            "the released buoy is still moving: {b:?}"
        );
        assert!(
            a_later[k].abs() < 1e-5,
            "the statics' buoy moves: {a_later:?}"
        );
    }
    assert!(
        a[2].abs() > 0.01 && a[6].abs() > 5.0,
        "the side force and the eccentric centre of gravity move and heel it: {a:?}"
    );
    for k in 2..5 {
        assert!(
            (a[k] - b[k]).abs() < 2e-3,
            "column {k}: {} vs {}",
            a[k],
            b[k]
        );
    }
    for k in 5..8 {
        assert!(
            (a[k] - b[k]).abs() < 0.02,
            "column {k}: {} vs {}",
            a[k],
            b[k]
        );
    }
}

#[test]
fn a_pinned_arm_heels_until_its_weight_balances_the_moment() {
    // A pinned body, 500 kg with its centre of gravity 2 m below the pin, under a
    // constant moment of 2000 N m about x, a clump hanging on a rope from the pin
    // itself (no moment about it): at rest the weight's arm is M / (m g).
    let dir = tempfile::tempdir().unwrap();
    let text = r#"
[simulation]
duration = 0.1
output_interval = 0.1
backend = "cpu"

[environment]
depth = 50.0

[[line_types]]
name = "rope"
diameter = 0.02
mass_per_length = 1.0
ea = 2.0e6
damping = 1.0e-3
cn = 1.2
ct = 0.01
cm = 1.0

[[bodies]]
name = "arm"
motion = "pinned"
reference = [0.0, 0.0, -5.0]
angles = [-20.0, 5.0, 0.0]
mass = 500.0
cg = [0.0, 0.0, -2.0]
inertia = [100.0, 100.0, 100.0]
moment = [2000.0, 0.0, 0.0]

[[cables]]
name = "hang"
line_type = "rope"
length = 5.0
segments = 5
initial = "catenary"
start = { body = "arm", at = [0.0, 0.0, 0.0] }
end = { free = [0.0, 0.3, -10.0], mass = 20.0 }
"#;
    let r = rows(dir.path(), text);
    let (first, last) = (&r[0], r.last().unwrap());
    // The equilibria are a family (any turn about the line from the pin to the centre of
    // gravity): the centre of gravity, R (0, 0, -2), is where the moment balances,
    // (0, M / (m g), -sqrt(4 - (M / (m g))^2)).
    let [roll, pitch, yaw] = [first[5], first[6], first[7]].map(f64::to_radians);
    let rot = cablesim::body::kinematics::rotation(roll, pitch, yaw);
    let cg: Vec<f64> = (0..3).map(|i| -2.0 * rot[i][2]).collect();
    let arm = 2000.0 / (500.0 * 9.81);
    assert!(cg[0].abs() < 1e-5, "{cg:?}");
    assert!((cg[1] - arm).abs() < 1e-5, "{cg:?} against {arm}");
    assert!((cg[2] + (4.0 - arm * arm).sqrt()).abs() < 1e-5, "{cg:?}");
    assert!((first[4] + 5.0).abs() < 1e-12, "the pin stays: {first:?}");
    for k in 17..20 {
        assert!(last[k].abs() < 1e-5, "turning: {last:?}");
    }
}
