//! Damaged conditions in studies (the accidental limit state): a free buoy on three
//! lines, intact and with each chosen line broken, through `cablesim study run`.
//!
//! The validation: once the transient has died out, the broken line's neighbours carry
//! what the static equilibrium of the damaged mooring says, within 1 %. The equilibrium
//! is solved here, independently of the simulation: the body's pose (surge, heave and
//! pitch; the damaged mooring is symmetric about the x axis) by Newton's method on its
//! force and moment balance, each line's force at its fairlead from the analytic
//! elastic catenary (`physics::catenary`, itself checked against MoorPy in
//! `tests/cpu/catenary.rs`), the body's weight at its centre of gravity and its
//! buoyancy at its reference point.

use cablesim::physics::catenary::{catenary, wet_weight};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

const DEPTH: f64 = 50.0;
const RHO: f64 = 1025.0;
const G: f64 = 9.81;
const MASS: f64 = 2000.0;
const VOLUME: f64 = 3.0;
const CG_Z: f64 = -0.5;
const LENGTH: f64 = 68.0;
const EA: f64 = 1.0e7;
const ANCHOR_R: f64 = 60.0;
const FAIRLEAD_R: f64 = 1.5;
const FAIRLEAD_Z: f64 = -1.0;

fn run(args: &[&str]) -> std::process::Output {
    Command::new(BIN)
        .env("RAYON_NUM_THREADS", "2")
        .args(args)
        .output()
        .unwrap()
}

