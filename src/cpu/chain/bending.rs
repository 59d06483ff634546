//! Bending stiffness on the chain fast path (docs/src/model/bending.md): the forces of
//! a chain's hinges, in branch-free loops over its nodes that the compiler vectorises,
//! added to the node pass as extra forces (the columns `col::XFX..`, which the node
//! loop then reads for every node).
//!
//! The same hinges and forces as the general path's `bending_pass`
//! (`physics::bending_hinge`), in another order: each hinge's pair `(f1, f2)` once
//! per node into two column triples, then each node's sum `f2` of the hinge before
//! it, `f1` of the hinge after it and `-(f1 + f2)` of its own; and the angle's
//! arctangent as a rational function with selects ([`atan2_pos`], within an f64 ulp
//! of `f64::atan2`: a library call per lane would keep the loop scalar). So the two
//! paths agree to round-off, not to the bit (`tests/cpu/bending.rs`).

use super::lanes::{col, ColumnsView, Stride};
use crate::model::{Block, Hinge, Layout, NO_ELEM};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// The hinges of a chain block, as the fast path reads them.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChainBend {
    /// Per node (padded with zeros): the stiffness `EI / lbar` of the hinge at the
    /// node, N m; 0 where there is none (a pinned end, a node between elements
    /// without `EI`).
    pub(super) kh: Vec<f64>,
    /// A clamped end a: its held direction and stiffness.
    pub(super) clamp_a: Option<([f64; 3], f64)>,
    /// A clamped end b: its held direction and stiffness.
    pub(super) clamp_b: Option<([f64; 3], f64)>,
}

impl ChainBend {
    /// The hinges `hinges` of chain block `b` (its slice of `Layout::hinges`), or
    /// `None` where they are not a chain's: an interior hinge between elements that
    /// are not consecutive, a clamp other than at the chain's first or last element
    /// (the block then takes the general passes).
    pub(crate) fn new(lay: &Layout, b: &Block, hinges: &[Hinge]) -> Option<Self> {
        let n0 = b.node_start as usize;
        let (e0, e1) = (b.elem_start, b.elem_end);
        let n = (b.node_end - b.node_start) as usize;
        let mut c = ChainBend {
            kh: vec![0.0; n],
            ..Default::default()
        };
        for h in hinges {
            if h.prev == NO_ELEM {
                (h.next == e0).then_some(())?;
                c.clamp_a = Some((h.dir, h.k));
            } else if h.next == NO_ELEM {
                (h.prev + 1 == e1).then_some(())?;
                c.clamp_b = Some((h.dir, h.k));
            } else {
                (h.next == h.prev + 1).then_some(())?;
                // Element k of a chain joins nodes k and k + 1.
                let i = lay.elem_b[h.prev as usize] as usize - n0;
                c.kh[i] = h.k;
            }
        }
        Some(c)
    }
}

/// `atan(num / den)` for `0 <= num <= den`: above 0.66 by `pi/4 + atan(x)` with
/// `x = (num - den) / (num + den)`, then Cephes' rational approximation
/// `x + x^3 P(x^2) / Q(x^2)` (the shaders' `bending_atan`); one division for the
/// argument, one for the rational.
#[inline(always)]
fn atan_ratio(num: f64, den: f64) -> f64 {
    let big = num > 0.66 * den;
    let x = if big {
        (num - den) / (num + den)
    } else {
        num / den
    };
    let (y, lo) = if big {
        (FRAC_PI_4, 0.5 * 6.123233995736766e-17)
    } else {
        (0.0, 0.0)
    };
    let z = x * x;
    let p = (((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z
        - 7.500855792314704667340e1)
        * z
        - 1.228866684490136173410e2)
        * z
        - 6.485021904942025371773e1;
    let q = ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z
        + 4.328810604912902668951e2)
        * z
        + 4.853903996359136964868e2)
        * z
        + 1.945506571482613964425e2;
    y + ((x * (z * p / q) + x) + lo)
}

/// `atan2(s, c)` for `s >= 0` (not both zero), without branches (the shaders'
/// `bending_atan2`).
#[inline(always)]
pub(crate) fn atan2_pos(s: f64, c: f64) -> f64 {
    let ac = c.abs();
    // |c| >= s: atan(s / |c|), else pi/2 - atan(|c| / s); mirrored for c < 0.
    let near = ac >= s;
    let (num, den) = if near { (s, ac) } else { (ac, s) };
    let a = atan_ratio(num, den);
    let r = if near { a } else { FRAC_PI_2 - a };
    if c < 0.0 {
        PI - r
    } else {
        r
    }
}

