//! Rainflow counting of a load history, after ASTM E1049-85 (reapproved 2017),
//! section 5.4.4 "Rainflow Counting", streamed one sample at a time.
//!
//! **Reversals.** Samples become peaks and valleys (reversals) as they come: a sample
//! equal to the one before is skipped, and a sample is a reversal when the history
//! turns there (the change into it and the change out of it have opposite signs). The
//! first and the last sample are reversals too, as the standard's example treats the
//! ends of a history.
//!
//! **Counting** (the standard's three-point rule). The reversals are stacked as they
//! come; after each, let `X` be the range of the two newest and `Y` the range of the
//! two before them (`Y` newer than the start of the stack). While `X >= Y`:
//! - if `Y` holds the first reversal on the stack (the stack holds three), `Y` counts
//!   as **half a cycle** and its first point leaves the stack;
//! - otherwise `Y` counts as **one cycle** and its two points leave the stack.
//!
//! **The residue.** At the end of the history, each range between successive reversals
//! still on the stack counts as **half a cycle** (the standard's step 5.4.4 (6): "count
//! each range that has not been previously counted as one-half cycle"). No cycle is
//! closed across the end of the record (such as repeating the history, which would
//! turn the residue's largest range into a full cycle), so a record's count does not
//! depend on anything outside it.
//!
//! The counting is the one the `rainflow` Python package (3.2) implements: the tests
//! compare the two on the tension records of runs, cycle by cycle.

/// One counted cycle or half cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cycle {
    /// The range: the absolute difference of its two reversals, in the history's unit.
    pub range: f64,
    /// The mean of its two reversals.
    pub mean: f64,
    /// 1 for a full cycle, 0.5 for a half cycle.
    pub count: f64,
}

/// Streaming rainflow counter (module documentation): push the samples in order with
/// [`Rainflow::push`], then [`Rainflow::finish`] for the residue. Memory: the stack of
/// reversals not yet counted, whose ranges decrease from its bottom up (a few dozen
/// for the tension of a line in a stationary sea state).
#[derive(Clone, Debug, Default)]
pub struct Rainflow {
    /// Reversals not yet counted, oldest first.
    stack: Vec<f64>,
    /// Samples pushed.
    samples: u64,
    /// The first sample.
    first: f64,
    /// The latest sample that differed from the one before it (a candidate reversal).
    x: f64,
    /// The change into `x`.
    d_last: f64,
}

impl Rainflow {
    /// An empty counter.
    pub fn new() -> Self {
        Self::default()
    }

    /// The samples pushed.
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// Pushes sample `v`; `cycle` is called with every cycle this closes.
    pub fn push(&mut self, v: f64, cycle: &mut impl FnMut(Cycle)) {
        match self.samples {
            0 => {
                self.first = v;
                self.reversal(v, cycle);
            }
            1 => {
                self.x = v;
                self.d_last = v - self.first;
            }
            _ => {
                if v != self.x {
                    let d_next = v - self.x;
                    if self.d_last * d_next < 0.0 {
                        self.reversal(self.x, cycle);
                    }
                    self.x = v;
                    self.d_last = d_next;
                }
            }
        }
        self.samples += 1;
    }

    /// Ends the history: the last sample is a reversal, and the ranges left on the
    /// stack count as half cycles (the residue).
    pub fn finish(mut self, cycle: &mut impl FnMut(Cycle)) {
        if self.samples >= 2 {
            self.reversal(self.x, cycle);
        }
        for w in self.stack.windows(2) {
            cycle(Cycle {
                range: (w[0] - w[1]).abs(),
                mean: 0.5 * (w[0] + w[1]),
                count: 0.5,
            });
        }
    }

    fn reversal(&mut self, p: f64, cycle: &mut impl FnMut(Cycle)) {
        self.stack.push(p);
        while self.stack.len() >= 3 {
            let n = self.stack.len();
            let (x1, x2, x3) = (self.stack[n - 3], self.stack[n - 2], self.stack[n - 1]);
            let x = (x3 - x2).abs();
            let y = (x2 - x1).abs();
            if x < y {
                break;
            }
            let c = Cycle {
                range: y,
                mean: 0.5 * (x1 + x2),
                count: if n == 3 { 0.5 } else { 1.0 },
            };
            cycle(c);
            if n == 3 {
                self.stack.remove(0);
            } else {
                self.stack.truncate(n - 3);
                self.stack.push(x3);
            }
        }
    }
}

/// Every cycle and half cycle of `series`, in the order they are counted (the
/// residue's half cycles last).
pub fn cycles(series: &[f64]) -> Vec<Cycle> {
    let mut out = Vec::new();
    let mut rf = Rainflow::new();
    let mut push = |c: Cycle| out.push(c);
    for &v in series {
        rf.push(v, &mut push);
    }
    rf.finish(&mut push);
    out
}
