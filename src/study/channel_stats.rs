//! Streaming statistics of one channel of one member: fixed memory, one pass.
//!
//! A member of a study runs for hours of simulated time at millisecond steps; keeping its
//! time series would cost gigabytes per study, so every channel is reduced while it runs.
//! [`ChannelStats`] holds a few numbers whatever the record's length:
//!
//! - the maximum and the time it was first reached, the minimum and its time;
//! - the mean and standard deviation by Welford's update (numerically stable: no sum of
//!   squares that cancels when the mean is large against the spread, as a mooring line's
//!   pretension is against its dynamic part);
//! - the number of zero-up-crossings of the signal about its mean (see below);
//! - the first and last retained times, so a record's length (and a mean zero-up-crossing
//!   period) is known.
//!
//! Samples before the transient time are dropped: the start-up of a member (ramped waves,
//! the line settling) is not part of the stationary sea state being reduced.
//!
//! **The crossing reference.** A zero-up-crossing of a signal is a crossing of its mean
//! level from below, and the record's mean is only known at its end. Here the reference
//! for the step from sample `i-1` to sample `i` is the mean of the retained samples
//! `1..i-1`, and an up-crossing is counted when `x[i-1] < m[i-1] <= x[i]`: both samples
//! are compared with the same level, so what is counted is a true crossing of a level.
//! Why this choice rather than a level fixed at the end of the transient: a level fixed
//! then (the static tension, or the mean over some part of the transient) carries the
//! start-up's bias for the whole record (the mean tension of a line in a sea state with
//! current and drift differs from the one during the ramp), and a biased level misses
//! crossings over the whole record, for ever. The running mean's error instead shrinks
//! as the record grows (about `sigma / sqrt(n_cycles)` after `n_cycles` wave cycles), so
//! it differs from the final mean's count only in the first few cycles: for a 3-hour
//! record of about a thousand cycles, a fraction of a percent. The unit tests bound the
//! difference against a two-pass count about the final mean.

use serde::{Deserialize, Serialize};

/// A value of a channel and the time it was reached.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Extreme {
    /// The value, in the channel's unit (N for tensions and forces, N m for moments).
    pub value: f64,
    /// Simulated time of the member, s.
    pub time: f64,
}

/// Streaming statistics of one channel (see the module documentation).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChannelStats {
    /// Samples at times before this are ignored, s.
    transient: f64,
    /// Retained samples.
    count: u64,
    /// Mean of the retained samples, channel unit.
    mean: f64,
    /// Sum of squared deviations from the mean (Welford's `M2`), channel unit squared.
    m2: f64,
    /// Largest retained sample (the first, when it is reached several times).
    max: Option<Extreme>,
    /// Smallest retained sample (the first, when it is reached several times).
    min: Option<Extreme>,
    /// Up-crossings of the running mean (module documentation).
    up_crossings: u64,
    /// The previous retained sample, for the crossing test; `None` before the first and
    /// after pooling (a pooled value has no single "previous sample").
    last: Option<f64>,
    /// Summed length of the records pooled into this one before the current record, s.
    pooled_duration: f64,
    /// First and last retained times of the record being streamed, s.
    span: Option<(f64, f64)>,
}

impl ChannelStats {
    /// Empty statistics that will ignore samples at times before `transient` (s).
    pub fn new(transient: f64) -> Self {
        ChannelStats {
            transient,
            count: 0,
            mean: 0.0,
            m2: 0.0,
            max: None,
            min: None,
            up_crossings: 0,
            last: None,
            pooled_duration: 0.0,
            span: None,
        }
    }

