//! The packed layout: every cable of a run in flat arrays.
//!
//! Nodes and elements of all cables live in single arrays; each node has an
//! incidence list (compressed rows) naming the elements it belongs to, so forces are
//! gathered per node without atomics; constrained nodes point into a route table.
//! Nodes and elements are ordered by *block*: a block is a connected component (one
//! cable, or a network of cables sharing nodes), contiguous in both arrays, so blocks
//! can be stepped independently (one thread, or one workgroup range, per block).
//!
//! The CPU reference path and the GPU path both read this layout.

use super::{Current, Environment, LineCoefs, LineType, Route};
use crate::error::Error;

/// Sentinel for "no constraint".
pub const NO_CONSTRAINT: u32 = u32::MAX;

/// A point mass attached to a node (clump weight, buoy, end mass).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointMass {
    /// Mass, kg.
    pub mass: f64,
    /// Displaced volume, m^3 (buoyancy `rho V g`).
    pub volume: f64,
    /// Drag coefficient times frontal area `Cd A`, m^2 (isotropic quadratic drag).
    pub drag_area: f64,
    /// Isotropic added-mass coefficient `Ca` (added mass `Ca rho V`).
    pub added_mass_coef: f64,
}

/// A node as a scenario describes it, before packing.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeDef {
    /// Initial position, m.
    pub position: [f64; 3],
    /// Optional point mass.
    pub point: PointMass,
    /// Prescribed motion, if any.
    pub route: Option<Route>,
    /// Name of the scenario entity that made this node (for error messages).
    pub label: Option<String>,
}

/// A cable as a scenario describes it, before packing.
#[derive(Clone, Debug, PartialEq)]
pub struct CableDef {
    /// Name, unique in the run.
    pub name: String,
    /// Index into `ModelDef::line_types` (the first section's when the cable has
    /// several).
    pub line_type: usize,
    /// Per element: its line type, for a cable of several sections (chain - rope -
    /// chain); empty when every element is `line_type`.
    pub elem_lines: Vec<usize>,
    /// The chain of node indices (into `ModelDef::nodes`), start to end.
    pub nodes: Vec<usize>,
    /// Unstretched length of each element (`nodes.len() - 1` of them), m.
    pub l0: Vec<f64>,
    /// Index into `ModelDef::currents`.
    pub current: usize,
    /// Whether node positions of this cable are written to the output.
    pub output_positions: bool,
}

/// A whole model as described, before packing.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ModelDef {
    /// Shared environment.
    pub env: Environment,
    /// Line types.
    pub line_types: Vec<LineType>,
    /// Current profiles (cables refer to them by index).
    pub currents: Vec<Current>,
    /// Nodes (shared nodes appear once and are referred to by several cables).
    pub nodes: Vec<NodeDef>,
    /// Cables.
    pub cables: Vec<CableDef>,
    /// Cable ends whose direction is held (bending, `super::bending`).
    pub clamps: Vec<super::Clamp>,
    /// Cables joined end to end that bend as one (bending, `super::bending`).
    pub joints: Vec<super::Joint>,
    /// Nets loaded by a screen model (`super::screen`), knots by described node.
    pub screens: super::Screens,
}

/// A cable in the packed layout.
#[derive(Clone, Debug, PartialEq)]
pub struct CableInfo {
    /// Name.
    pub name: String,
    /// Packed node indices, start to end.
    pub nodes: Vec<u32>,
    /// Packed element indices, start to end.
    pub elements: Vec<u32>,
    /// Line type index.
    pub line_type: usize,
    /// Current index.
    pub current: usize,
    /// Whether node positions are written out.
    pub output_positions: bool,
}

/// What [`Layout::build_indexed`] returns: the layout, the initial positions in packed
/// order, and the packed index of each described node.
pub type Packed = (Layout, Vec<[f64; 3]>, Vec<u32>);

/// A contiguous range of nodes and elements forming one connected component.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    /// First node.
    pub node_start: u32,
    /// One past the last node.
    pub node_end: u32,
    /// First element.
    pub elem_start: u32,
    /// One past the last element.
    pub elem_end: u32,
    /// True when the component is one simple chain in node order (node `i` and `i+1`
    /// joined by element `i`), which the static solver exploits.
    pub is_chain: bool,
}

