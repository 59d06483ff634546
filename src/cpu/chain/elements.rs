//! The element pass of the chain fast path: per-element water velocity (currents,
//! waves), then the branch-free element loop ([`element_kernel`], shared with the
//! network path) writing unit tangents, tensions, half drag plus half weight less
//! buoyancy, and the wetted half masses into the padded element columns.

use super::consts::ChainConsts;
use super::lanes::{
    chunks_for, col, keep_chunks, lanes, lanes_mut, lanes_next, ColumnsView, Stride,
};
use crate::cpu::water::{hermite_at, node_water, ChainCols};
use crate::model::Current;
use crate::physics::wetted_fraction;

/// What is the same for every element of a chain in still water with one uniform
/// current and one line type: the current and the line's constants, which the
/// element loop then reads from here instead of five columns and the current's three
/// (the same values, so the same bits). Held as whole chunks of `L` lanes, made once
/// per run of steps: the loop reads them as memory operands, where a scalar each
/// was broadcast and spilled to the stack again every step (about 16 instructions).
#[derive(Clone, Copy)]
pub(super) struct UniformLine<const L: usize> {
    u: [[f64; L]; 3],
    ea: [f64; L],
    eac: [f64; L],
    comp: [f64; L],
    dn: [f64; L],
    dt: [f64; L],
}

impl<const L: usize> Default for UniformLine<L> {
    fn default() -> Self {
        UniformLine {
            u: [[0.0; L]; 3],
            ea: [0.0; L],
            eac: [0.0; L],
            comp: [0.0; L],
            dn: [0.0; L],
            dt: [0.0; L],
        }
    }
}

impl<const L: usize> UniformLine<L> {
    /// Whether block `c` has a uniform line: its current is uniform and every element
    /// has the same `EA`, damping, compression factor and drag coefficients (to the
    /// bit); then [`Self::make`] makes it.
    pub(super) fn fits(c: &ChainConsts) -> bool {
        let ne = c.l0.len();
        let same = |v: &[f64]| v[..ne].iter().all(|x| x.to_bits() == v[0].to_bits());
        c.uniform.is_some()
            && ne != 0
            && [&c.ea, &c.eac, &c.comp, &c.drag_n, &c.drag_t]
                .into_iter()
                .all(|v| same(v))
    }

    /// The uniform line of block `c`, which [`Self::fits`].
    pub(super) fn make(c: &ChainConsts) -> Self {
        let u = c.uniform.expect("a uniform current");
        UniformLine {
            u: [[u[0]; L], [u[1]; L], [u[2]; L]],
            ea: [c.ea[0]; L],
            eac: [c.eac[0]; L],
            comp: [c.comp[0]; L],
            dn: [c.drag_n[0]; L],
            dt: [c.drag_t[0]; L],
        }
    }
}

