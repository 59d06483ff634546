//! The waves a block's nodes see on the CPU path: surface elevation, wave velocity and
//! wave acceleration per node, from the sea state's kinematics cache (`sea::cache`:
//! the component sum evaluated at refresh times, interpolated in time between them),
//! or evaluated exactly at every stage (for tests of the cache).
//!
//! Each block keeps its own cache: blocks are stepped independently (in parallel, many
//! steps at a time), so a block's refresh reads only its own nodes' state.
//!
//! The chain kernel reads the cache as columns ([`BlockWaves::chain_columns`]): each
//! node's elevation and each element's midpoint wave velocity and acceleration (the
//! mean of its two nodes'), values and rates formed once per refresh at both cache
//! times, so that a stage interpolates seven columns (four multiply-adds a value, the
//! cubic Hermite weights formed once per stage) straight into the element loop's
//! inputs instead of interpolating per node and then averaging. Interpolation is
//! linear in the cached values and rates, so this is the same value up to round-off.
//! With several depth bands (the power basis) and every node under the surface, the
//! element loop interpolates the six element columns in its own lanes
//! (`cpu::chain::elements::elements_fused`) rather than reading them back from
//! columns [`ChainCols::fill`] wrote: the same arithmetic, one pass fewer.

use crate::cpu::chain::column_stride;
use crate::sea::bands::BandPlan;
use crate::sea::cache::{
    evaluate_nodes, wave_cache_hermite, wave_cache_midpoint, WaveCache, CACHE_STRIDE,
};
use crate::sea::SeaState;

/// Per-node water values: `eta, u (3), a (3)` ([`CACHE_STRIDE`] per node), m, m/s,
/// m/s^2; empty in still water.
pub(crate) type Water = Vec<f64>;

/// One block's wave kinematics.
#[derive(Clone, Debug)]
pub(crate) struct BlockWaves {
    cache: WaveCache,
    /// Evaluate the sum at every stage instead of interpolating the cache.
    exact: bool,
    pos: Vec<f64>,
    vel: Vec<f64>,
    /// The chain kernel's columns of the cache, for the cache's refresh they were
    /// formed after.
    cols: ChainColumns,
}

/// A chain block's cache as columns, in the order of [`wave_cache_hermite`]'s
/// arguments: values at `t0`, rates at `t0`, values at `t1`, rates at `t1`.
///
/// Derived from the cache alone, so a clone is an empty one (formed again, whole, at
/// its first use: the same values as the entries formed a refresh at a time, which
/// are the same function of the same cache entries): the CPU solver is copied whole
/// for a checkpoint at each output time, and these columns were most of the copy.
#[derive(Debug, Default)]
struct ChainColumns {
    /// The cache's refresh count ([`WaveCache::generation`]) these columns were
    /// formed for.
    generation: Option<u64>,
    /// With several bands: the time the power-basis columns are referred to (the
    /// coarsest band's `t0`); `None`: Hermite columns of one band.
    power_ref: Option<f64>,
    /// Scratch: the nodes' power-basis coefficients.
    power: [Vec<f64>; 4],
    /// Elevation over each node, m (rates: m/s): four columns `stride` apart (one a
    /// side). This and `mid` zero past the chain's nodes, read in whole chunks of
    /// lanes.
    eta: Vec<f64>,
    /// Per element (between nodes `k` and `k + 1`): the mean of its nodes' wave
    /// velocity `x, y, z` then wave acceleration `x, y, z` (or of their rates), 24
    /// columns `stride` apart, column `6 side + q`.
    mid: Vec<f64>,
    /// The distance between two columns ([`column_stride`]): the chain's per-stage
    /// block's, so that its element loop reaches the 24 columns from one base
    /// register by constant displacements, where 24 separate `Vec`s left their
    /// pointers on the stack, reloaded before each load.
    stride: usize,
}

impl BlockWaves {
    /// Waves of `sea` for a block of `n` nodes, refreshed per depth band on the grid
    /// of `plan`.
    pub(crate) fn new(sea: &SeaState, n: usize, exact: bool, plan: &BandPlan) -> Self {
        Self {
            cache: WaveCache::with_bands(sea, n, plan),
            exact,
            pos: vec![0.0; 3 * n],
            vel: vec![0.0; 3 * n],
            cols: ChainColumns::default(),
        }
    }

