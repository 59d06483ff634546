//! The CPU's arrangement of the component sums of [`super::kinematics`]: the packed
//! components as columns, and the sums over them in two passes that vectorise (four
//! components at a time with AVX2 and FMA, eight with AVX-512), for the values alone
//! ([`wave_kinematics_columns`], the arrangement of `wave_kinematics_tau`) and for the
//! values with their rates along a moving path ([`wave_kinematics_rates_columns`], of
//! `wave_kinematics_rates_tau`). The results agree with the one-component-at-a-time
//! twins to round-off.

use super::cut::decay_prefix;
use super::kinematics::{wave_eval_depth, wave_eval_depth_rate, Kinematics, PackedComponent};
use super::{poly, Stretching};

/// The packed components as columns, one array per field (the fields of
/// [`PackedComponent`] that the sum reads), so that the CPU's loops over components
/// read consecutive memory and vectorise.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ComponentColumns {
    kx: Vec<f64>,
    ky: Vec<f64>,
    k: Vec<f64>,
    omega: Vec<f64>,
    phase_ref: Vec<f64>,
    amp: Vec<f64>,
    amp_u: Vec<f64>,
    amp_a: Vec<f64>,
    cos_b: Vec<f64>,
    sin_b: Vec<f64>,
    cut0: Vec<f64>,
    cut1: Vec<f64>,
    cut2: Vec<f64>,
    /// Whether `k` is ascending (a [`super::kinematics::WaveField`]'s components
    /// are): then the components whose seabed term is below round-off at a given
    /// height are a suffix, which the decay pass finds by bisection.
    k_ascending: bool,
}

impl ComponentColumns {
    /// The columns of `comps`.
    pub fn new(comps: &[PackedComponent]) -> Self {
        let col = |f: fn(&PackedComponent) -> f64| comps.iter().map(f).collect::<Vec<_>>();
        Self {
            kx: col(|c| c.kx),
            ky: col(|c| c.ky),
            k: col(|c| c.k),
            omega: col(|c| c.omega),
            phase_ref: col(|c| c.phase_ref),
            amp: col(|c| c.amp),
            amp_u: col(|c| c.amp_u),
            amp_a: col(|c| c.amp_a),
            cos_b: col(|c| c.cos_b),
            sin_b: col(|c| c.sin_b),
            cut0: col(|c| c.cut0),
            cut1: col(|c| c.cut1),
            cut2: col(|c| c.cut2),
            k_ascending: comps.windows(2).all(|w| w[0].k <= w[1].k),
        }
    }

    /// The same columns, taken as not sorted by `k` (the decay pass then computes the
    /// seabed term of every component and selects it): for the test that the split
    /// by [`Self::new`]'s order gives the same bits.
    #[doc(hidden)]
    pub fn without_order(mut self) -> Self {
        self.k_ascending = false;
        self
    }

    /// The number of components.
    pub fn len(&self) -> usize {
        self.k.len()
    }

    /// True when there are no components.
    pub fn is_empty(&self) -> bool {
        self.k.is_empty()
    }
}

/// Per-component working columns of [`wave_kinematics_columns`] and
/// [`wave_kinematics_rates_columns`] (sines, cosines, the phase rates and the terms of
/// the sums), kept between calls so that a loop over nodes allocates them once.
/// Cloning gives an empty one (the columns are overwritten before being read, so
/// their contents are never state: a copy of the solver for a checkpoint, at each
/// output time, need not copy 17 columns per cache).
#[derive(Debug, Default)]
pub struct KinematicsScratch {
    sin: Vec<f64>,
    cos: Vec<f64>,
    theta_rate: Vec<f64>,
    /// The depth decay `(ch, sh)` of each component (both 0 for a component that
    /// contributes nothing).
    ch: Vec<f64>,
    sh: Vec<f64>,
    terms: [Vec<f64>; 12],
}

