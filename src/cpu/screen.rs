//! Screen-model net loads on the CPU path (docs/src/model/screen.md): each knot of a
//! screen net gathers a quarter of the force of every panel it is a corner of
//! (`physics::screen_panel_force`), from the state at the start of the step, for the
//! general passes ([`super::passes`]) and the network fast path ([`super::chain`]).
//! The GPU path computes the same per knot (`screen_knot_force` in WGSL).

use super::water::node_water;
use crate::math::V3;
use crate::model::screen::knot_panels;
use crate::model::{Layout, ScreenKnot};
use crate::physics::screen_panel_force;

type V = V3<f64>;

/// The force of knot `k`'s panels on it: a quarter of each. `pos(i)`, `vel(i)` give
/// node `i`'s (packed index) position and velocity; `wave(i)` its wave velocity
/// (`None` in still water). The water at a panel is the current at the height of its
/// centre plus the mean of its corners' wave velocities.
#[inline]
pub(crate) fn screen_knot_force(
    lay: &Layout,
    k: &ScreenKnot,
    pos: impl Fn(usize) -> V,
    vel: impl Fn(usize) -> V,
    wave: impl Fn(usize) -> Option<[f64; 3]>,
) -> V {
    let co = lay.screen.nets[k.net as usize].coefs(lay.env.water_density, [0.0, 0.0]);
    let current = &lay.currents[lay.node_current[k.node as usize] as usize];
    let mut f = V::zero();
    for c in knot_panels(k) {
        let p = c.map(|i| pos(i as usize));
        let v = c.map(|i| vel(i as usize));
        let zc = 0.25 * (p[0].z + p[1].z + p[2].z + p[3].z);
        let mut u = current.at(zc);
        let mut uw = V::zero();
        for &i in &c {
            if let Some(w) = wave(i as usize) {
                uw += V::from_f64(w);
            }
        }
        u += uw * 0.25;
        f += screen_panel_force(&co, p, v, u) * 0.25;
    }
    f
}

/// The screen forces on the knots of the block of nodes `n0..n0 + r.len()` (block-local
/// `r`, `v`, water `w` as [`node_water`] reads it, empty in still water), into `out`
/// as `(block-local node, force)` sorted by node; cleared first.
pub(crate) fn screen_block_forces(
    lay: &Layout,
    n0: usize,
    r: &[V],
    v: &[V],
    w: &[f64],
    out: &mut Vec<(usize, V)>,
) {
    out.clear();
    for k in lay.screen.knots_in(n0 as u32, (n0 + r.len()) as u32) {
        let f = screen_knot_force(
            lay,
            k,
            |i| r[i - n0],
            |i| v[i - n0],
            |i| (!w.is_empty()).then(|| node_water(w, i - n0).1),
        );
        out.push((k.node as usize - n0, f));
    }
}
