//! `[[environment.waves.trains]]` given as data rather than a spectrum: `"components"`
//! (a table of wave components, in a CSV file or as `rows` in the scenario) and
//! `"record"` (a measured wave-elevation record at a reference point, decomposed into
//! components by a real FFT: `sea::measured`). Both become wave components as a
//! spectrum's do, so both paths run them unchanged. Keys and formats:
//! docs/src/sea_states.md, "Measured and tabulated seas".
//!
//! Every problem is an error naming the scenario, the train's key and, for a file, the
//! file, its line and its column (for `rows`, the row and column in the key).

use super::route_file::read_numbers_one_of;
use super::wave_checks::{self, TrainInputs};
use super::waves::{RawTrain, BREAKING_STEEPNESS};
use super::{err, finite, positive, show};
use crate::error::Error;
use crate::sea::dispersion::wave_number;
use crate::sea::measured::{decompose, place};
use crate::sea::WaveComponent;
use std::f64::consts::TAU;
use std::path::Path;

/// The fewest samples an elevation record may have (it gives `N / 2` components).
pub const MIN_RECORD_SAMPLES: usize = 8;

/// How far a record's sample may be from its place on the even grid
/// `t_0 + n dt` (`dt` the record's mean step), as a fraction of `dt`. A timing error
/// `e` shifts a component's phase by `w e`: at most `pi e / dt` at the Nyquist
/// frequency, 0.03 rad at this tolerance.
pub const SAMPLING_TOLERANCE: f64 = 0.01;

/// Above this many components a train is accepted with a warning: every refresh of
/// the kinematics cache sums all of them at every node.
pub const MANY_COMPONENTS: usize = 4096;

/// The accepted headers of a component table: frequency in Hz (`frequency`) or rad/s
/// (`omega`), with or without a `direction` column.
const TABLE_HEADERS: [&[&str]; 4] = [
    &["frequency", "amplitude", "phase", "direction"],
    &["omega", "amplitude", "phase", "direction"],
    &["frequency", "amplitude", "phase"],
    &["omega", "amplitude", "phase"],
];

/// Maps an error's message with `prefix` (where in a file or table it arose).
fn at(e: Error, prefix: &str) -> Error {
    match e {
        Error::Scenario {
            path,
            field,
            message,
        } => Error::Scenario {
            path,
            field,
            message: format!("{prefix}: {message}"),
        },
        other => other,
    }
}

/// The steepest component (`H / L = 2 A k / 2 pi`) beyond the breaking limit, as a
/// warning naming where it is, with how many others are.
fn steepness_warning(p: &Path, field: &str, comps: &[(String, WaveComponent)]) -> Option<String> {
    let steep: Vec<(&String, f64)> = comps
        .iter()
        .map(|(w, c)| (w, 2.0 * c.amplitude * c.k / TAU))
        .filter(|&(_, s)| s > BREAKING_STEEPNESS)
        .collect();
    let (where_, s) = steep.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(format!(
        "{}: {field}: {where_}: H/L = {s:.3} is steeper than the breaking limit 1/7 ({} \
         component(s) are); linear theory does not describe such a wave",
        p.display(),
        steep.len()
    ))
}

/// A warning when a train has more than [`MANY_COMPONENTS`] components.
fn many_warning(p: &Path, field: &str, n: usize, hint: &str) -> Option<String> {
    (n > MANY_COMPONENTS).then(|| {
        format!(
            "{}: {field}: {n} wave components: every refresh of the kinematics cache sums \
             them all at every node{hint}",
            p.display()
        )
    })
}

