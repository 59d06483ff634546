//! The `[environment.waves]` table: wave trains and kinematics options, validated into
//! a [`SeaState`]. The keys are documented in docs/src/sea_states.md.
//!
//! ```toml
//! [environment.waves]
//! stretching = "wheeler"   # or "constant" (profile held at z = 0 above it)
//! ramp = 20.0              # start-up ramp, s (default 0: none)
//! seed = 1                 # random phases (default 0)
//! cache_tolerance = 1e-3   # kinematics cache interpolation tolerance (default 1e-3)
//! depth_bands = true       # CPU path: refresh the cache per depth band (default true)
//!
//! [[environment.waves.trains]]
//! type = "jonswap"         # "jonswap" | "pierson_moskowitz" | "table" | "regular"
//!                          # | "components" | "record" (scenario::wave_inputs)
//! hs = 6.0
//! tp = 11.0
//! direction = 30.0         # degrees, direction of travel from +x towards +y
//! ```

use super::wave_checks::{self, TrainInputs};
use super::wave_inputs;
use super::{err, finite, positive};
use crate::error::Error;
use crate::sea::dispersion::wave_number;
use crate::sea::irregular::{discretise, Discretisation, DEFAULT_COMPONENTS};
use crate::sea::spectrum::{dnv_peak_factor, Spectrum, JONSWAP_GAMMA_MAX};
use crate::sea::{SeaState, Stretching, WaveComponent};
use serde::Deserialize;
use std::f64::consts::TAU;
use std::path::Path;

/// The shortest start-up ramp, s (0, no ramp, aside).
pub const MIN_RAMP: f64 = 1e-3;

/// Fewest components an irregular train may have.
pub const MIN_COMPONENTS: i64 = 10;

/// The steepest wave `H / L` linear theory is asked for before a warning (the
/// breaking limit).
pub const BREAKING_STEEPNESS: f64 = 1.0 / 7.0;

/// `[environment.waves]` as written.
#[derive(Debug, Deserialize, Default, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawWaves {
    /// `"wheeler"` (default) or `"constant"`.
    pub stretching: Option<String>,
    /// Start-up ramp duration, s.
    pub ramp: Option<f64>,
    /// Seed of the random phases (and directions).
    pub seed: Option<i64>,
    /// Relative tolerance of the kinematics cache.
    pub cache_tolerance: Option<f64>,
    /// Whether the CPU path's cache refreshes per depth band (`sea::bands`).
    pub depth_bands: Option<bool>,
    #[serde(default)]
    /// The wave trains, summed.
    pub trains: Vec<RawTrain>,
}

/// One `[[environment.waves.trains]]` entry as written.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawTrain {
    #[serde(rename = "type")]
    /// `"regular"`, `"jonswap"`, `"pierson_moskowitz"` or `"table"`.
    pub kind: String,
    /// Significant wave height, m.
    pub hs: Option<f64>,
    /// Peak period, s.
    pub tp: Option<f64>,
    /// JONSWAP peak factor (default: DNV-RP-C205's).
    pub gamma: Option<f64>,
    /// Spectrum table rows `[w, S]`, rad/s and m^2 s/rad.
    pub spectrum: Option<Vec<[f64; 2]>>,
    /// Number of components of an irregular train.
    pub components: Option<i64>,
    /// Exponent `n` of the `cos^n` directional spreading (none: long-crested).
    pub spreading: Option<f64>,
    /// Amplitude of a regular wave, m.
    pub amplitude: Option<f64>,
    /// Height (twice the amplitude) of a regular wave, m.
    pub height: Option<f64>,
    /// Period of a regular wave, s.
    pub period: Option<f64>,
    /// Phase of a regular wave, degrees.
    pub phase: Option<f64>,
    /// Direction of travel, degrees from +x towards +y.
    pub direction: Option<f64>,
    /// `"components"` and `"record"` trains: the CSV file (relative to the scenario's
    /// folder).
    pub file: Option<String>,
    /// `"components"` train: rows `[omega, amplitude, phase, direction]` (rad/s, m,
    /// degrees, degrees), instead of a file.
    pub rows: Option<Vec<[f64; 4]>>,
    /// `"record"` train: the horizontal point `[x, y]` (m) where the record was taken.
    pub reference: Option<[f64; 2]>,
    /// `"record"` train: the highest frequency kept, Hz.
    pub max_frequency: Option<f64>,
}

