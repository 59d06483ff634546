//! The one harness that compares two runs of the same model (GPU against the CPU
//! reference, or one GPU kernel against the other), used by every run-against-run
//! test of this binary.
//!
//! A comparison takes a [`Snapshot`] of each run (positions, velocities, tensions,
//! reactions, in the layout's packed order) and finds, per quantity, where the two
//! differ most relative to the tolerance there ([`largest`]). A failed check names
//! that place in the model (cable, node or element, route) and prints both runs'
//! values, so a failure says what went wrong where, not only by how much.
//!
//! The round-off contract shared by the f64 comparisons ([`RoundOff`]): two runs whose
//! arithmetic differs only in round-off perturb each step by a few ulps of the quantity
//! involved, positions by about `eps L` (`L` the largest coordinate relative to its
//! block's mean, what the GPU's block origins leave) and velocities by `eps V` (`V` the
//! largest speed). A stable, damped model does not amplify such perturbations
//! exponentially, so after `N` steps the runs differ by at most about `N eps L` in
//! position, times a constant for the operations per step that round differently,
//! taken as 10. A position difference `dr` in the fastest mode (angular frequency
//! `omega_max = 2 / dt_stable`) comes with a velocity difference `omega_max dr`, plus
//! the velocity's own `N eps V`; it changes a strain by `dr / l0_min`, so a tension
//! by `EA dr / l0_min`, plus the strain's own round-off `eps EA` and `eps T_max`.
//! Reactions (`F - M a` at driven nodes) and end forces get the tension tolerance.

use cablesim::cpu::{CpuSolver, Evaluation};
use cablesim::gpu::GpuSolver;
use cablesim::model::Layout;

/// One run's state and evaluation at one time, in the packed order of its layout.
pub struct Snapshot {
    /// What ran (for messages): "CPU f64", "GPU f32 fused", ...
    pub label: String,
    /// Simulated time, s.
    pub t: f64,
    /// Node positions, m.
    pub r: Vec<[f64; 3]>,
    /// Node velocities, m/s.
    pub v: Vec<[f64; 3]>,
    /// Per element: axial force, N; per constraint: reaction, N (and the rest).
    pub eval: Evaluation,
}

impl Snapshot {
    /// The CPU solver's state now.
    pub fn cpu(label: impl Into<String>, s: &mut CpuSolver) -> Self {
        Snapshot {
            label: label.into(),
            t: s.t(),
            r: s.r.iter().map(|x| x.to_f64()).collect(),
            v: s.v.iter().map(|x| x.to_f64()).collect(),
            eval: s.evaluate().unwrap(),
        }
    }

    /// The GPU solver's state now (read back).
    pub fn gpu(label: impl Into<String>, s: &mut GpuSolver) -> Self {
        let (r, v) = s.state().unwrap();
        Snapshot {
            label: label.into(),
            t: s.t(),
            r,
            v,
            eval: s.evaluate().unwrap(),
        }
    }
}

/// A compared value: a scalar or a vector.
pub trait Value: Copy + std::fmt::Debug {
    /// The distance between two values (absolute difference, Euclidean distance).
    fn dist(self, other: Self) -> f64;
}

impl Value for f64 {
    fn dist(self, other: Self) -> f64 {
        (self - other).abs()
    }
}

impl Value for [f64; 3] {
    fn dist(self, other: Self) -> f64 {
        ((self[0] - other[0]).powi(2) + (self[1] - other[1]).powi(2) + (self[2] - other[2]).powi(2))
            .sqrt()
    }
}

pub use crate::common::dist;

/// Euclidean norm.
pub fn norm(a: [f64; 3]) -> f64 {
    a.dist([0.0; 3])
}

/// What an index of a compared array stands for in the layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// A node (packed index).
    Node,
    /// An element (packed index).
    Element,
    /// A constraint (index into `Layout::routes`).
    Route,
    /// A cable end: index `2 c` the start of cable `c`, `2 c + 1` its end.
    CableEnd,
}

impl Place {
    /// Where index `i` is in `lay`, in words.
    pub fn describe(self, lay: &Layout, i: usize) -> String {
        match self {
            Place::Node => {
                let c = lay.node_cable[i] as usize;
                format!(
                    "cable '{}' node {} (packed {i})",
                    lay.cables[c].name, lay.node_index_in_cable[i]
                )
            }
            Place::Element => {
                let c = &lay.cables[lay.elem_cable[i] as usize];
                let j = c.elements.iter().position(|&e| e as usize == i).unwrap();
                format!("cable '{}' element {j} (packed {i})", c.name)
            }
            Place::Route => {
                let n = lay.constraint_node[i] as usize;
                format!("route {i} at {}", Place::Node.describe(lay, n))
            }
            Place::CableEnd => format!(
                "cable '{}' {}",
                lay.cables[i / 2].name,
                ["start", "end"][i % 2]
            ),
        }
    }
}

/// Where two arrays differ most relative to their tolerance.
#[derive(Clone, Debug)]
pub struct Largest<V> {
    /// The difference there.
    pub diff: f64,
    /// The tolerance there.
    pub tol: f64,
    /// The index.
    pub at: usize,
    /// Both values there.
    pub a: V,
    pub b: V,
}

