//! Nets built from a few numbers (aquaculture net panels and cylindrical cages): knots
//! on a rectangular or cylindrical grid, joined by twines (cables of a few elements)
//! along rows and columns, so that every knot is a node shared by up to four twines.
//!
//! The top row of knots is held where it is generated (a floating collar or a
//! headline, as a fixed route); the bottom row can carry sinkers (point masses). The
//! twines start straight at their unstretched length, so the net starts at rest as
//! generated and sags under its weight and the current from there.

use super::{CableDef, ModelDef, NodeDef, PointMass, Route};
use crate::error::Error;

/// The grid of a net.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NetShape {
    /// A vertical panel in the x-z plane: `columns x rows` knots, `width x depth` m,
    /// its top-left knot at `top`, columns along +x, rows down -z.
    Panel {
        /// Knots across.
        columns: usize,
        /// Knots down.
        rows: usize,
        /// Width, m.
        width: f64,
        /// Depth, m.
        depth: f64,
        /// Top-left knot, m.
        top: [f64; 3],
    },
    /// A cylinder about a vertical axis: `around x rows` knots, closed around, `radius`
    /// and `depth` m, the centre of its top ring at `top`.
    Cylinder {
        /// Knots around.
        around: usize,
        /// Knots down.
        rows: usize,
        /// Radius, m.
        radius: f64,
        /// Depth, m.
        depth: f64,
        /// Centre of the top ring, m.
        top: [f64; 3],
    },
}

/// Everything a net is built from.
#[derive(Clone, Debug, PartialEq)]
pub struct NetSpec {
    /// Name: cables are `NAME.h<row>.<col>` (along rows) and `NAME.v<row>.<col>`
    /// (down columns), knots are labelled `NAME.knot<row>.<col>`.
    pub name: String,
    /// Index into `ModelDef::line_types` (the twine).
    pub line_type: usize,
    /// Index into `ModelDef::currents`.
    pub current: usize,
    /// The grid.
    pub shape: NetShape,
    /// Elements per twine (at least 1).
    pub segments: usize,
    /// A point mass at every knot of the bottom row (none when its mass is zero).
    pub sinker: PointMass,
    /// Whether the twines' node positions are written out.
    pub output_positions: bool,
    /// Screen-model loads on the netting (`super::screen`), or `None`: the twines'
    /// Morison drag. With a screen model the twines keep their mass, weight, buoyancy
    /// and added mass but lose their drag; `axis` is set here (the cylinder's axis).
    pub screen: Option<super::ScreenNet>,
}

impl NetShape {
    /// Knots across (or around) and down.
    pub(crate) fn counts(&self) -> (usize, usize) {
        match *self {
            NetShape::Panel { columns, rows, .. } => (columns, rows),
            NetShape::Cylinder { around, rows, .. } => (around, rows),
        }
    }

    /// Position of knot `(row, col)`.
    pub(crate) fn knot(&self, row: usize, col: usize) -> [f64; 3] {
        match *self {
            NetShape::Panel {
                columns,
                rows,
                width,
                depth,
                top,
            } => [
                top[0] + width * col as f64 / (columns - 1) as f64,
                top[1],
                top[2] - depth * row as f64 / (rows - 1) as f64,
            ],
            NetShape::Cylinder {
                around,
                rows,
                radius,
                depth,
                top,
            } => {
                let a = std::f64::consts::TAU * col as f64 / around as f64;
                [
                    top[0] + radius * a.cos(),
                    top[1] + radius * a.sin(),
                    top[2] - depth * row as f64 / (rows - 1) as f64,
                ]
            }
        }
    }
}

/// Appends net `spec` to `def`: its knots and twine nodes, and its twines as cables.
/// Returns the number of cables added. Errors name the net and what is wrong.
pub fn add_net(def: &mut ModelDef, spec: &NetSpec) -> Result<usize, Error> {
    add_net_at(def, spec, None)
}