/// Element pass over SoA positions and velocities `p`, currents `u`, into the padded
/// element columns of the block `wv` (tangents, tensions, forces: module
/// [`super::lanes`]'s `col`), `hmw` and `haw` (the wetted half masses: along the
/// tangent, and what the normal plane has more). `under`: whether
/// every node is known to be at or below the surface `eta` (else found here). Returns
/// whether it was: then the wetted half masses are the block's `c.hm` and `c.ha`, and
/// `hmw`, `haw` are not written. `uni`: the block's uniform line in still water, if it is one
/// (then `u` is not read).
///
/// # Safety
/// Every column of `c`, `p`, `u`, `aw`, `eta`, `wv`, `hmw` and `haw` has at least
/// [`super::lanes::padded_len`]`(c.n)` entries (module [`super::lanes`]), no slice of
/// `wv`'s columns lives during the call, and `L` is 4 or 8.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) unsafe fn elements<const WAVES: bool, const L: usize, St: Stride>(
    c: &ChainConsts,
    p: &[Vec<f64>; 6],
    u: &[Vec<f64>; 3],
    aw: &[Vec<f64>; 3],
    eta: &[f64],
    wv: &ColumnsView<'_, St>,
    hmw: &mut [f64],
    haw: &mut [f64],
    under: Option<bool>,
    uni: Option<&UniformLine<L>>,
) -> bool {
    let ne = c.l0.len();
    // Every node at or below the surface (the common case: a line in still water, or
    // deep in waves) makes every wetted fraction exactly 1 (`wetted_fraction`'s first
    // case), so the loop without it gives the same bits, and stays vectorised. (The
    // padding nodes, at zero under a zero surface, count as under it.)
    let under = under.unwrap_or_else(|| {
        let nn = chunks_for::<L>(ne + 1);
        // SAFETY: the caller's columns hold `padded_len(c.n) >= nn * L` entries.
        let (eta_c, z_c) = unsafe { (lanes::<L>(eta, nn), lanes::<L>(&p[2], nn)) };
        let mut under = [true; L];
        for j in 0..nn {
            keep_chunks();
            for l in 0..L {
                under[l] &= eta_c[j][l] - z_c[j][l] >= 0.0;
            }
        }
        under.iter().all(|&x| x)
    });
    if under {
        // SAFETY: the caller's columns, as this function's.
        unsafe {
            match uni {
                Some(k) if !WAVES => {
                    element_chunks::<WAVES, true, false, L, St>(c, p, u, aw, wv, k, None)
                }
                _ => element_chunks::<WAVES, false, false, L, St>(
                    c,
                    p,
                    u,
                    aw,
                    wv,
                    &UniformLine::default(),
                    None,
                ),
            }
        };
        return true;
    }
    // SAFETY: seven distinct columns of the block, reached only here.
    let (tx, ty, tz, ten, fx, fy, fz) = unsafe {
        (
            wv.col_mut(col::TX),
            wv.col_mut(col::TX + 1),
            wv.col_mut(col::TX + 2),
            wv.col_mut(col::TEN),
            wv.col_mut(col::FX),
            wv.col_mut(col::FX + 1),
            wv.col_mut(col::FX + 2),
        )
    };
    element_kernel::<WAVES, false>(
        [
            &p[0][..ne],
            &p[1][..ne],
            &p[2][..ne],
            &p[3][..ne],
            &p[4][..ne],
            &p[5][..ne],
            &eta[..ne],
        ],
        [
            &p[0][1..ne + 1],
            &p[1][1..ne + 1],
            &p[2][1..ne + 1],
            &p[3][1..ne + 1],
            &p[4][1..ne + 1],
            &p[5][1..ne + 1],
            &eta[1..ne + 1],
        ],
        &u[0][..ne],
        &u[1][..ne],
        &u[2][..ne],
        &aw[0][..ne],
        &aw[1][..ne],
        &aw[2][..ne],
        c,
        0,
        &mut tx[1..ne + 1],
        &mut ty[1..ne + 1],
        &mut tz[1..ne + 1],
        &mut ten[1..ne + 1],
        &mut fx[1..ne + 1],
        &mut fy[1..ne + 1],
        &mut fz[1..ne + 1],
        &mut hmw[1..ne + 1],
        &mut haw[1..ne + 1],
    );
    false
}

