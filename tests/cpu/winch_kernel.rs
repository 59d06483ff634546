//! Winch cables (ALE-GLMF) on the chain fast path against the general path, while the
//! winch pays out and hauls in: the variable element through the vectorised element
//! loop, its damping on the material strain rate, the mass-flow forces added to the
//! node force before the solve, and the insertions and deletions of nodes.

use crate::ale::{clump, hanging, out_and_back, solver, winch};
use crate::common::*;
use cablesim::ale::WinchEnd;
use cablesim::options::Scheme;

#[test]
fn winch_fast_path_matches_the_general_path_through_payout_and_retrieval() {
    let (l_s, n, dt) = (2.0, 5usize, 2e-4);
    // 9 s: paid out 12 m (5 to 11 elements, ramps with Lddot = +-2 m/s^2) and 2 m of
    // it hauled back in (one node deleted).
    let steps = 45_000;
    for end in [WinchEnd::Start, WinchEnd::End] {
        for scheme in [Scheme::Symplectic, Scheme::Rk4] {
            let def = hanging(rope(), n, l_s, clump(20.0), end, [0.6, 0.2, 0.0]);
            let mut general = solver(
                def.clone(),
                winch(end, out_and_back(), 1e3, l_s),
                dt,
                scheme,
            );
            general.use_chain_kernel = false;
            let mut fast = solver(def, winch(end, out_and_back(), 1e3, l_s), dt, scheme);
            let (mut most, mut worst_r, mut worst_v) = (0, 0.0f64, 0.0f64);
            for _ in 0..9 {
                general.advance(steps / 9).unwrap();
                fast.advance(steps / 9).unwrap();
                assert_eq!(
                    fast.r.len(),
                    general.r.len(),
                    "{end:?} {scheme:?}: node counts"
                );
                most = most.max(fast.r.len());
                for (a, b) in fast.r.iter().zip(&general.r) {
                    worst_r = worst_r.max((*a - *b).norm());
                }
                for (a, b) in fast.v.iter().zip(&general.v) {
                    worst_v = worst_v.max((*a - *b).norm());
                }
            }
            assert!(
                most >= 11,
                "{end:?} {scheme:?}: the cable was paid out ({most} nodes)"
            );
            assert!(
                fast.r.len() < most,
                "{end:?} {scheme:?}: and hauled in ({} nodes)",
                fast.r.len()
            );
            assert!(
                worst_r < 1e-10 && worst_v < 1e-8,
                "{end:?} {scheme:?}: fast and general paths differ by {worst_r:e} m, {worst_v:e} m/s"
            );
            eprintln!("{end:?} {scheme:?}: {worst_r:e} m, {worst_v:e} m/s");
        }
    }
}
