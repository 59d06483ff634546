//! Net cages as fish farms float them (docs/src/cage.md): a cylindrical net
//! ([`super::net`]) hung from a floating collar, a ring of pipe that rides the water
//! surface and bends, and kept in shape by a sinker tube, a heavy ring on chains below
//! the net; and what a designer reads off a run: the volume the net encloses and the
//! water's force on it.
//!
//! The collar is a ring of cables, one between each two neighbouring top knots of the
//! net, so that the top knots are the collar's nodes: the net hangs from the collar
//! instead of being held. The cables of a ring are joined end to end by
//! [`super::Joint`]s, so that with `EI > 0` the ring bends as one pipe across the
//! knots. The sinker tube is the same ring below the net, joined to its bottom knots by
//! chains. A ring's nodes start on its circle (the knots' polygon refined on the arc),
//! so that a ring of pipe with bending stiffness and no rest curvature starts as a
//! regular polygon, in equilibrium under its own bending.

use super::{CableDef, Joint, LineType, ModelDef, NetShape, NetSpec, NodeDef, PointMass};
use crate::error::Error;
use std::f64::consts::PI;
use std::ops::Range;

/// A pipe (HDPE for a collar) as a line type: its section from the outer diameter and
/// the wall, its mass from the material's density, `EA` and `EI` from its Young's
/// modulus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pipe {
    /// Outer diameter `D`, m (the hydrodynamic and buoyant diameter).
    pub diameter: f64,
    /// Wall thickness `t`, m (`0 < t <= D / 2`).
    pub wall: f64,
    /// Density of the material, kg/m^3 (HDPE about 950).
    pub density: f64,
    /// Young's modulus `E`, Pa (HDPE about 0.9e9 to 1.1e9).
    pub youngs_modulus: f64,
    /// Whether the bore is flooded (its water is carried as mass; a collar's is dry).
    pub flooded: bool,
    /// Ballast carried inside per length (chain or concrete in a sinker tube), kg/m.
    pub ballast: f64,
    /// Normal drag coefficient `Cn`.
    pub cn: f64,
    /// Normal added-mass coefficient `Cm`.
    pub cm: f64,
}

impl Pipe {
    /// The wall's section `pi (D^2 - d^2) / 4`, `d = D - 2 t`, m^2.
    pub fn wall_area(&self) -> f64 {
        let d = self.diameter - 2.0 * self.wall;
        PI / 4.0 * (self.diameter.powi(2) - d.powi(2))
    }

    /// The section's second moment `pi (D^4 - d^4) / 64`, m^4.
    pub fn second_moment(&self) -> f64 {
        let d = self.diameter - 2.0 * self.wall;
        PI / 64.0 * (self.diameter.powi(4) - d.powi(4))
    }

    /// The pipe as a line type named `name`: diameter `D`, mass per length the wall's
    /// (`density` times its section) plus the ballast and, when flooded, the bore's
    /// water (`water_density`), `EA = E A_wall`, `EI = E I`, drag and added mass as
    /// given, the tangential drag 0.01 of any line type.
    pub fn line_type(&self, name: String, water_density: f64) -> LineType {
        let bore = PI / 4.0 * (self.diameter - 2.0 * self.wall).powi(2);
        LineType {
            name,
            diameter: self.diameter,
            mass_per_length: self.density * self.wall_area()
                + self.ballast
                + if self.flooded {
                    water_density * bore
                } else {
                    0.0
                },
            ea: self.youngs_modulus * self.wall_area(),
            damping: 0.0,
            cn: self.cn,
            ct: 0.01,
            cm: self.cm,
            cat: 0.0,
            ei: self.youngs_modulus * self.second_moment(),
            allow_compression: true,
            ea_curve: None,
            viscoelastic: None,
        }
    }
}

/// A ring of a cage (its collar or its sinker tube).
#[derive(Clone, Debug, PartialEq)]
pub struct RingSpec {
    /// Index into `ModelDef::line_types`.
    pub line_type: usize,
    /// Elements between two neighbouring knots (at least 1).
    pub segments: usize,
}

/// The sinker tube: a ring below the net's bottom row on chains.
#[derive(Clone, Debug, PartialEq)]
pub struct SinkerTube {
    /// The ring.
    pub ring: RingSpec,
    /// Its radius, m.
    pub radius: f64,
    /// The chains' line type (index into `ModelDef::line_types`).
    pub chain_line_type: usize,
    /// How far the tube hangs below the bottom row (the chains' length when the tube's
    /// radius is the net's), m.
    pub chain_length: f64,
    /// A chain at every `every`-th bottom knot, from knot 0.
    pub every: usize,
    /// Elements per chain.
    pub chain_segments: usize,
}

