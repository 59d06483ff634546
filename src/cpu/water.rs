//! The waves a block's nodes see on the CPU path: surface elevation, wave velocity and
//! wave acceleration per node, from the sea state's kinematics cache (`sea::cache`:
//! the component sum evaluated at refresh times, interpolated in time between them),
//! or evaluated exactly at every stage (for tests of the cache).
//!
//! Each block keeps its own cache: blocks are stepped independently (in parallel, many
//! steps at a time), so a block's refresh reads only its own nodes' state.

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
}

impl BlockWaves {
    /// Waves of `sea` for a block of `n` nodes.
    pub(crate) fn new(sea: &SeaState, n: usize, exact: bool) -> Self {
        Self {
            cache: WaveCache::new(sea, n),
            exact,
            pos: vec![0.0; 3 * n],
            vel: vec![0.0; 3 * n],
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
}

/// Node `i`'s elevation, wave velocity and wave acceleration in `w`.
#[inline(always)]
pub(crate) fn node_water(w: &[f64], i: usize) -> (f64, [f64; 3], [f64; 3]) {
    let o = &w[i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE];
    (o[0], [o[1], o[2], o[3]], [o[4], o[5], o[6]])
}
