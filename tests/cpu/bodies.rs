//! Bodies with prescribed motion on the CPU path: a body's simulated motion in a
//! regular wave against its RAO, a 6-DOF table through a scenario run and back out of
//! `bodies.csv` (with the body's load against the cable's end force), and the errors
//! of bad input.

use super::common::*;
use cablesim::body::rao::RAO_KNOT_TOLERANCE;
use cablesim::body::{Body, MeanPose, Motion, RaoMotion, RaoTable};
use cablesim::cpu::CpuSolver;
use cablesim::model::{CableDef, Current, Layout, ModelDef, NodeDef, PointMass, Route};
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use cablesim::sea::WaveComponent;
use std::f64::consts::{PI, TAU};
use std::path::Path;
use std::sync::Arc;

/// Least-squares fit of `x(t) = c + a cos(w t) + b sin(w t) + (2 w terms)`: `(a, b)`.
fn fit(ts: &[f64], xs: &[f64], w: f64) -> (f64, f64) {
    let basis = |t: f64| {
        [
            1.0,
            (w * t).cos(),
            (w * t).sin(),
            (2.0 * w * t).cos(),
            (2.0 * w * t).sin(),
        ]
    };
    let mut m = nalgebra::DMatrix::<f64>::zeros(ts.len(), 5);
    for (i, &t) in ts.iter().enumerate() {
        for (j, b) in basis(t).into_iter().enumerate() {
            m[(i, j)] = b;
        }
    }
    let y = nalgebra::DVector::from_column_slice(xs);
    let c = m.svd(true, true).solve(&y, 1e-12).unwrap();
    (c[1], c[2])
}

fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

