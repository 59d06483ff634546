//! The network path's element loop in whole chunks of lanes (a piece's elements, the
//! last chunk overlapping the one before it: no scalar remainder), its submerged test,
//! and one gathered element at a time: the chain path's element arithmetic
//! ([`element_lane`]) behind the network's pieces (moved out of `chain/elements.rs`).

use super::super::consts::ChainConsts;
use super::super::elements::{chunk_at, element_lane, overlapped_chunks, put_chunk, ElemConsts};
use super::super::lanes::keep_chunks;

/// Whether every end of the `ne` elements with ends `a`, `b` (`[x, y, z, vx, vy, vz,
/// eta]`, as [`element_kernel`](super::super::elements::element_kernel)'s) is at or below the surface (then every wetted
/// fraction is exactly 1); in still water (`WAVES` false) the surface is at zero and
/// its columns are not read. In whole chunks of `L` lanes where `ne >= L`.
#[inline(always)]
pub(super) fn all_under<const WAVES: bool, const L: usize>(
    a: [&[f64]; 7],
    b: [&[f64]; 7],
    ne: usize,
) -> bool {
    let (za, zb, ea, eb) = (&a[2][..ne], &b[2][..ne], &a[6][..ne], &b[6][..ne]);
    let under = |k: usize| {
        if WAVES {
            (ea[k] - za[k] >= 0.0) & (eb[k] - zb[k] >= 0.0)
        } else {
            (za[k] <= 0.0) & (zb[k] <= 0.0)
        }
    };
    if ne < L {
        return (0..ne).all(under);
    }
    // Per lane, a count of the ends over the surface (integers: the comparisons'
    // masks stay in vector registers; `bool` lanes would be packed to bytes).
    let mut over = [0u64; L];
    for o in overlapped_chunks::<L>(ne) {
        keep_chunks();
        // SAFETY: `o + L <= ne`, and every slice here has `ne` entries.
        let (za, zb) = unsafe { (chunk_at::<L>(za, o), chunk_at::<L>(zb, o)) };
        if WAVES {
            // SAFETY: as above.
            let (ea, eb) = unsafe { (chunk_at::<L>(ea, o), chunk_at::<L>(eb, o)) };
            for l in 0..L {
                over[l] += (!((ea[l] - za[l] >= 0.0) & (eb[l] - zb[l] >= 0.0))) as u64;
            }
        } else {
            for l in 0..L {
                over[l] += (!((za[l] <= 0.0) & (zb[l] <= 0.0))) as u64;
            }
        }
    }
    over.iter().all(|&x| x == 0)
}

/// [`element_kernel`](super::super::elements::element_kernel) for `SUBMERGED` elements (every end at or below the surface) of a
/// network piece of at least `L` elements, over whole chunks of `L` lanes
/// ([`overlapped_chunks`]: no scalar remainder): each chunk loads its inputs into
/// locals, runs [`element_lane`] per lane and stores, as the chain's element loop does (`element_chunks`). `UNIFORM`: every element's water velocity is `un` (a uniform current in
/// still water; `u` is not read); else `u`'s. Same bits as [`element_kernel`](super::super::elements::element_kernel).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn element_chunks_net<const WAVES: bool, const UNIFORM: bool, const L: usize>(
    a: [&[f64]; 7],
    b: [&[f64]; 7],
    u: [&[f64]; 3],
    un: [f64; 3],
    aw: [&[f64]; 3],
    c: &ChainConsts,
    e0: usize,
    out: [&mut [f64]; 8],
) {
    let [tx, ty, tz, ten, fx, fy, fz, haw] = out;
    let ne = tx.len();
    assert!(ne >= L);
    // Every column read or written below holds the piece's `ne` entries (checked once
    // here: the chunks' loads and stores are unchecked).
    let k = net_consts(c, e0, ne);
    assert!(net_inputs_hold::<WAVES, UNIFORM>(a, b, u, aw, ne));
    let outs = [&*ty, &*tz, &*ten, &*fx, &*fy, &*fz, &*haw];
    assert!(outs.iter().all(|q| q.len() == ne));
    for o in overlapped_chunks::<L>(ne) {
        keep_chunks();
        // SAFETY: `o + L <= ne`, and every column has `ne` entries or more (above).
        let r = unsafe { element_chunk_net::<WAVES, UNIFORM, L>(a, b, u, un, aw, &k, o) };
        // SAFETY: as above.
        unsafe {
            put_chunk::<L>(tx, o, r[0]);
            put_chunk::<L>(ty, o, r[1]);
            put_chunk::<L>(tz, o, r[2]);
            put_chunk::<L>(ten, o, r[3]);
            put_chunk::<L>(fx, o, r[4]);
            put_chunk::<L>(fy, o, r[5]);
            put_chunk::<L>(fz, o, r[6]);
            put_chunk::<L>(haw, o, r[7]);
        }
    }
}