impl Clone for KinematicsScratch {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl KinematicsScratch {
    /// Columns of length `n` (their contents are overwritten before being read).
    fn fit(&mut self, n: usize) {
        for v in [
            &mut self.sin,
            &mut self.cos,
            &mut self.theta_rate,
            &mut self.ch,
            &mut self.sh,
        ]
        .into_iter()
        .chain(self.terms.iter_mut())
        {
            v.resize(n, 0.0);
        }
    }
}

/// The inputs of one evaluation: where, when, how fast (the velocity is read only for
/// the rates).
#[doc(hidden)]
#[derive(Clone, Copy)]
pub struct Point {
    pub r: f64,
    pub r_rate: f64,
    pub p: [f64; 3],
    pub v: [f64; 3],
    pub tau: f64,
}

/// `wave_kinematics_tau` over components in columns, with working columns `scratch`;
/// on x86-64 the component loops run eight components at a time with AVX-512, four
/// with AVX2 ([`crate::lanes`]).
///
/// The terms are those of the one-at-a-time formulas (the WGSL twin's), with the loops
/// split so that each vectorises: two passes, every phase's sine and cosine and the
/// elevation (which sets the Wheeler depth), then the depth decay and the velocity
/// and acceleration terms. With AVX2 and FMA the polynomials use fused multiply-adds,
/// and every sum is four interleaved partial sums ([`sum_lanes`]): the result agrees
/// with the sequential loop to round-off, not bit for bit.
/// Exponentials whose terms are below round-off contribute exactly 0:
/// `e^{-k (zs + 2 h)}` when it is under `1e-17` of `e^{k zs}` (deep water:
/// `2 k (zs + h) > 39`), and a whole component whose decay `e^{k zs}` is under `1e-30`
/// (then so is the other term: short waves deep down). Sines, cosines and exponentials
/// are the inlined, branch-free polynomials of [`poly`] (the WGSL's own).
pub fn wave_kinematics_columns(
    cols: &ComponentColumns,
    depth: f64,
    stretching: Stretching,
    r: f64,
    p: [f64; 3],
    tau: f64,
    scratch: &mut KinematicsScratch,
) -> Kinematics {
    let at = Point {
        r,
        r_rate: 0.0,
        p,
        v: [0.0; 3],
        tau,
    };
    dispatch::<false>(cols, depth, stretching, at, scratch).0
}

/// `wave_kinematics_rates_tau` over components in columns: the values of
/// [`wave_kinematics_columns`] and their rates along a path through `p` with velocity
/// `v`, in the same two passes (the rates' extra terms reuse the sines, cosines and
/// exponentials of the values). Returns `(values, rates)`.
#[allow(clippy::too_many_arguments)]
pub fn wave_kinematics_rates_columns(
    cols: &ComponentColumns,
    depth: f64,
    stretching: Stretching,
    r: f64,
    r_rate: f64,
    p: [f64; 3],
    v: [f64; 3],
    tau: f64,
    scratch: &mut KinematicsScratch,
) -> (Kinematics, Kinematics) {
    let at = Point {
        r,
        r_rate,
        p,
        v,
        tau,
    };
    dispatch::<true>(cols, depth, stretching, at, scratch)
}

/// The AVX-512 body (8 components a vector) where the CPU has it and
/// [`crate::lanes::avx512_wanted`] says so, the AVX2 + FMA body (4) where it has
/// those, the plain one otherwise. The two vector bodies give the same bits: the
/// polynomials are the same fused multiply-adds per component, and the sums keep
/// four partial sums at both widths ([`sum_lanes`]).
#[inline(always)]
fn dispatch<const RATES: bool>(
    cols: &ComponentColumns,
    depth: f64,
    stretching: Stretching,
    at: Point,
    scratch: &mut KinematicsScratch,
) -> (Kinematics, Kinematics) {
    dispatch_at::<RATES>(
        crate::lanes::avx512_wanted(),
        cols,
        depth,
        stretching,
        at,
        scratch,
    )
}

/// [`dispatch`] with the choice of AVX-512 given (`wide`; taken only where the CPU has
/// it), for the test that both widths agree.
#[inline(always)]
#[doc(hidden)]
pub fn dispatch_at<const RATES: bool>(
    wide: bool,
    cols: &ComponentColumns,
    depth: f64,
    stretching: Stretching,
    at: Point,
    scratch: &mut KinematicsScratch,
) -> (Kinematics, Kinematics) {
    scratch.fit(cols.len());
    #[cfg(target_arch = "x86_64")]
    {
        if wide && crate::lanes::avx512_present() && std::arch::is_x86_feature_detected!("fma") {
            // SAFETY: the CPU has AVX-512 (F, DQ, VL) and FMA, checked just above.
            return unsafe { columns_avx512::<RATES>(cols, depth, stretching, at, scratch) };
        }
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            // SAFETY: the CPU has AVX2 and FMA, checked just above.
            return unsafe { columns_avx2::<RATES>(cols, depth, stretching, at, scratch) };
        }
    }
    let _ = wide;
    columns_body::<false, RATES>(cols, depth, stretching, at, scratch)
}