    /// Adds the sample `x` (channel unit) at simulated time `t` (s). Samples must come in
    /// increasing time and be finite: the runner stops a member whose state is not finite
    /// before its values reach the statistics.
    pub fn push(&mut self, t: f64, x: f64) {
        if t < self.transient {
            return;
        }
        debug_assert!(x.is_finite(), "non-finite sample {x} at t = {t}");
        if let Some(prev) = self.last {
            // Same level on both sides: the mean before this sample.
            if prev < self.mean && x >= self.mean {
                self.up_crossings += 1;
            }
        }
        self.count += 1;
        let delta = x - self.mean;
        self.mean += delta / self.count as f64;
        self.m2 += delta * (x - self.mean);
        if self.max.is_none_or(|m| x > m.value) {
            self.max = Some(Extreme { value: x, time: t });
        }
        if self.min.is_none_or(|m| x < m.value) {
            self.min = Some(Extreme { value: x, time: t });
        }
        self.span = Some(match self.span {
            None => (t, t),
            Some((t0, _)) => (t0, t),
        });
        self.last = Some(x);
    }

    /// The time before which samples are ignored, s.
    pub fn transient(&self) -> f64 {
        self.transient
    }
    /// Retained samples.
    pub fn count(&self) -> u64 {
        self.count
    }
    /// Mean of the retained samples (`None` when there are none).
    pub fn mean(&self) -> Option<f64> {
        (self.count > 0).then_some(self.mean)
    }
    /// Standard deviation of the retained samples about their mean, with divisor `n`
    /// (the record's own spread, not an estimate for a wider population; with the
    /// hundreds of thousands of samples of a study member the two differ by nothing
    /// visible). `None` when there are no samples.
    pub fn std(&self) -> Option<f64> {
        (self.count > 0).then(|| (self.m2 / self.count as f64).max(0.0).sqrt())
    }
    /// The largest retained sample and the first time it was reached.
    pub fn max(&self) -> Option<Extreme> {
        self.max
    }
    /// The smallest retained sample and the first time it was reached.
    pub fn min(&self) -> Option<Extreme> {
        self.min
    }
    /// Zero-up-crossings about the running mean (module documentation).
    pub fn up_crossings(&self) -> u64 {
        self.up_crossings
    }
    /// Retained record length (summed over pooled records), s.
    pub fn duration(&self) -> f64 {
        self.pooled_duration + self.span.map_or(0.0, |(t0, t1)| t1 - t0)
    }
    /// Mean zero-up-crossing period, s: the record length over the up-crossings
    /// (`None` without a crossing).
    pub fn mean_up_crossing_period(&self) -> Option<f64> {
        (self.up_crossings > 0).then(|| self.duration() / self.up_crossings as f64)
    }

    /// Pools `other` into `self`: the result describes the union of the two records'
    /// samples, as if one record (Chan, Golub and LeVeque's pairwise update of the mean
    /// and `M2`). Meaningful for independent records of the same channel and the same
    /// stationary process, such as the seeds of one sea state: the pooled mean is the
    /// best estimate of the mean tension, the maximum the largest over the records, the
    /// crossing counts and the durations add (each record's crossings about its own
    /// running mean; none is counted across the join). It is not the same as one longer
    /// record cut in two, whose join could hide a crossing. After pooling, further
    /// `push`es start a new record.
    ///
    /// Floating-point pooling is not associative to the last bit: to be reproducible,
    /// pool in a fixed order (the study pools members in member order).
    pub fn pool(&mut self, other: &ChannelStats) {
        if other.count == 0 {
            return;
        }
        let duration = self.duration() + other.duration();
        if self.count == 0 {
            let transient = self.transient;
            *self = other.clone();
            self.transient = transient;
        } else {
            let (na, nb) = (self.count as f64, other.count as f64);
            let n = na + nb;
            let delta = other.mean - self.mean;
            self.mean += delta * (nb / n);
            self.m2 += other.m2 + delta * delta * (na * nb / n);
            self.count += other.count;
            // Both hold samples here, so both have extremes; ties keep `self`'s (the
            // earlier record in a fixed pooling order).
            if let (Some(a), Some(b)) = (self.max, other.max) {
                if b.value > a.value {
                    self.max = Some(b);
                }
            }
            if let (Some(a), Some(b)) = (self.min, other.min) {
                if b.value < a.value {
                    self.min = Some(b);
                }
            }
            self.up_crossings += other.up_crossings;
        }
        self.pooled_duration = duration;
        self.last = None;
        self.span = None;
    }
}
