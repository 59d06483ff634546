//! A seabed grid (`[environment] seabed_file`): a chain on a 4 degree slope relaxed to
//! its static equilibrium against the sloped elastic catenary (computed here), the run
//! that follows staying at rest, and the errors for ends off or under the grid.

use cablesim::cpu::CpuSolver;
use cablesim::initial::prepare;
use cablesim::options::{Scheme, SolverOptions};
use cablesim::scenario::Scenario;
use std::path::{Path, PathBuf};

const ALPHA_DEG: f64 = 4.0;
const SPAN: f64 = 470.0;
const RISE: f64 = 90.0;
const LENGTH: f64 = 500.0;
const EA: f64 = 7.5e9;

fn wet_weight() -> f64 {
    (100.0 - 1025.0 * std::f64::consts::PI * 0.1 * 0.1 / 4.0) * 9.81
}

/// The elastic catenary from an anchor on a frictionless seabed of slope `alpha`
/// (rising towards the fairlead) to a fairlead `x`, `z` from it: the grounded length
/// `LB` lies on the slope with its tension growing by `w sin(alpha)` per metre up the
/// slope (no friction); the suspended part leaves the slope tangentially (vertical
/// tension `H tan(alpha)` at touchdown). Returns `(H, LB, anchor tension, fairlead
/// tension)`; Newton's method on `(H, LB)`.
fn sloped_catenary(x: f64, z: f64, l: f64, ea: f64, w: f64, alpha: f64) -> (f64, f64, f64, f64) {
    let (sa, ca, ta) = (alpha.sin(), alpha.cos(), alpha.tan());
    let res = |h: f64, lb: f64| {
        let t_a = h / ca - w * sa * lb;
        let g = lb + (t_a * lb + w * sa * lb * lb / 2.0) / ea;
        let ls = l - lb;
        let (v0, vf) = (h * ta, h * ta + w * ls);
        let xs = h / w * ((vf / h).asinh() - (v0 / h).asinh()) + h * ls / ea;
        let zs = h / w * ((1.0 + (vf / h).powi(2)).sqrt() - (1.0 + (v0 / h).powi(2)).sqrt())
            + (vf * vf - v0 * v0) / (2.0 * ea * w);
        (
            [g * ca + xs - x, g * sa + zs - z],
            t_a,
            (h * h + vf * vf).sqrt(),
        )
    };
    let (mut h, mut lb) = (1e5, l / 3.0);
    for _ in 0..100 {
        let (r, _, _) = res(h, lb);
        let (dh, dl) = (1e-6 * h, 1e-6 * lb);
        let (rh, _, _) = res(h + dh, lb);
        let (rl, _, _) = res(h, lb + dl);
        let j = [
            [(rh[0] - r[0]) / dh, (rl[0] - r[0]) / dl],
            [(rh[1] - r[1]) / dh, (rl[1] - r[1]) / dl],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        h -= (j[1][1] * r[0] - j[0][1] * r[1]) / det;
        lb -= (j[0][0] * r[1] - j[1][0] * r[0]) / det;
    }
    let (r, t_a, t_f) = res(h, lb);
    assert!(r[0].abs() < 1e-6 && r[1].abs() < 1e-6, "{r:?}");
    (h, lb, t_a, t_f)
}

/// A folder with a plane seabed grid `z = z0 + x tan(alpha)` (3 x 2 points) and a
/// scenario of one chain from an anchor on it at `x = 0` to a fairlead `SPAN`, `RISE`
/// away.
fn slope_case(segments: usize, anchor_z_offset: f64, tag: &str) -> (PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("cablesim_slope_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let t = ALPHA_DEG.to_radians().tan();
    let z0 = -100.0;
    let xs = [-50.0, 200.0, 600.0];
    let mut grid = format!("3 2\n{} {} {}\n-50 50\n", xs[0], xs[1], xs[2]);
    for x in xs {
        for y in [-50.0, 50.0] {
            grid += &format!("{x} {y} {:.17e}\n", z0 + x * t);
        }
    }
    std::fs::write(dir.join("slope.txt"), grid).unwrap();
    let text = format!(
        r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0
backend = "cpu"

[environment]
seabed_file = "slope.txt"

[environment.seabed]
stiffness = 3.0e6
damping = 3.0e4

[[line_types]]
name = "chain"
diameter = 0.1
mass_per_length = 100.0
ea = {EA:e}
damping = 1.0e-3
cn = 2.4
ct = 0.4
cm = 1.0

[[cables]]
name = "line1"
line_type = "chain"
length = {LENGTH:e}
segments = {segments}
start = {{ fixed = [0.0, 0.0, {za:e}] }}
end = {{ fixed = [{SPAN:e}, 0.0, {zf:e}] }}
initial = "catenary"
"#,
        za = z0 + anchor_z_offset,
        zf = z0 + RISE
    );
    (dir, text)
}

fn load(dir: &Path, text: &str) -> Result<Scenario, String> {
    Scenario::parse(text, &dir.join("slope.toml")).map_err(|e| e.to_string())
}

#[test]
fn chain_on_a_slope_matches_the_sloped_catenary() {
    let w = wet_weight();
    let alpha = ALPHA_DEG.to_radians();
    let (h, lb, t_a, t_f) = sloped_catenary(SPAN, RISE, LENGTH, EA, w, alpha);
    // The slope matters: on flat ground the anchor would hold the whole H.
    let (h0, _, t_a0, t_f0) = sloped_catenary(SPAN, RISE, LENGTH, EA, w, 0.0);
    println!("analytic, 4 deg: H {h:.1} N, LB {lb:.2} m, anchor {t_a:.1} N, fairlead {t_f:.1} N");
    println!("analytic, flat: H {h0:.1} N, anchor {t_a0:.1} N, fairlead {t_f0:.1} N");
    assert!(t_a < 0.5 * h);
    let mut errs = Vec::new();
    for n in [50, 100] {
        let (dir, text) = slope_case(n, 0.0, &format!("n{n}"));
        let sc = load(&dir, &text).unwrap();
        let (lay, pos, residual) = prepare(&sc).unwrap();
        let grid = lay.env.seabed.grid.expect("the grid");
        // Every node rests on or above the slope (within the contact's own
        // penetration, w / K ~ 3e-4 m).
        for (i, p) in pos.iter().enumerate() {
            let zb = grid.height(p[0], p[1]);
            assert!(
                p[2] > zb - 1e-3,
                "node {i} at {p:?} is below the seabed {zb}"
            );
        }
        let opts = SolverOptions {
            scheme: Scheme::Symplectic,
            dt: 2e-4,
            ..SolverOptions::default()
        };
        let mut s = CpuSolver::new(lay.clone(), &pos, opts);
        let ev = s.evaluate().unwrap();
        let fa = ev.reaction[0];
        let ff = ev.reaction[1];
        let norm = |f: [f64; 3]| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let (ea_, ef) = ((norm(fa) - t_a) / t_a, (norm(ff) - t_f) / t_f);
        println!(
            "{n} segments: fairlead {:.1} N ({:+.3} %), anchor {:.1} N ({:+.2} %), residual {residual:.2e} N",
            norm(ff),
            100.0 * ef,
            norm(fa),
            100.0 * ea_
        );
        assert!(ef.abs() < 0.01, "{n} segments: fairlead force off by {ef}");
        assert!(ea_.abs() < 0.15, "{n} segments: anchor force off by {ea_}");
        errs.push((ef.abs(), ea_.abs()));
        if n == 50 {
            // Released from its static shape, the line stays at rest.
            s.advance(2000).unwrap();
            let moved = pos
                .iter()
                .enumerate()
                .map(|(i, b)| {
                    let a = s.r[i].to_f64();
                    norm([a[0] - b[0], a[1] - b[1], a[2] - b[2]])
                })
                .fold(0.0, f64::max);
            println!("50 segments: largest drift after 2000 steps {moved:.2e} m");
            assert!(moved < 0.02, "drifted {moved} m");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    assert!(
        errs[1].0 < errs[0].0 + 1e-4,
        "fairlead error grew: {errs:?}"
    );
}

#[test]
fn ends_off_or_under_the_grid_are_errors() {
    // The anchor 1 m under the slope.
    let (dir, text) = slope_case(10, -1.0, "under");
    let e = load(&dir, &text).unwrap_err();
    assert!(
        e.contains("cables[0]") && e.contains("below the seabed") && e.contains("slope.txt"),
        "{e}"
    );
    // The fairlead beyond the grid's last x (600 m), the anchor on the grid.
    let (_, on) = slope_case(10, 0.0, "under");
    assert!(load(&dir, &on).is_ok());
    let far = on.replace(&format!("fixed = [{SPAN:e}, 0.0"), "fixed = [650.0, 0.0");
    assert_ne!(far, on);
    let e = load(&dir, &far).unwrap_err();
    assert!(
        e.contains("outside the seabed grid") && e.contains("x in [-50, 600]"),
        "{e}"
    );
    // A missing file names itself.
    let e = load(&dir, &text.replace("slope.txt", "nothing.txt")).unwrap_err();
    assert!(
        e.contains("nothing.txt") && e.contains("cannot read"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
