//! `[fatigue]`: which line types have a T-N curve, and where their cables' fatigue is
//! counted (`crate::fatigue`). A run of a scenario with this table writes
//! `fatigue.csv`; a study of it adds the scatter diagram's annual damage.

use super::{err, non_negative, positive};
use crate::error::Error;
use crate::fatigue::{chain_area, FatigueLocation, FatigueSpec, Location, TnCurve, NAMED_CURVES};
use crate::model::ModelDef;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// The `[fatigue]` table as written.
#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub struct RawFatigue {
    pub transient: Option<f64>,
    pub locations: Option<Vec<toml::Value>>,
    #[serde(default)]
    pub line_types: BTreeMap<String, RawCurve>,
    #[serde(default)]
    pub cables: BTreeMap<String, RawFatigueCable>,
}

/// `[fatigue.line_types.NAME]`: a line type's T-N curve and nominal area.
#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub struct RawCurve {
    pub curve: Option<String>,
    pub a_d: Option<f64>,
    pub m: Option<f64>,
    pub area_m2: Option<f64>,
    pub bar_diameter: Option<f64>,
}

/// `[fatigue.cables.NAME]`: one cable's own locations.
#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub struct RawFatigueCable {
    pub locations: Option<Vec<toml::Value>>,
}

/// One line type's curve and area, checked.
fn curve(p: &Path, name: &str, r: &RawCurve) -> Result<(TnCurve, f64), Error> {
    let f = |k: &str| format!("fatigue.line_types.{name}.{k}");
    let curve = match (&r.curve, r.a_d, r.m) {
        (Some(c), None, None) => TnCurve::named(c).ok_or_else(|| {
            let known: Vec<&str> = NAMED_CURVES.iter().map(|c| c.0).collect();
            err(
                p,
                f("curve"),
                format!("unknown curve \"{c}\" (known: {})", known.join(", ")),
            )
        })?,
        (None, Some(a_d), Some(m)) => TnCurve {
            name: None,
            a_d: positive(p, &f("a_d"), a_d)?,
            m: positive(p, &f("m"), m)?,
        },
        (Some(_), _, _) => {
            return Err(err(
                p,
                f("curve"),
                "give either a named `curve` or its parameters `a_d` and `m`, not both",
            ))
        }
        (None, None, _) => return Err(err(p, f("a_d"), "missing: give `curve`, or `a_d` and `m`")),
        (None, Some(_), None) => return Err(err(p, f("m"), "missing: the curve's slope")),
    };
    let chain = matches!(curve.name.as_deref(), Some("studless_chain" | "stud_chain"));
    let area = match (r.area_m2, r.bar_diameter) {
        (Some(a), None) => positive(p, &f("area_m2"), a)?,
        (None, Some(d)) => {
            let d = positive(p, &f("bar_diameter"), d)?;
            if !chain {
                return Err(err(
                    p,
                    f("bar_diameter"),
                    "a bar diameter gives the nominal area of a chain (2 pi d^2 / 4) only: \
                     give a rope's nominal area as `area_m2`",
                ));
            }
            chain_area(d)
        }
        (Some(_), Some(_)) => {
            return Err(err(
                p,
                f("bar_diameter"),
                "give either `area_m2` or `bar_diameter`, not both",
            ))
        }
        (None, None) => {
            return Err(err(
                p,
                f("area_m2"),
                "missing: the nominal area (m^2) the tension range is divided by \
                 (or `bar_diameter` for a chain)",
            ))
        }
    };
    Ok((curve, area))
}

