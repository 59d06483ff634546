//! `[[nets]]`: a net panel or a cylindrical cage from a few numbers (docs/src/scenario.md, "[[nets]]");
//! the geometry is built by [`crate::model::add_net`].

use super::raw::RawNet;
use super::{current, err, finite, non_negative, positive};
use crate::error::Error;
use crate::model::{ModelDef, NetShape, NetSpec, PointMass};
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
    Ok(NetSpec {
        name: n.name.clone(),
        line_type,
        current: cur,
        shape,
        segments: segments as usize,
        sinker,
        output_positions: n.output_positions.unwrap_or_else(|| output(&n.name)),
    })
}
