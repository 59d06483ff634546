//! The ANCF reference cable model (`cablesim::ancf`) against closed-form statics
//! (Euler-Bernoulli cantilever, elastic catenary), against the GLMF on a driven
//! dynamic case, and its integrator's energy behaviour and stable step.

mod common;

use cablesim::ancf::{AncfCable, AncfConfig, AncfEnd, StaticOptions};

use cablesim::model::{Environment, LineType, Seabed};
use cablesim::physics::catenary::catenary;
use common::*;

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Gravity `g`, no water, no seabed.
fn dry(g: f64) -> Environment {
    Environment {
        gravity: g,
        water_density: 0.0,
        depth: f64::INFINITY,
        seabed: Seabed::default(),
    }
}

/// A rod for the cantilever tests: `EI = 1e4 N m^2`, `EA = 1e6 N`, compression allowed.
fn rod(mass_per_length: f64) -> LineType {
    LineType {
        name: "rod".into(),
        diameter: 0.05,
        mass_per_length,
        ea: 1e6,
        damping: 0.0,
        cn: 1.0,
        ct: 0.01,
        cm: 0.0,
        ei: 1e4,
        allow_compression: true,
    }
}

/// Cantilever along x from the origin, clamped there, solved for static equilibrium.
fn cantilever(lt: LineType, length: f64, n: usize, g: f64, tip: [f64; 3]) -> AncfCable {
    let cfg = AncfConfig::new(
        lt,
        length,
        n,
        AncfEnd::clamped([0.0; 3], [1.0, 0.0, 0.0]),
        AncfEnd::free([length, 0.0, 0.0]).with_force(tip),
        dry(g),
    );
    let mut c = AncfCable::new(cfg).unwrap();
    let rep = c.solve_static(&StaticOptions::default()).unwrap();
    assert!(rep.max_residual <= rep.tolerance, "{rep:?}");
    c
}

/// A tip load on a cantilever: the tip deflects by `P L^3 / 3 EI` and the whole line
/// follows `w(x) = P x^2 (3L - x) / 6 EI` (a cubic, which the cubic element holds exactly,
/// so every mesh is right; what remains is the geometric nonlinearity, `(w/L)^2`).
#[test]
fn cantilever_tip_load_matches_euler_bernoulli() {
    let (l, ei) = (10.0f64, 1e4);
    let p = 0.03; // tip deflection 1e-3 m = 1e-4 L: small deflection
    let exact_tip = p * l.powi(3) / (3.0 * ei);
    for n in [1, 2, 4, 8] {
        let c = cantilever(rod(1.0), l, n, 0.0, [0.0, 0.0, -p]);
        let tip = -c.node_positions()[n][2];
        let err_tip = (tip - exact_tip).abs() / exact_tip;
        let mut err_curve = 0.0f64;
        for k in 0..=100 {
            let x = l * k as f64 / 100.0;
            let w = p * x * x * (3.0 * l - x) / (6.0 * ei);
            err_curve = err_curve.max((-c.position_at(x)[2] - w).abs() / exact_tip);
        }
        eprintln!(
            "cantilever tip load, {n} elements: tip {tip:.9e} m (exact {exact_tip:.9e}), relative error {err_tip:.2e}, curve {err_curve:.2e}"
        );
        assert!(err_tip < 1e-5, "{n} elements: tip error {err_tip:e}");
        assert!(err_curve < 1e-5, "{n} elements: curve error {err_curve:e}");
    }
}

/// A uniform load `q` on a cantilever: `w(x) = q x^2 (6L^2 - 4Lx + x^2) / 24 EI`, a
/// quartic, which cubic elements approximate with an error falling as `h^4` (nodal values
/// are exact for Euler-Bernoulli elements with consistent loads; the error lives between
/// the nodes). The load is the line's weight, gravity acting on nothing else.
#[test]
fn cantilever_distributed_load_converges_to_euler_bernoulli() {
    let (l, ei, g) = (10.0f64, 1e4, 9.81);
    let q = 0.008; // N/m: tip deflection q L^4 / 8 EI = 1e-3 m
    let tip_exact = q * l.powi(4) / (8.0 * ei);
    let mut errs = Vec::new();
    for n in [1, 2, 4, 8] {
        let c = cantilever(rod(q / g), l, n, g, [0.0; 3]);
        let mut err = 0.0f64;
        for k in 0..=200 {
            let x = l * k as f64 / 200.0;
            let w = q * x * x * (6.0 * l * l - 4.0 * l * x + x * x) / (24.0 * ei);
            err = err.max((-c.position_at(x)[2] - w).abs() / tip_exact);
        }
        let tip = -c.node_positions()[n][2];
        eprintln!(
            "cantilever uniform load, {n} elements: tip {tip:.9e} m (exact {tip_exact:.9e}), max curve error {err:.3e} of the tip deflection"
        );
        errs.push(err);
    }
    for w in errs.windows(2) {
        assert!(
            w[1] < w[0] / 10.0,
            "refining must cut the error by about 16 (h^4): {errs:?}"
        );
    }
    assert!(errs[3] < 1e-4, "8 elements: {errs:?}");
}

