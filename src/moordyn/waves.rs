//! MoorDyn's wave inputs (MoorDyn-C 2.x, `source/Waves.cpp` and `source/Waves/`), read
//! into cablesim wave components written in the scenario as a `"components"` train's
//! `rows` (`[omega, amplitude, phase, direction]`, rad/s, m, degrees, degrees):
//!
//! - `WaveKin` 7: `wave_frequencies.txt` in the model file's folder, rows
//!   `omega re im [beta]` (rad/s, the complex amplitude in m, the direction in rad),
//!   the first at 0 rad/s. MoorDyn sums `|a| sin(w t - k (x cos b + y sin b) + arg a)`
//!   at the nodes (`SpectrumKin`); cablesim's `A cos(k (...) - w t + phi)` is the same
//!   wave with `A = |a|`, `phi = 90 deg - arg a`. A row at 0 rad/s is a constant rise
//!   of MoorDyn's surface by `im`, not a wave: it is left out (a warning when not 0).
//! - `WaveKin` 3: `wave_elevation.txt`, rows `t eta` (s, m) measured at the origin.
//!   MoorDyn resamples it linearly at `i dtWave` for `i = 0 .. floor(t_last / dtWave)`
//!   (the first value held before the first time), drops the last sample when their
//!   number `N` is odd, takes its real FFT and keeps the bins of `w = i dw <= pi`
//!   rad/s (`dw = pi / (dtWave N / 2)`: it cuts everything above 0.5 Hz), travelling
//!   along +x. The same resampling and cut here; the FFT's bins become components as
//!   in `sea::measured` (the mean, MoorDyn's bin 0, is left out: a warning when not 0).
//!   MoorDyn evaluates them on the grid of `water_grid.txt` and interpolates linearly
//!   in space and time; cablesim evaluates them at the nodes (the grid is not read).

use super::convert::Warning;
use super::err_at;
use crate::error::Error;
use crate::sea::measured::decompose;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::path::{Path, PathBuf};

/// The fewest resampled samples a `wave_elevation.txt` may give.
pub const MIN_SAMPLES: usize = crate::scenario::wave_inputs::MIN_RECORD_SAMPLES;

/// MoorDyn's default `dtWave`, s.
pub const DEFAULT_DT_WAVE: f64 = 0.25;

/// The waves of a MoorDyn file, ready to write.
pub(super) struct MdWaves {
    /// `WaveKin` (3 or 7) and the option's line.
    pub(super) mode: (u8, usize),
    /// The file read.
    pub(super) file: String,
    /// Rows `[omega, amplitude, phase, direction]`: rad/s, m, degrees, degrees.
    pub(super) rows: Vec<[f64; 4]>,
    /// What the conversion did, as comment lines.
    pub(super) notes: Vec<String>,
}

/// The lines of `name` in the model file's folder, each with its 1-based number, the
/// text before any `#`, blank lines left out; `line` is the `WaveKin` option's.
fn lines_of(p: &Path, line: usize, name: &str) -> Result<(PathBuf, Vec<(usize, String)>), Error> {
    let file = p.parent().unwrap_or(Path::new(".")).join(name);
    let text = crate::input::read_text(&file).map_err(|e| {
        err_at(
            p,
            line,
            "option WaveKin",
            format!("{}: {e}", file.display()),
        )
    })?;
    let rows = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.split('#').next().unwrap_or("").trim().to_string()))
        .filter(|(_, l)| !l.is_empty())
        .collect();
    Ok((file, rows))
}

/// The numbers of a row; `names` names the columns, the first `need` required.
fn numbers(
    file: &Path,
    line: usize,
    text: &str,
    names: &[&str],
    need: usize,
) -> Result<Vec<f64>, Error> {
    let words: Vec<&str> = text.split_whitespace().collect();
    if words.len() < need {
        return Err(err_at(
            file,
            line,
            "row",
            format!(
                "needs {} values ({}), found {}",
                need,
                names[..need].join(", "),
                words.len()
            ),
        ));
    }
    words
        .iter()
        .take(names.len())
        .enumerate()
        .map(|(c, w)| match w.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(err_at(
                file,
                line,
                names[c],
                format!("must be a finite number, got \"{w}\""),
            )),
        })
        .collect()
}

/// `WaveKin` 7: the components of `wave_frequencies.txt` (module doc).
pub(super) fn frequencies(
    p: &Path,
    line: usize,
    warn: &mut Vec<Warning>,
) -> Result<MdWaves, Error> {
    let (file, lines) = lines_of(p, line, "wave_frequencies.txt")?;
    let shown = file.display().to_string();
    let names = ["omega", "real part", "imaginary part", "direction"];
    if lines.len() < 2 {
        return Err(err_at(
            &file,
            0,
            "rows",
            format!(
                "{} row(s): MoorDyn needs at least 2 (the first at 0 rad/s)",
                lines.len()
            ),
        ));
    }
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for (k, (l, text)) in lines.iter().enumerate() {
        let v = numbers(&file, *l, text, &names, 3)?;
        let (omega, re, im) = (v[0], v[1], v[2]);
        let beta = v.get(3).copied().unwrap_or(0.0);
        if beta.abs() > TAU {
            return Err(err_at(
                &file,
                *l,
                "direction",
                format!("{beta} is beyond +-2 pi: MoorDyn takes the direction in radians"),
            ));
        }
        if k == 0 && omega != 0.0 {
            return Err(err_at(
                &file,
                *l,
                "omega",
                format!("MoorDyn requires the first row at 0 rad/s, got {omega}"),
            ));
        }
        if omega < 0.0 {
            return Err(err_at(
                &file,
                *l,
                "omega",
                format!("frequency must not be negative, got {omega}"),
            ));
        }
        if omega == 0.0 {
            if im != 0.0 {
                warn.push(Warning {
                    line,
                    message: format!(
                        "{shown} line {l}: the row at 0 rad/s raises MoorDyn's surface by \
                         {im} m everywhere (its imaginary part); cablesim's mean level stays \
                         at z = 0"
                    ),
                });
            }
            notes.push(format!(
                "line {l}: the row at 0 rad/s is not a wave, left out"
            ));
            continue;
        }
        let amplitude = re.hypot(im);
        let phase = (FRAC_PI_2 - im.atan2(re)).rem_euclid(TAU);
        rows.push([omega, amplitude, phase.to_degrees(), beta.to_degrees()]);
    }
    Ok(MdWaves {
        mode: (7, line),
        file: shown,
        rows,
        notes,
    })
}

