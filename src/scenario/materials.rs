//! `[[line_types]]` as written: raw values, or a material and a nominal size whose
//! properties come from a documented table (docs/src/line_types.md).
//!
//! The table's coefficients are those of MoorPy's default property table (NREL's MoorPy,
//! `MoorProps_default.yaml`), which takes chain stiffness from DNV-OS-E301, drag
//! coefficients from DNV-OS-E301 adjusted to the volume-equivalent diameter, and added
//! mass from Bureau Veritas NR 493: properties scale with the nominal diameter `d_n`
//! (m) as `mass = m2 d_n^2`, `EA = e2 d_n^2 + e3 d_n^3` (chain, wire) or `EA = k MBL`
//! with `MBL = b2 d_n^2 + b3 d_n^3` (fibre ropes: the quasi-static stiffness), and the
//! volume-equivalent diameter is `dvol_dnom d_n` or, from the material's density,
//! `sqrt(4 mass / (pi density))`.

use super::{err, non_negative, positive};
use crate::error::Error;
use crate::model::LineType;
use serde::Deserialize;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::Path;

/// A line material of the property table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Material {
    /// R4 studless chain (also `"chain"`).
    #[serde(alias = "chain")]
    ChainStudless,
    /// R4 studlink chain.
    ChainStudlink,
    /// Steel wire rope.
    Wire,
    /// Polyester rope.
    Polyester,
    /// Nylon rope.
    Nylon,
    /// HMPE rope.
    Hmpe,
}

/// One material's coefficients (SI; `d_n` the nominal diameter in m).
struct Props {
    /// Mass per length per `d_n^2`, kg/m^3.
    mass_d2: f64,
    /// `EA` per `d_n^2` and per `d_n^3`, N/m^2 and N/m^3 (chain, wire).
    ea_d2: f64,
    ea_d3: f64,
    /// Quasi-static `EA` per MBL (fibre ropes), -.
    ea_mbl: f64,
    /// MBL per `d_n`, `d_n^2` and `d_n^3`, N/m, N/m^2, N/m^3.
    mbl_d: f64,
    mbl_d2: f64,
    mbl_d3: f64,
    /// Volume-equivalent diameter per nominal diameter (0: from `density`).
    dvol_dnom: f64,
    /// Material density, kg/m^3 (fibre ropes).
    density: f64,
    /// Normal and axial drag, normal added mass, on the volume-equivalent diameter.
    cd: f64,
    cd_ax: f64,
    ca: f64,
}

impl Material {
    fn props(self) -> Props {
        let zero = Props {
            mass_d2: 0.0,
            ea_d2: 0.0,
            ea_d3: 0.0,
            ea_mbl: 0.0,
            mbl_d: 0.0,
            mbl_d2: 0.0,
            mbl_d3: 0.0,
            dvol_dnom: 0.0,
            density: 0.0,
            cd: 0.0,
            cd_ax: 0.0,
            ca: 0.0,
        };
        match self {
            Material::ChainStudless => Props {
                mass_d2: 20.0e3,
                ea_d2: 85.6e9,
                ea_d3: -3.93e7,
                mbl_d: 9.11e2,
                mbl_d2: 1.21e9,
                mbl_d3: -2.19e9,
                dvol_dnom: 1.80,
                cd: 1.333,
                cd_ax: 0.639,
                ca: 1.0,
                ..zero
            },
            Material::ChainStudlink => Props {
                mass_d2: 21.9e3,
                ea_d2: 88.0e9,
                mbl_d: 9.11e2,
                mbl_d2: 1.21e9,
                mbl_d3: -2.19e9,
                dvol_dnom: 1.89,
                cd: 1.376,
                cd_ax: 0.741,
                ca: 1.0,
                ..zero
            },
            Material::Wire => Props {
                mass_d2: 5293.0,
                ea_d2: 97.1e9,
                mbl_d2: 1022e6,
                dvol_dnom: 1.18,
                cd: 1.021,
                // The table neglects the wire's axial drag; keep the default's order.
                cd_ax: 0.0,
                ca: 1.0,
                ..zero
            },
            Material::Polyester => Props {
                mass_d2: 679.0,
                mbl_d2: 308e6,
                ea_mbl: 14.0,
                density: 1380.0,
                cd: 2.021,
                ca: 1.1,
                ..zero
            },
            Material::Nylon => Props {
                mass_d2: 585.0,
                mbl_d2: 207e6,
                mbl_d3: 230e6,
                ea_mbl: 5.0,
                density: 1140.0,
                cd: 1.979,
                ca: 1.1,
                ..zero
            },
            Material::Hmpe => Props {
                mass_d2: 496.0,
                mbl_d2: 580e6,
                mbl_d3: 651e6,
                ea_mbl: 56.0,
                density: 975.0,
                cd: 1.988,
                ca: 1.1,
                ..zero
            },
        }
    }
}

