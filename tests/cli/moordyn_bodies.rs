//! MoorDyn's BODIES and FAILURE sections converted: a free body's fields and its
//! `|` cells, fixed, coupled and pinned bodies, points on bodies, MoorDyn's attitude
//! order, TmaxIC's choice of the initial state, failures of whole points and of some
//! of a point's lines, errors naming the row and the field; and a point that fails
//! with its cables carrying its own mass and volume.

use cablesim::body::kinematics::rotation;
use cablesim::model::Route;
use cablesim::moordyn::{convert_text, ConvertOptions};
use cablesim::scenario::Scenario;
use std::path::Path;

const FILE: &str = "\
MoorDyn v2 input file with bodies, written for cablesim's tests
---------------------- LINE TYPES -----------------------------------
TypeName  Diam   Mass/m  EA     BA/-zeta  EI   Cd   Ca   CdAx  CaAx
(name)    (m)    (kg/m)  (N)    (N-s/-)   (-)  (-)  (-)  (-)   (-)
rope      0.05   2.5     1.0e7  2.0e4     0    1.2  1.0  0.2   0.0
---------------------- BODIES ---------------------------------------
ID  Attachment  X0  Y0  Z0  r0  p0  y0  Mass  CG  I  Volume  CdA  Ca
(#) (word) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)
1   Free     0.0  0.0  -20.0  2.0  -3.0  4.0  2000.0  0.1|0.0|-0.5  2000|2100|3000  3.0  2.0|5.0  1.0
2   Fixed    40.0 0.0  -45.0  10.0 20.0  30.0 0       0     0              0    0        0
3   Coupled  0.0  30.0 -2.0   0    0     0    0       0     0              0    0        0
4   CoupledPinned 0.0 -30.0 -3.0 0 0    0    500.0   -2.0  100            0.5  1.0      0.5
---------------------- POINTS ---------------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(#) (word)  (m) (m) (m) (kg) (m^3) (m^2) (-)
1   Fixed   -60.0  0.0  -50.0  0    0    0  0
2   Body1   1.5    0.0  -1.0   10   0.02 0  0
3   Body2   1.0    2.0  3.0    0    0    0  0
4   Body3   0.0    0.0  -1.0   0    0    0  0
5   Body4   0.0    0.0  -1.0   0    0    0  0
6   Body1   -1.0   0.0  -1.0   0    0    0  0
---------------------- LINES ----------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs
(#) (name)    (#)      (#)      (m)       (-)      (-)
1   rope  1  2  75.0  10  -
2   rope  3  2  50.0  10  -
3   rope  4  6  40.0  10  -
4   rope  5  6  40.0  10  -
---------------------- FAILURE --------------------------------------
FailureID  Point  Line(s)  FailTime  FailTen
()         ()     (,)      (s)       (N)
1          P2     1        0         3.0e5
2          6      3,4      12.5      0
---------------------- OPTIONS --------------------------------------
0.0002  dtM
9.81    g
1025    rho
50      WtrDpth
30      TmaxIC
---------------------- OUTPUTS --------------------------------------
END
------------------------- need this line ----------------------------
";

fn convert(text: &str) -> (String, Scenario) {
    let path = Path::new("model.dat");
    let c = convert_text(text, path, &ConvertOptions::default()).expect("converts");
    let sc = Scenario::parse(&c.toml, path)
        .unwrap_or_else(|e| panic!("converted scenario does not load: {e}\n{}", c.toml));
    (c.toml, sc)
}

fn error_of(text: &str) -> String {
    convert_text(text, Path::new("model.dat"), &ConvertOptions::default())
        .expect_err("should be refused")
        .to_string()
}

fn with(old: &str, new: &str) -> String {
    assert!(FILE.contains(old), "{old}");
    FILE.replacen(old, new, 1)
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).unwrap() + 1
}

/// The body named `name` through the routes of the model's nodes.
fn body(sc: &Scenario, name: &str) -> std::sync::Arc<cablesim::body::Body> {
    sc.model
        .nodes
        .iter()
        .find_map(|n| match &n.route {
            Some(Route::Body { body, .. }) if body.name == name => Some(body.clone()),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no body {name}"))
}

/// MoorDyn's attitude, `R = Rx(r) Ry(p) Rz(y)`.
fn moordyn_rotation(r: f64, p: f64, y: f64) -> [[f64; 3]; 3] {
    let (r, p, y) = (r.to_radians(), p.to_radians(), y.to_radians());
    let rx = [
        [1.0, 0.0, 0.0],
        [0.0, r.cos(), -r.sin()],
        [0.0, r.sin(), r.cos()],
    ];
    let ry = [
        [p.cos(), 0.0, p.sin()],
        [0.0, 1.0, 0.0],
        [-p.sin(), 0.0, p.cos()],
    ];
    let rz = [
        [y.cos(), -y.sin(), 0.0],
        [y.sin(), y.cos(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    c[i][j] += a[i][k] * b[k][j];
                }
            }
        }
        c
    };
    mul(mul(rx, ry), rz)
}

#[test]
fn a_free_body_and_its_cells_map_to_a_free_body() {
    let (toml, sc) = convert(FILE);
    let b = body(&sc, "body1");
    let d = b.dynamic().expect("body1 is free");
    let s = &d.body.spec;
    assert_eq!(s.mass, 2000.0);
    assert_eq!(s.cg, [0.1, 0.0, -0.5]);
    assert_eq!(
        s.cb, s.cg,
        "MoorDyn's buoyancy acts at the centre of gravity"
    );
    assert_eq!(
        s.inertia,
        [[2000.0, 0.0, 0.0], [0.0, 2100.0, 0.0], [0.0, 0.0, 3000.0]]
    );
    assert_eq!(s.volume, 3.0);
    assert_eq!(s.drag_area, [2.0; 3]);
    assert_eq!(s.rotational_drag, [5.0; 3]);
    for k in 0..3 {
        assert!((s.added_mass[k][k] - 1025.0 * 3.0).abs() < 1e-9);
        assert_eq!(s.added_mass[k + 3][k + 3], 0.0);
    }
    assert!(d.equilibrium, "TmaxIC = 30: starts in equilibrium\n{toml}");
    // MoorDyn's attitude Rx Ry Rz written as cablesim's roll, pitch, yaw (Rz Ry Rx).
    let [r, p, y] = s.angles;
    let got = rotation(r, p, y + b.pose.heading);
    let want = moordyn_rotation(2.0, -3.0, 4.0);
    for i in 0..3 {
        for j in 0..3 {
            assert!(
                (got[i][j] - want[i][j]).abs() < 1e-12,
                "{got:?} vs {want:?}"
            );
        }
    }
    // The point on it carries its mass, and sits at its body coordinates.
    assert!(
        toml.contains("name = \"point2\"\nbody = \"body1\"\nat = [1.5, 0.0, -1.0]\nmass = 10.0"),
        "{toml}"
    );
}

#[test]
fn fixed_coupled_and_pinned_bodies_map_to_their_kinds() {
    let (toml, sc) = convert(FILE);
    // The fixed body's point: a fixed point at X + R p, MoorDyn's R.
    let r = moordyn_rotation(10.0, 20.0, 30.0);
    let p = [1.0, 2.0, 3.0];
    let want: Vec<f64> = (0..3)
        .map(|i| [40.0, 0.0, -45.0][i] + (0..3).map(|k| r[i][k] * p[k]).sum::<f64>())
        .collect();
    let start = sc.model.nodes[sc.model.cables[1].nodes[0]].position;
    for k in 0..3 {
        assert!((start[k] - want[k]).abs() < 1e-9, "{start:?} vs {want:?}");
    }
    // The coupled body: a prescribed body, held still.
    let b3 = body(&sc, "body3");
    assert!(b3.dynamic().is_none());
    assert_eq!(b3.pose.reference, [0.0, 30.0, -2.0]);
    // The pinned one: rotation free; its CG one value is z.
    let b4 = body(&sc, "body4");
    let d = b4.dynamic().expect("body4 is pinned");
    assert_eq!(d.body.kind, cablesim::body::free::FreeKind::Pinned);
    assert_eq!(d.body.spec.cg, [0.0, 0.0, -2.0]);
    assert_eq!(d.body.spec.inertia[1][1], 100.0);
    assert!(toml.contains("motion = \"pinned\""));
}

#[test]
fn tmaxic_zero_starts_the_bodies_at_the_files_pose() {
    let (toml, sc) = convert(&with("30      TmaxIC", "0       TmaxIC"));
    assert!(toml.contains("initial = \"pose\""), "{toml}");
    assert!(!body(&sc, "body1").dynamic().unwrap().equilibrium);
    let (_, sc) = convert(&with("30      TmaxIC\n", ""));
    assert!(
        body(&sc, "body1").dynamic().unwrap().equilibrium,
        "MoorDyn's default is 120 s"
    );
}

#[test]
fn failures_map_to_ends_points_and_points_of_their_own() {
    let (toml, sc) = convert(FILE);
    let mut f: Vec<(String, bool, Option<f64>, Option<f64>)> = sc
        .failures
        .iter()
        .map(|x| (x.cable.clone(), x.at_start, x.time, x.tension))
        .collect();
    f.sort_by(|a, b| a.0.cmp(&b.0));
    // Failure 1: lines 1 and 2 end at point 2, so line 1's end moves to a point of its
    // own that fails on tension. Failure 2: lines 3 and 4 are all of point 6's: the
    // point fails with both, at 12.5 s.
    assert_eq!(
        f,
        vec![
            ("line1".into(), false, None, Some(3.0e5)),
            ("line3".into(), false, Some(12.5), None),
            ("line4".into(), false, Some(12.5), None),
        ],
        "{toml}"
    );
    assert!(toml.contains("name = \"point2_failure1\""), "{toml}");
    assert!(
        toml.contains("end = { point = \"point2_failure1\" }"),
        "{toml}"
    );
    // Line 2 stays on point 2 itself.
    assert!(toml.contains("end = { point = \"point2\" }"), "{toml}");
    // The failing point carries its own mass: it is point 2's (10 kg) on the body, and
    // the split one has none.
    let split = sc.model.nodes[sc.model.cables[0].nodes[10]].point;
    assert_eq!(split.mass, 0.0);
    let shared = sc.model.nodes[sc.model.cables[1].nodes[10]].point;
    assert_eq!(shared.mass, 10.0);
}

#[test]
fn bad_bodies_and_failures_are_errors_naming_the_row_and_field() {
    let cases: Vec<(String, &str, &str)> = vec![
        (with("0.1|0.0|-0.5", "0.1|-0.5"), "0.1|-0.5", "body 1 CG"),
        (
            with("2000|2100|3000", "2000|x|3000"),
            "2000|x|3000",
            "body 1 I",
        ),
        (
            with("2.0|5.0  1.0", "2.0|5.0|1|1  1.0"),
            "2.0|5.0|1|1",
            "body 1 CdA",
        ),
        (
            with("3.0  2.0|5.0  1.0", "3.0  2.0|5.0  1|2"),
            "2.0|5.0  1|2",
            "body 1 Ca",
        ),
        (
            with("1   Free ", "1   Floating "),
            "1   Floating",
            "body 1 Attachment",
        ),
        (
            with("2   Fixed    40.0", "3   Fixed    40.0"),
            "3   Fixed    40.0",
            "body ID",
        ),
        (
            with(
                "1   Free     0.0  0.0  -20.0  2.0  -3.0  4.0  2000.0",
                "1   Free     0.0  0.0  -20.0  2.0  -3.0  4.0  0.0",
            ),
            "-3.0  4.0  0.0",
            "body 1 Mass",
        ),
        (
            with("2000|2100|3000", "2000|0|3000"),
            "2000|0|3000",
            "body 1 I",
        ),
        (
            with("2   Body1   1.5", "2   Body7   1.5"),
            "2   Body7",
            "point 2 attachment",
        ),
        (
            with("1          P2     1 ", "1          P9     1 "),
            "1          P9",
            "failure 1 Point",
        ),
        (
            with("1          P2     1 ", "1          P2     7 "),
            "1          P2     7",
            "failure 1 Line(s)",
        ),
        (
            with("1          P2     1 ", "1          P2     3 "),
            "1          P2     3",
            "failure 1 Line(s)",
        ),
        (
            with("0         3.0e5", "0         -3.0e5"),
            "-3.0e5",
            "failure 1 FailTen",
        ),
        (
            with("0         3.0e5", "0         0"),
            "1          P2     1        0         0",
            "failure 1 FailTime",
        ),
        (
            with("1          P2     1 ", "1          R1A    1 "),
            "R1A",
            "failure 1 Point",
        ),
        (
            with("2          6      3,4", "2          6      1,3"),
            "6      1,3",
            "failure 2 Line(s)",
        ),
    ];
    for (text, needle, what) in cases {
        let e = error_of(&text);
        let n = line_of(&text, needle);
        assert!(
            e.contains(&format!("line {n}:")) && e.contains(what) && e.contains("model.dat"),
            "expected line {n} and \"{what}\" in: {e}"
        );
    }
    // A free point has no support to leave.
    let e = error_of(&with("1   Fixed   -60.0", "1   Free    -60.0").replace(
        "1          P2     1        0         3.0e5",
        "1          P1     1        0         3.0e5",
    ));
    assert!(e.contains("failure 1 Point") && e.contains("free"), "{e}");
}

#[test]
fn a_point_that_fails_takes_its_cables_and_its_own_buoyancy() {
    // A buoyant hook (1 m^3, 50 kg) held at (0, 0, -30) with two light ropes hanging
    // from it to small clumps: at 1 s it fails, both ropes with it, and the hook rises
    // with them (its own volume lifts it: it is a free point now, with its mass).
    let dir = tempfile::tempdir().unwrap();
    let text = r#"
[simulation]
duration = 4.0
output_interval = 0.5
backend = "cpu"

[environment]
depth = 60.0

[[line_types]]
name = "rope"
diameter = 0.02
mass_per_length = 0.5
ea = 2.0e6
damping = 1.0e-3
cn = 1.2
ct = 0.01
cm = 1.0

[[points]]
name = "hook"
fixed = [0.0, 0.0, -30.0]
mass = 50.0
volume = 1.0
drag_area = 0.5
fail_time = 1.0

[[cables]]
name = "a"
line_type = "rope"
length = 10.0
segments = 5
start = { point = "hook" }
end = { free = [2.0, 0.0, -39.8], mass = 20.0 }

[[cables]]
name = "b"
line_type = "rope"
length = 10.0
segments = 5
start = { point = "hook" }
end = { free = [-2.0, 0.0, -39.8], mass = 20.0 }
"#;
    std::fs::write(dir.path().join("s.toml"), text).unwrap();
    let sc = Scenario::load(&dir.path().join("s.toml")).unwrap();
    assert_eq!(sc.failures.len(), 2);
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
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let f = s["failures"].as_array().unwrap();
    assert_eq!(f.len(), 2, "{f:?}");
    let t0 = f[0]["time"].as_f64().unwrap();
    assert!((1.0..1.01).contains(&t0), "{f:?}");
    assert_eq!(f[1]["time"].as_f64().unwrap(), t0, "together: {f:?}");
    let cables: Vec<&str> = f.iter().map(|x| x["cable"].as_str().unwrap()).collect();
    assert!(cables.contains(&"a") && cables.contains(&"b"));
    // The hook's height over time (points.csv): held until 1 s, then rising.
    let csv = std::fs::read_to_string(out.join("points.csv")).unwrap();
    let mut rd = csv.lines();
    let head: Vec<&str> = rd.next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (ct, cp, cz) = (col("time"), col("point"), col("z"));
    let hook: Vec<(f64, f64)> = rd
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[cp] == "hook")
        .map(|r| (r[ct].parse().unwrap(), r[cz].parse().unwrap()))
        .collect();
    for &(t, z) in &hook {
        if t <= 1.0 - 1e-9 {
            assert!((z + 30.0f64).abs() < 1e-9, "held: t {t} z {z}");
        }
    }
    let last = hook.last().unwrap();
    assert!(last.1 > -29.0, "the buoyant hook rises once free: {hook:?}");
}
