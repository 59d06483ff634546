//! The older element frames against the GLMF (paper Sec. 2.1-2.6, Table 2).
//!
//! # Tolerances
//! `EPS` is f64 machine epsilon. For each element the *load scale* is
//! `S = (drag_n + drag_t) l |v_rel|^2 + (1 + Cm) rho A l0 |a_w| + |w| l0`, a bound on
//! every term of the external load and on every intermediate quantity of both paths
//! (the frame vectors are unit vectors, so their components times a load are bounded
//! by the load). Both paths compute `E`, `l`, `t = E/l`, `v_rel` and `a_w` by the very
//! same expressions, so those are bitwise equal; what differs is the frame algebra
//! (cross products, two normalisations, one re-projection, `A^T v` as 3-term dot
//! products, the drag law, `A f` as 3-term sums) against GLMF's projections. Each of
//! these is a short chain of about 20-30 roundings, each of relative size at most
//! `EPS` on a quantity bounded by `S` (standard forward error bound `gamma_n ~ n EPS`),
//! so `|f_frame - f_glmf| <= ~30 EPS S` per path; `64 EPS S` covers both paths with a
//! little headroom, while any wrong sign, factor or axis gives an `O(1) S` difference.
//!
//! Where a frame is *conditioned* worse than the unit vectors above, the bound is
//! multiplied by its amplification factor `kappa`, stated where used: the Euler frame's
//! `cos(theta)` carries a relative error `EPS l/|dz|` which `phi` inherits in the first
//! branch of Eq. 9 (`kappa = l/|dz|`); the Frenet tangent `(alpha + beta)/|alpha + beta|`
//! sums two rounded differences (`kappa = (|alpha| + |beta|)/l`). Both are `O(1)` on
//! generic inputs and the bound stays far below any real error.

use cablesim::cpu::CpuSolver;
use cablesim::math::V3;
use cablesim::model::{
    CableDef, Current, Environment, Layout, LineCoefs, LineType, ModelDef, NodeDef, PointMass,
    Route,
};
use cablesim::options::{Formulation, SolverOptions};
use cablesim::physics::frames::{
    element_frame, frame_element, frame_element_with, frame_external, frenet_virtual_node,
    singular_tolerance, Frame, NormalDrag,
};
use cablesim::physics::{glmf_element, glmf_external, Coefs, ElementInput, ElementLoads};
use cablesim::Error;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type V = V3<f64>;
const EPS: f64 = f64::EPSILON;
const FRAMES: [Frame; 3] = [Frame::Euler, Frame::Frenet, Frame::Rvef];

fn line_type(rng: &mut ChaCha8Rng) -> LineType {
    LineType {
        name: "random".into(),
        diameter: rng.gen_range(0.005..0.3),
        mass_per_length: rng.gen_range(0.2..300.0),
        ea: rng.gen_range(1e5..1e10),
        damping: rng.gen_range(0.0..1e-2),
        cn: rng.gen_range(0.5..2.5),
        ct: rng.gen_range(0.001..0.1),
        cm: rng.gen_range(0.0..2.0),
        cat: rng.gen_range(0.0..2.0),
        ei: 0.0,
        allow_compression: rng.gen_bool(0.2),
        ea_curve: None,
        viscoelastic: None,
    }
}

fn coefs(rng: &mut ChaCha8Rng) -> Coefs<f64> {
    Coefs::from_line(&LineCoefs::new(&line_type(rng), 1025.0, 9.81))
}

fn rvec(rng: &mut ChaCha8Rng, s: f64) -> V {
    V::new(
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
    )
}

fn unit(rng: &mut ChaCha8Rng) -> V {
    loop {
        let v = rvec(rng, 1.0);
        let n = v.norm();
        if n > 0.1 && n < 1.0 {
            return v / n;
        }
    }
}