/// What a material and a nominal diameter give.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialLine {
    /// Volume-equivalent (hydrodynamic) diameter, m.
    pub diameter: f64,
    /// Mass per length, kg/m.
    pub mass_per_length: f64,
    /// Axial stiffness, N.
    pub ea: f64,
    /// Minimum breaking load, N.
    pub mbl: f64,
    /// Normal drag coefficient (on `diameter`).
    pub cn: f64,
    /// Tangential drag coefficient (on `pi diameter`); `None` where the table has none.
    pub ct: Option<f64>,
    /// Normal added-mass coefficient.
    pub cm: f64,
}

impl Material {
    /// The properties of a line of this material with nominal diameter `dn` (m).
    pub fn line(self, dn: f64) -> MaterialLine {
        let p = self.props();
        let mass = p.mass_d2 * dn * dn;
        let mbl = p.mbl_d * dn + p.mbl_d2 * dn * dn + p.mbl_d3 * dn * dn * dn;
        let ea = if p.ea_mbl > 0.0 {
            p.ea_mbl * mbl
        } else {
            p.ea_d2 * dn * dn + p.ea_d3 * dn * dn * dn
        };
        let diameter = if p.dvol_dnom > 0.0 {
            p.dvol_dnom * dn
        } else {
            (4.0 * mass / (PI * p.density)).sqrt()
        };
        MaterialLine {
            diameter,
            mass_per_length: mass,
            ea,
            mbl,
            cn: p.cd,
            ct: (p.cd_ax > 0.0).then_some(p.cd_ax),
            cm: p.ca,
        }
    }
}

/// A `[[line_types]]` entry as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLineType {
    /// Name that cables refer to.
    pub name: String,
    /// Material of the property table (with `nominal_diameter`).
    #[serde(default)]
    pub material: Option<Material>,
    /// Nominal diameter, m (with `material`).
    #[serde(default)]
    pub nominal_diameter: Option<f64>,
    /// Hydrodynamic diameter, m (overrides the material's).
    #[serde(default)]
    pub diameter: Option<f64>,
    /// Mass per length, kg/m.
    #[serde(default)]
    pub mass_per_length: Option<f64>,
    /// Axial stiffness, N.
    #[serde(default)]
    pub ea: Option<f64>,
    /// Internal damping time constant, s.
    #[serde(default)]
    pub damping: f64,
    /// Normal drag coefficient.
    #[serde(default)]
    pub cn: Option<f64>,
    /// Tangential drag coefficient.
    #[serde(default)]
    pub ct: Option<f64>,
    /// Normal added-mass coefficient.
    #[serde(default)]
    pub cm: Option<f64>,
    /// Tangential added-mass coefficient (default 0).
    #[serde(default)]
    pub cat: Option<f64>,
    /// Bending stiffness, N m^2.
    #[serde(default)]
    pub ei: f64,
    /// Elastic force in compression too.
    #[serde(default)]
    pub allow_compression: bool,
    /// Nonlinear axial stiffness: rows `[strain, tension]` (in place of `ea`).
    #[serde(default)]
    pub ea_curve: Option<Vec<[f64; 2]>>,
    /// The same read from a file of two columns, strain and tension (path relative to
    /// the scenario file; `#` starts a comment).
    #[serde(default)]
    pub ea_curve_file: Option<String>,
    /// Viscoelastic fibre rope: the dynamic stiffness `EA_d`, N (`ea` is then the
    /// static one); with `ea_dynamic_slope`, its value at zero mean tension.
    #[serde(default)]
    pub ea_dynamic: Option<f64>,
    /// The slope of the dynamic stiffness against the mean tension (-).
    #[serde(default)]
    pub ea_dynamic_slope: Option<f64>,
    /// The static branch's damping `BA_s`, N s.
    #[serde(default)]
    pub ba_static: Option<f64>,
    /// The dynamic spring's damping `BA_d`, N s (default 0).
    #[serde(default)]
    pub ba_dynamic: Option<f64>,
}

