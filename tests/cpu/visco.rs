//! The viscoelastic fibre rope (`physics::visco`, docs/src/model/axial.md): one rope
//! element stepped by the CPU solver under a step stretch and a sinusoidal stretch
//! against the model's closed-form response (the state's exponential relaxation, the
//! complex dynamic stiffness, its amplitude and phase), the mean-load dependent dynamic
//! stiffness, statics on the static stiffness, and the line-type keys' bad input.

use cablesim::cpu::CpuSolver;
use cablesim::options::{Scheme, SolverOptions};
use cablesim::physics::visco_dynamic_stiffness;
use cablesim::scenario::Scenario;
use std::path::Path;

/// Static and dynamic stiffness (N), the slope against the mean tension, the static
/// branch's and the dynamic spring's damping (N s).
#[derive(Clone, Copy)]
struct Rope {
    ks: f64,
    kd: f64,
    slope: f64,
    c1: f64,
    c2: f64,
}

const L0: f64 = 10.0;

/// One element of `rope` between fixed ends `L0 (1 + eps)` apart.
fn element(rope: Rope, eps: f64) -> (cablesim::model::Layout, Vec<[f64; 3]>) {
    let text = format!(
        r#"
[simulation]
duration = 1.0
dt = 0.001
output_interval = 1.0
backend = "cpu"

[environment]
gravity = 9.81
water_density = 1025.0
depth = 1000.0

[[line_types]]
name = "rope"
diameter = 0.1
mass_per_length = 10.0
ea = {:?}
ea_dynamic = {:?}
ea_dynamic_slope = {:?}
ba_static = {:?}
ba_dynamic = {:?}

[[cables]]
name = "e"
line_type = "rope"
length = {L0:?}
segments = 1
start = {{ fixed = [0.0, 0.0, -100.0] }}
end = {{ fixed = [{:?}, 0.0, -100.0] }}
"#,
        rope.ks,
        rope.kd,
        rope.slope,
        rope.c1,
        rope.c2,
        L0 * (1.0 + eps)
    );
    let sc = Scenario::parse(&text, Path::new("/tmp/visco.toml")).unwrap();
    cablesim::model::Layout::build(&sc.model).unwrap()
}

/// `K1` of the model at dynamic stiffness `k2`.
fn k1(ks: f64, k2: f64) -> f64 {
    k2 * ks / (k2 - ks)
}

/// The element at rest at strain `eps0`, then held at `eps1` from t = 0 (both ends on
/// fixed routes: the nodes do not move, only the state relaxes). Returns the tension
/// at times `dt * every * j`, j = 0..=n.
fn step_response(
    rope: Rope,
    eps0: f64,
    eps1: f64,
    scheme: Scheme,
    dt: f64,
    every: u64,
    n: usize,
) -> Vec<f64> {
    let (lay, mut pos) = element(rope, eps1);
    let target = pos[1];
    pos[1][0] = L0 * (1.0 + eps0);
    let opts = SolverOptions {
        dt,
        scheme,
        ..Default::default()
    };
    let mut cpu = CpuSolver::new(lay, &pos, opts);
    // At rest at eps0: the tension of the static stiffness.
    let t0 = cpu.evaluate().unwrap().tension[0];
    assert!(
        (t0 - rope.ks * eps0).abs() <= 1e-9 * rope.ks * eps0.abs().max(1e-3),
        "rest tension {t0}, static {}",
        rope.ks * eps0
    );
    cpu.r[1] = cablesim::math::V3::from_f64(target);
    let mut out = vec![cpu.evaluate().unwrap().tension[0]];
    for _ in 0..n {
        cpu.advance(every).unwrap();
        out.push(cpu.evaluate().unwrap().tension[0]);
    }
    // The ends did not move.
    assert_eq!(cpu.r[1].to_f64(), target);
    out
}