/// The validated sea state and the warnings it raised (each names the field).
pub fn sea_state(
    path: &Path,
    raw: Option<&RawWaves>,
    depth: f64,
    gravity: f64,
) -> Result<(SeaState, Vec<String>), Error> {
    sea_state_for_run(path, raw, depth, gravity, None)
}

/// [`sea_state`] for a run of `duration` s, when known: a `"record"` train shorter
/// than the run is accepted with a warning (the run repeats it).
pub fn sea_state_for_run(
    path: &Path,
    raw: Option<&RawWaves>,
    depth: f64,
    gravity: f64,
    duration: Option<f64>,
) -> Result<(SeaState, Vec<String>), Error> {
    let mut sea = SeaState::still(depth);
    let mut warnings = Vec::new();
    let Some(w) = raw else {
        return Ok((sea, warnings));
    };
    let p = path;
    const F: &str = "environment.waves";
    sea.stretching = match w.stretching.as_deref() {
        None | Some("wheeler") => Stretching::Wheeler,
        Some("constant") => Stretching::Constant,
        Some(o) => {
            return Err(err(
                p,
                format!("{F}.stretching"),
                format!("must be \"wheeler\" or \"constant\", got \"{o}\""),
            ))
        }
    };
    if let Some(r) = w.ramp {
        finite(p, &format!("{F}.ramp"), r)?;
        if r < 0.0 {
            return Err(err(
                p,
                format!("{F}.ramp"),
                format!("must not be negative, got {r}"),
            ));
        }
        // The ramp's rate (in the accelerations) goes as 1 / ramp: a ramp far shorter
        // than any step overflows it.
        if r > 0.0 && r < MIN_RAMP {
            return Err(err(
                p,
                format!("{F}.ramp"),
                format!("{r:e} s is shorter than {MIN_RAMP} s: use 0 for no ramp"),
            ));
        }
        sea.ramp_duration = r;
    }
    if let Some(t) = w.cache_tolerance {
        let t = positive(p, &format!("{F}.cache_tolerance"), t)?;
        if t >= 1.0 {
            return Err(err(
                p,
                format!("{F}.cache_tolerance"),
                format!("is a relative error, must be below 1, got {t}"),
            ));
        }
        sea.cache_tolerance = t;
    }
    let seed = match w.seed {
        None => 0,
        Some(s) if s >= 0 => s as u64,
        Some(s) => {
            return Err(err(
                p,
                format!("{F}.seed"),
                format!("must not be negative, got {s}"),
            ))
        }
    };
    for (i, t) in w.trains.iter().enumerate() {
        let f = |k: &str| format!("{F}.trains[{i}].{k}");
        let direction = match t.direction {
            Some(d) => finite(p, &f("direction"), d)?.to_radians(),
            None => 0.0,
        };
        let allowed: &[&str] = match t.kind.as_str() {
            "regular" => &["amplitude", "height", "period", "phase", "direction"],
            "jonswap" => &["hs", "tp", "gamma", "components", "spreading", "direction"],
            "pierson_moskowitz" => &["hs", "tp", "components", "spreading", "direction"],
            "table" => &["spectrum", "components", "spreading", "direction"],
            "components" => &["file", "rows", "direction"],
            "record" => &["file", "reference", "max_frequency", "direction"],
            o => {
                return Err(err(
                    p,
                    f("type"),
                    format!(
                        "unknown wave train type \"{o}\": one of \"regular\", \"jonswap\", \
                         \"pierson_moskowitz\", \"table\", \"components\", \"record\""
                    ),
                ))
            }
        };
        for (key, given) in [
            ("hs", t.hs.is_some()),
            ("tp", t.tp.is_some()),
            ("gamma", t.gamma.is_some()),
            ("spectrum", t.spectrum.is_some()),
            ("components", t.components.is_some()),
            ("spreading", t.spreading.is_some()),
            ("amplitude", t.amplitude.is_some()),
            ("height", t.height.is_some()),
            ("period", t.period.is_some()),
            ("phase", t.phase.is_some()),
            ("file", t.file.is_some()),
            ("rows", t.rows.is_some()),
            ("reference", t.reference.is_some()),
            ("max_frequency", t.max_frequency.is_some()),
        ] {
            if given && !allowed.contains(&key) {
                return Err(err(
                    p,
                    f(key),
                    format!("is not a key of a \"{}\" train", t.kind),
                ));
            }
        }
        let required = |key: &str, v: Option<f64>| -> Result<f64, Error> {
            match v {
                Some(x) => positive(p, &f(key), x),
                None => Err(err(
                    p,
                    f(key),
                    format!("is required for a \"{}\" train", t.kind),
                )),
            }
        };
        let tolerance = sea.cache_tolerance;
        let given = match t.kind.as_str() {
            "components" => Some(wave_inputs::components(
                p,
                &f,
                t,
                t.direction.map(|_| direction),
                depth,
                gravity,
                tolerance,
            )?),
            "record" => Some(wave_inputs::record(
                p, &f, t, direction, depth, gravity, tolerance, duration,
            )?),
            _ => None,
        };
        if let Some((components, w)) = given {
            warnings.extend(w);
            sea.components.extend(components);
            continue;
        }
        if t.kind == "regular" {
            let amplitude = match (t.amplitude, t.height) {
                (Some(a), None) => positive(p, &f("amplitude"), a)?,
                (None, Some(h)) => positive(p, &f("height"), h)? / 2.0,
                (Some(_), Some(_)) => {
                    return Err(err(p, f("height"), "give amplitude or height, not both"))
                }
                (None, None) => {
                    return Err(err(
                        p,
                        f("amplitude"),
                        "a regular train needs amplitude or height",
                    ))
                }
            };
            let period = required("period", t.period)?;
            let phase = match t.phase {
                Some(x) => finite(p, &f("phase"), x)?.to_radians(),
                None => 0.0,
            };
            let omega = TAU / period;
            let k = wave_number(omega, depth, gravity);
            let steep = 2.0 * amplitude * k / TAU;
            if steep > BREAKING_STEEPNESS {
                warnings.push(format!(
                    "{}: {}: H/L = {steep:.3} is steeper than the breaking limit 1/7; linear \
                     theory does not describe such a wave",
                    p.display(),
                    f("height")
                ));
            }
            let component = WaveComponent {
                amplitude,
                omega,
                k,
                direction,
                phase,
            };
            let key = if t.height.is_some() {
                "height"
            } else {
                "amplitude"
            };
            let inputs = TrainInputs {
                height: (
                    &f(key),
                    amplitude * if t.height.is_some() { 2.0 } else { 1.0 },
                ),
                period: (&f("period"), period),
            };
            let tolerance = sea.cache_tolerance;
            wave_checks::train(p, &inputs, &[component], depth, tolerance)?;
            sea.components.push(component);
            continue;
        }
        let spectrum = match t.kind.as_str() {
            "table" => table(p, &f("spectrum"), t.spectrum.as_deref())?,
            kind => {
                let hs = required("hs", t.hs)?;
                let tp = required("tp", t.tp)?;
                let steep = hs * wave_number(TAU / tp, depth, gravity) / TAU;
                if steep > BREAKING_STEEPNESS {
                    warnings.push(format!(
                        "{}: {}: Hs/L at the peak period = {steep:.3} is steeper than the \
                         breaking limit 1/7",
                        p.display(),
                        f("hs")
                    ));
                }
                if kind == "jonswap" {
                    let gamma = match t.gamma {
                        Some(g) => {
                            let g = positive(p, &f("gamma"), g)?;
                            if g < 1.0 {
                                return Err(err(
                                    p,
                                    f("gamma"),
                                    format!("the peak factor must be at least 1, got {g}"),
                                ));
                            }
                            jonswap_gamma_in_range(p, &f("gamma"), g)?
                        }
                        None => dnv_peak_factor(hs, tp),
                    };
                    Spectrum::Jonswap { hs, tp, gamma }
                } else {
                    Spectrum::PiersonMoskowitz { hs, tp }
                }
            }
        };
        let components = match t.components {
            None => DEFAULT_COMPONENTS,
            Some(n) if n >= MIN_COMPONENTS => n as usize,
            Some(n) => {
                return Err(err(
                    p,
                    f("components"),
                    format!(
                        "an irregular train needs at least {MIN_COMPONENTS} components (default \
                         {DEFAULT_COMPONENTS}), got {n}"
                    ),
                ))
            }
        };
        let spreading = match t.spreading {
            Some(s) => Some(positive(p, &f("spreading"), s)?),
            None => None,
        };
        let d = Discretisation {
            components,
            direction,
            spreading,
            seed,
            stream: i as u64,
        };
        let components = discretise(&spectrum, &d, depth, gravity);
        let (hf, tf) = match &spectrum {
            Spectrum::Table { .. } => (f("spectrum"), f("spectrum")),
            _ => (f("hs"), f("tp")),
        };
        let inputs = TrainInputs {
            height: (&hf, t.hs.unwrap_or(1.0)),
            period: (&tf, t.tp.unwrap_or(1.0)),
        };
        let tolerance = sea.cache_tolerance;
        wave_checks::train(p, &inputs, &components, depth, tolerance)?;
        sea.components.extend(components);
    }
    Ok((sea, warnings))
}

