//! Stage 3 of the run pipeline, the initial state: straight lines as laid out by the
//! scenario, or catenaries relaxed to the discrete model's static equilibrium.

use crate::error::Error;
use crate::model::{Block, Layout, NO_CONSTRAINT};
use crate::physics::catenary::catenary_positions;
use crate::scenario::{InitialShape, Scenario};
use crate::statics::{relax_blocks, static_forces, RelaxOptions};
use rayon::prelude::*;

/// Builds the layout and the initial state (catenary first guesses relaxed to the
/// discrete static equilibrium). Returns the layout, positions and the largest
/// residual force left by the relaxation.
///
/// A run with winch cables has no bending in the lumped-mass model yet: its layout is
/// built with every line type's `ei` at zero (the ANCF reference keeps it), as the
/// steppers' `with_winches` do, so that the step plan and the statics agree with them.
pub fn prepare(sc: &Scenario) -> Result<(Layout, Vec<[f64; 3]>, f64), Error> {
    let (mut lay, mut pos) = if sc.winches.is_empty() {
        Layout::build(&sc.model)?
    } else {
        let mut def = sc.model.clone();
        for lt in &mut def.line_types {
            lt.ei = 0.0;
        }
        Layout::build(&def)?
    };
    let residual = apply(sc, &mut lay, &mut pos)?;
    Ok((lay, pos, residual))
}

/// Applies each cable's initial shape to `pos` (packed order): a `catenary` cable gets
/// the analytic elastic catenary (with seabed contact) between its end positions as a
/// first guess, then every block holding such a cable is relaxed to the discrete static
/// equilibrium (current drag included). Straight cables are left as laid out. Returns
/// the largest residual force left by the relaxation, N (0 when nothing was relaxed).
///
/// A block the relaxation does not bring to its tolerance is not an error when its
/// lines run between held ends: it starts from the better of the best state found and
/// the analytic catenary, with a warning. A block with free ends (a buoy, a free point)
/// is an error that says what to change: the point's net lift against the wet weight
/// of the cables it carries.
///
/// Free and pinned bodies that take their equilibrium (`initial = "equilibrium"`, the
/// default) with lines in a relaxed block are then moved to their static equilibrium
/// with those lines (`statics::bodies`): `lay`'s routes then hold the bodies at that
/// pose.
pub fn apply(sc: &Scenario, lay: &mut Layout, pos: &mut [[f64; 3]]) -> Result<f64, Error> {
    let opts = RelaxOptions::default();
    let residual = apply_with(sc, lay, pos, &opts)?;
    // The blocks relaxed: those holding a catenary cable.
    let mut relax = vec![false; lay.blocks.len()];
    for (ci, shape) in sc.initial.iter().enumerate() {
        if *shape == InitialShape::Catenary {
            let first = lay.cables[ci].nodes[0];
            relax[lay.blocks.partition_point(|b| b.node_end <= first)] = true;
        }
    }
    let bodies = crate::statics::bodies::relax_bodies(lay, pos, &opts, &relax)?;
    for b in &bodies.bodies {
        let [r, p, y] = b.angles.map(f64::to_degrees);
        let at = format!(
            "reference point ({:.4}, {:.4}, {:.4}) m, roll {r:.3}, pitch {p:.3}, yaw {y:.3} deg",
            b.position[0], b.position[1], b.position[2]
        );
        if b.converged {
            log::info!(
                "initial equilibrium: body '{}' at rest with its lines at {at} (residual {:.2e} N, {:.2e} N m)",
                b.name, b.residual.0, b.residual.1
            );
        } else {
            log::warn!(
                "initial equilibrium: body '{}' did not reach its static equilibrium with its lines; starting from the best pose found, {at}, where {:.3e} N and {:.3e} N m are left: expect a start-up transient (or set initial = \"pose\" on the body)",
                b.name, b.residual.0, b.residual.1
            );
        }
    }
    Ok(residual)
}

