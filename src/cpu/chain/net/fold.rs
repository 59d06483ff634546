//! The element pass's last step on the network path: each element's results folded into
//! what it adds to its two nodes, written into their slots ([`super::Loads`]).

use super::super::consts::ChainConsts;
use super::super::elements::{chunk_at, overlapped_chunks, put_chunk};
use super::super::lanes::keep_chunks;
use super::element_chunks::{element_chunk_run, net_consts, net_inputs_hold};
use super::{cut, LoadsOut, NetConsts, Piece, COLS, NT};
use std::ops::Range;

/// A run's elements (`ne`, ends from nodes `a0`, `b0` on) in stretches whose two
/// ends' nodes each stay in one tile (so that each end's slot columns are contiguous).
#[inline(always)]
fn stretches(a0: usize, b0: usize, ne: usize) -> impl Iterator<Item = Range<usize>> {
    let mut k0 = 0;
    std::iter::from_fn(move || {
        (k0 < ne).then(|| {
            let (a, b) = (a0 + k0, b0 + k0);
            let len = (ne - k0).min(NT - a % NT).min(NT - b % NT);
            k0 += len;
            k0 - len..k0
        })
    })
}

/// The element loop and the fold in one loop, for a run `piece` whose elements are all
/// submerged: per chunk of `L` elements, [`element_chunk_net`] then [`fold_chunk`],
/// written straight into the ends' slots in `out` (the element results never stored:
/// what [`super::element_chunks::element_chunks_net`] then [`node_shares`] do, with
/// the same bits, less 8 stores and 8 loads per chunk). `a`, `b`, `u`, `aw` as for
/// [`element_chunk_net`], over the piece's elements. Returns false, having done
/// nothing, when a stretch ([`stretches`]) is shorter than `L`. `view`: the ends'
/// first nodes in the state columns `x` that `a`, `b` were cut from (whose columns
/// the loop reads, through one pointer per column for both ends).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn run_shares<const WAVES: bool, const UNIFORM: bool, const L: usize>(
    c: &ChainConsts,
    eslot: &[Vec<u8>; 2],
    piece: &Piece,
    a: [&[f64]; 7],
    b: [&[f64]; 7],
    u: [&[f64]; 3],
    un: [f64; 3],
    aw: [&[f64]; 3],
    view: ([usize; 2], [&[f64]; 6]),
    out: LoadsOut,
) -> bool {
    let Some((a0, b0)) = piece.ends else {
        return false;
    };
    let (e0, ne) = (piece.elems.start, piece.elems.len());
    if stretches(a0, b0, ne).any(|ks| ks.len() < L) {
        return false;
    }
    let (sa, sb) = (eslot[0][e0] as usize, eslot[1][e0] as usize);
    assert!(net_inputs_hold::<WAVES, UNIFORM>(a, b, u, aw, ne));
    // The ends' state columns from the view's node `xa0` on (`a`'s are the view's
    // from its node `xa0`, `b`'s from `xb0`), read at two indices.
    let ([xa0, xb0], x) = view;
    assert!(x.iter().all(|q| q.len() >= xa0.max(xb0) + ne));
    for ks in stretches(a0, b0, ne) {
        let (k0, len) = (ks.start, ks.len());
        let (ia, ib) = (xa0 + k0, xb0 + k0);
        // (Columns not read, `u` with `UNIFORM` and `aw` in still water, are the
        // scratch's, as long as the piece.)
        let (u, aw) = (cut(u, ks.clone()), cut(aw, ks.clone()));
        let k = net_consts(c, e0 + k0, len);
        let hm = &c.hm[e0 + k0 + 1..e0 + k0 + 1 + len];
        // SAFETY: as in `node_shares`: the run's ends are nodes `a0 ..`, `b0 ..` in
        // slots `sa`, `sb` all along, slots of these elements only, that `out`'s
        // contract gives this call alone; the stretch keeps each end in one tile.
        let (na, nb) = (a0 + k0, b0 + k0);
        let mut ma: [&mut [f64]; 6] =
            std::array::from_fn(|q| unsafe { out.column(COLS * sa + q, na, len) });
        let mut mb: [&mut [f64]; 6] =
            std::array::from_fn(|q| unsafe { out.column(COLS * sb + q, nb, len) });
        let mut fa: [&mut [f64]; 3] =
            std::array::from_fn(|q| unsafe { out.column(COLS * sa + 6 + q, na, len) });
        let mut fb: [&mut [f64]; 3] =
            std::array::from_fn(|q| unsafe { out.column(COLS * sb + 6 + q, nb, len) });
        for o in overlapped_chunks::<L>(len) {
            keep_chunks();
            // SAFETY (every chunk): `o + L <= len`, and every column read holds the
            // stretch's `len` entries (the inputs checked above, the constants and
            // the slots cut to it).
            let r = unsafe {
                element_chunk_run::<WAVES, UNIFORM, L>(x, ia + o, ib + o, u, un, aw, &k, o)
            };
            let s = fold_chunk::<L>(
                [r[0], r[1], r[2]],
                r[7],
                unsafe { chunk_at::<L>(hm, o) },
                r[3],
                [r[4], r[5], r[6]],
            );
            // SAFETY: as above.
            unsafe { put_shares::<L>(&mut ma, &mut mb, &mut fa, &mut fb, o, s) };
        }
    }
    true
}