/// `sum v` as four interleaved partial sums (lanes `j mod 4`), then the lanes and the
/// remainder: the reduction of the vectorised bodies (by [`sum_lanes_avx`] on x86-64,
/// which gives the same bits; public for the test that says so).
#[inline(always)]
#[doc(hidden)]
pub fn sum_lanes(v: &[f64]) -> f64 {
    let mut acc = [0.0f64; 4];
    let chunks = v.chunks_exact(4);
    let rest = chunks.remainder();
    for c in chunks {
        for l in 0..4 {
            acc[l] += c[l];
        }
    }
    let mut s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for x in rest {
        s += x;
    }
    s
}

/// [`sum_lanes`] with the four partial sums in one 256-bit register: the same
/// additions in the same order, so the same bits. Why by hand: written as
/// `acc[l] += c[l]`, the compiler pairs the lanes for the final
/// `(acc[0] + acc[1]) + (acc[2] + acc[3])` and adds two 128-bit halves with shuffles,
/// 1.4 instructions per element (the 14 sums of a refresh were 7.4 instructions per
/// node-step of the design member, counted); and it does not unroll the loop, whose
/// control (three instructions) then costs more than its one addition: hence sixteen
/// elements an iteration, about 0.45 instructions per element in all.
///
/// # Safety
/// The CPU must have AVX: call it only from code compiled with AVX enabled (the
/// bodies of [`columns_avx2`] and [`columns_avx512`]), where it inlines.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn sum_lanes_avx(v: &[f64]) -> f64 {
    use std::arch::x86_64::{_mm256_add_pd, _mm256_loadu_pd, _mm256_setzero_pd, _mm256_storeu_pd};
    let sixteens = v.chunks_exact(16);
    let chunks = sixteens.remainder().chunks_exact(4);
    let rest = chunks.remainder();
    let mut acc = _mm256_setzero_pd();
    // Each lane adds its elements in order, as in `sum_lanes`.
    for c in sixteens {
        // SAFETY: `c` holds sixteen f64, four unaligned loads of four.
        let p = c.as_ptr();
        acc = _mm256_add_pd(acc, _mm256_loadu_pd(p));
        acc = _mm256_add_pd(acc, _mm256_loadu_pd(p.add(4)));
        acc = _mm256_add_pd(acc, _mm256_loadu_pd(p.add(8)));
        acc = _mm256_add_pd(acc, _mm256_loadu_pd(p.add(12)));
    }
    for c in chunks {
        // SAFETY: `c` holds four f64 (an unaligned load).
        acc = _mm256_add_pd(acc, _mm256_loadu_pd(c.as_ptr()));
    }
    let mut a = [0.0f64; 4];
    // SAFETY: `a` holds four f64.
    _mm256_storeu_pd(a.as_mut_ptr(), acc);
    let mut s = (a[0] + a[1]) + (a[2] + a[3]);
    for x in rest {
        s += x;
    }
    s
}

/// [`sum_lanes_avx`] where the CPU has AVX (`None` elsewhere), for the test that it
/// gives the bits of [`sum_lanes`].
#[doc(hidden)]
pub fn sum_lanes_wide(v: &[f64]) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx")]
        unsafe fn with_avx(v: &[f64]) -> f64 {
            sum_lanes_avx(v)
        }
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU has AVX, checked just above.
            return Some(unsafe { with_avx(v) });
        }
    }
    let _ = v;
    None
}

