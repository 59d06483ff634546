//! The channels a study reduces: which signal of which cable or body.
//!
//! In a study file a channel is written `OWNER.QUANTITY`, the owner a cable or body name
//! or `*` for all of them (split at the last `.`, so a name may itself hold dots):
//!
//! | quantity      | owner | the signal, at each output time                                |
//! |---------------|-------|----------------------------------------------------------------|
//! | `tension_max` | cable | the largest element tension along the cable, N                 |
//! | `start_force` | cable | the magnitude of the force the cable exerts at its start end, N |
//! | `end_force`   | cable | the same at its end end, N                                     |
//! | `tension[K]`  | cable | the tension of element `K` (0 at the start), or `tension[*]`, N |
//! | `fx` ... `fz` | body  | the total force of the cables on the body, N                   |
//! | `mx` ... `mz` | body  | their moment about the body's reference point, N m             |
//! | `offset`      | body  | the horizontal distance of its reference point from `reference`, m |
//!
//! and `default` stands for `*.tension_max`, `*.start_force`, `*.end_force` and the
//! `offset` of every free body: what a mooring check needs. Patterns are resolved against the base model: an unknown cable or
//! body, or an element past a cable's last, is an error naming the entry.

use crate::error::Error;
use crate::model::ModelDef;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;

/// A component of the cables' load on a body.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BodyComponent {
    /// Force along x, N.
    Fx,
    /// Force along y, N.
    Fy,
    /// Force along z, N.
    Fz,
    /// Moment about x through the body's reference point, N m.
    Mx,
    /// Moment about y, N m.
    My,
    /// Moment about z, N m.
    Mz,
}

const BODY_COMPONENTS: [(&str, BodyComponent); 6] = [
    ("fx", BodyComponent::Fx),
    ("fy", BodyComponent::Fy),
    ("fz", BodyComponent::Fz),
    ("mx", BodyComponent::Mx),
    ("my", BodyComponent::My),
    ("mz", BodyComponent::Mz),
];

/// Which signal of its owner a channel follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// The largest element tension of a cable, N.
    TensionMax,
    /// The magnitude of a cable's force on its start support, N.
    StartForce,
    /// The magnitude of a cable's force on its end support, N.
    EndForce,
    /// The tension of one element of a cable (0 at the start), N.
    Tension(usize),
    /// A component of the cables' load on a body.
    Body(BodyComponent),
    /// A body's horizontal offset: the distance in plan of its reference point from
    /// its `reference` position, m.
    Offset,
}

impl Quantity {
    /// Whether the owner is a cable (else a body).
    pub fn of_cable(self) -> bool {
        !matches!(self, Quantity::Body(_) | Quantity::Offset)
    }

    /// Whether the channel is a line tension, which a line capacity applies to.
    pub fn is_tension(self) -> bool {
        self.of_cable()
    }

    /// The unit of the channel's values.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Body(BodyComponent::Mx | BodyComponent::My | BodyComponent::Mz) => "N m",
            Quantity::Offset => "m",
            _ => "N",
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Quantity::TensionMax => write!(f, "tension_max"),
            Quantity::StartForce => write!(f, "start_force"),
            Quantity::EndForce => write!(f, "end_force"),
            Quantity::Tension(k) => write!(f, "tension[{k}]"),
            Quantity::Offset => write!(f, "offset"),
            Quantity::Body(c) => {
                let name = BODY_COMPONENTS.iter().find(|(_, b)| b == c).unwrap().0;
                write!(f, "{name}")
            }
        }
    }
}

/// One resolved channel.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Channel {
    /// The cable or body.
    pub owner: String,
    /// The signal.
    pub quantity: Quantity,
    /// The cable's line type (cable channels only): the capacity that applies.
    pub line_type: Option<String>,
}

impl Channel {
    /// `OWNER.QUANTITY`, as in the study file and the output tables.
    pub fn name(&self) -> String {
        format!("{}.{}", self.owner, self.quantity)
    }
}