/// Folds the element loop's results for the elements of `piece` into what they add to
/// their nodes (the general path's `hm I + a (I - t t^T)`, and `f/2 + (+-1 T) t` per
/// end), written into each end's slot in `out`, for a run (one slot per end along it:
/// vector stores); gathered elements take [`super::gathered::gathered_shares`]. `hm`:
/// the elements' half masses along their tangents (the block's `hm` for submerged
/// elements, else the element loop's `hmw`), `haw` what the normal plane has more.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn node_shares<const L: usize>(
    nc: &NetConsts,
    piece: &Piece,
    t: &[Vec<f64>; 3],
    ten: &[f64],
    f: &[Vec<f64>; 3],
    hm: &[f64],
    haw: &[f64],
    out: LoadsOut,
) {
    let e0 = piece.elems.start;
    let ne = ten.len();
    let [tx, ty, tz] = t.each_ref().map(|q| &q[..ne]);
    let [fx, fy, fz] = f.each_ref().map(|q| &q[..ne]);
    let (haw, hm) = (&haw[..ne], &hm[..ne]);
    let (sa, sb) = (nc.eslot[0][e0] as usize, nc.eslot[1][e0] as usize);
    // Gathered elements take `gathered_shares`.
    let (a0, b0) = piece.ends.expect("node_shares of a run");
    for ks in stretches(a0, b0, ne) {
        let (k0, len) = (ks.start, ks.len());
        let (a, b) = (a0 + k0, b0 + k0);
        // SAFETY: a run's ends are nodes `a0 ..`, `b0 ..` of the block, in
        // slots `sa`, `sb` all along (`pieces`), slots that belong to these
        // elements only (so the two sides' columns do not overlap) and that
        // `out`'s contract gives this call alone; `len` keeps each in a tile.
        let (ma, mb): ([&mut [f64]; 6], [&mut [f64]; 6]) = unsafe {
            (
                std::array::from_fn(|q| out.column(COLS * sa + q, a, len)),
                std::array::from_fn(|q| out.column(COLS * sb + q, b, len)),
            )
        };
        let [tx, ty, tz] = [tx, ty, tz].map(|q| &q[ks.clone()]);
        let (haw, hm) = (&haw[ks.clone()], &hm[ks.clone()]);
        let ([fx, fy, fz], ten) = ([fx, fy, fz].map(|q| &q[ks.clone()]), &ten[ks]);
        if len >= L {
            // SAFETY: as above, the force columns too (other columns of the
            // same slots).
            let (fa, fb): ([&mut [f64]; 3], [&mut [f64]; 3]) = unsafe {
                (
                    std::array::from_fn(|q| out.column(COLS * sa + 6 + q, a, len)),
                    std::array::from_fn(|q| out.column(COLS * sb + 6 + q, b, len)),
                )
            };
            fold_chunks::<L>([tx, ty, tz], haw, hm, ten, [fx, fy, fz], ma, mb, fa, fb);
            continue;
        }
        let [xxa, yya, zza, xya, xza, yza] = ma;
        let [xxb, yyb, zzb, xyb, xzb, yzb] = mb;
        fold_mass(
            tx, ty, tz, haw, hm, xxa, yya, zza, xya, xza, yza, xxb, yyb, zzb, xyb, xzb, yzb,
        );
        // SAFETY: as above; the mass columns' slices are no longer used.
        let (fa, fb): ([&mut [f64]; 3], [&mut [f64]; 3]) = unsafe {
            (
                std::array::from_fn(|q| out.column(COLS * sa + 6 + q, a, len)),
                std::array::from_fn(|q| out.column(COLS * sb + 6 + q, b, len)),
            )
        };
        let ([fxa, fya, fza], [fxb, fyb, fzb]) = (fa, fb);
        fold_force(tx, ty, tz, ten, fx, fy, fz, fxa, fya, fza, fxb, fyb, fzb);
    }
}

