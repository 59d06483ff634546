//! The derived kinematics of a wave train, refused by field when f64 cannot hold them
//! or no step could follow them: a wave number that overflows or underflows (a period
//! far out of range), water faster than [`WAVE_SPEED_LIMIT`], accelerations (and the kinematics
//! cache's fourth derivative) beyond [`MAGNITUDE_LIMIT`], or a train whose kinematics'
//! squares overflow or underflow (the cache could not size its refresh interval).

use super::err;
use super::validate::MAGNITUDE_LIMIT;
use crate::error::Error;
use crate::sea::cache::refresh_interval;
use crate::sea::WaveComponent;
use std::path::Path;

/// The fastest water a wave may move at the surface, m/s: the default
/// `simulation.max_speed`, orders of magnitude beyond any sea (a breaking wave's crest
/// moves at its phase speed, tens of m/s).
pub const WAVE_SPEED_LIMIT: f64 = 1e4;

/// One train as written, to name the field at fault: the height (or amplitude) key and
/// its value in metres, the period key and its value in seconds.
pub struct TrainInputs<'a> {
    /// Field and value (m) of the height, amplitude or `hs`.
    pub height: (&'a str, f64),
    /// Field and value (s) of the period or `tp`.
    pub period: (&'a str, f64),
}

impl TrainInputs<'_> {
    /// The input furthest from 1 (in orders of magnitude, metres against seconds): the
    /// one to blame when their product is out of range.
    fn culprit(&self) -> &str {
        let (h, t) = (self.height.1.log10().abs(), self.period.1.log10().abs());
        if t > h {
            self.period.0
        } else {
            self.height.0
        }
    }

    fn values(&self) -> String {
        if self.height.0 == self.period.0 {
            return format!("the {} table", key(self.height.0));
        }
        format!(
            "{} = {:e} m, {} = {:e} s",
            key(self.height.0),
            self.height.1,
            key(self.period.0),
            self.period.1
        )
    }
}

/// The last key of a dotted field.
fn key(field: &str) -> &str {
    field.rsplit('.').next().unwrap_or(field)
}

/// Checks the components `comps` of one train (see the module's doc) in water `depth`
/// deep (m, may be infinite), with the kinematics cache's `tolerance`.
pub fn train(
    p: &Path,
    t: &TrainInputs,
    comps: &[WaveComponent],
    depth: f64,
    tolerance: f64,
) -> Result<(), Error> {
    for c in comps {
        if !(c.omega.is_finite() && c.omega > 0.0 && c.k.is_finite() && c.k > 0.0) {
            return Err(err(
                p,
                t.period.0,
                format!(
                    "{}: a component of frequency {:e} rad/s has wave number {:e} rad/m, not a positive finite number in f64; check the value and its units",
                    t.values(),
                    c.omega,
                    c.k
                ),
            ));
        }
        if !c.amplitude.is_finite() {
            return Err(err(
                p,
                t.culprit(),
                format!(
                    "{}: a component's amplitude is {:e} m; check the values and their units",
                    t.values(),
                    c.amplitude
                ),
            ));
        }
        // At the surface the orbital velocity is a w coth(k d) (1 in deep water).
        let coth = if depth.is_finite() {
            1.0 / (c.k * depth).tanh()
        } else {
            1.0
        };
        let speed = c.amplitude * c.omega * coth;
        if !(speed <= WAVE_SPEED_LIMIT) {
            return Err(err(
                p,
                t.culprit(),
                format!(
                    "{}: the water at the surface moves at {speed:e} m/s (a component of amplitude {:e} m, {:e} rad/s), above {WAVE_SPEED_LIMIT:e} m/s, far beyond any sea; check the values and their units",
                    t.values(),
                    c.amplitude,
                    c.omega
                ),
            ));
        }
        let accel = speed * c.omega;
        let fourth = accel * c.omega * c.omega;
        if !(accel <= MAGNITUDE_LIMIT && fourth <= MAGNITUDE_LIMIT) {
            return Err(err(
                p,
                t.culprit(),
                format!(
                    "{}: the water's acceleration {accel:e} m/s^2 (or its second derivative {fourth:e} m/s^4) at {:e} rad/s is beyond {MAGNITUDE_LIMIT:e}: it overflows f64 where the solver squares it; check the values and their units",
                    t.values(),
                    c.omega
                ),
            ));
        }
    }
    let interval = refresh_interval(comps, tolerance);
    let interval_ok = interval > 0.0 && interval.is_finite();
    if !comps.is_empty() && !interval_ok {
        return Err(err(
            p,
            t.culprit(),
            format!(
                "{}: the squares of the train's kinematics overflow or underflow f64 (the kinematics cache cannot size its refresh interval from them); check the values and their units (leave a train out for still water)",
                t.values()
            ),
        ));
    }
    Ok(())
}
