//! The water-acceleration load against its equations (docs/src/model/glmf.md): a free,
//! fully submerged horizontal element in a wave carries `rho V (1 + cm) a` across and
//! `rho V (1 + cat) a` along (`V = A l0`), and accelerates by that over its mass block,
//! on the general path (the load, from an evaluation, and the acceleration of a first
//! step) and the vectorised chain path (the acceleration of a first step), with the
//! exact wave sum and with the kinematics cache (interpolated at a refresh knot: the
//! same values). Symplectic Euler from rest: the first step's velocity is `dt a(0)`.
//! Coefficients with `cat` zero (MoorDyn's default), below `cm` and above it.

use super::common::*;
use cablesim::cpu::CpuSolver;
use cablesim::options::SolverOptions;

const CASES: [(f64, f64); 4] = [(1.0, 0.0), (1.0, 0.5), (0.8, 2.0), (0.0, 1.0)];

fn close(what: &str, got: [f64; 3], want: [f64; 3], scale: f64, tol: f64) {
    for q in 0..3 {
        assert!(
            (got[q] - want[q]).abs() <= tol * scale,
            "{what}: component {q}: {} against {} (scale {scale:e})",
            got[q],
            want[q]
        );
    }
}

#[test]
fn submerged_element_carries_the_full_froude_krylov_load_on_every_cpu_path() {
    for (cm, cat) in CASES {
        let (lay, pos, sea) = froude_krylov_case(cm, cat);
        assert!(lay.blocks[0].is_chain);
        let (force, acc, scale) = froude_krylov_expected(&lay, &pos, &sea);
        // The water accelerates along and across the element by far more than the
        // tolerances below: the case tests both parts.
        assert!(
            acc[0].abs() > 1e-3 * scale && acc[1].abs() > 1e-3 * scale,
            "{acc:?}"
        );
        let dt = 1e-4;
        let opts = SolverOptions {
            dt,
            ..SolverOptions::default()
        };
        let fscale = scale * (lay.line_types[0].mass_per_length + 3.0 * 8.05) * 2.0;
        for exact in [true, false] {
            // The general path's loads and accelerations at t = 0.
            let mut s = CpuSolver::new(lay.clone(), &pos, opts);
            s.set_sea(&sea, exact);
            s.use_chain_kernel = false;
            let ev = s.evaluate().unwrap();
            let total: [f64; 3] = std::array::from_fn(|q| ev.force[0][q] + ev.force[1][q]);
            let what = format!("cm {cm}, cat {cat}, exact {exact}");
            close(&format!("{what}: load"), total, force, fscale, 1e-12);
            for i in 0..2 {
                close(
                    &format!("{what}: node {i} acc"),
                    ev.acc[i],
                    acc,
                    scale,
                    1e-12,
                );
            }
            // A first step on each path.
            for chain in [false, true] {
                let mut s = CpuSolver::new(lay.clone(), &pos, opts);
                s.set_sea(&sea, exact);
                s.use_chain_kernel = chain;
                s.advance(1).unwrap();
                for i in 0..2 {
                    let a = s.v[i].to_f64().map(|v| v / dt);
                    close(
                        &format!("{what}, chain path {chain}: node {i} first step"),
                        a,
                        acc,
                        scale,
                        1e-10,
                    );
                }
            }
        }
    }
}
