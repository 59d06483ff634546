//! The options section of a MoorDyn file read into the values cablesim uses (with the
//! line each came from, for comments and warnings), and MoorDyn's steady current
//! profile file (its wave files: `moordyn::waves`).

use super::err_at;
use super::parse::MoorDynFile;
use super::Warning;
use crate::error::Error;
use std::path::Path;

/// The options cablesim uses, with the line each came from (0: MoorDyn's default).
pub(super) struct Opts {
    pub(super) g: (f64, usize),
    pub(super) rho: (f64, usize),
    pub(super) depth: Option<(f64, usize)>,
    pub(super) kbot: (f64, usize),
    pub(super) cbot: (f64, usize),
    /// `FrictionCoefficient` (MoorDyn-C): isotropic.
    pub(super) mu: Option<(f64, usize)>,
    /// `MU_KT` (MoorDyn-F): transverse, default 0.
    pub(super) mu_transverse: Option<(f64, usize)>,
    /// `MU_KA` (MoorDyn-F): axial, default 0.
    pub(super) mu_axial: Option<(f64, usize)>,
    /// `SeafloorFile`: the grid file found (absolute), its value as written, its line.
    pub(super) seafloor: Option<(std::path::PathBuf, String, usize)>,
    pub(super) fric_damp: Option<(f64, usize)>,
    pub(super) dt_out: Option<(f64, usize)>,
    pub(super) dt_m: Option<(f64, usize)>,
    pub(super) cfl: Option<(f64, usize)>,
    /// `Currents` 1 or 3 (a steady profile in `current_profile.txt`), and its line.
    pub(super) currents: Option<(u8, usize)>,
    /// `WaveKin` 3 or 7 (`moordyn::waves`), and its line.
    pub(super) wave_kin: Option<(u8, usize)>,
    /// `dtWave`, s, and its line (for `WaveKin` 3).
    pub(super) dt_wave: Option<(f64, usize)>,
    pub(super) scheme: Option<(String, usize)>,
    pub(super) ic: Vec<(String, String, usize)>,
    pub(super) ignored: Vec<(String, usize)>,
}

pub(super) fn opt_num(p: &Path, line: usize, name: &str, value: &str) -> Result<f64, Error> {
    match value.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(err_at(
            p,
            line,
            format!("option {name}"),
            format!("must be a number, got \"{value}\""),
        )),
    }
}

pub(super) fn read_options(
    file: &MoorDynFile,
    p: &Path,
    warn: &mut Vec<Warning>,
) -> Result<Opts, Error> {
    // Defaults: MoorDyn-C's (MoorDyn2.cpp sets g = 9.80665 and rho = 1025, although
    // its v2 documentation says g = 9.81; v1 documents 9.80665).
    let g0 = 9.80665;
    let mut o = Opts {
        g: (g0, 0),
        rho: (1025.0, 0),
        depth: None,
        kbot: (3.0e6, 0),
        cbot: (3.0e5, 0),
        mu: None,
        mu_transverse: None,
        mu_axial: None,
        seafloor: None,
        fric_damp: None,
        dt_out: None,
        dt_m: None,
        cfl: None,
        currents: None,
        wave_kin: None,
        dt_wave: None,
        scheme: None,
        ic: Vec::new(),
        ignored: Vec::new(),
    };
    for r in &file.options {
        let l = r.line;
        let name = r.name.to_lowercase();
        let val = r.value.as_str();
        let n = || opt_num(p, l, &r.name, val);
        // MoorDyn-F files may say DEFAULT (take OpenFAST's value); standalone, the
        // default is MoorDyn-C's.
        if val.eq_ignore_ascii_case("default") {
            warn.push(Warning {
                line: l,
                message: format!(
                    "{} = DEFAULT takes OpenFAST's value in MoorDyn-F; MoorDyn-C's default \
                     is used",
                    r.name
                ),
            });
            continue;
        }
        match name.as_str() {
            "dtm" | "dt" => o.dt_m = Some((n()?, l)),
            "cfl" => o.cfl = Some((n()?, l)),
            "tscheme" => o.scheme = Some((val.to_string(), l)),
            "g" | "gravity" => o.g = (n()?, l),
            "rho" | "rhow" | "wtrdnsty" => o.rho = (n()?, l),
            "wtrdpth" | "depth" => match val.parse::<f64>() {
                Ok(x) if x.is_finite() => o.depth = Some((x, l)),
                _ => {
                    return Err(err_at(
                        p,
                        l,
                        format!("option {}", r.name),
                        format!(
                            "\"{val}\" is not a depth in metres: a bathymetry grid is given \
                             by the option SeafloorFile"
                        ),
                    ))
                }
            },
            "kbot" | "kb" => o.kbot = (n()?, l),
            "cbot" | "cb" => o.cbot = (n()?, l),
            "frictioncoefficient" => o.mu = Some((n()?, l)),
            "mu_kt" => o.mu_transverse = Some((n()?, l)),
            "mu_ka" => o.mu_axial = Some((n()?, l)),
            "fricdamp" | "cv" => o.fric_damp = Some((n()?, l)),
            "statdynfricscale" | "mc" => {
                let x = n()?;
                if x != 1.0 {
                    warn.push(Warning {
                        line: l,
                        message: format!(
                            "{} = {x}: cablesim has one friction coefficient for sliding \
                             and sticking (ratio 1)",
                            r.name
                        ),
                    });
                }
            }
            "dtout" => o.dt_out = Some((n()?, l)),
            "dtic" | "icdt" | "tmaxic" | "ictmax" | "cdscaleic" | "icdfac" | "threshic"
            | "icthresh" | "icgendynamic" | "gendynamicic" | "fileic" | "icfile" => {
                o.ic.push((r.name.clone(), val.to_string(), l))
            }
            "wavekin" => {
                let mode = n()?;
                if mode == 3.0 || mode == 7.0 {
                    o.wave_kin = Some((mode as u8, l));
                } else if mode != 0.0 {
                    return Err(err_at(
                        p,
                        l,
                        format!("option {}", r.name),
                        format!(
                            "WaveKin = {val}: only 3 (an elevation record, \
                             wave_elevation.txt) and 7 (wave components, \
                             wave_frequencies.txt) convert; MoorDyn's external waves (1) \
                             and its FFT grid of a frequency file (2) are not read"
                        ),
                    ));
                }
            }
            "dtwave" => o.dt_wave = Some((n()?, l)),
            "currents" => {
                let mode = n()?;
                if mode == 1.0 || mode == 3.0 {
                    o.currents = Some((mode as u8, l));
                } else if mode != 0.0 {
                    return Err(err_at(
                        p,
                        l,
                        format!("option {}", r.name),
                        format!(
                            "Currents = {val}: only steady profiles (1 or 3, read from \
                             current_profile.txt) convert; MoorDyn's dynamic and 4D current \
                             grids are not read"
                        ),
                    ));
                }
            }
            "waterkin" => {
                if !val.eq_ignore_ascii_case("null") && !val.is_empty() && val != "\"\"" {
                    return Err(err_at(
                        p,
                        l,
                        format!("option {}", r.name),
                        format!("water kinematics file \"{val}\" is not read; only still water converts"),
                    ));
                }
            }
            "seafloorfile" => {
                o.seafloor = Some((seafloor_path(p, l, &r.name, val)?, val.to_string(), l))
            }
            "unifycurrentgrid" | "writelog" | "writeunits" | "disableoutput" | "disableouttime"
            | "outswitch" | "echo" | "inertialf" | "inertialf_rampt" => {
                o.ignored.push((r.name.clone(), l))
            }
            _ => warn.push(Warning {
                line: l,
                message: format!("unknown option \"{}\" ignored", r.name),
            }),
        }
    }
    Ok(o)
}

