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
            "BODIES" => {
                return Err(err_at(
                    p,
                    first,
                    "BODIES",
                    "bodies with their own dynamics are not supported; a coupled body's \
                     fairleads can be given as Coupled points instead",
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
    for (i, t) in file.line_types.iter().enumerate() {
        let (ea, ba) = check_type(p, t, file.version, &mut warn)?;
        if types.insert(t.name.as_str(), (i, ea, ba)).is_some() {
            return Err(err_at(
                p,
                t.line,
                format!("line type \"{}\"", t.name),
                "duplicate line type name",
            ));
        }
    }

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
        let k = point_kind(p, r)?;
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
    let lowest = file
        .points
        .iter()
        .map(|r| -r.pos[2])
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
    if let (Some((ma, l)), Some((mt, _))) = (o.mu_axial, o.mu) {
        if ma != mt {
            warn.push(Warning {
                line: l,
                message: format!(
                    "MU_KA = {ma} differs from MU_KT = {mt}: cablesim's friction is isotropic \
                     on the seabed plane; MU_KT is used"
                ),
            });
        }
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
        let (c, note) = if ba < 0.0 {
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
    let _ = writeln!(
        w,
        "depth = {}  # m, seabed at z = -depth ({depth_note})",
        f(depth)
    );
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
    match o.mu {
        Some((m, l)) => {
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
        None => {
            let _ = writeln!(w, "friction = {}  # no FrictionCoefficient option", f(mu));
        }
    }
    if !o.ic.is_empty() {
        let list: Vec<String> =
            o.ic.iter()
                .map(|(n, v, l)| format!("{n} = {v} (line {l})"))
                .collect();
        let _ = writeln!(
            w,
            "\n# MoorDyn's initial-condition settings ({}) are not needed: each cable starts \
             from the elastic catenary relaxed to the static equilibrium by Newton's method \
             (initial = \"catenary\").",
            list.join(", ")
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
        let _ = writeln!(w, "ea = {}  # N", f(ea));
        let _ = writeln!(w, "# {}", lt.note);
        let _ = writeln!(w, "damping = {}  # s", f(lt.c));
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

    // Points: free points, and fixed or coupled ones that several lines share, are
    // `[[points]]`; a fixed or coupled point of one line is written at that line's end.
    // A coupled (vessel) point is a held end, still or following a motion file: the
    // scenario format has no bodies yet (`[[bodies]]` is being added), so a vessel's
    // fairleads cannot yet share one rigid body's motion; once it exists they could.
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
        }
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
                    "point {} ({}, line {}): driven by the motion file (t,x,y,z); a body \
                     attachment once cablesim has bodies",
                    r.id, r.attachment, r.line
                ),
                None => format!(
                    "point {} ({}, line {}): the vessel's point, held still (no motion file \
                     given; `cablesim convert --motion {}=FILE.csv` drives it); a body \
                     attachment once cablesim has bodies",
                    r.id, r.attachment, r.line, r.id
                ),
            },
            PointKind::Free => format!(
                "point {} ({}, line {}): free; its position is a first guess, relaxed to \
                 equilibrium",
                r.id, r.attachment, r.line
            ),
        };
        if kinds[i] != PointKind::Free && (r.mass != 0.0 || r.volume != 0.0 || r.cda != 0.0) {
            n.push_str("; its mass, volume and CdA do not act on a held point");
        }
        n
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
        let _ = writeln!(w, "{}", end_table(i).replace(", file", "\nfile"));
        if kinds[i] == PointKind::Free {
            let _ = writeln!(w, "mass = {}  # kg", f(r.mass));
            let _ = writeln!(w, "volume = {}  # m^3, buoyancy rho V g", f(r.volume));
            let _ = writeln!(w, "drag_area = {}  # m^2, CdA", f(r.cda));
            let _ = writeln!(w, "added_mass = {}  # Ca, on the volume", f(r.ca));
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
        for (key, id) in [("start", a), ("end", b)] {
            let i = id - 1;
            if named[i] {
                let _ = writeln!(w, "{key} = {{ point = \"point{id}\" }}");
            } else {
                let _ = writeln!(w, "# {}", point_note(i));
                let _ = writeln!(w, "{key} = {{ {} }}", end_table(i));
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
