//! A MoorDyn input file's tables, as written, each row with its line number.
//!
//! The file is a list of sections, each opened by a header line holding `---` and a
//! key phrase (`LINE TYPES`, `POINTS`, ...). Table sections have two more lines
//! (column names, units) before their rows; `OPTIONS` and `OUTPUTS` have rows at once.
//! Rows end at the next line holding `---`. `#` starts a comment. Two layouts exist:
//!
//! - v1 (MoorDyn v1, C and FAST): `LINE DICTIONARY`/`LINE TYPES` rows
//!   `Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt` (9 columns); `NODE PROPERTIES`/
//!   `CONNECTION PROPERTIES` rows `ID Type X Y Z M V FX FY FZ CdA Ca`;
//!   `LINE PROPERTIES` rows `ID LineType UnstrLen NumSegs NodeAnch NodeFair Flags`.
//! - v2: `LINE TYPES` rows `Name Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx
//!   [Cl [dF cF]]` (10, 11 or 13 columns); `POINTS` rows `ID Attachment X Y Z Mass
//!   Volume CdA Ca` (or with `FX FY FZ` before `CdA`, 12 columns); `LINES` rows
//!   `ID LineType AttachA AttachB UnstrLen NumSegs Outputs`.
//!
//! The layout is told by the line-type rows (9 columns: v1), and for the lines table
//! by its column-name line where that is plain (`UnstrLen` third: v1 order;
//! `AttachA` third: v2 order). Nothing here judges whether cablesim can run a value:
//! that is `convert`'s job.

use super::err_at;
use crate::error::Error;
use std::path::Path;

/// The input-file layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Version {
    /// MoorDyn v1.
    V1,
    /// MoorDyn v2.
    V2,
}

/// A row of the line-type table.
#[derive(Clone, Debug, PartialEq)]
pub struct LineTypeRow {
    /// 1-based line number in the file.
    pub line: usize,
    /// Type name.
    pub name: String,
    /// Volume-equivalent diameter, m.
    pub diam: f64,
    /// Mass per unit length in air, kg/m.
    pub mass: f64,
    /// Axial stiffness as written, N (a number; `|`-separated values or a table file
    /// name mean a nonlinear or viscoelastic model).
    pub ea: String,
    /// Internal damping as written: BA in N s, or a negative damping ratio `-zeta`
    /// (`|`-separated values mean static and dynamic damping).
    pub ba: String,
    /// Bending stiffness EI, N m^2 (v2 only; 0 in v1).
    pub ei: f64,
    /// Transverse drag coefficient (on the frontal area d l).
    pub cd: f64,
    /// Transverse added-mass coefficient (on the displaced volume).
    pub ca: f64,
    /// Tangential drag coefficient (on the surface area pi d l).
    pub cdax: f64,
    /// Tangential added-mass coefficient.
    pub caax: f64,
    /// VIV cross-flow lift coefficient (v2, optional; 0 when absent).
    pub cl: f64,
}

/// A row of the point table.
#[derive(Clone, Debug, PartialEq)]
pub struct PointRow {
    /// 1-based line number in the file.
    pub line: usize,
    /// Point ID (sequential from 1).
    pub id: usize,
    /// Attachment word as written (`Fixed`, `Vessel`, `Coupled`, `Free`, `Body2`, ...).
    pub attachment: String,
    /// Position (an initial guess for free points), m.
    pub pos: [f64; 3],
    /// Mass, kg.
    pub mass: f64,
    /// Displaced volume, m^3.
    pub volume: f64,
    /// Steady external force, N (zero when the row has no force columns).
    pub force: [f64; 3],
    /// Drag coefficient times area, m^2.
    pub cda: f64,
    /// Added-mass coefficient (on the volume).
    pub ca: f64,
}