/// The constants [`element_chunk_net`] reads for the `ne` elements from `e0` on.
#[inline(always)]
pub(super) fn net_consts(c: &ChainConsts, e0: usize, ne: usize) -> [&[f64]; 11] {
    let e1 = e0 + ne;
    [
        &c.il0[e0..e1],
        &c.ea[e0..e1],
        &c.eac[e0..e1],
        &c.comp[e0..e1],
        &c.drag_n[e0..e1],
        &c.drag_t[e0..e1],
        &c.half_wz[e0..e1],
        &c.half_bz[e0..e1],
        &c.half_fk[e0..e1],
        &c.ha[e0 + 1..e1 + 1],
        &c.half_fkt[e0..e1],
    ]
}

/// Whether every input column [`element_chunk_net`] reads holds `ne` entries or more.
#[inline(always)]
pub(super) fn net_inputs_hold<const WAVES: bool, const UNIFORM: bool>(
    a: [&[f64]; 7],
    b: [&[f64]; 7],
    u: [&[f64]; 3],
    aw: [&[f64]; 3],
    ne: usize,
) -> bool {
    let ins = a.iter().chain(&b).chain(if WAVES { &aw[..] } else { &[] });
    ins.chain(if UNIFORM { &[] } else { &u[..] })
        .all(|q| q.len() >= ne)
}

/// One chunk of [`element_chunks_net`]: the `L` submerged elements from entry `o` on
/// of ends `a`, `b`, water velocity `u` (or `un` with `UNIFORM`), wave acceleration
/// `aw`, constants `k` ([`net_consts`]); returns `t` (3), `ten`, `f` (3), `haw`, each
/// a chunk of lanes ([`element_lane`] per lane).
///
/// # Safety
/// `o + L` is at most the length of every column read ([`net_inputs_hold`], and the
/// columns of `k`).
#[inline(always)]
pub(super) unsafe fn element_chunk_net<const WAVES: bool, const UNIFORM: bool, const L: usize>(
    a: [&[f64]; 7],
    b: [&[f64]; 7],
    u: [&[f64]; 3],
    un: [f64; 3],
    aw: [&[f64]; 3],
    k: &[&[f64]; 11],
    o: usize,
) -> [[f64; L]; 8] {
    // SAFETY: the caller's bound.
    let ld = |s: &[f64]| unsafe { chunk_at::<L>(s, o) };
    // (The surface is not read: submerged elements.)
    let (pa, pb): ([[f64; L]; 6], [[f64; L]; 6]) = (
        [ld(a[0]), ld(a[1]), ld(a[2]), ld(a[3]), ld(a[4]), ld(a[5])],
        [ld(b[0]), ld(b[1]), ld(b[2]), ld(b[3]), ld(b[4]), ld(b[5])],
    );
    // SAFETY: the caller's bound.
    unsafe { element_chunk_ends::<WAVES, UNIFORM, L>(pa, pb, u, un, aw, k, o) }
}

/// [`element_chunk_net`] for a run's chunk whose ends are read from the block's state
/// columns `x` (`[x, y, z, vx, vy, vz]`) at nodes `ia .. ia + L` and `ib .. ib + L`:
/// one base pointer per column for both ends (two indices), where the ends' 12 cut
/// columns each took a pointer of their own, more than the registers (spilled, a
/// reload per column and chunk).
///
/// # Safety
/// `ia + L` and `ib + L` at most the length of every column of `x`; `o + L` as for
/// [`element_chunk_net`] (`u`, `aw`, `k`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) unsafe fn element_chunk_run<const WAVES: bool, const UNIFORM: bool, const L: usize>(
    x: [&[f64]; 6],
    ia: usize,
    ib: usize,
    u: [&[f64]; 3],
    un: [f64; 3],
    aw: [&[f64]; 3],
    k: &[&[f64]; 11],
    o: usize,
) -> [[f64; L]; 8] {
    // SAFETY: the caller's bounds.
    let (pa, pb): ([[f64; L]; 6], [[f64; L]; 6]) = unsafe {
        (
            std::array::from_fn(|q| chunk_at::<L>(x[q], ia)),
            std::array::from_fn(|q| chunk_at::<L>(x[q], ib)),
        )
    };
    // SAFETY: the caller's bound.
    unsafe { element_chunk_ends::<WAVES, UNIFORM, L>(pa, pb, u, un, aw, k, o) }
}

