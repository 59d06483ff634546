//! The element pass's last step on the network path: each element's results folded into
//! what it adds to its two nodes, written into their slots ([`super::Loads`]).

use super::super::elements::{chunk_at, overlapped_chunks, put_chunk};
use super::super::lanes::keep_chunks;
use super::{LoadsOut, NetConsts, Piece, COLS, NT};

/// Folds the element loop's results for the elements of `piece` into what they add to
/// their nodes (the general path's `m/2 I + a (I - t t^T)`, and `f/2 + (+-1 T) t` per
/// end), written into each end's slot in `out`: with vector stores for a run (one slot
/// per end along it), one by one for gathered elements.
#[inline(always)]
pub(super) fn node_shares<const L: usize>(
    nc: &NetConsts,
    piece: &Piece,
    t: &[Vec<f64>; 3],
    ten: &[f64],
    f: &[Vec<f64>; 3],
    haw: &[f64],
    out: LoadsOut,
) {
    let e0 = piece.elems.start;
    let ne = ten.len();
    let [tx, ty, tz] = t.each_ref().map(|q| &q[..ne]);
    let [fx, fy, fz] = f.each_ref().map(|q| &q[..ne]);
    let (haw, hm) = (&haw[..ne], &nc.c.hm[e0 + 1..e0 + 1 + ne]);
    let (sa, sb) = (nc.eslot[0][e0] as usize, nc.eslot[1][e0] as usize);
    match piece.ends {
        Some((a0, b0)) => {
            // In stretches whose two ends' nodes each stay in one tile.
            let mut k0 = 0;
            while k0 < ne {
                let (a, b) = (a0 + k0, b0 + k0);
                let len = (ne - k0).min(NT - a % NT).min(NT - b % NT);
                let ks = k0..k0 + len;
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
                    k0 += len;
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
                k0 += len;
            }
        }
        None => {
            let (ea, eb) = (&nc.ends[0][e0..e0 + ne], &nc.ends[1][e0..e0 + ne]);
            let (sa, sb) = (&nc.eslot[0][e0..e0 + ne], &nc.eslot[1][e0..e0 + ne]);
            for k in 0..ne {
                let (tn, ntn) = (ten[k], -ten[k]);
                let a = haw[k];
                let m = [
                    hm[k] + (a - a * tx[k] * tx[k]),
                    hm[k] + (a - a * ty[k] * ty[k]),
                    hm[k] + (a - a * tz[k] * tz[k]),
                    -(a * tx[k] * ty[k]),
                    -(a * tx[k] * tz[k]),
                    -(a * ty[k] * tz[k]),
                ];
                let fa = [fx[k] + tx[k] * tn, fy[k] + ty[k] * tn, fz[k] + tz[k] * tn];
                let fb = [
                    fx[k] + tx[k] * ntn,
                    fy[k] + ty[k] * ntn,
                    fz[k] + tz[k] * ntn,
                ];
                for (i, s, fs) in [(ea[k], sa[k], fa), (eb[k], sb[k], fb)] {
                    let (i, c0) = (i as usize, COLS * s as usize);
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
    let [mut xxa, mut yya, mut zza, mut xya, mut xza, mut yza] = ma;
    let [mut xxb, mut yyb, mut zzb, mut xyb, mut xzb, mut yzb] = mb;
    let ([mut fxa, mut fya, mut fza], [mut fxb, mut fyb, mut fzb]) = (fa, fb);
    for o in overlapped_chunks::<L>(len) {
        keep_chunks();
        // SAFETY (every chunk): `o + L <= len`, the length of every column (above).
        let ld = |s: &[f64]| unsafe { chunk_at::<L>(s, o) };
        let (tx, ty, tz, a, hm, tn) = (ld(t[0]), ld(t[1]), ld(t[2]), ld(haw), ld(hm), ld(ten));
        let (fx, fy, fz) = (ld(f[0]), ld(f[1]), ld(f[2]));
        let mut r = [[0.0; L]; 12];
        for l in 0..L {
            let (tx, ty, tz, a, hm) = (tx[l], ty[l], tz[l], a[l], hm[l]);
            let (tn, ntn) = (tn[l], -tn[l]);
            r[0][l] = hm + (a - a * tx * tx);
            r[1][l] = hm + (a - a * ty * ty);
            r[2][l] = hm + (a - a * tz * tz);
            r[3][l] = -(a * tx * ty);
            r[4][l] = -(a * tx * tz);
            r[5][l] = -(a * ty * tz);
            r[6][l] = fx[l] + tx * tn;
            r[7][l] = fy[l] + ty * tn;
            r[8][l] = fz[l] + tz * tn;
            r[9][l] = fx[l] + tx * ntn;
            r[10][l] = fy[l] + ty * ntn;
            r[11][l] = fz[l] + tz * ntn;
        }
        // SAFETY: as above.
        unsafe {
            for (q, m) in [&mut xxa, &mut yya, &mut zza, &mut xya, &mut xza, &mut yza]
                .into_iter()
                .enumerate()
            {
                put_chunk::<L>(m, o, r[q]);
            }
            for (q, m) in [&mut xxb, &mut yyb, &mut zzb, &mut xyb, &mut xzb, &mut yzb]
                .into_iter()
                .enumerate()
            {
                put_chunk::<L>(m, o, r[q]);
            }
            for (q, v) in [&mut fxa, &mut fya, &mut fza].into_iter().enumerate() {
                put_chunk::<L>(v, o, r[6 + q]);
            }
            for (q, v) in [&mut fxb, &mut fyb, &mut fzb].into_iter().enumerate() {
                put_chunk::<L>(v, o, r[9 + q]);
            }
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