/// The closed-form step response of the model (constant dynamic stiffness): the state
/// relaxes from its rest value at eps0 to its rest value at eps1 as
/// `x(t) = x1 + (x0 - x1) exp(-t / tau)`, `tau = (c1 + c2) / (K1 + K2)`, and the tension
/// is `K1 x + c1 xdot`.
fn step_closed_form(rope: Rope, eps0: f64, eps1: f64, t: f64) -> f64 {
    let (k2, c) = (rope.kd, rope.c1 + rope.c2);
    let k1 = k1(rope.ks, k2);
    let x_of = |e: f64| k2 * e / (k1 + k2);
    let (x0, x1) = (x_of(eps0), x_of(eps1));
    let tau = c / (k1 + k2);
    let x = x1 + (x0 - x1) * (-t / tau).exp();
    let xdot = (k2 * eps1 - (k1 + k2) * x) / c;
    k1 * x + rope.c1 * xdot
}

const POLY: Rope = Rope {
    ks: 1.0e6,
    kd: 3.0e6,
    slope: 0.0,
    c1: 1.0e6,
    c2: 2.0e5,
};

#[test]
fn rope_element_under_a_step_stretch_relaxes_as_the_closed_form() {
    let (eps0, eps1) = (0.01, 0.02);
    let k2 = POLY.kd;
    let tau = (POLY.c1 + POLY.c2) / (k1(POLY.ks, k2) + k2);
    for (scheme, dt, tol) in [
        (Scheme::Symplectic, 1e-4f64, 2e-3),
        (Scheme::Rk2, 1e-3, 1e-4),
        (Scheme::Rk4, 1e-3, 1e-9),
    ] {
        let every = (0.02 / dt).round() as u64;
        let n = 100;
        let got = step_response(POLY, eps0, eps1, scheme, dt, every, n);
        let jump = POLY.ks * (eps1 - eps0);
        let mut worst: f64 = 0.0;
        for (j, &t) in got.iter().enumerate() {
            let time = j as f64 * every as f64 * dt;
            let want = step_closed_form(POLY, eps0, eps1, time);
            worst = worst.max((t - want).abs() / jump);
        }
        eprintln!("{scheme:?}: worst {worst:.3e} of the static jump {jump} N");
        assert!(worst < tol, "{scheme:?}: worst {worst:.3e} of the jump");
        // The instantaneous response is stiffer than the static one, and relaxes to it
        // (2 s = several tau).
        assert!(got[0] - POLY.ks * eps0 > 1.5 * jump, "first {}", got[0]);
        assert!(tau < 0.5);
        assert!(
            (got[n] - POLY.ks * eps1).abs() < 1e-3 * jump,
            "last {}",
            got[n]
        );
    }
}

#[test]
fn rope_element_under_a_sinusoidal_stretch_has_the_closed_form_dynamic_stiffness() {
    let (em, ea, period) = (0.02, 0.004, 2.0);
    let w = 2.0 * std::f64::consts::PI / period;
    let dt = 2e-4;
    let per = (period / dt).round() as usize;
    let (lay, pos) = element(POLY, em);
    let opts = SolverOptions {
        dt,
        ..Default::default()
    };
    let mut cpu = CpuSolver::new(lay, &pos, opts);
    let at = |t: f64| {
        (
            [L0 * (1.0 + em + ea * (w * t).sin()), 0.0, -100.0],
            [L0 * ea * w * (w * t).cos(), 0.0, 0.0],
        )
    };
    // Three periods of transient (tau is about 0.27 s), then two measured: the node is
    // put on the stretch before each step and each evaluation.
    let (skip, keep) = (3 * per, 2 * per);
    let (mut s_sin, mut s_cos, mut s_mean) = (0.0, 0.0, 0.0);
    for k in 0..skip + keep {
        let t = k as f64 * dt;
        let (r, v) = at(t);
        cpu.r[1] = cablesim::math::V3::from_f64(r);
        cpu.v[1] = cablesim::math::V3::from_f64(v);
        if k >= skip {
            let ten = cpu.evaluate().unwrap().tension[0];
            s_sin += ten * (w * t).sin();
            s_cos += ten * (w * t).cos();
            s_mean += ten;
        }
        cpu.advance(1).unwrap();
    }
    let n = keep as f64;
    let (re, im, mean) = (2.0 * s_sin / n / ea, 2.0 * s_cos / n / ea, s_mean / n);
    // K(w) = (K1 + i w c1) (K2 + i w c2) / (K1 + K2 + i w (c1 + c2)).
    let (k2, k1) = (POLY.kd, k1(POLY.ks, POLY.kd));
    let (ar, ai) = (k1, w * POLY.c1);
    let (br, bi) = (k2, w * POLY.c2);
    let (nr, ni) = (ar * br - ai * bi, ar * bi + ai * br);
    let (dr, di) = (k1 + k2, w * (POLY.c1 + POLY.c2));
    let d2 = dr * dr + di * di;
    let (kr, ki) = ((nr * dr + ni * di) / d2, (ni * dr - nr * di) / d2);
    let kmag = (kr * kr + ki * ki).sqrt();
    eprintln!(
        "K(w): got {re:.6e} + {im:.6e} i, closed form {kr:.6e} + {ki:.6e} i; mean {mean} vs {}",
        POLY.ks * em
    );
    // Between the static and the high-frequency stiffness, with a phase.
    assert!(kr > 1.2 * POLY.ks && kr < POLY.kd, "Re K {kr}");
    assert!(ki / kr > 0.2, "phase {}", (ki / kr).atan());
    assert!(
        (re - kr).abs() < 3e-3 * kmag,
        "Re K: got {re}, closed form {kr}"
    );
    assert!(
        (im - ki).abs() < 3e-3 * kmag,
        "Im K: got {im}, closed form {ki}"
    );
    assert!(
        (mean - POLY.ks * em).abs() < 1e-3 * POLY.ks * em,
        "mean {mean}"
    );
}