/// A `"components"` train: its components (in the table's order) and warnings.
/// `f` names a key of the train; `direction` is the train's `direction` key (rad), if
/// given.
pub(super) fn components(
    p: &Path,
    f: &dyn Fn(&str) -> String,
    t: &RawTrain,
    direction: Option<f64>,
    depth: f64,
    gravity: f64,
    tolerance: f64,
) -> Result<(Vec<WaveComponent>, Vec<String>), Error> {
    // Each row: where it is (for messages), the field errors name, the values
    // (frequency in rad/s, amplitude, phase and direction in degrees, the direction
    // None where the table has no such column), and the error for column `c`.
    struct Row {
        place: String,
        field: String,
        values: [f64; 4],
        /// The first column as written (Hz or rad/s), for messages.
        written: f64,
        has_direction: bool,
    }
    let (rows, col_names, source): (Vec<Row>, [&str; 4], String) = match (&t.file, &t.rows) {
        (Some(_), Some(_)) => {
            return Err(err(
                p,
                f("rows"),
                "give the components in `file` or in `rows`, not both",
            ))
        }
        (None, None) => {
            return Err(err(
                p,
                f("file"),
                "a \"components\" train needs `file` (a CSV table of frequency or omega, \
                 amplitude, phase[, direction]) or `rows` ([omega, amplitude, phase, \
                 direction] each)",
            ))
        }
        (Some(file), None) => {
            let field = f("file");
            let path = p.parent().unwrap_or(Path::new(".")).join(file);
            let shown = path.display().to_string();
            let (which, read) =
                read_numbers_one_of(&path, p, &field, "wave component", &TABLE_HEADERS)?;
            let hz = which % 2 == 0;
            let has_direction = which < 2;
            if has_direction && direction.is_some() {
                return Err(err(
                    p,
                    f("direction"),
                    format!(
                        "{shown} gives each component's direction (its column `direction`): \
                         leave the train's `direction` out"
                    ),
                ));
            }
            let rows = read
                .into_iter()
                .map(|(line, v)| Row {
                    place: format!("{shown} line {line}"),
                    field: field.clone(),
                    values: [
                        if hz { TAU * v[0] } else { v[0] },
                        v[1],
                        v[2],
                        v.get(3).copied().unwrap_or(0.0),
                    ],
                    written: v[0],
                    has_direction,
                })
                .collect();
            let first = if hz { "frequency" } else { "omega" };
            (rows, [first, "amplitude", "phase", "direction"], shown)
        }
        (None, Some(given)) => {
            if direction.is_some() {
                return Err(err(
                    p,
                    f("direction"),
                    "`rows` give each component's direction: leave the train's `direction` out",
                ));
            }
            let mut rows = Vec::with_capacity(given.len());
            for (j, r) in given.iter().enumerate() {
                for (c, x) in r.iter().enumerate() {
                    finite(p, &f(&format!("rows[{j}][{c}]")), *x)?;
                }
                rows.push(Row {
                    place: format!("row {j}"),
                    field: f(&format!("rows[{j}]")),
                    values: *r,
                    written: r[0],
                    has_direction: true,
                });
            }
            if rows.is_empty() {
                return Err(err(p, f("rows"), "no rows"));
            }
            (
                rows,
                ["omega", "amplitude", "phase", "direction"],
                f("rows"),
            )
        }
    };
    let inline = t.file.is_none();
    let bad = |r: &Row, c: usize, message: String| {
        if inline {
            err(p, format!("{}[{c}]", r.field), message)
        } else {
            err(
                p,
                r.field.clone(),
                format!("{}, column {}: {message}", r.place, col_names[c]),
            )
        }
    };
    let mut comps: Vec<(String, WaveComponent)> = Vec::with_capacity(rows.len());
    for r in &rows {
        let [omega, amplitude, phase, dir] = r.values;
        if omega <= 0.0 {
            return Err(bad(
                r,
                0,
                format!(
                    "frequency must be positive, got {} (a component of zero frequency is \
                     a shift of the mean level, not a wave)",
                    show(r.written)
                ),
            ));
        }
        if amplitude < 0.0 {
            return Err(bad(
                r,
                1,
                format!(
                    "amplitude must not be negative, got {} (give the phase 180 degrees \
                     further instead)",
                    show(amplitude)
                ),
            ));
        }
        let c = WaveComponent {
            amplitude,
            omega,
            k: wave_number(omega, depth, gravity),
            direction: if r.has_direction {
                dir.to_radians()
            } else {
                direction.unwrap_or(0.0)
            },
            phase: phase.to_radians(),
        };
        if amplitude > 0.0 {
            let inputs = TrainInputs {
                height: (&r.field, amplitude),
                period: (&r.field, TAU / omega),
            };
            wave_checks::train(p, &inputs, &[c], depth, tolerance).map_err(|e| at(e, &r.place))?;
        }
        comps.push((r.place.clone(), c));
    }
    if comps.iter().all(|(_, c)| c.amplitude == 0.0) {
        return Err(err(
            p,
            if inline { f("rows") } else { f("file") },
            format!("{source}: every amplitude is zero (leave the train out for still water)"),
        ));
    }
    let all: Vec<WaveComponent> = comps.iter().map(|(_, c)| *c).collect();
    let field = if inline { f("rows") } else { f("file") };
    let inputs = TrainInputs {
        height: (&field, 1.0),
        period: (&field, 1.0),
    };
    wave_checks::train(p, &inputs, &all, depth, tolerance)?;
    let mut warnings = Vec::new();
    warnings.extend(steepness_warning(p, &field, &comps));
    warnings.extend(many_warning(p, &field, all.len(), ""));
    Ok((all, warnings))
}