/// A row of the lines table.
#[derive(Clone, Debug, PartialEq)]
pub struct LineRow {
    /// 1-based line number in the file.
    pub line: usize,
    /// Line ID (sequential from 1).
    pub id: usize,
    /// Line type name.
    pub line_type: String,
    /// End A (anchor end) as written: a point ID (`3`, `C3`, `P3`, `Point3`) or a rod
    /// end (`R1A`).
    pub attach_a: String,
    /// End B (fairlead end), as for `attach_a`.
    pub attach_b: String,
    /// Unstretched length, m.
    pub length: f64,
    /// Number of segments.
    pub segments: i64,
    /// Output flags as written (`-` for none).
    pub flags: String,
}

/// A row of the bodies table: `ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG I Volume CdA
/// Ca`. The cells that may hold several `|`-separated values are kept as written.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyRow {
    /// 1-based line number in the file.
    pub line: usize,
    /// Body ID (sequential from 1).
    pub id: usize,
    /// Attachment word as written (`Free`, `Fixed`, `Coupled`, `CoupledPinned`, ...).
    pub attachment: String,
    /// Reference point, m, and roll, pitch, yaw, degrees (MoorDyn's order: `R = Rx(r)
    /// Ry(p) Rz(y)`).
    pub r6: [f64; 6],
    /// Mass, kg.
    pub mass: f64,
    /// Centre of gravity as written (`z`, or `x|y|z`), m.
    pub cg: String,
    /// Inertia as written (`I`, or `Ixx|Iyy|Izz`), kg m^2.
    pub inertia: String,
    /// Displaced volume, m^3.
    pub volume: f64,
    /// Drag coefficient times area as written (1, 2, 3 or 6 values), m^2 (m^5 for the
    /// rotations).
    pub cda: String,
    /// Added-mass coefficients as written (1 or 3 values).
    pub ca: String,
}

/// A row of the FAILURE section (MoorDyn-F): `FailureID Point Line(s) FailTime
/// FailTen`.
#[derive(Clone, Debug, PartialEq)]
pub struct FailureRow {
    /// 1-based line number in the file.
    pub line: usize,
    /// Failure ID as written.
    pub id: String,
    /// The point as written (`5`, `P5`, `C5`, `Point5`; `R1a` names a rod end).
    pub point: String,
    /// The lines as written (`1,2,3`).
    pub lines: String,
    /// Failure time, s (0: none).
    pub time: f64,
    /// Failure tension, N (0: none).
    pub tension: f64,
}

/// An `OPTIONS` row: `value name [description]`.
#[derive(Clone, Debug, PartialEq)]
pub struct OptionRow {
    /// 1-based line number in the file.
    pub line: usize,
    /// The value as written.
    pub value: String,
    /// The option name as written (MoorDyn compares names case-insensitively).
    pub name: String,
}

/// A section that cablesim does not read (rods, bodies, failures, ...), kept so the
/// conversion can refuse it by line.
#[derive(Clone, Debug, PartialEq)]
pub struct OtherSection {
    /// 1-based line number of the header.
    pub line: usize,
    /// The header's key phrase.
    pub kind: &'static str,
    /// Line numbers of its rows.
    pub rows: Vec<usize>,
}

