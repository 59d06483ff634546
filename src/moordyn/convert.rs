//! A MoorDyn input file's tables mapped to a cablesim scenario, written as scenario
//! TOML with a comment on each choice. What cannot be expressed is an error naming the
//! file's line; what is dropped with little effect is a warning naming it.
//!
//! The definitions compared (MoorDyn's from its input-file documentation and
//! `Line.cpp`/`Point.cpp` of MoorDyn-C v2; cablesim's from its line-type and seabed
//! docs):
//!
//! - Normal drag: MoorDyn `1/2 rho Cd d l |vp| vp` (frontal area d l); cablesim
//!   `1/2 rho cn d l |vn| vn`: `cn = Cd`.
//! - Tangential drag: MoorDyn `1/2 rho CdAx pi d l |vq| vq` (surface area pi d l, v1
//!   `Cdt` alike); cablesim `1/2 rho ct pi d l |vt| vt`: `ct = CdAx`.
//! - Normal added mass: MoorDyn `Ca rho (pi d^2/4) l` across the line; cablesim
//!   `cm rho A l` likewise: `cm = Ca`. Tangential added mass: MoorDyn `CaAx rho (pi
//!   d^2/4) l` along the line (v1 `Cat`), with the Froude-Krylov load `(1 + CaAx) rho V
//!   a_t` along it; cablesim `cat rho A l0` and `(1 + cat) rho A l0 a_t`: `cat = CaAx`.
//! - Internal damping: MoorDyn's segment force is `BA epsdot` (N s); cablesim's is
//!   `EA c epsdot` with the time constant `c` (s): `c = BA / EA`. A negative entry is
//!   a damping ratio `zeta = -BA`, for which MoorDyn sets
//!   `BA = zeta (L/N) sqrt(EA m)` per line (segment length `L/N`, mass per length
//!   `m`), so `c = zeta (L/N) sqrt(m / EA) = zeta (L/N) / sqrt(EA/m)`: the segment's
//!   axial wave-crossing time times the ratio. It depends on the line's segment length,
//!   so lines of one MoorDyn type may need cablesim types of their own.
//! - Seabed: MoorDyn's kBot (Pa/m) and cBot (Pa s/m) are pressures per metre of
//!   penetration (per m/s) on the area `d l` of each node, so the force per metre of
//!   line is `kBot d` (N/m per m) and `cBot d` (N s/m per m), cablesim's `stiffness`
//!   and `damping`, which are one value for the whole seabed: with line types of
//!   different diameters, the diameter of the longest total length of line is used and
//!   a warning names the others.
//! - Points: MoorDyn's point mass, volume (buoyancy `rho V g`), `CdA`
//!   (`1/2 rho CdA |v| v`) and `Ca` (added mass `Ca rho V`, isotropic) are cablesim's
//!   `mass`, `volume`, `drag_area`, `added_mass` unchanged.

use super::bodies::{fail_keys, read_bodies, read_failures, BodyKind, MdBody, MdFailure};
use super::err_at;
use super::options::{read_current_profile, read_options};
use super::parse::{MoorDynFile, Version};
use super::tables::{attach_point, check_type, point_kind, PointKind};
use crate::error::Error;
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write;
use std::path::Path;

/// Choices a MoorDyn file does not make.
#[derive(Clone, Debug)]
pub struct ConvertOptions {
    /// Simulated duration, s (a MoorDyn input file has none: its driver gives it).
    pub duration: f64,
    /// Motion files for vessel/coupled points: point ID -> CSV file `t,x,y,z` (as
    /// cablesim's `route = "table"` reads it; a relative path is taken from the
    /// scenario file's folder).
    pub motions: BTreeMap<usize, String>,
}

impl Default for ConvertOptions {
    fn default() -> Self {
        Self {
            duration: 60.0,
            motions: BTreeMap::new(),
        }
    }
}

pub use super::Warning;

/// The conversion's result.
#[derive(Clone, Debug)]
pub struct Converted {
    /// Scenario TOML, with comments.
    pub toml: String,
    /// Warnings, in file order.
    pub warnings: Vec<Warning>,
}

/// `12.5` style: Rust's shortest round-trip form, which TOML reads as a float.
fn f(x: f64) -> String {
    format!("{x:?}")
}