/// `sum v`: lanes with FMA (the vectorised build), in order otherwise.
#[inline(always)]
fn sum<const FMA: bool>(v: &[f64]) -> f64 {
    if FMA {
        // SAFETY: `FMA` is true only in the bodies of `columns_avx2` and
        // `columns_avx512`, which run where the CPU has AVX2 and FMA (checked in
        // `dispatch_at`) and are compiled with them.
        #[cfg(target_arch = "x86_64")]
        return unsafe { sum_lanes_avx(v) };
        #[cfg(not(target_arch = "x86_64"))]
        return sum_lanes(v);
    }
    v.iter().sum()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn columns_avx2<const RATES: bool>(
    cols: &ComponentColumns,
    depth: f64,
    stretching: Stretching,
    at: Point,
    scratch: &mut KinematicsScratch,
) -> (Kinematics, Kinematics) {
    columns_body::<true, RATES>(cols, depth, stretching, at, scratch)
}

/// The same, with 512-bit vectors: the compiler vectorises the component loops 8 at
/// a time.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,avx512f,avx512dq,avx512vl")]
unsafe fn columns_avx512<const RATES: bool>(
    cols: &ComponentColumns,
    depth: f64,
    stretching: Stretching,
    at: Point,
    scratch: &mut KinematicsScratch,
) -> (Kinematics, Kinematics) {
    columns_body::<true, RATES>(cols, depth, stretching, at, scratch)
}

/// The body; `FMA`: fused polynomials and lane sums (only where the target has FMA);
/// `RATES`: the rates too (otherwise they come back zero).
#[inline(always)]
fn columns_body<const FMA: bool, const RATES: bool>(
    cols: &ComponentColumns,
    depth: f64,
    stretching: Stretching,
    at: Point,
    scratch: &mut KinematicsScratch,
) -> (Kinematics, Kinematics) {
    let Point {
        r,
        r_rate,
        p,
        v,
        tau,
    } = at;
    let n = cols.len();
    let (kx, ky, ph, om, amp) = (
        &cols.kx[..n],
        &cols.ky[..n],
        &cols.phase_ref[..n],
        &cols.omega[..n],
        &cols.amp[..n],
    );
    let (k, amp_u, amp_a, cos_b, sin_b) = (
        &cols.k[..n],
        &cols.amp_u[..n],
        &cols.amp_a[..n],
        &cols.cos_b[..n],
        &cols.sin_b[..n],
    );
    let KinematicsScratch {
        sin,
        cos,
        theta_rate,
        ch,
        sh,
        terms,
    } = scratch;
    let (sin, cos, td) = (&mut sin[..n], &mut cos[..n], &mut theta_rate[..n]);
    let (ch, sh) = (&mut ch[..n], &mut sh[..n]);
    let [t0, t1, t2, t3, t4, t5, d0, d1, d2, d3, d4, d5] = terms;
    let (t0, t1, t2, t3, t4, t5) = (
        &mut t0[..n],
        &mut t1[..n],
        &mut t2[..n],
        &mut t3[..n],
        &mut t4[..n],
        &mut t5[..n],
    );
    let (d0, d1, d2, d3, d4, d5) = (
        &mut d0[..n],
        &mut d1[..n],
        &mut d2[..n],
        &mut d3[..n],
        &mut d4[..n],
        &mut d5[..n],
    );
    for j in 0..n {
        // The phase of `wave_theta`, same order of operations.
        let theta = kx[j] * p[0] + ky[j] * p[1] + ph[j] - om[j] * tau;
        let (s, c) = poly::sin_cos_with::<FMA>(theta);
        sin[j] = s;
        cos[j] = c;
        t0[j] = amp[j] * c;
        if RATES {
            // The Doppler-shifted frequency seen along the path.
            let thd = kx[j] * v[0] + ky[j] * v[1] - om[j];
            td[j] = thd;
            d0[j] = -(amp[j] * s) * thd;
        }
    }
    let se = sum::<FMA>(t0);
    let eta = r * se;
    let (eta_rate, zs_rate) = if RATES {
        let eta_rate = r * sum::<FMA>(d0) + r_rate * se;
        let zs_rate = wave_eval_depth_rate(p[2], eta, depth, stretching, v[2], eta_rate);
        (eta_rate, zs_rate)
    } else {
        (0.0, 0.0)
    };
    let zs = wave_eval_depth(p[2], eta, depth, stretching);
    // Height above the seabed of the evaluation point (infinite in deep water).
    let above_bed = zs + depth;
    // With the rates (the cache's refresh), the decay cut: only the prefix of the
    // components (sorted by k) that `wave_decay_prefix` keeps.
    let n = if RATES {
        let speed = v[0].hypot(v[1]) + zs_rate.abs();
        decay_prefix(n, zs, speed, r_rate, |j| {
            (cols.k[j], cols.cut0[j], cols.cut1[j], cols.cut2[j])
        })
    } else {
        n
    };
    let (k, amp_u, amp_a, cos_b, sin_b) =
        (&k[..n], &amp_u[..n], &amp_a[..n], &cos_b[..n], &sin_b[..n]);
    let (sin, cos, td, ch, sh) = (&sin[..n], &cos[..n], &td[..n], &mut ch[..n], &mut sh[..n]);
    let (t0, t1, t2, t3, t4, t5) = (
        &mut t0[..n],
        &mut t1[..n],
        &mut t2[..n],
        &mut t3[..n],
        &mut t4[..n],
        &mut t5[..n],
    );
    let (d0, d1, d2, d3, d4, d5) = (
        &mut d0[..n],
        &mut d1[..n],
        &mut d2[..n],
        &mut d3[..n],
        &mut d4[..n],
        &mut d5[..n],
    );
    // The second pass as three loops (decay; value terms; rate terms), each short
    // enough that the compiler vectorises it: as one loop with the rates, it did not
    // (scalar, 2.5x the values-only instructions per component).
    // The seabed's reflection `e2` is below round-off (`2 k (zs + h) > 39`) from the
    // first component that passes that test on (`k` ascending, `zs + h >= 0`): a
    // suffix, which the second loop leaves it out of (the same bits: `e1 + 0.0`).
    // Near the surface in 320 m of water that is every wave shorter than 8 s
    // (`k > 0.061`), two thirds of the design member's sea. Components not sorted
    // by `k`, or a NaN height, keep all in the first loop, as before.
    let reach_bed = if cols.k_ascending {
        k.partition_point(|&kj| !(2.0 * kj * above_bed > 39.0))
    } else {
        n
    };
    for j in 0..reach_bed {
        let e1 = poly::exp_neg_with::<FMA>(k[j] * zs);
        // Computed always and then selected (no branch, so that the loop vectorises).
        let e2 = poly::exp_neg_with::<FMA>(-k[j] * (zs + 2.0 * depth));
        let e2 = if 2.0 * k[j] * above_bed > 39.0 {
            0.0
        } else {
            e2
        };
        // Not `e1 < 1e-30`: a NaN depth must come out NaN, as in the plain loop
        // (which skips only on a true comparison).
        let live = !(e1 < 1e-30);
        ch[j] = if live { e1 + e2 } else { 0.0 };
        sh[j] = if live { e1 - e2 } else { 0.0 };
    }
    for j in reach_bed..n {
        let e1 = poly::exp_neg_with::<FMA>(k[j] * zs);
        let e2 = 0.0;
        let live = !(e1 < 1e-30);
        ch[j] = if live { e1 + e2 } else { 0.0 };
        sh[j] = if live { e1 - e2 } else { 0.0 };
    }
    // A component that is not live has `ch = sh = 0`, so its terms are exactly 0 (the
    // factors beside them are finite).
    for j in 0..n {
        let (s, co) = (sin[j], cos[j]);
        let (cc, ss, cs, sc) = (ch[j] * co, sh[j] * s, ch[j] * s, sh[j] * co);
        let uh = amp_u[j] * cc;
        let ah = amp_a[j] * cs;
        t0[j] = uh * cos_b[j];
        t1[j] = uh * sin_b[j];
        t2[j] = amp_u[j] * ss;
        t3[j] = ah * cos_b[j];
        t4[j] = ah * sin_b[j];
        t5[j] = amp_a[j] * sc;
    }
    if RATES {
        for j in 0..n {
            let (s, co) = (sin[j], cos[j]);
            let (cc, ss, cs, sc) = (ch[j] * co, sh[j] * s, ch[j] * s, sh[j] * co);
            let (thd, kz) = (td[j], k[j] * zs_rate);
            let uh_rate = amp_u[j] * (kz * sc - cs * thd);
            let ah_rate = amp_a[j] * (kz * ss + cc * thd);
            d0[j] = uh_rate * cos_b[j];
            d1[j] = uh_rate * sin_b[j];
            d2[j] = amp_u[j] * (kz * cs + sc * thd);
            d3[j] = ah_rate * cos_b[j];
            d4[j] = ah_rate * sin_b[j];
            d5[j] = amp_a[j] * (kz * cc - ss * thd);
        }
    }
    // Unramped sums (a_z without its sign).
    let u = [sum::<FMA>(t0), sum::<FMA>(t1), sum::<FMA>(t2)];
    let a = [sum::<FMA>(t3), sum::<FMA>(t4), -sum::<FMA>(t5)];
    let values = Kinematics {
        eta,
        u: u.map(|v| r * v),
        a: a.map(|v| r * v),
    };
    if !RATES {
        return (values, Kinematics::default());
    }
    let du = [sum::<FMA>(d0), sum::<FMA>(d1), sum::<FMA>(d2)];
    let da = [sum::<FMA>(d3), sum::<FMA>(d4), -sum::<FMA>(d5)];
    let rate = |x: [f64; 3], dx: [f64; 3]| [0, 1, 2].map(|q| r * dx[q] + r_rate * x[q]);
    let rates = Kinematics {
        eta: eta_rate,
        u: rate(u, du),
        a: rate(a, da),
    };
    (values, rates)
}
