//! The element pass over a piece of gathered elements (those not in a run: a
//! cylinder's closing twine per row, a row's first twine, the inner twines of
//! multi-element twines): element by element, its two ends read by index, the chain's
//! element arithmetic, then the fold of its results into its two nodes' slots, all in
//! registers. A net cage has a few such elements per tile (64 of 8064 in the example
//! cage), in one- or two-element pieces, so what counts here is the cost per piece:
//! no scratch columns gathered, filled, computed and read back (was 700-odd
//! instructions a piece, about 12 a node-step of the cage).

use super::element_chunks::element_one;
use super::{LoadsOut, NetConsts, COLS};
use crate::cpu::water::node_water;
use crate::model::Layout;
use std::ops::Range;

/// Elements `er` (all gathered), their ends' state `src` (`[x, y, z, vx, vy, vz, eta]`
/// from block node `base` on), water `w` (per block node; empty in still water), what
/// they add to their nodes written into their slots in `out`. Per element the
/// arithmetic of the run path: the current at the element's mid-depth (or the uniform
/// one) plus the mean of its ends' wave velocities, the element loop (wetted fraction
/// computed), the fold (`m/2 I + a (I - t t^T)`, `f/2 +- T t`).
#[inline(always)]
pub(super) fn gathered_shares<const WAVES: bool>(
    nc: &NetConsts,
    lay: &Layout,
    er: Range<usize>,
    src: [&[f64]; 7],
    base: usize,
    w: &[f64],
    out: LoadsOut,
) {
    let c = &nc.c;
    let n = src[0].len();
    assert!(src.iter().all(|q| q.len() == n));
    for e in er {
        let (ia, ib) = (nc.ends[0][e] as usize, nc.ends[1][e] as usize);
        let (ja, jb) = (ia.wrapping_sub(base), ib.wrapping_sub(base));
        // The elements reach no node outside the view.
        assert!(ja < n && jb < n);
        // In still water the surface (`eta`) is zero, as the run path reads it.
        let a: [f64; 7] = std::array::from_fn(|q| src[q][ja]);
        let b: [f64; 7] = std::array::from_fn(|q| src[q][jb]);
        let mut u = match c.uniform {
            Some(un) => un,
            None => lay.currents[c.current[e] as usize]
                .at::<f64>(0.5 * (a[2] + b[2]))
                .to_f64(),
        };
        let mut aw = [0.0; 3];
        if WAVES {
            // The mean of the two ends' wave velocity and acceleration.
            let (_, ua, aa) = node_water(w, ia);
            let (_, ub, ab) = node_water(w, ib);
            for q in 0..3 {
                u[q] += 0.5 * (ua[q] + ub[q]);
                aw[q] = 0.5 * (aa[q] + ab[q]);
            }
        }
        let ([tx, ty, tz], tn, f, hm, a) = element_one::<WAVES>(a, b, u, aw, c, e);
        let ntn = -tn;
        let m = [
            hm + (a - a * tx * tx),
            hm + (a - a * ty * ty),
            hm + (a - a * tz * tz),
            -(a * tx * ty),
            -(a * tx * tz),
            -(a * ty * tz),
        ];
        let fa = [f[0] + tx * tn, f[1] + ty * tn, f[2] + tz * tn];
        let fb = [f[0] + tx * ntn, f[1] + ty * ntn, f[2] + tz * ntn];
        for (i, s, fs) in [(ia, nc.eslot[0][e], fa), (ib, nc.eslot[1][e], fb)] {
            let c0 = COLS * s as usize;
            // SAFETY: node `i` is in the block and slot `s` below the width
            // (`NetConsts::new`); this element's slot is this call's alone.
            unsafe {
                for (q, &v) in m.iter().enumerate() {
                    out.column(c0 + q, i, 1)[0] = v;
                }
                for (q, &v) in fs.iter().enumerate() {
                    out.column(c0 + 6 + q, i, 1)[0] = v;
                }
            }
        }
    }
}