#[test]
fn a_body_moves_by_its_rao_in_a_regular_wave() {
    // RAOs on a grid; the wave meets the body exactly at grid point (0.6 rad/s, 90 deg
    // relative), so the expected response is the table's own numbers there.
    let omega = vec![0.4, 0.6, 0.8];
    let headings: Vec<f64> = [0.0f64, 90.0, 180.0, 270.0]
        .iter()
        .map(|d| d.to_radians())
        .collect();
    let target: [(f64, f64); 6] = [
        (0.35, 40.0),
        (0.8, -120.0),
        (0.95, 15.0),
        (2.5, 100.0),
        (1.2, -60.0),
        (0.7, 170.0),
    ];
    let mut values = Vec::new();
    for i in 0..3 {
        for j in 0..4 {
            values.push(std::array::from_fn(|k| {
                if i == 1 && j == 1 {
                    let (a, p) = target[k];
                    (if k >= 3 { a.to_radians() } else { a }, p.to_radians())
                } else {
                    // Different elsewhere, so a wrong lookup shows.
                    (
                        0.1 + 0.05 * (i + j + k) as f64,
                        (30.0 * (i * 4 + j + k) as f64).to_radians(),
                    )
                }
            }));
        }
    }
    let rao = RaoTable::new(omega, headings, values);
    let heading = 35f64.to_radians();
    let wave = WaveComponent {
        amplitude: 1.0,
        omega: 0.6,
        k: 0.6 * 0.6 / 9.81,
        direction: heading + PI / 2.0,
        phase: 0.7,
    };
    let pose = MeanPose {
        reference: [20.0, -10.0, 0.0],
        offset: [3.0, 1.0, 0.0],
        heading,
    };
    let m = pose.position();
    let body = Arc::new(Body::new(
        "ship".into(),
        pose,
        Motion::Rao(RaoMotion::new(&rao, &[wave], m[0], m[1], heading, 10.0)),
    ));

    // Three short hanging lines with their tops on the body: at the reference point, L
    // above it, and L forward of it.
    let l = 10.0;
    let ats = [[0.0, 0.0, 0.0], [0.0, 0.0, l], [l, 0.0, 0.0]];
    let mut def = ModelDef {
        env: water(),
        line_types: vec![rope()],
        currents: vec![Current::default()],
        ..Default::default()
    };
    for (c, at) in ats.into_iter().enumerate() {
        let route = Route::Body {
            body: body.clone(),
            at,
        };
        let top = route.eval(0.0).r;
        let first = def.nodes.len();
        for k in 0..=5 {
            def.nodes.push(NodeDef {
                position: [top[0], top[1], top[2] - 2.0 * k as f64],
                point: PointMass::default(),
                route: (k == 0).then(|| route.clone()),
                label: None,
            });
        }
        def.cables.push(CableDef {
            name: format!("c{c}"),
            line_type: 0,
            nodes: (first..=first + 5).collect(),
            l0: vec![2.0; 5],
            current: 0,
            output_positions: true,
            elem_lines: Vec::new(),
        });
    }
    let (lay, pos) = Layout::build(&def).unwrap();
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let period = TAU / 0.6;
    // dt dividing the sampling interval of 0.05 s.
    let per = (0.05 / (0.8 * bound.dt)).ceil() as u64;
    let dt = 0.05 / per as f64;
    let mut cpu = CpuSolver::new(
        lay.clone(),
        &pos,
        SolverOptions {
            dt,
            ..Default::default()
        },
    );
    let top_nodes: Vec<usize> = lay.cables.iter().map(|c| c.nodes[0] as usize).collect();
    // Ramp over 10 s, then four whole periods.
    cpu.advance((15.0 / dt).round() as u64).unwrap();
    let (mut ts, mut xs) = (Vec::new(), vec![Vec::new(); 3]);
    let n = (4.0 * period / 0.05).round() as usize;
    for _ in 0..n {
        cpu.advance(per).unwrap();
        ts.push(cpu.steps() as f64 * dt);
        for (c, &i) in top_nodes.iter().enumerate() {
            xs[c].push(cpu.r[i].to_f64());
        }
    }
    // Each coordinate's complex amplitude `a - i b` (x = a cos wt + b sin wt).
    let amp = |c: usize, d: usize| {
        let x: Vec<f64> = xs[c].iter().map(|p| p[d]).collect();
        let (a, b) = fit(&ts, &x, 0.6);
        nalgebra::Complex::new(a, -b)
    };
    let (sh, ch) = heading.sin_cos();
    let z: Vec<[nalgebra::Complex<f64>; 3]> =
        (0..3).map(|c| [amp(c, 0), amp(c, 1), amp(c, 2)]).collect();
    // Into the mean-heading axes (surge, sway, heave).
    let local =
        |v: [nalgebra::Complex<f64>; 3]| [v[0] * ch + v[1] * sh, v[1] * ch - v[0] * sh, v[2]];
    let p0 = local(z[0]);
    let up = local([z[1][0] - z[0][0], z[1][1] - z[0][1], z[1][2] - z[0][2]]);
    let fwd = local([z[2][0] - z[0][0], z[2][1] - z[0][1], z[2][2] - z[0][2]]);
    // Small angles: the point L above moves (L pitch, -L roll), the point L forward
    // moves L yaw sideways (second-order terms are at 0 and 2w, outside the fit).
    let got = [p0[0], p0[1], p0[2], -up[1] / l, up[0] / l, fwd[1] / l];
    // Expected: xi = A |H| cos(w t - theta0 + p) with theta0 the wave's phase angle at
    // the reference point at t = 0, i.e. complex amplitude A |H| e^{i (p - theta0)}.
    let th0 = wave.theta(m[0], m[1], 0.0);
    let names = ["surge", "sway", "heave", "roll", "pitch", "yaw"];
    for k in 0..6 {
        let (a, p) = target[k];
        let a = if k >= 3 { a.to_radians() } else { a };
        let (ga, gp) = (got[k].norm(), wrap(got[k].arg() + th0));
        eprintln!(
            "{}: amplitude {ga:.6} (RAO {a:.6}), phase {:.4} deg (RAO {p})",
            names[k],
            gp.to_degrees()
        );
        assert!(
            (ga - a).abs() < 2e-3 * a,
            "{}: amplitude {ga} vs {a}",
            names[k]
        );
        assert!(
            wrap(gp - p.to_radians()).abs() < 2e-3,
            "{}: phase {} deg vs {p}",
            names[k],
            gp.to_degrees()
        );
    }
}

/// Writes `text` to `dir/name`.
fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

const HEAD: &str = r#"
[simulation]
duration = 20.0
output_interval = 0.5
backend = "cpu"

