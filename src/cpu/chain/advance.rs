//! The advance driver of the chain fast path: the structure-of-arrays state and
//! scratch ([`ChainScratch`]), the run-time AVX2 dispatch ([`advance_chain`]: the
//! whole run of steps, kernels inlined, is compiled once for AVX2 and once for the
//! baseline target), and the time schemes (symplectic Euler, RK2, RK4) over the
//! element and node passes, with the divergence check after each step.

use super::consts::ChainConsts;
use super::elements::{add_waves, currents, elements, elements_fused, UniformLine};
use super::lanes::{
    chunks_for, col, keep_chunks, lanes_mut, padded_len, Columns, ColumnsView, Dyn, Fixed, Stride,
    SHORT_STRIDE,
};
use super::nodes::{nodes, point_surface, Masses};
use super::winch::{ale_constants, ale_tension, AleScratch};
use crate::ale::AleElem;
use crate::cpu::water::{BlockWaves, Water};
use crate::math::{Sym3, V3};
use crate::model::{Layout, RouteState};
use crate::options::{Scheme, SolverOptions};
use crate::step::{diverged, StepFailure};

/// What a call adds for a block with nodes held on free bodies (`cpu::free`).
#[derive(Default)]
pub(crate) struct Held<'a> {
    /// The held nodes (block-local) and their targets, their bodies' points now: they
    /// take the targets' accelerations in place of their routes'.
    pub targets: &'a [(usize, RouteState)],
    /// Where each held node's force and mass block at the step's start go (packed
    /// node, force, mass block), for its body to lump in; the call steps one step.
    pub lumps: Option<&'a mut Vec<(usize, V3<f64>, Sym3<f64>)>>,
    /// The scratch holds this block from the previous call (its padded constants and
    /// per-run columns): only the state is read in again. A block stepped one step at a
    /// time with its bodies keeps its scratch (`ChainScratch` per block of a unit).
    pub prepared: bool,
}

/// Structure-of-arrays state and scratch of one chain, reused across blocks.
#[derive(Default)]
pub(crate) struct ChainScratch {
    x: [Vec<f64>; 6],
    // Stage state and accumulators of the Runge-Kutta schemes.
    xs: [Vec<f64>; 6],
    x0: [Vec<f64>; 6],
    sum: [Vec<f64>; 6],
    w: Work,
    /// The per-stage results the node loop reads and the accelerations it writes, in
    /// one block (module [`super::lanes`]'s `col`).
    wb: Columns,
    /// The block's constants with their columns padded to whole chunks of lanes,
    /// which a winch cable's variable elements change every stage; and what the run
    /// keeps about those.
    wc: ChainConsts,
    ale: AleScratch,
    /// Whether the block has a uniform line (`UniformLine::fits`), found when the
    /// scratch was prepared for it.
    uniform_line: bool,
}

/// What one evaluation writes.
#[derive(Default)]
struct Work {
    // Per-element water velocity (current, plus waves) and wave acceleration.
    u: [Vec<f64>; 3],
    aw: [Vec<f64>; 3],
    // Surface elevation over each node, m (zero in still water).
    eta: Vec<f64>,
    // The padded elements' half masses along their tangents and what their normal
    // planes have more, with the added masses times their wetted fractions.
    hmw: Vec<f64>,
    haw: Vec<f64>,
}

fn resize(v: &mut [Vec<f64>], n: usize) {
    for x in v {
        x.clear();
        x.resize(n, 0.0);
    }
}