fn quote(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

fn v3(x: [f64; 3]) -> String {
    format!("[{}, {}, {}]", f(x[0]), f(x[1]), f(x[2]))
}

/// Writes MoorDyn's waves (`moordyn::waves`) as `[environment.waves]` with one
/// `"components"` train; still water, with a comment, when every amplitude is zero.
fn write_waves(w: &mut String, md: &super::waves::MdWaves) {
    let (mode, l) = md.mode;
    let what = if mode == 7 {
        "MoorDyn sums these components at the nodes, as cablesim does"
    } else {
        "the elevation record resampled and decomposed by FFT as MoorDyn does"
    };
    let _ = writeln!(w, "# WaveKin = {mode} (line {l}): {}; {what}.", md.file);
    for n in &md.notes {
        let _ = writeln!(w, "# {n}.");
    }
    if md.rows.iter().all(|r| r[1] == 0.0) {
        let _ = writeln!(w, "# Every amplitude is zero: still water.");
        return;
    }
    let _ = writeln!(w, "\n[environment.waves]");
    let _ = writeln!(
        w,
        "# MoorDyn has no start-up ramp and stretches the profile as Wheeler does (cablesim's \
         default); the components act from t = 0."
    );
    let _ = writeln!(w, "\n[[environment.waves.trains]]");
    let _ = writeln!(w, "type = \"components\"");
    let rows_are = if mode == 7 {
        "MoorDyn's complex amplitude a gives A = |a| and phase = 90 - arg(a) in degrees \
         (MoorDyn writes |a| sin(omega t - k x + arg a))"
    } else {
        "FFT bin i of the N resampled samples, X_i, gives A = 2 |X_i| / N and phase = \
         -arg(X_i) in degrees (the record at the origin from t = 0)"
    };
    let _ = writeln!(
        w,
        "# [omega (rad/s), amplitude (m), phase (degrees), direction (degrees)] with \
         eta = A cos(k (x cos b + y sin b) - omega t + phase): {rows_are}."
    );
    let _ = writeln!(w, "rows = [");
    for r in &md.rows {
        let _ = writeln!(
            w,
            "    [{}, {}, {}, {}],",
            f(r[0]),
            f(r[1]),
            f(r[2]),
            f(r[3])
        );
    }
    let _ = writeln!(w, "]");
}

/// Writes one MoorDyn body as `[[bodies]]`; `initial` is the free and pinned bodies'
/// `initial` key and the note on it (from TmaxIC).
fn write_body(w: &mut String, b: &MdBody, initial: &(&str, String)) {
    let r = &b.row;
    let name = b.name();
    let x = [r.r6[0], r.r6[1], r.r6[2]];
    let attitude = format!(
        "r0, p0, y0 = {}, {}, {} deg in MoorDyn's order (R = Rx Ry Rz)",
        f(r.r6[3]),
        f(r.r6[4]),
        f(r.r6[5])
    );
    match b.kind {
        BodyKind::Fixed => {
            let _ = writeln!(
                w,
                "\n# Body {} ({}, line {}): fixed; its points are written as fixed points at \
                 their places ({attitude}).",
                r.id, r.attachment, r.line
            );
            return;
        }
        BodyKind::Coupled => {
            let _ = writeln!(w, "\n[[bodies]]");
            let _ = writeln!(
                w,
                "# Body {} ({}, line {}): coupled (its motion comes from MoorDyn's caller): \
                 held still at its pose here; give it a `motion_file` (t,x,y,z,roll,pitch,yaw) \
                 to drive it ({attitude}).",
                r.id, r.attachment, r.line
            );
            let _ = writeln!(w, "name = {}", quote(&name));
            let _ = writeln!(w, "reference = {}  # X0, Y0, Z0", v3(x));
            return;
        }
        _ => {}
    }
    let _ = writeln!(w, "\n[[bodies]]");
    let pinned = b.kind == BodyKind::Pinned;
    let _ = writeln!(
        w,
        "# Body {} ({}, line {}): {}.",
        r.id,
        r.attachment,
        r.line,
        if pinned {
            "coupled pinned: its reference point is held (still here; a `motion_file` with \
             zero angles drives it), its rotation free"
        } else {
            "free, moved by its own dynamics"
        }
    );
    let _ = writeln!(w, "name = {}", quote(&name));
    let _ = writeln!(w, "motion = \"{}\"", if pinned { "pinned" } else { "free" });
    let _ = writeln!(w, "# {}.", initial.1);
    let _ = writeln!(w, "initial = \"{}\"", initial.0);
    let _ = writeln!(w, "reference = {}  # X0, Y0, Z0", v3(x));
    let _ = writeln!(
        w,
        "angles = {}  # roll, pitch, yaw (R = Rz Ry Rx) of MoorDyn's {attitude}",
        v3(b.angles)
    );
    let _ = writeln!(w, "mass = {}  # kg, Mass", f(r.mass));
    let _ = writeln!(w, "cg = {}  # m, CG \"{}\"", v3(b.cg), r.cg);
    let _ = writeln!(
        w,
        "inertia = {}  # kg m^2 about the centre of gravity, I \"{}\"",
        v3(b.inertia),
        r.inertia
    );
    let _ = writeln!(w, "volume = {}  # m^3, Volume", f(r.volume));
    let _ = writeln!(
        w,
        "cb = {}  # MoorDyn's buoyancy acts at the centre of gravity",
        v3(b.cg)
    );
    let _ = writeln!(
        w,
        "ca = {}  # Ca \"{}\": added mass Ca rho V per body axis at the reference point",
        v3(b.ca),
        r.ca
    );
    let _ = writeln!(
        w,
        "drag_area = {}  # m^2, CdA \"{}\" (translations)",
        v3([b.cda[0], b.cda[1], b.cda[2]]),
        r.cda
    );
    let _ = writeln!(
        w,
        "rotational_drag = {}  # CdA (rotations): -1/2 rho CdA w |w| per body axis",
        v3([b.cda[3], b.cda[4], b.cda[5]])
    );
}

/// Maps a parsed MoorDyn file to scenario TOML. `path` names the file in messages.
pub fn convert(file: &MoorDynFile, path: &Path, opts: &ConvertOptions) -> Result<Converted, Error> {
    let p = path;
    let mut warn = Vec::new();

    // Sections with no cablesim counterpart.
    for s in &file.others {
        let Some(&first) = s.rows.first() else {
            continue;
        };
        match s.kind {
            "ROD TYPES" => warn.push(Warning {
                line: s.line,
                message: "ROD TYPES ignored (no rods are converted)".into(),
            }),
            "RODS" => {
                return Err(err_at(
                    p,
                    first,
                    "RODS",
                    "rods are not supported (cablesim has no rigid or pinned rod objects)",
                ))
            }
            kind => {
                return Err(err_at(
                    p,
                    first,
                    kind,
                    format!("the {kind} section (MoorDyn-F) is not supported"),
                ))
            }
        }
    }

    let o = read_options(file, p, &mut warn)?;
    for (what, (x, l)) in [
        ("g", o.g),
        ("rho", o.rho),
        ("kBot", o.kbot),
        ("cBot", o.cbot),
    ] {
        if x < 0.0 {
            return Err(err_at(
                p,
                l,
                format!("option {what}"),
                format!("must not be negative, got {x}"),
            ));
        }
    }

    let current = match o.currents {
        Some((mode, l)) => {
            let (rows, file) = read_current_profile(p, l)?;
            Some((mode, l, rows, file))
        }
        None => None,
    };
    let waves = match o.wave_kin {
        Some((7, l)) => Some(super::waves::frequencies(p, l, &mut warn)?),
        Some((_, l)) => Some(super::waves::elevation(
            p,
            l,
            o.dt_wave.unwrap_or((super::waves::DEFAULT_DT_WAVE, 0)),
            &mut warn,
        )?),
        None => None,
    };

    // Line types.
    let mut types: HashMap<&str, (usize, f64, f64)> = HashMap::new();
    let mut curves: HashMap<&str, super::tables::EaCurve> = HashMap::new();
    let mut viscos: HashMap<&str, super::tables::MdVisco> = HashMap::new();
    for (i, t) in file.line_types.iter().enumerate() {
        let (ea, ba, curve, visco) = check_type(p, t, file.version, &mut warn)?;
        if let Some(c) = curve {
            curves.insert(t.name.as_str(), c);
        }
        if let Some(v) = visco {
            viscos.insert(t.name.as_str(), v);
        }
        if types.insert(t.name.as_str(), (i, ea, ba)).is_some() {
            return Err(err_at(
                p,
                t.line,
                format!("line type \"{}\"", t.name),
                "duplicate line type name",
            ));
        }
    }

    // Bodies.
    let bodies = read_bodies(p, &file.bodies, &mut warn)?;

    // Points.
    let mut kinds = Vec::with_capacity(file.points.len());
    for (i, r) in file.points.iter().enumerate() {
        if r.id != i + 1 {
            return Err(err_at(
                p,
                r.line,
                "point ID",
                format!(
                    "point IDs must run 1, 2, 3, ...: expected {}, got {}",
                    i + 1,
                    r.id
                ),
            ));
        }
        let k = point_kind(p, r, bodies.len())?;
        if r.force != [0.0; 3] {
            return Err(err_at(
                p,
                r.line,
                format!("point {} FX FY FZ", r.id),
                "steady external point forces are not supported",
            ));
        }
        for (c, x) in [
            ("Mass", r.mass),
            ("Volume", r.volume),
            ("CdA", r.cda),
            ("Ca", r.ca),
        ] {
            if x < 0.0 {
                return Err(err_at(
                    p,
                    r.line,
                    format!("point {} {c}", r.id),
                    format!("must not be negative, got {x}"),
                ));
            }
        }
        kinds.push(k);
    }
    for &id in opts.motions.keys() {
        match kinds.get(id.wrapping_sub(1)) {
            Some(PointKind::Coupled) => {}
            _ => {
                return Err(err_at(
                    p,
                    0,
                    format!("motion for point {id}"),
                    "a motion file needs a Vessel/Coupled point of that ID",
                ))
            }
        }
    }

    // Lines, and how many line ends each point holds.
    let mut uses = vec![0usize; file.points.len()];
    let mut ends = Vec::with_capacity(file.lines.len());
    for (i, l) in file.lines.iter().enumerate() {
        if l.id != i + 1 {
            return Err(err_at(
                p,
                l.line,
                "line ID",
                format!(
                    "line IDs must run 1, 2, 3, ...: expected {}, got {}",
                    i + 1,
                    l.id
                ),
            ));
        }
        if !types.contains_key(l.line_type.as_str()) {
            let mut known: Vec<_> = file.line_types.iter().map(|t| t.name.as_str()).collect();
            known.sort();
            return Err(err_at(
                p,
                l.line,
                format!("line {} LineType", l.id),
                format!(
                    "unknown line type \"{}\" (defined: {})",
                    l.line_type,
                    known.join(", ")
                ),
            ));
        }
        if l.length <= 0.0 {
            return Err(err_at(
                p,
                l.line,
                format!("line {} UnstrLen", l.id),
                format!("must be positive, got {}", l.length),
            ));
        }
        if l.segments < 1 {
            return Err(err_at(
                p,
                l.line,
                format!("line {} NumSegs", l.id),
                format!("must be at least 1, got {}", l.segments),
            ));
        }
        let a = attach_point(p, l, "AttachA", &l.attach_a, file.points.len())?;
        let b = attach_point(p, l, "AttachB", &l.attach_b, file.points.len())?;
        if a == b {
            return Err(err_at(
                p,
                l.line,
                format!("line {}", l.id),
                "both ends on the same point",
            ));
        }
        uses[a - 1] += 1;
        uses[b - 1] += 1;
        ends.push((a, b));
    }

    // Failures: a row listing every line at its point fails the point (its lines go
    // together, with the point's mass); a row listing some of them moves those ends to
    // a point of their own at the same place, which fails.
    let failures = read_failures(p, &file.failures, file.points.len(), &ends, &mut warn)?;
    let mut whole: Vec<Option<&MdFailure>> = vec![None; file.points.len()];
    let mut split: Vec<&MdFailure> = Vec::new();
    for fl in &failures {
        let i = fl.point - 1;
        if kinds[i] == PointKind::Free {
            return Err(err_at(
                p,
                fl.line,
                format!("failure {} Point", fl.id),
                format!(
                    "point {} is free: it has no support for its lines to leave (cablesim \
                     fails lines at fixed, coupled or body points)",
                    fl.point
                ),
            ));
        }
        if fl.lines.len() == uses[i] {
            whole[i] = Some(fl);
        } else {
            split.push(fl);
        }
    }
    // Per line end (line index, 0 = A / 1 = B): the split failure that moves it.
    let split_of = |k: usize, end: usize| -> Option<&MdFailure> {
        let id = ends[k].0 * (1 - end) + ends[k].1 * end;
        split
            .iter()
            .find(|fl| fl.point == id && fl.lines.contains(&(k + 1)))
            .copied()
    };

    for (i, r) in file.points.iter().enumerate() {
        if uses[i] == 0 {
            warn.push(Warning {
                line: r.line,
                message: format!("point {} has no lines and is left out", r.id),
            });
        }
    }

    // Water depth: MoorDyn-C takes WtrDpth (default 0) and lowers the seabed to any
    // point below it, so an anchor given at the bottom sets the depth.
    let global = |i: usize| -> [f64; 3] {
        match kinds[i] {
            PointKind::Body(b) => bodies[b - 1].place(file.points[i].pos),
            _ => file.points[i].pos,
        }
    };
    let lowest = (0..file.points.len())
        .map(|i| -global(i)[2])
        .fold(f64::NEG_INFINITY, f64::max);
    let (depth, depth_note) = match o.depth {
        Some((d, l)) if d >= lowest => (d, format!("WtrDpth, line {l}")),
        Some((d, l)) => (
            lowest,
            format!(
                "WtrDpth = {} at line {l} is above the lowest point; MoorDyn lowers the \
                 seabed to that point",
                f(d)
            ),
        ),
        None => (
            lowest,
            "no WtrDpth option: MoorDyn puts the seabed at the lowest point".to_string(),
        ),
    };
    if depth <= 0.0 {
        return Err(err_at(
            p,
            o.depth.map(|x| x.1).unwrap_or(0),
            "option WtrDpth",
            format!("the water depth must be positive, got {depth}"),
        ));
    }

    // The seabed's per-metre constants need one diameter: that of the most line length.
    let mut len_by_type = vec![0.0; file.line_types.len()];
    for l in &file.lines {
        len_by_type[types[l.line_type.as_str()].0] += l.length;
    }
    let main_type = (0..len_by_type.len())
        .max_by(|&a, &b| len_by_type[a].total_cmp(&len_by_type[b]))
        .unwrap_or(0);
    let d_ref = file.line_types[main_type].diam;
    let others: Vec<String> = file
        .lines
        .iter()
        .map(|l| &file.line_types[types[l.line_type.as_str()].0])
        .filter(|t| t.diam != d_ref)
        .map(|t| format!("\"{}\" (d = {} m)", t.name, f(t.diam)))
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    if !others.is_empty() {
        warn.push(Warning {
            line: o.kbot.1,
            message: format!(
                "kBot/cBot: the seabed's per-metre stiffness and damping use the diameter \
                 of \"{}\" (d = {} m); MoorDyn scales them by each line's own diameter, so \
                 the contact of {} is {}",
                file.line_types[main_type].name,
                f(d_ref),
                others.join(", "),
                "stiffer or softer in proportion (static forces change only through \
                 the penetration depth)"
            ),
        });
    }
    let mu = o.mu.map(|x| x.0).unwrap_or(0.0);
    // MoorDyn-F's MU_KT / MU_KA (each 0 unless given) take the place of MoorDyn-C's
    // FrictionCoefficient.
    let split_mu = o.mu_transverse.is_some() || o.mu_axial.is_some();
    if let (true, Some((m, l))) = (split_mu, o.mu) {
        warn.push(Warning {
            line: l,
            message: format!(
                "FrictionCoefficient = {m} is left out: MU_KT / MU_KA (MoorDyn-F's \
                 transverse and axial coefficients) are given and used"
            ),
        });
    }

    // cablesim line types: one per MoorDyn type and damping time constant.
    struct Lt {
        name: String,
        src: usize,
        c: f64,
        note: String,
    }
    let mut lts: Vec<Lt> = Vec::new();
    let mut line_lt = Vec::with_capacity(file.lines.len());
    for l in &file.lines {
        let (ti, ea, ba) = types[l.line_type.as_str()];
        let t = &file.line_types[ti];
        let seg = l.length / l.segments as f64;
        let curve = curves.get(t.name.as_str());
        let visco = viscos.get(t.name.as_str());
        // A viscoelastic line's `c` is its static damping BA_s (N s), not a time constant.
        let (c, note) = if let (true, Some(_)) = (ba < 0.0, visco) {
            let zeta = -ba;
            (
                zeta * seg * (ea * t.mass).sqrt(),
                format!(
                    "BA_s = {} (line {}): damping ratio zeta = {}; MoorDyn sets BA_s = zeta \
                     (L/N) sqrt(EA_s m) with L/N = {} m",
                    t.ba,
                    t.line,
                    f(zeta),
                    f(seg)
                ),
            )
        } else if visco.is_some() {
            (
                ba,
                format!("BA = {} N s (line {}): BA_s|BA_d", t.ba, t.line),
            )
        } else if let (true, Some(cv)) = (ba < 0.0, curve) {
            // A curve: MoorDyn takes the last row's secant for the damping ratio.
            let zeta = -ba;
            (
                zeta * seg * (cv.secant * t.mass).sqrt() / ea,
                format!(
                    "BA/-zeta = {} (line {}): damping ratio zeta = {}; MoorDyn sets BA = zeta \
                     (L/N) sqrt(EA m) with EA the curve's last secant {} N, and c = BA/EA with \
                     EA the curve's largest slope {} N, L/N = {} m",
                    t.ba,
                    t.line,
                    f(zeta),
                    f(cv.secant),
                    f(ea),
                    f(seg)
                ),
            )
        } else if ba < 0.0 {
            let zeta = -ba;
            (
                zeta * seg * (t.mass / ea).sqrt(),
                format!(
                    "BA/-zeta = {} (line {}): damping ratio zeta = {}; MoorDyn sets BA = zeta \
                     (L/N) sqrt(EA m), so c = BA/EA = zeta (L/N) sqrt(m/EA) with L/N = {} m",
                    t.ba,
                    t.line,
                    f(zeta),
                    f(seg)
                ),
            )
        } else {
            (
                ba / ea,
                format!("BA = {} N s (line {}): c = BA/EA", t.ba, t.line),
            )
        };
        let k = match lts.iter().position(|x| x.src == ti && x.c == c) {
            Some(k) => k,
            None => {
                let taken = lts.iter().any(|x| x.src == ti);
                lts.push(Lt {
                    name: if taken {
                        format!("{}_line{}", t.name, l.id)
                    } else {
                        t.name.clone()
                    },
                    src: ti,
                    c,
                    note,
                });
                lts.len() - 1
            }
        };
        line_lt.push(k);
    }

    // The TOML.
    let mut s = String::new();
    let w = &mut s;
    let fname = p.display();
    let ver = match file.version {
        Version::V1 => "v1",
        Version::V2 => "v2",
    };
    let _ = writeln!(
        w,
        "# Converted from the MoorDyn {ver} input file {fname} by `cablesim convert`."
    );
    let _ = writeln!(
        w,
        "# Each value says where it came from; \"line N\" is a line of that file."
    );
    if !warn.is_empty() {
        let _ = writeln!(w, "#\n# Warnings:");
        let mut ws = warn.clone();
        ws.sort_by_key(|x| x.line);
        for x in &ws {
            let _ = writeln!(w, "# - line {}: {}", x.line, x.message);
        }
    }
    let _ = writeln!(w);
    let _ = writeln!(w, "[simulation]");
    let _ = writeln!(
        w,
        "# A MoorDyn input file has no duration (its driver gives one): {} s here.",
        f(opts.duration)
    );
    let _ = writeln!(w, "duration = {}", f(opts.duration));
    match o.dt_m {
        Some((dt, l)) => {
            let _ = writeln!(
                w,
                "# dtM = {} s (line {l}) was chosen for MoorDyn's scheme; cablesim picks the \
                 largest stable step of its own.",
                f(dt)
            );
        }
        None => {
            let _ = writeln!(
                w,
                "# No dtM: cablesim picks the largest stable step of its own."
            );
        }
    }
    if let Some((c, l)) = o.cfl {
        let _ = writeln!(
            w,
            "# CFL = {} (line {l}) is MoorDyn's step rule; cablesim's `auto` step is its own \
             stability bound times a safety factor.",
            f(c)
        );
    }
    let _ = writeln!(w, "dt = \"auto\"");
    let out_int = match o.dt_out {
        Some((x, l)) if x > 0.0 => {
            let _ = writeln!(w, "# dtOut, line {l}.");
            x.min(opts.duration)
        }
        _ => {
            let _ = writeln!(w, "# No dtOut: outputs every second.");
            1.0f64.min(opts.duration)
        }
    };
    let _ = writeln!(w, "output_interval = {}", f(out_int));
    match &o.scheme {
        Some((sch, l)) => match sch.to_uppercase().as_str() {
            "RK2" => {
                let _ = writeln!(w, "scheme = \"rk2\"  # tScheme RK2, line {l}");
            }
            "RK4" => {
                let _ = writeln!(w, "scheme = \"rk4\"  # tScheme RK4, line {l}");
            }
            _ => {
                let _ = writeln!(
                    w,
                    "# tScheme {sch} (line {l}) has no counterpart: cablesim's default \
                     (symplectic Euler) is used."
                );
            }
        },
        None => {
            let _ = writeln!(
                w,
                "# No tScheme: cablesim's default scheme (symplectic Euler), not MoorDyn's RK2."
            );
        }
    }

    let _ = writeln!(w, "\n[environment]");
    let src = |l: usize, what: &str| {
        if l == 0 {
            format!("MoorDyn's default {what}")
        } else {
            format!("{what}, line {l}")
        }
    };
    let _ = writeln!(w, "gravity = {}  # m/s^2, {}", f(o.g.0), src(o.g.1, "g"));
    let _ = writeln!(
        w,
        "water_density = {}  # kg/m^3, {}",
        f(o.rho.0),
        src(o.rho.1, "rho")
    );
    match &o.seafloor {
        None => {
            let _ = writeln!(
                w,
                "depth = {}  # m, seabed at z = -depth ({depth_note})",
                f(depth)
            );
        }
        Some((path, val, l)) => {
            let _ = writeln!(
                w,
                "# SeafloorFile = {val} (line {l}): the seabed is that grid, bilinear; the \
                 waves' depth is its mean depth, as MoorDyn takes it."
            );
            let _ = writeln!(w, "seabed_file = {:?}", path.display().to_string());
        }
    }
    match &current {
        None if waves.is_none() => {
            let _ = writeln!(
                w,
                "# Still water: MoorDyn's WaveKin and Currents are 0 (WaveKin 3 and 7 and \
                 Currents 1 and 3 convert; other values are refused)."
            );
        }
        None => {
            let _ = writeln!(w, "# No current: MoorDyn's Currents is 0.");
        }
        Some((mode, l, rows, file)) => {
            let _ = writeln!(
                w,
                "# Currents = {mode} (line {l}): MoorDyn's steady profile from {file}, \
                 linear in z and held beyond its ends, as here. Rows [z, ux, uy, uz] (m, m/s)."
            );
            let _ = writeln!(w, "current_profile = [");
            for r in rows {
                let _ = writeln!(
                    w,
                    "    [{}, {}, {}, {}],",
                    f(r[0]),
                    f(r[1]),
                    f(r[2]),
                    f(r[3])
                );
            }
            let _ = writeln!(w, "]");
        }
    }
    if let Some(md) = &waves {
        write_waves(w, md);
    }
    let _ = writeln!(w, "\n[environment.seabed]");
    let _ = writeln!(
        w,
        "# MoorDyn's kBot and cBot are pressures on the area d l of each node: per metre of \
         line that is kBot d and cBot d, with d = {} m (line type \"{}\").",
        f(d_ref),
        file.line_types[main_type].name
    );
    let _ = writeln!(
        w,
        "stiffness = {}  # N/m per m: kBot = {} Pa/m ({}) times d",
        f(o.kbot.0 * d_ref),
        f(o.kbot.0),
        src(o.kbot.1, "kBot")
    );
    let _ = writeln!(
        w,
        "damping = {}  # N s/m per m: cBot = {} Pa s/m ({}) times d",
        f(o.cbot.0 * d_ref),
        f(o.cbot.0),
        src(o.cbot.1, "cBot")
    );
    let given = |x: Option<(f64, usize)>, key: &str| match x {
        Some((m, l)) => (m, format!("{key}, line {l}")),
        None => (0.0, format!("no {key} option: MoorDyn-F's default")),
    };
    match (split_mu, o.mu) {
        (true, _) => {
            let (mt, st) = given(o.mu_transverse, "MU_KT");
            let (ma, sa) = given(o.mu_axial, "MU_KA");
            let _ = writeln!(w, "friction_transverse = {}  # {st}", f(mt));
            let _ = writeln!(w, "friction_axial = {}  # {sa}", f(ma));
            let fd = o.fric_damp.map(|x| x.0).unwrap_or(200.0);
            let _ = writeln!(
                w,
                "# MoorDyn-F's friction along and across the line is each a damping mu CV v \
                 (CV = {}) capped at mu times the contact force; cablesim's is mu times the \
                 contact force, linear below friction_velocity (its default), with the two \
                 coefficients weighting the axial and transverse parts of the sliding \
                 velocity (docs/src/model/seabed.md). Both vanish at rest.",
                f(fd)
            );
        }
        (false, Some((m, l))) => {
            let _ = writeln!(w, "friction = {}  # line {l}", f(m));
            let fd = o.fric_damp.map(|x| x.0).unwrap_or(200.0);
            let _ = writeln!(
                w,
                "# MoorDyn's friction is a damping mu FricDamp v (FricDamp = {}) capped at mu \
                 times the contact force; cablesim's is mu times the contact force, linear \
                 below friction_velocity (its default). Both vanish at rest.",
                f(fd)
            );
        }
        (false, None) => {
            let _ = writeln!(w, "friction = {}  # no FrictionCoefficient option", f(mu));
        }
    }
    // MoorDyn's TmaxIC: > 0 (default 120 s) finds the initial equilibrium, free bodies
    // included; 0 starts from the file's pose.
    let tmax_ic =
        o.ic.iter()
            .find(|(n, _, _)| ["tmaxic", "ictmax"].contains(&n.to_lowercase().as_str()))
            .map(|(_, v, l)| (v.parse::<f64>().unwrap_or(120.0), *l));
    let body_initial = match tmax_ic {
        Some((t, l)) if t <= 0.0 => (
            "pose",
            format!("TmaxIC = 0 (line {l}): MoorDyn starts from the file's pose, its lines as catenaries between their ends; the run is the release from there"),
        ),
        Some((t, l)) => (
            "equilibrium",
            format!("TmaxIC = {} (line {l}): MoorDyn finds the static equilibrium of the body with its lines first; cablesim solves for it (Newton on the body's pose)", f(t)),
        ),
        None => (
            "equilibrium",
            "no TmaxIC (MoorDyn's default 120 s): MoorDyn finds the static equilibrium of the body with its lines first; cablesim solves for it (Newton on the body's pose)".to_string(),
        ),
    };
    if !o.ic.is_empty() {
        let list: Vec<String> =
            o.ic.iter()
                .map(|(n, v, l)| format!("{n} = {v} (line {l})"))
                .collect();
        let _ = writeln!(
            w,
            "\n# MoorDyn's initial-condition settings ({}) are not needed: each cable starts \
             from the elastic catenary relaxed to the static equilibrium by Newton's method \
             (initial = \"catenary\"){}.",
            list.join(", "),
            if bodies
                .iter()
                .any(|b| matches!(b.kind, BodyKind::Free | BodyKind::Pinned))
            {
                "; TmaxIC decides whether the free and pinned bodies start in equilibrium \
                 (their `initial`)"
            } else {
                ""
            }
        );
    }
    if !o.ignored.is_empty() {
        let list: Vec<String> = o
            .ignored
            .iter()
            .map(|(n, l)| format!("{n} (line {l})"))
            .collect();
        let _ = writeln!(
            w,
            "# Options about MoorDyn's own logs and outputs, not used: {}.",
            list.join(", ")
        );
    }

    for lt in &lts {
        let t = &file.line_types[lt.src];
        let (_, ea, _) = types[t.name.as_str()];
        let _ = writeln!(w, "\n[[line_types]]");
        let _ = writeln!(w, "# MoorDyn line type \"{}\", line {}.", t.name, t.line);
        let _ = writeln!(w, "name = {}", quote(&lt.name));
        let _ = writeln!(w, "diameter = {}  # m, Diam (volume-equivalent)", f(t.diam));
        let _ = writeln!(w, "mass_per_length = {}  # kg/m", f(t.mass));
        match curves.get(t.name.as_str()) {
            Some(cv) => {
                let _ = writeln!(
                    w,
                    "# EA: the strain-tension curve of \"{}\" (largest slope {} N). Past its last \
                     row cablesim goes on with the last slope, where MoorDyn holds the last tension.",
                    cv.file,
                    f(ea)
                );
                let rows: Vec<String> = cv
                    .rows
                    .iter()
                    .map(|r| format!("[{}, {}]", f(r[0]), f(r[1])))
                    .collect();
                let _ = writeln!(w, "ea_curve = [{}]", rows.join(", "));
            }
            None => {
                let _ = writeln!(w, "ea = {}  # N", f(ea));
            }
        }
        let _ = writeln!(w, "# {}", lt.note);
        match viscos.get(t.name.as_str()) {
            Some(v) => {
                let _ = writeln!(
                    w,
                    "# Viscoelastic (EA = \"{}\"): ea is the static stiffness EA_s.",
                    t.ea
                );
                if v.slope != 0.0 {
                    let _ = writeln!(
                        w,
                        "ea_dynamic = {}  # N, EA_Dc: the dynamic stiffness at zero mean tension",
                        f(v.ea_dynamic)
                    );
                    let _ = writeln!(
                        w,
                        "ea_dynamic_slope = {}  # EA_D_Lm: EA_d = EA_Dc + EA_D_Lm * mean tension",
                        f(v.slope)
                    );
                } else {
                    let _ = writeln!(w, "ea_dynamic = {}  # N, EA_d", f(v.ea_dynamic));
                }
                let _ = writeln!(w, "ba_static = {}  # N s, BA_s", f(lt.c));
                let _ = writeln!(w, "ba_dynamic = {}  # N s, BA_d", f(v.ba_dynamic));
            }
            None => {
                let _ = writeln!(w, "damping = {}  # s", f(lt.c));
            }
        }
        let (cd, cdax, ca, caax) = match file.version {
            Version::V1 => ("Cdn", "Cdt", "Can", "Cat"),
            Version::V2 => ("Cd", "CdAx", "Ca", "CaAx"),
        };
        let _ = writeln!(w, "cn = {}  # {cd}, on the frontal area d l", f(t.cd));
        let _ = writeln!(
            w,
            "ct = {}  # {cdax}, on the surface area pi d l (as cablesim's ct)",
            f(t.cdax)
        );
        let _ = writeln!(w, "cm = {}  # {ca}, normal added mass", f(t.ca));
        let _ = writeln!(w, "cat = {}  # {caax}, tangential added mass", f(t.caax));
        if t.ei > 0.0 {
            let _ = writeln!(
                w,
                "ei = {}  # N m^2, bending stiffness (the line's ends pinned)",
                f(t.ei)
            );
        }
    }

    // Bodies.
    for b in &bodies {
        write_body(w, b, &body_initial);
    }

    // Points: free points, and fixed, coupled or body points that several lines share
    // or that fail, are `[[points]]`; any other is written at its line's end. A coupled
    // (vessel) point is a held end, still or following a motion file.
    let named: Vec<bool> = (0..file.points.len())
        .map(|i| kinds[i] == PointKind::Free || uses[i] > 1)
        .collect();
    let end_table = |i: usize| -> String {
        let r = &file.points[i];
        match kinds[i] {
            PointKind::Fixed => format!("fixed = {}", v3(r.pos)),
            PointKind::Coupled => match opts.motions.get(&r.id) {
                Some(file) => format!("route = \"table\", file = {}", quote(file)),
                None => format!("fixed = {}", v3(r.pos)),
            },
            PointKind::Free => format!("free = {}", v3(r.pos)),
            PointKind::Body(b) => {
                let md = &bodies[b - 1];
                match md.kind {
                    BodyKind::Fixed => format!("fixed = {}", v3(md.place(r.pos))),
                    BodyKind::Coupled => format!(
                        "body = {}, at = {}",
                        quote(&md.name()),
                        v3(md.turned(r.pos))
                    ),
                    BodyKind::Free | BodyKind::Pinned => {
                        format!("body = {}, at = {}", quote(&md.name()), v3(r.pos))
                    }
                }
            }
        }
    };
    // A point on a free or pinned body carries its mass, volume and drag into it.
    let on_dynamic = |i: usize| match kinds[i] {
        PointKind::Body(b) => matches!(bodies[b - 1].kind, BodyKind::Free | BodyKind::Pinned),
        _ => false,
    };
    let point_note = |i: usize| -> String {
        let r = &file.points[i];
        let mut n = match kinds[i] {
            PointKind::Fixed => format!(
                "point {} ({}, line {}): held in place",
                r.id, r.attachment, r.line
            ),
            PointKind::Coupled => match opts.motions.get(&r.id) {
                Some(_) => format!(
                    "point {} ({}, line {}): driven by the motion file (t,x,y,z)",
                    r.id, r.attachment, r.line
                ),
                None => format!(
                    "point {} ({}, line {}): the vessel's point, held still (no motion file \
                     given; `cablesim convert --motion {}=FILE.csv` drives it)",
                    r.id, r.attachment, r.line, r.id
                ),
            },
            PointKind::Free => format!(
                "point {} ({}, line {}): free; its position is a first guess, relaxed to \
                 equilibrium",
                r.id, r.attachment, r.line
            ),
            PointKind::Body(b) => {
                let md = &bodies[b - 1];
                match md.kind {
                    BodyKind::Fixed => format!(
                        "point {} ({}, line {}): on fixed body {b}, held at its place {}",
                        r.id,
                        r.attachment,
                        r.line,
                        v3(md.place(r.pos))
                    ),
                    BodyKind::Coupled => format!(
                        "point {} ({}, line {}): on coupled body {b}{}",
                        r.id,
                        r.attachment,
                        r.line,
                        if md.rot == nalgebra::Matrix3::identity() {
                            String::new()
                        } else {
                            " (its body coordinates turned by the body's initial attitude, as the prescribed body is written level)".to_string()
                        }
                    ),
                    _ => format!(
                        "point {} ({}, line {}): on body {b}, at its body coordinates; its mass, \
                         volume and drag are lumped into the body",
                        r.id, r.attachment, r.line
                    ),
                }
            }
        };
        if kinds[i] != PointKind::Free
            && !on_dynamic(i)
            && (r.mass != 0.0 || r.volume != 0.0 || r.cda != 0.0)
        {
            n.push_str("; its mass, volume and CdA do not act on a held point");
        }
        n
    };
    let point_mass = |w: &mut String, i: usize| {
        let r = &file.points[i];
        if kinds[i] == PointKind::Free
            || (on_dynamic(i) && (r.mass != 0.0 || r.volume != 0.0 || r.cda != 0.0))
        {
            let _ = writeln!(w, "mass = {}  # kg", f(r.mass));
            let _ = writeln!(w, "volume = {}  # m^3, buoyancy rho V g", f(r.volume));
            let _ = writeln!(w, "drag_area = {}  # m^2, CdA", f(r.cda));
            let _ = writeln!(w, "added_mass = {}  # Ca, on the volume", f(r.ca));
        }
    };
    let fail_note = |fl: &MdFailure| -> String {
        format!(
            "FAILURE {} (line {}): {}{}",
            fl.id,
            fl.line,
            match fl.time {
                Some(t) => format!("at t >= {} s", f(t)),
                None => String::new(),
            },
            match (fl.time, fl.tension) {
                (Some(_), Some(x)) => format!(" or when an end tension reaches {} N", f(x)),
                (None, Some(x)) => format!("when an end tension reaches {} N", f(x)),
                _ => String::new(),
            }
        )
    };
    for (i, r) in file.points.iter().enumerate() {
        if uses[i] == 0 {
            let _ = writeln!(
                w,
                "\n# Point {} (line {}) has no lines: left out.",
                r.id, r.line
            );
            continue;
        }
        if !named[i] {
            continue;
        }
        let _ = writeln!(w, "\n[[points]]");
        let _ = writeln!(w, "# {}", point_note(i));
        let _ = writeln!(w, "name = \"point{}\"", r.id);
        let _ = writeln!(
            w,
            "{}",
            end_table(i)
                .replace(", file", "\nfile")
                .replace(", at", "\nat")
        );
        point_mass(w, i);
        if let Some(fl) = whole[i] {
            let _ = writeln!(
                w,
                "# {}: every line here fails together; the point leaves its support with them.",
                fail_note(fl)
            );
            for kv in fail_keys(fl).trim_start_matches(", ").split(", ") {
                let _ = writeln!(w, "{kv}");
            }
        }
    }
    for fl in &split {
        let i = fl.point - 1;
        let _ = writeln!(w, "\n[[points]]");
        let _ = writeln!(
            w,
            "# {}: lines {} leave point {} together (MoorDyn joins them at a new massless \
             free point): they are held here, at point {}'s place, until then.",
            fail_note(fl),
            fl.lines
                .iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            fl.point,
            fl.point
        );
        let _ = writeln!(w, "name = \"point{}_failure{}\"", fl.point, fl.id);
        let _ = writeln!(
            w,
            "{}",
            end_table(i)
                .replace(", file", "\nfile")
                .replace(", at", "\nat")
        );
        for kv in fail_keys(fl).trim_start_matches(", ").split(", ") {
            let _ = writeln!(w, "{kv}");
        }
    }

    for (k, l) in file.lines.iter().enumerate() {
        let (a, b) = ends[k];
        let _ = writeln!(w, "\n[[cables]]");
        let _ = writeln!(
            w,
            "# MoorDyn line {} (line {}): end A = point {a}, end B = point {b}.",
            l.id, l.line
        );
        let _ = writeln!(w, "name = \"line{}\"", l.id);
        let lt = &lts[line_lt[k]];
        let _ = writeln!(w, "line_type = {}", quote(&lt.name));
        let _ = writeln!(w, "length = {}  # m, UnstrLen", f(l.length));
        let _ = writeln!(w, "segments = {}  # NumSegs", l.segments);
        for (e, (key, id)) in [("start", a), ("end", b)].into_iter().enumerate() {
            let i = id - 1;
            if let Some(fl) = split_of(k, e) {
                let _ = writeln!(w, "{key} = {{ point = \"point{id}_failure{}\" }}", fl.id);
            } else if named[i] {
                let _ = writeln!(w, "{key} = {{ point = \"point{id}\" }}");
            } else {
                let _ = writeln!(w, "# {}", point_note(i));
                let mut extra = String::new();
                let r = &file.points[i];
                if on_dynamic(i) && (r.mass != 0.0 || r.volume != 0.0 || r.cda != 0.0) {
                    extra = format!(
                        ", mass = {}, volume = {}, drag_area = {}, added_mass = {}",
                        f(r.mass),
                        f(r.volume),
                        f(r.cda),
                        f(r.ca)
                    );
                }
                if let Some(fl) = whole[i] {
                    let _ = writeln!(w, "# {}.", fail_note(fl));
                    extra += &fail_keys(fl);
                }
                let _ = writeln!(w, "{key} = {{ {}{extra} }}", end_table(i));
            }
        }
        let _ = writeln!(
            w,
            "initial = \"catenary\"  # MoorDyn also starts from its static equilibrium"
        );
        if l.flags.contains('p') {
            let _ = writeln!(
                w,
                "output_positions = true  # LineOutputs \"{}\" asks for node positions",
                l.flags
            );
        } else if l.flags != "-" {
            let _ = writeln!(
                w,
                "# LineOutputs \"{}\": cablesim writes its own end forces and tensions for \
                 every cable (end_forces.csv, tensions.csv).",
                l.flags
            );
        }
    }
    if !file.outputs.is_empty() {
        let list: Vec<&str> = file.outputs.iter().map(|(_, s)| s.as_str()).collect();
        let _ = writeln!(
            w,
            "\n# OUTPUTS (line {}): {}. cablesim writes the end forces of every cable \
             (FairTen/AnchTen correspond to the forces at end B/A) to end_forces.csv and element \
             tensions to tensions.csv; other channels have no separate file.",
            file.outputs[0].0,
            list.join(", ")
        );
    }
    warn.sort_by_key(|x| x.line);
    Ok(Converted {
        toml: s,
        warnings: warn,
    })
}