/// A MoorDyn input file's tables.
#[derive(Clone, Debug, PartialEq)]
pub struct MoorDynFile {
    /// The layout found.
    pub version: Version,
    /// Line types.
    pub line_types: Vec<LineTypeRow>,
    /// Points (v1 nodes / connections).
    pub points: Vec<PointRow>,
    /// Lines.
    pub lines: Vec<LineRow>,
    /// Options.
    pub options: Vec<OptionRow>,
    /// Output channels, with their line numbers.
    pub outputs: Vec<(usize, String)>,
    /// Bodies.
    pub bodies: Vec<BodyRow>,
    /// Failures (MoorDyn-F).
    pub failures: Vec<FailureRow>,
    /// Sections cablesim does not read.
    pub others: Vec<OtherSection>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub enum Kind {
    LineTypes,
    Points,
    Lines,
    Options,
    Outputs,
    Bodies,
    Failure,
    Other(&'static str),
    /// A header with no known key phrase (the title line, `need this line`).
    Unknown,
}

/// The section a header line opens. Longer phrases are tried first where one contains
/// another (`LINE TYPES` before `LINES`, `ROD TYPES` before `RODS`).
#[doc(hidden)]
pub fn kind_of(header: &str) -> Kind {
    let h = header.to_uppercase();
    let has = |keys: &[&str]| keys.iter().any(|k| h.contains(k));
    if has(&["LINE DICTIONARY", "LINE TYPES"]) {
        Kind::LineTypes
    } else if has(&["ROD DICTIONARY", "ROD TYPES"]) {
        Kind::Other("ROD TYPES")
    } else if has(&["BODIES", "BODY LIST", "BODY PROPERTIES"]) {
        Kind::Bodies
    } else if has(&["RODS", "ROD LIST", "ROD PROPERTIES"]) {
        Kind::Other("RODS")
    } else if has(&[
        "POINTS",
        "POINT LIST",
        "POINT PROPERTIES",
        "CONNECTION PROPERTIES",
        "NODE PROPERTIES",
    ]) {
        Kind::Points
    } else if has(&["LINES", "LINE LIST", "LINE PROPERTIES"]) {
        Kind::Lines
    } else if has(&["OPTIONS"]) {
        Kind::Options
    } else if has(&["OUTPUT"]) {
        Kind::Outputs
    } else if has(&["FAILURE"]) {
        Kind::Failure
    } else if has(&["CONTROL"]) {
        Kind::Other("CONTROL")
    } else if has(&["EXTERNAL LOADS"]) {
        Kind::Other("EXTERNAL LOADS")
    } else if has(&["SYROPE IC"]) {
        Kind::Other("SYROPE IC")
    } else {
        Kind::Unknown
    }
}

/// True when `text` looks like a MoorDyn input file: a `---` header naming line types
/// and one naming lines.
pub fn looks_like_moordyn(text: &str) -> bool {
    let mut types = false;
    let mut lines = false;
    for l in text.lines().filter(|l| l.contains("---")) {
        match kind_of(l) {
            Kind::LineTypes => types = true,
            Kind::Lines => lines = true,
            _ => {}
        }
    }
    types && lines
}

/// A row's fields: whitespace-separated, with `#` comments removed.
#[doc(hidden)]
pub fn fields(line: &str) -> Vec<String> {
    let body = line.split('#').next().unwrap_or("");
    body.split_whitespace().map(str::to_string).collect()
}

struct Section {
    kind: Kind,
    header: usize,
    /// The column-name line (table sections), with its fields.
    columns: Vec<String>,
    /// (1-based line number, fields) of each non-empty row.
    rows: Vec<(usize, Vec<String>)>,
}

fn sections(text: &str) -> Vec<Section> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if !lines[i].contains("---") {
            i += 1;
            continue;
        }
        let kind = kind_of(lines[i]);
        let header = i + 1;
        i += 1;
        let mut columns = Vec::new();
        let table = !matches!(kind, Kind::Options | Kind::Outputs | Kind::Unknown);
        if table {
            // Column names, then units (MoorDyn skips exactly two lines).
            for k in 0..2 {
                if i < lines.len() && !lines[i].contains("---") {
                    if k == 0 {
                        columns = fields(lines[i]);
                    }
                    i += 1;
                }
            }
        }
        let mut rows = Vec::new();
        while i < lines.len() && !lines[i].contains("---") {
            let f = fields(lines[i]);
            // An `END` row closes the outputs list (v1 and FAST files).
            if kind == Kind::Outputs && f.first().is_some_and(|w| w.eq_ignore_ascii_case("END")) {
                i += 1;
                while i < lines.len() && !lines[i].contains("---") {
                    i += 1;
                }
                break;
            }
            if !f.is_empty() {
                rows.push((i + 1, f));
            }
            i += 1;
        }
        out.push(Section {
            kind,
            header,
            columns,
            rows,
        });
    }
    out
}

fn num(p: &Path, line: usize, what: &str, s: &str) -> Result<f64, Error> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(err_at(
            p,
            line,
            what,
            format!("must be a finite number, got \"{s}\""),
        )),
    }
}

fn int(p: &Path, line: usize, what: &str, s: &str) -> Result<i64, Error> {
    s.parse::<i64>()
        .map_err(|_| err_at(p, line, what, format!("must be an integer, got \"{s}\"")))
}