/// Locations as written (`"start"`, `"end"`, an element index), checked against a cable
/// of `elements` elements; `field` names the list.
fn locations(
    p: &Path,
    field: &str,
    v: &[toml::Value],
    cable: &str,
    elements: usize,
) -> Result<Vec<Location>, Error> {
    if v.is_empty() {
        return Err(err(p, field, "the list is empty"));
    }
    let mut out: Vec<Location> = Vec::with_capacity(v.len());
    for (i, x) in v.iter().enumerate() {
        let f = format!("{field}[{i}]");
        let loc = match x {
            toml::Value::String(s) if s == "start" => Location::Start,
            toml::Value::String(s) if s == "end" => Location::End,
            toml::Value::Integer(k) => {
                if *k < 0 || *k as usize >= elements {
                    return Err(err(
                        p,
                        f,
                        format!(
                            "element {k} is off cable \"{cable}\", whose elements are 0 to {}",
                            elements - 1
                        ),
                    ));
                }
                Location::Element(*k as usize)
            }
            other => {
                return Err(err(
                    p,
                    f,
                    format!("a location is \"start\", \"end\" or an element index, got {other}"),
                ))
            }
        };
        if out.contains(&loc) {
            return Err(err(p, f, format!("location {loc} is listed twice")));
        }
        out.push(loc);
    }
    Ok(out)
}

/// Resolves `[fatigue]` against the model: every cable whose line type has a curve,
/// at its own locations or the table's (default both ends).
pub(super) fn resolve(p: &Path, raw: &RawFatigue, model: &ModelDef) -> Result<FatigueSpec, Error> {
    let transient = non_negative(p, "fatigue.transient", raw.transient.unwrap_or(0.0))?;
    if raw.line_types.is_empty() {
        return Err(err(
            p,
            "fatigue.line_types",
            "missing: the T-N curve and nominal area of at least one line type",
        ));
    }
    let mut curves = BTreeMap::new();
    for (name, r) in &raw.line_types {
        if !model.line_types.iter().any(|lt| &lt.name == name) {
            return Err(err(
                p,
                format!("fatigue.line_types.{name}"),
                format!("no line type is named \"{name}\""),
            ));
        }
        curves.insert(name.clone(), curve(p, name, r)?);
    }
    for name in raw.cables.keys() {
        let Some(c) = model.cables.iter().find(|c| &c.name == name) else {
            return Err(err(
                p,
                format!("fatigue.cables.{name}"),
                format!("no cable is named \"{name}\""),
            ));
        };
        if c.elem_lines.iter().any(|&l| l != c.line_type) {
            return Err(err(
                p,
                format!("fatigue.cables.{name}"),
                format!("cable \"{name}\" has several sections: fatigue is not computed on such cables yet"),
            ));
        }
        let lt = &model.line_types[c.line_type].name;
        if !curves.contains_key(lt) {
            return Err(err(
                p,
                format!("fatigue.cables.{name}"),
                format!(
                    "cable \"{name}\" is of line type \"{lt}\", which has no curve in \
                     [fatigue.line_types]"
                ),
            ));
        }
    }
    let default = vec![
        toml::Value::String("start".into()),
        toml::Value::String("end".into()),
    ];
    let mut out = Vec::new();
    for (i, c) in model.cables.iter().enumerate() {
        let lt = &model.line_types[c.line_type].name;
        let Some((curve, area)) = curves.get(lt) else {
            continue;
        };
        if c.elem_lines.iter().any(|&l| l != c.line_type) {
            // Several sections: left out (named cables are refused above).
            continue;
        }
        let (field, list) = match raw.cables.get(&c.name).and_then(|x| x.locations.as_ref()) {
            Some(l) => (format!("fatigue.cables.{}.locations", c.name), l),
            None => (
                "fatigue.locations".to_string(),
                raw.locations.as_ref().unwrap_or(&default),
            ),
        };
        for location in locations(p, &field, list, &c.name, c.l0.len())? {
            out.push(FatigueLocation {
                cable: c.name.clone(),
                cable_index: i,
                location,
                line_type: lt.clone(),
                curve: curve.clone(),
                area_m2: *area,
            });
        }
    }
    Ok(FatigueSpec {
        transient,
        locations: out,
    })
}
