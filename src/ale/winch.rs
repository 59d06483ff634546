//! Winches and their remeshing decisions ([`WinchTracker`]).

use super::schedule::PayoutSchedule;
use std::sync::Arc;

/// Insert a node when the variable element exceeds this many standard lengths.
pub const INSERT_RATIO: f64 = 1.5;
/// Delete a node when the variable element falls below this many standard lengths.
pub const DELETE_RATIO: f64 = 0.5;

/// Which end of its cable a winch is at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WinchEnd {
    /// The cable's start node (its first node).
    Start,
    /// The cable's end node (its last node).
    End,
}

/// A winch paying out or hauling in a cable (the book's "ALE winches" chapter, docs/src/model/winches.md).
#[derive(Clone, Debug, PartialEq)]
pub struct Winch {
    /// Index of the cable (into `ModelDef::cables`, the same order as `Layout::cables`).
    pub cable: usize,
    /// The end the winch is at; that node must be held (fixed or on a route).
    pub end: WinchEnd,
    /// The payout schedule.
    pub schedule: Arc<PayoutSchedule>,
    /// Drum capacity: the largest deployed length, m (`f64::INFINITY`: no limit).
    pub drum_length: f64,
    /// Standard element length `l_s` of the remeshing rules, m.
    pub element_length: f64,
}

/// Why a winch cannot follow its schedule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WinchLimit {
    /// The schedule pays out more than the drum holds.
    Drum {
        /// Deployed length asked for, m.
        length: f64,
        /// The drum's capacity, m.
        drum: f64,
    },
    /// The schedule hauls in past the cable's last node.
    LastNode {
        /// Deployed length asked for, m.
        length: f64,
        /// The shortest the last element may be (`0.5 l_s`), m.
        min: f64,
    },
}

impl std::fmt::Display for WinchLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            WinchLimit::Drum { length, drum } => write!(
                f,
                "payout past the drum's capacity: the schedule asks for {length:.6} m deployed, the drum holds drum_length = {drum} m"
            ),
            WinchLimit::LastNode { length, min } => write!(
                f,
                "hauled in past the cable's last node: the schedule asks for {length:.6} m deployed, but with one element left it cannot be shorter than 0.5 x the standard element length = {min} m"
            ),
        }
    }
}

/// One change of a winch cable's mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeshOp {
    /// Insert a material node on the variable element at `xi = l_s / l0_v` from the
    /// material node `m` towards the winch.
    Insert {
        /// Where, as a fraction of the variable element from `m`.
        xi: f64,
        /// The variable element's unstretched length before the insertion, m.
        l0_before: f64,
    },
    /// Delete the material node `m` next to the winch; the variable element absorbs
    /// its neighbour.
    Delete,
}

/// The kinematic mesh state of one winch cable: the unstretched lengths of its fixed
/// elements and the variable element's length as a function of the payout. It makes
/// every remeshing decision; the stepper moves nodes accordingly.
#[derive(Clone, Debug, PartialEq)]
pub struct WinchTracker {
    /// Standard element length `l_s`, m.
    pub l_std: f64,
    /// Drum capacity, m.
    pub drum: f64,
    /// Deployed length at `t = 0` (sum of the initial `l0`), m.
    pub length0: f64,
    /// Unstretched lengths of the fixed elements, from the far end towards the winch
    /// (the last one is next to the variable element), m.
    pub fixed: Vec<f64>,
    /// The variable element's `l0` at the last remeshing, m.
    pub base_l0: f64,
    /// The payout `dL` at the last remeshing, m.
    pub base_dl: f64,
    /// Nodes inserted so far.
    pub inserted: u64,
    /// Nodes deleted so far.
    pub deleted: u64,
}

