//! `[[nets]]`: a net panel or a cylindrical cage from a few numbers (docs/src/scenario.md, "[[nets]]");
//! the geometry is built by [`crate::model::add_net`].

use super::raw::RawNet;
use super::{current, err, finite, non_negative, positive};
use crate::error::Error;
use crate::model::{ModelDef, NetShape, NetSpec, PointMass, ScreenModel, ScreenNet, WakeModel};
use std::collections::HashMap;
use std::path::Path;

/// Validates net `n` (its field prefix `field`) into a [`NetSpec`]; a per-net current
/// is added to `model.currents`. `output` says whether a net of this name writes its
/// positions when the net itself does not say.
pub fn parse(
    p: &Path,
    field: &str,
    n: &RawNet,
    line_types: &HashMap<String, usize>,
    model: &mut ModelDef,
    output: impl Fn(&str) -> bool,
) -> Result<NetSpec, Error> {
    let f = |k: &str| format!("{field}.{k}");
    let &line_type = line_types.get(&n.line_type).ok_or_else(|| {
        err(
            p,
            f("line_type"),
            format!("unknown line type \"{}\"", n.line_type),
        )
    })?;
    let ei = model.line_types[line_type].ei;
    if ei > 0.0 {
        return Err(err(
            p,
            f("line_type"),
            format!(
                "line type \"{}\" has bending stiffness ei = {ei:e} N m^2: nets have no \
                 bending along their twines yet; give the net a line type with ei = 0",
                n.line_type
            ),
        ));
    }
    let [a, b] = n.knots;
    let closed = match n.shape.as_str() {
        "panel" => false,
        "cylinder" => true,
        other => {
            return Err(err(
                p,
                f("shape"),
                format!("must be \"panel\" or \"cylinder\", got \"{other}\""),
            ))
        }
    };
    let min_a = if closed { 3 } else { 2 };
    if a < min_a || b < 2 || a > 100_000 || b > 100_000 {
        return Err(err(
            p,
            f("knots"),
            format!("needs [across, down] with at least {min_a} across and 2 down, got [{a}, {b}]"),
        ));
    }
    let size = [
        positive(p, &format!("{}[0]", f("size")), n.size[0])?,
        positive(p, &format!("{}[1]", f("size")), n.size[1])?,
    ];
    for (k, x) in n.top.iter().enumerate() {
        finite(p, &format!("{}[{k}]", f("top")), *x)?;
    }
    super::validate::position(p, &f("top"), n.top)?;
    for (k, x) in size.iter().enumerate() {
        super::validate::magnitude(p, &format!("{}[{k}]", f("size")), *x, "m")?;
    }
    let segments = n.segments.unwrap_or(1);
    if !(1..=1000).contains(&segments) {
        return Err(err(
            p,
            f("segments"),
            format!("must be an integer from 1 to 1000, got {segments}"),
        ));
    }
    let sinker = match &n.sinker {
        None => PointMass::default(),
        Some(s) => PointMass {
            mass: non_negative(p, &f("sinker.mass"), s.mass)?,
            volume: non_negative(p, &f("sinker.volume"), s.volume.unwrap_or(0.0))?,
            drag_area: non_negative(p, &f("sinker.drag_area"), s.drag_area.unwrap_or(0.0))?,
            added_mass_coef: non_negative(p, &f("sinker.added_mass"), s.added_mass.unwrap_or(0.0))?,
        },
    };
    let cur = match current(p, &format!("{field}."), n.current, &n.current_profile)? {
        Some(c) => {
            model.currents.push(c);
            model.currents.len() - 1
        }
        None => 0,
    };
    let (a, b) = (a as usize, b as usize);
    let shape = if closed {
        NetShape::Cylinder {
            around: a,
            rows: b,
            radius: size[0],
            depth: size[1],
            top: n.top,
        }
    } else {
        NetShape::Panel {
            columns: a,
            rows: b,
            width: size[0],
            depth: size[1],
            top: n.top,
        }
    };
    let screen = screen(p, &f, n, model.line_types[line_type].diameter)?;
    if !closed && screen.is_some_and(|s| s.wake != WakeModel::None) {
        return Err(err(
            p,
            f("wake"),
            "wake shielding needs a closed net (shape = \"cylinder\"): a plane panel has no \
             downstream side of its own",
        ));
    }
    Ok(NetSpec {
        name: n.name.clone(),
        line_type,
        current: cur,
        shape,
        segments: segments as usize,
        sinker,
        output_positions: n.output_positions.unwrap_or_else(|| output(&n.name)),
        screen,
    })
}