/// A cable as the channel resolution sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct CableChannels {
    /// Cable name.
    pub name: String,
    /// Its line type's name.
    pub line_type: String,
    /// Its elements at the start of the run.
    pub elements: usize,
}

/// What a base model offers to reduce: its cables and bodies, in model order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModelChannels {
    /// The cables.
    pub cables: Vec<CableChannels>,
    /// Body names.
    pub bodies: Vec<String>,
    /// Each body's `reference` position, m (in `bodies` order; a body missing here
    /// has its offset measured from the origin).
    pub body_references: Vec<[f64; 3]>,
    /// Whether each body is free (`motion = "free"`), in `bodies` order.
    pub free_bodies: Vec<bool>,
}

impl ModelChannels {
    /// The cables of a model (bodies, which the model does not hold, are added by the
    /// caller).
    pub fn from_model(model: &ModelDef) -> Self {
        ModelChannels {
            cables: model
                .cables
                .iter()
                .map(|c| CableChannels {
                    name: c.name.clone(),
                    line_type: model.line_types[c.line_type].name.clone(),
                    elements: c.l0.len(),
                })
                .collect(),
            bodies: Vec::new(),
            body_references: Vec::new(),
            free_bodies: Vec::new(),
        }
    }
}

/// Which element(s) a `tension[...]` pattern names.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Elements {
    All,
    One(usize),
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum PatternQuantity {
    Fixed(Quantity),
    Tensions(Elements),
    /// The offsets of the free bodies (`default`).
    FreeOffsets,
}

/// A channel entry as written, parsed but not yet resolved against a model.
#[derive(Clone, Debug, PartialEq)]
struct Pattern {
    /// `None` for `*`.
    owner: Option<String>,
    quantity: PatternQuantity,
}

const QUANTITIES: &str = "tension_max, start_force, end_force, tension[K], tension[*], \
                          fx, fy, fz, mx, my, mz, offset";

fn parse(entry: &str) -> Result<Vec<Pattern>, String> {
    if entry == "default" {
        let mut v = [
            Quantity::TensionMax,
            Quantity::StartForce,
            Quantity::EndForce,
        ]
        .map(|q| Pattern {
            owner: None,
            quantity: PatternQuantity::Fixed(q),
        })
        .to_vec();
        v.push(Pattern {
            owner: None,
            quantity: PatternQuantity::FreeOffsets,
        });
        return Ok(v);
    }
    let (owner, q) = entry.rsplit_once('.').ok_or_else(|| {
        format!("\"{entry}\" is not `default` nor `OWNER.QUANTITY` (a cable or body name, or *)")
    })?;
    if owner.is_empty() {
        return Err(format!(
            "\"{entry}\" has no cable or body name before the `.`"
        ));
    }
    let quantity = match q {
        "tension_max" => PatternQuantity::Fixed(Quantity::TensionMax),
        "start_force" => PatternQuantity::Fixed(Quantity::StartForce),
        "end_force" => PatternQuantity::Fixed(Quantity::EndForce),
        "offset" => PatternQuantity::Fixed(Quantity::Offset),
        _ => {
            if let Some((_, c)) = BODY_COMPONENTS.iter().find(|(n, _)| *n == q) {
                PatternQuantity::Fixed(Quantity::Body(*c))
            } else if let Some(inner) = q.strip_prefix("tension[").and_then(|r| r.strip_suffix(']'))
            {
                if inner == "*" {
                    PatternQuantity::Tensions(Elements::All)
                } else {
                    let k = inner.parse::<usize>().map_err(|_| {
                        format!("\"{entry}\": the element in tension[...] must be an index from 0 or *, got \"{inner}\"")
                    })?;
                    PatternQuantity::Tensions(Elements::One(k))
                }
            } else {
                return Err(format!(
                    "\"{entry}\": unknown quantity \"{q}\" (known: {QUANTITIES})"
                ));
            }
        }
    };
    Ok(vec![Pattern {
        owner: (owner != "*").then(|| owner.to_string()),
        quantity,
    }])
}