/// A generic element: random length, strain, orientation, velocities and water.
fn random_input(rng: &mut ChaCha8Rng) -> ElementInput<f64> {
    let l0 = rng.gen_range(0.5..50.0);
    let l = l0 * rng.gen_range(0.8..1.1);
    let ra = rvec(rng, 500.0);
    ElementInput {
        ra,
        rb: ra + unit(rng) * l,
        va: rvec(rng, 3.0),
        vb: rvec(rng, 3.0),
        l0,
        current: rvec(rng, 2.0),
        water_accel: rvec(rng, 1.0),
    }
}

fn vrel(e: &ElementInput<f64>) -> V {
    e.current - (e.va + e.vb) * 0.5
}

/// The load scale `S` of the module doc.
fn load_scale(c: &Coefs<f64>, e: &ElementInput<f64>) -> f64 {
    let l = (e.rb - e.ra).norm();
    (c.drag_n + c.drag_t) * l * vrel(e).norm2()
        + c.froude_krylov.max(c.froude_krylov_t) * e.l0 * e.water_accel.norm()
        + c.wet_weight_z.abs() * e.l0
}

/// Scale of the axial force: its elastic and damping parts.
fn tension_scale(c: &Coefs<f64>, e: &ElementInput<f64>) -> f64 {
    let l = (e.rb - e.ra).norm();
    c.ea * (l / e.l0 - 1.0).abs() + c.ea_c * (e.vb - e.va).norm() / e.l0
}

/// Asserts that `got` equals the GLMF loads of `e` within `64 EPS kappa` times the
/// scales, part by part; returns the worst error in units of `EPS S`.
fn assert_matches_glmf(
    what: &str,
    frame: Frame,
    c: &Coefs<f64>,
    e: &ElementInput<f64>,
    mid: V,
    kappa: f64,
) -> f64 {
    let got = frame_element(frame, c, e, mid).unwrap_or_else(|r| panic!("{what}: {r}"));
    let want = glmf_element(c, e);
    let s = load_scale(c, e);
    let tol = 64.0 * EPS * kappa;
    let df = (got.f_half - want.f_half).norm();
    assert!(
        df <= tol * s,
        "{what}: f_half {:?} vs GLMF {:?}: |diff| = {df:.3e} > {:.3e} (S = {s:.3e}, kappa = {kappa:.2})",
        got.f_half,
        want.f_half,
        tol * s
    );
    let dt = (got.tension - want.tension).abs();
    assert!(
        dt <= tol * tension_scale(c, e),
        "{what}: tension {} vs {}",
        got.tension,
        want.tension
    );
    assert!(
        (got.t - want.t).norm() <= tol,
        "{what}: t {:?} vs {:?}",
        got.t,
        want.t
    );
    assert_eq!(
        (got.half_mass, got.half_added),
        (want.half_mass, want.half_added)
    );
    // Part by part: a compensating pair of errors cannot hide.
    let l = (e.rb - e.ra).norm();
    let gp = frame_external(frame, NormalDrag::Vector, c, e, mid).unwrap();
    let wp = glmf_external(c, e, want.t, l);
    for (name, a, b) in [
        ("drag_n", gp.drag_n, wp.drag_n),
        ("drag_t", gp.drag_t, wp.drag_t),
        ("froude_krylov", gp.froude_krylov, wp.froude_krylov),
        ("wet_weight", gp.wet_weight, wp.wet_weight),
    ] {
        assert!(
            (a - b).norm() <= tol * s,
            "{what}: {name} {a:?} vs GLMF {b:?}"
        );
    }
    df / (EPS * s)
}

fn assert_finite(what: &str, g: &ElementLoads<f64>) {
    assert!(
        g.f_half.is_finite() && g.tension.is_finite() && g.t.is_finite(),
        "{what}: GLMF not finite: {g:?}"
    );
}

// ---------------------------------------------------------------------------------------
// 1. RVEF == GLMF (paper Eqs. 21-31)