/// The forces `(f1, f2)` of a hinge of stiffness `k` between unit tangents `q1`, `q2`
/// of elements of inverse lengths `il1`, `il2` (`physics::bending_hinge`).
#[inline(always)]
fn hinge(q1: [f64; 3], il1: f64, q2: [f64; 3], il2: f64, k: f64) -> ([f64; 3], [f64; 3]) {
    let c = q1[0] * q2[0] + q1[1] * q2[1] + q1[2] * q2[2];
    let x = [
        q1[1] * q2[2] - q1[2] * q2[1],
        q1[2] * q2[0] - q1[0] * q2[2],
        q1[0] * q2[1] - q1[1] * q2[0],
    ];
    let s = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let phi = atan2_pos(s, c);
    let small = s < 1e-4;
    let g = if small {
        1.0 + phi * phi / 6.0
    } else {
        phi / if small { 1.0 } else { s }
    };
    let kg = k * g;
    let (a1, a2) = (-kg * il1, kg * il2);
    (
        [
            (q2[0] - q1[0] * c) * a1,
            (q2[1] - q1[1] * c) * a1,
            (q2[2] - q1[2] * c) * a1,
        ],
        [
            (q1[0] - q2[0] * c) * a2,
            (q1[1] - q2[1] * c) * a2,
            (q1[2] - q2[2] * c) * a2,
        ],
    )
}

/// The first bending column: per padded element, the inverse of its current length;
/// then each hinge's `f1` and `f2` per node (shifted by one: node `i` at entry `i + 1`).
pub(super) const IL: usize = col::COUNT;
const F1: usize = col::COUNT + 1;
const F2: usize = col::COUNT + 4;
/// The columns of a chain block with bending.
pub(super) const COUNT: usize = col::COUNT + 7;

/// Writes the bending force of every node of a chain of `n` nodes (positions `p`)
/// into the extra forces' columns (`=`, over every padded entry: the point masses'
/// forces are added after), from the element tangents the element pass left in the
/// block `wv` (which has [`COUNT`] columns).
///
/// # Safety
/// Every column of `p` and `wv` has at least `padded_len(n)` entries, no slice of
/// `wv`'s columns lives during the call, and `bd.kh` has `n` entries or more.
#[inline(always)]
pub(super) unsafe fn bending_forces<St: Stride>(
    n: usize,
    bd: &ChainBend,
    p: &[Vec<f64>; 6],
    wv: &ColumnsView<'_, St>,
) {
    let len = super::lanes::padded_len(n);
    // SAFETY: distinct columns of the block (the caller's), reached only here.
    let (tx, ty, tz, il) = unsafe {
        (
            &wv.col(col::TX)[..len],
            &wv.col(col::TX + 1)[..len],
            &wv.col(col::TX + 2)[..len],
            &mut wv.col_mut(IL)[..len],
        )
    };
    let ne = n.saturating_sub(1);
    inverse_lengths(&p[0][..n], &p[1][..n], &p[2][..n], &mut il[1..ne + 1]);
    // SAFETY: as above.
    let (f1x, f1y, f1z, f2x, f2y, f2z) = unsafe {
        (
            &mut wv.col_mut(F1)[..len],
            &mut wv.col_mut(F1 + 1)[..len],
            &mut wv.col_mut(F1 + 2)[..len],
            &mut wv.col_mut(F2)[..len],
            &mut wv.col_mut(F2 + 1)[..len],
            &mut wv.col_mut(F2 + 2)[..len],
        )
    };
    let il = &*il;
    // The interior hinges, nodes 1..n-1: node i joins padded elements i and i + 1;
    // its pair at entry i + 1.
    if n >= 3 {
        let m = n - 2;
        hinge_loop(
            [&tx[1..m + 1], &ty[1..m + 1], &tz[1..m + 1], &il[1..m + 1]],
            [&tx[2..m + 2], &ty[2..m + 2], &tz[2..m + 2], &il[2..m + 2]],
            &bd.kh[1..m + 1],
            &mut f1x[2..m + 2],
            &mut f1y[2..m + 2],
            &mut f1z[2..m + 2],
            &mut f2x[2..m + 2],
            &mut f2y[2..m + 2],
            &mut f2z[2..m + 2],
        );
    }
    // The clamped ends: the held direction in place of the missing element (length
    // 1); the force on the missing far node is dropped, so the held node takes the
    // other's opposite only.
    let (o1, o2) = (1, n);
    f1x[o1] = 0.0;
    f1y[o1] = 0.0;
    f1z[o1] = 0.0;
    f2x[o1] = 0.0;
    f2y[o1] = 0.0;
    f2z[o1] = 0.0;
    f1x[o2] = 0.0;
    f1y[o2] = 0.0;
    f1z[o2] = 0.0;
    f2x[o2] = 0.0;
    f2y[o2] = 0.0;
    f2z[o2] = 0.0;
    if ne >= 1 {
        if let Some((d, k)) = bd.clamp_a {
            let (_, f2) = hinge(d, 1.0, [tx[1], ty[1], tz[1]], il[1], k);
            (f2x[o1], f2y[o1], f2z[o1]) = (f2[0], f2[1], f2[2]);
        }
        if let Some((d, k)) = bd.clamp_b {
            let (f1, _) = hinge([tx[ne], ty[ne], tz[ne]], il[ne], d, 1.0, k);
            (f1x[o2], f1y[o2], f1z[o2]) = (f1[0], f1[1], f1[2]);
        }
    }
    // Each node: f2 of the hinge before it, f1 of the hinge after it, less its own
    // pair. Entries 0 and n + 1 of the force columns are zero (no hinge).
    // SAFETY: as above.
    let (xfx, xfy, xfz) = unsafe {
        (
            &mut wv.col_mut(col::XFX)[..len],
            &mut wv.col_mut(col::XFX + 1)[..len],
            &mut wv.col_mut(col::XFX + 2)[..len],
        )
    };
    let (f1x, f1y, f1z, f2x, f2y, f2z) = (&*f1x, &*f1y, &*f1z, &*f2x, &*f2y, &*f2z);
    node_sum(
        &mut xfx[..n],
        &f2x[..n],
        &f1x[1..n + 1],
        &f2x[1..n + 1],
        &f1x[2..n + 2],
    );
    node_sum(
        &mut xfy[..n],
        &f2y[..n],
        &f1y[1..n + 1],
        &f2y[1..n + 1],
        &f1y[2..n + 2],
    );
    node_sum(
        &mut xfz[..n],
        &f2z[..n],
        &f1z[1..n + 1],
        &f2z[1..n + 1],
        &f1z[2..n + 2],
    );
}