[[line_types]]
name = "rope"
diameter = 0.02
mass_per_length = 1.0
ea = 2.0e6
damping = 1.0e-4
cn = 1.2
ct = 0.01
cm = 1.0
"#;

fn motion_row(t: f64) -> [f64; 6] {
    [
        0.5 * (0.6 * t).sin(),
        0.3 * (0.5 * t + 1.0).sin(),
        0.8 * (0.7 * t).cos(),
        3.0 * (0.6 * t).sin(),
        2.0 * (0.4 * t + 0.5).sin(),
        4.0 * (0.3 * t).sin(),
    ]
}

#[test]
fn a_motion_table_runs_through_a_scenario_and_back_out_of_bodies_csv() {
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("t,x,y,z,roll,pitch,yaw\n");
    for k in 0..=80 {
        let t = 0.25 * k as f64;
        let r = motion_row(t);
        csv += &format!(
            "{t},{},{},{},{},{},{}\n",
            r[0], r[1], r[2], r[3], r[4], r[5]
        );
    }
    write(dir.path(), "ship.csv", &csv);
    let text = format!(
        r#"{HEAD}
[[bodies]]
name = "ship"
reference = [5.0, 2.0, 0.0]
offset = [1.0, -1.0, 0.5]
heading = 30.0
motion_file = "ship.csv"

[[cables]]
name = "hang"
line_type = "rope"
length = 10.0
segments = 5
start = {{ body = "ship", at = [8.0, -3.0, -2.0] }}
end = {{ free = [14.0, -1.0, -12.0], mass = 20.0, volume = 0.005 }}
"#
    );
    let path = dir.path().join("s.toml");
    write(dir.path(), "s.toml", &text);
    let sc = Scenario::load(&path).unwrap();
    let out = dir.path().join("out");
    cablesim::sim::run(
        &sc,
        &cablesim::sim::RunOptions {
            out_dir: out.clone(),
            overrides: Default::default(),
            progress: false,
        },
    )
    .unwrap();
    let bodies = std::fs::read_to_string(out.join("bodies.csv")).unwrap();
    let ends = std::fs::read_to_string(out.join("end_forces.csv")).unwrap();
    let mut lines = bodies.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz"
    );
    let starts: Vec<Vec<f64>> = ends
        .lines()
        .skip(1)
        .filter(|l| l.contains(",start,"))
        .map(|l| l.split(',').filter_map(|x| x.parse().ok()).collect())
        .collect();
    let (sh, ch) = 30f64.to_radians().sin_cos();
    let (mut rows, mut sum_f) = (0, 0.0);
    for (line, end) in lines.zip(&starts) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[1], "ship");
        let v: Vec<f64> = f.iter().map(|x| x.parse().unwrap_or(f64::NAN)).collect();
        let t = v[0];
        // The pose: the table's row at that time (an output time is a sample time),
        // the translations turned by the heading, the heading added to the yaw.
        let r = motion_row(t);
        let want = [
            6.0 + ch * r[0] - sh * r[1],
            1.0 + sh * r[0] + ch * r[1],
            0.5 + r[2],
            r[3],
            r[4],
            r[5] + 30.0,
        ];
        for k in 0..6 {
            assert!(
                (v[2 + k] - want[k]).abs() < 1e-9,
                "t {t} column {}: {} vs {}",
                k + 2,
                v[2 + k],
                want[k]
            );
        }
        // One cable: the body's force is its end force, the moment that force's about
        // the reference point at the attachment point.
        let force = [v[8], v[9], v[10]];
        assert_eq!(end[0], t);
        for k in 0..3 {
            assert!((force[k] - end[1 + k]).abs() <= 1e-9 * (1.0 + force[k].abs()));
        }
        let at = [8.0, -3.0, -2.0];
        let rot = cablesim::body::kinematics::rotation(
            r[3].to_radians(),
            r[4].to_radians(),
            (r[5] + 30.0).to_radians(),
        );
        let q = cablesim::body::kinematics::mat_vec(&rot, at);
        let mom = q.cross(cablesim::math::V3::from_f64(force));
        let fnorm = (force[0].powi(2) + force[1].powi(2) + force[2].powi(2)).sqrt();
        for (k, m) in [mom.x, mom.y, mom.z].into_iter().enumerate() {
            // The end node sits on its target to the constraint's tracking error.
            assert!(
                (v[11 + k] - m).abs() < 1e-3 * fnorm,
                "t {t} moment {k}: {} vs {m}",
                v[11 + k]
            );
        }
        sum_f += fnorm;
        rows += 1;
    }
    assert_eq!(rows, 41);
    // The line and its clump hang from the body: a load near their wet weight (about
    // 210 N) on average. It starts stretched, so the clump bounces and the force passes
    // near zero at some output times; the mean is the steady measure.
    let mean_f = sum_f / rows as f64;
    assert!(
        mean_f > 100.0,
        "the line hangs from the body: mean |F| {mean_f} N"
    );
}