#[test]
fn rvef_equals_glmf_on_random_inputs() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let mut worst: f64 = 0.0;
    for k in 0..20_000 {
        let c = coefs(&mut rng);
        let e = random_input(&mut rng);
        // Random continuous inputs are never within sqrt(eps) of the singularity.
        worst = worst.max(assert_matches_glmf(
            &format!("sample {k}"),
            Frame::Rvef,
            &c,
            &e,
            V::zero(),
            1.0,
        ));
    }
    println!("RVEF vs GLMF: worst |diff| = {worst:.2} EPS S");
}

#[test]
fn rvef_equals_glmf_close_to_its_singularity() {
    // v_rel at an angle delta to the element, down to just above the threshold: the
    // frame's axes lose digits there, but its loads do not (module doc of `frames`).
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let tol = singular_tolerance::<f64>();
    for k in 0..2_000 {
        let c = coefs(&mut rng);
        let mut e = random_input(&mut rng);
        let t = (e.rb - e.ra) / (e.rb - e.ra).norm();
        let n = t.cross(unit(&mut rng));
        let n = n / n.norm();
        let delta = 10f64.powf(rng.gen_range(-7.7..-1.0));
        assert!(delta > 1.2 * tol);
        let speed = rng.gen_range(0.01..5.0);
        let sign = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        // Nodes at rest: the velocity scale |U| + |v_mid| is |v_rel|.
        e.va = V::zero();
        e.vb = V::zero();
        e.current = (t * (sign * delta.cos()) + n * delta.sin()) * speed;
        assert_matches_glmf(
            &format!("sample {k}, delta {delta:.1e}"),
            Frame::Rvef,
            &c,
            &e,
            V::zero(),
            1.0,
        );
    }
}

// ---------------------------------------------------------------------------------------
// 2. The paper's Table 2: where each frame is singular, and GLMF is not

/// A generic element of a bent cable in a cross current, with its neighbours.
fn generic() -> (ElementInput<f64>, V) {
    let p = |s: f64| V::new(0.02 * s * s, 0.3 * s, -10.0 - s);
    let (p0, a, b, p3) = (p(0.0), p(5.0), p(10.0), p(15.0));
    let e = ElementInput {
        ra: a,
        rb: b,
        va: V::new(0.1, 0.0, -0.05),
        vb: V::new(0.2, -0.1, 0.0),
        l0: 5.0,
        current: V::new(1.0, 0.2, 0.0),
        water_accel: V::new(0.05, 0.0, 0.1),
    };
    (e, frenet_virtual_node(Some(p0), a, b, Some(p3)))
}

