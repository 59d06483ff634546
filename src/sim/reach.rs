//! How high each sea's nodes reach over a run, for the waves' kinematics cache: the
//! refresh interval grows with the depth the nodes stay at (`sea::schedule`), so the
//! run bounds it once, before anything steps, the same for the CPU and the GPU path
//! (both build their schedules from the one [`SeaSet`] with its `reach`), and checks
//! at every output time that no node went above it.
//!
//! The bound of a sea ([`sea_reach`]): the highest of its nodes' starting heights and
//! of the heights their held ends' routes reach over the run (sampled every
//! [`ROUTE_SAMPLE`] s, each sample raised by what its vertical velocity and
//! acceleration could add within half a sample: a vessel's RAO-driven fairleads are
//! followed through the whole run), plus [`REACH_MARGIN`]. A free node rising more
//! than the margin above where it started and above its ends (a float, a line lifted
//! by a current) breaks the bound: [`ReachWatch`] warns once, naming the cable.

use crate::model::{Layout, Route, NO_CONSTRAINT};
use crate::output::Snapshot;
use crate::sea::SeaSet;

/// Added to the highest height found, m: what a free node near a held end may rise
/// above it (a line's top elements follow its fairlead, not exactly).
pub const REACH_MARGIN: f64 = 2.0;

/// Spacing of the samples of a held end's route over the run, s.
pub const ROUTE_SAMPLE: f64 = 1.0;

/// The highest heights `routes` reach over `[0, duration]`, m: samples every
/// [`ROUTE_SAMPLE`] s, each raised by `|v_z| h / 2 + |a_z| h^2 / 8` (what the motion
/// could add between samples), and a table's rows. All routes at each time in turn:
/// the ends on one body then share its state at that time (`Body::state` keeps it),
/// one RAO evaluation per body and sample.
pub fn route_tops(routes: &[&Route], duration: f64) -> Vec<f64> {
    let h = ROUTE_SAMPLE;
    let n = (duration / h).ceil().max(0.0) as u64;
    let mut top = vec![f64::NEG_INFINITY; routes.len()];
    for k in 0..=n {
        let t = (k as f64 * h).min(duration);
        for (top, route) in top.iter_mut().zip(routes) {
            let s = route.eval(t);
            *top = top.max(s.r[2] + s.v[2].abs() * h / 2.0 + s.a[2].abs() * h * h / 8.0);
        }
    }
    for (top, route) in top.iter_mut().zip(routes) {
        if let Route::Table { p, .. } = route {
            *top = p.iter().map(|p| p[2]).fold(*top, f64::max);
        }
    }
    top
}

/// Per sea of `seas`: the highest height its nodes reach over a run of `duration` s
/// from positions `pos` (packed order of `lay`), m (see the module doc); infinite
/// (unknown) for a sea with no nodes.
pub fn sea_reach(lay: &Layout, pos: &[[f64; 3]], seas: &SeaSet, duration: f64) -> Vec<f64> {
    let mut reach = vec![f64::NEG_INFINITY; seas.seas.len()];
    // Only the routes that hold a node of a sea with waves.
    let in_waves = |i: usize| !seas.seas[seas.sea_of_cable(lay.node_cable[i] as usize)].is_still();
    let mut held: Vec<usize> = (0..pos.len())
        .filter(|&i| in_waves(i) && lay.node_constraint[i] != NO_CONSTRAINT)
        .map(|i| lay.node_constraint[i] as usize)
        .collect();
    held.sort_unstable();
    held.dedup();
    let routes: Vec<&Route> = held.iter().map(|&k| &lay.routes[k]).collect();
    let tops = route_tops(&routes, duration);
    for (i, p) in pos.iter().enumerate() {
        let q = seas.sea_of_cable(lay.node_cable[i] as usize);
        let mut z = p[2];
        let k = lay.node_constraint[i];
        if k != NO_CONSTRAINT {
            if let Ok(j) = held.binary_search(&(k as usize)) {
                z = z.max(tops[j]);
            }
        }
        reach[q] = reach[q].max(z);
    }
    reach
        .iter()
        .map(|&z| {
            if z.is_finite() {
                z + REACH_MARGIN
            } else {
                f64::INFINITY
            }
        })
        .collect()
}

/// Checks at output times that every cable's nodes stay under their sea's reach, and
/// warns the first time one does not.
#[derive(Clone, Debug)]
pub struct ReachWatch {
    /// Per cable: its sea's reach, m.
    cable_reach: Vec<f64>,
    #[doc(hidden)]
    pub warned: bool,
}

impl ReachWatch {
    /// A watch over `n_cables` cables of `seas` (with its `reach` set), or none when
    /// no sea has waves or no reach is set.
    pub fn new(seas: &SeaSet, n_cables: usize) -> Option<Self> {
        (!seas.is_still() && !seas.reach.is_empty()).then(|| Self {
            cable_reach: (0..n_cables)
                .map(|c| {
                    let q = seas.sea_of_cable(c);
                    if seas.seas[q].is_still() {
                        f64::INFINITY
                    } else {
                        seas.reach_of(q)
                    }
                })
                .collect(),
            warned: false,
        })
    }

    /// The first cable of `snap` with a node above its sea's reach: `(cable, node,
    /// height)`.
    pub fn breach(&self, snap: &Snapshot) -> Option<(usize, usize, f64)> {
        snap.cables.iter().enumerate().find_map(|(c, cs)| {
            let reach = self.cable_reach.get(c).copied().unwrap_or(f64::INFINITY);
            cs.positions
                .iter()
                .position(|p| p[2] > reach)
                .map(|i| (c, i, cs.positions[i][2]))
        })
    }

    /// Warns (once per run) when a node of `snap` is above its sea's reach.
    pub fn check(&mut self, snap: &Snapshot) {
        if self.warned {
            return;
        }
        if let Some((c, i, z)) = self.breach(snap) {
            self.warned = true;
            log::warn!(
                "waves: node {i} of cable '{}' is at z = {z:.2} m at t = {:.2} s, above the \
                 {:.2} m its sea's nodes were bounded by when the run was prepared (route \
                 ends over the run, starting heights, plus {REACH_MARGIN} m): the wave \
                 kinematics cache refreshes at an interval set for nodes that stay under \
                 that height, so the wave loads near this node are less accurate than the \
                 cache tolerance (docs/src/sea_states.md, \"Cost: the per-node kinematics \
                 cache\"); warned once",
                snap.cables[c].name,
                snap.time,
                self.cable_reach[c]
            );
        }
    }
}
