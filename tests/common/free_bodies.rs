//! The free-body scenarios several test modules run (`tests/cpu/free_bodies.rs`,
//! `tests/gpu/free_bodies.rs`).

/// A buoy (3 m^3, 2000 kg) on three lines to anchors 60 m away in 50 m of water,
/// offset and turned off its equilibrium; leg 0 fails at `fail_time`. A pinned arm
/// with a rope and a clump hanging from it, released rolled 10 degrees; its rope
/// fails when its tension reaches `fail_tension`. The clump starts 4.7 m under the
/// rope's point on the rolled arm, `(30, 1.0716, -5.3188)`, the 5 m rope slack: it
/// falls 0.3 m and snaps the rope taut (some 7 kN), a steep rise through any threshold
/// between the rope's hanging tension (183 N to 234 N as the arm swings) and that. (The
/// clump once started 5 m under the unrolled point, 5.18 m from the rolled one: the
/// rope started stretched 3.6 %, 7.3e4 N, and failed at the first step.)
pub fn buoy_and_arm(duration: f64, fail_time: f64, fail_tension: f64) -> String {
    let mut s = format!(
        r#"
[simulation]
duration = {duration}
output_interval = 0.25
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
name = "buoy"
motion = "free"
reference = [0.0, 0.0, -20.0]
offset = [2.0, -1.0, 0.5]
angles = [6.0, -4.0, 10.0]
mass = 2000.0
cg = [0.1, 0.0, -0.5]
inertia = [2000.0, 2100.0, 3000.0]
volume = 3.0
cb = [0.0, 0.05, 0.0]
ca = [1.0, 0.8, 1.2]
drag_area = [2.0, 2.0, 2.5]
rotational_drag = [20.0, 20.0, 10.0]
force = [500.0, 0.0, 0.0]
damping = [[1500.0, 0, 0, 0, 0, 0], [0, 1500.0, 0, 0, 0, 0], [0, 0, 3000.0, 0, 0, 0], [0, 0, 0, 2.0e4, 0, 0], [0, 0, 0, 0, 2.0e4, 0], [0, 0, 0, 0, 0, 500.0]]

[[bodies]]
name = "arm"
motion = "pinned"
reference = [30.0, 0.0, -5.0]
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
start = {{ body = "arm", at = [0.0, 1.0, -0.5], fail_tension = {fail_tension} }}
end = {{ free = [30.0, 1.0716, -10.0188], mass = 20.0 }}
"#
    );
    for k in 0..3 {
        let a = (120.0 * k as f64).to_radians();
        let (c, sn) = (a.cos(), a.sin());
        let fail = if k == 0 {
            format!(", fail_time = {fail_time}")
        } else {
            String::new()
        };
        s += &format!(
            r#"
[[cables]]
name = "leg{k}"
line_type = "chain"
length = 68.0
segments = 12
initial = "catenary"
start = {{ fixed = [{}, {}, -50.0] }}
end = {{ body = "buoy", at = [{}, {}, -1.0]{fail} }}
"#,
            60.0 * c,
            60.0 * sn,
            1.5 * c,
            1.5 * sn
        );
    }
    s
}
