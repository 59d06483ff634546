//! `[[points]]`: named nodes that cable ends share.

use super::ends::{self, EndKind};
use super::{bodies, err, validate, NamedPoint};
use crate::error::Error;
use crate::model::{ModelDef, NodeDef};
use std::collections::HashMap;
use std::path::Path;

/// The points read, each a node of the model.
pub(super) struct Points {
    /// Node of each point by name (for the ends that name one).
    pub index: HashMap<String, usize>,
    /// Name and node of each, in scenario order.
    pub named: Vec<NamedPoint>,
    /// (field, node, free) of each point, for the check of unused points.
    pub fields: Vec<(String, usize, bool)>,
    /// (field, node, failure) of each point that fails (its `cable` is the point's
    /// name): every cable end on it fails with it.
    pub failures: Vec<(String, usize, crate::model::EndFailure)>,
}

/// Adds a node to `model` for each `[[points]]` table, validated (positions above the
/// seabed at `depth`, routes slower than `max_speed`).
pub(super) fn parse(
    p: &Path,
    tables: &[toml::Table],
    bodies: &bodies::Bodies,
    depth: f64,
    max_speed: f64,
    model: &mut ModelDef,
) -> Result<Points, Error> {
    let mut point_index: HashMap<String, usize> = HashMap::new();
    let mut named_points = Vec::with_capacity(tables.len());
    // (field, node, free) of each point, for the check of unused points.
    let mut point_fields = Vec::with_capacity(tables.len());
    let mut point_failures = Vec::new();
    for (i, t) in tables.iter().enumerate() {
        let field = format!("points[{i}]");
        let name = match t.get("name") {
            Some(toml::Value::String(s)) => s.clone(),
            _ => {
                return Err(err(
                    p,
                    format!("{field}.name"),
                    "every point needs a string `name`",
                ))
            }
        };
        let field = format!("points[{i}] (\"{name}\")");
        let spec = ends::parse_end(
            p,
            &field,
            t,
            &["name", "fail_time", "fail_tension"],
            &HashMap::new(),
            bodies,
        )?;
        if let Some(fl) = super::cables::failure(p, &field, t, &spec.kind, &name, true)? {
            point_failures.push((field.clone(), model.nodes.len(), fl));
        }
        let free = matches!(spec.kind, EndKind::Free(_));
        let (position, route, point) = match spec.kind {
            EndKind::Point(_) => {
                return Err(err(p, field, "a point cannot refer to another point"))
            }
            EndKind::Fixed(x) | EndKind::Free(x) => (x, spec.route, spec.mass),
            EndKind::Route => (
                spec.route
                    .as_ref()
                    .map(|r| r.eval(0.0).r)
                    .unwrap_or([0.0; 3]),
                spec.route,
                spec.mass,
            ),
        };
        validate::position(p, &field, position)?;
        validate::height(p, &field, position, depth, model.env.seabed.grid)?;
        if let Some(r) = &route {
            validate::route_speed(p, &field, r, max_speed)?;
        }
        point_fields.push((field.clone(), model.nodes.len(), free));
        named_points.push(NamedPoint {
            name: name.clone(),
            node: model.nodes.len(),
        });
        if point_index
            .insert(name.clone(), model.nodes.len())
            .is_some()
        {
            return Err(err(
                p,
                format!("{field}.name"),
                format!("duplicate point name \"{name}\""),
            ));
        }
        model.nodes.push(NodeDef {
            position,
            point,
            route,
            label: Some(name),
        });
    }
    Ok(Points {
        index: point_index,
        named: named_points,
        fields: point_fields,
        failures: point_failures,
    })
}
