//! What a step of either backend yields, shared by the CPU and GPU solvers: the
//! failure of a step, the loads of a state, a winch cable's standing, and the blow-up
//! check that ends a run.

use crate::math::V3;
use crate::options::SolverOptions;
use crate::physics::ElementLoads;

type V = V3<f64>;

/// Why a step could not complete (in packed indices; the solvers name them).
#[derive(Clone, Debug, PartialEq)]
pub enum StepFailure {
    /// A node's state is non-finite or absurd.
    Diverged {
        /// Packed node index.
        node: usize,
        /// Simulated time, s.
        time: f64,
        /// What was found.
        what: String,
    },
    /// An element frame is singular.
    Singular {
        /// Packed element index.
        element: usize,
        /// Simulated time, s.
        time: f64,
        /// The frame.
        frame: &'static str,
        /// Why.
        reason: String,
    },
}

/// Loads and reactions of one state, evaluated without stepping.
#[derive(Clone, Debug, Default)]
pub struct Evaluation {
    /// Per node: acceleration, m/s^2; with [`Self::picked`], only the picked elements'
    /// end nodes', in the order of [`Self::picked_nodes`]. Read them through
    /// [`Self::node_acc`].
    pub acc: Vec<[f64; 3]>,
    /// Per node: total force on the node, N (empty with [`Self::picked`]).
    pub force: Vec<[f64; 3]>,
    /// Per element: axial force, N.
    pub tension: Vec<f64>,
    /// Per constraint: the force the cable exerts on its support, `F_k - M_k a_k`, N.
    pub reaction: Vec<[f64; 3]>,
    /// Per element: its loads (tangent, axial force, half external load, half masses);
    /// with [`Self::picked`], only those elements', in its order. Read them through
    /// [`Self::element`].
    pub elements: Vec<ElementLoads<f64>>,
    /// The elements [`Self::elements`] holds, ascending, when it holds only some (the
    /// outputs' evaluation keeps those the outputs read, not every element's 104 bytes);
    /// `None`: every element.
    pub picked: Option<Vec<u32>>,
    /// With [`Self::picked`]: the picked elements' end nodes, ascending (whose
    /// accelerations [`Self::acc`] holds).
    pub picked_nodes: Vec<u32>,
}

impl Evaluation {
    /// Node `i`'s acceleration, m/s^2.
    ///
    /// # Panics
    /// If the evaluation holds only some nodes' and not `i`'s.
    pub fn node_acc(&self, i: u32) -> [f64; 3] {
        match &self.picked {
            None => self.acc[i as usize],
            Some(_) => {
                let k = self
                    .picked_nodes
                    .binary_search(&i)
                    .expect("an end node of an element the evaluation was asked to keep");
                self.acc[k]
            }
        }
    }

    /// Element `e`'s loads.
    ///
    /// # Panics
    /// If the evaluation holds only some elements and not `e`.
    pub fn element(&self, e: u32) -> &ElementLoads<f64> {
        match &self.picked {
            None => &self.elements[e as usize],
            Some(p) => {
                let k = p
                    .binary_search(&e)
                    .expect("an element the evaluation was asked to keep");
                &self.elements[k]
            }
        }
    }
}

/// Where a winch cable stands (ALE-GLMF, [`crate::ale`]).
#[derive(Clone, Debug, PartialEq)]
pub struct WinchStatus {
    /// Cable index (into `Layout::cables`).
    pub cable: usize,
    /// Deployed unstretched length `L(t)`, m.
    pub deployed_length: f64,
    /// Unstretched length of the variable element (next to the winch) now, m.
    pub variable_l0: f64,
    /// Physical coordinate `p` of each node of the cable, in the cable's node order
    /// (start to end), m: unstretched arc length from the far end.
    pub physical_coordinates: Vec<f64>,
    /// Elements of the cable now.
    pub elements: usize,
    /// Nodes inserted so far.
    pub inserted: u64,
    /// Nodes deleted so far.
    pub deleted: u64,
}

/// The blow-up check of a node's new state: `None` when sane, else what was found (a
/// non-finite state, a speed over `opts.max_speed`, a position farther than
/// `opts.max_distance` from the origin).
#[inline(always)]
pub fn blow_up(opts: &SolverOptions, r: V, v: V) -> Option<String> {
    // Written so NaN fails the comparisons.
    if v.max_abs() < opts.max_speed && r.max_abs() < opts.max_distance {
        return None;
    }
    Some(what_blew_up(opts, r, v))
}

/// What is wrong with a node state that failed [`blow_up`].
#[cold]
fn what_blew_up(opts: &SolverOptions, r: V, v: V) -> String {
    if !r.is_finite() || !v.is_finite() {
        format!(
            "non-finite state (position {:?}, velocity {:?})",
            r.to_f64(),
            v.to_f64()
        )
    } else if v.max_abs() >= opts.max_speed {
        format!(
            "speed {:.3e} m/s over the limit {:.1e} m/s",
            v.norm(),
            opts.max_speed
        )
    } else {
        format!(
            "position {:?} farther than {:.1e} m from the origin",
            r.to_f64(),
            opts.max_distance
        )
    }
}

/// The failure for node `node` (packed index) found in state `r`, `v` at `time`.
pub fn diverged(opts: &SolverOptions, r: V, v: V, node: usize, time: f64) -> StepFailure {
    StepFailure::Diverged {
        node,
        time,
        what: what_blew_up(opts, r, v),
    }
}