fn line() -> Coefs<f64> {
    let lt = LineType {
        name: "case2".into(),
        diameter: 0.04,
        mass_per_length: 4000.0 * std::f64::consts::PI * 0.04 * 0.04 / 4.0,
        ea: 5e10 * std::f64::consts::PI * 0.04 * 0.04 / 4.0,
        damping: 1e-5,
        cn: 1.0,
        ct: 0.01,
        cm: 0.2,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    Coefs::from_line(&LineCoefs::new(&lt, 1025.0, 9.81))
}

fn expect_singular(frame: Frame, e: &ElementInput<f64>, mid: V, words: &[&str]) {
    let c = line();
    let r = frame_element(frame, &c, e, mid);
    let reason = match r {
        Err(reason) => reason,
        Ok(l) => panic!("{frame:?} should be singular here, got {l:?}"),
    };
    for w in words {
        assert!(reason.contains(w), "{frame:?}: '{reason}' lacks '{w}'");
    }
    assert!(element_frame(frame, e, mid).is_err());
}

#[test]
fn every_frame_is_defined_on_a_generic_configuration() {
    let (e, mid) = generic();
    let c = line();
    for f in FRAMES {
        assert_matches_glmf(&format!("{f:?}"), f, &c, &e, mid, 2.0);
    }
}

#[test]
fn rvef_is_singular_when_relative_velocity_is_parallel_or_zero() {
    let (mut e, mid) = generic();
    let c = line();
    let t = (e.rb - e.ra) / (e.rb - e.ra).norm();
    // A cable at rest in still water.
    e.va = V::zero();
    e.vb = V::zero();
    e.current = V::zero();
    expect_singular(Frame::Rvef, &e, mid, &["relative velocity zero"]);
    assert_finite("at rest", &glmf_element(&c, &e));
    // An element drifting with the current: v_rel = 0 again.
    e.current = V::new(0.7, -0.2, 0.1);
    e.va = e.current;
    e.vb = e.current;
    expect_singular(Frame::Rvef, &e, mid, &["relative velocity zero"]);
    assert_finite("drifting", &glmf_element(&c, &e));
    // Flow along the element (either way).
    for s in [1.3, -0.4] {
        e.va = V::zero();
        e.vb = V::zero();
        e.current = t * s;
        expect_singular(Frame::Rvef, &e, mid, &["parallel", "|z x v_rel|"]);
        let g = glmf_element(&c, &e);
        assert_finite("parallel flow", &g);
        assert!(g.f_half.norm() > 0.0);
    }
    // Nodes moving along the element in still water.
    e.current = V::zero();
    e.va = t * 0.5;
    e.vb = t * 0.7;
    expect_singular(Frame::Rvef, &e, mid, &["parallel"]);
    // The other frames do not care.
    assert!(frame_element(Frame::Euler, &c, &e, mid).is_ok());
    assert!(frame_element(Frame::Frenet, &c, &e, mid).is_ok());
}

#[test]
fn frenet_is_singular_on_a_straight_cable() {
    let (mut e, _) = generic();
    let c = line();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..200 {
        // Four collinear nodes, unequal spacing, anywhere.
        let u = unit(&mut rng);
        let o = rvec(&mut rng, 300.0);
        let s: Vec<f64> = [0.0, 1.0, 2.0, 3.0]
            .iter()
            .map(|k| k * 5.0 + rng.gen_range(-1.0..1.0))
            .collect();
        let p: Vec<V> = s.iter().map(|&si| o + u * si).collect();
        e.ra = p[1];
        e.rb = p[2];
        e.l0 = s[2] - s[1];
        for (prev, next) in [
            (Some(p[0]), Some(p[3])),
            (Some(p[0]), None),
            (None, Some(p[3])),
            (None, None),
        ] {
            let mid = frenet_virtual_node(prev, e.ra, e.rb, next);
            expect_singular(Frame::Frenet, &e, mid, &["collinear", "straight"]);
            assert_finite("straight", &glmf_element(&c, &e));
        }
        // Euler and RVEF are defined on the same element (generic direction and flow).
        assert!(frame_element(Frame::Euler, &c, &e, V::zero()).is_ok());
        assert!(frame_element(Frame::Rvef, &c, &e, V::zero()).is_ok());
    }
}

#[test]
fn euler_is_singular_at_horizontal_elements() {
    let (mut e, mid) = generic();
    let c = line();
    // Horizontal element, either way along x: theta = atan(dx/0).
    for d in [
        V::new(5.0, 0.0, 0.0),
        V::new(-3.0, 4.0, 0.0),
        V::new(0.0, 5.0, 0.0), // along y: dx = dz = 0
        V::new(1.0, 1.0, 1e-12),
    ] {
        e.rb = e.ra + d;
        expect_singular(Frame::Euler, &e, mid, &["theta", "dz"]);
        assert_finite("horizontal", &glmf_element(&c, &e));
        assert!(frame_element(Frame::Rvef, &c, &e, mid).is_ok());
    }
    // Vertical elements (a hanging cable) are fine: theta = phi = 0, A = I.
    e.rb = e.ra + V::new(0.0, 0.0, -5.0);
    let ax = element_frame(Frame::Euler, &e, mid).unwrap();
    assert_eq!(ax.cols[2], V::new(0.0, 0.0, 1.0));
    assert_matches_glmf("vertical", Frame::Euler, &c, &e, mid, 1.0);
}

#[test]
fn zero_length_element_is_singular_for_every_frame() {
    let (mut e, mid) = generic();
    e.rb = e.ra;
    for f in FRAMES {
        expect_singular(f, &e, mid, &["zero-length"]);
    }
    // The GLMF's only singularity (Table 2): non-finite output, which the stepper's
    // blow-up check reports.
    let g = glmf_element(&line(), &e);
    assert!(!g.f_half.is_finite() || !g.t.is_finite());
}

#[test]
fn singularity_thresholds_are_sharp() {
    // Just below sqrt(eps) of the scale: singular; a decade above: defined and equal to
    // the GLMF (Euler with its l/|dz| amplification).
    let tol = singular_tolerance::<f64>();
    let c = line();
    let (base, _) = generic();
    for (below, above) in [(0.5 * tol, 10.0 * tol), (0.9 * tol, 1.1 * tol)] {
        // RVEF: flow at an angle to the element.
        let mut e = base;
        e.va = V::zero();
        e.vb = V::zero();
        let t = (e.rb - e.ra) / (e.rb - e.ra).norm();
        let n = t.cross(V::new(0.0, 1.0, 0.0));
        let n = n / n.norm();
        for (angle, ok) in [(below, false), (above, true)] {
            e.current = (t * angle.cos() + n * angle.sin()) * 2.0;
            assert_eq!(
                frame_element(Frame::Rvef, &c, &e, V::zero()).is_ok(),
                ok,
                "rvef at {angle:.2e}"
            );
            if ok {
                assert_matches_glmf("rvef threshold", Frame::Rvef, &c, &e, V::zero(), 1.0);
            }
        }
        // Euler: dz relative to l.
        let mut e = base;
        for (rel, ok) in [(below, false), (above, true)] {
            let h = V::new(3.0, 4.0, 0.0);
            e.rb = e.ra + h + V::new(0.0, 0.0, -rel * 5.0);
            assert_eq!(
                frame_element(Frame::Euler, &c, &e, V::zero()).is_ok(),
                ok,
                "euler at {rel:.2e}"
            );
            if ok {
                assert_matches_glmf(
                    "euler threshold",
                    Frame::Euler,
                    &c,
                    &e,
                    V::zero(),
                    1.0 / rel,
                );
            }
        }
        // Frenet: sag of the virtual node relative to |alpha| + |beta|.
        let mut e = base;
        e.rb = e.ra + V::new(3.0, 0.0, -4.0);
        let m = (e.ra + e.rb) * 0.5;
        let n = V::new(0.8, 0.0, 0.6);
        for (rel, ok) in [(below, false), (above, true)] {
            // A sag `h` normal to the chord: |n'| = 2 h, |alpha| + |beta| = 5 (1 + O(h^2)),
            // so the threshold is at h = 2.5 tol; `rel` is |n'| / (|alpha| + |beta|).
            let mid2 = m + n * (2.5 * rel);
            assert_eq!(
                frame_element(Frame::Frenet, &c, &e, mid2).is_ok(),
                ok,
                "frenet at {rel:.2e}"
            );
            if ok {
                assert_matches_glmf("frenet threshold", Frame::Frenet, &c, &e, mid2, 1.0);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// 3. Euler and Frenet == GLMF where defined

#[test]
fn euler_equals_glmf_where_defined() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let tol = singular_tolerance::<f64>();
    let (mut worst, mut singular, mut second_branch) = (0.0f64, 0, 0);
    for k in 0..20_000 {
        let c = coefs(&mut rng);
        let mut e = random_input(&mut rng);
        if k % 10 == 0 {
            // Near-horizontal elements, down to the threshold.
            let d = e.rb - e.ra;
            let l = d.norm();
            let dz = l * 10f64.powf(rng.gen_range(-9.0..-1.0)) * d.z.signum();
            let h = (l * l - dz * dz).sqrt() / (d.x * d.x + d.y * d.y).sqrt();
            e.rb = e.ra + V::new(d.x * h, d.y * h, dz);
        }
        let d = e.rb - e.ra;
        let l = d.norm();
        match frame_element(Frame::Euler, &c, &e, V::zero()) {
            Err(r) => {
                assert!(d.z.abs() <= tol * l * 1.0001, "sample {k}: {r}");
                assert!(r.contains("theta"), "{r}");
                assert_finite("euler singular", &glmf_element(&c, &e));
                singular += 1;
            }
            Ok(_) => {
                let theta = (d.x / d.z).atan();
                if theta.cos() <= theta.sin() {
                    second_branch += 1;
                }
                // First branch of Eq. 9: cos(theta) carries EPS l/|dz| (module doc).
                let kappa = l / d.z.abs();
                let w = assert_matches_glmf(
                    &format!("sample {k}"),
                    Frame::Euler,
                    &c,
                    &e,
                    V::zero(),
                    kappa,
                );
                worst = worst.max(w / kappa);
            }
        }
    }
    println!(
        "Euler vs GLMF: worst |diff| = {worst:.2} kappa EPS S; {singular} singular, {second_branch} in Eq. 9's second branch"
    );
    assert!(singular > 50 && second_branch > 1000);
}

#[test]
fn frenet_equals_glmf_where_defined() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let mut worst = 0.0f64;
    for k in 0..20_000 {
        let c = coefs(&mut rng);
        let e = random_input(&mut rng);
        let d = e.rb - e.ra;
        // Neighbours along a random bend; at least one, so the cable is not straight.
        let bend = |rng: &mut ChaCha8Rng| (d + rvec(rng, 0.5 * d.norm())) * rng.gen_range(0.7..1.3);
        let prev = e.ra - bend(&mut rng);
        let next = e.rb + bend(&mut rng);
        let (prev, next) = match k % 3 {
            0 => (Some(prev), Some(next)),
            1 => (Some(prev), None),
            _ => (None, Some(next)),
        };
        let mid = frenet_virtual_node(prev, e.ra, e.rb, next);
        let kappa = ((mid - e.ra).norm() + (e.rb - mid).norm()) / d.norm();
        let w = assert_matches_glmf(&format!("sample {k}"), Frame::Frenet, &c, &e, mid, kappa);
        worst = worst.max(w);
    }
    println!("Frenet vs GLMF: worst |diff| = {worst:.2} EPS S");
}

#[test]
fn per_axis_normal_drag_of_eq11_depends_on_the_frame() {
    // The per-axis form is not the GLMF drag in general; the vector form is. For the
    // RVEF both coincide (v_x = 0 by construction, Eq. 19).
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let c = line();
    let mut largest: f64 = 0.0;
    for _ in 0..200 {
        let e = random_input(&mut rng);
        let s = load_scale(&c, &e);
        let g = glmf_element(&c, &e);
        for f in [Frame::Euler, Frame::Rvef] {
            let p = frame_element_with(f, NormalDrag::PerAxis, &c, &e, V::zero());
            let Ok(p) = p else { continue };
            let diff = (p.f_half - g.f_half).norm() / s;
            if f == Frame::Rvef {
                assert!(diff < 64.0 * EPS, "rvef per-axis {diff:.3e}");
            } else {
                largest = largest.max(diff);
            }
        }
    }
    assert!(
        largest > 1e-3,
        "per-axis Euler drag should differ: {largest:.3e}"
    );
}

// ---------------------------------------------------------------------------------------
// 4. Through the solver

/// A 10-element cable hanging from a fixed top node at z = -10 m; with `bend`, its
/// nodes lie on a parabola `x = bend s^2 / 100` and each `l0` is the chord (no initial
/// strain), so the Frenet frame is defined.
fn hanging_cable(current: [f64; 3], bend: f64) -> (Layout, Vec<[f64; 3]>) {
    let lt = LineType {
        name: "wire".into(),
        diameter: 0.04,
        mass_per_length: 5.0,
        ea: 6.0e7,
        damping: 1e-5,
        cn: 1.0,
        ct: 0.01,
        cm: 0.2,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    let n = 11;
    let pos: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let s = 5.0 * i as f64;
            [bend * s * s / 100.0, 0.0, -10.0 - s]
        })
        .collect();
    let l0 = pos
        .windows(2)
        .map(|w| (V::from_f64(w[1]) - V::from_f64(w[0])).norm())
        .collect();
    let def = ModelDef {
        env: Environment::default(),
        line_types: vec![lt],
        currents: vec![Current::uniform(current)],
        nodes: pos
            .iter()
            .enumerate()
            .map(|(i, &p)| NodeDef {
                position: p,
                point: PointMass::default(),
                route: (i == 0).then_some(Route::Fixed { position: p }),
                label: None,
            })
            .collect(),
        cables: vec![CableDef {
            name: "riser".into(),
            line_type: 0,
            nodes: (0..n).collect(),
            l0,
            current: 0,
            output_positions: false,
            elem_lines: Vec::new(),
        }],
        clamps: Vec::new(),
        joints: Vec::new(),
        screens: Default::default(),
    };
    Layout::build(&def).unwrap()
}

fn solver(formulation: Formulation, current: [f64; 3], bend: f64) -> CpuSolver {
    let (lay, pos) = hanging_cable(current, bend);
    CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            formulation,
            dt: 2e-4,
            ..SolverOptions::default()
        },
    )
}