/// A run's shares of its nodes (the arithmetic of [`fold_mass`] and [`fold_force`],
/// written to the same columns) over whole chunks of `L` lanes of its `len >= L`
/// elements ([`overlapped_chunks`]: no scalar remainder): each chunk loads its inputs
/// into locals, computes and stores, so no run-time overlap checks either.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fold_chunks<const L: usize>(
    t: [&[f64]; 3],
    haw: &[f64],
    hm: &[f64],
    ten: &[f64],
    f: [&[f64]; 3],
    ma: [&mut [f64]; 6],
    mb: [&mut [f64]; 6],
    fa: [&mut [f64]; 3],
    fb: [&mut [f64]; 3],
) {
    let len = haw.len();
    assert!(len >= L);
    // Every column holds the run's `len` entries (checked once: the chunks' loads and
    // stores are unchecked).
    let mut ins = t.iter().chain(&f).chain([&hm, &ten]);
    assert!(ins.all(|q| q.len() == len));
    let mut outs = ma.iter().chain(&mb).chain(&fa).chain(&fb);
    assert!(outs.all(|q| q.len() == len));
    let (mut ma, mut mb, mut fa, mut fb) = (ma, mb, fa, fb);
    for o in overlapped_chunks::<L>(len) {
        keep_chunks();
        // SAFETY (every chunk): `o + L <= len`, the length of every column (above).
        let ld = |s: &[f64]| unsafe { chunk_at::<L>(s, o) };
        let r = fold_chunk::<L>(
            [ld(t[0]), ld(t[1]), ld(t[2])],
            ld(haw),
            ld(hm),
            ld(ten),
            [ld(f[0]), ld(f[1]), ld(f[2])],
        );
        // SAFETY: as above.
        unsafe { put_shares::<L>(&mut ma, &mut mb, &mut fa, &mut fb, o, r) };
    }
}

/// One chunk of `L` elements' shares of their nodes ([`fold_mass`]'s and
/// [`fold_force`]'s arithmetic per lane): the mass block `xx, yy, zz, xy, xz, yz`,
/// the force on node a, the force on node b.
#[inline(always)]
fn fold_chunk<const L: usize>(
    t: [[f64; L]; 3],
    a: [f64; L],
    hm: [f64; L],
    tn: [f64; L],
    f: [[f64; L]; 3],
) -> [[f64; L]; 12] {
    let mut r = [[0.0; L]; 12];
    for l in 0..L {
        let (tx, ty, tz, a, hm) = (t[0][l], t[1][l], t[2][l], a[l], hm[l]);
        let (tn, ntn) = (tn[l], -tn[l]);
        r[0][l] = hm + (a - a * tx * tx);
        r[1][l] = hm + (a - a * ty * ty);
        r[2][l] = hm + (a - a * tz * tz);
        r[3][l] = -(a * tx * ty);
        r[4][l] = -(a * tx * tz);
        r[5][l] = -(a * ty * tz);
        r[6][l] = f[0][l] + tx * tn;
        r[7][l] = f[1][l] + ty * tn;
        r[8][l] = f[2][l] + tz * tn;
        r[9][l] = f[0][l] + tx * ntn;
        r[10][l] = f[1][l] + ty * ntn;
        r[11][l] = f[2][l] + tz * ntn;
    }
    r
}

