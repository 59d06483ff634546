//! T-N curves (tension range against cycles to failure) and Miner's damage.
//!
//! A curve is `n(s) = a_D s^-m`: `n` cycles of nominal stress range `s` (MPa: the
//! tension range over the component's nominal area) break the component. One cycle of
//! range `s` does damage `1 / n(s) = s^m / a_D`; Miner's rule adds them. The named
//! curves are those of DNV-OS-E301 (Position mooring) for the fatigue limit state;
//! `docs/src/studies.md` cites them and says which values could be checked against the
//! standard's text.

use serde::{Deserialize, Serialize};

/// The named curves: name, `a_D`, `m`.
pub const NAMED_CURVES: [(&str, f64, f64); 4] = [
    ("studless_chain", 6.0e10, 3.0),
    ("stud_chain", 1.2e11, 3.0),
    ("multi_strand_rope", 3.4e14, 4.0),
    ("spiral_rope", 1.7e17, 4.8),
];

/// A T-N curve `n = a_D s^-m`, `s` in MPa.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TnCurve {
    /// The curve's name when it is one of [`NAMED_CURVES`], else `None` (given by its
    /// parameters).
    pub name: Option<String>,
    /// Intercept `a_D` (cycles at 1 MPa).
    pub a_d: f64,
    /// Slope `m`.
    pub m: f64,
}

impl TnCurve {
    /// A named curve ([`NAMED_CURVES`]), or `None` for an unknown name.
    pub fn named(name: &str) -> Option<TnCurve> {
        NAMED_CURVES
            .iter()
            .find(|(n, _, _)| *n == name)
            .map(|&(n, a_d, m)| TnCurve {
                name: Some(n.to_string()),
                a_d,
                m,
            })
    }

    /// Cycles to failure at stress range `s` (MPa).
    pub fn cycles_to_failure(&self, s: f64) -> f64 {
        self.a_d * s.powf(-self.m)
    }

    /// Miner's damage of `count` cycles of tension range `range` (N) on nominal area
    /// `area_m2` (m^2): `count (range / area_m2 / 1e6)^m / a_D`, the form `fatigue.csv`
    /// states.
    pub fn damage(&self, range: f64, area_m2: f64, count: f64) -> f64 {
        let s = range / area_m2 / 1.0e6;
        count * s.powf(self.m) / self.a_d
    }
}

/// The nominal area of a chain of bar diameter `d` (m): two bars carry the load,
/// `2 pi d^2 / 4`, m^2.
pub fn chain_area(d: f64) -> f64 {
    2.0 * std::f64::consts::PI * d * d / 4.0
}

/// The closed-form damage of a narrow-band Gaussian stress process over time `t` (s):
/// ranges are twice Rayleigh amplitudes, so `D = (nu0 t / a_D) (2 sqrt(2) sigma)^m
/// Gamma(1 + m/2)`, with `nu0` the mean zero-up-crossing rate (Hz) and `sigma` the
/// standard deviation of the stress (MPa).
pub fn narrow_band_damage(curve: &TnCurve, nu0: f64, t: f64, sigma: f64) -> f64 {
    nu0 * t / curve.a_d
        * (2.0 * std::f64::consts::SQRT_2 * sigma).powf(curve.m)
        * gamma(1.0 + curve.m / 2.0)
}

/// The gamma function for `x > 0` (Lanczos, g = 7, 9 terms: relative error below
/// 1e-13 over the slopes T-N curves use).
pub fn gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return std::f64::consts::PI / ((std::f64::consts::PI * x).sin() * gamma(1.0 - x));
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    (2.0 * std::f64::consts::PI).sqrt() * t.powf(x + 0.5) * (-t).exp() * a
}