/// The rest of [`element_chunk_net`], the ends' state `pa`, `pb` loaded.
///
/// # Safety
/// As [`element_chunk_net`].
#[inline(always)]
unsafe fn element_chunk_ends<const WAVES: bool, const UNIFORM: bool, const L: usize>(
    pa: [[f64; L]; 6],
    pb: [[f64; L]; 6],
    u: [&[f64]; 3],
    un: [f64; 3],
    aw: [&[f64]; 3],
    k: &[&[f64]; 11],
    o: usize,
) -> [[f64; L]; 8] {
    // SAFETY: the caller's bound.
    let ld = |s: &[f64]| unsafe { chunk_at::<L>(s, o) };
    let uc = if UNIFORM {
        [[un[0]; L], [un[1]; L], [un[2]; L]]
    } else {
        [ld(u[0]), ld(u[1]), ld(u[2])]
    };
    let awc = if WAVES {
        [ld(aw[0]), ld(aw[1]), ld(aw[2])]
    } else {
        [[0.0; L]; 3]
    };
    let kc = [
        ld(k[0]),
        ld(k[1]),
        ld(k[2]),
        ld(k[3]),
        ld(k[4]),
        ld(k[5]),
        ld(k[6]),
        ld(k[7]),
        ld(k[8]),
        ld(k[9]),
        ld(k[10]),
    ];
    let mut r = [[0.0; L]; 8];
    for l in 0..L {
        // (Arrays written out: `array::map` here need not be inlined.)
        let e = element_lane::<WAVES, true>(
            [
                pa[0][l], pa[1][l], pa[2][l], pa[3][l], pa[4][l], pa[5][l], 0.0,
            ],
            [
                pb[0][l], pb[1][l], pb[2][l], pb[3][l], pb[4][l], pb[5][l], 0.0,
            ],
            [uc[0][l], uc[1][l], uc[2][l]],
            [awc[0][l], awc[1][l], awc[2][l]],
            ElemConsts {
                il0: kc[0][l],
                ea: kc[1][l],
                eac: kc[2][l],
                comp: kc[3][l],
                dn: kc[4][l],
                dt: kc[5][l],
                hw: kc[6][l],
                hb: kc[7][l],
                hfk: kc[8][l],
                hfkt: kc[10][l],
                // Submerged: the mass along the tangent is the block's `hm`.
                hmd: 0.0,
                hat: 0.0,
                ha: kc[9][l],
                diam: 0.0,
            },
        );
        [r[0][l], r[1][l], r[2][l]] = e.t;
        r[3][l] = e.ten;
        [r[4][l], r[5][l], r[6][l]] = e.f;
        r[7][l] = e.haw;
    }
    r
}

/// [`element_lane`] for one element `e` of `c`, its wetted fraction computed (exactly
/// 1 for an element under the surface, so the same bits as `SUBMERGED`): for the
/// network path's gathered elements. Returns the tangent, tension, force, `hmw` and
/// `haw` of [`ElemOut`].
#[inline(always)]
pub(super) fn element_one<const WAVES: bool>(
    a: [f64; 7],
    b: [f64; 7],
    u: [f64; 3],
    aw: [f64; 3],
    c: &ChainConsts,
    e: usize,
) -> ([f64; 3], f64, [f64; 3], f64, f64) {
    let k = ElemConsts {
        il0: c.il0[e],
        ea: c.ea[e],
        eac: c.eac[e],
        comp: c.comp[e],
        dn: c.drag_n[e],
        dt: c.drag_t[e],
        hw: c.half_wz[e],
        hb: c.half_bz[e],
        hfk: c.half_fk[e],
        hfkt: c.half_fkt[e],
        hmd: c.hmd[e],
        hat: c.hat[e],
        ha: c.ha[e + 1],
        diam: c.diameter[e],
    };
    let o = element_lane::<WAVES, false>(a, b, u, aw, k);
    (o.t, o.ten, o.f, o.hmw, o.haw)
}