fn run_ok(args: &[&str]) {
    let out = run(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn read_csv(path: &Path) -> Vec<BTreeMap<String, String>> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let h = r.headers().unwrap().clone();
    r.records()
        .map(|rec| {
            let rec = rec.unwrap();
            h.iter()
                .zip(rec.iter())
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

fn num(row: &BTreeMap<String, String>, k: &str) -> f64 {
    row[k]
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {:?}", row[k]))
}

/// The buoy of `tests/cpu/free_bodies.rs` (and `scripts/compare_free_body.py`) as a
/// study's base scenario, with `study` appended.
fn buoy_study(dir: &Path, study: &str) -> PathBuf {
    let mut s = format!(
        r#"
[simulation]
duration = 10.0
output_interval = 1.0

[environment]
depth = {DEPTH}
water_density = {RHO}
gravity = {G}

[environment.waves]
ramp = 5.0

[[line_types]]
name = "rope"
diameter = 0.05
mass_per_length = 2.5
ea = {EA}
damping = 2.0e-3
cn = 1.2
ct = 0.2
cm = 1.0

[[bodies]]
name = "buoy"
motion = "free"
reference = [0.0, 0.0, -20.0]
mass = {MASS}
cg = [0.0, 0.0, {CG_Z}]
inertia = [2000.0, 2000.0, 3000.0]
volume = {VOLUME}
ca = [1.0, 1.0, 1.0]
drag_area = [2.0, 2.0, 2.0]
damping = [[1500.0, 0, 0, 0, 0, 0], [0, 1500.0, 0, 0, 0, 0], [0, 0, 3000.0, 0, 0, 0], [0, 0, 0, 2.0e4, 0, 0], [0, 0, 0, 0, 2.0e4, 0], [0, 0, 0, 0, 0, 500.0]]
"#
    );
    for k in 0..3 {
        let a = (120.0 * k as f64).to_radians();
        s += &format!(
            r#"
[[cables]]
name = "leg{k}"
line_type = "rope"
length = {LENGTH}
segments = 20
initial = "catenary"
start = {{ fixed = [{}, {}, {}] }}
end = {{ body = "buoy", at = [{}, {}, {FAIRLEAD_Z}] }}
"#,
            ANCHOR_R * a.cos(),
            ANCHOR_R * a.sin(),
            -DEPTH,
            FAIRLEAD_R * a.cos(),
            FAIRLEAD_R * a.sin(),
        );
    }
    s += study;
    let p = dir.join("buoy_study.toml");
    std::fs::write(&p, s).unwrap();
    p
}

/// The force and moment (about the reference point) on the body at pose `(x, z,
/// pitch)` (y, roll and yaw zero), and each leg's fairlead tension, with the legs
/// `legs` (of 0, 1, 2) attached: `([Fx, Fz, My], tensions)`.
fn balance(q: [f64; 3], legs: &[usize]) -> ([f64; 3], Vec<f64>) {
    let (x, z, th) = (q[0], q[1], q[2]);
    let (c, s) = (th.cos(), th.sin());
    // Rotation about y by the pitch: body (px, py, pz) -> (c px + s pz, py, -s px + c pz).
    let rot = |p: [f64; 3]| [c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2]];
    let w = wet_weight(2.5, 0.05, RHO, G);
    let mut f = [0.0; 3]; // Fx, Fy, Fz
    let mut my = 0.0;
    // Weight at the centre of gravity, buoyancy at the reference point.
    let rg = rot([0.0, 0.0, CG_Z]);
    f[2] += (RHO * VOLUME - MASS) * G;
    my += -rg[0] * (-MASS * G);
    let mut tensions = Vec::new();
    for &k in legs {
        let a = (120.0 * k as f64).to_radians();
        let r = rot([FAIRLEAD_R * a.cos(), FAIRLEAD_R * a.sin(), FAIRLEAD_Z]);
        let p = [x + r[0], r[1], z + r[2]];
        let anchor = [ANCHOR_R * a.cos(), ANCHOR_R * a.sin(), -DEPTH];
        let (dx, dy) = (p[0] - anchor[0], p[1] - anchor[1]);
        let xf = dx.hypot(dy);
        let cat = catenary(xf, p[2] - anchor[2], LENGTH, EA, w, true).unwrap();
        // The line pulls the fairlead towards the anchor (horizontally) and down.
        let fl = [-cat.hf * dx / xf, -cat.hf * dy / xf, -cat.vf];
        for i in 0..3 {
            f[i] += fl[i];
        }
        my += r[2] * fl[0] - r[0] * fl[2];
        tensions.push(cat.fairlead_tension());
    }
    ([f[0], f[2], my], tensions)
}

/// The static equilibrium pose `(x, z, pitch)` with legs `legs`, by Newton's method
/// (finite-difference Jacobian, backtracking on the residual) from `q`.
fn equilibrium(mut q: [f64; 3], legs: &[usize]) -> [f64; 3] {
    let norm = |r: [f64; 3]| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    for _ in 0..100 {
        let r = balance(q, legs).0;
        if norm(r) < 1e-6 {
            return q;
        }
        let mut j = [[0.0; 3]; 3];
        for c in 0..3 {
            let h = 1e-6;
            let mut qp = q;
            qp[c] += h;
            let rp = balance(qp, legs).0;
            for i in 0..3 {
                j[i][c] = (rp[i] - r[i]) / h;
            }
        }
        let d = solve3(j, [-r[0], -r[1], -r[2]]);
        let mut t = 1.0;
        loop {
            let trial = [q[0] + t * d[0], q[1] + t * d[1], q[2] + t * d[2]];
            let ok = std::panic::catch_unwind(|| balance(trial, legs).0).ok();
            if let Some(rt) = ok {
                if norm(rt) < norm(r) || t < 1e-6 {
                    q = trial;
                    break;
                }
            }
            t *= 0.5;
        }
    }
    panic!("the static equilibrium did not converge: {q:?}");
}

/// Solves the 3x3 system `a x = b` (Cramer's rule).
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    let mut x = [0.0; 3];
    for c in 0..3 {
        let mut m = a;
        for i in 0..3 {
            m[i][c] = b[i];
        }
        x[c] = det(m) / d;
    }
    x
}

/// Each row of `study.csv` by (condition, channel), for sea state `ss`.
fn by_condition(
    rows: &[BTreeMap<String, String>],
    ss: usize,
) -> BTreeMap<(String, String), BTreeMap<String, String>> {
    rows.iter()
        .filter(|r| r["sea_state"] == ss.to_string())
        .map(|r| ((r["condition"].clone(), r["channel"].clone()), r.clone()))
        .collect()
}

/// The neighbours of a broken line carry the damaged mooring's static equilibrium
/// tensions within 1 % once the transient has died out (and the intact lines the
/// intact mooring's), the buoy's offset is the equilibrium's; the design check applies
/// the consequence class's ULS factors to the intact condition and its ALS factors to
/// the damaged one, leaves the broken line out of its own condition, and the summary
/// names the governing condition and line of each limit state. Two shards merged give
/// the one machine's files.
#[test]
fn a_broken_lines_neighbours_carry_the_damaged_moorings_static_tensions() {
    let tmp = tempfile::tempdir().unwrap();
    let study = buoy_study(
        tmp.path(),
        r#"
[study]
seed = 7
seeds = 2
duration = 400.0
transient = 300.0
sea_states = [ { name = "calm", hs = 0.1, tp = 6.0 } ]
channels = ["default"]

[study.conditions]
broken = ["leg0"]

[study.design]
consequence_class = 1
capacities = { rope = 1.0e5 }
"#,
    );
    let s = study.to_str().unwrap();
    let one = tmp.path().join("one");
    run_ok(&["study", "run", s, "-q", "--out", one.to_str().unwrap()]);
    let rows = read_csv(&one.join("study.csv"));
    let t = by_condition(&rows, 0);
    // Two conditions x one sea state x two seeds.
    let members = read_csv(&one.join("members.csv"));
    let mut conds: Vec<&str> = members.iter().map(|r| r["condition"].as_str()).collect();
    conds.dedup();
    assert_eq!(conds, ["intact", "leg0"]);

    let intact = equilibrium([0.0, -15.0, 0.0], &[0, 1, 2]);
    let damaged = equilibrium([-25.0, -5.0, 0.0], &[1, 2]);
    let (_, t_intact) = balance(intact, &[0, 1, 2]);
    let (_, t_damaged) = balance(damaged, &[1, 2]);
    assert!(
        intact[0].abs() < 1e-6,
        "the intact pose is centred: {intact:?}"
    );
    assert!(
        damaged[0] < -10.0,
        "the damaged mooring lets the buoy drift: {damaged:?}"
    );
    for (cond, legs, tensions) in [
        ("intact", vec![0, 1, 2], &t_intact),
        ("leg0", vec![1, 2], &t_damaged),
    ] {
        for (k, want) in legs.iter().zip(tensions.iter()) {
            let row = &t[&(cond.to_string(), format!("leg{k}.end_force"))];
            let (mean, std) = (num(row, "mean"), num(row, "std"));
            assert!(
                (mean - want).abs() <= 0.01 * want,
                "{cond}: leg{k} carries {mean} N, the static equilibrium {want} N"
            );
            // At rest after the transient.
            assert!(
                std <= 0.01 * mean,
                "{cond}: leg{k} still moving (std {std} N)"
            );
        }
    }
    // The buoy's offset from its reference position.
    for (cond, q) in [("intact", intact), ("leg0", damaged)] {
        let row = &t[&(cond.to_string(), "buoy.offset".to_string())];
        assert_eq!(row["unit"], "m");
        let want = q[0].abs();
        let got = num(row, "mean");
        assert!(
            (got - want).abs() <= 0.01 * want.max(1.0),
            "{cond}: offset {got} m, the equilibrium's {want} m"
        );
    }
    // The design check: ULS factors (class 1: 1.1, 1.5) intact, ALS (1.0, 1.1) damaged;
    // the broken line has none in its own condition.
    let row_of = |c: &str, ch: &str| t[&(c.to_string(), ch.to_string())].clone();
    let f = |c: &str, ch: &str| {
        let r = row_of(c, ch);
        (num(&r, "mean_factor"), num(&r, "dynamic_factor"))
    };
    assert_eq!(f("intact", "leg0.end_force"), (1.1, 1.5));
    assert_eq!(f("leg0", "leg1.end_force"), (1.0, 1.1));
    assert_eq!(row_of("leg0", "leg1.end_force")["limit_state"], "als");
    assert!(row_of("leg0", "leg0.end_force")["utilisation"].is_empty());
    let row = &row_of("leg0", "leg1.end_force");
    let (mean, mpm) = (num(row, "mean"), num(row, "mpm"));
    let td = 1.0 * mean + 1.1 * (mpm - mean);
    assert!((num(row, "design_tension") - td).abs() <= 1e-9 * td);
    // The governing condition and line of each limit state.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(one.join("study.json")).unwrap()).unwrap();
    let gov = json["governing"].as_array().unwrap();
    assert_eq!(gov.len(), 2);
    assert_eq!(gov[0]["limit_state"], "uls");
    assert_eq!(gov[0]["condition_name"], "intact");
    assert_eq!(gov[1]["limit_state"], "als");
    assert_eq!(gov[1]["condition_name"], "leg0");
    let line = gov[1]["line"].as_str().unwrap();
    assert!(line == "leg1" || line == "leg2", "{line}");
    // It is the largest utilisation of the damaged condition's rows.
    let largest = rows
        .iter()
        .filter(|r| r["condition"] == "leg0" && !r["utilisation"].is_empty())
        .map(|r| num(r, "utilisation"))
        .fold(f64::MIN, f64::max);
    assert_eq!(gov[1]["utilisation"].as_f64().unwrap(), largest);
    assert_eq!(json["conditions"].as_array().unwrap().len(), 2);

    // Two shards, merged: the one machine's files.
    let (s1, s2, merged) = (
        tmp.path().join("s1"),
        tmp.path().join("s2"),
        tmp.path().join("m"),
    );
    for (k, d) in [("1/2", &s1), ("2/2", &s2)] {
        run_ok(&[
            "study",
            "run",
            s,
            "-q",
            "--shard",
            k,
            "--out",
            d.to_str().unwrap(),
        ]);
    }
    run_ok(&[
        "study",
        "merge",
        s1.to_str().unwrap(),
        s2.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    for f in ["study.csv", "members.csv", "study.json"] {
        let a = std::fs::read(one.join(f)).unwrap();
        let b = std::fs::read(merged.join(f)).unwrap();
        assert!(
            a == b,
            "{f} differs between one machine and the merged shards"
        );
    }
}

/// A line that fails at a time in the record: before it, the member holds the intact
/// tensions; after it, the broken line's fairlead force drops to nothing and its
/// neighbours take up the load (their maximum, in the transient, above the intact
/// mean). With a fatigue scatter diagram the damaged condition runs the extreme sea
/// state only, a sea state of its own `seeds` count runs that many, the fatigue is the
/// intact mooring's, and the shards and the Slurm path carry both.
#[test]
fn a_line_failing_in_the_record_and_a_scatter_diagram_run_as_their_own_members() {
    let tmp = tempfile::tempdir().unwrap();
    let study = buoy_study(
        tmp.path(),
        r#"
[study]
seed = 7
seeds = 2
duration = 120.0
transient = 20.0
sea_states = [
  { name = "fatigue", hs = 0.1, tp = 6.0, seeds = 1, probability = 1.0 },
  { name = "extreme", hs = 0.2, tp = 7.0 },
]
channels = ["default"]

[study.conditions]
broken = ["leg0"]
fail_time = 40.0

[study.design]
mean_factor = 1.2
dynamic_factor = 1.6
accidental_mean_factor = 1.0
accidental_dynamic_factor = 1.2
capacities = { rope = 1.0e5 }

[study.fatigue]
design_fatigue_factor = 3.0

[fatigue]
[fatigue.line_types.rope]
curve = "spiral_rope"
area_m2 = 0.00098
"#,
    );
    let s = study.to_str().unwrap();
    let one = tmp.path().join("one");
    run_ok(&["study", "run", s, "-q", "--out", one.to_str().unwrap()]);
    let members = read_csv(&one.join("members.csv"));
    let mut seen: Vec<(String, String)> = members
        .iter()
        .map(|r| (r["condition"].clone(), r["sea_state"].clone()))
        .collect();
    seen.dedup();
    assert_eq!(
        seen,
        [
            ("intact".to_string(), "0".to_string()),
            ("intact".to_string(), "1".to_string()),
            ("leg0".to_string(), "1".to_string())
        ],
        "the damaged condition runs the extreme sea state only"
    );
    let t = by_condition(&read_csv(&one.join("study.csv")), 1);
    let get = |c: &str, ch: &str| t[&(c.to_string(), ch.to_string())].clone();
    // The broken line's force drops to nothing once it has failed.
    let broken = get("leg0", "leg0.end_force");
    assert!(num(&broken, "min_smallest") < 0.01 * num(&get("intact", "leg0.end_force"), "mean"));
    // Its neighbours take up the load.
    for k in [1, 2] {
        let ch = format!("leg{k}.end_force");
        assert!(num(&get("leg0", &ch), "max_largest") > 1.05 * num(&get("intact", &ch), "mean"));
    }
    // The given factors, by limit state.
    assert_eq!(num(&get("intact", "leg1.end_force"), "mean_factor"), 1.2);
    assert_eq!(num(&get("leg0", "leg1.end_force"), "dynamic_factor"), 1.2);
    // Fatigue: the intact members only (3 legs x 2 ends x 2 sea states).
    let fat = read_csv(&one.join("fatigue.csv"));
    assert_eq!(fat.len(), 12);
    // The fatigue sea state runs its one seed, the extreme one the study's two.
    for r in &fat {
        let want = if r["sea_state"] == "0" { "1" } else { "2" };
        assert_eq!(r["seeds"], want, "{r:?}");
    }
    assert_eq!(
        members.iter().filter(|r| r["sea_state"] == "0").count(),
        10,
        "one member x 10 channels"
    );
    // Two shards, merged: the one machine's files, fatigue.csv among them.
    let (s1, s2, merged) = (
        tmp.path().join("s1"),
        tmp.path().join("s2"),
        tmp.path().join("m"),
    );
    for (k, d) in [("1/2", &s1), ("2/2", &s2)] {
        run_ok(&[
            "study",
            "run",
            s,
            "-q",
            "--shard",
            k,
            "--out",
            d.to_str().unwrap(),
        ]);
    }
    run_ok(&[
        "study",
        "merge",
        s2.to_str().unwrap(),
        s1.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    for f in ["study.csv", "members.csv", "study.json", "fatigue.csv"] {
        let a = std::fs::read(one.join(f)).unwrap();
        let b = std::fs::read(merged.join(f)).unwrap();
        assert!(
            a == b,
            "{f} differs between one machine and the merged shards"
        );
    }
    // The Slurm path (the submission script under a stand-in `sbatch` that runs each
    // task at once): three shards and their merge give the same four files.
    let bin = tmp.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let sbatch = bin.join("sbatch");
    std::fs::write(&sbatch, super::study_run::FAKE_SBATCH).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&sbatch, std::fs::Permissions::from_mode(0o755)).unwrap();
    let runs = tmp.path().join("runs");
    run_ok(&[
        "study",
        "slurm",
        s,
        "--shards",
        "3",
        "--out",
        runs.to_str().unwrap(),
    ]);
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap());
    let out = Command::new("bash")
        .arg(runs.join("submit.sh"))
        .arg("--wait")
        .env("PATH", path)
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("merged: study.csv, members.csv, study.json, fatigue.csv in"),
        "{text}"
    );
    for f in ["study.csv", "members.csv", "study.json", "fatigue.csv"] {
        let a = std::fs::read(one.join(f)).unwrap();
        let b = std::fs::read(runs.join(f)).unwrap();
        assert!(a == b, "{f} differs between one machine and the Slurm path");
    }
    // The command line's closing line lists fatigue.csv.
    let out = run(&[
        "study",
        "merge",
        s1.to_str().unwrap(),
        s2.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(
        e.contains("study.csv, members.csv, study.json, fatigue.csv in"),
        "{e}"
    );
}

/// Bad `[study.conditions]` and design factors are refused by key.
#[test]
fn bad_conditions_are_refused_by_key() {
    let tmp = tempfile::tempdir().unwrap();
    let base = r#"
[study]
seeds = 1
duration = 20.0
transient = 5.0
sea_states = [ { hs = 0.1, tp = 6.0 } ]
"#;
    for (extra, key, words) in [
        (
            "[study.conditions]\nbroken = [\"leg0\", \"leg9\"]\n",
            "study.conditions.broken[1]",
            "no cable named \"leg9\"",
        ),
        (
            "[study.conditions]\nbroken = \"some\"\n",
            "study.conditions.broken",
            "\"each\" or a list",
        ),
        (
            "[study.conditions]\nbroken = \"each\"\nfail_time = 30.0\n",
            "study.conditions.fail_time",
            "after the record ends",
        ),
        (
            "[study.conditions]\nintact = false\n",
            "study.conditions.intact",
            "no condition",
        ),
        (
            "[study.conditions]\nbroken = \"each\"\n[study.design]\nmean_factor = 1.1\ndynamic_factor = 1.5\ncapacities = { rope = 1.0e5 }\n",
            "study.design.accidental_mean_factor",
            "consequence_class",
        ),
        (
            "[study.design]\nconsequence_class = 3\ncapacities = { rope = 1.0e5 }\n",
            "study.design.consequence_class",
            "1 or 2",
        ),
        (
            "[study.design]\nconsequence_class = 2\naccidental_mean_factor = 1.0\ncapacities = { rope = 1.0e5 }\n",
            "study.design.accidental_mean_factor",
            "no damaged condition",
        ),
    ] {
        let p = buoy_study(tmp.path(), &format!("{base}{extra}"));
        let out = run(&["study", "run", p.to_str().unwrap(), "-q", "--out", tmp.path().join("o").to_str().unwrap()]);
        let e = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{extra} was accepted");
        assert!(e.contains(key) && e.contains(words), "{extra}: {e}");
        assert!(e.contains("buoy_study.toml"), "{e}");
    }
}