/// All cables of a run in flat arrays (see the module doc).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Layout {
    /// Environment.
    pub env: Environment,
    /// Line types, as given.
    pub line_types: Vec<LineType>,
    /// Folded line constants, per line type.
    pub line_coefs: Vec<LineCoefs>,
    /// Currents, per profile.
    pub currents: Vec<Current>,
    /// Cables.
    pub cables: Vec<CableInfo>,
    /// Blocks (connected components), in node order.
    pub blocks: Vec<Block>,

    /// Per node: the cable it is reported under (the first cable that uses it).
    pub node_cable: Vec<u32>,
    /// Per node: its index within that cable's node list.
    pub node_index_in_cable: Vec<u32>,
    /// Per node: point mass, kg (plus its added mass, isotropic).
    pub node_point_mass: Vec<f64>,
    /// Per node: z component of the point's weight less buoyancy, N.
    pub node_point_weight_z: Vec<f64>,
    /// Per node: `1/2 rho Cd A` of the point, kg/m.
    pub node_point_drag: Vec<f64>,
    /// Per node: the point's added mass `Ca rho V` (part of `node_point_mass`), kg,
    /// which it loses in air.
    pub node_point_added: Vec<f64>,
    /// Per node: the mass of water the point displaces, `rho V`, kg (its buoyancy
    /// `rho V g`, part of `node_point_weight_z`, is lost in air).
    pub node_point_displaced: Vec<f64>,
    /// Per node: radius of the sphere of the point's volume, m (how its volume
    /// crosses the water surface, `physics::point_wetted_fraction`).
    pub node_point_radius: Vec<f64>,
    /// Per node: tributary length for seabed contact, m.
    pub node_tributary: Vec<f64>,
    /// Per node: current profile index (its cable's).
    pub node_current: Vec<u32>,
    /// Per node: constraint index, or [`NO_CONSTRAINT`].
    pub node_constraint: Vec<u32>,
    /// Incidence rows: node `i`'s entries are `inc[inc_start[i]..inc_start[i+1]]`.
    pub inc_start: Vec<u32>,
    /// Incidence entries: `element * 2 + side`, side 0 when the node is the element's
    /// node a, 1 when it is node b.
    pub inc: Vec<u32>,

    /// Per element: node a.
    pub elem_a: Vec<u32>,
    /// Per element: node b.
    pub elem_b: Vec<u32>,
    /// Per element: unstretched length, m.
    pub elem_l0: Vec<f64>,
    /// Per element: line type index.
    pub elem_line: Vec<u32>,
    /// Per element: cable index.
    pub elem_cable: Vec<u32>,
    /// Per element: current profile index.
    pub elem_current: Vec<u32>,

    /// Per constraint: the node it holds.
    pub constraint_node: Vec<u32>,
    /// Per constraint: its route.
    pub routes: Vec<Route>,
    /// Cable ends whose direction is held (`ModelDef::clamps`).
    pub clamps: Vec<super::Clamp>,
    /// Cables joined end to end that bend as one (`ModelDef::joints`).
    pub joints: Vec<super::Joint>,
    /// Screen-model nets (`ModelDef::screens`), knots by packed node, sorted.
    pub screen: super::Screens,
}

