//! Checks of the model a scenario describes, beyond each value's own range: ends
//! against the seabed and the surface, points and line types no cable uses, derived
//! quantities that overflow f64, straight starts that are badly stretched. Errors name
//! the field at fault; warnings go to the log.

use super::err;
use crate::error::Error;
use crate::model::{ModelDef, Route};
use crate::options::SolverOptions;
use std::f64::consts::TAU;
use std::path::Path;

/// The largest magnitude a coordinate or a derived force, stiffness or mass may have:
/// the solvers square them (lengths, force magnitudes, sums of squares over all nodes),
/// and a value beyond `1e150` has a square beyond `1e300`, at the edge of f64. Every
/// physical input is many orders of magnitude below it.
pub const MAGNITUDE_LIMIT: f64 = 1e150;

/// Whether `x` is not a finite number within [`MAGNITUDE_LIMIT`].
fn out_of_range(x: f64) -> bool {
    !(x.abs() <= MAGNITUDE_LIMIT)
}

/// How far from the origin (m, per coordinate) a node may go before the solvers stop
/// the run as a blow-up (`SolverOptions::max_distance`).
pub fn max_distance() -> f64 {
    SolverOptions::default().max_distance
}

/// A position (m) given at `field`: each coordinate within [`MAGNITUDE_LIMIT`] (beyond
/// it the squared distances between nodes overflow f64) and within [`max_distance`]
/// (beyond it the first step stops the run as a blow-up).
pub fn position(p: &Path, field: &str, x: [f64; 3]) -> Result<(), Error> {
    if x.iter().any(|c| out_of_range(*c)) {
        return Err(err(
            p,
            field,
            format!(
                "position {x:?} m: a coordinate beyond {MAGNITUDE_LIMIT:e} m, whose square (in the lengths of the elements) overflows f64; check the value and its units"
            ),
        ));
    }
    let limit = max_distance();
    if x.iter().any(|c| !(c.abs() < limit)) {
        return Err(err(
            p,
            field,
            format!(
                "position {x:?} m: a coordinate {limit:e} m or more from the origin, where the solver stops a run as a blow-up; move the origin near the model, or check the value and its units"
            ),
        ));
    }
    Ok(())
}