/// What a cylindrical net becomes a cage with.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CageSpec {
    /// The floating collar (none: the top row is held, as a plain net's).
    pub collar: Option<RingSpec>,
    /// Existing nodes (`[[points]]`) that serve as top knots: `(column, node)`.
    pub shared_top: Vec<(usize, usize)>,
    /// The sinker tube.
    pub sinker_tube: Option<SinkerTube>,
}

/// A net as a run reports it (`nets.csv`): where its knots and parts are.
#[derive(Clone, Debug, PartialEq)]
pub struct NetInfo {
    /// The net's name.
    pub name: String,
    /// Knots around and down.
    pub around: usize,
    /// Rows of knots.
    pub rows: usize,
    /// The twines (indices into `ModelDef::cables`): first the `around` twines of each
    /// row in turn (`NAME.h<row>.<col>`, which start at knot `(row, col)`), then the
    /// twines down.
    pub twines: Range<usize>,
    /// The collar's cables (`NAME.collar.<col>`, from top knot `col` to the next).
    pub collar: Range<usize>,
    /// The sinker tube's cables (`NAME.tube.<col>`).
    pub tube: Range<usize>,
    /// The chains (`NAME.chain.<col>`).
    pub chains: Range<usize>,
    /// The volume the net encloses as generated (its knots on the cylinder), m^3.
    pub reference_volume: f64,
    /// The net's current (index into `ModelDef::currents`).
    pub current: usize,
}

impl NetInfo {
    /// The twine that starts at knot `(row, col)` (its first node is the knot).
    pub fn knot_cable(&self, row: usize, col: usize) -> usize {
        self.twines.start + row * self.around + col
    }
}

/// The volume enclosed by a cylindrical net's knots, m^3: `knots` row by row
/// (`around` per row, the rows from the top down), closed by the polygons of its top
/// and bottom rows. The closed surface is the side's quadrilaterals between
/// neighbouring knots of neighbouring rows, each cut into two triangles along its
/// diagonal from knot `(row, col)` to `(row + 1, col + 1)`, and each ring's polygon
/// fanned from its centroid; the volume is the divergence theorem's sum over those
/// triangles of `a . (b x c) / 6` (vertices taken from the centroid of all knots),
/// positive for a net whose knots run anticlockwise seen from above, as generated.
/// For knots on a cylinder of radius `r` and height `h` it is the prism
/// `around / 2 r^2 sin(2 pi / around) h`.
pub fn enclosed_volume(knots: &[[f64; 3]], around: usize) -> f64 {
    let n = around;
    if n < 3 || knots.len() < 2 * n || knots.len() % n != 0 {
        return 0.0;
    }
    let rows = knots.len() / n;
    let mut o = [0.0; 3];
    for k in knots {
        (0..3).for_each(|d| o[d] += k[d] / knots.len() as f64);
    }
    let p = |i: usize| -> [f64; 3] { [0, 1, 2].map(|d| knots[i][d] - o[d]) };
    let triple = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1])
            + a[1] * (b[2] * c[0] - b[0] * c[2])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
    };
    let mut six_v = 0.0;
    for row in 0..rows - 1 {
        for col in 0..n {
            let a = p(row * n + col);
            let b = p(row * n + (col + 1) % n);
            let c = p((row + 1) * n + (col + 1) % n);
            let d = p((row + 1) * n + col);
            six_v += triple(a, d, c) + triple(a, c, b);
        }
    }
    for (row, sign) in [(0, 1.0), (rows - 1, -1.0)] {
        let mut m = [0.0; 3];
        for col in 0..n {
            let q = p(row * n + col);
            (0..3).for_each(|d| m[d] += q[d] / n as f64);
        }
        for col in 0..n {
            let (a, b) = (p(row * n + col), p(row * n + (col + 1) % n));
            six_v += sign * triple(m, a, b);
        }
    }
    six_v / 6.0
}

