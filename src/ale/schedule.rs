//! Payout schedules: how a winch's deployed length `L(t)` changes.

/// The payout at one time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Payout {
    /// Deployed length paid out since `t = 0` (negative when hauled in), m.
    pub dl: f64,
    /// Payout rate `Ldot`, m/s (positive: payout).
    pub rate: f64,
    /// Payout acceleration `Lddot`, m/s^2.
    pub accel: f64,
}

impl Payout {
    /// The payout of a constant rate `rate` (m/s) at time `t` (what
    /// [`PayoutSchedule::eval`] gives for [`PayoutSchedule::constant`]).
    #[inline(always)]
    pub fn of_constant(rate: f64, t: f64) -> Self {
        Payout {
            dl: rate * t,
            rate,
            accel: 0.0,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    Constant {
        rate: f64,
    },
    Rates {
        t: Vec<f64>,
        rate: Vec<f64>,
        /// Integral of the rate from `t[0]` to `t[i]`.
        cum: Vec<f64>,
        /// The integral from `t[0]` to `0`.
        at0: f64,
    },
    Table {
        t: Vec<f64>,
        length: Vec<f64>,
        at0: f64,
    },
}

/// How the deployed length `L(t)` changes: a constant rate, a rate table (piecewise
/// linear in time), or a table of deployed lengths (piecewise linear in time).
#[derive(Clone, Debug, PartialEq)]
pub struct PayoutSchedule {
    kind: Kind,
}

impl PayoutSchedule {
    /// A constant rate, m/s (positive: payout, negative: retrieval): `L = L0 + rate t`.
    pub fn constant(rate: f64) -> Result<Self, String> {
        if !rate.is_finite() {
            return Err(format!("the rate must be a finite number, got {rate}"));
        }
        Ok(Self {
            kind: Kind::Constant { rate },
        })
    }

    /// A rate table: rows `(t, rate)` with times not decreasing; the rate is linear in
    /// time between rows (two rows at the same time make a jump) and held at the first
    /// and last rows' values outside the table. `L = L0 + integral_0^t rate`.
    pub fn rates(rows: &[(f64, f64)]) -> Result<Self, String> {
        if rows.is_empty() {
            return Err("needs at least one row [t, rate]".into());
        }
        for (i, &(t, r)) in rows.iter().enumerate() {
            if !t.is_finite() || !r.is_finite() {
                return Err(format!(
                    "row {i}: [{t}, {r}] is not a pair of finite numbers"
                ));
            }
            if i > 0 && t < rows[i - 1].0 {
                return Err(format!(
                    "row {i}: time {t} s comes before the previous row's {} s (times must not decrease)",
                    rows[i - 1].0
                ));
            }
            if i > 1 && t == rows[i - 1].0 && t == rows[i - 2].0 {
                return Err(format!(
                    "row {i}: three rows at t = {t} s (two make a jump; a third is ambiguous)"
                ));
            }
        }
        let t: Vec<f64> = rows.iter().map(|r| r.0).collect();
        let rate: Vec<f64> = rows.iter().map(|r| r.1).collect();
        let mut cum = vec![0.0; t.len()];
        for i in 1..t.len() {
            cum[i] = cum[i - 1] + (t[i] - t[i - 1]) * 0.5 * (rate[i - 1] + rate[i]);
        }
        let mut s = Self {
            kind: Kind::Rates {
                t,
                rate,
                cum,
                at0: 0.0,
            },
        };
        let a = s.integral(0.0).0;
        if let Kind::Rates { at0, .. } = &mut s.kind {
            *at0 = a;
        }
        Ok(s)
    }

    /// A table of deployed lengths: rows `(t, L)` with strictly increasing times and
    /// `L >= 0`, linearly interpolated, held at the first and last rows outside. The
    /// rate is the slope of the current segment; `Lddot` is zero (a kink is a jump of
    /// the rate: use [`PayoutSchedule::rates`] for smooth ramps).
    pub fn table(rows: &[(f64, f64)]) -> Result<Self, String> {
        if rows.is_empty() {
            return Err("needs at least one row t,length".into());
        }
        for (i, &(t, l)) in rows.iter().enumerate() {
            if !t.is_finite() || !l.is_finite() {
                return Err(format!(
                    "row {i}: ({t}, {l}) is not a pair of finite numbers"
                ));
            }
            if l < 0.0 {
                return Err(format!("row {i}: deployed length {l} m is negative"));
            }
            if i > 0 && t <= rows[i - 1].0 {
                return Err(format!(
                    "row {i}: time {t} s does not increase (previous {} s)",
                    rows[i - 1].0
                ));
            }
        }
        let mut s = Self {
            kind: Kind::Table {
                t: rows.iter().map(|r| r.0).collect(),
                length: rows.iter().map(|r| r.1).collect(),
                at0: 0.0,
            },
        };
        let a = s.table_length(0.0);
        if let Kind::Table { at0, .. } = &mut s.kind {
            *at0 = a;
        }
        Ok(s)
    }

    /// For a table: the deployed length it gives at `t = 0` (which must be the
    /// cable's initial length); `None` for rate schedules.
    pub fn table_length_at_zero(&self) -> Option<f64> {
        match &self.kind {
            Kind::Table { at0, .. } => Some(*at0),
            _ => None,
        }
    }

    /// True for a constant rate: the paid-out length is then monotone in time.
    pub fn is_constant(&self) -> bool {
        self.constant_rate().is_some()
    }

    /// The rate of a constant-rate schedule (`None` for tables).
    pub fn constant_rate(&self) -> Option<f64> {
        match self.kind {
            Kind::Constant { rate } => Some(rate),
            _ => None,
        }
    }

    /// True when the schedule never changes the length (zero rates, a flat table).
    pub fn is_still(&self) -> bool {
        match &self.kind {
            Kind::Constant { rate } => *rate == 0.0,
            Kind::Rates { rate, .. } => rate.iter().all(|&r| r == 0.0),
            Kind::Table { length, .. } => length.iter().all(|&l| l == length[0]),
        }
    }

    fn table_length(&self, tq: f64) -> f64 {
        let Kind::Table { t, length, .. } = &self.kind else {
            return 0.0;
        };
        let n = t.len();
        if tq <= t[0] {
            return length[0];
        }
        if tq >= t[n - 1] {
            return length[n - 1];
        }
        let i = t.partition_point(|&x| x <= tq).max(1);
        let s = (tq - t[i - 1]) / (t[i] - t[i - 1]);
        length[i - 1] + s * (length[i] - length[i - 1])
    }

    /// For a rate table: `(integral from t[0] to tq, rate, accel)`.
    fn integral(&self, tq: f64) -> (f64, f64, f64) {
        let Kind::Rates { t, rate, cum, .. } = &self.kind else {
            return (0.0, 0.0, 0.0);
        };
        let n = t.len();
        if tq <= t[0] {
            return ((tq - t[0]) * rate[0], rate[0], 0.0);
        }
        if tq >= t[n - 1] {
            return (cum[n - 1] + (tq - t[n - 1]) * rate[n - 1], rate[n - 1], 0.0);
        }
        // The last row at or before tq; then t[i] <= tq < t[i + 1], so the segment
        // has a positive width (a jump's zero-width segment is never selected).
        let i = t.partition_point(|&x| x <= tq) - 1;
        let slope = (rate[i + 1] - rate[i]) / (t[i + 1] - t[i]);
        let s = tq - t[i];
        let r = rate[i] + slope * s;
        (cum[i] + s * 0.5 * (rate[i] + r), r, slope)
    }

    /// Payout at time `t`: length paid out since `t = 0`, rate and acceleration.
    /// (Inlined: the steppers call it every stage.)
    #[inline]
    pub fn eval(&self, t: f64) -> Payout {
        match &self.kind {
            Kind::Constant { rate } => Payout::of_constant(*rate, t),
            Kind::Rates { at0, .. } => {
                let (f, rate, accel) = self.integral(t);
                Payout {
                    dl: f - at0,
                    rate,
                    accel,
                }
            }
            Kind::Table { t: ts, length, at0 } => {
                let n = ts.len();
                let rate = if n > 1 && t > ts[0] && t < ts[n - 1] {
                    let i = ts.partition_point(|&x| x <= t).max(1);
                    (length[i] - length[i - 1]) / (ts[i] - ts[i - 1])
                } else {
                    0.0
                };
                Payout {
                    dl: self.table_length(t) - at0,
                    rate,
                    accel: 0.0,
                }
            }
        }
    }
}