/// MoorDyn's steady current profile: `current_profile.txt` in the model file's folder,
/// three header lines, then rows `z ux [uy [uz]]` (m, m/s; missing components are 0),
/// interpolated linearly in z and held beyond the ends, as cablesim's
/// `current_profile` is. Returns the rows sorted by z, and the file's path.
pub(super) fn read_current_profile(
    p: &Path,
    line: usize,
) -> Result<(Vec<[f64; 4]>, String), Error> {
    let file = p
        .parent()
        .unwrap_or(Path::new("."))
        .join("current_profile.txt");
    let text = crate::input::read_text(&file).map_err(|e| {
        err_at(
            p,
            line,
            "option Currents",
            format!("{}: {e}", file.display()),
        )
    })?;
    let mut rows: Vec<([f64; 4], usize)> = Vec::new();
    for (i, l) in text.lines().enumerate().skip(3) {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.is_empty() {
            continue;
        }
        let mut r = [0.0; 4];
        if f.len() < 2 {
            return Err(err_at(&file, i + 1, "row", "needs at least z and ux"));
        }
        for (k, x) in f.iter().take(4).enumerate() {
            r[k] = match x.parse::<f64>() {
                Ok(v) if v.is_finite() => v,
                _ => {
                    return Err(err_at(
                        &file,
                        i + 1,
                        ["z", "ux", "uy", "uz"][k],
                        format!("must be a number, got \"{x}\""),
                    ))
                }
            };
        }
        rows.push((r, i + 1));
    }
    if rows.is_empty() {
        return Err(err_at(
            &file,
            0,
            "rows",
            "no rows after the three header lines",
        ));
    }
    rows.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]));
    for w in rows.windows(2) {
        if w[0].0[0] == w[1].0[0] {
            return Err(err_at(
                &file,
                w[1].1,
                "z",
                format!("depth {} is given twice", w[1].0[0]),
            ));
        }
    }
    Ok((
        rows.into_iter().map(|r| r.0).collect(),
        file.display().to_string(),
    ))
}

/// Where a `SeafloorFile` value points: MoorDyn opens it from its working directory,
/// which for its own test files is a folder above the input file's; so the file is
/// looked for from the input file's folder and each folder above it, then from the
/// working directory. The grid is read (and checked) by the scenario that names it.
fn seafloor_path(
    p: &Path,
    line: usize,
    name: &str,
    val: &str,
) -> Result<std::path::PathBuf, Error> {
    let val = val.trim_matches('"');
    let rel = Path::new(val);
    let mut tried = Vec::new();
    let mut dir = p.parent();
    while let Some(d) = dir {
        let c = d.join(rel);
        if c.is_file() {
            return Ok(c.canonicalize().unwrap_or(c));
        }
        tried.push(c.display().to_string());
        dir = d.parent();
    }
    if rel.is_file() {
        return Ok(rel.canonicalize().unwrap_or_else(|_| rel.to_path_buf()));
    }
    Err(err_at(
        p,
        line,
        format!("option {name}"),
        format!(
            "the seabed file \"{val}\" is not found (looked for {} and in the working directory)",
            tried.join(", ")
        ),
    ))
}
