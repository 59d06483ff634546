//! The waves a block's nodes see on the CPU path: surface elevation, wave velocity and
//! wave acceleration per node, from the sea state's kinematics cache (`sea::cache`:
//! the component sum evaluated at refresh times, interpolated in time between them),
//! or evaluated exactly at every stage (for tests of the cache).
//!
//! Each block keeps its own cache: blocks are stepped independently (in parallel, many
//! steps at a time), so a block's refresh reads only its own nodes' state.
//!
//! The chain kernel reads the cache as columns ([`BlockWaves::fill_chain`]): each
//! node's elevation and each element's midpoint wave velocity and acceleration (the
//! mean of its two nodes'), formed once per refresh at both cache times, so that a
//! stage interpolates seven columns straight into the element loop's inputs instead
//! of interpolating per node and then averaging. Interpolation is linear, so this is
//! the same value up to round-off.

use crate::sea::cache::{evaluate_nodes, WaveCache, CACHE_STRIDE};
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
    /// The chain kernel's columns of the cache, for the cache's `(t0, t1)` they were
    /// formed at.
    cols: ChainColumns,
}

/// A chain block's cache as columns at the cache's two times (index 0: `t0`, 1: `t1`).
#[derive(Clone, Debug, Default)]
struct ChainColumns {
    /// The cache times these columns were formed for.
    times: Option<(f64, f64)>,
    /// Elevation over each node, m.
    eta: [Vec<f64>; 2],
    /// Per element (between nodes `k` and `k + 1`): the mean of its nodes' wave
    /// velocity `x, y, z` then wave acceleration `x, y, z`.
    mid: [[Vec<f64>; 6]; 2],
}

impl BlockWaves {
    /// Waves of `sea` for a block of `n` nodes.
    pub(crate) fn new(sea: &SeaState, n: usize, exact: bool) -> Self {
        Self {
            cache: WaveCache::new(sea, n),
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
        out.resize(n * CACHE_STRIDE, 0.0);
        let c = &self.cache;
        let covered = c.t1 > c.t0 && t >= c.t0 && t <= c.t1;
        if self.exact || !covered {
            for i in 0..n {
                let (r, v) = state(i);
                self.pos[3 * i..3 * i + 3].copy_from_slice(&r);
                self.vel[3 * i..3 * i + 3].copy_from_slice(&v);
            }
        }
        if self.exact {
            evaluate_nodes(&self.cache.field, &self.pos, t, out);
            return;
        }
        if !covered {
            self.cache.refresh_if_due(t, &self.pos, &self.vel);
        }
        self.cache.interpolate(t, out);
    }

    /// Whether the sum is evaluated at every stage (no interpolation).
    pub(crate) fn exact(&self) -> bool {
        self.exact
    }

    /// The chain kernel's inputs at time `t` from the cache (not in exact mode): each
    /// node's elevation into `eta`, each element's midpoint wave velocity added to `u`
    /// and its midpoint wave acceleration into `aw` (elements `0..n - 1`). Refreshes
    /// the cache when `t` is past it (`state` as in [`Self::fill`]).
    #[inline(always)]
    pub(crate) fn fill_chain(
        &mut self,
        t: f64,
        n: usize,
        state: impl Fn(usize) -> ([f64; 3], [f64; 3]),
        eta: &mut [f64],
        u: &mut [Vec<f64>; 3],
        aw: &mut [Vec<f64>; 3],
    ) {
        debug_assert!(!self.exact);
        let c = &self.cache;
        if !(c.t1 > c.t0 && t >= c.t0 && t <= c.t1) {
            for i in 0..n {
                let (r, v) = state(i);
                self.pos[3 * i..3 * i + 3].copy_from_slice(&r);
                self.vel[3 * i..3 * i + 3].copy_from_slice(&v);
            }
            self.cache.refresh_if_due(t, &self.pos, &self.vel);
        }
        let c = &self.cache;
        if self.cols.times != Some((c.t0, c.t1)) {
            self.cols.form(&c.v0, &c.v1, n);
            self.cols.times = Some((c.t0, c.t1));
        }
        let s = c.weight(t);
        let ne = n - 1;
        let cols = &self.cols;
        lerp_into(&mut eta[..n], &cols.eta[0], &cols.eta[1], s);
        for q in 0..3 {
            lerp_add(&mut u[q][..ne], &cols.mid[0][q], &cols.mid[1][q], s);
            lerp_into(
                &mut aw[q][..ne],
                &cols.mid[0][3 + q],
                &cols.mid[1][3 + q],
                s,
            );
        }
    }
}

impl ChainColumns {
    /// Forms the columns of `n` nodes from the cache's values at its two times.
    fn form(&mut self, v0: &[f64], v1: &[f64], n: usize) {
        for (side, v) in [v0, v1].into_iter().enumerate() {
            let eta = &mut self.eta[side];
            eta.clear();
            eta.extend((0..n).map(|i| node_water(v, i).0));
            for (q, col) in self.mid[side].iter_mut().enumerate() {
                col.clear();
                col.extend((0..n - 1).map(|k| {
                    let (a, b) = (&v[k * CACHE_STRIDE..], &v[(k + 1) * CACHE_STRIDE..]);
                    0.5 * (a[1 + q] + b[1 + q])
                }));
            }
        }
    }
}

/// `out = (1 - s) a + s b`, elementwise (a loop that vectorises: `out`, `a` and `b`
/// are distinct slices of one length).
#[inline(always)]
fn lerp_into(out: &mut [f64], a: &[f64], b: &[f64], s: f64) {
    let (a, b) = (&a[..out.len()], &b[..out.len()]);
    for i in 0..out.len() {
        out[i] = (1.0 - s) * a[i] + s * b[i];
    }
}

/// `out += (1 - s) a + s b`, elementwise.
#[inline(always)]
fn lerp_add(out: &mut [f64], a: &[f64], b: &[f64], s: f64) {
    let (a, b) = (&a[..out.len()], &b[..out.len()]);
    for i in 0..out.len() {
        out[i] += (1.0 - s) * a[i] + s * b[i];
    }
}

/// Node `i`'s elevation, wave velocity and wave acceleration in `w`.
#[inline(always)]
pub(crate) fn node_water(w: &[f64], i: usize) -> (f64, [f64; 3], [f64; 3]) {
    let o = &w[i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE];
    (o[0], [o[1], o[2], o[3]], [o[4], o[5], o[6]])
}