// The loops, each array a parameter of its own: `&mut [f64]` parameters are known not
// to alias (the columns come from one block through raw pointers, which the compiler
// cannot tell apart), which is what lets it vectorise them whole.

/// `il[k] = 1 / |r[k + 1] - r[k]|` over the chain's elements.
#[inline(always)]
fn inverse_lengths(x: &[f64], y: &[f64], z: &[f64], il: &mut [f64]) {
    let ne = il.len();
    let (xa, ya, za) = (&x[..ne], &y[..ne], &z[..ne]);
    let (xb, yb, zb) = (&x[1..ne + 1], &y[1..ne + 1], &z[1..ne + 1]);
    for k in 0..ne {
        let d = [xb[k] - xa[k], yb[k] - ya[k], zb[k] - za[k]];
        il[k] = 1.0 / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    }
}

/// Each interior hinge's pair: tangents and inverse lengths `a` of the element before
/// and `b` of the one after, stiffness `kh`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn hinge_loop(
    a: [&[f64]; 4],
    b: [&[f64]; 4],
    kh: &[f64],
    f1x: &mut [f64],
    f1y: &mut [f64],
    f1z: &mut [f64],
    f2x: &mut [f64],
    f2y: &mut [f64],
    f2z: &mut [f64],
) {
    let m = kh.len();
    let [q1x, q1y, q1z, il1] = a;
    let [q2x, q2y, q2z, il2] = b;
    let (q1x, q1y, q1z, il1) = (&q1x[..m], &q1y[..m], &q1z[..m], &il1[..m]);
    let (q2x, q2y, q2z, il2) = (&q2x[..m], &q2y[..m], &q2z[..m], &il2[..m]);
    let (f1x, f1y, f1z) = (&mut f1x[..m], &mut f1y[..m], &mut f1z[..m]);
    let (f2x, f2y, f2z) = (&mut f2x[..m], &mut f2y[..m], &mut f2z[..m]);
    for i in 0..m {
        let (f1, f2) = hinge(
            [q1x[i], q1y[i], q1z[i]],
            il1[i],
            [q2x[i], q2y[i], q2z[i]],
            il2[i],
            kh[i],
        );
        f1x[i] = f1[0];
        f1y[i] = f1[1];
        f1z[i] = f1[2];
        f2x[i] = f2[0];
        f2y[i] = f2[1];
        f2z[i] = f2[2];
    }
}

/// Each node's sum: `f2` of the hinge before it, `f1` of the hinge after it, less its
/// own pair.
#[inline(always)]
fn node_sum(out: &mut [f64], f2b: &[f64], own1: &[f64], own2: &[f64], f1a: &[f64]) {
    let n = out.len();
    let (f2b, own1, own2, f1a) = (&f2b[..n], &own1[..n], &own2[..n], &f1a[..n]);
    for i in 0..n {
        out[i] = (f2b[i] + f1a[i]) - (own1[i] + own2[i]);
    }
}