/// Validates a spectrum table: at least three points, finite, frequencies positive and
/// strictly increasing, densities non-negative and not all zero, and no gap: no
/// interval wider than ten times the table's median interval (the spectrum would be a
/// straight line across it).
fn table(p: &Path, field: &str, rows: Option<&[[f64; 2]]>) -> Result<Spectrum, Error> {
    let Some(rows) = rows else {
        return Err(err(
            p,
            field,
            "a \"table\" train needs spectrum = [[w, S], ...] (rad/s, m^2 s/rad)",
        ));
    };
    if rows.len() < 3 {
        return Err(err(
            p,
            field,
            format!("needs at least 3 points, got {}", rows.len()),
        ));
    }
    for (j, r) in rows.iter().enumerate() {
        finite(p, &format!("{field}[{j}][0]"), r[0])?;
        finite(p, &format!("{field}[{j}][1]"), r[1])?;
        if r[0] <= 0.0 {
            return Err(err(
                p,
                format!("{field}[{j}][0]"),
                format!("frequency must be positive, got {}", r[0]),
            ));
        }
        if r[1] < 0.0 {
            return Err(err(
                p,
                format!("{field}[{j}][1]"),
                format!("spectral density must not be negative, got {}", r[1]),
            ));
        }
        if j > 0 && r[0] <= rows[j - 1][0] {
            return Err(err(
                p,
                format!("{field}[{j}][0]"),
                format!(
                    "frequencies must increase: {} follows {} (sort the table, remove duplicates)",
                    r[0],
                    rows[j - 1][0]
                ),
            ));
        }
    }
    let mut gaps: Vec<f64> = rows.windows(2).map(|w| w[1][0] - w[0][0]).collect();
    let widths = gaps.clone();
    gaps.sort_by(f64::total_cmp);
    let median = gaps[gaps.len() / 2];
    if let Some(j) = widths.iter().position(|&g| g > 10.0 * median) {
        return Err(err(
            p,
            format!("{field}[{}]", j + 1),
            format!(
                "gap in the table: {} to {} rad/s is more than ten times the median spacing \
                 {median} rad/s; add points (the spectrum would be a straight line across it)",
                rows[j][0],
                rows[j + 1][0]
            ),
        ));
    }
    if rows.iter().all(|r| r[1] == 0.0) {
        return Err(err(p, field, "every spectral density is zero"));
    }
    Ok(Spectrum::Table {
        omega: rows.iter().map(|r| r[0]).collect(),
        density: rows.iter().map(|r| r[1]).collect(),
    })
}

/// Refuses a JONSWAP peak factor above [`JONSWAP_GAMMA_MAX`] (why: there).
pub(crate) fn jonswap_gamma_in_range(p: &Path, field: &str, g: f64) -> Result<f64, Error> {
    if g > JONSWAP_GAMMA_MAX {
        return Err(err(
            p,
            field,
            format!(
                "a JONSWAP peak factor of at most {JONSWAP_GAMMA_MAX} (the range of \
                 DNV-RP-C205's form), got {}: above it the form's normalisation no longer \
                 keeps m0 = Hs^2/16 (7% low at 10, negative above 32.6); give a peakier \
                 sea as a spectrum table",
                super::show(g)
            ),
        ));
    }
    Ok(g)
}
