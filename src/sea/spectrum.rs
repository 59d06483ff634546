//! Wave spectra `S(w)` (one-sided, m^2 s/rad, over angular frequency `w` in rad/s):
//! JONSWAP, Pierson-Moskowitz and tables, and their moments.

use std::f64::consts::TAU;

/// The largest JONSWAP peak factor a scenario may give. The normalising factor
/// `1 - 0.287 ln g` of DNV-RP-C205 is an approximation that drifts as `g` grows: the
/// spectrum's `m0` is 1.8% below `Hs^2 / 16` at `g = 7`, 7% at 10, 39% at 20, and the
/// factor is negative above `g = e^(1 / 0.287) = 32.6`. DNV gives the form for the usual
/// range `1 <= g <= 7`; a peakier sea is better given as a spectrum table.
pub const JONSWAP_GAMMA_MAX: f64 = 7.0;

/// A wave spectrum.
#[derive(Clone, Debug, PartialEq)]
pub enum Spectrum {
    /// Pierson-Moskowitz:
    /// `S(w) = 5/16 Hs^2 w_p^4 w^-5 exp(-5/4 (w / w_p)^-4)`, `w_p = 2 pi / Tp`.
    PiersonMoskowitz {
        /// Significant wave height `Hs`, m.
        hs: f64,
        /// Peak period `Tp`, s.
        tp: f64,
    },
    /// JONSWAP (DNV-RP-C205 form): `(1 - 0.287 ln g) S_PM(w) g^r`,
    /// `r = exp(-(w - w_p)^2 / (2 s^2 w_p^2))`, `s = 0.07` for `w <= w_p`, 0.09 above.
    /// The factor `1 - 0.287 ln g` keeps `m0 = Hs^2 / 16` within 0.3% for
    /// `1 <= g <= 5` (1.8% low at `g = 7`); scenarios refuse `g` above
    /// [`JONSWAP_GAMMA_MAX`].
    Jonswap {
        /// Significant wave height `Hs`, m.
        hs: f64,
        /// Peak period `Tp`, s.
        tp: f64,
        /// Peak enhancement factor `g` (see [`dnv_peak_factor`] for the default).
        gamma: f64,
    },
    /// A table of `(w, S)` points, rad/s and m^2 s/rad, `w` increasing; linear between
    /// points, zero outside.
    Table {
        /// Angular frequencies, rad/s, strictly increasing.
        omega: Vec<f64>,
        /// Spectral density at each, m^2 s/rad.
        density: Vec<f64>,
    },
}

/// The default JONSWAP peak factor of DNV-RP-C205: 5 where `Tp / sqrt(Hs) <= 3.6`,
/// 1 where `>= 5`, `exp(5.75 - 1.15 Tp / sqrt(Hs))` between (`Hs` in m, `Tp` in s).
pub fn dnv_peak_factor(hs: f64, tp: f64) -> f64 {
    let r = tp / hs.sqrt();
    if r <= 3.6 {
        5.0
    } else if r >= 5.0 {
        1.0
    } else {
        (5.75 - 1.15 * r).exp()
    }
}

fn pierson_moskowitz(hs: f64, tp: f64, w: f64) -> f64 {
    if w <= 0.0 {
        return 0.0;
    }
    let wp = TAU / tp;
    let q = (wp / w).powi(4);
    5.0 / 16.0 * hs * hs * q / w * (-1.25 * q).exp()
}

impl Spectrum {
    /// `S(w)`, m^2 s/rad.
    pub fn density(&self, w: f64) -> f64 {
        match self {
            Spectrum::PiersonMoskowitz { hs, tp } => pierson_moskowitz(*hs, *tp, w),
            Spectrum::Jonswap { hs, tp, gamma } => {
                let wp = TAU / tp;
                let s = if w <= wp { 0.07 } else { 0.09 };
                let r = (-(w - wp).powi(2) / (2.0 * s * s * wp * wp)).exp();
                (1.0 - 0.287 * gamma.ln()) * pierson_moskowitz(*hs, *tp, w) * gamma.powf(r)
            }
            Spectrum::Table { omega, density } => {
                let n = omega.len();
                if n == 0 || w < omega[0] || w > omega[n - 1] {
                    return 0.0;
                }
                let j = omega.partition_point(|&x| x <= w).clamp(1, n - 1);
                let s = (w - omega[j - 1]) / (omega[j] - omega[j - 1]);
                density[j - 1] + s * (density[j] - density[j - 1])
            }
        }
    }

    /// A frequency range holding all but a negligible part of the energy, rad/s:
    /// `[0.2, 20] w_p` for the parametric spectra (the Pierson-Moskowitz energy
    /// outside is `exp(-781)` below and `1 - exp(-5/4 / 20^4) = 8e-6` above), the
    /// table's range for tables.
    pub fn support(&self) -> (f64, f64) {
        match self {
            Spectrum::PiersonMoskowitz { tp, .. } | Spectrum::Jonswap { tp, .. } => {
                let wp = TAU / tp;
                (0.2 * wp, 20.0 * wp)
            }
            Spectrum::Table { omega, .. } => (omega[0], omega[omega.len() - 1]),
        }
    }

    /// The cumulative energy `C(w) = int_{w_a}^{w} S` on `n + 1` equally spaced points
    /// over [`Spectrum::support`] `[w_a, w_b]`: `(w values, C values)`, trapezoidal
    /// (exact for tables whose points fall on the grid; `n = 20000` is well within
    /// 1e-6 of `m0` for the parametric spectra).
    pub fn cumulative(&self, n: usize) -> (Vec<f64>, Vec<f64>) {
        let (a, b) = self.support();
        let h = (b - a) / n as f64;
        let w: Vec<f64> = (0..=n).map(|i| a + h * i as f64).collect();
        let mut c = vec![0.0; n + 1];
        let mut prev = self.density(w[0]);
        for i in 1..=n {
            let s = self.density(w[i]);
            c[i] = c[i - 1] + 0.5 * h * (prev + s);
            prev = s;
        }
        (w, c)
    }

    /// The spectral moment `m_n = int w^n S(w) dw` (Simpson's rule, 20000 intervals
    /// over the support), m^2 (rad/s)^n.
    pub fn moment(&self, order: i32) -> f64 {
        let (a, b) = self.support();
        let n = 20_000;
        let h = (b - a) / n as f64;
        let f = |w: f64| w.powi(order) * self.density(w);
        let mut sum = f(a) + f(b);
        for i in 1..n {
            let wt = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += wt * f(a + h * i as f64);
        }
        sum * h / 3.0
    }
}
