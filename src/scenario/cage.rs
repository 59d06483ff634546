//! A `[[nets]]` entry's cage keys (docs/src/scenario.md, "Cages: collar and sinker
//! tube"): `[nets.collar]` and `[nets.sinker_tube]`, validated into a
//! [`crate::model::cage::CageSpec`]; the rings are built by [`crate::model::cage::add_cage`].

use super::raw::{RawNet, RawPipe};
use super::{err, non_negative, positive, show, warnings};
use crate::error::Error;
use crate::model::cage::{CageSpec, Flotation, NetInfo, Pipe, RingSpec, SinkerTube};
use crate::model::{ModelDef, NetShape, NetSpec};
use std::collections::HashMap;
use std::path::Path;

/// Default density of a pipe, kg/m^3 (HDPE).
pub const HDPE_DENSITY: f64 = 950.0;
/// Default Young's modulus of a pipe, Pa (HDPE, PE100 short-term).
pub const HDPE_MODULUS: f64 = 1.0e9;

/// Validates net `n`'s cage keys (its field prefix `field`, its net `spec`) into a
/// [`CageSpec`]; a ring given as a `pipe` adds its line type to `model.line_types`.
/// `points` maps the `[[points]]` names to their nodes.
pub fn parse(
    p: &Path,
    field: &str,
    n: &RawNet,
    spec: &NetSpec,
    line_types: &HashMap<String, usize>,
    points: &HashMap<String, usize>,
    model: &mut ModelDef,
) -> Result<CageSpec, Error> {
    let mut cage = CageSpec::default();
    if n.collar.is_none() && n.sinker_tube.is_none() {
        return Ok(cage);
    }
    let NetShape::Cylinder {
        around,
        rows: _,
        radius,
        depth,
        top,
    } = spec.shape
    else {
        let key = if n.collar.is_some() {
            "collar"
        } else {
            "sinker_tube"
        };
        return Err(err(
            p,
            format!("{field}.{key}"),
            "a collar or a sinker tube needs shape = \"cylinder\"",
        ));
    };
    let segments = |f: &str, s: Option<i64>| -> Result<usize, Error> {
        let s = s.unwrap_or(1);
        if (1..=1000).contains(&s) {
            Ok(s as usize)
        } else {
            Err(err(
                p,
                f,
                format!("must be an integer from 1 to 1000, got {s}"),
            ))
        }
    };
    if let Some(c) = &n.collar {
        let f = format!("{field}.collar");
        let line_type = ring_line_type(
            p,
            &f,
            c.line_type.as_deref(),
            c.pipe.as_ref(),
            &format!("{}.collar", spec.name),
            line_types,
            model,
        )?;
        let d = model.line_types[line_type].diameter;
        if top[2].abs() > d {
            warnings::warn(format!(
                "{}: {field}.top: the collar's ring starts at z = {} m, more than its \
                 diameter ({} m) from the still water surface; it floats at its freeboard \
                 once the run has relaxed it",
                p.display(),
                show(top[2]),
                show(d)
            ));
        }
        cage.collar = Some(RingSpec {
            line_type,
            segments: segments(&format!("{f}.segments"), c.segments)?,
        });
        // Points that become top knots.
        let spacing = 2.0 * radius * (std::f64::consts::PI / around as f64).sin();
        for (k, name) in c.points.iter().flatten().enumerate() {
            let pf = format!("{f}.points[{k}]");
            let &node = points
                .get(name)
                .ok_or_else(|| err(p, &pf, format!("no point named \"{name}\"")))?;
            let x = model.nodes[node].position;
            let a = (x[1] - top[1]).atan2(x[0] - top[0]);
            let col = ((a / (2.0 * std::f64::consts::PI) * around as f64).round() as i64)
                .rem_euclid(around as i64) as usize;
            let kp = spec.shape.knot(0, col);
            let dist =
                ((x[0] - kp[0]).powi(2) + (x[1] - kp[1]).powi(2) + (x[2] - kp[2]).powi(2)).sqrt();
            if dist > 0.5 * spacing {
                return Err(err(
                    p,
                    &pf,
                    format!(
                        "point \"{name}\" at [{}, {}, {}] is {} m from the nearest top knot \
                         ({col}, at [{}, {}, {}]), more than half the knots' spacing ({} m): \
                         the collar's ring is the net's top row ({field}.size[0] = {} m, \
                         {field}.top)",
                        show(x[0]),
                        show(x[1]),
                        show(x[2]),
                        show(dist),
                        show(kp[0]),
                        show(kp[1]),
                        show(kp[2]),
                        show(0.5 * spacing),
                        show(radius)
                    ),
                ));
            }
            if let Some((other, _)) = cage.shared_top.iter().find(|(c, _)| *c == col) {
                let _ = other;
                return Err(err(
                    p,
                    &pf,
                    format!("point \"{name}\" is at top knot {col}, as another point of the list"),
                ));
            }
            cage.shared_top.push((col, node));
        }
    }
    if let Some(t) = &n.sinker_tube {
        let f = format!("{field}.sinker_tube");
        let line_type = ring_line_type(
            p,
            &f,
            t.line_type.as_deref(),
            t.pipe.as_ref(),
            &format!("{}.tube", spec.name),
            line_types,
            model,
        )?;
        let &chain_line_type = line_types.get(&t.chain_line_type).ok_or_else(|| {
            err(
                p,
                format!("{f}.chain_line_type"),
                format!("unknown line type \"{}\"", t.chain_line_type),
            )
        })?;
        let chain_length = positive(p, &format!("{f}.chain_length"), t.chain_length)?;
        let tube_radius = match t.radius {
            Some(r) => positive(p, &format!("{f}.radius"), r)?,
            None => radius,
        };
        if (tube_radius - radius).abs() >= chain_length {
            return Err(err(
                p,
                format!("{f}.radius"),
                format!(
                    "the tube's radius {} m is {} m from the net's ({field}.size[0] = {} m): \
                     more than the chains' length ({f}.chain_length = {} m) can span",
                    show(tube_radius),
                    show((tube_radius - radius).abs()),
                    show(radius),
                    show(chain_length)
                ),
            ));
        }
        let z = top[2] - depth - chain_length;
        super::validate::height(
            p,
            &format!("{f}.chain_length"),
            [top[0] + tube_radius, top[1], z],
            model.env.depth,
            model.env.seabed.grid,
        )?;
        let every = t.every.unwrap_or(1);
        if every < 1 || every as usize > around {
            return Err(err(
                p,
                format!("{f}.every"),
                format!("must be an integer from 1 to the knots around ({around}), got {every}"),
            ));
        }
        cage.sinker_tube = Some(SinkerTube {
            ring: RingSpec {
                line_type,
                segments: segments(&format!("{f}.segments"), t.segments)?,
            },
            radius: tube_radius,
            chain_line_type,
            chain_length,
            every: every as usize,
            chain_segments: segments(&format!("{f}.chain_segments"), t.chain_segments)?,
        });
    }
    Ok(cage)
}