/// The element loop over elements `e0..e0 + tx.len()` of the block's constants `c`.
/// Every array is its own parameter: `&mut [f64]` parameters are known not to alias,
/// which is what lets the compiler vectorise the loop (arrays reached through one
/// `&mut [Vec<f64>; 3]` would need run-time overlap checks). `a` and `b` are the
/// elements' end nodes, `[x, y, z, vx, vy, vz, eta]` per element (for a chain, the
/// node arrays and the same shifted by one; for a network, gathered by index).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn element_kernel<const WAVES: bool, const SUBMERGED: bool>(
    a: [&[f64]; 7],
    b: [&[f64]; 7],
    ux: &[f64],
    uy: &[f64],
    uz: &[f64],
    awx: &[f64],
    awy: &[f64],
    awz: &[f64],
    c: &ChainConsts,
    e0: usize,
    tx: &mut [f64],
    ty: &mut [f64],
    tz: &mut [f64],
    ten: &mut [f64],
    fx: &mut [f64],
    fy: &mut [f64],
    fz: &mut [f64],
    hmw: &mut [f64],
    haw: &mut [f64],
) {
    let ne = tx.len();
    // Slices cut one by one: `array::map` here is a call per stage (not inlined).
    let [xa, ya, za, vxa, vya, vza, eta_a] = a;
    let [xb, yb, zb, vxb, vyb, vzb, eta_b] = b;
    let (xa, ya, za, vxa, vya, vza, eta_a) = (
        &xa[..ne],
        &ya[..ne],
        &za[..ne],
        &vxa[..ne],
        &vya[..ne],
        &vza[..ne],
        &eta_a[..ne],
    );
    let (xb, yb, zb, vxb, vyb, vzb, eta_b) = (
        &xb[..ne],
        &yb[..ne],
        &zb[..ne],
        &vxb[..ne],
        &vyb[..ne],
        &vzb[..ne],
        &eta_b[..ne],
    );
    let (ux, uy, uz) = (&ux[..ne], &uy[..ne], &uz[..ne]);
    let (hmw, haw) = (&mut hmw[..ne], &mut haw[..ne]);
    let e1 = e0 + ne;
    let (hb, ha) = (&c.half_bz[e0..e1], &c.ha[e0 + 1..e1 + 1]);
    let (hmd, hat) = (&c.hmd[e0..e1], &c.hat[e0..e1]);
    let (awx, awy, awz) = (&awx[..ne], &awy[..ne], &awz[..ne]);
    let (hfk, hfkt) = (&c.half_fk[e0..e1], &c.half_fkt[e0..e1]);
    let diam = &c.diameter[e0..e1];
    let (ty, tz, ten, fx, fy, fz) = (
        &mut ty[..ne],
        &mut tz[..ne],
        &mut ten[..ne],
        &mut fx[..ne],
        &mut fy[..ne],
        &mut fz[..ne],
    );
    let (il0, ea, eac, comp) = (
        &c.il0[e0..e1],
        &c.ea[e0..e1],
        &c.eac[e0..e1],
        &c.comp[e0..e1],
    );
    let (dn, dt, hw) = (&c.drag_n[e0..e1], &c.drag_t[e0..e1], &c.half_wz[e0..e1]);
    for k in 0..ne {
        let o = element_lane::<WAVES, SUBMERGED>(
            [xa[k], ya[k], za[k], vxa[k], vya[k], vza[k], eta_a[k]],
            [xb[k], yb[k], zb[k], vxb[k], vyb[k], vzb[k], eta_b[k]],
            [ux[k], uy[k], uz[k]],
            [awx[k], awy[k], awz[k]],
            ElemConsts {
                il0: il0[k],
                ea: ea[k],
                eac: eac[k],
                comp: comp[k],
                dn: dn[k],
                dt: dt[k],
                hw: hw[k],
                hb: hb[k],
                hfk: hfk[k],
                hfkt: hfkt[k],
                hmd: hmd[k],
                hat: hat[k],
                ha: ha[k],
                diam: diam[k],
            },
        );
        fx[k] = o.f[0];
        fy[k] = o.f[1];
        fz[k] = o.f[2];
        hmw[k] = o.hmw;
        haw[k] = o.haw;
        tx[k] = o.t[0];
        ty[k] = o.t[1];
        tz[k] = o.t[2];
        ten[k] = o.ten;
    }
}

/// The chunks of `L` lanes that cover `ne >= L` entries without a remainder: from entry
/// 0 on, `L` apart, the last one ending at entry `ne` (so it overlaps the one before
/// it when `L` does not divide `ne`). A loop whose lanes are independent and whose
/// outputs are not its inputs computes the overlapped entries twice, with the same
/// bits, and writes them twice: the network path's element and fold loops run so,
/// its pieces being of any length.
#[inline(always)]
pub fn overlapped_chunks<const L: usize>(ne: usize) -> impl Iterator<Item = usize> {
    debug_assert!(ne >= L);
    (0..ne.div_ceil(L)).map(move |j| (j * L).min(ne - L))
}

/// `L` entries of `s` from `o` on.
///
/// # Safety
/// `o + L <= s.len()`.
#[inline(always)]
pub(super) unsafe fn chunk_at<const L: usize>(s: &[f64], o: usize) -> [f64; L] {
    debug_assert!(o + L <= s.len());
    // SAFETY: the caller's bound; `[f64; L]` has the layout of `L` consecutive f64.
    unsafe { s.as_ptr().add(o).cast::<[f64; L]>().read_unaligned() }
}

/// Writes `v` to the `L` entries of `s` from `o` on.
///
/// # Safety
/// `o + L <= s.len()`.
#[inline(always)]
pub(super) unsafe fn put_chunk<const L: usize>(s: &mut [f64], o: usize, v: [f64; L]) {
    debug_assert!(o + L <= s.len());
    // SAFETY: as in `chunk_at`.
    unsafe { s.as_mut_ptr().add(o).cast::<[f64; L]>().write_unaligned(v) }
}