/// The symplectic Euler update `v += a dt`, then `x += v dt`, of the first `nc`
/// chunks of nodes of the padded SoA state `x` (module [`super::lanes`]; the padding
/// nodes stay at rest at zero), the number of nodes whose new state is non-finite
/// or over the limits ([`count_bad`]'s test), and whether every new `z` is at or
/// below zero (the element loop's test of a flat surface at zero, `0 - z >= 0`, which
/// it then need not make: [`elements`]), in one loop.
///
/// # Safety
/// Every column of `x` and `wv`'s accelerations has at least `nc * L` entries.
#[inline(always)]
unsafe fn symplectic_update<const L: usize, St: Stride>(
    x: &mut [Vec<f64>; 6],
    wv: &ColumnsView<'_, St>,
    nc: usize,
    dt: f64,
    vmax: f64,
    rmax: f64,
) -> (usize, bool) {
    // SAFETY (every use): the caller's columns.
    macro_rules! out {
        ($s:expr) => {
            unsafe { lanes_mut::<L>($s, 0, nc) }
        };
    }
    let [px, py, pz, vx, vy, vz] = x;
    let (px, py, pz) = (out!(px), out!(py), out!(pz));
    let (vx, vy, vz) = (out!(vx), out!(vy), out!(vz));
    // SAFETY: the accelerations, only read here.
    let (ax, ay, az) = unsafe {
        (
            wv.lanes::<L>(col::AX, 0, nc),
            wv.lanes::<L>(col::AX + 1, 0, nc),
            wv.lanes::<L>(col::AX + 2, 0, nc),
        )
    };
    let mut bad = [0usize; L];
    // The highest new `z` of each lane: every node is at or below zero exactly when
    // each is. A select written as x86's `max` (one instruction a chunk; an AND of
    // `z <= 0` flags took five with AVX2). A NaN may be passed over here, but it also
    // fails `ok` below, and a step with a bad node ends the run.
    let mut zmax = [f64::NEG_INFINITY; L];
    for i in 0..nc {
        keep_chunks();
        // Every input into locals first, then every output: no overlap to check.
        let (mut p, mut v) = ([px[i], py[i], pz[i]], [vx[i], vy[i], vz[i]]);
        let acc = [ax[i], ay[i], az[i]];
        for l in 0..L {
            for q in 0..3 {
                v[q][l] += acc[q][l] * dt;
                p[q][l] += v[q][l] * dt;
            }
            // `&`, not `&&`: no short circuit, so the loop vectorises. NaN fails every `<`.
            let ok = (p[0][l].abs() < rmax)
                & (p[1][l].abs() < rmax)
                & (p[2][l].abs() < rmax)
                & (v[0][l].abs() < vmax)
                & (v[1][l].abs() < vmax)
                & (v[2][l].abs() < vmax);
            bad[l] += (!ok) as usize;
            zmax[l] = if p[2][l] > zmax[l] { p[2][l] } else { zmax[l] };
        }
        [px[i], py[i], pz[i]] = p;
        [vx[i], vy[i], vz[i]] = v;
    }
    // `0 - z >= 0` exactly when `z <= 0`.
    (bad.iter().sum(), zmax.iter().all(|&z| z <= 0.0))
}

/// `x += v h` elementwise.
#[inline(always)]
fn axpy(x: &mut [f64], v: &[f64], h: f64) {
    let v = &v[..x.len()];
    for i in 0..x.len() {
        x[i] += v[i] * h;
    }
}

/// `out = x + v h` elementwise.
#[inline(always)]
fn xpvh(out: &mut [f64], x: &[f64], v: &[f64], h: f64) {
    let (x, v) = (&x[..out.len()], &v[..out.len()]);
    for i in 0..out.len() {
        out[i] = x[i] + v[i] * h;
    }
}

/// Counts nodes whose new state is non-finite or over the limits.
#[inline(always)]
fn count_bad(p: &[Vec<f64>; 6], n: usize, vmax: f64, rmax: f64) -> usize {
    let mut bad = 0usize;
    let p: [&[f64]; 6] = [
        &p[0][..n],
        &p[1][..n],
        &p[2][..n],
        &p[3][..n],
        &p[4][..n],
        &p[5][..n],
    ];
    #[allow(clippy::needless_range_loop)] // six arrays indexed together
    for i in 0..n {
        // `&`, not `&&`: no short circuit, so the loop vectorises. NaN fails every `<`.
        let ok = (p[0][i].abs() < rmax)
            & (p[1][i].abs() < rmax)
            & (p[2][i].abs() < rmax)
            & (p[3][i].abs() < vmax)
            & (p[4][i].abs() < vmax)
            & (p[5][i].abs() < vmax);
        bad += (!ok) as usize;
    }
    bad
}