/// Checks the syntax of channel entries (no model needed); `field` names the list in
/// messages (`study.channels`).
pub fn check_entries(path: &Path, field: &str, entries: &[String]) -> Result<(), Error> {
    for (i, e) in entries.iter().enumerate() {
        parse(e).map_err(|m| crate::scenario::err(path, format!("{field}[{i}]"), m))?;
    }
    Ok(())
}

/// Resolves channel entries against a model: the channels in the order of the entries,
/// a wildcard's in model order, each once (the first entry that names it places it).
pub fn resolve(
    path: &Path,
    field: &str,
    entries: &[String],
    model: &ModelChannels,
) -> Result<Vec<Channel>, Error> {
    let mut out: Vec<Channel> = Vec::new();
    let mut push = |c: Channel| {
        if !out.contains(&c) {
            out.push(c);
        }
    };
    for (i, e) in entries.iter().enumerate() {
        let f = format!("{field}[{i}]");
        let err = |m: String| crate::scenario::err(path, &f, m);
        for p in parse(e).map_err(err)? {
            let of_cable = match p.quantity {
                PatternQuantity::Fixed(q) => q.of_cable(),
                PatternQuantity::Tensions(_) => true,
                PatternQuantity::FreeOffsets => {
                    for (k, b) in model.bodies.iter().enumerate() {
                        if model.free_bodies.get(k).copied().unwrap_or(false) {
                            push(Channel {
                                owner: b.clone(),
                                quantity: Quantity::Offset,
                                line_type: None,
                            });
                        }
                    }
                    continue;
                }
            };
            if of_cable {
                let cables: Vec<&CableChannels> = match &p.owner {
                    None => model.cables.iter().collect(),
                    Some(name) => {
                        vec![model.cables.iter().find(|c| &c.name == name).ok_or_else(
                                || {
                                    err(format!(
                                        "\"{e}\": no cable named \"{name}\" in the base scenario{}",
                                        if model.bodies.contains(name) {
                                            " (it is a body: bodies have fx, fy, fz, mx, my, mz, offset)"
                                        } else {
                                            ""
                                        }
                                    ))
                                },
                            )?]
                    }
                };
                for c in cables {
                    let ch = |q| Channel {
                        owner: c.name.clone(),
                        quantity: q,
                        line_type: Some(c.line_type.clone()),
                    };
                    match p.quantity {
                        PatternQuantity::Fixed(q) => push(ch(q)),
                        PatternQuantity::Tensions(Elements::All) => {
                            (0..c.elements).for_each(|k| push(ch(Quantity::Tension(k))))
                        }
                        PatternQuantity::FreeOffsets => unreachable!("handled above"),
                        PatternQuantity::Tensions(Elements::One(k)) => {
                            if k >= c.elements {
                                return Err(err(format!(
                                    "\"{e}\": cable \"{}\" has {} elements (0 to {}), no element {k}",
                                    c.name,
                                    c.elements,
                                    c.elements.saturating_sub(1)
                                )));
                            }
                            push(ch(Quantity::Tension(k)))
                        }
                    }
                }
            } else {
                let PatternQuantity::Fixed(q) = p.quantity else {
                    unreachable!("body patterns are fixed quantities")
                };
                let bodies: Vec<&String> = match &p.owner {
                    None => model.bodies.iter().collect(),
                    Some(name) => {
                        vec![model.bodies.iter().find(|b| *b == name).ok_or_else(|| {
                            err(format!(
                                "\"{e}\": no body named \"{name}\" in the base scenario"
                            ))
                        })?]
                    }
                };
                for b in bodies {
                    push(Channel {
                        owner: b.clone(),
                        quantity: q,
                        line_type: None,
                    });
                }
            }
        }
    }
    if out.is_empty() {
        return Err(crate::scenario::err(
            path,
            field,
            "the entries name no channel of the base scenario",
        ));
    }
    Ok(out)
}