/// One element's constants (see [`ChainConsts`]): `hfk`, `hfkt` its half
/// water-acceleration coefficients across and along it, `hmd`, `hat` its half mass and
/// half tangential added mass, `ha` what its normal plane has more when wholly wet.
#[derive(Clone, Copy)]
pub(super) struct ElemConsts {
    pub(super) il0: f64,
    pub(super) ea: f64,
    pub(super) eac: f64,
    pub(super) comp: f64,
    pub(super) dn: f64,
    pub(super) dt: f64,
    pub(super) hw: f64,
    pub(super) hb: f64,
    pub(super) hfk: f64,
    pub(super) hfkt: f64,
    pub(super) hmd: f64,
    pub(super) hat: f64,
    pub(super) ha: f64,
    pub(super) diam: f64,
}

/// What the element loop writes for one element.
pub(super) struct ElemOut {
    /// Unit tangent.
    pub(super) t: [f64; 3],
    /// Tension, N.
    pub(super) ten: f64,
    /// Half drag plus half the weight less buoyancy (and, in waves, half the
    /// water-acceleration load), N.
    pub(super) f: [f64; 3],
    /// Half the mass along the tangent, its tangential added mass times the wetted
    /// fraction, kg.
    pub(super) hmw: f64,
    /// What the normal plane has more (`(Cm - Cat) rho A l0 / 2`) times the wetted
    /// fraction, kg.
    pub(super) haw: f64,
}

/// The element loop's arithmetic for one element with ends `a`, `b` (`[x, y, z, vx,
/// vy, vz, eta]`), water velocity `u` and wave acceleration `aw`: one definition for
/// the loop over elements ([`element_kernel`]) and the loop over whole chunks of
/// lanes ([`element_chunks`]), so both give the same bits.
#[inline(always)]
pub(super) fn element_lane<const WAVES: bool, const SUBMERGED: bool>(
    a: [f64; 7],
    b: [f64; 7],
    u: [f64; 3],
    aw: [f64; 3],
    k: ElemConsts,
) -> ElemOut {
    element_lane_lits::<WAVES, SUBMERGED>(a, b, u, aw, k, Literals::PLAIN)
}

/// The literals of [`element_lane`]'s arithmetic: `0.5`, `1.0` and `0.0`, as values.
#[derive(Clone, Copy)]
pub(super) struct Literals {
    half: f64,
    one: f64,
    zero: f64,
}

impl Literals {
    /// The literals themselves (folded by the compiler as before).
    pub(super) const PLAIN: Literals = Literals {
        half: 0.5,
        one: 1.0,
        zero: 0.0,
    };

    /// The same values hidden from the optimiser (`std::hint::black_box`), for the
    /// chain's loop over chunks: with AVX2's 16 vector registers a known 0.5 was
    /// re-broadcast from the constant pool before each of its six uses a chunk, and
    /// `x - 1.0` became `x + (-1.0)` with a broadcast of its own (two instructions each
    /// use); unknown values are broadcast once a step and kept in a register or read as
    /// a memory operand (one). The same values, so the same bits.
    #[inline(always)]
    pub(super) fn hidden() -> Literals {
        std::hint::black_box(Literals::PLAIN)
    }
}

/// [`element_lane`] with its literals given as values ([`Literals`]).
#[inline(always)]
pub(super) fn element_lane_lits<const WAVES: bool, const SUBMERGED: bool>(
    a: [f64; 7],
    b: [f64; 7],
    u: [f64; 3],
    aw: [f64; 3],
    k: ElemConsts,
    lits: Literals,
) -> ElemOut {
    let (l, il) = element_length(a, b, lits);
    element_lane_len::<WAVES, SUBMERGED>(a, b, u, aw, k, lits, l, il)
}

