//! `bodies.csv`: per body and output time, its pose and the total force and moment its
//! cables exert on it.
//!
//! The force is the sum, over the end nodes held on the body, of each node's
//! constraint reaction `F_k - M_k a_k` (every force on the node but the constraint's,
//! less its inertia: the force the cables, and a point mass at the end, exert on the
//! body there; the same reaction `end_forces.csv` reports). The moment is about the
//! body's reference point at that time: `sum (r_k - X) x F_k`, with `r_k` the node's
//! position.

use super::Body;
use crate::math::V3;
use crate::model::{Layout, Route};
use crate::output::BodyState;
use crate::step::Evaluation;
use std::sync::Arc;

/// The bodies of a layout and the constraints (route indices) held on each.
pub fn bodies_of(lay: &Layout) -> Vec<(Arc<Body>, Vec<usize>)> {
    let mut out: Vec<(Arc<Body>, Vec<usize>)> = Vec::new();
    for (c, r) in lay.routes.iter().enumerate() {
        if let Route::Body { body, .. } = r {
            match out.iter_mut().find(|(b, _)| Arc::ptr_eq(b, body)) {
                Some((_, cs)) => cs.push(c),
                None => out.push((body.clone(), vec![c])),
            }
        }
    }
    out
}

/// The state of a free or pinned body now, as its solver steps it.
#[derive(Clone, Debug)]
pub struct DynamicState {
    /// The body.
    pub body: Arc<Body>,
    /// Its kinematics at the reference point.
    pub state: super::BodyState,
    /// Roll, pitch, yaw, rad.
    pub angles: [f64; 3],
}

/// Total force (N) and moment (N m) about the body's reference point `x` from the
/// constraints `held` (route indices), given node positions `r` (packed order) and the
/// evaluation's reactions.
pub fn body_load(
    lay: &Layout,
    held: &[usize],
    r: &[[f64; 3]],
    reaction: &[[f64; 3]],
    x: V3<f64>,
) -> ([f64; 3], [f64; 3]) {
    let mut f = V3::<f64>::zero();
    let mut m = V3::<f64>::zero();
    for &c in held {
        let fk = V3::from_f64(reaction[c]);
        let rk = V3::from_f64(r[lay.constraint_node[c] as usize]);
        f += fk;
        m += (rk - x).cross(fk);
    }
    (f.to_f64(), m.to_f64())
}

/// Every body's pose and load at time `t`, from node positions `r` (packed order) and
/// the evaluation's reactions; free and pinned bodies at their states in `dynamic`.
pub fn body_states(
    lay: &Layout,
    t: f64,
    r: &[[f64; 3]],
    ev: &Evaluation,
    dynamic: &[DynamicState],
) -> Vec<BodyState> {
    let any_dynamic = !dynamic.is_empty();
    bodies_of(lay)
        .iter()
        .map(|(b, held)| {
            let (s, angles) = match dynamic.iter().find(|d| Arc::ptr_eq(&d.body, b)) {
                Some(d) => (d.state, d.angles),
                None => {
                    let d = b.dofs(t);
                    (b.state(t), [d.q[3], d.q[4], d.q[5] + b.pose.heading])
                }
            };
            let (force, moment) = body_load(lay, held, r, &ev.reaction, s.x);
            BodyState {
                name: b.name.clone(),
                position: [s.x.x, s.x.y, s.x.z],
                angles: angles.map(f64::to_degrees),
                force,
                moment,
                velocity: any_dynamic.then(|| {
                    let (v, w) = (s.v.to_f64(), s.omega.to_f64());
                    [v[0], v[1], v[2], w[0], w[1], w[2]]
                }),
            }
        })
        .collect()
}