/// The screen-model keys of net `n` (`f` names a key): `None` for Morison twines.
/// `diameter` is the line type's, the default twine diameter.
fn screen(
    p: &Path,
    f: &dyn Fn(&str) -> String,
    n: &RawNet,
    diameter: f64,
) -> Result<Option<ScreenNet>, Error> {
    let loads = n.loads.as_deref().unwrap_or("morison");
    match loads {
        "morison" => {
            let given = [
                ("screen_model", n.screen_model.is_some()),
                ("solidity", n.solidity.is_some()),
                ("mesh", n.mesh.is_some()),
                ("twine_diameter", n.twine_diameter.is_some()),
                ("viscosity", n.viscosity.is_some()),
                ("wake", n.wake.is_some()),
            ];
            if let Some((k, _)) = given.iter().find(|g| g.1) {
                return Err(err(
                    p,
                    f(k),
                    "is a key of the screen model: it needs loads = \"screen\"",
                ));
            }
            return Ok(None);
        }
        "screen" => {}
        other => {
            return Err(err(
                p,
                f("loads"),
                format!("must be \"morison\" or \"screen\", got \"{other}\""),
            ))
        }
    }
    let model = match n.screen_model.as_deref() {
        None => {
            return Err(err(
                p,
                f("screen_model"),
                "is required with loads = \"screen\": \"aarsnes\", \"loland\" or \
                 \"kristiansen_faltinsen\"",
            ))
        }
        Some(s) => ScreenModel::parse(s).ok_or_else(|| {
            err(
                p,
                f("screen_model"),
                format!(
                    "must be \"aarsnes\", \"loland\" or \"kristiansen_faltinsen\", got \"{s}\""
                ),
            )
        })?,
    };
    let twine_diameter = match n.twine_diameter {
        Some(d) => positive(p, &f("twine_diameter"), d)?,
        None => diameter,
    };
    let solidity = match (n.solidity, n.mesh) {
        (Some(_), Some(_)) => {
            return Err(err(
                p,
                f("mesh"),
                "give the netting by solidity or by mesh, not both",
            ))
        }
        (None, None) => {
            return Err(err(
                p,
                f("solidity"),
                "loads = \"screen\" needs the netting's solidity (or its mesh)",
            ))
        }
        (Some(sn), None) => {
            if !(sn > 0.0 && sn < 1.0) {
                return Err(err(
                    p,
                    f("solidity"),
                    format!("must be between 0 and 1 (exclusive), got {sn}"),
                ));
            }
            sn
        }
        (None, Some(mesh)) => {
            let mesh = positive(p, &f("mesh"), mesh)?;
            if mesh <= twine_diameter {
                return Err(err(
                    p,
                    f("mesh"),
                    format!(
                        "{mesh} m is not coarser than the twine ({twine_diameter} m): the \
                         meshes would be closed"
                    ),
                ));
            }
            let x = twine_diameter / mesh;
            2.0 * x - x * x
        }
    };
    let viscosity = positive(p, &f("viscosity"), n.viscosity.unwrap_or(1.0e-6))?;
    let wake = match n.wake.as_deref() {
        None => WakeModel::None,
        Some(s) => WakeModel::parse(s).ok_or_else(|| {
            err(
                p,
                f("wake"),
                format!("must be \"none\", \"loland\" or \"cheng\", got \"{s}\""),
            )
        })?,
    };
    Ok(Some(ScreenNet {
        model,
        solidity,
        twine_diameter,
        viscosity,
        wake,
        axis: [0.0, 0.0],
    }))
}