#[test]
fn rope_dynamic_stiffness_follows_the_mean_tension() {
    // EA_d = EA_Dc + EA_D_Lm T_mean: the instantaneous stiffness of a small step from
    // rest at two mean strains, with no dynamic damping (so the state cannot jump).
    let rope = Rope {
        ks: 1.0e6,
        kd: 2.0e6,
        slope: 40.0,
        c1: 1.0e6,
        c2: 0.0,
    };
    let d = 1e-5;
    let mut seen = Vec::new();
    for em in [0.005, 0.03] {
        let got = step_response(rope, em, em + d, Scheme::Symplectic, 1e-4, 20000, 1);
        let t_mean = rope.ks * em;
        let kdyn = (got[0] - t_mean) / d;
        let want = rope.kd + rope.slope * t_mean;
        eprintln!("mean strain {em}: dynamic stiffness {kdyn:.6e}, EA_Dc + EA_D_Lm T = {want:.6e}");
        assert!((kdyn - want).abs() < 1e-6 * want, "{kdyn} vs {want}");
        // And the closed form of the function itself at the rest state.
        let x = em * (1.0 - rope.ks / want);
        let k2 = visco_dynamic_stiffness(rope.ks, rope.kd, rope.slope, x);
        assert!((k2 - want).abs() < 1e-9 * want);
        assert!((k1(rope.ks, k2) * x - t_mean).abs() < 1e-9 * t_mean);
        // Relaxed after 2 s (tau is under 0.2 s): the static stiffness again.
        assert!(
            (got[1] - rope.ks * (em + d)).abs() < 1e-3 * rope.ks * d,
            "relaxed {} vs {}",
            got[1],
            rope.ks * (em + d)
        );
        seen.push(kdyn);
    }
    // The difference is the slope times the difference of the mean tensions.
    let want = rope.slope * rope.ks * (0.03 - 0.005);
    assert!(
        (seen[1] - seen[0] - want).abs() < 1e-5 * want,
        "load dependence {seen:?}, slope x dT = {want}"
    );
}

