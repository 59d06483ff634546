//! Checkpoints of a [`CpuSolver`]: its state at one step, to go back to.

use super::CpuSolver;
use crate::cpu::water::BlockWaves;
use crate::math::V3;

type V = V3<f64>;

/// The state of a [`CpuSolver`] at one step: positions and velocities where that is all
/// it carries from step to step (a fixed mesh in still water: element loads and scratch
/// are recomputed each step); with them the blocks' kinematics caches in waves (a
/// fixed mesh too: what else the solver holds does not change from step to step); the
/// whole solver where the mesh changes (winch cables: mesh and payout) or the elements
/// carry a state of their own (viscoelastic lines).
#[derive(Clone)]
pub struct CpuCheckpoint {
    /// Steps taken.
    pub steps: u64,
    saved: Saved,
    /// Free and pinned bodies' states (none without).
    free: Option<Box<crate::cpu::free::FreeRun>>,
}

#[derive(Clone)]
enum Saved {
    State {
        t: f64,
        node_steps: u64,
        r: Vec<V>,
        v: Vec<V>,
    },
    /// A fixed mesh in waves: the state and the blocks' caches (a checkpoint is taken
    /// at each output time, and a copy of the whole solver cost more than the caches).
    Waves {
        t: f64,
        node_steps: u64,
        r: Vec<V>,
        v: Vec<V>,
        wave_blocks: Vec<BlockWaves>,
    },
    Whole(Box<CpuSolver>),
}

impl std::fmt::Debug for CpuCheckpoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CpuCheckpoint")
            .field("steps", &self.steps)
            .finish_non_exhaustive()
    }
}

impl CpuSolver {
    /// The state now, to go back to with [`CpuSolver::restore`].
    pub fn checkpoint(&self) -> Option<CpuCheckpoint> {
        // Viscoelastic lines carry a state per element: the whole solver.
        let saved = if self.ale.is_some() || !self.failures.is_empty() || !self.visco.is_empty() {
            Saved::Whole(Box::new(self.clone()))
        } else if !self.wave_blocks.is_empty() {
            Saved::Waves {
                t: self.t,
                node_steps: self.node_steps,
                r: self.r.clone(),
                v: self.v.clone(),
                wave_blocks: self.wave_blocks.clone(),
            }
        } else {
            Saved::State {
                t: self.t,
                node_steps: self.node_steps,
                r: self.r.clone(),
                v: self.v.clone(),
            }
        };
        Some(CpuCheckpoint {
            steps: self.steps,
            saved,
            free: self.free.clone(),
        })
    }

    /// Goes back to the state `cp`, taken from this solver.
    pub fn restore(&mut self, cp: &CpuCheckpoint) {
        if cp.free.is_some() {
            self.free.clone_from(&cp.free);
        }
        match &cp.saved {
            Saved::State {
                t,
                node_steps,
                r,
                v,
            } => {
                self.steps = cp.steps;
                self.t = *t;
                self.node_steps = *node_steps;
                self.r.clone_from(r);
                self.v.clone_from(v);
            }
            Saved::Waves {
                t,
                node_steps,
                r,
                v,
                wave_blocks,
            } => {
                self.steps = cp.steps;
                self.t = *t;
                self.node_steps = *node_steps;
                self.r.clone_from(r);
                self.v.clone_from(v);
                self.wave_blocks.clone_from(wave_blocks);
            }
            Saved::Whole(w) => *self = (**w).clone(),
        }
    }
}
