//! Checks of the model a scenario describes, beyond each value's own range: ends
//! against the seabed and the surface, points and line types no cable uses, derived
//! quantities that overflow f64, straight starts that are badly stretched. Errors name
//! the field at fault; warnings go to the log.

use super::err;
use crate::error::Error;
use crate::model::ModelDef;
use std::path::Path;

/// How far below the seabed plane an end may sit before it is an error, m: rounding in
/// converted files, not a buried anchor.
fn below_tolerance(depth: f64) -> f64 {
    0.01 + 1e-4 * depth
}

/// How far above the surface an end may sit before a warning, m: a fairlead on a deck
/// is a few metres up; tens of metres (or a tenth of the depth) is a typo in a sign.
fn above_warning(depth: f64) -> f64 {
    if depth.is_finite() {
        (0.1 * depth).max(20.0)
    } else {
        50.0
    }
}

/// An end or point at height `z` (m) against the seabed (an error below it) and the
/// surface (a warning far above it).
pub fn height(p: &Path, field: &str, z: f64, depth: f64) -> Result<(), Error> {
    if depth.is_finite() && z < -depth - below_tolerance(depth) {
        return Err(err(
            p,
            field,
            format!(
                "z = {z} m is {:.3} m below the seabed (environment.depth = {depth} m puts it at z = {})",
                -depth - z,
                -depth
            ),
        ));
    }
    let up = above_warning(depth);
    if z > up {
        log::warn!(
            "{}: {field}: z = {z} m is more than {up} m above the water surface (z = 0): is the sign right?",
            p.display()
        );
    }
    Ok(())
}

/// A straight start of a cable of unstretched `length` between ends `a` and `b`: a
/// warning when it starts stretched by more than 10 %.
pub fn straight_strain(p: &Path, field: &str, length: f64, ea: f64, a: [f64; 3], b: [f64; 3]) {
    let chord = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt();
    let strain = chord / length - 1.0;
    if strain > 0.1 {
        log::warn!(
            "{}: {field}: starts straight between ends {chord:.4} m apart, {:.0} % longer than its length {length} m: a tension EA * strain = {:.3e} N at t = 0, and a violent start (check the length or the ends)",
            p.display(),
            100.0 * strain,
            ea * strain
        );
    }
}

/// Quantities derived from each line type on the elements that use it (stiffness and
/// damping over the shortest element, weights over the longest cable) and from the
/// seabed: each must stay a finite f64, else an error naming the input.
/// `line_field(i)` is line type `i`'s field prefix.
pub fn derived(
    p: &Path,
    model: &ModelDef,
    line_field: impl Fn(usize) -> String,
    baumgarte: (f64, f64),
) -> Result<(), Error> {
    let n = model.line_types.len();
    let (mut shortest, mut longest) = (vec![f64::INFINITY; n], vec![0.0f64; n]);
    for c in &model.cables {
        let total: f64 = c.l0.iter().sum();
        let lt = c.line_type;
        shortest[lt] = c.l0.iter().copied().fold(shortest[lt], f64::min);
        longest[lt] = longest[lt].max(total);
    }
    let env = &model.env;
    let g_rho = env.gravity * env.water_density;
    for (i, lt) in model.line_types.iter().enumerate() {
        if longest[i] == 0.0 {
            continue;
        }
        let (l0, len) = (shortest[i], longest[i]);
        let terms = [
            ("ea", "axial stiffness 2 EA / l0", 2.0 * lt.ea / l0),
            (
                "damping",
                "internal damping 2 EA c / l0",
                2.0 * lt.ea * lt.damping / l0,
            ),
            (
                "mass_per_length",
                "the weight of a cable",
                lt.mass_per_length * len * env.gravity.max(1.0),
            ),
            (
                "diameter",
                "the buoyancy and added mass of a cable",
                (lt.diameter * lt.diameter) * len * g_rho.max(1.0) * (1.0 + lt.cm),
            ),
            ("ei", "bending stiffness EI / l0^3", lt.ei / (l0 * l0 * l0)),
            (
                "cn",
                "the normal drag on a cable at 10 m/s",
                lt.cn * lt.diameter * len * env.water_density.max(1.0) * 100.0,
            ),
            (
                "ct",
                "the tangential drag on a cable at 10 m/s",
                lt.ct * lt.diameter * len * env.water_density.max(1.0) * 100.0,
            ),
        ];
        for (key, what, x) in terms {
            if !x.is_finite() {
                return Err(err(
                    p,
                    format!("{}.{key}", line_field(i)),
                    format!("{what} overflows f64 ({x}) on the elements of this line type (shortest l0 = {l0:e} m): no step can simulate it; check the value and its units"),
                ));
            }
        }
    }
    if env.depth.is_finite() {
        let l0 = shortest.iter().copied().fold(f64::INFINITY, f64::min);
        let l0 = if l0.is_finite() { l0 } else { 1.0 };
        let len = longest.iter().copied().fold(1.0, f64::max);
        // Per node: K (or C) times the node's share of length, over its mass.
        for (key, x) in [
            ("stiffness", env.seabed.stiffness * len / l0.min(1.0)),
            ("damping", env.seabed.damping * len / l0.min(1.0)),
        ] {
            if !x.is_finite() {
                return Err(err(
                    p,
                    format!("environment.seabed.{key}"),
                    format!("{} overflows f64 in the contact force of a node: no step can simulate it; check the value and its units", if key == "stiffness" { "K" } else { "C" }),
                ));
            }
        }
    }
    // The constraint gains enter the step bound as omega^2 = alpha, gamma = beta.
    let (alpha, beta) = baumgarte;
    for (key, x) in [
        ("baumgarte_alpha", 4.0 * alpha),
        ("baumgarte_beta", beta * beta),
    ] {
        if !x.is_finite() {
            return Err(err(
                p,
                format!("simulation.{key}"),
                "overflows f64 in the stable-step bound: no step can simulate it",
            ));
        }
    }
    Ok(())
}

/// Points no cable uses: a warning, or an error for a free point (nothing holds it:
/// it would fall without end). `points` are `(field, node, free)`.
pub fn unused_points(
    p: &Path,
    model: &ModelDef,
    points: &[(String, usize, bool)],
) -> Result<(), Error> {
    if points.is_empty() {
        return Ok(());
    }
    let mut used = vec![false; model.nodes.len()];
    for c in &model.cables {
        for &n in [c.nodes.first(), c.nodes.last()].into_iter().flatten() {
            used[n] = true;
        }
    }
    for (field, node, free) in points {
        if used[*node] {
            continue;
        }
        if *free {
            return Err(err(
                p,
                field.as_str(),
                "a free point that no cable uses: nothing holds it (attach a cable to it, make it `fixed`, or remove it)",
            ));
        }
        log::warn!("{}: {field}: no cable uses this point", p.display());
    }
    Ok(())
}

/// Line types no cable or net uses: a warning each.
pub fn unused_line_types(p: &Path, model: &ModelDef, line_field: impl Fn(usize) -> String) {
    let mut used = vec![false; model.line_types.len()];
    for c in &model.cables {
        used[c.line_type] = true;
    }
    for (i, u) in used.iter().enumerate() {
        if !u {
            log::warn!(
                "{}: {}: no cable or net uses this line type",
                p.display(),
                line_field(i)
            );
        }
    }
}