#[test]
fn rope_statics_take_the_static_stiffness() {
    // A hanging rope relaxed by the static solver: its tensions are the static EA's,
    // and the dynamic run from there stays at rest (the states start at rest).
    let text = r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0
backend = "cpu"

[environment]
gravity = 9.81
water_density = 1025.0
depth = 1000.0

[[line_types]]
name = "polyester"
diameter = 0.15
mass_per_length = 40.0
ea = 2.0e7
ea_dynamic = 6.0e7
ea_dynamic_slope = 20.0
ba_static = 4.0e7
ba_dynamic = 1.0e5

[[cables]]
name = "rope"
line_type = "polyester"
length = 500.0
segments = 20
start = { fixed = [0.0, 0.0, -600.0] }
end = { fixed = [420.0, 0.0, -300.0] }
initial = "catenary"
"#;
    let sc = Scenario::parse(text, Path::new("/tmp/visco_statics.toml")).unwrap();
    let (lay, pos, residual) = cablesim::initial::prepare(&sc).unwrap();
    assert!(residual < 1e-3, "relaxation residual {residual} N");
    let bound = cablesim::stability::stable_step(&lay, Default::default(), Default::default());
    let opts = SolverOptions {
        dt: 0.8 * bound.dt,
        ..Default::default()
    };
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    let ev0 = cpu.evaluate().unwrap();
    for e in 0..lay.n_elements() {
        let (a, b) = (lay.elem_a[e] as usize, lay.elem_b[e] as usize);
        let d: f64 = (0..3)
            .map(|k| (pos[b][k] - pos[a][k]).powi(2))
            .sum::<f64>()
            .sqrt();
        let eps = d / lay.elem_l0[e] - 1.0;
        assert!(eps > 1e-4, "element {e} strain {eps}");
        let want = 2.0e7 * eps;
        assert!(
            (ev0.tension[e] - want).abs() < 1e-9 * want,
            "element {e}: {} vs static {want}",
            ev0.tension[e]
        );
    }
    cpu.advance(2000).unwrap();
    let moved = (0..lay.n_nodes())
        .map(|i| (cpu.r[i].to_f64()[2] - pos[i][2]).abs())
        .fold(0.0, f64::max);
    assert!(moved < 1e-3, "moved {moved} m from the static shape");
}

fn bad(keys: &str) -> String {
    let text = format!(
        r#"
[simulation]
duration = 1.0
dt = 0.01
output_interval = 1.0

[environment]
depth = 100.0

[[line_types]]
name = "poly"
diameter = 0.1
mass_per_length = 10.0
{keys}

[[cables]]
name = "c"
line_type = "poly"
length = 10.0
segments = 2
start = {{ fixed = [0.0, 0.0, -50.0] }}
end = {{ fixed = [9.0, 0.0, -50.0] }}
"#
    );
    match Scenario::parse(&text, Path::new("/tmp/visco_bad.toml")) {
        Ok(_) => panic!("accepted: {keys}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn rope_bad_input_names_the_key() {
    let base = "ea = 1e6\nea_dynamic = 3e6\nba_static = 1e6";
    for (keys, key, what) in [
        (
            "ea = 1e6\nea_dynamic = -3e6\nba_static = 1e6",
            "ea_dynamic",
            "positive",
        ),
        (
            "ea = 1e6\nea_dynamic = 0.5e6\nba_static = 1e6",
            "ea_dynamic",
            "exceed the static",
        ),
        (
            "ea = 1e6\nea_dynamic = 1e6\nba_static = 1e6",
            "ea_dynamic",
            "exceed the static",
        ),
        (
            "ea = 1e6\nea_dynamic = 3e6\nba_static = 0.0",
            "ba_static",
            "positive",
        ),
        (
            "ea = 1e6\nea_dynamic = 3e6\nba_static = -1.0",
            "ba_static",
            "positive",
        ),
        (
            "ea = 1e6\nea_dynamic = 3e6",
            "ba_static",
            "needs `ba_static`",
        ),
        (
            &format!("{base}\nba_dynamic = -1.0"),
            "ba_dynamic",
            "negative",
        ),
        (
            &format!("{base}\nea_dynamic_slope = -0.1"),
            "ea_dynamic_slope",
            "negative",
        ),
        (&format!("{base}\ndamping = 0.1"), "damping", "ba_static"),
        (
            &format!("{base}\nallow_compression = true"),
            "allow_compression",
            "slack",
        ),
        (
            "ea = 1e6\nba_static = 1e6",
            "ba_static",
            "give `ea_dynamic`",
        ),
        (
            "ea_curve = [[0.01, 1e4], [0.02, 3e4]]\nea_dynamic = 3e6\nba_static = 1e6",
            "ea_dynamic",
            "strain-tension curve",
        ),
    ] {
        let e = bad(keys);
        assert!(
            e.contains(&format!("line_types[0] (\"poly\").{key}")) && e.contains(what),
            "{keys}: {e}"
        );
    }
}
