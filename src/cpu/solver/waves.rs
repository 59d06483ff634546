//! The water an output-time evaluation of a [`CpuSolver`] sees: the kinematics the
//! steps integrate (each block's cache interpolated at the current time, refreshed
//! first where the next step would refresh it), or the exact sum in exact mode.

use super::CpuSolver;
use crate::cpu::water::Water;
use crate::sea::cache::{evaluate_nodes, CACHE_STRIDE};
use crate::sea::cut::wave_decay_prefix;
use crate::sea::kinematics::{
    wave_eval_depth, wave_eval_depth_rate, wave_ramp_rate, KinematicsScratch,
};

impl CpuSolver {
    /// The exact water values of the block of nodes `n0..n1` at the current time
    /// (empty in still water): an output time's in exact mode, and the kinetic
    /// energy's (a diagnostic that leaves the cache alone).
    pub(super) fn water_exact_now(&self, n0: usize, n1: usize) -> Water {
        let Some(seas) = &self.seas else {
            return Water::new();
        };
        let field = &self.wave_fields[self.block_sea(seas, n0)];
        let pos: Vec<f64> = self.r[n0..n1].iter().flat_map(|r| r.to_f64()).collect();
        let mut out = vec![0.0; (n1 - n0) * CACHE_STRIDE];
        evaluate_nodes(field, &pos, self.t, &mut out);
        out
    }

    /// Makes every block's kinematics cache cover the current time, refreshing from
    /// the current state where the next step would ([`BlockWaves::cover`]: at time 0,
    /// after a remesh or [`Self::restart_waves`], or when the time is past the cache's
    /// newer time). Nothing in exact mode or still water.
    pub(super) fn cover_waves_now(&mut self) {
        if self.exact_waves {
            return;
        }
        let (t, r, v) = (self.t, &self.r, &self.v);
        for (b, w) in self.layout.blocks.iter().zip(self.wave_blocks.iter_mut()) {
            let n0 = b.node_start as usize;
            let n = b.node_end as usize - n0;
            w.cover(t, n, |i| (r[n0 + i].to_f64(), v[n0 + i].to_f64()));
        }
    }

    /// The water values of block `bi` (nodes `n0..n1`) at the current time for an
    /// output-time evaluation: the kinematics the steps integrate, the block's cache
    /// interpolated at the current time (it must cover it: [`Self::cover_waves_now`]),
    /// or the exact sum in exact mode; empty in still water.
    pub(super) fn water_now(&self, bi: usize, n0: usize, n1: usize) -> Water {
        if self.exact_waves || self.wave_blocks.is_empty() {
            return self.water_exact_now(n0, n1);
        }
        let mut out = Water::new();
        self.wave_blocks[bi].interpolate(self.t, n1 - n0, &mut out);
        out
    }

    /// Starts every block's kinematics cache afresh: the next step (or output-time
    /// evaluation) evaluates the sum at the nodes' state then. Call it after writing
    /// [`Self::r`] or [`Self::v`] in a sea mid-run, whose cache holds values along
    /// the nodes' old paths.
    pub fn restart_waves(&mut self) {
        self.install_waves();
    }

    /// Per node (packed order): its depth band now and the number of components the
    /// decay pass of a refresh at the current state would sum
    /// ([`crate::sea::cut::wave_decay_prefix`], the GPU refresh's `wave_decay_prefix`):
    /// the evaluation depth and its rate from the node's position, velocity and the
    /// elevation and its rate over it, the speed `|v_h| + |zs'|`. A diagnostic for
    /// counting the GPU refresh's work (examples/wave_prefix_count.rs); empty in
    /// still water. (A refresh evaluates its `t1` values at the position predicted
    /// one interval ahead: this is the state now.) The third number: how many of the
    /// prefix's components leave out the seabed's term (`2 k (zs + h) > 39`, the
    /// shader's `wave_depth_decay`: one `wave_exp` instead of two).
    pub fn wave_decay_prefixes(&self) -> Vec<(usize, usize, usize)> {
        let Some(seas) = &self.seas else {
            return Vec::new();
        };
        let mut out = Vec::with_capacity(self.r.len());
        let mut scratch = KinematicsScratch::default();
        for (b, w) in self.layout.blocks.iter().zip(&self.wave_blocks) {
            let n0 = b.node_start as usize;
            let field = &self.wave_fields[self.block_sea(seas, n0)];
            let r_rate = wave_ramp_rate(self.t, field.ramp_duration);
            for i in n0..b.node_end as usize {
                let (p, v) = (self.r[i].to_f64(), self.v[i].to_f64());
                let (k, dk) = field.kinematics_rates_with(p, v, self.t, &mut scratch);
                let zs = wave_eval_depth(p[2], k.eta, field.depth, field.stretching);
                let zs_rate =
                    wave_eval_depth_rate(p[2], k.eta, field.depth, field.stretching, v[2], dk.eta);
                let s = v[0].hypot(v[1]) + zs_rate.abs();
                let m = wave_decay_prefix(&field.comps, zs, s, r_rate);
                let above_bed = zs + field.depth;
                let seabed_skip = field.comps[..m]
                    .iter()
                    .filter(|c| 2.0 * c.k * above_bed > 39.0)
                    .count();
                out.push((w.cache().band_of(i - n0), m, seabed_skip));
            }
        }
        out
    }
}
