//! Packing several scenarios (a study's members) into one scenario: one model, one
//! layout, one run, each member in its own sea.
//!
//! Every member's line types, currents, nodes (with their routes and bodies), cables,
//! initial shapes and points are copied in after the previous members', their indices
//! shifted; cables and bodies are renamed `PREFIX/name` with the member's prefix, so
//! that names stay unique. Each member's sea goes into the packed scenario's
//! [`SeaSet`] (`Scenario::member_seas`), and its cables are marked with it: the CPU
//! and GPU paths then give each cable its member's waves, each sea on its own cache
//! schedule (`sea::set`). RAO-driven bodies were built from their member's wave
//! components when the member was validated, so they follow their member's sea.
//!
//! Members share nothing (no node, no body), so each member's cables form blocks of
//! their own: blocks are stepped independently, and a member's results in the packed
//! run are those of the member run alone (the tests compare them).
//!
//! What must agree between members: the `[simulation]` table and the environment
//! (gravity, water density, depth, seabed), which the packed run has once. Winches
//! (whose remeshing works per scenario) are not packed.

use crate::error::Error;
use crate::model::{ModelDef, Route};
use crate::scenario::{Limits, NamedPoint, Scenario};
use crate::sea::SeaSet;
use std::collections::HashMap;
use std::ops::Range;
use std::sync::Arc;

/// Where one member sits in a packed scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct PackedMember {
    /// The prefix of its cable and body names (`PREFIX/name`).
    pub prefix: String,
    /// Its cables: indices into the packed scenario's cables (layout order).
    pub cables: Range<usize>,
    /// Its sea: index into the packed scenario's seas.
    pub sea: usize,
}

/// A packed scenario and where each member is in it.
#[derive(Clone, Debug)]
pub struct Packed {
    /// The packed scenario.
    pub scenario: Scenario,
    /// The members, in the order given.
    pub members: Vec<PackedMember>,
}

/// The name of `name` of the member with prefix `prefix` in a packed scenario.
pub fn packed_name(prefix: &str, name: &str) -> String {
    format!("{prefix}/{name}")
}

/// Packs `members` (`(prefix, scenario)`, prefixes unique) into one scenario (the
/// module documentation says how). The `[simulation]` table, the path and the
/// `[ancf]` settings are the first member's.
pub fn pack(members: &[(String, Scenario)]) -> Result<Packed, Error> {
    let Some((_, first)) = members.first() else {
        return Err(Error::Model("packing needs at least one member".into()));
    };
    let mut model = ModelDef {
        env: first.model.env,
        ..ModelDef::default()
    };
    let mut initial = Vec::new();
    let mut points = Vec::new();
    let mut failures = Vec::new();
    let mut seas = Vec::new();
    let mut cable_sea = Vec::new();
    let mut out = Vec::with_capacity(members.len());
    for (prefix, sc) in members {
        let differs = |what: &str| {
            Error::Model(format!(
                "packing member \"{prefix}\" ({}): its {what} differs from the first member's; \
                 members packed into one run share it",
                sc.path.display()
            ))
        };
        if sc.model.env != first.model.env {
            return Err(differs(
                "environment (gravity, water density, depth, seabed)",
            ));
        }
        if sc.sim != first.sim {
            return Err(differs("[simulation] table"));
        }
        if !sc.winches.is_empty() {
            return Err(Error::Model(format!(
                "packing member \"{prefix}\" ({}): winch cables cannot be packed with other \
                 members (their remeshing works on one scenario); run the members one by one",
                sc.path.display()
            )));
        }
        if sc.member_seas.is_some() {
            return Err(Error::Model(format!(
                "packing member \"{prefix}\": it is itself a packed scenario"
            )));
        }
        let (lt0, cu0, nd0, ca0) = (
            model.line_types.len(),
            model.currents.len(),
            model.nodes.len(),
            model.cables.len(),
        );
        let sea = seas.len();
        seas.push(sc.sea.clone());
        model.line_types.extend(sc.model.line_types.iter().cloned());
        model.currents.extend(sc.model.currents.iter().cloned());
        // Each of the member's bodies once, renamed (ends on one body share it).
        let mut bodies: HashMap<*const crate::body::Body, Arc<crate::body::Body>> = HashMap::new();
        for n in &sc.model.nodes {
            let mut n = n.clone();
            if let Some(Route::Body { body, at }) = &n.route {
                let renamed = bodies
                    .entry(Arc::as_ptr(body))
                    .or_insert_with(|| {
                        Arc::new(crate::body::Body::new(
                            packed_name(prefix, &body.name),
                            body.pose,
                            body.motion.clone(),
                        ))
                    })
                    .clone();
                n.route = Some(Route::Body {
                    body: renamed,
                    at: *at,
                });
            }
            model.nodes.push(n);
        }
        failures.extend(sc.failures.iter().map(|f| crate::model::EndFailure {
            cable: packed_name(prefix, &f.cable),
            ..f.clone()
        }));
        for c in &sc.model.cables {
            let mut c = c.clone();
            c.name = packed_name(prefix, &c.name);
            c.line_type += lt0;
            for l in &mut c.elem_lines {
                *l += lt0;
            }
            c.current += cu0;
            for n in &mut c.nodes {
                *n += nd0;
            }
            model.cables.push(c);
            cable_sea.push(sea as u32);
        }
        model
            .clamps
            .extend(sc.model.clamps.iter().map(|k| crate::model::Clamp {
                cable: k.cable + ca0,
                ..*k
            }));
        model
            .joints
            .extend(sc.model.joints.iter().map(|j| crate::model::Joint {
                prev: j.prev + ca0,
                next: j.next + ca0,
            }));
        model.screens.append(&sc.model.screens, nd0 as u32, lt0);
        initial.extend(sc.initial.iter().copied());
        points.extend(sc.points.iter().map(|p| NamedPoint {
            name: packed_name(prefix, &p.name),
            node: p.node + nd0,
        }));
        out.push(PackedMember {
            prefix: prefix.clone(),
            cables: ca0..model.cables.len(),
            sea,
        });
    }
    let scenario = Scenario {
        path: first.path.clone(),
        sim: first.sim.clone(),
        model,
        initial,
        winches: Vec::new(),
        ancf: first.ancf,
        sea: seas[0].clone(),
        member_seas: Some(SeaSet {
            seas,
            cable_sea,
            reach: Vec::new(),
            banded: false,
        }),
        depth_bands: first.depth_bands,
        points,
        vtk: false,
        output_format: Default::default(),
        failures,
        // A study reports no nets' volumes.
        nets: Vec::new(),
        // The study counts its members' fatigue itself (`study::run`).
        fatigue: None,
        // Each member passed its own budget; the packed run is their sum.
        limits: {
            let (n, l) = (members.len() as f64, &first.limits);
            Limits {
                node_steps: l.node_steps * n,
                memory_gib: l.memory_gib * n,
                output_gib: l.output_gib * n,
            }
        },
    };
    Ok(Packed {
        scenario,
        members: out,
    })
}