/// [`add_net`], with the top row held (`top` `None`) or hanging from what it is joined
/// to (`Some`: a cage's collar, `super::cage`): then no top knot is held, and
/// `top[col]`, where given, is an existing node (a `[[points]]` entry) that serves as
/// knot `(0, col)` instead of a new one, keeping its own route and point mass.
pub fn add_net_at(
    def: &mut ModelDef,
    spec: &NetSpec,
    top: Option<&[Option<usize>]>,
) -> Result<usize, Error> {
    let bad = |m: String| Error::Model(format!("net '{}': {m}", spec.name));
    let (nc, nr) = spec.shape.counts();
    let closed = matches!(spec.shape, NetShape::Cylinder { .. });
    if nr < 2 || nc < if closed { 3 } else { 2 } {
        return Err(bad(format!(
            "needs at least {} knots across and 2 down, got {nc} x {nr}",
            if closed { 3 } else { 2 }
        )));
    }
    let (size_a, size_b) = match spec.shape {
        NetShape::Panel { width, depth, .. } => (width, depth),
        NetShape::Cylinder { radius, depth, .. } => (radius, depth),
    };
    if !(size_a > 0.0 && size_b > 0.0 && size_a.is_finite() && size_b.is_finite()) {
        return Err(bad(format!(
            "size must be positive, got [{size_a}, {size_b}]"
        )));
    }
    if spec.segments == 0 {
        return Err(bad("segments must be at least 1".into()));
    }
    let mut knots = Vec::with_capacity(nr * nc);
    for row in 0..nr {
        for col in 0..nc {
            let p = spec.shape.knot(row, col);
            if let Some(&Some(shared)) = top.and_then(|t| t.get(col)).filter(|_| row == 0) {
                knots.push(shared);
                continue;
            }
            knots.push(def.nodes.len());
            def.nodes.push(NodeDef {
                position: p,
                point: if row == nr - 1 {
                    spec.sinker
                } else {
                    PointMass::default()
                },
                route: (row == 0 && top.is_none()).then_some(Route::Fixed { position: p }),
                label: Some(format!("{}.knot{row}.{col}", spec.name)),
            });
        }
    }
    let knot = |row: usize, col: usize| knots[row * nc + col];
    // Screen loads: the knots and their grid neighbours, and the twines' line type
    // without drag (a copy, so that other cables of the line type keep theirs).
    let mut line_type = spec.line_type;
    if let Some(sn) = spec.screen {
        let axis = match spec.shape {
            NetShape::Cylinder { top, .. } => [top[0], top[1]],
            NetShape::Panel { .. } => {
                if sn.wake != super::WakeModel::None {
                    return Err(bad(
                        "wake shielding needs a closed net (shape = \"cylinder\"): a plane \
                         panel has no downstream side of its own"
                            .into(),
                    ));
                }
                [0.0, 0.0]
            }
        };
        let net = def.screens.nets.len() as u32;
        def.screens.nets.push(super::ScreenNet { axis, ..sn });
        let at = |row: i64, col: i64| -> u32 {
            let col = if closed {
                col.rem_euclid(nc as i64)
            } else {
                col
            };
            if row < 0 || row >= nr as i64 || col < 0 || col >= nc as i64 {
                super::NO_KNOT
            } else {
                knot(row as usize, col as usize) as u32
            }
        };
        for row in 0..nr as i64 {
            for col in 0..nc as i64 {
                let around = [
                    (-1, -1),
                    (-1, 0),
                    (-1, 1),
                    (0, 1),
                    (1, 1),
                    (1, 0),
                    (1, -1),
                    (0, -1),
                ]
                .map(|(dr, dc)| at(row + dr, col + dc));
                def.screens.knots.push(super::ScreenKnot {
                    node: at(row, col),
                    net,
                    around,
                });
            }
        }
        let mut lt = def.line_types[spec.line_type].clone();
        lt.name = format!("{} (net '{}', screen loads)", lt.name, spec.name);
        lt.cn = 0.0;
        lt.ct = 0.0;
        def.line_types.push(lt);
        line_type = def.line_types.len() - 1;
        def.screens.twine_lines.push((line_type, spec.line_type));
    }
    let mut added = 0;
    let mut twine = |def: &mut ModelDef, a: usize, b: usize, name: String| {
        let (pa, pb) = (def.nodes[a].position, def.nodes[b].position);
        let bar =
            ((pb[0] - pa[0]).powi(2) + (pb[1] - pa[1]).powi(2) + (pb[2] - pa[2]).powi(2)).sqrt();
        let n = spec.segments;
        let mut nodes = Vec::with_capacity(n + 1);
        nodes.push(a);
        for k in 1..n {
            let f = k as f64 / n as f64;
            nodes.push(def.nodes.len());
            def.nodes.push(NodeDef {
                position: [0, 1, 2].map(|d| pa[d] + f * (pb[d] - pa[d])),
                point: PointMass::default(),
                route: None,
                label: None,
            });
        }
        nodes.push(b);
        def.cables.push(CableDef {
            name,
            line_type,
            nodes,
            l0: vec![bar / n as f64; n],
            current: spec.current,
            output_positions: spec.output_positions,
            elem_lines: Vec::new(),
        });
        added += 1;
    };
    for row in 0..nr {
        let cols = if closed { nc } else { nc - 1 };
        for col in 0..cols {
            twine(
                def,
                knot(row, col),
                knot(row, (col + 1) % nc),
                format!("{}.h{row}.{col}", spec.name),
            );
        }
    }
    for row in 0..nr - 1 {
        for col in 0..nc {
            twine(
                def,
                knot(row, col),
                knot(row + 1, col),
                format!("{}.v{row}.{col}", spec.name),
            );
        }
    }
    Ok(added)
}