/// A `"record"` train: the components of its elevation record (sea::measured), and
/// warnings. `direction` is the train's direction (rad); `duration` the run's, s, when
/// known (a longer run repeats the record).
#[allow(clippy::too_many_arguments)]
pub(super) fn record(
    p: &Path,
    f: &dyn Fn(&str) -> String,
    t: &RawTrain,
    direction: f64,
    depth: f64,
    gravity: f64,
    tolerance: f64,
    duration: Option<f64>,
) -> Result<(Vec<WaveComponent>, Vec<String>), Error> {
    let field = f("file");
    let Some(file) = &t.file else {
        return Err(err(
            p,
            &field,
            "a \"record\" train needs `file`: a CSV elevation record with the header \
             `t,eta` (s, m), evenly sampled",
        ));
    };
    let path = p.parent().unwrap_or(Path::new(".")).join(file);
    let shown = path.display().to_string();
    let (_, rows) = read_numbers_one_of(&path, p, &field, "elevation record", &[&["t", "eta"]])?;
    let n = rows.len();
    if n < MIN_RECORD_SAMPLES {
        return Err(err(
            p,
            &field,
            format!(
                "{shown}: {n} samples; an elevation record needs at least \
                 {MIN_RECORD_SAMPLES} (it gives N / 2 wave components)"
            ),
        ));
    }
    for w in rows.windows(2) {
        if w[1].1[0] <= w[0].1[0] {
            return Err(err(
                p,
                &field,
                format!(
                    "{shown} line {}, column t: time {} does not increase (previous {})",
                    w[1].0,
                    show(w[1].1[0]),
                    show(w[0].1[0])
                ),
            ));
        }
    }
    let t0 = rows[0].1[0];
    let dt = (rows[n - 1].1[0] - t0) / (n - 1) as f64;
    for (i, (line, v)) in rows.iter().enumerate() {
        let off = v[0] - (t0 + i as f64 * dt);
        if !(off.abs() <= SAMPLING_TOLERANCE * dt) {
            return Err(err(
                p,
                &field,
                format!(
                    "{shown} line {line}, column t: the record is not evenly sampled: \
                     sample {i} at t = {} s is {} s ({:.1}% of the mean step {} s) off \
                     t0 + {i} dt, more than the {}% allowed; resample the record evenly",
                    show(v[0]),
                    show(off),
                    100.0 * off.abs() / dt,
                    show(dt),
                    100.0 * SAMPLING_TOLERANCE
                ),
            ));
        }
    }
    let eta: Vec<f64> = rows.iter().map(|(_, v)| v[1]).collect();
    let d = decompose(&eta, dt);
    let spread = eta
        .iter()
        .map(|e| (e - d.mean).abs())
        .fold(0.0f64, f64::max);
    let scale = eta.iter().map(|e| e.abs()).fold(0.0f64, f64::max);
    if !(spread > 1e-12 * scale) {
        return Err(err(
            p,
            &field,
            format!(
                "{shown}: the elevation is constant ({} m): no waves (leave the train out \
                 for still water)",
                show(d.mean)
            ),
        ));
    }
    let mut harmonics = d.harmonics;
    if let Some(fmax) = t.max_frequency {
        let fmax = positive(p, &f("max_frequency"), fmax)?;
        harmonics.retain(|h| h.omega <= TAU * fmax);
        if harmonics.is_empty() {
            return Err(err(
                p,
                f("max_frequency"),
                format!(
                    "{} Hz keeps no component: the record's lowest frequency is 1 / T = {} \
                     Hz (T = {} s)",
                    show(fmax),
                    show(1.0 / d.period),
                    show(d.period)
                ),
            ));
        }
    }
    let reference = match t.reference {
        Some(r) => [
            finite(p, &f("reference[0]"), r[0])?,
            finite(p, &f("reference[1]"), r[1])?,
        ],
        None => [0.0, 0.0],
    };
    let comps = place(&harmonics, t0, reference, direction, depth, gravity);
    let inputs = TrainInputs {
        height: (&field, spread),
        period: (&field, dt),
    };
    wave_checks::train(p, &inputs, &comps, depth, tolerance).map_err(|e| at(e, &shown))?;
    let mut warnings = Vec::new();
    let placed: Vec<(String, WaveComponent)> = comps
        .iter()
        .map(|c| (format!("the component of {} Hz", show(c.omega / TAU)), *c))
        .collect();
    warnings.extend(steepness_warning(p, &field, &placed));
    if let Some(run) = duration {
        if run > d.period {
            warnings.push(format!(
                "{}: {field}: {shown} spans T = {} s ({n} samples of {} s), the run {} s: \
                 after T the waves repeat the record (the FFT's periodic extension)",
                p.display(),
                show(d.period),
                show(dt),
                show(run)
            ));
        }
    }
    warnings.extend(many_warning(
        p,
        &field,
        comps.len(),
        ": `max_frequency` (Hz) leaves out those above it",
    ));
    Ok((comps, warnings))
}