impl<V: Value> Largest<V> {
    /// `diff / tol`: at most 1 within the tolerance (0 for equal values, infinite for
    /// a NaN difference or any difference where the tolerance is 0).
    pub fn ratio(&self) -> f64 {
        score(self.diff, self.tol)
    }
}

fn score(diff: f64, tol: f64) -> f64 {
    if diff == 0.0 {
        0.0
    } else if diff.is_nan() {
        f64::INFINITY
    } else {
        diff / tol
    }
}

/// The index where `a` and `b` differ most relative to `tol(index)` (with a uniform
/// tolerance: where they differ most). `None` for empty arrays.
pub fn largest<V: Value>(a: &[V], b: &[V], tol: impl Fn(usize) -> f64) -> Option<Largest<V>> {
    assert_eq!(a.len(), b.len(), "compared arrays of different lengths");
    let mut worst: Option<Largest<V>> = None;
    for (i, (&x, &y)) in a.iter().zip(b).enumerate() {
        let d = x.dist(y);
        let tol = tol(i);
        let better = match &worst {
            None => true,
            Some(w) => score(d, tol) > w.ratio(),
        };
        if better {
            worst = Some(Largest {
                diff: d,
                tol,
                at: i,
                a: x,
                b: y,
            });
        }
    }
    worst
}