    /// Fills `out` with every node's water values at time `t`; `state(i)` is node `i`'s
    /// position and velocity (read only when the sum is evaluated).
    pub(crate) fn fill(
        &mut self,
        t: f64,
        n: usize,
        state: impl Fn(usize) -> ([f64; 3], [f64; 3]),
        out: &mut Water,
    ) {
        if self.exact {
            self.read_state(n, &state);
            out.resize(n * CACHE_STRIDE, 0.0);
            evaluate_nodes(&self.cache.field, &self.pos, t, out);
            return;
        }
        self.cover(t, n, state);
        self.interpolate(t, n, out);
    }

    /// Makes the cache cover time `t`: refreshes it from the nodes' state (`state` as
    /// in [`Self::fill`]) when `t` is outside it (before the first refresh, past its
    /// newer time, or before its older one), as every stage does before it
    /// interpolates. An output-time evaluation calls it too, with the state the next
    /// step starts from: it refreshes exactly where and how that step would (which
    /// then finds the cache covering its time), so the run is the same with or without
    /// outputs.
    pub(crate) fn cover(
        &mut self,
        t: f64,
        n: usize,
        state: impl Fn(usize) -> ([f64; 3], [f64; 3]),
    ) {
        if !self.cache.covers(t) {
            self.read_state(n, &state);
            self.cache.refresh_if_due(t, &self.pos, &self.vel);
        }
    }

    /// The interpolated water values of the `n` nodes at `t` into `out` (the cache
    /// must cover `t`: [`Self::cover`]).
    pub(crate) fn interpolate(&self, t: f64, n: usize, out: &mut Water) {
        out.resize(n * CACHE_STRIDE, 0.0);
        self.cache.interpolate(t, out);
    }

    fn read_state(&mut self, n: usize, state: &impl Fn(usize) -> ([f64; 3], [f64; 3])) {
        for i in 0..n {
            let (r, v) = state(i);
            self.pos[3 * i..3 * i + 3].copy_from_slice(&r);
            self.vel[3 * i..3 * i + 3].copy_from_slice(&v);
        }
    }

    /// The block's kinematics cache.
    pub(crate) fn cache(&self) -> &WaveCache {
        &self.cache
    }

    /// Whether the sum is evaluated at every stage (no interpolation).
    pub(crate) fn exact(&self) -> bool {
        self.exact
    }

    /// The chain kernel's view of the cache at time `t` (not in exact mode): its
    /// columns, formed for the cache's latest refresh, and the interpolation weights
    /// of `t`. Refreshes the cache when `t` is past it (`state` as in [`Self::fill`]).
    #[inline(always)]
    pub(crate) fn chain_columns(
        &mut self,
        t: f64,
        n: usize,
        state: impl Fn(usize) -> ([f64; 3], [f64; 3]),
    ) -> ChainCols<'_> {
        debug_assert!(!self.exact);
        self.cover(t, n, state);
        let c = &self.cache;
        if self.cols.generation != Some(c.generation) {
            self.cols.form(c, n);
            self.cols.generation = Some(c.generation);
        }
        let (w, unit) = match self.cols.power_ref {
            Some(t_ref) => {
                let tau = t - t_ref;
                ([1.0, tau, tau * tau, tau * tau * tau], true)
            }
            None => (c.weights(t), false),
        };
        ChainCols {
            eta: &self.cols.eta,
            mid: &self.cols.mid,
            stride: self.cols.stride,
            w,
            unit,
        }
    }
}

/// The chain kernel's view of a block's cache at one time ([`BlockWaves::chain_columns`]):
/// the columns `[v0, d0, v1, d1]` of each node's elevation and of each element's
/// midpoint wave velocity and acceleration, and the weights `w` that interpolate them.
/// Every column is zero past the chain's nodes up to the stride ([`column_stride`], at
/// least the chain's padded length), so the element loop may read them in whole chunks
/// of lanes.
pub(crate) struct ChainCols<'a> {
    /// Elevation over each node (the four columns, [`Self::eta_col`]).
    pub(crate) eta: &'a [f64],
    /// Per element, the mean of its nodes' wave velocity (`q` 0-2) or acceleration
    /// (`q` 3-5), side `side` of `[v0, d0, v1, d1]`: column `6 side + q`
    /// ([`Self::mid_col`]).
    pub(crate) mid: &'a [f64],
    /// The distance between two columns, entries ([`column_stride`]).
    pub(crate) stride: usize,
    /// The weights of the time asked for.
    pub(crate) w: [f64; 4],
    /// The power basis (several bands): `w[0]` is exactly 1.
    pub(crate) unit: bool,
}