impl WinchTracker {
    /// The state at `t = 0` of a cable whose element lengths, start to end, are
    /// `l0s`, with payout `dl0` at `t = 0` (zero for every schedule).
    pub fn new(w: &Winch, l0s: &[f64], dl0: f64) -> Self {
        let mut fixed: Vec<f64> = l0s.to_vec();
        let base_l0 = match w.end {
            WinchEnd::Start => {
                let v = fixed.remove(0);
                fixed.reverse();
                v
            }
            WinchEnd::End => fixed.pop().expect("a cable has an element"),
        };
        let length0 = l0s.iter().sum();
        Self {
            l_std: w.element_length,
            drum: w.drum_length,
            length0,
            fixed,
            base_l0,
            base_dl: dl0,
            inserted: 0,
            deleted: 0,
        }
    }

    /// Number of elements of the cable now.
    pub fn n_elements(&self) -> usize {
        self.fixed.len() + 1
    }

    /// The variable element's unstretched length at payout `dl`, m.
    #[inline]
    pub fn variable_l0(&self, dl: f64) -> f64 {
        self.base_l0 + (dl - self.base_dl)
    }

    /// Deployed length at payout `dl`, m.
    #[inline]
    pub fn deployed(&self, dl: f64) -> f64 {
        self.length0 + dl
    }

    /// Physical coordinates `p` of the nodes, from the far end (`p = 0`) to the winch
    /// node (`p = L`), at payout `dl`, m.
    pub fn physical_coordinates(&self, dl: f64) -> Vec<f64> {
        let mut p = Vec::with_capacity(self.fixed.len() + 2);
        let mut s = 0.0;
        p.push(s);
        for &l in &self.fixed {
            s += l;
            p.push(s);
        }
        p.push(s + self.variable_l0(dl));
        p
    }

    /// True when the mesh must change (or a limit is passed) at payout `dl`.
    #[inline]
    pub fn needs_action(&self, dl: f64) -> bool {
        let l = self.variable_l0(dl);
        // Written so that NaN asks for action (and then fails).
        !(l <= INSERT_RATIO * self.l_std
            && l >= DELETE_RATIO * self.l_std
            && self.deployed(dl) <= self.drum_limit())
    }

    fn drum_limit(&self) -> f64 {
        self.drum * (1.0 + 1e-12)
    }

    /// Applies the remeshing rules at payout `dl`; returns the operations in order, or
    /// the limit the schedule passes (the mesh is then left as it was).
    pub fn remesh(&mut self, dl: f64) -> Result<Vec<MeshOp>, WinchLimit> {
        let length = self.deployed(dl);
        if length > self.drum_limit() || length.is_nan() {
            return Err(WinchLimit::Drum {
                length,
                drum: self.drum,
            });
        }
        let mut ops = Vec::new();
        loop {
            let l = self.variable_l0(dl);
            if l > INSERT_RATIO * self.l_std {
                ops.push(MeshOp::Insert {
                    xi: self.l_std / l,
                    l0_before: l,
                });
                self.fixed.push(self.l_std);
                self.base_l0 = l - self.l_std;
                self.base_dl = dl;
                self.inserted += 1;
            } else if l < DELETE_RATIO * self.l_std {
                let Some(f) = self.fixed.pop() else {
                    return Err(WinchLimit::LastNode {
                        length,
                        min: DELETE_RATIO * self.l_std,
                    });
                };
                ops.push(MeshOp::Delete);
                self.base_l0 = l + f;
                self.base_dl = dl;
                self.deleted += 1;
            } else {
                return Ok(ops);
            }
        }
    }

    /// Follows the schedule over the step times `(step0 + k) dt`, `k = 1..=nsteps`,
    /// without dynamics: the mesh sequence the stepper will go through. Returns the
    /// fewest elements reached, or the first step time at which a limit is passed.
    pub fn scan(
        &mut self,
        schedule: &PayoutSchedule,
        dt: f64,
        step0: u64,
        nsteps: u64,
    ) -> Result<usize, (f64, WinchLimit)> {
        let mut fewest = self.n_elements();
        for k in 1..=nsteps {
            let t = (step0 + k) as f64 * dt;
            let dl = schedule.eval(t).dl;
            if self.needs_action(dl) {
                self.remesh(dl).map_err(|e| (t, e))?;
                fewest = fewest.min(self.n_elements());
            }
        }
        Ok(fewest)
    }
}