/// A ring's line type: a named one, or its `pipe` as a new line type `name`.
fn ring_line_type(
    p: &Path,
    f: &str,
    line_type: Option<&str>,
    pipe: Option<&RawPipe>,
    name: &str,
    line_types: &HashMap<String, usize>,
    model: &mut ModelDef,
) -> Result<usize, Error> {
    match (line_type, pipe) {
        (Some(_), Some(_)) | (None, None) => Err(err(
            p,
            f,
            "give the ring either `line_type` or `pipe`, one of them",
        )),
        (Some(l), None) => line_types.get(l).copied().ok_or_else(|| {
            err(
                p,
                format!("{f}.line_type"),
                format!("unknown line type \"{l}\""),
            )
        }),
        (None, Some(r)) => {
            let g = |k: &str| format!("{f}.pipe.{k}");
            let diameter = positive(p, &g("diameter"), r.diameter)?;
            let wall = positive(p, &g("wall"), r.wall)?;
            if wall > 0.5 * diameter {
                return Err(err(
                    p,
                    g("wall"),
                    format!(
                        "the wall ({} m) is thicker than half the diameter ({} m)",
                        show(wall),
                        show(diameter)
                    ),
                ));
            }
            let pipe = Pipe {
                diameter,
                wall,
                density: positive(p, &g("density"), r.density.unwrap_or(HDPE_DENSITY))?,
                youngs_modulus: positive(
                    p,
                    &g("youngs_modulus"),
                    r.youngs_modulus.unwrap_or(HDPE_MODULUS),
                )?,
                flooded: r.flooded.unwrap_or(false),
                ballast: non_negative(p, &g("ballast"), r.ballast.unwrap_or(0.0))?,
                cn: non_negative(p, &g("cn"), r.cn.unwrap_or(1.2))?,
                cm: non_negative(p, &g("cm"), r.cm.unwrap_or(1.0))?,
            };
            model
                .line_types
                .push(pipe.line_type(name.to_string(), model.env.water_density));
            Ok(model.line_types.len() - 1)
        }
    }
}

/// Warns when cage `info`'s collar cannot float what hangs from it, or barely: with the
/// freeboard of [`crate::model::cage::flotation`].
pub fn check_flotation(p: &Path, field: &str, model: &ModelDef, info: &NetInfo) {
    let Some(Flotation {
        capacity,
        load,
        freeboard,
    }) = crate::model::cage::flotation(model, info)
    else {
        return;
    };
    if load >= capacity {
        warnings::warn(format!(
            "{}: {field}.collar: the collar cannot float its net: its buoyancy submerged is \
             {} N, what it carries (its own weight, the net's, the sinkers', the sinker \
             tube's and the chains' in water) {} N; freeboard {} m: it sinks",
            p.display(),
            show(capacity),
            show(load),
            show(freeboard)
        ));
    } else if load > 0.9 * capacity {
        warnings::warn(format!(
            "{}: {field}.collar: the collar carries {} N of its {} N buoyancy ({:.0}%): \
             freeboard {} m, little reserve for the mooring's pull and the waves",
            p.display(),
            show(load),
            show(capacity),
            100.0 * load / capacity,
            show(freeboard)
        ));
    }
}
