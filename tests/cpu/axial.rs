//! Nonlinear axial stiffness (a strain-tension curve per line type) and cables of
//! several sections: the static shape of a hanging line from a scenario file against
//! the elastic catenary integrated with the same curves (an independent quadrature of
//! the continuous line, not the discrete model), and the curve's bad input.

use cablesim::cpu::CpuSolver;
use cablesim::options::SolverOptions;
use cablesim::physics::{tabulated_slope, tabulated_tension, tabulated_work};
use cablesim::scenario::Scenario;
use std::path::Path;

/// A section of the continuous line: unstretched length (m), wet weight per length
/// (N/m), and its curve rows (or one EA).
struct Section {
    length: f64,
    w: f64,
    curve: Option<Vec<[f64; 2]>>,
    ea: f64,
}

/// The strain at tension `t` of a section: the inverse of its curve, written here from
/// the rows (linear from (0, 0) to the first row, between rows, and on with the last
/// slope), or `t / EA`.
fn strain_of(s: &Section, t: f64) -> f64 {
    let Some(rows) = &s.curve else {
        return t / s.ea;
    };
    let mut pts = vec![[0.0, 0.0]];
    pts.extend(rows.iter().copied().filter(|r| r[0] > 0.0));
    let n = pts.len();
    let mut k = 1;
    while k + 1 < n && pts[k][1] < t {
        k += 1;
    }
    let (p, q) = (pts[k - 1], pts[k]);
    p[0] + (t - p[1]) * (q[0] - p[0]) / (q[1] - p[1])
}

/// The far end `(x, z)` of the continuous line from its start at the origin, for the
/// horizontal tension `h` and the vertical tension `v0` at the start (N): the line
/// `dx/ds = (1 + eps) H / T`, `dz/ds = (1 + eps) V / T` with `V(s) = v0 + int w`, by
/// Simpson's rule on each section.
fn far_end(secs: &[Section], h: f64, v0: f64) -> (f64, f64) {
    let (mut x, mut z, mut v) = (0.0, 0.0, v0);
    for s in secs {
        let m = 4000;
        let ds = s.length / m as f64;
        let f = |vv: f64| {
            let t = (h * h + vv * vv).sqrt();
            let e = 1.0 + strain_of(s, t);
            (e * h / t, e * vv / t)
        };
        for k in 0..m {
            let va = v + s.w * ds * k as f64;
            let (a, b, c) = (f(va), f(va + 0.5 * s.w * ds), f(va + s.w * ds));
            x += ds / 6.0 * (a.0 + 4.0 * b.0 + c.0);
            z += ds / 6.0 * (a.1 + 4.0 * b.1 + c.1);
        }
        v += s.w * s.length;
    }
    (x, z)
}