fn expect_singular_frame(mut s: CpuSolver, want: &str, words: &str) {
    let err = s.advance(10).expect_err("the frame should be singular");
    let msg = err.to_string();
    match err {
        Error::SingularFrame {
            frame,
            cable,
            element,
            time,
            reason,
        } => {
            assert_eq!(frame, want);
            assert_eq!(cable, "riser");
            assert!(element < 10, "element {element}");
            assert_eq!(time, 0.0);
            assert!(reason.contains(words), "{reason}");
            assert!(msg.contains(want) && msg.contains("riser") && msg.contains("element"));
        }
        other => panic!("expected SingularFrame, got {other}"),
    }
}

#[test]
fn solver_reports_singular_rvef_for_a_cable_at_rest_in_still_water() {
    expect_singular_frame(
        solver(Formulation::Frame(Frame::Rvef), [0.0; 3], 0.0),
        "rvef",
        "relative velocity zero",
    );
    // The same model runs with the GLMF, and with the RVEF once there is a cross current.
    solver(Formulation::Glmf, [0.0; 3], 0.0)
        .advance(10)
        .unwrap();
    solver(Formulation::Frame(Frame::Rvef), [1.0, 0.0, 0.0], 0.0)
        .advance(10)
        .unwrap();
}

#[test]
fn solver_reports_singular_frenet_for_a_straight_cable() {
    expect_singular_frame(
        solver(Formulation::Frame(Frame::Frenet), [1.0, 0.0, 0.0], 0.0),
        "frenet",
        "collinear",
    );
    solver(Formulation::Frame(Frame::Frenet), [1.0, 0.0, 0.0], 0.2)
        .advance(10)
        .unwrap();
}

#[test]
fn solver_with_every_frame_tracks_glmf() {
    // A bent hanging cable in a cross current: every frame is defined throughout, and
    // the trajectories agree with the GLMF's to round-off (amplified over 500 steps).
    let current = [1.0, 0.3, 0.0];
    let mut g = solver(Formulation::Glmf, current, 0.2);
    let r0 = g.r.clone();
    g.advance(500).unwrap();
    let moved =
        g.r.iter()
            .zip(&r0)
            .map(|(a, b)| (*a - *b).norm())
            .fold(0.0, f64::max);
    assert!(moved > 1e-3, "the cable should move: {moved:.3e} m");
    for f in FRAMES {
        let mut s = solver(Formulation::Frame(f), current, 0.2);
        s.advance(500).unwrap_or_else(|e| panic!("{f:?}: {e}"));
        let diff =
            s.r.iter()
                .zip(&g.r)
                .map(|(a, b)| (*a - *b).norm())
                .fold(0.0, f64::max);
        println!("{f:?}: max |r - r_glmf| = {diff:.3e} m after 0.1 s");
        assert!(diff < 1e-9, "{f:?}: {diff:.3e} m");
    }
}