/// [`apply`] with the relaxation's options (`require_convergence` is ignored: what a
/// block that does not converge does is [`apply`]'s rule).
pub fn apply_with(
    sc: &Scenario,
    lay: &Layout,
    pos: &mut [[f64; 3]],
    opts: &RelaxOptions,
) -> Result<f64, Error> {
    let env = &lay.env;
    let mut relax = vec![false; lay.blocks.len()];
    // Each cable's catenary on its own (a fleet's thousands in parallel), then written
    // into the packed positions.
    let guesses: Vec<(usize, Vec<[f64; 3]>)> = sc
        .initial
        .par_iter()
        .enumerate()
        .filter(|(_, shape)| **shape == InitialShape::Catenary)
        .map(|(ci, _)| {
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
            // The seabed under the catenary: the plane, or with a seabed grid a flat
            // seabed at the grid's height under the lower end, the nodes then lifted onto
            // the grid where they lie below it; the relaxation then lays the line on the
            // slope.
            let bed = match env.seabed.grid {
                None => -env.depth,
                Some(g) => {
                    let low = if a[2] <= b[2] { a } else { b };
                    g.height(low[0], low[1])
                }
            };
            let lift = |mut guess: Vec<[f64; 3]>| {
                if let Some(g) = env.seabed.grid {
                    for p in guess.iter_mut() {
                        p[2] = p[2].max(g.height(p[0], p[1]));
                    }
                }
                guess
            };
            let sections = cable
                .elements
                .iter()
                .any(|&e| lay.elem_line[e as usize] as usize != cable.line_type);
            if !sections {
                let w = lt.wet_weight_per_length(env.gravity, env.water_density);
                return (ci, lift(catenary_positions(a, b, length, n, lt.ea, w, bed)));
            }
            // Several sections: one catenary of the length-weighted wet weight and the
            // series stiffness as the first guess, each node at its arc length along it.
            let (mut wl, mut compliance) = (0.0, 0.0);
            for &e in &cable.elements {
                let t = &lay.line_types[lay.elem_line[e as usize] as usize];
                let l0 = lay.elem_l0[e as usize];
                wl += t.wet_weight_per_length(env.gravity, env.water_density) * l0;
                compliance += l0 / t.ea;
            }
            let fine = (4 * n).max(64);
            let curve =
                catenary_positions(a, b, length, fine, length / compliance, wl / length, bed);
            let mut out = Vec::with_capacity(n + 1);
            let mut arc = 0.0;
            for k in 0..=n {
                if k > 0 {
                    arc += lay.elem_l0[cable.elements[k - 1] as usize];
                }
                let x = (arc / length * fine as f64).clamp(0.0, fine as f64);
                let j = (x.floor() as usize).min(fine - 1);
                let f = x - j as f64;
                let (p, q) = (curve[j], curve[j + 1]);
                out.push([0, 1, 2].map(|d| p[d] + f * (q[d] - p[d])));
            }
            (ci, lift(out))
        })
        .collect();
    for (ci, guess) in guesses {
        let cable = &lay.cables[ci];
        let n = cable.elements.len();
        // The ends stay where the scenario puts them (shared points included).
        for k in 1..n {
            pos[cable.nodes[k] as usize] = guess[k];
        }
        // The block holding the cable (blocks are contiguous, in node order).
        let first = cable.nodes[0];
        let bi = lay.blocks.partition_point(|b| b.node_end <= first);
        assert!(
            bi < lay.blocks.len() && lay.blocks[bi].node_start <= first,
            "every node is in a block"
        );
        relax[bi] = true;
    }
    if !relax.iter().any(|&x| x) {
        return Ok(0.0);
    }
    let guess = pos.to_vec();
    let opts = RelaxOptions {
        require_convergence: false,
        ..*opts
    };
    let report = relax_blocks(lay, pos, &opts, &relax)?;
    let mut residual = 0.0f64;
    for b in &report.blocks {
        if b.converged {
            residual = residual.max(b.max_residual);
            continue;
        }
        let block = lay.blocks[b.block];
        let names = block_cables(lay, &block);
        let worst = match b.worst_node {
            Some(n) => {
                let (cable, k) = lay.describe_node(n);
                format!(" at cable '{cable}', node {k}")
            }
            None => String::new(),
        };
        let failed = format!(
            "the static equilibrium of {names} was not found from the catenary first guess (largest residual force {:.3e} N{worst}, tolerance {:.3e} N)",
            b.max_residual, b.tolerance
        );
        let free_ends = free_ends(lay, &block);
        if !free_ends.is_empty() {
            return Err(Error::Statics(format!(
                "{failed}. {}",
                free_point_diagnosis(sc, lay, &free_ends)
            )));
        }
        // Lines between held ends: the run can go on from a shape near the
        // equilibrium, so say so rather than refuse it. Of the best state the solver
        // reached and the analytic catenary (exact for an inextensible line without
        // seabed friction), keep the one with the smaller residual force.
        let (n0, n1) = (block.node_start as usize, block.node_end as usize);
        let forces = static_forces(lay, &guess);
        let at_guess = (n0..n1)
            .filter(|&i| lay.node_constraint[i] == NO_CONSTRAINT)
            .map(|i| norm(forces[i]))
            .fold(0.0f64, f64::max);
        let (off, start) = if at_guess < b.max_residual {
            pos[n0..n1].copy_from_slice(&guess[n0..n1]);
            (at_guess, "the analytic catenary")
        } else {
            (b.max_residual, "the best state found")
        };
        log::warn!(
            "initial equilibrium: {failed}; starting from {start} instead, which leaves a residual force of up to {off:.3e} N: expect a start-up transient (more segments, or initial = \"straight\", may do better)"
        );
        residual = residual.max(off);
    }
    log::info!(
        "initial equilibrium: {} block(s) relaxed in {} Newton iterations, largest residual force {:.3e} N",
        report.blocks.len(),
        report.iterations,
        residual
    );
    Ok(residual)
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// "cable 'a'" or "cables 'a', 'b'": the cables of a block, for messages.
fn block_cables(lay: &Layout, block: &Block) -> String {
    let names: Vec<String> = lay
        .cables
        .iter()
        .filter(|c| c.nodes.first().is_some_and(|&n| in_block(block, n)))
        .map(|c| format!("'{}'", c.name))
        .collect();
    let s = if names.len() == 1 { "" } else { "s" };
    format!("cable{s} {}", names.join(", "))
}

fn in_block(block: &Block, n: u32) -> bool {
    block.node_start <= n && n < block.node_end
}

/// The cable ends of a block that no route holds (free points, free ends), each once.
fn free_ends(lay: &Layout, block: &Block) -> Vec<u32> {
    let mut ends: Vec<u32> = lay
        .cables
        .iter()
        .filter(|c| c.nodes.first().is_some_and(|&n| in_block(block, n)))
        .flat_map(|c| [c.nodes[0], c.nodes[c.nodes.len() - 1]])
        .filter(|&n| lay.node_constraint[n as usize] == NO_CONSTRAINT)
        .collect();
    ends.sort_unstable();
    ends.dedup();
    ends
}

/// What a user can act on when a block with free ends has no equilibrium found: for
/// each free end, its net lift (buoyancy less weight of its point) against the wet
/// weight of the cables hanging from it, and what to change.
fn free_point_diagnosis(sc: &Scenario, lay: &Layout, ends: &[u32]) -> String {
    let env = &lay.env;
    // The scenario's name of a point (the packed index of each described node).
    let labels: Vec<Option<String>> = match Layout::build_indexed(&sc.model) {
        Ok((_, _, index)) => {
            let mut l = vec![None; lay.n_nodes()];
            for (def, &packed) in sc.model.nodes.iter().zip(&index) {
                if let Some(slot) = l.get_mut(packed as usize) {
                    if slot.is_none() {
                        *slot = def.label.clone();
                    }
                }
            }
            l
        }
        Err(_) => vec![None; lay.n_nodes()],
    };
    let mut parts = Vec::new();
    for &n in ends {
        let i = n as usize;
        let attached: Vec<&crate::model::CableInfo> = lay
            .cables
            .iter()
            .filter(|c| c.nodes[0] == n || c.nodes[c.nodes.len() - 1] == n)
            .collect();
        let hanging: f64 = attached
            .iter()
            .map(|c| {
                let lt = &lay.line_types[c.line_type];
                let length: f64 = c.elements.iter().map(|&e| lay.elem_l0[e as usize]).sum();
                lt.wet_weight_per_length(env.gravity, env.water_density) * length
            })
            .sum();
        // The z component of weight and buoyancy together: up for a buoy.
        let lift = lay.node_point_weight_z[i];
        let names: Vec<String> = attached.iter().map(|c| format!("'{}'", c.name)).collect();
        let what = match &labels[i] {
            Some(l) => format!("The free point '{l}'"),
            None => format!("The free end of cable {}", names[0]),
        };
        let kn = |x: f64| x / 1e3;
        let verdict = if lift <= 0.0 {
            format!(
                "{what} has no net lift ({:.1} kN heavier than the water it displaces) and hangs on cable(s) {} of {:.1} kN wet weight: it sinks with them to the seabed, and unless the seabed or taut cables hold it there is no rest position",
                kn(-lift),
                names.join(", "),
                kn(hanging)
            )
        } else if lift < hanging {
            format!(
                "{what} has a net lift (buoyancy less weight) of {:.1} kN but carries cable(s) {} of {:.1} kN wet weight in all: it cannot hold them all up: they rest on the seabed and pull it down, far from where the scenario places it; to hang them from it give it a net lift above {:.1} kN (more volume or less mass) or use lighter or shorter cables, or place it near the seabed where it comes to rest",
                kn(lift),
                names.join(", "),
                kn(hanging),
                kn(hanging)
            )
        } else {
            format!(
                "{what} has a net lift of {:.1} kN and carries cable(s) {} of {:.1} kN wet weight: it can hold them up, but its equilibrium is far from where the scenario places it; place it nearer its rest position",
                kn(lift),
                names.join(", "),
                kn(hanging)
            )
        };
        parts.push(verdict);
    }
    format!(
        "{}. Or start from initial = \"straight\" (no static equilibrium is sought) and let the run settle",
        parts.join("; ")
    )
}