/// An element's length `l` and its inverse `1 / l` from its ends `a`, `b`: the first
/// two of [`element_lane`]'s three operations on the divider.
#[inline(always)]
pub(super) fn element_length(a: [f64; 7], b: [f64; 7], lits: Literals) -> (f64, f64) {
    let (dx, dy, dz) = (b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    let l = (dx * dx + dy * dy + dz * dz).sqrt();
    (l, lits.one / l)
}

/// [`element_lane_lits`] given the element's length and its inverse
/// ([`element_length`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn element_lane_len<const WAVES: bool, const SUBMERGED: bool>(
    a: [f64; 7],
    b: [f64; 7],
    u: [f64; 3],
    aw: [f64; 3],
    k: ElemConsts,
    lits: Literals,
    l: f64,
    il: f64,
) -> ElemOut {
    let Literals { half, one, zero } = lits;
    let (dx, dy, dz) = (b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    let (ex, ey, ez) = (dx * il, dy * il, dz * il);
    let eps = l * k.il0 - one;
    let epsdot = (ex * (b[3] - a[3]) + ey * (b[4] - a[4]) + ez * (b[5] - a[5])) * k.il0;
    // Slack: the elastic part vanishes in compression unless the line is a rod.
    let elastic = k.ea * eps * if eps > zero { one } else { k.comp };
    let tension = elastic + k.eac * epsdot;
    let rx = u[0] - half * (a[3] + b[3]);
    let ry = u[1] - half * (a[4] + b[4]);
    let rz = u[2] - half * (a[5] + b[5]);
    let vt = ex * rx + ey * ry + ez * rz;
    let (nx, ny, nz) = (rx - ex * vt, ry - ey * vt, rz - ez * vt);
    // Water terms times the wetted fraction; the dry part loses its buoyancy.
    let wet = if SUBMERGED {
        1.0
    } else {
        wetted_fraction(a[6] - a[2], b[6] - b[2], k.diam)
    };
    let kn = k.dn * l * (nx * nx + ny * ny + nz * nz).sqrt() * wet;
    let kt = k.dt * l * vt.abs() * vt * wet;
    // Submerged, `hw - 0 hb` is `hw`, bit for bit: two operations fewer an element.
    let hw_wet = if SUBMERGED {
        k.hw
    } else {
        k.hw - (1.0 - wet) * k.hb
    };
    // Half of drag, plus half the weight less buoyancy (no water acceleration yet).
    let mut f = [
        half * (nx * kn + ex * kt),
        half * (ny * kn + ey * kt),
        half * (nz * kn + ez * kt) + hw_wet,
    ];
    if WAVES {
        // Froude-Krylov and added mass (physics::froude_krylov): across the element on
        // the normal wave acceleration P a_w, along it on (t . a_w) t.
        let an = ex * aw[0] + ey * aw[1] + ez * aw[2];
        let (kf, kt) = (k.hfk * wet, k.hfkt * wet);
        let at = kt * an;
        f[0] += kf * (aw[0] - ex * an) + ex * at;
        f[1] += kf * (aw[1] - ey * an) + ey * at;
        f[2] += kf * (aw[2] - ez * an) + ez * at;
    }
    ElemOut {
        t: [ex, ey, ez],
        ten: tension,
        f,
        hmw: k.hmd + k.hat * wet,
        haw: k.ha * wet,
    }
}

/// The element pass in waves from the cache's power-basis columns `w` (several depth
/// bands: [`ChainCols::unit`]) when every node is under the surface: interpolates each
/// node's elevation into `eta` and checks it against the node's height in the same
/// pass; then, if every node is under, runs the element loop with each element's wave
/// velocity and acceleration interpolated in its lanes ([`element_chunks`] with
/// `FUSED`) instead of written to the columns `u`, `aw` by one pass and read back by
/// the next. The same arithmetic per value as [`ChainCols::fill`] then [`elements`],
/// so the same bits. Returns `false`, having written only `eta`, when some node is
/// above the surface: the caller then fills the columns and runs [`elements`].
/// `uni`: the block's line constants and uniform current, if it has them (else `u`
/// holds the currents).
///
/// # Safety
/// As [`elements`]; `w`'s columns hold [`super::lanes::padded_len`]`(c.n)` entries.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) unsafe fn elements_fused<const L: usize, St: Stride>(
    c: &ChainConsts,
    p: &[Vec<f64>; 6],
    w: &ChainCols,
    u: &[Vec<f64>; 3],
    eta: &mut [f64],
    wv: &ColumnsView<'_, St>,
    uni: Option<&UniformLine<L>>,
) -> bool {
    debug_assert!(w.unit);
    let nn = chunks_for::<L>(c.n);
    // SAFETY: the caller's columns hold `padded_len(c.n) >= nn * L` entries.
    let (z_c, eta_c) = unsafe { (lanes::<L>(&p[2], nn), lanes_mut::<L>(eta, 0, nn)) };
    // SAFETY: as above, for the cache's columns.
    let ec = unsafe {
        [
            lanes::<L>(w.eta_col(0), nn),
            lanes::<L>(w.eta_col(1), nn),
            lanes::<L>(w.eta_col(2), nn),
            lanes::<L>(w.eta_col(3), nn),
        ]
    };
    let wt = w.w;
    let mut under = [true; L];
    for j in 0..nn {
        keep_chunks();
        let (e0, e1, e2, e3, z) = (ec[0][j], ec[1][j], ec[2][j], ec[3][j], z_c[j]);
        let mut h = [0.0; L];
        for l in 0..L {
            h[l] = hermite_at::<true>(wt, e0[l], e1[l], e2[l], e3[l]);
            under[l] &= h[l] - z[l] >= 0.0;
        }
        eta_c[j] = h;
    }
    if !under.iter().all(|&x| x) {
        return false;
    }
    // SAFETY: the caller's columns, as this function's.
    unsafe {
        match uni {
            Some(k) => element_chunks::<true, true, true, L, St>(c, p, u, u, wv, k, Some(w)),
            None => element_chunks::<true, false, true, L, St>(
                c,
                p,
                u,
                u,
                wv,
                &UniformLine::default(),
                Some(w),
            ),
        }
    }
    true
}