fn need(p: &Path, line: usize, table: &str, f: &[String], n: usize) -> Result<(), Error> {
    if f.len() < n {
        Err(err_at(
            p,
            line,
            table,
            format!("needs at least {n} columns, got {}", f.len()),
        ))
    } else {
        Ok(())
    }
}

/// Reads a MoorDyn input file's text; `path` names the file in messages.
pub fn parse(text: &str, path: &Path) -> Result<MoorDynFile, Error> {
    let p = path;
    let secs = sections(text);
    // The layout: the line-type rows' width decides.
    let mut version = Version::V2;
    for s in secs.iter().filter(|s| s.kind == Kind::LineTypes) {
        if let Some((_, f)) = s.rows.first() {
            if f.len() == 9 {
                version = Version::V1;
            }
        }
    }
    let mut file = MoorDynFile {
        version,
        line_types: Vec::new(),
        points: Vec::new(),
        lines: Vec::new(),
        options: Vec::new(),
        outputs: Vec::new(),
        bodies: Vec::new(),
        failures: Vec::new(),
        others: Vec::new(),
    };
    for s in &secs {
        match s.kind {
            Kind::LineTypes => {
                for (line, f) in &s.rows {
                    let l = *line;
                    let t = "LINE TYPES row";
                    let row = match version {
                        Version::V1 => {
                            need(p, l, t, f, 9)?;
                            LineTypeRow {
                                line: l,
                                name: f[0].clone(),
                                diam: num(p, l, "Diam", &f[1])?,
                                mass: num(p, l, "MassDen", &f[2])?,
                                ea: f[3].clone(),
                                ba: f[4].clone(),
                                ei: 0.0,
                                ca: num(p, l, "Can", &f[5])?,
                                caax: num(p, l, "Cat", &f[6])?,
                                cd: num(p, l, "Cdn", &f[7])?,
                                cdax: num(p, l, "Cdt", &f[8])?,
                                cl: 0.0,
                            }
                        }
                        Version::V2 => {
                            need(p, l, t, f, 10)?;
                            if ![10, 11, 13].contains(&f.len()) {
                                return Err(err_at(
                                    p,
                                    l,
                                    t,
                                    format!(
                                        "has {} columns; MoorDyn v2 line types have 10, 11 \
                                         (with Cl) or 13 (with Cl, dF, cF)",
                                        f.len()
                                    ),
                                ));
                            }
                            LineTypeRow {
                                line: l,
                                name: f[0].clone(),
                                diam: num(p, l, "Diam", &f[1])?,
                                mass: num(p, l, "Mass/m", &f[2])?,
                                ea: f[3].clone(),
                                ba: f[4].clone(),
                                ei: num(p, l, "EI", &f[5])?,
                                cd: num(p, l, "Cd", &f[6])?,
                                ca: num(p, l, "Ca", &f[7])?,
                                cdax: num(p, l, "CdAx", &f[8])?,
                                caax: num(p, l, "CaAx", &f[9])?,
                                cl: match f.get(10) {
                                    Some(x) => num(p, l, "Cl", x)?,
                                    None => 0.0,
                                },
                            }
                        }
                    };
                    file.line_types.push(row);
                }
            }
            Kind::Points => {
                for (line, f) in &s.rows {
                    let l = *line;
                    need(p, l, "POINTS row", f, 9)?;
                    let with_force = f.len() >= 12;
                    let c = |k: usize| if with_force { k + 3 } else { k };
                    let pos = [
                        num(p, l, "X", &f[2])?,
                        num(p, l, "Y", &f[3])?,
                        num(p, l, "Z", &f[4])?,
                    ];
                    let force = if with_force {
                        [
                            num(p, l, "FX", &f[7])?,
                            num(p, l, "FY", &f[8])?,
                            num(p, l, "FZ", &f[9])?,
                        ]
                    } else {
                        [0.0; 3]
                    };
                    let id = int(p, l, "ID", &f[0])?;
                    file.points.push(PointRow {
                        line: l,
                        id: id.max(0) as usize,
                        attachment: f[1].clone(),
                        pos,
                        mass: num(p, l, "Mass", &f[5])?,
                        volume: num(p, l, "Volume", &f[6])?,
                        force,
                        cda: num(p, l, "CdA", &f[c(7)])?,
                        ca: num(p, l, "Ca", &f[c(8)])?,
                    });
                }
            }
            Kind::Lines => {
                // Column order: v1 `ID Type UnstrLen NumSegs NodeAnch NodeFair Flags`,
                // v2 `ID Type AttachA AttachB UnstrLen NumSegs Outputs`.
                let third = s.columns.get(2).map(|c| c.to_lowercase());
                let v1_order = match third.as_deref() {
                    Some(c) if c.contains("len") => true,
                    Some(c) if c.contains("attach") => false,
                    _ => version == Version::V1,
                };
                for (line, f) in &s.rows {
                    let l = *line;
                    need(p, l, "LINES row", f, 6)?;
                    let (a, b, len, seg) = if v1_order { (4, 5, 2, 3) } else { (2, 3, 4, 5) };
                    let (len_name, seg_name) = ("UnstrLen", "NumSegs");
                    file.lines.push(LineRow {
                        line: l,
                        id: int(p, l, "ID", &f[0])?.max(0) as usize,
                        line_type: f[1].clone(),
                        attach_a: f[a].clone(),
                        attach_b: f[b].clone(),
                        length: num(p, l, len_name, &f[len])?,
                        segments: int(p, l, seg_name, &f[seg])?,
                        flags: f.get(6).cloned().unwrap_or_else(|| "-".into()),
                    });
                }
            }
            Kind::Options => {
                for (line, f) in &s.rows {
                    if f.len() < 2 {
                        return Err(err_at(
                            p,
                            *line,
                            "OPTIONS row",
                            "needs a value and an option name",
                        ));
                    }
                    file.options.push(OptionRow {
                        line: *line,
                        value: f[0].clone(),
                        name: f[1].clone(),
                    });
                }
            }
            Kind::Outputs => {
                for (line, f) in &s.rows {
                    for w in f {
                        file.outputs.push((*line, w.clone()));
                    }
                }
            }
            Kind::Bodies => {
                for (line, f) in &s.rows {
                    let l = *line;
                    need(p, l, "BODIES row", f, 14)?;
                    let mut r6 = [0.0; 6];
                    for (k, name) in ["X0", "Y0", "Z0", "r0", "p0", "y0"].iter().enumerate() {
                        r6[k] = num(p, l, name, &f[2 + k])?;
                    }
                    file.bodies.push(BodyRow {
                        line: l,
                        id: int(p, l, "ID", &f[0])?.max(0) as usize,
                        attachment: f[1].clone(),
                        r6,
                        mass: num(p, l, "Mass", &f[8])?,
                        cg: f[9].clone(),
                        inertia: f[10].clone(),
                        volume: num(p, l, "Volume", &f[11])?,
                        cda: f[12].clone(),
                        ca: f[13].clone(),
                    });
                }
            }
            Kind::Failure => {
                for (line, f) in &s.rows {
                    let l = *line;
                    need(p, l, "FAILURE row", f, 5)?;
                    file.failures.push(FailureRow {
                        line: l,
                        id: f[0].clone(),
                        point: f[1].clone(),
                        lines: f[2].clone(),
                        time: num(p, l, "FailTime", &f[3])?,
                        tension: num(p, l, "FailTen", &f[4])?,
                    });
                }
            }
            Kind::Other(kind) => file.others.push(OtherSection {
                line: s.header,
                kind,
                rows: s.rows.iter().map(|(l, _)| *l).collect(),
            }),
            Kind::Unknown => {}
        }
    }
    if file.line_types.is_empty() {
        return Err(err_at(
            p,
            0,
            "LINE TYPES",
            "no line types (a `--- LINE TYPES ---` section with rows)",
        ));
    }
    if file.lines.is_empty() {
        return Err(err_at(
            p,
            0,
            "LINES",
            "no lines (a `--- LINES ---` section with rows)",
        ));
    }
    Ok(file)
}