impl ChainCols<'_> {
    /// Side `side` of the elevations.
    #[inline(always)]
    pub(crate) fn eta_col(&self, side: usize) -> &[f64] {
        &self.eta[side * self.stride..(side + 1) * self.stride]
    }

    /// Side `side` of the elements' quantity `q`.
    #[inline(always)]
    pub(crate) fn mid_col(&self, side: usize, q: usize) -> &[f64] {
        let c = 6 * side + q;
        &self.mid[c * self.stride..(c + 1) * self.stride]
    }

    /// The chain kernel's inputs from the columns: each node's elevation into `eta`
    /// (unless `with_eta` is false: already there), each element's midpoint wave
    /// velocity plus the current into `u` (`uniform`: the block's one current, written
    /// with the waves' velocity; `None`: added to the currents `u` already holds) and
    /// its midpoint wave acceleration into `aw`, for the `n` nodes and their `n - 1`
    /// elements.
    #[inline(always)]
    pub(crate) fn fill(
        &self,
        n: usize,
        eta: &mut [f64],
        with_eta: bool,
        u: &mut [Vec<f64>; 3],
        uniform: Option<[f64; 3]>,
        aw: &mut [Vec<f64>; 3],
    ) {
        let (w, power) = (self.w, self.unit);
        let ne = n - 1;
        if with_eta {
            let ec = [
                self.eta_col(0),
                self.eta_col(1),
                self.eta_col(2),
                self.eta_col(3),
            ];
            wave_cache_hermite_cols(&mut eta[..n], ec, w, HermiteOut::Set, power);
        }
        // The sides written out, not by `array::map` or a closure: neither was inlined
        // into the AVX-512 caller (a call a column a step).
        macro_rules! sides {
            ($q:expr) => {
                [
                    self.mid_col(0, $q),
                    self.mid_col(1, $q),
                    self.mid_col(2, $q),
                    self.mid_col(3, $q),
                ]
            };
        }
        for q in 0..3 {
            let (uq, aq) = (q, 3 + q);
            let uc = sides!(uq);
            let into = uniform.map_or(HermiteOut::Add, |un| HermiteOut::Over(un[q]));
            wave_cache_hermite_cols(&mut u[q][..ne], uc, w, into, power);
            let ac = sides!(aq);
            wave_cache_hermite_cols(&mut aw[q][..ne], ac, w, HermiteOut::Set, power);
        }
    }
}

impl Clone for ChainColumns {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl ChainColumns {
    /// Forms the columns of `n` nodes from the cache: with one band, its four arrays
    /// (values and rates at its two times, interpolated with the band's Hermite
    /// weights); with several, each node's cubic in the power basis of `t - t_ref`
    /// ([`WaveCache::power_node`], `t_ref` the coarsest band's `t0`), so that every
    /// node, whatever its band, interpolates with the same weights `1, tau, tau^2,
    /// tau^3` (an element between two bands too: its midpoint is the mean of its
    /// nodes' cubics). Until the coarsest band refreshes (and `t_ref` moves) only the
    /// nodes the last refresh touched
    /// change, and only their entries are formed again.
    fn form(&mut self, cache: &WaveCache, n: usize) {
        if cache.clocks.len() == 1 {
            self.power_ref = None;
            self.form_from_arrays([&cache.v0, &cache.d0, &cache.v1, &cache.d1], n);
            return;
        }
        let t_ref = cache.power_ref();
        let mut p = std::mem::take(&mut self.power);
        let follows = self.generation.map(|g| g + 1) == Some(cache.generation);
        if self.power_ref == Some(t_ref) && follows && p[0].len() == n * CACHE_STRIDE {
            // Only the refreshed nodes, their elevations and their elements.
            for (i, due) in cache.due().iter().enumerate().take(n) {
                if due.is_nan() {
                    continue;
                }
                cache.power_node(i, t_ref, &mut p);
                let st = self.stride;
                for (side, v) in p.iter().enumerate() {
                    self.eta[side * st + i] = v[i * CACHE_STRIDE];
                    for k in i.saturating_sub(1)..(i + 1).min(n - 1) {
                        let m = element_midpoint(v, k);
                        for q in 0..6 {
                            self.mid[(6 * side + q) * st + k] = m[2 + q];
                        }
                    }
                }
            }
        } else {
            self.power_ref = Some(t_ref);
            cache.power_coefficients(t_ref, &mut p);
            self.form_from_arrays([&p[0], &p[1], &p[2], &p[3]], n);
        }
        self.power = p;
    }