/// The element loop of a chain whose every node is under the surface, over `nc`
/// whole chunks of elements of the padded columns (module [`super::lanes`]):
/// element `k` reads nodes `k` and `k + 1` of `p` and writes padded element `k + 1`
/// (not its wetted half masses: wholly wet, they are the block's `hm` and `ha`). With `UNI`
/// the current and the line's constants are `k`'s, in every lane (the padding lanes
/// too: their results are dropped or reset, as with zeros). With `FUSED` (waves,
/// `cols` given, its power basis) the element's wave velocity and acceleration are
/// interpolated here from `cols`, the velocity added to the current (`k`'s with
/// `UNI`, else `u`'s), and `aw` is not read.
/// The lanes past the last element write padded elements past it, the end ghost
/// included (reset by the caller).
///
/// # Safety
/// As [`elements`]; with `FUSED`, as [`elements_fused`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn element_chunks<
    const WAVES: bool,
    const UNI: bool,
    const FUSED: bool,
    const L: usize,
    St: Stride,
>(
    c: &ChainConsts,
    p: &[Vec<f64>; 6],
    u: &[Vec<f64>; 3],
    aw: &[Vec<f64>; 3],
    wv: &ColumnsView<'_, St>,
    k: &UniformLine<L>,
    cols: Option<&ChainCols>,
) {
    let ne = c.l0.len();
    let nc = chunks_for::<L>(ne);
    // SAFETY (every use): the caller's columns hold `padded_len(c.n) >= nc * L + 1`
    // entries.
    macro_rules! at {
        ($s:expr) => {
            unsafe { lanes::<L>($s, nc) }
        };
    }
    macro_rules! next {
        ($s:expr) => {
            unsafe { lanes_next::<L>($s, nc) }
        };
    }
    // The block's columns from padded element 1 on: one base register, constant
    // displacements with a fixed stride. SAFETY: as above; written only here.
    macro_rules! out {
        ($q:expr) => {
            unsafe { wv.lanes_mut::<L>($q, 1, nc) }
        };
    }
    let (xa, ya, za, vxa, vya, vza) = (
        at!(&p[0]),
        at!(&p[1]),
        at!(&p[2]),
        at!(&p[3]),
        at!(&p[4]),
        at!(&p[5]),
    );
    let (xb, yb, zb, vxb, vyb, vzb) = (
        next!(&p[0]),
        next!(&p[1]),
        next!(&p[2]),
        next!(&p[3]),
        next!(&p[4]),
        next!(&p[5]),
    );
    let (ux, uy, uz) = (at!(&u[0]), at!(&u[1]), at!(&u[2]));
    let (awx, awy, awz) = (at!(&aw[0]), at!(&aw[1]), at!(&aw[2]));
    let (il0, ea, eac, comp) = (at!(&c.il0), at!(&c.ea), at!(&c.eac), at!(&c.comp));
    let (dn, dt, hw, hb) = (
        at!(&c.drag_n),
        at!(&c.drag_t),
        at!(&c.half_wz),
        at!(&c.half_bz),
    );
    let (hfk, hfkt) = (at!(&c.half_fk), at!(&c.half_fkt));
    // With `FUSED`: `mc[q][side]`, the cache's columns of wave velocity (`q` 0-2) and
    // acceleration (3-5), and the weights of the time. Written out, not with
    // `std::array::from_fn`: its closures, not inlined into the AVX2 caller, left the
    // 24 slices in a stack array the loop reloaded (20 instructions a node-step more).
    let (mc, wt) = match cols {
        Some(w) if FUSED => {
            // The 24 columns from one base by multiples of the stride (a constant for
            // short chains: `St`, the per-stage block's, which the cache shares).
            let st = wv.stride();
            assert_eq!(w.stride, st.get(), "the cache's columns at another stride");
            let m = w.mid.as_ptr();
            macro_rules! col {
                ($side:expr, $q:expr) => {
                    // SAFETY: column `6 side + q` of the 24, each `stride >= padded_len`
                    // entries (the caller's `nc` chunks fit, as for the block's).
                    unsafe {
                        std::slice::from_raw_parts(
                            m.add((6 * $side + $q) * st.get()).cast::<[f64; L]>(),
                            nc,
                        )
                    }
                };
            }
            macro_rules! sides {
                ($q:expr) => {
                    [col!(0, $q), col!(1, $q), col!(2, $q), col!(3, $q)]
                };
            }
            (
                [
                    sides!(0),
                    sides!(1),
                    sides!(2),
                    sides!(3),
                    sides!(4),
                    sides!(5),
                ],
                w.w,
            )
        }
        _ => ([[&[][..]; 4]; 6], [0.0; 4]),
    };
    let (tx, ty, tz) = (out!(col::TX), out!(col::TX + 1), out!(col::TX + 2));
    let (fx, fy, fz) = (out!(col::FX), out!(col::FX + 1), out!(col::FX + 2));
    let ten = out!(col::TEN);
    // The literals hidden from the optimiser ([`Literals::hidden`]).
    let lits = Literals::hidden();
    // Every chunk's lengths and their inverses first, in the tangents' columns (written
    // again below): a chunk's square root, division and second square root are one
    // chain of dependent operations on the divider, which the out-of-order window did
    // not overlap across a short line's few chunks (3 to 8); a loop of independent
    // chunks keeps the divider busy instead. The same operations, so the same bits.
    for j in 0..nc {
        keep_chunks();
        let (xa, ya, za) = (xa[j], ya[j], za[j]);
        let (xb, yb, zb) = (xb[j], yb[j], zb[j]);
        let (mut ls, mut ils) = ([0.0; L], [0.0; L]);
        for l in 0..L {
            (ls[l], ils[l]) = element_length(
                [xa[l], ya[l], za[l], 0.0, 0.0, 0.0, 0.0],
                [xb[l], yb[l], zb[l], 0.0, 0.0, 0.0, 0.0],
                lits,
            );
        }
        (tx[j], ty[j]) = (ls, ils);
    }
    for j in 0..nc {
        keep_chunks();
        let (ls, ils) = (tx[j], ty[j]);
        // Every input into locals first, then every output: no overlap to check.
        let (xa, ya, za, vxa, vya, vza) = (xa[j], ya[j], za[j], vxa[j], vya[j], vza[j]);
        let (xb, yb, zb, vxb, vyb, vzb) = (xb[j], yb[j], zb[j], vxb[j], vyb[j], vzb[j]);
        let il0 = il0[j];
        let (awx, awy, awz) = if FUSED {
            (
                cubic_lanes(&mc[3], j, wt),
                cubic_lanes(&mc[4], j, wt),
                cubic_lanes(&mc[5], j, wt),
            )
        } else {
            (awx[j], awy[j], awz[j])
        };
        let ((ux, uy, uz), (ea, eac, comp, dn, dt)) = if UNI {
            let u = &k.u;
            ((u[0], u[1], u[2]), (k.ea, k.eac, k.comp, k.dn, k.dt))
        } else {
            (
                (ux[j], uy[j], uz[j]),
                (ea[j], eac[j], comp[j], dn[j], dt[j]),
            )
        };
        // The current plus the waves' velocity: `b + h` as `ChainCols::fill` writes it
        // over a uniform current, `u + h` as it adds to the currents in `u`.
        let (ux, uy, uz) = if FUSED {
            (
                plus_lanes(ux, cubic_lanes(&mc[0], j, wt)),
                plus_lanes(uy, cubic_lanes(&mc[1], j, wt)),
                plus_lanes(uz, cubic_lanes(&mc[2], j, wt)),
            )
        } else {
            (ux, uy, uz)
        };
        let (hw, hb, hfk, hfkt) = (hw[j], hb[j], hfk[j], hfkt[j]);
        let mut o = [[0.0; L]; 7];
        for l in 0..L {
            let e = element_lane_len::<WAVES, true>(
                [xa[l], ya[l], za[l], vxa[l], vya[l], vza[l], 0.0],
                [xb[l], yb[l], zb[l], vxb[l], vyb[l], vzb[l], 0.0],
                [ux[l], uy[l], uz[l]],
                [awx[l], awy[l], awz[l]],
                ElemConsts {
                    il0: il0[l],
                    ea: ea[l],
                    eac: eac[l],
                    comp: comp[l],
                    dn: dn[l],
                    dt: dt[l],
                    hw: hw[l],
                    hb: hb[l],
                    hfk: hfk[l],
                    hfkt: hfkt[l],
                    hmd: 0.0,
                    hat: 0.0,
                    ha: 0.0,
                    diam: 0.0,
                },
                lits,
                ls[l],
                ils[l],
            );
            [o[0][l], o[1][l], o[2][l]] = e.t;
            o[3][l] = e.ten;
            [o[4][l], o[5][l], o[6][l]] = e.f;
        }
        [tx[j], ty[j], tz[j], ten[j], fx[j], fy[j], fz[j]] = o;
    }
    // The lanes past the last element wrote the end ghost (padded element `ne + 1`)
    // unless the elements fill their chunks: zero again.
    let (j, l) = (ne / L, ne % L);
    if j < nc {
        for q in [tx, ty, tz, ten, fx, fy, fz] {
            q[j][l] = 0.0;
        }
    }
}