/// Appends cylindrical net `spec` to `def` as a cage: the net (its top row hanging from
/// the collar when there is one, else held), the collar's and the sinker tube's rings
/// and the chains. Returns where its parts are. Errors name the net and what is wrong.
pub fn add_cage(def: &mut ModelDef, spec: &NetSpec, cage: &CageSpec) -> Result<NetInfo, Error> {
    let bad = |m: String| Error::Model(format!("net '{}': {m}", spec.name));
    let NetShape::Cylinder {
        around,
        rows,
        radius,
        depth,
        top,
    } = spec.shape
    else {
        if cage.collar.is_some() || cage.sinker_tube.is_some() {
            return Err(bad(
                "a collar or a sinker tube needs a cylindrical net".into()
            ));
        }
        let first = def.cables.len();
        let n = super::add_net(def, spec)?;
        let (around, rows) = spec.shape.counts();
        return Ok(NetInfo {
            name: spec.name.clone(),
            around,
            rows,
            twines: first..first + n,
            collar: first + n..first + n,
            tube: first + n..first + n,
            chains: first + n..first + n,
            reference_volume: 0.0,
            current: spec.current,
        });
    };
    let first = def.cables.len();
    let n_twines = if cage.collar.is_some() {
        let mut shared = vec![None; around];
        for &(col, node) in &cage.shared_top {
            if col >= around {
                return Err(bad(format!("no top knot {col}")));
            }
            shared[col] = Some(node);
        }
        super::net::add_net_at(def, spec, Some(&shared))?
    } else {
        if !cage.shared_top.is_empty() {
            return Err(bad("points join the top knots only with a collar".into()));
        }
        super::add_net(def, spec)?
    };
    let twines = first..first + n_twines;
    // Knot (row, col) is the first node of twine NAME.h<row>.<col>.
    let knot =
        |def: &ModelDef, row: usize, col: usize| def.cables[first + row * around + col].nodes[0];
    let generated: Vec<[f64; 3]> = (0..rows)
        .flat_map(|row| (0..around).map(move |col| (row, col)))
        .map(|(row, col)| spec.shape.knot(row, col))
        .collect();
    let reference_volume = enclosed_volume(&generated, around);

    let collar_start = def.cables.len();
    if let Some(ring) = &cage.collar {
        let ends: Vec<usize> = (0..around).map(|c| knot(&*def, 0, c)).collect();
        add_ring(
            def,
            spec,
            "collar",
            ring,
            &ends,
            [top[0], top[1]],
            radius,
            top[2],
        )?;
    }
    let collar = collar_start..def.cables.len();
    let tube_start = def.cables.len();
    let mut chains = tube_start..tube_start;
    if let Some(t) = &cage.sinker_tube {
        if t.every == 0 || t.chain_segments == 0 {
            return Err(bad(
                "the sinker tube's chains need every >= 1 and segments >= 1".into(),
            ));
        }
        let z = top[2] - depth - t.chain_length;
        let first_node = def.nodes.len();
        for col in 0..around {
            let a = 2.0 * PI * col as f64 / around as f64;
            def.nodes.push(NodeDef {
                position: [top[0] + t.radius * a.cos(), top[1] + t.radius * a.sin(), z],
                point: PointMass::default(),
                route: None,
                label: Some(format!("{}.tube{col}", spec.name)),
            });
        }
        let ends: Vec<usize> = (first_node..first_node + around).collect();
        add_ring(
            def,
            spec,
            "tube",
            &t.ring,
            &ends,
            [top[0], top[1]],
            t.radius,
            z,
        )?;
        let chain_start = def.cables.len();
        for col in (0..around).step_by(t.every) {
            let (a, b) = (knot(&*def, rows - 1, col), ends[col]);
            add_straight(
                def,
                format!("{}.chain.{col}", spec.name),
                t.chain_line_type,
                spec,
                a,
                b,
                t.chain_segments,
            );
        }
        chains = chain_start..def.cables.len();
    }
    let tube = tube_start..chains.start.max(tube_start);
    Ok(NetInfo {
        name: spec.name.clone(),
        around,
        rows,
        twines,
        collar,
        tube,
        chains,
        reference_volume,
        current: spec.current,
    })
}