/// One check of one quantity between two labelled runs of the same layout.
pub struct Check<'a> {
    /// The test case, for messages.
    pub name: &'a str,
    /// The layout both runs share (for the place of a difference).
    pub lay: &'a Layout,
    /// The two runs' labels and times.
    pub a: (&'a str, f64),
    pub b: (&'a str, f64),
}

impl<'a> Check<'a> {
    /// A check between two snapshots of runs of `lay`.
    pub fn new(name: &'a str, lay: &'a Layout, a: &'a Snapshot, b: &'a Snapshot) -> Self {
        Check {
            name,
            lay,
            a: (&a.label, a.t),
            b: (&b.label, b.t),
        }
    }

    /// Finds where `a` and `b` (values of `quantity` in `unit` at each `place`) differ
    /// most relative to `tol(index)`, asserts that it is within, and returns it. The
    /// failure names the place and prints both values.
    pub fn within<V: Value>(
        &self,
        quantity: &str,
        unit: &str,
        place: Place,
        a: &[V],
        b: &[V],
        tol: impl Fn(usize) -> f64,
    ) -> Option<Largest<V>> {
        let w = largest(a, b, tol)?;
        // Written so that a NaN fails.
        assert!(
            w.diff <= w.tol,
            "{}",
            self.message(quantity, unit, place, &w)
        );
        Some(w)
    }

    /// [`Check::within`] for one value, at index `at` of `place`.
    #[allow(clippy::too_many_arguments)]
    pub fn one<V: Value>(
        &self,
        quantity: &str,
        unit: &str,
        place: Place,
        at: usize,
        a: V,
        b: V,
        tol: f64,
    ) -> Largest<V> {
        let w = Largest {
            diff: a.dist(b),
            tol,
            at,
            a,
            b,
        };
        assert!(
            w.diff <= w.tol,
            "{}",
            self.message(quantity, unit, place, &w)
        );
        w
    }

    /// The failure message of [`Check::within`] for `w`.
    pub fn message<V: Value>(
        &self,
        quantity: &str,
        unit: &str,
        place: Place,
        w: &Largest<V>,
    ) -> String {
        format!(
            "{}: {quantity} differ most at {}: by {:e} {unit} > tolerance {:e} {unit}\n  \
             {} (t = {} s): {:?}\n  {} (t = {} s): {:?}",
            self.name,
            place.describe(self.lay, w.at),
            w.diff,
            w.tol,
            self.a.0,
            self.a.1,
            w.a,
            self.b.0,
            self.b.1,
            w.b
        )
    }
}

/// Largest coordinate relative to its block's mean position, plus 1 m: the position
/// scale `L` of the round-off bound (what the GPU's block origins leave).
pub fn origin_scale(lay: &Layout, r: &[[f64; 3]]) -> f64 {
    let mut s = 0.0f64;
    for b in &lay.blocks {
        let (n0, n1) = (b.node_start as usize, b.node_end as usize);
        let k = (n1 - n0) as f64;
        let mean = r[n0..n1].iter().fold([0.0; 3], |m, p| {
            [m[0] + p[0] / k, m[1] + p[1] / k, m[2] + p[2] / k]
        });
        for p in &r[n0..n1] {
            s = s.max(dist(*p, mean) + 1.0);
        }
    }
    s
}

/// The round-off bounds of the module doc after `steps` steps at machine epsilon
/// `eps`, for a model of largest axial stiffness `ea` (N), shortest element `l0_min`
/// (m) and fastest mode `omega` (rad/s), scaled by the reference run's state.
#[derive(Clone, Copy, Debug)]
pub struct RoundOff {
    /// Positions, m.
    pub r: f64,
    /// Velocities, m/s.
    pub v: f64,
    /// Tensions, reactions and end forces, N.
    pub force: f64,
    /// The largest tension of the reference, N (`T_max`).
    pub scale_t: f64,
}

impl RoundOff {
    pub fn new(
        lay: &Layout,
        reference: &Snapshot,
        steps: u64,
        eps: f64,
        ea: f64,
        l0_min: f64,
        omega: f64,
    ) -> Self {
        let n = steps as f64;
        let scale_l = origin_scale(lay, &reference.r);
        let scale_v = reference
            .v
            .iter()
            .map(|v| norm(*v))
            .fold(0.0, f64::max)
            .max(1e-3);
        let scale_t = reference
            .eval
            .tension
            .iter()
            .map(|t| t.abs())
            .fold(0.0, f64::max);
        let r = 10.0 * n * eps * scale_l;
        let v = omega * r + 10.0 * n * eps * scale_v;
        let force = ea * (r / l0_min + 100.0 * eps) + 100.0 * eps * scale_t;
        RoundOff {
            r,
            v,
            force,
            scale_t,
        }
    }

    /// Asserts positions, velocities, tensions and reactions of `a` within the bounds
    /// of `b` (the reference); returns the largest differences in that order.
    pub fn check(&self, name: &str, lay: &Layout, a: &Snapshot, b: &Snapshot) -> Diffs {
        let c = Check::new(name, lay, a, b);
        let (r, v, t, re) = (self.r, self.v, self.force, self.force);
        let zero = || Largest {
            diff: 0.0,
            tol: 1.0,
            at: 0,
            a: [0.0; 3],
            b: [0.0; 3],
        };
        let r = c.within("positions", "m", Place::Node, &a.r, &b.r, |_| r);
        let v = c.within("velocities", "m/s", Place::Node, &a.v, &b.v, |_| v);
        let tension = c.within(
            "tensions",
            "N",
            Place::Element,
            &a.eval.tension,
            &b.eval.tension,
            |_| t,
        );
        let reaction = c.within(
            "reactions",
            "N",
            Place::Route,
            &a.eval.reaction,
            &b.eval.reaction,
            |_| re,
        );
        Diffs {
            r: r.unwrap_or_else(zero),
            v: v.unwrap_or_else(zero),
            tension: tension.unwrap_or(Largest {
                diff: 0.0,
                tol: 1.0,
                at: 0,
                a: 0.0,
                b: 0.0,
            }),
            reaction: reaction.unwrap_or_else(zero),
        }
    }
}

/// The largest differences of one [`RoundOff::check`].
pub struct Diffs {
    pub r: Largest<[f64; 3]>,
    pub v: Largest<[f64; 3]>,
    pub tension: Largest<f64>,
    pub reaction: Largest<[f64; 3]>,
}

impl Diffs {
    /// One line: each largest difference, its tolerance and where it is.
    pub fn report(&self, lay: &Layout) -> String {
        format!(
            "|dr| {:.3e} m (tol {:.1e}, at {}), |dv| {:.3e} m/s (tol {:.1e}), |dT| {:.3e} N (tol {:.1e}, at {}), |dReaction| {:.3e} N",
            self.r.diff,
            self.r.tol,
            Place::Node.describe(lay, self.r.at),
            self.v.diff,
            self.v.tol,
            self.tension.diff,
            self.tension.tol,
            Place::Element.describe(lay, self.tension.at),
            self.reaction.diff,
        )
    }
}

/// Per cable, its unstretched length, m.
pub fn cable_lengths(lay: &Layout) -> Vec<f64> {
    lay.cables
        .iter()
        .map(|c| c.elements.iter().map(|&e| lay.elem_l0[e as usize]).sum())
        .collect()
}

/// The f32 position contract: every node of every cable of `a` within `frac` of its
/// cable's unstretched length of `b`'s; returns the worst, as a fraction of the length.
/// A node that several cables share (a knot) is held to the shortest one's.
pub fn nodes_within_length(c: &Check, a: &[[f64; 3]], b: &[[f64; 3]], frac: f64) -> f64 {
    let length = cable_lengths(c.lay);
    let mut node_length = vec![f64::INFINITY; a.len()];
    for (cable, l) in c.lay.cables.iter().zip(&length) {
        for &i in &cable.nodes {
            node_length[i as usize] = node_length[i as usize].min(*l);
        }
    }
    let tol = |i: usize| frac * node_length[i];
    c.within("positions", "m", Place::Node, a, b, tol)
        .map_or(0.0, |w| w.ratio() * frac)
}

/// Per cable, the end forces (`output::end_forces`, what `end_forces.csv` reports) of
/// its start and end, N: index `2 c` and `2 c + 1` ([`Place::CableEnd`]).
pub fn end_forces(lay: &Layout, ev: &Evaluation) -> Vec<[f64; 3]> {
    lay.cables
        .iter()
        .flat_map(|c| {
            let f = cablesim::output::end_forces(lay, ev, c);
            [f.start, f.end]
        })
        .collect()
}