/// The cache's cubic of one column (`m`: its four sides as chunks of lanes) in chunk
/// `j`, with the power basis's weights `w` (`hermite_at`'s order). A function, not a
/// closure: closures are not inlined into the AVX2 caller.
#[inline(always)]
fn cubic_lanes<const L: usize>(m: &[&[[f64; L]]; 4], j: usize, w: [f64; 4]) -> [f64; L] {
    let (v0, d0, v1, d1) = (m[0][j], m[1][j], m[2][j], m[3][j]);
    let mut h = [0.0; L];
    for l in 0..L {
        h[l] = hermite_at::<true>(w, v0[l], d0[l], v1[l], d1[l]);
    }
    h
}

/// `b + h` lane by lane.
#[inline(always)]
fn plus_lanes<const L: usize>(mut b: [f64; L], h: [f64; L]) -> [f64; L] {
    for l in 0..L {
        b[l] += h[l];
    }
    b
}

/// Fills the per-element current (midpoint height) when the block's is not uniform.
#[inline(always)]
pub(super) fn currents(
    c: &ChainConsts,
    currents: &[Current],
    p: &[Vec<f64>; 6],
    u: &mut [Vec<f64>; 3],
) {
    let ne = c.l0.len();
    if let Some(un) = c.uniform {
        for (q, uq) in u.iter_mut().enumerate() {
            uq[..ne].fill(un[q]);
        }
        return;
    }
    for k in 0..ne {
        let v = currents[c.current[k] as usize]
            .at::<f64>(0.5 * (p[2][k] + p[2][k + 1]))
            .to_f64();
        for q in 0..3 {
            u[q][k] = v[q];
        }
    }
}

/// Waves: adds the mean of each element's two nodes' wave velocities to its water
/// velocity `u`, writes the mean of their wave accelerations to `aw`, and each node's
/// surface elevation to `eta`, from the per-node water values `w`.
#[inline(always)]
pub(super) fn add_waves(
    ne: usize,
    w: &[f64],
    u: &mut [Vec<f64>; 3],
    aw: &mut [Vec<f64>; 3],
    eta: &mut [f64],
) {
    for (i, e) in eta[..ne + 1].iter_mut().enumerate() {
        *e = node_water(w, i).0;
    }
    for k in 0..ne {
        let (_, ua, aa) = node_water(w, k);
        let (_, ub, ab) = node_water(w, k + 1);
        for q in 0..3 {
            u[q][k] += 0.5 * (ua[q] + ub[q]);
            aw[q][k] = 0.5 * (aa[q] + ab[q]);
        }
    }
}