    /// Forms the columns from four arrays of [`CACHE_STRIDE`] per node.
    fn form_from_arrays(&mut self, v: [&[f64]; 4], n: usize) {
        let st = column_stride(n);
        self.stride = st;
        for (c, len) in [(&mut self.eta, 4 * st), (&mut self.mid, 24 * st)] {
            c.clear();
            c.resize(len, 0.0);
        }
        for (side, v) in v.into_iter().enumerate() {
            for i in 0..n {
                self.eta[side * st + i] = node_water(v, i).0;
            }
            for k in 0..n - 1 {
                let m = element_midpoint(v, k);
                for q in 0..6 {
                    self.mid[(6 * side + q) * st + k] = m[2 + q];
                }
            }
        }
    }
}

/// Element `k`'s share ([`wave_cache_midpoint`]) of nodes `k` and `k + 1` in `v`
/// ([`CACHE_STRIDE`] per node).
#[inline(always)]
fn element_midpoint(v: &[f64], k: usize) -> [f64; 8] {
    wave_cache_midpoint(
        &v[k * CACHE_STRIDE..(k + 1) * CACHE_STRIDE],
        &v[(k + 1) * CACHE_STRIDE..(k + 2) * CACHE_STRIDE],
    )
}

/// What [`wave_cache_hermite_cols`] does with the interpolated value `h` of entry `i`.
#[derive(Clone, Copy)]
enum HermiteOut {
    /// `out[i] = h`.
    Set,
    /// `out[i] += h` (a current already there).
    Add,
    /// `out[i] = b + h`: the same bits as `out[i] = b` then `out[i] += h`, without
    /// filling `out` with the block's uniform current `b` first at every stage.
    Over(f64),
}

/// `h = w0 v0 + w1 d0 + w2 v1 + w3 d1` elementwise over the columns `c = [v0, d0, v1,
/// d1]` ([`wave_cache_hermite`] into the kernel's inputs), written as `into` says.
/// `unit`: `w0` is exactly 1 (the power basis), and `v0` is taken as it is: `1 * v0`
/// is `v0` to the bit, so the same sum with one multiply fewer. Loops that vectorise
/// (distinct slices of one length), one per case, so no branch inside.
#[inline(always)]
fn wave_cache_hermite_cols(
    out: &mut [f64],
    c: [&[f64]; 4],
    w: [f64; 4],
    into: HermiteOut,
    unit: bool,
) {
    if unit {
        debug_assert!(w[0] == 1.0);
        hermite_cols_into::<true>(out, c, w, into);
    } else if let HermiteOut::Set = into {
        let n = out.len();
        wave_cache_hermite(&c[0][..n], &c[1][..n], &c[2][..n], &c[3][..n], w, out);
    } else {
        hermite_cols_into::<false>(out, c, w, into);
    }
}

/// [`wave_cache_hermite_cols`]'s loops; `UNIT`: `w0` is 1.
#[inline(always)]
fn hermite_cols_into<const UNIT: bool>(
    out: &mut [f64],
    c: [&[f64]; 4],
    w: [f64; 4],
    into: HermiteOut,
) {
    let n = out.len();
    let (v0, d0, v1, d1) = (&c[0][..n], &c[1][..n], &c[2][..n], &c[3][..n]);
    match into {
        HermiteOut::Set => {
            for i in 0..n {
                out[i] = hermite_at::<UNIT>(w, v0[i], d0[i], v1[i], d1[i]);
            }
        }
        HermiteOut::Add => {
            for i in 0..n {
                out[i] += hermite_at::<UNIT>(w, v0[i], d0[i], v1[i], d1[i]);
            }
        }
        HermiteOut::Over(b) => {
            for i in 0..n {
                out[i] = b + hermite_at::<UNIT>(w, v0[i], d0[i], v1[i], d1[i]);
            }
        }
    }
}

/// One entry of [`wave_cache_hermite`], in its order of operations (`UNIT`: `w0` is 1).
#[inline(always)]
pub(crate) fn hermite_at<const UNIT: bool>(w: [f64; 4], v0: f64, d0: f64, v1: f64, d1: f64) -> f64 {
    let first = if UNIT { v0 } else { w[0] * v0 };
    first + w[1] * d0 + w[2] * v1 + w[3] * d1
}

/// Node `i`'s elevation, wave velocity and wave acceleration in `w`.
#[inline(always)]
pub(crate) fn node_water(w: &[f64], i: usize) -> (f64, [f64; 3], [f64; 3]) {
    let o = &w[i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE];
    (o[0], [o[1], o[2], o[3]], [o[4], o[5], o[6]])
}