/// Newton's method for `(h, v0)` that put the far end at `(x, z)`, from `guess`.
fn solve(secs: &[Section], x: f64, z: f64, guess: (f64, f64)) -> (f64, f64) {
    let (mut h, mut v0) = guess;
    for _ in 0..60 {
        let (fx, fz) = far_end(secs, h, v0);
        let (rx, rz) = (fx - x, fz - z);
        if rx.abs() + rz.abs() < 1e-9 {
            break;
        }
        let (dh, dv) = (
            1e-6 * h.abs().max(1.0),
            1e-6 * (h.abs() + v0.abs()).max(1.0),
        );
        let (hx, hz) = far_end(secs, h + dh, v0);
        let (vx, vz) = far_end(secs, h, v0 + dv);
        let j = [
            [(hx - fx) / dh, (vx - fx) / dv],
            [(hz - fz) / dh, (vz - fz) / dv],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        h -= (j[1][1] * rx - j[0][1] * rz) / det;
        v0 -= (-j[1][0] * rx + j[0][0] * rz) / det;
    }
    let (fx, fz) = far_end(secs, h, v0);
    assert!(
        (fx - x).abs() + (fz - z).abs() < 1e-6,
        "reference not converged"
    );
    (h, v0)
}

const G: f64 = 9.81;
const RHO: f64 = 1025.0;

fn wet(mass: f64, d: f64) -> f64 {
    (mass - RHO * std::f64::consts::PI * d * d / 4.0) * G
}

const HEAD: &str = r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0
backend = "cpu"

[environment]
gravity = 9.81
water_density = 1025.0
depth = 1000.0
"#;

/// A polyester-like stiffening curve (strain, tension in N).
const POLY: [[f64; 2]; 5] = [
    [0.005, 1.0e5],
    [0.01, 3.0e5],
    [0.02, 9.0e5],
    [0.03, 1.8e6],
    [0.05, 4.0e6],
];

fn poly_toml() -> String {
    let rows: Vec<String> = POLY
        .iter()
        .map(|r| format!("[{:?}, {:?}]", r[0], r[1]))
        .collect();
    format!(
        r#"
[[line_types]]
name = "polyester"
diameter = 0.15
mass_per_length = 40.0
ea_curve = [{}]
damping = 0.01

[[line_types]]
name = "chain"
diameter = 0.12
mass_per_length = 100.0
ea = 1.0e9
damping = 0.001
"#,
        rows.join(", ")
    )
}

/// The static end tensions of the scenario's one cable (start, end) and the end
/// positions, from the relaxed initial state.
fn relaxed_tensions(text: &str) -> ([f64; 2], [[f64; 3]; 2], cablesim::model::Layout) {
    let sc = Scenario::parse(text, Path::new("/tmp/axial.toml")).unwrap();
    let (lay, pos, residual) = cablesim::initial::prepare(&sc).unwrap();
    assert!(residual < 1e-3, "relaxation residual {residual} N");
    let mut s = CpuSolver::new(lay.clone(), &pos, SolverOptions::default());
    let ev = s.evaluate().unwrap();
    let f = cablesim::output::end_forces(&lay, &ev, &lay.cables[0]);
    let n = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let c = &lay.cables[0];
    (
        [n(f.start), n(f.end)],
        [
            pos[c.nodes[0] as usize],
            pos[*c.nodes.last().unwrap() as usize],
        ],
        lay,
    )
}

fn check_against_reference(name: &str, text: &str, secs: &[Section]) -> f64 {
    let (t, ends, lay) = relaxed_tensions(text);
    let dx = ((ends[1][0] - ends[0][0]).powi(2) + (ends[1][1] - ends[0][1]).powi(2)).sqrt();
    let dz = ends[1][2] - ends[0][2];
    // Start Newton from the anchor tension along the chord, less half the weight.
    let total_w: f64 = secs.iter().map(|s| s.w * s.length).sum();
    let chord = (dx * dx + dz * dz).sqrt();
    let (h, v0) = solve(
        secs,
        dx,
        dz,
        (t[0] * dx / chord, t[0] * dz / chord - 0.5 * total_w),
    );
    let ta = (h * h + v0 * v0).sqrt();
    let tb = (h * h + (v0 + total_w).powi(2)).sqrt();
    let ea = (t[0] - ta).abs() / ta;
    let eb = (t[1] - tb).abs() / tb;
    eprintln!(
        "{name}: {} elements; anchor T {:.6e} N (reference {ta:.6e}, {:.4}%), fairlead T {:.6e} N \
         (reference {tb:.6e}, {:.4}%)",
        lay.n_elements(),
        t[0],
        100.0 * ea,
        t[1],
        100.0 * eb
    );
    assert!(
        ea < 0.005 && eb < 0.005,
        "{name}: end tensions off the reference by more than 0.5%"
    );
    ea.max(eb)
}

/// A hanging polyester line whose strain runs over several rows of its curve.
#[test]
fn tabulated_line_matches_the_elastic_catenary_with_its_curve() {
    let text = format!(
        "{HEAD}{}\n{}",
        poly_toml(),
        r#"
[[cables]]
name = "rope"
line_type = "polyester"
length = 490.0
segments = 60
start = { fixed = [0.0, 0.0, -600.0] }
end = { fixed = [400.0, 0.0, -300.0] }
initial = "catenary"
"#
    );
    let secs = [Section {
        length: 490.0,
        w: wet(40.0, 0.15),
        curve: Some(POLY.to_vec()),
        ea: 0.0,
    }];
    let (t, _, _) = relaxed_tensions(&text);
    // The strain at the ends lies past the curve's first rows: its nonlinear part.
    let eps = strain_of(&secs[0], t[1]);
    assert!(eps > 0.012 && eps < 0.05, "strain {eps}");
    check_against_reference("polyester", &text, &secs);
}

/// Chain - polyester - chain in one cable (no points between), against the
/// continuous line of the three sections.
#[test]
fn chain_rope_chain_cable_matches_the_multi_section_catenary() {
    let text = format!(
        "{HEAD}{}\n{}",
        poly_toml(),
        r#"
[[cables]]
name = "mooring"
start = { fixed = [0.0, 0.0, -900.0] }
end = { fixed = [500.0, 0.0, -100.0] }
initial = "catenary"
sections = [
    { line_type = "chain", length = 100.0, segments = 20 },
    { line_type = "polyester", length = 800.0, segments = 40 },
    { line_type = "chain", length = 50.0, segments = 10 },
]
"#
    );
    let chain = |length| Section {
        length,
        w: wet(100.0, 0.12),
        curve: None,
        ea: 1.0e9,
    };
    let secs = [
        chain(100.0),
        Section {
            length: 800.0,
            w: wet(40.0, 0.15),
            curve: Some(POLY.to_vec()),
            ea: 0.0,
        },
        chain(50.0),
    ];
    let sc = Scenario::parse(&text, Path::new("/tmp/axial.toml")).unwrap();
    let (lay, _) = cablesim::model::Layout::build(&sc.model).unwrap();
    // One cable, one block, each element with its section's line type and length.
    assert_eq!(lay.cables.len(), 1);
    assert_eq!(lay.n_elements(), 70);
    let lines: Vec<u32> = lay.elem_line.clone();
    assert!(lines[..20].iter().all(|&l| l == 1) && lines[60..].iter().all(|&l| l == 1));
    assert!(lines[20..60].iter().all(|&l| l == 0));
    assert!((lay.elem_l0[0] - 5.0).abs() < 1e-12 && (lay.elem_l0[30] - 20.0).abs() < 1e-12);
    check_against_reference("chain-polyester-chain", &text, &secs);
}

/// The curve functions: slack at and below zero strain, linear from (0, 0), the
/// last slope past the last row, and the work integral against its closed form.
#[test]
fn tabulated_curve_functions() {
    let rows = POLY.to_vec();
    assert_eq!(tabulated_tension(&rows, -0.01), 0.0);
    assert_eq!(tabulated_tension(&rows, 0.0), 0.0);
    assert!((tabulated_tension(&rows, 0.0025) - 5.0e4).abs() < 1e-6);
    assert!((tabulated_tension(&rows, 0.015) - 6.0e5).abs() < 1e-6);
    // Past the last row: on with the slope (4e6 - 1.8e6) / 0.02 = 1.1e8.
    assert!((tabulated_tension(&rows, 0.06) - (4.0e6 + 0.01 * 1.1e8)).abs() < 1e-3);
    assert!((tabulated_slope(&rows, 0.06) - 1.1e8).abs() < 1e-3);
    // Work from 0 to 0.01: triangle (0.005 * 1e5 / 2) plus trapezoid.
    let w = 0.5 * 0.005 * 1.0e5 + 0.5 * 0.005 * (1.0e5 + 3.0e5);
    assert!((tabulated_work(&rows, 0.0, 0.01) - w).abs() < 1e-9 * w);
    // Additive, and odd in the increment.
    let (a, b) = (
        tabulated_work(&rows, 0.0, 0.013),
        tabulated_work(&rows, 0.013, 0.024),
    );
    assert!((a + b - tabulated_work(&rows, 0.0, 0.037)).abs() < 1e-9 * (a + b));
    assert!((tabulated_work(&rows, 0.037, -0.024) + b).abs() < 1e-9 * b);
}

/// A curve that does not increase, has one row, or holds a non-finite value: an error
/// naming the file, the line type, the row and the value.
#[test]
fn bad_curves_are_refused_with_the_row_and_value() {
    let case = |curve: &str| {
        let text = format!(
            "{HEAD}\n[[line_types]]\nname = \"rope\"\ndiameter = 0.1\nmass_per_length = 20.0\n\
             ea_curve = {curve}\n\n[[cables]]\nname = \"c\"\nline_type = \"rope\"\nlength = 100.0\n\
             segments = 10\nstart = {{ fixed = [0.0, 0.0, -200.0] }}\nend = {{ fixed = [90.0, 0.0, -180.0] }}\n"
        );
        Scenario::parse(&text, Path::new("/tmp/bad_curve.toml"))
            .err()
            .expect("refused")
            .to_string()
    };
    let e = case("[[0.01, 1e5], [0.02, 3e5], [0.015, 4e5]]");
    assert!(
        e.contains("/tmp/bad_curve.toml")
            && e.contains("line_types[0]")
            && e.contains("row 3")
            && e.contains("0.015"),
        "{e}"
    );
    let e = case("[[0.01, 1e5], [0.02, 0.9e5]]");
    assert!(
        e.contains("row 2") && e.contains("tensions must increase") && e.contains("90000"),
        "{e}"
    );
    let e = case("[[0.01, 1e5]]");
    assert!(e.contains("at least two rows"), "{e}");
    let e = case("[[0.01, 1e5], [0.02, nan]]");
    assert!(
        e.contains("row 2") && e.contains("finite") && e.contains("NaN"),
        "{e}"
    );
    let e = case("[[0.0, 1e3], [0.02, 3e5]]");
    assert!(e.contains("row 1") && e.contains("zero strain"), "{e}");
}

/// A curve from a file: read relative to the scenario, with errors naming the file and
/// its line.
#[test]
fn curve_files_are_read_and_their_errors_name_the_line() {
    let dir = std::env::temp_dir().join(format!("cablesim_curve_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scenario = dir.join("rope.toml");
    let text = format!(
        "{HEAD}\n[[line_types]]\nname = \"rope\"\ndiameter = 0.1\nmass_per_length = 20.0\n\
         ea_curve_file = \"rope_curve.txt\"\n\n[[cables]]\nname = \"c\"\nline_type = \"rope\"\n\
         length = 100.0\nsegments = 10\nstart = {{ fixed = [0.0, 0.0, -200.0] }}\n\
         end = {{ fixed = [90.0, 0.0, -180.0] }}\n"
    );
    std::fs::write(&scenario, &text).unwrap();
    std::fs::write(
        dir.join("rope_curve.txt"),
        "# strain  tension (N)\n0.005 1.0e5\n0.01, 3.0e5\n\n0.02 9.0e5  # last\n",
    )
    .unwrap();
    let sc = Scenario::load(&scenario).unwrap();
    assert_eq!(
        sc.model.line_types[0].ea_curve.as_deref(),
        Some(&[[0.005, 1.0e5], [0.01, 3.0e5], [0.02, 9.0e5]][..])
    );
    // EA is the curve's largest slope: (9e5 - 3e5) / 0.01.
    assert!((sc.model.line_types[0].ea - 6.0e7).abs() < 1e-3);
    std::fs::write(dir.join("rope_curve.txt"), "0.005 1.0e5\n0.01 x\n").unwrap();
    let e = Scenario::load(&scenario).err().unwrap().to_string();
    assert!(
        e.contains("rope_curve.txt") && e.contains("line 2") && e.contains("0.01 x"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `sections` with `line_type`, an unknown line type in a section, a section of zero
/// segments: errors naming the cable and the section's key.
#[test]
fn bad_sections_are_refused_naming_the_section() {
    let case = |cable: &str| {
        let text = format!(
            "{HEAD}{}\n[[cables]]\nname = \"m\"\nstart = {{ fixed = [0.0, 0.0, -900.0] }}\n\
             end = {{ fixed = [500.0, 0.0, -100.0] }}\n{cable}\n",
            poly_toml()
        );
        Scenario::parse(&text, Path::new("/tmp/bad_sections.toml"))
            .err()
            .expect("refused")
            .to_string()
    };
    let e = case(
        "line_type = \"chain\"\nsections = [{ line_type = \"chain\", length = 10.0, segments = 2 }]",
    );
    assert!(
        e.contains("cables[0]") && e.contains("sections") && e.contains("not both"),
        "{e}"
    );
    let e = case(
        "sections = [{ line_type = \"chain\", length = 10.0, segments = 2 }, \
         { line_type = \"nylon\", length = 10.0, segments = 2 }]",
    );
    assert!(
        e.contains("sections[1].line_type") && e.contains("\"nylon\""),
        "{e}"
    );
    let e = case("sections = [{ line_type = \"chain\", length = 10.0, segments = 0 }]");
    assert!(
        e.contains("sections[0].segments") && e.contains("got 0"),
        "{e}"
    );
    let e = case("length = 10.0\nsegments = 2");
    assert!(e.contains("line_type") && e.contains("sections"), "{e}");
}