/// Reads a strain-tension curve file: a row of two numbers (whitespace or a comma
/// between) per line, blank lines and text after `#` left out. Errors name the file and
/// the line.
pub fn read_curve_file(path: &Path) -> Result<Vec<[f64; 2]>, Error> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| err(path, "curve file", format!("cannot be read: {e}")))?;
    let mut rows = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let body = line.split('#').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let cells: Vec<&str> = body
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|c| !c.is_empty())
            .collect();
        let nums: Vec<f64> = cells.iter().filter_map(|c| c.parse().ok()).collect();
        if cells.len() != 2 || nums.len() != 2 {
            return Err(err(
                path,
                format!("line {}", n + 1),
                format!("expected two numbers (strain, tension), got \"{body}\""),
            ));
        }
        rows.push([nums[0], nums[1]]);
    }
    Ok(rows)
}

impl RawLineType {
    /// The line type: given values, else the material's, else the defaults (`cn` 1,
    /// `ct` 0.01, `cm` 1, `cat` 0: the property table has no tangential added mass);
    /// `diameter`, `mass_per_length` and `ea` are required without a
    /// material.
    pub fn resolve(&self, p: &Path, i: usize) -> Result<LineType, Error> {
        let f = |k: &str| format!("line_types[{i}] (\"{}\").{k}", self.name);
        let mat = match (self.material, self.nominal_diameter) {
            (Some(m), Some(dn)) => {
                if !(dn > 0.0 && dn.is_finite()) {
                    return Err(err(
                        p,
                        f("nominal_diameter"),
                        format!("must be positive, got {dn}"),
                    ));
                }
                Some(m.line(dn))
            }
            (Some(_), None) => {
                return Err(err(p, f("nominal_diameter"), "is required with `material`"));
            }
            (None, Some(_)) => {
                return Err(err(p, f("material"), "is required with `nominal_diameter`"));
            }
            (None, None) => None,
        };
        let need = |given: Option<f64>, from: Option<f64>, key: &str| {
            given.or(from).ok_or_else(|| {
                err(
                    p,
                    f(key),
                    format!(
                        "missing field `{key}` (give it, or `material` and `nominal_diameter`)"
                    ),
                )
            })
        };
        let curve = match (&self.ea_curve, &self.ea_curve_file) {
            (Some(_), Some(_)) => {
                return Err(err(
                    p,
                    f("ea_curve"),
                    "give `ea_curve` or `ea_curve_file`, not both",
                ));
            }
            (Some(rows), None) => Some((rows.clone(), p.to_path_buf(), f("ea_curve"))),
            (None, Some(file)) => {
                let path = p.parent().unwrap_or(Path::new(".")).join(file);
                let rows = read_curve_file(&path)?;
                Some((rows, path, format!("curve of {}", f("ea_curve_file"))))
            }
            (None, None) => None,
        };
        let ea_given = match &curve {
            Some((rows, file, what)) => {
                if self.ea.is_some() {
                    return Err(err(
                        p,
                        f("ea"),
                        "give `ea` or a strain-tension curve, not both",
                    ));
                }
                if self.allow_compression {
                    return Err(err(
                        p,
                        f("allow_compression"),
                        "a line with a strain-tension curve is slack in compression",
                    ));
                }
                crate::physics::axial::check_curve(rows).map_err(|m| err(file, what.clone(), m))?;
                Some(crate::physics::tabulated_max_slope(rows))
            }
            None => self.ea,
        };
        Ok(LineType {
            name: self.name.clone(),
            diameter: need(self.diameter, mat.map(|m| m.diameter), "diameter")?,
            mass_per_length: need(
                self.mass_per_length,
                mat.map(|m| m.mass_per_length),
                "mass_per_length",
            )?,
            ea: need(ea_given, mat.map(|m| m.ea), "ea")?,
            damping: self.damping,
            cn: self.cn.or(mat.map(|m| m.cn)).unwrap_or(1.0),
            ct: self.ct.or(mat.and_then(|m| m.ct)).unwrap_or(0.01),
            cm: self.cm.or(mat.map(|m| m.cm)).unwrap_or(1.0),
            cat: self.cat.unwrap_or(0.0),
            ei: self.ei,
            allow_compression: self.allow_compression,
            ea_curve: curve.map(|c| c.0),
            viscoelastic: self.viscoelastic(p, &f)?,
        })
    }

