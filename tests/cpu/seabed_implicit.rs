//! The seabed's damping and friction taken implicitly by the symplectic scheme
//! (docs/src/model/seabed.md): at its new automatic step, set by the axial waves, the
//! catenary example with a moving fairlead and sliding grounded nodes gives the contact
//! results of the explicit contact at a small step (RK4, whose contact is explicit and
//! whose step is still bounded by the seabed's damping).

use cablesim::cpu::CpuSolver;
use cablesim::model::{Layout, Route};
use cablesim::options::{Scheme, SolverOptions};
use cablesim::scenario::Scenario;
use cablesim::stability::{stable_step, AUTO_SAFETY};

/// The catenary example relaxed to equilibrium, its fairlead driven toward the anchor
/// and sideways (1.8 m/s), with seabed friction (mu = 0.5): grounded nodes slide and lift off.
fn moving_catenary() -> (Layout, Vec<[f64; 3]>) {
    let sc = Scenario::load("examples/catenary.toml").unwrap();
    let (mut lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let fair = lay.cables[0].nodes[50] as usize;
    let c = lay.node_constraint[fair] as usize;
    lay.routes[c] = Route::Line {
        start: pos[fair],
        velocity: [-1.0, 1.5, 0.0],
    };
    lay.env.seabed.friction = 0.5;
    (lay, pos)
}

/// Runs `duration` seconds at about `dt` (a whole number of steps).
fn run(lay: &Layout, pos: &[[f64; 3]], scheme: Scheme, dt: f64, duration: f64) -> CpuSolver {
    let steps = (duration / dt).ceil() as u64;
    let opts = SolverOptions {
        scheme,
        dt: duration / steps as f64,
        ..Default::default()
    };
    let mut s = CpuSolver::new(lay.clone(), pos, opts);
    s.advance(steps).unwrap();
    s
}

#[test]
fn implicit_contact_at_the_axial_step_matches_explicit_contact_at_a_small_step() {
    let (lay, pos) = moving_catenary();
    let sym = stable_step(&lay, Scheme::Symplectic, Default::default());
    let rk4 = stable_step(&lay, Scheme::Rk4, Default::default());
    // The symplectic step is now the axial waves'; the explicit contact's is shorter.
    assert!(sym.term.starts_with("axial waves"), "{}", sym.term);
    assert!(rk4.term.starts_with("seabed"), "{}", rk4.term);
    assert!(sym.dt > 2.0 * rk4.dt, "{} {}", sym.dt, rk4.dt);
    let duration = 6.0;
    let mut reference = run(&lay, &pos, Scheme::Rk4, rk4.dt / 4.0, duration);
    let mut implicit = run(
        &lay,
        &pos,
        Scheme::Symplectic,
        AUTO_SAFETY * sym.dt,
        duration,
    );
    let mut small = run(&lay, &pos, Scheme::Symplectic, rk4.dt / 4.0, duration);
    let (er, ei, es) = (
        reference.evaluate().unwrap(),
        implicit.evaluate().unwrap(),
        small.evaluate().unwrap(),
    );
    let norm = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let diff = |a: [f64; 3], b: [f64; 3]| norm([a[0] - b[0], a[1] - b[1], a[2] - b[2]]);
    // The anchor's force (constraint 0: the cable's start).
    let anchor = |e: &cablesim::step::Evaluation| e.reaction[0];
    let f_ref = anchor(&er);
    let d_anchor = diff(anchor(&ei), f_ref) / norm(f_ref);
    let d_anchor_small = diff(anchor(&es), f_ref) / norm(f_ref);
    // The grounded nodes: position and sliding velocity.
    let zb = -lay.env.depth;
    let grounded: Vec<usize> = (0..lay.n_nodes())
        .filter(|&i| reference.r[i].z < zb + 1e-3 && lay.node_constraint[i] == u32::MAX)
        .collect();
    // Grounded nodes that slid along the seabed (friction at work, mostly creeping
    // below v_eps, where it is the stiff damper the explicit step was bounded by).
    let sliding = grounded
        .iter()
        .filter(|&&i| {
            let d = [
                reference.r[i].x - pos[i][0],
                reference.r[i].y - pos[i][1],
                0.0,
            ];
            norm(d) > 0.1
        })
        .count();
    let worst = |s: &CpuSolver| {
        grounded
            .iter()
            .map(|&i| {
                let (a, b) = (s.r[i].to_f64(), reference.r[i].to_f64());
                diff(a, b)
            })
            .fold(0.0f64, f64::max)
    };
    let (d_pos, d_pos_small) = (worst(&implicit), worst(&small));
    let moved = grounded
        .iter()
        .map(|&i| diff(reference.r[i].to_f64(), pos[i]))
        .fold(0.0f64, f64::max);
    println!(
        "steps {:.3e} s (implicit, {}) vs {:.3e} s (RK4 reference); {} grounded nodes, {sliding} slid over 0.1 m, moved up to {moved:.3} m; \
         anchor force {:?} N, relative difference {d_anchor:.2e} (implicit at dt / 4: {d_anchor_small:.2e}); grounded positions within {d_pos:.2e} m ({d_pos_small:.2e} m)",
        AUTO_SAFETY * sym.dt, sym.term, rk4.dt / 4.0, grounded.len(), f_ref
    );
    // The case is what it is meant to be: a stretch on the seabed, held by friction
    // (creeping) but for the nodes near touchdown, which slide and settle.
    assert!(
        grounded.len() >= 10 && sliding >= 1 && moved > 1.0,
        "{} {sliding} {moved}",
        grounded.len()
    );
    // Measured (this test's output): 2.2e-3 and 8.0e-6 m at the auto step, 2.7e-4 and
    // 9.9e-7 m at the reference's step: the symplectic scheme's first-order error,
    // shrinking with the step toward the explicit contact's results.
    assert!(d_anchor < 5e-3, "{d_anchor}");
    assert!(d_pos < 3e-5, "{d_pos}");
    assert!(d_anchor_small < 0.25 * d_anchor && d_pos_small < 0.25 * d_pos);
}
