//! `nets.csv`'s rows: each cylindrical net's enclosed volume and the water's force on
//! it, formed from a state read back and its evaluation, so that both backends give
//! them alike (docs/src/cage.md, "Outputs").

use super::sink::NetState;
use crate::model::cage::{enclosed_volume, NetInfo};
use crate::model::Layout;
use crate::step::Evaluation;

/// The states of the cylindrical nets among `nets` (a panel encloses nothing and is left
/// out) from the packed positions `r`, velocities `v` and the evaluation `ev` of the same
/// state.
pub fn net_states(
    lay: &Layout,
    ev: &Evaluation,
    r: &[[f64; 3]],
    v: &[[f64; 3]],
    nets: &[NetInfo],
) -> Vec<NetState> {
    nets.iter()
        .filter(|n| n.reference_volume > 0.0)
        .map(|n| {
            let knots: Vec<[f64; 3]> = (0..n.rows)
                .flat_map(|row| (0..n.around).map(move |col| (row, col)))
                .map(|(row, col)| r[lay.cables[n.knot_cable(row, col)].nodes[0] as usize])
                .collect();
            let volume = enclosed_volume(&knots, n.around);
            // Each element's external load is `2 f_half`: drag, the water-acceleration
            // load and the weight less buoyancy, which is vertical.
            let mut force = [0.0; 2];
            for c in &lay.cables[n.twines.clone()] {
                for &e in &c.elements {
                    let f = ev.element(e).f_half;
                    force[0] += 2.0 * f.x;
                    force[1] += 2.0 * f.y;
                }
            }
            // A screen-model net: its panels' loads, each whole (the sum of its knots'
            // quarters), from the state and the current.
            let fs = crate::cpu::screen::screen_net_force(lay, r, v, &knots_nodes(lay, n));
            force[0] += fs[0];
            force[1] += fs[1];
            // The collar's nodes, each once (a ring cable's last node is the next one's
            // first), or the top knots.
            let ring: Vec<usize> = if n.collar.is_empty() {
                (0..n.around)
                    .map(|col| lay.cables[n.knot_cable(0, col)].nodes[0] as usize)
                    .collect()
            } else {
                lay.cables[n.collar.clone()]
                    .iter()
                    .flat_map(|c| c.nodes[..c.nodes.len() - 1].iter().map(|&i| i as usize))
                    .collect()
            };
            let collar_z = ring.iter().map(|&i| r[i][2]).sum::<f64>() / ring.len() as f64;
            let top_z = knots[..n.around].iter().map(|k| k[2]).sum::<f64>() / n.around as f64;
            let u = lay.currents[n.current].at(top_z.min(0.0));
            NetState {
                name: n.name.clone(),
                volume,
                volume_ratio: volume / n.reference_volume,
                force,
                collar_z,
                current: (u.x * u.x + u.y * u.y + u.z * u.z).sqrt(),
            }
        })
        .collect()
}

/// The packed nodes of the knots of net `n`.
fn knots_nodes(lay: &Layout, n: &NetInfo) -> Vec<usize> {
    (0..n.rows)
        .flat_map(|row| (0..n.around).map(move |col| (row, col)))
        .map(|(row, col)| lay.cables[n.knot_cable(row, col)].nodes[0] as usize)
        .collect()
}