/// The error of loading scenario `text` (with `files` written beside it).
fn error_of(text: &str, files: &[(&str, &str)]) -> String {
    let dir = tempfile::tempdir().unwrap();
    for (name, body) in files {
        write(dir.path(), name, body);
    }
    write(dir.path(), "s.toml", text);
    Scenario::load(dir.path().join("s.toml"))
        .unwrap_err()
        .to_string()
}

fn with_body(body: &str, end: &str) -> String {
    format!(
        r#"{HEAD}
[[bodies]]
name = "ship"
reference = [0.0, 0.0, 0.0]
{body}

[[cables]]
name = "hang"
line_type = "rope"
length = 10.0
segments = 5
start = {end}
end = {{ free = [0.0, 0.0, -10.0] }}
"#
    )
}

const RAO_HEAD: &str = "omega,heading,surge_amp,surge_phase,sway_amp,sway_phase,heave_amp,heave_phase,roll_amp,roll_phase,pitch_amp,pitch_phase,yaw_amp,yaw_phase\n";

fn rao_row(w: f64, h: f64) -> String {
    format!("{w},{h},0.1,0,0.2,0,1.0,0,1,0,2,0,0.5,0\n")
}

#[test]
fn bad_body_input_names_the_file_the_field_and_the_problem() {
    let ok_end = r#"{ body = "ship", at = [0.0, 0.0, 0.0] }"#;
    // Unknown body.
    let e = error_of(
        &with_body("", r#"{ body = "tug", at = [0.0, 0.0, 0.0] }"#),
        &[],
    );
    assert!(
        e.contains("s.toml")
            && e.contains("start.body")
            && e.contains("unknown body \"tug\"")
            && e.contains("ship"),
        "{e}"
    );
    // A body end without `at`.
    let e = error_of(&with_body("", r#"{ body = "ship" }"#), &[]);
    assert!(e.contains("start.at") && e.contains("missing"), "{e}");
    // Non-finite heading in the scenario.
    let e = error_of(&with_body("heading = nan", ok_end), &[]);
    assert!(
        e.contains("bodies[0] (\"ship\").heading") && e.contains("finite"),
        "{e}"
    );
    // Non-finite angle in a motion file: the file, the line, the column.
    let motion = "t,x,y,z,roll,pitch,yaw\n0,0,0,0,0,0,0\n1,0,0,0,nan,0,0\n";
    let e = error_of(
        &with_body("motion_file = \"m.csv\"", ok_end),
        &[("m.csv", motion)],
    );
    assert!(
        e.contains("motion_file")
            && e.contains("m.csv line 3, column roll")
            && e.contains("not a finite number"),
        "{e}"
    );
    // Times that do not increase.
    let motion = "t,x,y,z,roll,pitch,yaw\n0,0,0,0,0,0,0\n0,0,0,0,1,0,0\n";
    let e = error_of(
        &with_body("motion_file = \"m.csv\"", ok_end),
        &[("m.csv", motion)],
    );
    assert!(
        e.contains("m.csv line 3, column t") && e.contains("does not increase"),
        "{e}"
    );
    // An unreadable motion file.
    let e = error_of(&with_body("motion_file = \"missing.csv\"", ok_end), &[]);
    assert!(
        e.contains("motion_file")
            && e.contains("cannot read motion file")
            && e.contains("missing.csv"),
        "{e}"
    );
    // A wrong header.
    let e = error_of(
        &with_body("motion_file = \"m.csv\"", ok_end),
        &[("m.csv", "t,x,y,z\n0,0,0,0\n")],
    );
    assert!(e.contains("header must be `t,x,y,z,roll,pitch,yaw`"), "{e}");
    // RAO tables: unsorted frequencies.
    let rao = format!(
        "{RAO_HEAD}{}{}{}{}",
        rao_row(0.5, 0.0),
        rao_row(0.5, 180.0),
        rao_row(0.3, 0.0),
        rao_row(0.3, 180.0)
    );
    let e = error_of(
        &with_body("rao_file = \"r.csv\"", ok_end),
        &[("r.csv", &rao)],
    );
    assert!(
        e.contains("rao_file") && e.contains("r.csv line 4, column omega") && e.contains("sorted"),
        "{e}"
    );
    // Unsorted headings.
    let rao = format!("{RAO_HEAD}{}{}", rao_row(0.5, 180.0), rao_row(0.5, 0.0));
    let e = error_of(
        &with_body("rao_file = \"r.csv\"", ok_end),
        &[("r.csv", &rao)],
    );
    assert!(
        e.contains("r.csv line 3, column heading") && e.contains("must increase"),
        "{e}"
    );
    // A gap: the second frequency lacks heading 180.
    let rao = format!(
        "{RAO_HEAD}{}{}{}{}",
        rao_row(0.3, 0.0),
        rao_row(0.3, 180.0),
        rao_row(0.5, 0.0),
        rao_row(0.7, 0.0)
    );
    let e = error_of(
        &with_body("rao_file = \"r.csv\"", ok_end),
        &[("r.csv", &rao)],
    );
    assert!(
        e.contains("r.csv line 4, column heading")
            && e.contains("omega 0.5 has no row for heading 180"),
        "{e}"
    );
    // The gap in the last frequency.
    let rao = format!(
        "{RAO_HEAD}{}{}{}",
        rao_row(0.3, 0.0),
        rao_row(0.3, 180.0),
        rao_row(0.5, 0.0)
    );
    let e = error_of(
        &with_body("rao_file = \"r.csv\"", ok_end),
        &[("r.csv", &rao)],
    );
    assert!(e.contains("omega 0.5 has no row for heading 180"), "{e}");
    // A non-finite phase.
    let rao = format!("{RAO_HEAD}0.3,0,0.1,0,0.2,0,1.0,inf,1,0,2,0,0.5,0\n");
    let e = error_of(
        &with_body("rao_file = \"r.csv\"", ok_end),
        &[("r.csv", &rao)],
    );
    assert!(
        e.contains("line 2, column heave_phase") && e.contains("not a finite number"),
        "{e}"
    );
    // Both kinds of motion.
    let e = error_of(
        &with_body("rao_file = \"r.csv\"\nmotion_file = \"m.csv\"", ok_end),
        &[],
    );
    assert!(
        e.contains("bodies[0] (\"ship\")") && e.contains("not both"),
        "{e}"
    );
    // A body end offset.
    let e = error_of(
        &with_body(
            "",
            r#"{ body = "ship", at = [0.0, 0.0, 0.0], offset = [1.0, 0.0, 0.0] }"#,
        ),
        &[],
    );
    assert!(
        e.contains("start.offset") && e.contains("cannot be offset"),
        "{e}"
    );
    // A good RAO table by period parses (the body has no waves to move it yet).
    let rao = RAO_HEAD.replacen("omega", "period", 1)
        + &rao_row(8.0, 0.0)
        + &rao_row(8.0, 180.0)
        + &rao_row(12.0, 0.0)
        + &rao_row(12.0, 180.0);
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "r.csv", &rao);
    write(
        dir.path(),
        "s.toml",
        &with_body("rao_file = \"r.csv\"", ok_end),
    );
    Scenario::load(dir.path().join("s.toml")).unwrap();
}

#[test]
fn an_rao_body_heaves_with_the_scenarios_regular_wave() {
    // Heave RAO 0.9 m/m with a 25 deg lead at every heading and frequency; a regular
    // wave of amplitude 1 m, period 10 s, travelling towards 30 deg, phase 40 deg,
    // ramped in over 5 s. Past the ramp, bodies.csv's z must be
    // z_ref + 0.9 cos(theta(x_ref, t) - 25 deg) at every output time (to the
    // interpolation tolerance of the knots).
    let dir = tempfile::tempdir().unwrap();
    let mut rao = String::from(RAO_HEAD);
    for w in [0.3, 0.9] {
        for h in [0.0, 120.0, 240.0] {
            rao += &format!("{w},{h},0,0,0,0,0.9,25,0,0,0,0,0,0\n");
        }
    }
    write(dir.path(), "r.csv", &rao);
    let text = format!(
        r#"{HEAD}
[environment.waves]
ramp = 5.0

[[environment.waves.trains]]
type = "regular"
amplitude = 1.0
period = 10.0
direction = 30.0
phase = 40.0

[[bodies]]
name = "buoy"
reference = [30.0, -20.0, 0.0]
offset = [2.0, 1.0, -1.0]
heading = 70.0
rao_file = "r.csv"

[[cables]]
name = "hang"
line_type = "rope"
length = 10.0
segments = 5
start = {{ body = "buoy", at = [0.0, 0.0, -1.0] }}
end = {{ free = [32.0, -19.0, -12.0] }}
"#
    );
    write(dir.path(), "s.toml", &text);
    let sc = Scenario::load(dir.path().join("s.toml")).unwrap();
    let out = dir.path().join("out");
    cablesim::sim::run(
        &sc,
        &cablesim::sim::RunOptions {
            out_dir: out.clone(),
            overrides: Default::default(),
            progress: false,
        },
    )
    .unwrap();
    let bodies = std::fs::read_to_string(out.join("bodies.csv")).unwrap();
    let w = TAU / 10.0;
    let k = w * w / 9.81;
    let b = 30f64.to_radians();
    let (x, y) = (32.0, -19.0);
    let mut checked = 0;
    for line in bodies.lines().skip(1) {
        let v: Vec<f64> = line
            .split(',')
            .map(|s| s.parse().unwrap_or(f64::NAN))
            .collect();
        let t = v[0];
        let theta = k * (x * b.cos() + y * b.sin()) - w * t + 40f64.to_radians();
        // The ramp 0.5 (1 - cos(pi t / 5)) before 5 s, 1 after.
        let ramp = if t < 5.0 {
            0.5 * (1.0 - (PI * t / 5.0).cos())
        } else {
            1.0
        };
        let want = -1.0 + ramp * 0.9 * (theta - 25f64.to_radians()).cos();
        // Interpolated between exact knots: within the knots' tolerance of the
        // amplitude (one component: `RAO_KNOT_TOLERANCE` of it at most).
        let tol = 1e-12 + 0.9 * RAO_KNOT_TOLERANCE;
        assert!((v[4] - want).abs() < tol, "t {t}: z {} vs {want}", v[4]);
        // No other motion.
        assert!((v[2] - x).abs() < 1e-12 && (v[3] - y).abs() < 1e-12);
        assert!(v[5].abs() < 1e-12 && v[6].abs() < 1e-12 && (v[7] - 70.0).abs() < 1e-9);
        checked += 1;
    }
    assert_eq!(checked, 41);
}

#[test]
fn the_docs_example_parses() {
    // docs/src/bodies.md's example scenario, with a motion file beside it.
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/src/bodies.md"))
        .unwrap();
    let example = doc.split("## Example").nth(1).expect("an Example section");
    let toml = example
        .split("```toml")
        .nth(1)
        .unwrap()
        .split("```")
        .next()
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("t,x,y,z,roll,pitch,yaw\n");
    for k in 0..=120 {
        let t = 0.5 * k as f64;
        let r = motion_row(t);
        csv += &format!(
            "{t},{},{},{},{},{},{}\n",
            r[0], r[1], r[2], r[3], r[4], r[5]
        );
    }
    write(dir.path(), "barge_motion.csv", &csv);
    write(dir.path(), "s.toml", toml);
    let sc = Scenario::load(dir.path().join("s.toml")).unwrap();
    let on_body = sc
        .model
        .nodes
        .iter()
        .filter(|n| matches!(n.route, Some(Route::Body { .. })))
        .count();
    assert_eq!(on_body, 2);
}