/// Writes a [`fold_chunk`] to entries `o .. o + L` of the slots' columns: the mass
/// block to both ends (`*a`, `*b`), each end's force to its own.
///
/// # Safety
/// `o + L` is at most every column's length.
#[inline(always)]
unsafe fn put_shares<const L: usize>(
    ma: &mut [&mut [f64]; 6],
    mb: &mut [&mut [f64]; 6],
    fa: &mut [&mut [f64]; 3],
    fb: &mut [&mut [f64]; 3],
    o: usize,
    r: [[f64; L]; 12],
) {
    // SAFETY: the caller's bound.
    unsafe {
        for q in 0..6 {
            put_chunk::<L>(ma[q], o, r[q]);
        }
        for q in 0..6 {
            put_chunk::<L>(mb[q], o, r[q]);
        }
        for q in 0..3 {
            put_chunk::<L>(fa[q], o, r[6 + q]);
            put_chunk::<L>(fb[q], o, r[9 + q]);
        }
    }
}

/// A run's share of its nodes' mass blocks, `m/2 I + a (I - t t^T)` entry by entry
/// (`hm` the half mass, `haw` the added mass `a`), written to both ends' slots (`*a`,
/// `*b`). Every array is its own parameter, as in
/// [`element_kernel`](super::super::elements::element_kernel): outputs known not to
/// alias need no run-time overlap checks before the vector loop.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fold_mass(
    tx: &[f64],
    ty: &[f64],
    tz: &[f64],
    haw: &[f64],
    hm: &[f64],
    xxa: &mut [f64],
    yya: &mut [f64],
    zza: &mut [f64],
    xya: &mut [f64],
    xza: &mut [f64],
    yza: &mut [f64],
    xxb: &mut [f64],
    yyb: &mut [f64],
    zzb: &mut [f64],
    xyb: &mut [f64],
    xzb: &mut [f64],
    yzb: &mut [f64],
) {
    let ne = tx.len();
    let (ty, tz, haw, hm) = (&ty[..ne], &tz[..ne], &haw[..ne], &hm[..ne]);
    let (xxa, yya, zza) = (&mut xxa[..ne], &mut yya[..ne], &mut zza[..ne]);
    let (xya, xza, yza) = (&mut xya[..ne], &mut xza[..ne], &mut yza[..ne]);
    let (xxb, yyb, zzb) = (&mut xxb[..ne], &mut yyb[..ne], &mut zzb[..ne]);
    let (xyb, xzb, yzb) = (&mut xyb[..ne], &mut xzb[..ne], &mut yzb[..ne]);
    for k in 0..ne {
        let a = haw[k];
        let xx = hm[k] + (a - a * tx[k] * tx[k]);
        let yy = hm[k] + (a - a * ty[k] * ty[k]);
        let zz = hm[k] + (a - a * tz[k] * tz[k]);
        let xy = -(a * tx[k] * ty[k]);
        let xz = -(a * tx[k] * tz[k]);
        let yz = -(a * ty[k] * tz[k]);
        (xxa[k], yya[k], zza[k], xya[k], xza[k], yza[k]) = (xx, yy, zz, xy, xz, yz);
        (xxb[k], yyb[k], zzb[k], xyb[k], xzb[k], yzb[k]) = (xx, yy, zz, xy, xz, yz);
    }
}

/// A run's forces on its nodes: `f/2 + T t` on node a (`*a`), `f/2 - T t` on node b
/// (`*b`); every array its own parameter, as in [`fold_mass`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fold_force(
    tx: &[f64],
    ty: &[f64],
    tz: &[f64],
    ten: &[f64],
    fx: &[f64],
    fy: &[f64],
    fz: &[f64],
    fxa: &mut [f64],
    fya: &mut [f64],
    fza: &mut [f64],
    fxb: &mut [f64],
    fyb: &mut [f64],
    fzb: &mut [f64],
) {
    let ne = tx.len();
    let (ty, tz, ten) = (&ty[..ne], &tz[..ne], &ten[..ne]);
    let (fx, fy, fz) = (&fx[..ne], &fy[..ne], &fz[..ne]);
    let (fxa, fya, fza) = (&mut fxa[..ne], &mut fya[..ne], &mut fza[..ne]);
    let (fxb, fyb, fzb) = (&mut fxb[..ne], &mut fyb[..ne], &mut fzb[..ne]);
    for k in 0..ne {
        let (tn, ntn) = (ten[k], -ten[k]);
        fxa[k] = fx[k] + tx[k] * tn;
        fya[k] = fy[k] + ty[k] * tn;
        fza[k] = fz[k] + tz[k] * tn;
        fxb[k] = fx[k] + tx[k] * ntn;
        fyb[k] = fy[k] + ty[k] * ntn;
        fzb[k] = fz[k] + tz[k] * ntn;
    }
}
