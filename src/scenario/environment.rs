//! The `[environment]` table: gravity, water, depth, seabed and currents (the waves
//! are in `waves.rs`).

use super::raw::RawEnvironment;
use super::{err, finite, non_negative, positive, validate};
use crate::error::Error;
use crate::model::{Bathymetry, Current, Environment};
use std::path::Path;

/// The `[environment]` table, validated, and its current (still water without one).
pub(super) fn environment(p: &Path, e: &RawEnvironment) -> Result<(Environment, Current), Error> {
    let grid = match &e.seabed_file {
        Some(f) => Some(Bathymetry::read(&p.parent().unwrap_or(Path::new(".")).join(f))?.keep()),
        None => None,
    };
    let depth = match (e.depth, grid) {
        (Some(d), _) => positive(p, "environment.depth", d)?,
        // The waves' depth over a seabed grid: its mean depth, as MoorDyn takes it.
        (None, Some(g)) => {
            let (low, mean) = g.lowest_and_mean();
            if mean >= 0.0 {
                return Err(err(
                    p,
                    "environment.seabed_file",
                    format!(
                        "the grid's mean height is {mean} m (lowest {low} m): no water over it"
                    ),
                ));
            }
            -mean
        }
        (None, None) => f64::INFINITY,
    };
    let mut sb = e.seabed;
    sb.grid = grid;
    non_negative(p, "environment.seabed.stiffness", sb.stiffness)?;
    non_negative(p, "environment.seabed.damping", sb.damping)?;
    non_negative(p, "environment.seabed.friction", sb.friction)?;
    if let Some(mt) = sb.friction_transverse.take() {
        if sb.friction != 0.0 {
            return Err(err(
                p,
                "environment.seabed.friction_transverse",
                "give either friction (both directions) or friction_transverse, not both"
                    .to_string(),
            ));
        }
        // Each of the split keys defaults to `friction` (here 0, not given).
        sb.friction_axial = Some(sb.friction_axial.unwrap_or(sb.friction));
        sb.friction = non_negative(p, "environment.seabed.friction_transverse", mt)?;
    }
    if let Some(ma) = sb.friction_axial {
        non_negative(p, "environment.seabed.friction_axial", ma)?;
    }
    positive(
        p,
        "environment.seabed.friction_velocity",
        sb.friction_velocity,
    )?;
    let env = Environment {
        gravity: validate::magnitude(
            p,
            "environment.gravity",
            non_negative(p, "environment.gravity", e.gravity)?,
            "m/s^2",
        )?,
        water_density: validate::magnitude(
            p,
            "environment.water_density",
            non_negative(p, "environment.water_density", e.water_density)?,
            "kg/m^3",
        )?,
        depth,
        seabed: sb,
    };
    let global_current =
        current(p, "environment.", e.current, &e.current_profile)?.unwrap_or_default();
    Ok((env, global_current))
}

fn vec3(path: &Path, field: &str, v: [f64; 3]) -> Result<[f64; 3], Error> {
    for (k, x) in v.iter().enumerate() {
        finite(path, &format!("{field}[{k}]"), *x)?;
    }
    Ok(v)
}

pub(super) fn current(
    path: &Path,
    field: &str,
    uniform: Option<[f64; 3]>,
    profile: &Option<Vec<[f64; 4]>>,
) -> Result<Option<Current>, Error> {
    match (uniform, profile) {
        (Some(_), Some(_)) => Err(err(
            path,
            field,
            "give either `current` or `current_profile`, not both",
        )),
        (Some(u), None) => {
            let f = format!("{field}current");
            let u = vec3(path, &f, u)?;
            validate::current_speed(path, &f, u)?;
            Ok(Some(Current::uniform(u)))
        }
        (None, Some(rows)) => {
            let f = format!("{field}current_profile");
            if rows.is_empty() {
                return Err(err(path, &f, "needs at least one row [z, ux, uy, uz]"));
            }
            let mut table = Vec::with_capacity(rows.len());
            for (i, r) in rows.iter().enumerate() {
                for (k, x) in r.iter().enumerate() {
                    finite(path, &format!("{f}[{i}][{k}]"), *x)?;
                }
                validate::current_speed(path, &format!("{f}[{i}]"), [r[1], r[2], r[3]])?;
                if i > 0 && r[0] <= rows[i - 1][0] {
                    return Err(err(
                        path,
                        format!("{f}[{i}]"),
                        "depths z must increase strictly from row to row",
                    ));
                }
                table.push((r[0], [r[1], r[2], r[3]]));
            }
            Ok(Some(Current { table }))
        }
        (None, None) => Ok(None),
    }
}
