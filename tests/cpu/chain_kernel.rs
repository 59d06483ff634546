//! The vectorised chain fast path of the CPU stepper agrees with the general path.
//!
//! Contract: same physics, different arithmetic order (closed-form Woodbury solve of
//! the mass block instead of the adjugate; padded gathers), so trajectories agree to
//! round-off amplified by the dynamics over the run: here 1e-9 m after 2000 steps of
//! a line whose nodes move by metres, for every scheme and with every extra the fast
//! path fixes up (route-driven node, point mass with drag, seabed friction, a current
//! profile). Chains up to 128 nodes keep their per-stage columns at a fixed stride,
//! longer ones at their own length: both are checked.

use super::common::*;
use cablesim::cpu::CpuSolver;
use cablesim::model::{Current, Environment, Layout, PointMass, Route, Seabed};
use cablesim::options::{Scheme, SolverOptions};

fn model() -> (Layout, Vec<[f64; 3]>) {
    model_of(40)
}

/// The line of `model` in `segments` elements.
fn model_of(segments: usize) -> (Layout, Vec<[f64; 3]>) {
    let env = Environment {
        depth: 100.0,
        seabed: Seabed {
            friction: 0.5,
            ..Seabed::default()
        },
        ..Environment::default()
    };
    let a = [-220.0, 0.0, -100.0];
    let b = [0.0, 0.0, -10.0];
    let mut def = straight_cable(
        env,
        wire(),
        a,
        b,
        250.0,
        segments,
        Some(Route::Fixed { position: a }),
        Some(Route::Circle {
            center: [0.0, 5.0, -10.0],
            radius: 5.0,
            period: 20.0,
            axis: [0.0, 0.0, 1.0],
            phase: -std::f64::consts::FRAC_PI_2,
            advance: 0.0,
        }),
        PointMass::default(),
        [0.0; 3],
    );
    def.currents[0] = Current {
        table: vec![
            (-100.0, [0.1, 0.0, 0.0]),
            (-50.0, [0.4, 0.2, 0.0]),
            (0.0, [0.8, 0.3, 0.0]),
        ],
    };
    // A clump weight with drag in the middle, and the line sags onto the seabed.
    def.nodes[segments / 2].point = PointMass {
        mass: 500.0,
        volume: 0.05,
        drag_area: 0.8,
        added_mass_coef: 1.0,
    };
    for (k, n) in def.nodes.iter_mut().enumerate() {
        if k > 0 && k < segments {
            n.position[2] -= 30.0 * (std::f64::consts::PI * k as f64 / segments as f64).sin();
            n.position[2] = n.position[2].max(-100.00001);
        }
    }
    Layout::build(&def).unwrap()
}

#[test]
fn chain_fast_path_matches_the_general_path() {
    // 41 nodes (the block at the fixed stride) and 151 (at the chain's own length; the
    // step shorter with the shorter elements).
    for (segments, dt, scheme) in [
        (40, 1e-4, Scheme::Symplectic),
        (40, 1e-4, Scheme::Rk2),
        (40, 1e-4, Scheme::Rk4),
        (150, 2.5e-5, Scheme::Symplectic),
        (150, 2.5e-5, Scheme::Rk4),
    ] {
        let (lay, pos) = model_of(segments);
        assert!(lay.blocks[0].is_chain);
        let opts = SolverOptions {
            dt,
            scheme,
            ..Default::default()
        };
        let mut fast = CpuSolver::new(lay.clone(), &pos, opts);
        let mut slow = CpuSolver::new(lay, &pos, opts);
        slow.use_chain_kernel = false;
        // 2000 steps either way (0.05 s of the long chain: its shorter elements, in
        // seabed friction, amplify the two paths' round-off past the bound below by
        // 0.2 s, 5e-5 m).
        let steps = 2000;
        fast.advance(steps).unwrap();
        slow.advance(steps).unwrap();
        let moved = fast
            .r
            .iter()
            .zip(&pos)
            .map(|(r, p)| (r.x - p[0]).abs().max((r.z - p[2]).abs()))
            .fold(0.0, f64::max);
        assert!(
            moved > 0.1,
            "{segments} elements, {scheme:?}: the line should move, moved {moved} m"
        );
        let worst_r = fast
            .r
            .iter()
            .zip(&slow.r)
            .map(|(a, b)| (*a - *b).norm())
            .fold(0.0, f64::max);
        let worst_v = fast
            .v
            .iter()
            .zip(&slow.v)
            .map(|(a, b)| (*a - *b).norm())
            .fold(0.0, f64::max);
        assert!(
            worst_r < 1e-9 && worst_v < 1e-7,
            "{segments} elements, {scheme:?}: fast and general paths differ by {worst_r:e} m, {worst_v:e} m/s"
        );
    }
}

#[test]
fn chain_fast_path_reports_blow_up_like_the_general_path() {
    let (lay, pos) = model();
    // Far above the stable step: it must stop with the cable, node and time named.
    let opts = SolverOptions {
        dt: 2e-2,
        ..Default::default()
    };
    let mut fast = CpuSolver::new(lay, &pos, opts);
    let err = fast.advance(10_000).unwrap_err().to_string();
    assert!(
        err.contains("diverged") && err.contains("cable 'c0'") && err.contains("node"),
        "{err}"
    );
}