/// A ring of cables `NAME.<part>.<col>` through nodes `ends` (one per knot, on the
/// circle of `radius` about `centre` at height `z`), `ring.segments` elements each,
/// their inner nodes on the arc; each cable joined to the next ([`Joint`]), the last to
/// the first.
#[allow(clippy::too_many_arguments)]
fn add_ring(
    def: &mut ModelDef,
    spec: &NetSpec,
    part: &str,
    ring: &RingSpec,
    ends: &[usize],
    centre: [f64; 2],
    radius: f64,
    z: f64,
) -> Result<(), Error> {
    let n = ends.len();
    let s = ring.segments;
    if s == 0 {
        return Err(Error::Model(format!(
            "net '{}': the {part}'s segments must be at least 1",
            spec.name
        )));
    }
    let first = def.cables.len();
    for col in 0..n {
        let mut nodes = vec![ends[col]];
        for k in 1..s {
            let a = 2.0 * PI * (col as f64 + k as f64 / s as f64) / n as f64;
            nodes.push(def.nodes.len());
            def.nodes.push(NodeDef {
                position: [
                    centre[0] + radius * a.cos(),
                    centre[1] + radius * a.sin(),
                    z,
                ],
                point: PointMass::default(),
                route: None,
                label: None,
            });
        }
        nodes.push(ends[(col + 1) % n]);
        let l0 = nodes
            .windows(2)
            .map(|w| distance(def.nodes[w[0]].position, def.nodes[w[1]].position))
            .collect();
        def.cables.push(CableDef {
            name: format!("{}.{part}.{col}", spec.name),
            line_type: ring.line_type,
            nodes,
            l0,
            current: spec.current,
            output_positions: spec.output_positions,
            elem_lines: Vec::new(),
        });
    }
    for col in 0..n {
        def.joints.push(Joint {
            prev: first + col,
            next: first + (col + 1) % n,
        });
    }
    Ok(())
}

/// A straight cable `name` from node `a` to node `b` of `segments` equal elements at
/// its unstretched length.
fn add_straight(
    def: &mut ModelDef,
    name: String,
    line_type: usize,
    spec: &NetSpec,
    a: usize,
    b: usize,
    segments: usize,
) {
    let (pa, pb) = (def.nodes[a].position, def.nodes[b].position);
    let mut nodes = vec![a];
    for k in 1..segments {
        let f = k as f64 / segments as f64;
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
        l0: vec![distance(pa, pb) / segments as f64; segments],
        current: spec.current,
        output_positions: spec.output_positions,
        elem_lines: Vec::new(),
    });
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
}

/// How a cage floats, from its parts' weights in water (the hand calculation of
/// docs/src/cage.md; what the collar's mooring adds is not known here).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flotation {
    /// The collar's buoyancy when just submerged, `rho g A L`, N.
    pub capacity: f64,
    /// What it carries: its own weight, the net's, the sinkers', the sinker tube's and
    /// the chains' weight less buoyancy, N.
    pub load: f64,
    /// Where the collar's node line sits above still water at rest, m: the model wets
    /// a band of one diameter below the node line ([`crate::physics::wetted_fraction`]),
    /// so the band's wet share is `load / capacity` and the node line is
    /// `D (1 - load / capacity)` above the water (negative: the collar sinks).
    pub freeboard: f64,
}

/// The flotation of cage `info` in `def` (`None` without a collar).
pub fn flotation(def: &ModelDef, info: &NetInfo) -> Option<Flotation> {
    let c0 = def.cables.get(info.collar.start)?;
    if info.collar.is_empty() {
        return None;
    }
    let (g, rho) = (def.env.gravity, def.env.water_density);
    let line_weight = |r: &Range<usize>| -> f64 {
        def.cables[r.clone()]
            .iter()
            .map(|c| {
                let lt = &def.line_types[c.line_type];
                lt.wet_weight_per_length(g, rho) * c.l0.iter().sum::<f64>()
            })
            .sum()
    };
    let collar_lt = &def.line_types[c0.line_type];
    let length: f64 = def.cables[info.collar.clone()]
        .iter()
        .map(|c| c.l0.iter().sum::<f64>())
        .sum();
    let capacity = rho * g * collar_lt.area() * length;
    let collar_weight = collar_lt.mass_per_length * g * length;
    // Point masses on the net's knots (sinkers) and on the tube's nodes.
    let mut points = 0.0;
    let mut seen = std::collections::HashSet::new();
    for r in [&info.twines, &info.tube, &info.chains] {
        for c in &def.cables[r.clone()] {
            for &n in &c.nodes {
                if seen.insert(n) {
                    let p = &def.nodes[n].point;
                    if def.nodes[n].route.is_none() {
                        points += (p.mass - rho * p.volume) * g;
                    }
                }
            }
        }
    }
    let load = collar_weight
        + line_weight(&info.twines)
        + line_weight(&info.tube)
        + line_weight(&info.chains)
        + points;
    Some(Flotation {
        capacity,
        load,
        freeboard: collar_lt.diameter * (1.0 - load / capacity),
    })
}