/// Advances a chain block; `r`, `v` are its AoS state (block-local).
#[allow(clippy::too_many_arguments)]
pub(crate) fn advance_chain(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
    held: Held<'_>,
) -> Result<(), StepFailure> {
    #[cfg(target_arch = "x86_64")]
    {
        if crate::lanes::avx512_wanted() {
            // SAFETY: the CPU has AVX-512 (F, DQ, VL), checked just above.
            return unsafe {
                advance_chain_avx512(
                    c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps, held,
                )
            };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            return unsafe {
                advance_chain_avx2(
                    c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps, held,
                )
            };
        }
    }
    advance_chain_body::<4>(
        c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps, held,
    )
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn advance_chain_avx2(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
    held: Held<'_>,
) -> Result<(), StepFailure> {
    advance_chain_body::<4>(
        c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps, held,
    )
}

/// The same, 8 lanes to a chunk (one AVX-512 register).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512dq,avx512vl")]
#[allow(clippy::too_many_arguments)]
unsafe fn advance_chain_avx512(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
    held: Held<'_>,
) -> Result<(), StepFailure> {
    advance_chain_body::<8>(
        c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps, held,
    )
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn advance_chain_body<const L: usize>(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
    held: Held<'_>,
) -> Result<(), StepFailure> {
    // A short chain's block at the fixed stride (its columns at constant offsets from
    // one base register), a long one's at its padded length.
    let len = padded_len(c.n);
    // Still water and waves in separate instantiations (`WAVES`): the whole run of
    // steps is one function, and the waves' code in it (the element loop that
    // interpolates the waves in its lanes, the cache's columns) moved the register
    // allocation of the still-water loops (BENCHMARKS.md, "hstraight5").
    macro_rules! scheme {
        ($waves:literal, $friction:literal, $st:expr) => {
            advance_chain_scheme::<$waves, $friction, L, _>(
                c, lay, opts, sc, ale, r, v, n0, waves, wbuf, step0, dt, nsteps, $st, held,
            )
        };
    }
    macro_rules! stride {
        ($waves:literal) => {
            match (c.friction, len <= SHORT_STRIDE) {
                (true, true) => scheme!($waves, true, Fixed::<SHORT_STRIDE>),
                (true, false) => scheme!($waves, true, Dyn(len)),
                (false, true) => scheme!($waves, false, Fixed::<SHORT_STRIDE>),
                (false, false) => scheme!($waves, false, Dyn(len)),
            }
        };
    }
    if waves.is_some() {
        stride!(true)
    } else {
        stride!(false)
    }
}

/// `WAVES`: whether `waves` is `Some` (the caller's dispatch), so that the still-water
/// instantiation has none of the waves' code.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn advance_chain_scheme<const WAVES: bool, const FRICTION: bool, const L: usize, St: Stride>(
    c: &ChainConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut ChainScratch,
    ale: &[AleElem],
    r: &mut [crate::math::V3<f64>],
    v: &mut [crate::math::V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
    st: St,
    held: Held<'_>,
) -> Result<(), StepFailure> {
    let n = c.n;
    let nc = chunks_for::<L>(n);
    debug_assert_eq!(WAVES, waves.is_some());
    let mut waves = if WAVES { waves } else { None };
    if !WAVES {
        wbuf.clear();
    }
    // Every column padded to whole chunks of lanes (module `lanes`), with zeros.
    let len = padded_len(n);
    let Held {
        targets: held,
        mut lumps,
        prepared,
    } = held;
    debug_assert!(!prepared || (sc.wc.n == n && sc.x[0].len() == len));
    debug_assert!(lumps.is_none() || nsteps == 1);
    // The lumps this call adds name block-local nodes until the end.
    let lump0 = lumps.as_ref().map_or(0, |l| l.len());
    if prepared {
        // The scratch is this block's from the last call: the state only.
        for i in 0..n {
            sc.x[0][i] = r[i].x;
            sc.x[1][i] = r[i].y;
            sc.x[2][i] = r[i].z;
            sc.x[3][i] = v[i].x;
            sc.x[4][i] = v[i].y;
            sc.x[5][i] = v[i].z;
        }
    } else {
        prepare_scratch::<WAVES, St>(c, lay, opts, sc, ale, r, v, len, st);
    }
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn prepare_scratch<const WAVES: bool, St: Stride>(
        c: &ChainConsts,
        lay: &Layout,
        opts: &SolverOptions,
        sc: &mut ChainScratch,
        ale: &[AleElem],
        r: &[crate::math::V3<f64>],
        v: &[crate::math::V3<f64>],
        len: usize,
        st: St,
    ) {
        let n = c.n;
        sc.wc.copy_padded_from(c, len);
        resize(&mut sc.x, len);
        resize(&mut sc.w.u, len);
        resize(&mut sc.w.aw, len);
        for v in [&mut sc.w.eta, &mut sc.w.hmw, &mut sc.w.haw] {
            v.clear();
            v.resize(len, 0.0);
        }
        // `st` is `len` or more (the caller's choice).
        // A chain with bending has the bending pass's columns after the rest.
        let ncols = if c.bend.is_some() {
            super::bending::COUNT
        } else {
            col::COUNT
        };
        sc.wb.reset(ncols, st.get());
        {
            let wv = sc.wb.view(st);
            // SAFETY: two distinct columns of the block, reached only here.
            let (pm, pwz) = unsafe { (wv.col_mut(col::PM), wv.col_mut(col::PWZ)) };
            pm[..len].copy_from_slice(&sc.wc.pm[..len]);
            pwz[..len].copy_from_slice(&sc.wc.pwz[..len]);
        }
        if opts.scheme != Scheme::Symplectic {
            resize(&mut sc.xs, len);
            resize(&mut sc.x0, len);
            resize(&mut sc.sum, len);
        }
        for i in 0..n {
            sc.x[0][i] = r[i].x;
            sc.x[1][i] = r[i].y;
            sc.x[2][i] = r[i].z;
            sc.x[3][i] = v[i].x;
            sc.x[4][i] = v[i].y;
            sc.x[5][i] = v[i].z;
        }
        if c.uniform.is_some() && !WAVES {
            currents(c, &lay.currents, &sc.x, &mut sc.w.u);
        }
        // Always: the scratch may hold the previous block's variable elements.
        sc.ale.prepare(c, lay, ale);
    }
    let ChainScratch {
        x,
        xs,
        x0,
        sum,
        w: wk,
        wc,
        ale: asc,
        wb,
        uniform_line,
    } = sc;
    // One view of the block for the run: its columns from one base pointer (constant
    // offsets with a fixed stride).
    let wv = wb.view(st);
    // A function, not a closure: closures are not inlined into the AVX2 caller and
    // would be compiled for the baseline target.
    //
    // Safety: every column of `wc`, `state`, `sc` and `wv` has at least
    // `padded_len(wc.n)` entries, and no slice of `wv`'s columns lives during the call.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    unsafe fn eval<const WAVES: bool, const FRICTION: bool, const L: usize, St: Stride>(
        wc: &mut ChainConsts,
        asc: &mut AleScratch,
        lay: &Layout,
        opts: &SolverOptions,
        ale: &[AleElem],
        state: &[Vec<f64>; 6],
        time: f64,
        under: Option<bool>,
        uni: Option<&UniformLine<L>>,
        wuni: Option<&UniformLine<L>>,
        waves: &mut Option<&mut BlockWaves>,
        wbuf: &mut Water,
        sc: &mut Work,
        wv: &ColumnsView<'_, St>,
        held: &[(usize, RouteState)],
        lumps: Option<&mut Vec<(usize, V3<f64>, Sym3<f64>)>>,
    ) {
        let Work {
            u,
            aw,
            eta,
            hmw,
            haw,
        } = sc;
        // Winch cables: the variable elements' constants at this time.
        if !ale.is_empty() {
            // SAFETY: `asc` was prepared for this block, and `wc`'s columns are padded.
            unsafe { ale_constants(asc, time, wc) };
        }
        let c = &*wc;
        // A uniform current in still water was filled once for the run; in waves from
        // the cache, the element loop adds the waves' velocity to it (`elements_fused`)
        // or `ChainCols::fill` writes it with them.
        let cache_waves = WAVES && waves.as_deref().is_some_and(|wb| !wb.exact());
        if c.uniform.is_none() || (WAVES && !cache_waves) {
            currents(c, &lay.currents, state, u);
        }
        let wb = if WAVES { waves.as_deref_mut() } else { None };
        let wholly_wet = if let Some(wb) = wb {
            let st = |i: usize| {
                (
                    [state[0][i], state[1][i], state[2][i]],
                    [state[3][i], state[4][i], state[5][i]],
                )
            };
            if wb.exact() {
                wb.fill(time, c.n, st, wbuf);
                add_waves(c.l0.len(), wbuf, u, aw, eta);
                // SAFETY: the caller's columns.
                unsafe { elements::<true, L, St>(c, state, u, aw, eta, wv, hmw, haw, None, None) }
            } else {
                // The per-node values are needed only by the point masses' loads
                // (`nodes`); the elements read the cache's columns.
                if !c.point_drag.is_empty() || !c.point_volume.is_empty() {
                    wb.fill(time, c.n, st, wbuf);
                }
                let cols = wb.chain_columns(time, c.n, st);
                // Several bands (the power basis): the elevations and the surface test
                // in one pass, then, every node under, the element loop interpolating
                // the waves in its lanes. `u` holds the currents unless `wuni` has them.
                if cols.unit && wuni.is_none() && c.uniform.is_some() {
                    currents(c, &lay.currents, state, u);
                }
                // SAFETY: the caller's columns; the cache's are padded.
                if cols.unit
                    && unsafe { elements_fused::<L, St>(c, state, &cols, u, eta, wv, wuni) }
                {
                    true
                } else {
                    cols.fill(c.n, eta, !cols.unit, u, c.uniform, aw);
                    let under = cols.unit.then_some(false);
                    // SAFETY: the caller's columns.
                    unsafe {
                        elements::<true, L, St>(c, state, u, aw, eta, wv, hmw, haw, under, None)
                    }
                }
            }
        } else {
            // SAFETY: the caller's columns.
            unsafe { elements::<false, L, St>(c, state, u, aw, eta, wv, hmw, haw, under, uni) }
        };
        // SAFETY: as `ale_constants`; the tensions' column, reached only here.
        unsafe { ale_tension(asc, state, wv.col_mut(col::TEN)) };
        // SAFETY: two distinct columns of the block, reached only here; the points' nodes
        // are nodes of the block.
        unsafe { point_surface(c, state, eta, wv.col_mut(col::PM), wv.col_mut(col::PWZ)) };
        let m = Masses {
            eta,
            w: wbuf,
            // Every element wholly wet: the block's half masses, bit for bit.
            hm: if wholly_wet { &c.hm } else { hmw },
            ha: if wholly_wet { &c.ha } else { haw },
            kl: &c.kl,
            cl: &c.cl,
            mukl: &c.mukl,
        };
        unsafe { nodes::<FRICTION, L, St>(c, lay, opts, time, state, &m, asc, wv, held, lumps) };
    }
    let mut result = Ok(());
    let mut bad = 0;
    // In still water, whether every node is at or below the surface (z = 0), as the
    // last symplectic update found; `None`: the element loop finds out.
    let mut under = None;
    let still = !WAVES;
    // In still water, a chain of one line type under one uniform current.
    if !prepared {
        *uniform_line = UniformLine::<L>::fits(c);
    }
    let fits = *uniform_line;
    let uni = (still && fits).then(|| UniformLine::<L>::make(c));
    // Behind a reference the optimiser cannot see through (`black_box`), so that the
    // element loop reads its lanes as memory operands: a local it could see into was
    // split into values that were copied from one stack slot to another every step.
    let uni = std::hint::black_box(uni.as_ref());
    // In waves, the same for the element loop that interpolates the waves in its lanes
    // (`elements_fused`, which adds them to this current).
    let wuni = (!still && fits).then(|| UniformLine::<L>::make(c));
    // As `uni`.
    let wuni = std::hint::black_box(wuni.as_ref());
    // SAFETY: the stages' columns (`x`, `xs`, `wc`, `wk`, `a`) were made
    // `padded_len(n)` long above, and nothing in the loop resizes them.
    unsafe {
        for k in 0..nsteps {
            // Through `i64` (the same value below 2^63 steps): one conversion
            // instruction, where `u64` to `f64` takes five without AVX-512.
            let time = (step0 + k) as i64 as f64 * dt;
            match opts.scheme {
                Scheme::Symplectic => {
                    eval::<WAVES, FRICTION, L, St>(
                        wc,
                        asc,
                        lay,
                        opts,
                        ale,
                        x,
                        time,
                        under,
                        uni,
                        wuni,
                        &mut waves,
                        wbuf,
                        wk,
                        &wv,
                        held,
                        lumps.as_deref_mut(),
                    );
                    let (b, u) = symplectic_update::<L, St>(
                        x,
                        &wv,
                        nc,
                        dt,
                        opts.max_speed,
                        opts.max_distance,
                    );
                    bad = b;
                    under = still.then_some(u);
                }
                Scheme::Rk2 => {
                    let h = 0.5 * dt;
                    eval::<WAVES, FRICTION, L, St>(
                        wc,
                        asc,
                        lay,
                        opts,
                        ale,
                        x,
                        time,
                        None,
                        uni,
                        wuni,
                        &mut waves,
                        wbuf,
                        wk,
                        &wv,
                        held,
                        lumps.as_deref_mut(),
                    );
                    for q in 0..3 {
                        xpvh(&mut xs[q][..n], &x[q], &x[3 + q], h);
                        xpvh(&mut xs[3 + q][..n], &x[3 + q], wv.col(col::AX + q), h);
                    }
                    eval::<WAVES, FRICTION, L, St>(
                        wc,
                        asc,
                        lay,
                        opts,
                        ale,
                        xs,
                        time + h,
                        None,
                        uni,
                        wuni,
                        &mut waves,
                        wbuf,
                        wk,
                        &wv,
                        held,
                        None,
                    );
                    let (pos, vel) = x.split_at_mut(3);
                    for q in 0..3 {
                        axpy(&mut pos[q][..n], &xs[3 + q], dt);
                        axpy(&mut vel[q][..n], wv.col(col::AX + q), dt);
                    }
                }
                Scheme::Rk4 => {
                    let h = 0.5 * dt;
                    for q in 0..6 {
                        x0[q].copy_from_slice(&x[q]);
                        xs[q].copy_from_slice(&x[q]);
                        sum[q].fill(0.0);
                    }
                    for (stage, (tau, w, next)) in
                        [(0.0, 1.0, h), (h, 2.0, h), (h, 2.0, dt), (dt, 1.0, 0.0)]
                            .into_iter()
                            .enumerate()
                    {
                        eval::<WAVES, FRICTION, L, St>(
                            wc,
                            asc,
                            lay,
                            opts,
                            ale,
                            xs,
                            time + tau,
                            None,
                            uni,
                            wuni,
                            &mut waves,
                            wbuf,
                            wk,
                            &wv,
                            held,
                            if stage == 0 {
                                lumps.as_deref_mut()
                            } else {
                                None
                            },
                        );
                        let (spos, svel) = xs.split_at_mut(3);
                        for q in 0..3 {
                            let aq = wv.col(col::AX + q);
                            axpy(&mut sum[q][..n], &svel[q], w);
                            axpy(&mut sum[3 + q][..n], aq, w);
                            if stage < 3 {
                                xpvh(&mut spos[q][..n], &x0[q], &svel[q], next);
                                xpvh(&mut svel[q][..n], &x0[3 + q], aq, next);
                            }
                        }
                    }
                    for q in 0..6 {
                        xpvh(&mut x[q][..n], &x0[q], &sum[q], dt / 6.0);
                    }
                }
            }
            if opts.scheme != Scheme::Symplectic {
                bad = count_bad(x, n, opts.max_speed, opts.max_distance);
            }
            if bad > 0 {
                let i = (0..n)
                    .find(|&i| {
                        !(x[0][i].abs() < opts.max_distance
                            && x[1][i].abs() < opts.max_distance
                            && x[2][i].abs() < opts.max_distance
                            && x[3][i].abs() < opts.max_speed
                            && x[4][i].abs() < opts.max_speed
                            && x[5][i].abs() < opts.max_speed)
                    })
                    .unwrap_or(0);
                result = Err((i, time + dt));
                break;
            }
        }
    }
    for i in 0..n {
        r[i] = crate::math::V3::new(x[0][i], x[1][i], x[2][i]);
        v[i] = crate::math::V3::new(x[3][i], x[4][i], x[5][i]);
    }
    if let Some(l) = lumps {
        for e in &mut l[lump0..] {
            e.0 += n0;
        }
    }
    result.map_err(|(i, time)| diverged(opts, r[i], v[i], n0 + i, time))
}