/// MoorDyn's resampling of a record `(t, eta)` at `i dt` (module doc): the samples,
/// an even number of them.
pub fn resample(times: &[f64], eta: &[f64], dt: f64) -> Vec<f64> {
    let last = times[times.len() - 1];
    let mut nt = (last / dt).floor().max(0.0) as usize + 1;
    if nt % 2 == 1 {
        nt -= 1;
    }
    let mut j = 1;
    (0..nt)
        .map(|i| {
            let t = i as f64 * dt;
            if t <= times[0] {
                return eta[0];
            }
            if t >= last {
                return eta[eta.len() - 1];
            }
            while times[j] < t {
                j += 1;
            }
            let f = (t - times[j - 1]) / (times[j] - times[j - 1]);
            eta[j - 1] + f * (eta[j] - eta[j - 1])
        })
        .collect()
}

/// The components MoorDyn takes from a resampled record `eta` at step `dt`: the FFT's
/// bins `i >= 1` with `w = i pi / (dt N / 2) <= pi` rad/s, as rows (module doc), and
/// the record's mean.
pub fn record_rows(eta: &[f64], dt: f64) -> (Vec<[f64; 4]>, f64) {
    let n = eta.len();
    let d = decompose(eta, dt);
    let dw = PI / (dt * (n / 2) as f64);
    let rows = d
        .harmonics
        .iter()
        .enumerate()
        .map(|(k, h)| ((k + 1) as f64 * dw, h))
        .filter(|(w, _)| *w <= PI)
        .map(|(w, h)| [w, h.amplitude, (-h.phase).rem_euclid(TAU).to_degrees(), 0.0])
        .collect();
    (rows, d.mean)
}

/// `WaveKin` 3: the components of `wave_elevation.txt` at MoorDyn's `dtWave`
/// (`dt_wave`: the value and its line, 0 for the default) (module doc).
pub(super) fn elevation(
    p: &Path,
    line: usize,
    dt_wave: (f64, usize),
    warn: &mut Vec<Warning>,
) -> Result<MdWaves, Error> {
    let (file, lines) = lines_of(p, line, "wave_elevation.txt")?;
    let shown = file.display().to_string();
    let (dt, dt_line) = dt_wave;
    if !(dt > 0.0) {
        return Err(err_at(
            p,
            dt_line,
            "option dtWave",
            format!("must be positive, got {dt}"),
        ));
    }
    let mut times = Vec::with_capacity(lines.len());
    let mut eta = Vec::with_capacity(lines.len());
    for (l, text) in &lines {
        let v = numbers(&file, *l, text, &["t", "eta"], 2)?;
        if let Some(&prev) = times.last() {
            if v[0] <= prev {
                return Err(err_at(
                    &file,
                    *l,
                    "t",
                    format!("time {} does not increase (previous {prev})", v[0]),
                ));
            }
        }
        times.push(v[0]);
        eta.push(v[1]);
    }
    if times.is_empty() {
        return Err(err_at(&file, 0, "rows", "no rows"));
    }
    let samples = resample(&times, &eta, dt);
    if samples.len() < MIN_SAMPLES {
        let at = if dt_line == 0 {
            "MoorDyn's default dtWave".to_string()
        } else {
            format!("dtWave, line {dt_line} of {}", p.display())
        };
        return Err(err_at(
            &file,
            0,
            "rows",
            format!(
                "the record ends at t = {} s: resampled every {dt} s ({at}) from t = 0 it \
                 gives {} samples, fewer than {MIN_SAMPLES}",
                times[times.len() - 1],
                samples.len()
            ),
        ));
    }
    let (rows, mean) = record_rows(&samples, dt);
    let scale = samples.iter().map(|e| e.abs()).fold(0.0f64, f64::max);
    if mean.abs() > 1e-9 * scale {
        warn.push(Warning {
            line,
            message: format!(
                "{shown}: the resampled record's mean {mean:.6e} m is a constant rise of \
                 MoorDyn's surface; cablesim's mean level stays at z = 0"
            ),
        });
    }
    let n = samples.len();
    let notes = vec![
        format!(
            "{} samples every {dt} s from t = 0 (dtWave{}), period {} s; {} of their {} \
             FFT bins at or below pi rad/s kept, as MoorDyn keeps them",
            n,
            if dt_line == 0 {
                ", MoorDyn's default".to_string()
            } else {
                format!(", line {dt_line}")
            },
            n as f64 * dt,
            rows.len(),
            n / 2
        ),
        "water_grid.txt is not read: the components are evaluated at the nodes (MoorDyn \
         interpolates them on that grid, linearly in x, y, z and t)"
            .to_string(),
    ];
    Ok(MdWaves {
        mode: (3, line),
        file: shown,
        rows,
        notes,
    })
}