/// A line hanging between two fixed points (negligible EI) against the analytic
/// elastic catenary: positions along the line, node tensions (section forces from the
/// elements' consistent nodal forces), the strain tension at element midpoints and the
/// end forces all converge with refinement.
///
/// The ANCF's Green-strain law `N |r'| = EA (eps + 3/2 eps^2 + ...)` is not the
/// catenary's `EA eps`; at this line's strains (at most 4.2e-4) the difference stretches the
/// line by about `1.5 eps^2 L`, 3e-7 L, under every figure asserted here.
#[test]
fn hanging_cable_converges_to_elastic_catenary() {
    let mut lt = wire();
    lt.ei = 0.0;
    let env = Environment {
        depth: f64::INFINITY,
        ..Default::default()
    };
    let (length, xf, zf) = (1000.0, 800.0, 200.0);
    let w = -cablesim::model::LineCoefs::new(&lt, env.water_density, env.gravity).wet_weight_z;
    let cat = catenary(xf, zf, length, lt.ea, w, false).unwrap();
    let tf = cat.fairlead_tension();
    let (a, b) = ([0.0, 0.0, 0.0], [xf, 0.0, zf]);
    // First guess: a parabola of about the right length below the chord.
    let chord = (xf * xf + zf * zf).sqrt();
    let sag = (3.0 * chord * (length - chord) / 8.0).sqrt();
    let mut errs = Vec::new();
    for n in [2, 4, 8, 16] {
        let cfg = AncfConfig::new(
            lt.clone(),
            length,
            n,
            AncfEnd::fixed(a),
            AncfEnd::fixed(b),
            env,
        );
        let mut c = AncfCable::new(cfg).unwrap();
        c.set_shape(|s| {
            let u = s / length;
            [u * xf, 0.0, u * zf - 4.0 * sag * u * (1.0 - u)]
        });
        let rep = c.solve_static(&StaticOptions::default()).unwrap();
        let le = length / n as f64;
        let mut ep = 0.0f64;
        for k in 0..=400 {
            let s = length * k as f64 / 400.0;
            let e = cat.position(s);
            ep = ep.max(dist(c.position_at(s), [e[0], 0.0, e[1]]));
        }
        let tn = c.node_tensions().unwrap();
        let mut en = 0.0f64;
        for (k, t) in tn.iter().enumerate() {
            en = en.max((t - cat.tension(k as f64 * le)).abs());
        }
        let mut em = 0.0f64;
        for e in 0..n {
            let s = (e as f64 + 0.5) * le;
            em = em.max((c.tension_at(s) - cat.tension(s)).abs());
        }
        let ends = c.end_forces().unwrap();
        let (anchor, top) = (ends[0].unwrap(), ends[1].unwrap());
        // The line pulls the fairlead towards the anchor and down, the anchor towards the
        // fairlead and (here, fully suspended) down.
        let ee = dist(top, [-cat.hf, 0.0, -cat.vf]).max(dist(anchor, [cat.ha, 0.0, cat.va]));
        let (ep, en, em, ee) = (ep / length, en / tf, em / tf, ee / tf);
        eprintln!(
            "catenary, {n:2} elements (Newton {:2} iterations): position {ep:.2e} L, node tension {en:.2e}, \
             midpoint strain tension {em:.2e}, end forces {ee:.2e} (of the fairlead tension {tf:.1} N)",
            rep.iterations
        );
        errs.push([ep, en, em, ee]);
    }
    // Positions fall by about 8 per halving, node tensions and end forces by 20-30;
    // the strain tension oscillates along coarse elements and converges late.
    for w in errs.windows(2) {
        for (k, (what, factor)) in [
            ("position", 4.0),
            ("node tension", 8.0),
            ("midpoint tension", 1.0),
            ("end force", 8.0),
        ]
        .iter()
        .enumerate()
        {
            assert!(
                w[1][k] < w[0][k] / factor,
                "{what} error must shrink by {factor} per refinement: {errs:?}"
            );
        }
    }
    let e = errs[3];
    assert!(
        e[0] < 2e-5 && e[1] < 1e-5 && e[2] < 1e-2 && e[3] < 1e-5,
        "16 elements: {e:?}"
    );
}