impl Layout {
    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.node_cable.len()
    }
    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.elem_a.len()
    }
    /// The incidence entries of node `i`.
    #[inline(always)]
    pub fn incidence(&self, i: usize) -> &[u32] {
        &self.inc[self.inc_start[i] as usize..self.inc_start[i + 1] as usize]
    }
    /// Whether any element of block `b` has a tabulated strain-tension curve or the
    /// viscoelastic model (such blocks take the CPU path's general passes, not the
    /// chain and network fast paths).
    pub fn block_has_curves(&self, b: &Block) -> bool {
        let special = |lt: &LineType| lt.ea_curve.is_some() || lt.viscoelastic.is_some();
        self.line_types.iter().any(special)
            && (b.elem_start..b.elem_end)
                .any(|e| special(&self.line_types[self.elem_line[e as usize] as usize]))
    }
    /// Whether any line type is viscoelastic (the solvers then carry one state per
    /// element: `physics::visco`).
    pub fn has_visco(&self) -> bool {
        self.line_types.iter().any(|lt| lt.viscoelastic.is_some())
    }

    /// Whether block `b` holds knots of a screen-model net.
    pub fn block_has_screen(&self, b: &Block) -> bool {
        !self.screen.knots_in(b.node_start, b.node_end).is_empty()
    }
    /// Where a packed node sits, for messages: `(cable name, node index in cable)`.
    pub fn describe_node(&self, i: usize) -> (String, usize) {
        let c = self.node_cable[i] as usize;
        (
            self.cables[c].name.clone(),
            self.node_index_in_cable[i] as usize,
        )
    }
    /// Where a packed element sits: `(cable name, element index in cable)`.
    pub fn describe_element(&self, e: usize) -> (String, usize) {
        let c = self.elem_cable[e] as usize;
        let k = self.cables[c]
            .elements
            .iter()
            .position(|&x| x as usize == e)
            .unwrap_or(0);
        (self.cables[c].name.clone(), k)
    }

    /// Replaces block `bi`, which must hold cable `ci` alone (a chain), by `one`: the
    /// layout of that cable alone (built from a description of it with this layout's
    /// one line type and current), whose node and element counts may differ. Nodes and
    /// elements after the block move by the difference; the block's constraints keep
    /// their numbers (`one`'s constraint `k` is this layout's `constraints[k]`, in the
    /// order `one` numbers them). The arrays are moved in place: no other block is
    /// rebuilt, so a winch cable remeshes in time proportional to the model's size
    /// with a small constant, not a full [`Layout::build`].
    /// `one` has one line type and one current; `line` and `current` are their indices
    /// here.
    pub fn splice_chain(
        &mut self,
        bi: usize,
        ci: usize,
        one: &Layout,
        constraints: &[u32],
        line: u32,
        current: u32,
    ) {
        let b = self.blocks[bi];
        let (ns, ne_old) = (b.node_start as usize, b.node_end as usize);
        let (es, ee_old) = (b.elem_start as usize, b.elem_end as usize);
        let (n_new, e_new) = (one.n_nodes(), one.n_elements());
        let dn = n_new as i64 - (ne_old - ns) as i64;
        let de = e_new as i64 - (ee_old - es) as i64;
        let sh = |x: u32, d: i64| (x as i64 + d) as u32;
        fn splice<T: Clone>(
            v: &mut Vec<T>,
            r: std::ops::Range<usize>,
            new: impl IntoIterator<Item = T>,
        ) {
            v.splice(r, new);
        }
        // Per node.
        splice(
            &mut self.node_cable,
            ns..ne_old,
            std::iter::repeat_n(ci as u32, n_new),
        );
        splice(
            &mut self.node_index_in_cable,
            ns..ne_old,
            one.node_index_in_cable.iter().copied(),
        );
        splice(
            &mut self.node_point_mass,
            ns..ne_old,
            one.node_point_mass.iter().copied(),
        );
        splice(
            &mut self.node_point_weight_z,
            ns..ne_old,
            one.node_point_weight_z.iter().copied(),
        );
        splice(
            &mut self.node_point_drag,
            ns..ne_old,
            one.node_point_drag.iter().copied(),
        );
        splice(
            &mut self.node_point_added,
            ns..ne_old,
            one.node_point_added.iter().copied(),
        );
        splice(
            &mut self.node_point_displaced,
            ns..ne_old,
            one.node_point_displaced.iter().copied(),
        );
        splice(
            &mut self.node_point_radius,
            ns..ne_old,
            one.node_point_radius.iter().copied(),
        );
        splice(
            &mut self.node_tributary,
            ns..ne_old,
            one.node_tributary.iter().copied(),
        );
        splice(
            &mut self.node_current,
            ns..ne_old,
            std::iter::repeat_n(current, n_new),
        );
        splice(
            &mut self.node_constraint,
            ns..ne_old,
            one.node_constraint.iter().map(|&k| {
                if k == NO_CONSTRAINT {
                    k
                } else {
                    constraints[k as usize]
                }
            }),
        );
        // Incidence rows of the block, then everything after it.
        let (i0, i1) = (self.inc_start[ns] as usize, self.inc_start[ne_old] as usize);
        let di = one.inc.len() as i64 - (i1 - i0) as i64;
        splice(
            &mut self.inc,
            i0..i1,
            one.inc.iter().map(|&x| x + 2 * es as u32),
        );
        for x in &mut self.inc[i0 + one.inc.len()..] {
            *x = sh(*x, 2 * de);
        }
        splice(
            &mut self.inc_start,
            ns..ne_old + 1,
            one.inc_start.iter().map(|&x| x + i0 as u32),
        );
        for x in &mut self.inc_start[ns + n_new + 1..] {
            *x = sh(*x, di);
        }
        // Per element.
        splice(
            &mut self.elem_a,
            es..ee_old,
            one.elem_a.iter().map(|&x| x + ns as u32),
        );
        splice(
            &mut self.elem_b,
            es..ee_old,
            one.elem_b.iter().map(|&x| x + ns as u32),
        );
        for x in self.elem_a[es + e_new..]
            .iter_mut()
            .chain(&mut self.elem_b[es + e_new..])
        {
            *x = sh(*x, dn);
        }
        splice(&mut self.elem_l0, es..ee_old, one.elem_l0.iter().copied());
        splice(
            &mut self.elem_line,
            es..ee_old,
            std::iter::repeat_n(line, e_new),
        );
        splice(
            &mut self.elem_cable,
            es..ee_old,
            std::iter::repeat_n(ci as u32, e_new),
        );
        splice(
            &mut self.elem_current,
            es..ee_old,
            std::iter::repeat_n(current, e_new),
        );
        // Screen knots after the block move with their nodes (none is in a winch block).
        let shift = |x: &mut u32| {
            if *x != super::screen::NO_KNOT && *x as usize >= ne_old {
                *x = sh(*x, dn);
            }
        };
        for k in &mut self.screen.knots {
            shift(&mut k.node);
            k.around.iter_mut().for_each(shift);
        }
        // Constraints, cables, blocks.
        for x in &mut self.constraint_node {
            if *x as usize >= ne_old {
                *x = sh(*x, dn);
            }
        }
        for (k, &gk) in constraints.iter().enumerate() {
            self.constraint_node[gk as usize] = one.constraint_node[k] + ns as u32;
        }
        for (cj, c) in self.cables.iter_mut().enumerate() {
            if cj != ci && c.nodes.first().is_some_and(|&x| x as usize >= ne_old) {
                c.nodes.iter_mut().for_each(|x| *x = sh(*x, dn));
                c.elements.iter_mut().for_each(|x| *x = sh(*x, de));
            }
        }
        let c = &mut self.cables[ci];
        c.nodes = one.cables[0].nodes.iter().map(|&x| x + ns as u32).collect();
        c.elements = one.cables[0]
            .elements
            .iter()
            .map(|&x| x + es as u32)
            .collect();
        self.blocks[bi].node_end = (ns + n_new) as u32;
        self.blocks[bi].elem_end = (es + e_new) as u32;
        self.blocks[bi].is_chain = one.blocks[0].is_chain;
        for b in &mut self.blocks[bi + 1..] {
            b.node_start = sh(b.node_start, dn);
            b.node_end = sh(b.node_end, dn);
            b.elem_start = sh(b.elem_start, de);
            b.elem_end = sh(b.elem_end, de);
        }
    }

    /// Packs a model description. Returns the layout and the initial positions in
    /// packed node order.
    pub fn build(def: &ModelDef) -> Result<(Layout, Vec<[f64; 3]>), Error> {
        Self::build_indexed(def).map(|(lay, pos, _)| (lay, pos))
    }

    /// [`Layout::build`], also returning where each described node went: entry `d` is
    /// the packed index of `def.nodes[d]`.
    pub fn build_indexed(def: &ModelDef) -> Result<Packed, Error> {
        let nn = def.nodes.len();
        let env = def.env;
        for (ci, c) in def.cables.iter().enumerate() {
            if c.nodes.len() < 2 || c.l0.len() + 1 != c.nodes.len() {
                return Err(Error::Model(format!(
                    "cable '{}' needs at least one element",
                    c.name
                )));
            }
            if c.line_type >= def.line_types.len()
                || c.current >= def.currents.len()
                || c.elem_lines.iter().any(|&l| l >= def.line_types.len())
                || !(c.elem_lines.is_empty() || c.elem_lines.len() == c.l0.len())
            {
                return Err(Error::Model(format!(
                    "cable {ci} refers to a missing line type or current"
                )));
            }
            if let Some(&bad) = c.nodes.iter().find(|&&n| n >= nn) {
                return Err(Error::Model(format!(
                    "cable '{}' refers to missing node {bad}",
                    c.name
                )));
            }
        }
        // Elements in description order, then union-find over nodes.
        let mut parent: Vec<usize> = (0..nn).collect();
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for c in &def.cables {
            for w in c.nodes.windows(2) {
                let (ra, rb) = (find(&mut parent, w[0]), find(&mut parent, w[1]));
                if ra != rb {
                    parent[ra] = rb;
                }
            }
        }
        // Order components by their first appearance (cables in order, then loose nodes),
        // and nodes inside a component by first appearance along the cables: one cable
        // alone comes out in chain order. Flat arrays, no per-component allocation: a
        // winch remesh rebuilds the layout of thousands of cables.
        let mut comp_of_root = vec![u32::MAX; nn];
        let mut node_comp = vec![u32::MAX; nn];
        let mut first_seen: Vec<usize> = Vec::with_capacity(nn);
        let mut comp_count: Vec<usize> = Vec::new();
        {
            let mut visit = |n: usize, parent: &mut Vec<usize>| {
                if node_comp[n] != u32::MAX {
                    return;
                }
                let root = find(parent, n);
                if comp_of_root[root] == u32::MAX {
                    comp_of_root[root] = comp_count.len() as u32;
                    comp_count.push(0);
                }
                let ci = comp_of_root[root];
                node_comp[n] = ci;
                comp_count[ci as usize] += 1;
                first_seen.push(n);
            };
            for c in &def.cables {
                for &n in &c.nodes {
                    visit(n, &mut parent);
                }
            }
            for n in 0..nn {
                visit(n, &mut parent);
            }
        }
        let n_comp = comp_count.len();
        let mut comp_start = vec![0usize; n_comp + 1];
        for (k, &c) in comp_count.iter().enumerate() {
            comp_start[k + 1] = comp_start[k] + c;
        }
        let mut new_index = vec![u32::MAX; nn];
        let mut fill_comp = comp_start.clone();
        for &n in &first_seen {
            let ci = node_comp[n] as usize;
            new_index[n] = fill_comp[ci] as u32;
            fill_comp[ci] += 1;
        }
        // Elements grouped by block, in cable order within each block: `(cable, k)`.
        let mut elem_count = vec![0usize; n_comp + 1];
        for c in &def.cables {
            elem_count[node_comp[c.nodes[0]] as usize + 1] += c.l0.len();
        }
        for k in 0..n_comp {
            elem_count[k + 1] += elem_count[k];
        }
        let mut block_elems = vec![(0usize, 0usize); elem_count[n_comp]];
        let mut fill_e = elem_count.clone();
        for (ci, c) in def.cables.iter().enumerate() {
            let b = node_comp[c.nodes[0]] as usize;
            for k in 0..c.l0.len() {
                block_elems[fill_e[b]] = (ci, k);
                fill_e[b] += 1;
            }
        }
        let ne = block_elems.len();
        let line_coefs: Vec<LineCoefs> = def
            .line_types
            .iter()
            .map(|lt| LineCoefs::new(lt, env.water_density, env.gravity))
            .collect();

        let mut lay = Layout {
            env,
            line_types: def.line_types.clone(),
            line_coefs,
            currents: def.currents.clone(),
            cables: def
                .cables
                .iter()
                .map(|c| CableInfo {
                    name: c.name.clone(),
                    nodes: c.nodes.iter().map(|&n| new_index[n]).collect(),
                    elements: vec![0; c.l0.len()],
                    line_type: c.line_type,
                    current: c.current,
                    output_positions: c.output_positions,
                })
                .collect(),
            blocks: Vec::new(),
            node_cable: vec![u32::MAX; nn],
            node_index_in_cable: vec![0; nn],
            node_point_mass: vec![0.0; nn],
            node_point_weight_z: vec![0.0; nn],
            node_point_drag: vec![0.0; nn],
            node_point_added: vec![0.0; nn],
            node_point_displaced: vec![0.0; nn],
            node_point_radius: vec![0.0; nn],
            node_tributary: vec![0.0; nn],
            node_current: vec![0; nn],
            node_constraint: vec![NO_CONSTRAINT; nn],
            inc_start: Vec::new(),
            inc: Vec::new(),
            elem_a: Vec::with_capacity(ne),
            elem_b: Vec::with_capacity(ne),
            elem_l0: Vec::with_capacity(ne),
            elem_line: Vec::with_capacity(ne),
            elem_cable: Vec::with_capacity(ne),
            elem_current: Vec::with_capacity(ne),
            constraint_node: Vec::new(),
            routes: Vec::new(),
            clamps: def.clamps.clone(),
            joints: def.joints.clone(),
            screen: def.screens.mapped(|n| new_index[n as usize]),
        };
        let mut positions = vec![[0.0; 3]; nn];
        for (old, nd) in def.nodes.iter().enumerate() {
            let i = new_index[old] as usize;
            positions[i] = nd.position;
            let p = &nd.point;
            let rho = env.water_density;
            lay.node_point_mass[i] = p.mass + p.added_mass_coef * rho * p.volume;
            lay.node_point_weight_z[i] = -(p.mass - rho * p.volume) * env.gravity;
            lay.node_point_drag[i] = 0.5 * rho * p.drag_area;
            lay.node_point_added[i] = p.added_mass_coef * rho * p.volume;
            lay.node_point_displaced[i] = rho * p.volume;
            lay.node_point_radius[i] = crate::physics::sphere_radius(p.volume);
        }
        let mut block_elem_start = vec![0usize; n_comp + 1];
        for bi in 0..n_comp {
            for &(ci, k) in &block_elems[elem_count[bi]..elem_count[bi + 1]] {
                let c = &def.cables[ci];
                let e = lay.elem_a.len() as u32;
                lay.cables[ci].elements[k] = e;
                lay.elem_a.push(new_index[c.nodes[k]]);
                lay.elem_b.push(new_index[c.nodes[k + 1]]);
                lay.elem_l0.push(c.l0[k]);
                lay.elem_line
                    .push(c.elem_lines.get(k).copied().unwrap_or(c.line_type) as u32);
                lay.elem_cable.push(ci as u32);
                lay.elem_current.push(c.current as u32);
            }
            block_elem_start[bi + 1] = lay.elem_a.len();
        }
        for (ci, c) in lay.cables.iter().enumerate() {
            for (k, &n) in c.nodes.iter().enumerate() {
                let n = n as usize;
                if lay.node_cable[n] == u32::MAX {
                    lay.node_cable[n] = ci as u32;
                    lay.node_index_in_cable[n] = k as u32;
                    lay.node_current[n] = c.current as u32;
                }
            }
        }
        // Loose nodes (a point on no cable) are reported under cable 0.
        for n in lay.node_cable.iter_mut() {
            if *n == u32::MAX {
                *n = 0;
            }
        }
        // Incidence (compressed rows), and tributary lengths.
        let mut count = vec![0u32; nn + 1];
        for e in 0..ne {
            count[lay.elem_a[e] as usize + 1] += 1;
            count[lay.elem_b[e] as usize + 1] += 1;
        }
        for i in 0..nn {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        lay.inc = vec![0; 2 * ne];
        for e in 0..ne {
            for (side, n) in [(0u32, lay.elem_a[e]), (1, lay.elem_b[e])] {
                let n = n as usize;
                lay.inc[fill[n] as usize] = e as u32 * 2 + side;
                fill[n] += 1;
                lay.node_tributary[n] += 0.5 * lay.elem_l0[e];
            }
        }
        lay.inc_start = count;
        // Constraints.
        for (old, nd) in def.nodes.iter().enumerate() {
            if let Some(r) = &nd.route {
                let i = new_index[old];
                lay.node_constraint[i as usize] = lay.routes.len() as u32;
                lay.constraint_node.push(i);
                lay.routes.push(r.clone());
            }
        }
        // Blocks.
        let mut node_start = 0u32;
        for bi in 0..n_comp {
            let count = comp_count[bi];
            let node_end = node_start + count as u32;
            let (e0, e1) = (block_elem_start[bi], block_elem_start[bi + 1]);
            let is_chain = (e1 - e0) + 1 == count
                && (e0..e1).all(|e| {
                    let k = (e - e0) as u32;
                    lay.elem_a[e] == node_start + k && lay.elem_b[e] == node_start + k + 1
                });
            lay.blocks.push(Block {
                node_start,
                node_end,
                elem_start: e0 as u32,
                elem_end: e1 as u32,
                is_chain,
            });
            node_start = node_end;
        }
        Ok((lay, positions, new_index))
    }
}
