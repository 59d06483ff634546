//! Stage 3 of the run pipeline, the initial state: straight lines as laid out by the
//! scenario, or catenaries relaxed to the discrete model's static equilibrium.

use crate::error::Error;
use crate::model::Layout;
use crate::physics::catenary::catenary_positions;
use crate::scenario::{InitialShape, Scenario};
use crate::statics::{relax_blocks, RelaxOptions};

/// Builds the layout and the initial state (catenary first guesses relaxed to the
/// discrete static equilibrium). Returns the layout, positions and the largest
/// residual force left by the relaxation.
pub fn prepare(sc: &Scenario) -> Result<(Layout, Vec<[f64; 3]>, f64), Error> {
    let (lay, mut pos) = Layout::build(&sc.model)?;
    let residual = apply(sc, &lay, &mut pos)?;
    Ok((lay, pos, residual))
}

/// Applies each cable's initial shape to `pos` (packed order): a `catenary` cable gets
/// the analytic elastic catenary (with seabed contact) between its end positions as a
/// first guess, then every block holding such a cable is relaxed to the discrete static
/// equilibrium (current drag included). Straight cables are left as laid out. Returns
/// the largest residual force left by the relaxation, N (0 when nothing was relaxed).
pub fn apply(sc: &Scenario, lay: &Layout, pos: &mut [[f64; 3]]) -> Result<f64, Error> {
    let env = &lay.env;
    let mut relax = vec![false; lay.blocks.len()];
    for (ci, shape) in sc.initial.iter().enumerate() {
        if *shape != InitialShape::Catenary {
            continue;
        }
        let cable = &lay.cables[ci];
        let lt = &lay.line_types[cable.line_type];
        let n = cable.elements.len();
        let length: f64 = cable
            .elements
            .iter()
            .map(|&e| lay.elem_l0[e as usize])
            .sum();
        let a = pos[cable.nodes[0] as usize];
        let b = pos[cable.nodes[n] as usize];
        let w = lt.wet_weight_per_length(env.gravity, env.water_density);
        let guess = catenary_positions(a, b, length, n, lt.ea, w, -env.depth);
        // The ends stay where the scenario puts them (shared points included).
        for k in 1..n {
            pos[cable.nodes[k] as usize] = guess[k];
        }
        let first = cable.nodes[0];
        let bi = lay
            .blocks
            .iter()
            .position(|b| b.node_start <= first && first < b.node_end)
            .expect("every node is in a block");
        relax[bi] = true;
    }
    if !relax.iter().any(|&x| x) {
        return Ok(0.0);
    }
    let report = relax_blocks(lay, pos, &RelaxOptions::default(), &relax)?;
    log::info!(
        "initial equilibrium: {} block(s) relaxed in {} Newton iterations, largest residual force {:.3e} N",
        report.blocks.len(),
        report.iterations,
        report.max_residual
    );
    Ok(report.max_residual)
}