/// The speed of a driven end's route against `max_speed` (m/s, `simulation.max_speed`):
/// a route faster than `sqrt(3) max_speed` drags its node past the limit, and the first
/// step stops the run as a blow-up. Tables are checked where they are read.
pub fn route_speed(p: &Path, field: &str, route: &Route, max_speed: f64) -> Result<(), Error> {
    // Of two factors, the one further from 1 in orders of magnitude is named.
    let culprit = |a: (&'static str, f64), b: (&'static str, f64)| {
        if a.1.abs().log10().abs() >= b.1.abs().log10().abs() {
            a.0
        } else {
            b.0
        }
    };
    let (key, speed) = match *route {
        Route::Line { velocity: v, .. } => {
            ("velocity", (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        }
        Route::Circle {
            radius,
            period,
            advance,
            ..
        } => {
            let (round, along) = (TAU * radius / period, advance / period);
            let key = if round.abs() >= along.abs() {
                culprit(("diameter", 2.0 * radius), ("period", period))
            } else {
                culprit(("advance", advance), ("period", period))
            };
            (key, round.hypot(along))
        }
        _ => return Ok(()),
    };
    // Beyond sqrt(3) max_speed some velocity component is beyond max_speed at every
    // instant (the solver's test is by component).
    if !(speed <= 3f64.sqrt() * max_speed) {
        return Err(err(
            p,
            format!("{field}.{key}"),
            format!("the route moves its end at {speed:e} m/s, more than sqrt(3) x simulation.max_speed = {max_speed:e} m/s: a velocity component is above max_speed, and the first step would stop the run as a blow-up; check the values and their units"),
        ));
    }
    Ok(())
}

/// A value (in `unit`) given at `field` that the solvers multiply into forces and
/// square (a cable's length, gravity, the water's density): within [`MAGNITUDE_LIMIT`].
pub fn magnitude(p: &Path, field: &str, x: f64, unit: &str) -> Result<f64, Error> {
    if out_of_range(x) {
        return Err(err(
            p,
            field,
            format!("{x:e} {unit} is beyond {MAGNITUDE_LIMIT:e} {unit}, whose square overflows f64; check the value and its units"),
        ));
    }
    Ok(x)
}

/// A current velocity (m/s) given at `field`: its speed squared (in the drag) within
/// [`MAGNITUDE_LIMIT`].
pub fn current_speed(p: &Path, field: &str, u: [f64; 3]) -> Result<(), Error> {
    let limit = MAGNITUDE_LIMIT.sqrt();
    if u.iter().any(|c| !(c.abs() <= limit)) {
        return Err(err(
            p,
            field,
            format!("current {u:?} m/s: a component beyond {limit:e} m/s, whose square in the drag overflows f64; check the value and its units"),
        ));
    }
    Ok(())
}

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

/// An end or point at `pos` (m) against the seabed (an error below it: the plane
/// `z = -depth`, or the seabed grid `grid` at the point's `x`, `y`, which must lie
/// within the grid) and the surface (a warning far above it).
pub fn height(
    p: &Path,
    field: &str,
    pos: [f64; 3],
    depth: f64,
    grid: Option<&crate::model::Bathymetry>,
) -> Result<(), Error> {
    let z = pos[2];
    if let Some(g) = grid {
        if !g.covers(pos[0], pos[1], 0.0) {
            return Err(err(
                p,
                field,
                format!(
                    "x = {}, y = {} m lies outside the seabed grid of {} ({}): the grid must cover every end and point",
                    pos[0],
                    pos[1],
                    g.path.display(),
                    g.extent()
                ),
            ));
        }
        let zb = g.height(pos[0], pos[1]);
        if z < zb - below_tolerance(-zb) {
            return Err(err(
                p,
                field,
                format!(
                    "z = {z} m is {:.3} m below the seabed, which the grid of {} puts at z = {zb:.3} m at x = {}, y = {}",
                    zb - z,
                    g.path.display(),
                    pos[0],
                    pos[1]
                ),
            ));
        }
    } else if depth.is_finite() && z < -depth - below_tolerance(depth) {
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
        super::warnings::warn(format!(
            "{}: {field}: z = {z} m is more than {up} m above the water surface (z = 0): is the sign right?",
            p.display()
        ));
    }
    Ok(())
}

/// A straight start of a cable of unstretched `length` between ends `a` and `b`: a
/// warning when it starts stretched by more than 10 %.
pub fn straight_strain(p: &Path, field: &str, length: f64, ea: f64, a: [f64; 3], b: [f64; 3]) {
    let chord = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt();
    let strain = chord / length - 1.0;
    if strain > 0.1 {
        super::warnings::warn(format!(
            "{}: {field}: starts straight between ends {chord:.4} m apart, {:.0} % longer than its length {length} m: a tension EA * strain = {:.3e} N at t = 0, and a violent start (check the length or the ends)",
            p.display(),
            100.0 * strain,
            ea * strain
        ));
    }
}

/// Quantities derived from each line type on the elements that use it (stiffness and
/// damping over the shortest element, weights over the longest cable, drag in the
/// fastest current or 10 m/s), from each point mass (its weight, buoyancy and drag;
/// `node_field(n)` names the entry that gives node `n`'s) and from the seabed: each
/// must stay within
/// [`MAGNITUDE_LIMIT`] (the solvers square them), else an error naming the input and
/// the factors of the product. `line_field(i)` is line type `i`'s field prefix.
pub fn derived(
    p: &Path,
    model: &ModelDef,
    line_field: impl Fn(usize) -> String,
    node_field: impl Fn(usize) -> String,
    baumgarte: (f64, f64),
) -> Result<(), Error> {
    let n = model.line_types.len();
    let (mut shortest, mut longest) = (vec![f64::INFINITY; n], vec![0.0f64; n]);
    for c in &model.cables {
        let total: f64 = c.l0.iter().sum();
        if c.elem_lines.is_empty() {
            let lt = c.line_type;
            shortest[lt] = c.l0.iter().copied().fold(shortest[lt], f64::min);
            longest[lt] = longest[lt].max(total);
        } else {
            // A cable of several sections: each line type's elements, and the whole
            // cable's length for each.
            for (&lt, &l0) in c.elem_lines.iter().zip(&c.l0) {
                shortest[lt] = shortest[lt].min(l0);
                longest[lt] = longest[lt].max(total);
            }
        }
    }
    let env = &model.env;
    let g_rho = env.gravity * env.water_density;
    let (g, rho) = (env.gravity, env.water_density);
    // The fastest current anywhere (its drag goes as the square), at least 10 m/s.
    let u = model
        .currents
        .iter()
        .flat_map(|c| c.table.iter())
        .map(|(_, u)| (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt())
        .fold(10.0f64, |a, b| if b.is_nan() { b } else { a.max(b) });
    for (i, lt) in model.line_types.iter().enumerate() {
        if longest[i] == 0.0 {
            continue;
        }
        let (l0, len) = (shortest[i], longest[i]);
        let (d, ea) = (lt.diameter, lt.ea);
        let terms = [
            (
                "ea",
                format!("axial stiffness 2 EA / l0 (EA {ea:e} N, l0 {l0:e} m)"),
                2.0 * ea / l0,
            ),
            (
                "damping",
                format!(
                    "internal damping 2 EA c / l0 (EA {ea:e} N, c {:e} s, l0 {l0:e} m)",
                    lt.damping
                ),
                2.0 * ea * lt.damping / l0,
            ),
            (
                "mass_per_length",
                format!(
                    "the weight of a cable (mass_per_length {:e} kg/m x length {len:e} m x gravity {g:e} m/s^2)",
                    lt.mass_per_length
                ),
                lt.mass_per_length * len * g.max(1.0),
            ),
            (
                "diameter",
                format!(
                    "the buoyancy of a cable (diameter {d:e} m, length {len:e} m, gravity {g:e} m/s^2, water_density {rho:e} kg/m^3)"
                ),
                (d * d) * len * g_rho.max(1.0),
            ),
            (
                "cm",
                format!(
                    "the added mass of a cable (cm {:e}, diameter {d:e} m, length {len:e} m, water_density {rho:e} kg/m^3)",
                    lt.cm
                ),
                (d * d) * len * rho.max(1.0) * lt.cm,
            ),
            (
                "cat",
                format!(
                    "the tangential added mass of a cable (cat {:e}, diameter {d:e} m, length {len:e} m, water_density {rho:e} kg/m^3)",
                    lt.cat
                ),
                (d * d) * len * rho.max(1.0) * lt.cat,
            ),
            (
                "ei",
                format!("bending stiffness EI / l0^3 (EI {:e} N m^2, l0 {l0:e} m)", lt.ei),
                lt.ei / (l0 * l0 * l0),
            ),
            (
                "cn",
                format!(
                    "the normal drag on a cable (cn {:e}, diameter {d:e} m, length {len:e} m, water_density {rho:e} kg/m^3, at {u:e} m/s: the fastest current or 10 m/s)",
                    lt.cn
                ),
                lt.cn * d * len * rho.max(1.0) * u * u,
            ),
            (
                "ct",
                format!(
                    "the tangential drag on a cable (ct {:e}, diameter {d:e} m, length {len:e} m, water_density {rho:e} kg/m^3, at {u:e} m/s: the fastest current or 10 m/s)",
                    lt.ct
                ),
                lt.ct * d * len * rho.max(1.0) * u * u,
            ),
        ];
        for (key, what, x) in terms {
            if out_of_range(x) {
                return Err(err(
                    p,
                    format!("{}.{key}", line_field(i)),
                    format!("{what} is {x:e} on the elements of this line type, beyond {MAGNITUDE_LIMIT:e}: it overflows f64 where the solver squares it, and no step can simulate it; check the values and their units"),
                ));
            }
        }
    }
    // The point masses' loads: weight, buoyancy, drag in the fastest current.
    for (n, node) in model.nodes.iter().enumerate() {
        let pm = &node.point;
        for (key, what, x) in [
            ("mass", "weight (mass x gravity)", pm.mass * g),
            (
                "volume",
                "buoyancy (volume x water_density x gravity)",
                pm.volume * g_rho,
            ),
            (
                "drag_area",
                "drag (drag_area x water_density x speed^2)",
                pm.drag_area * rho * u * u,
            ),
            (
                "added_mass",
                "added mass's weight (added_mass x volume x water_density x gravity)",
                pm.added_mass_coef * pm.volume * g_rho.max(1.0),
            ),
        ] {
            if out_of_range(x) {
                return Err(err(
                    p,
                    format!("{}.{key}", node_field(n)),
                    format!("the point mass's {what} is {x:e} N (gravity {g:e} m/s^2, water_density {rho:e} kg/m^3, speed {u:e} m/s: the fastest current or 10 m/s), beyond {MAGNITUDE_LIMIT:e} N: it overflows f64 where the solver squares it; check the values and their units"),
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
            if out_of_range(x) {
                return Err(err(
                    p,
                    format!("environment.seabed.{key}"),
                    format!("{} overflows f64 in the contact force of a node (beyond {MAGNITUDE_LIMIT:e} per metre of penetration, or per m/s): no step can simulate it; check the value and its units", if key == "stiffness" { "K" } else { "C" }),
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
        super::warnings::warn(format!(
            "{}: {field}: no cable uses this point",
            p.display()
        ));
    }
    Ok(())
}

/// Line types no cable or net uses: a warning each.
pub fn unused_line_types(p: &Path, model: &ModelDef, line_field: impl Fn(usize) -> String) {
    let mut used = vec![false; model.line_types.len()];
    for c in &model.cables {
        used[c.line_type] = true;
        for &lt in &c.elem_lines {
            used[lt] = true;
        }
    }
    // A screen net's twines use a copy of their line type (model::net).
    for &(copy, original) in &model.screens.twine_lines {
        if used[copy] {
            used[original] = true;
        }
        used[copy] = true;
    }
    for (i, u) in used.iter().enumerate() {
        if !u {
            super::warnings::warn(format!(
                "{}: {}: no cable or net uses this line type",
                p.display(),
                line_field(i)
            ));
        }
    }
}