    /// The viscoelastic model of the keys `ea_dynamic`, `ea_dynamic_slope`,
    /// `ba_static`, `ba_dynamic` (`None` without them), checked for what can run:
    /// positive stiffness and static damping, a dynamic stiffness above the static
    /// one, a slope and a dynamic damping at least zero. The errors name the key.
    fn viscoelastic(
        &self,
        p: &Path,
        f: &dyn Fn(&str) -> String,
    ) -> Result<Option<crate::model::Viscoelastic>, Error> {
        let Some(kd) = self.ea_dynamic else {
            for (k, x) in [
                ("ea_dynamic_slope", self.ea_dynamic_slope),
                ("ba_static", self.ba_static),
                ("ba_dynamic", self.ba_dynamic),
            ] {
                if x.is_some() {
                    return Err(err(
                        p,
                        f(k),
                        format!("`{k}` belongs to a viscoelastic line: give `ea_dynamic` too"),
                    ));
                }
            }
            return Ok(None);
        };
        let finite = |k: &str, x: f64| {
            if x.is_finite() {
                Ok(x)
            } else {
                Err(err(p, f(k), format!("must be finite, got {x}")))
            }
        };
        let kd = finite("ea_dynamic", kd)?;
        if !(kd > 0.0) {
            return Err(err(
                p,
                f("ea_dynamic"),
                format!("must be positive, got {kd}"),
            ));
        }
        if self.ea_curve.is_some() || self.ea_curve_file.is_some() {
            return Err(err(
                p,
                f("ea_dynamic"),
                "a viscoelastic line has one static `ea`, not a strain-tension curve",
            ));
        }
        if self.allow_compression {
            return Err(err(
                p,
                f("allow_compression"),
                "a viscoelastic line is slack in compression",
            ));
        }
        if self.damping != 0.0 {
            return Err(err(
                p,
                f("damping"),
                "a viscoelastic line's damping is `ba_static` and `ba_dynamic` (N s), not \
                 `damping`",
            ));
        }
        let slope = finite("ea_dynamic_slope", self.ea_dynamic_slope.unwrap_or(0.0))?;
        if slope < 0.0 {
            return Err(err(
                p,
                f("ea_dynamic_slope"),
                format!("must not be negative, got {slope}"),
            ));
        }
        let Some(c1) = self.ba_static else {
            return Err(err(
                p,
                f("ba_static"),
                "a viscoelastic line needs `ba_static`, the static branch's damping (N s)",
            ));
        };
        let c1 = finite("ba_static", c1)?;
        if !(c1 > 0.0) {
            return Err(err(
                p,
                f("ba_static"),
                format!("must be positive, got {c1}"),
            ));
        }
        let c2 = finite("ba_dynamic", self.ba_dynamic.unwrap_or(0.0))?;
        if c2 < 0.0 {
            return Err(err(
                p,
                f("ba_dynamic"),
                format!("must not be negative, got {c2}"),
            ));
        }
        Ok(Some(crate::model::Viscoelastic {
            ea_dynamic: kd,
            ea_dynamic_slope: slope,
            ba_static: c1,
            ba_dynamic: c2,
        }))
    }
}

/// The `[[line_types]]`, resolved and validated, and the index of each by name.
pub(super) fn line_types(
    p: &Path,
    raw: &[RawLineType],
) -> Result<(Vec<LineType>, HashMap<String, usize>), Error> {
    let mut lt_index = HashMap::new();
    let line_types = raw
        .iter()
        .enumerate()
        .map(|(i, lt)| lt.resolve(p, i))
        .collect::<Result<Vec<_>, _>>()?;
    for (i, lt) in line_types.iter().enumerate() {
        let f = |k: &str| format!("line_types[{i}] (\"{}\").{k}", lt.name);
        positive(p, &f("diameter"), lt.diameter)?;
        positive(p, &f("mass_per_length"), lt.mass_per_length)?;
        positive(p, &f("ea"), lt.ea)?;
        non_negative(p, &f("damping"), lt.damping)?;
        non_negative(p, &f("cn"), lt.cn)?;
        non_negative(p, &f("ct"), lt.ct)?;
        non_negative(p, &f("cm"), lt.cm)?;
        non_negative(p, &f("cat"), lt.cat)?;
        non_negative(p, &f("ei"), lt.ei)?;
        if let Some(v) = lt.viscoelastic {
            if !(v.ea_dynamic > lt.ea) {
                return Err(err(
                    p,
                    f("ea_dynamic"),
                    format!(
                        "the dynamic stiffness must exceed the static `ea` = {}, got {}",
                        lt.ea, v.ea_dynamic
                    ),
                ));
            }
        }
        if lt_index.insert(lt.name.clone(), i).is_some() {
            return Err(err(
                p,
                format!("line_types[{i}].name"),
                format!("duplicate line type name \"{}\"", lt.name),
            ));
        }
    }
    Ok((line_types, lt_index))
}
