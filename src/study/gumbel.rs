//! The Gumbel law of the seed maxima, and its two fits.
//!
//! The largest value of a long record of a stationary process is, over many records, close
//! to Gumbel distributed: `F(x) = exp(-exp(-(x - mu) / beta))`, location `mu`, scale
//! `beta > 0`. Its mode, the most probable maximum, is `mu`; its mean is
//! `mu + gamma_E beta`; its standard deviation `pi beta / sqrt(6)`; its quantile of
//! probability `p` is `mu - beta ln(-ln p)`.
//!
//! Two fits of a sample of maxima (one per seed):
//! - **moments**: `beta = s sqrt(6) / pi`, `mu = mean - gamma_E beta`, with `s` the sample
//!   standard deviation (divisor `n - 1`);
//! - **maximum likelihood**: `beta` is the root of
//!   `g(beta) = beta - mean + sum x_i w_i / sum w_i`, `w_i = exp(-x_i / beta)`, and then
//!   `mu = -beta ln(mean of w_i)`. `g` rises strictly with `beta` (the weighted mean
//!   rises towards the plain mean as the weights even out), is negative near 0 and
//!   non-negative at `beta = mean - min`, so the root is unique and bisection on that
//!   bracket finds it to round-off, with no starting guess to go wrong. The samples are
//!   shifted by their minimum first, so no weight overflows and the largest is 1.
//!
//! With 10 to 20 seeds both fits have sampling errors of several percent of `beta`; the
//! maximum-likelihood fit has the smaller variance (asymptotically `0.608 beta^2 / n` for
//! `beta` against `1.1 beta^2 / n` for the moments), which is why it is the default.

use serde::{Deserialize, Serialize};

/// The Euler-Mascheroni constant `gamma_E`.
pub const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

/// A Gumbel (type I extreme value) law of maxima.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Gumbel {
    /// Location `mu`, the mode (most probable value), in the channel's unit.
    pub mu: f64,
    /// Scale `beta`, in the channel's unit (0 only for a sample of equal values).
    pub beta: f64,
}

/// Why a sample cannot be fitted.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FitError {
    /// A fit of two parameters needs at least two values.
    #[error("a Gumbel fit needs at least 2 maxima, got {0}")]
    TooFew(usize),
    /// A value is NaN or infinite.
    #[error("maximum {index} is not finite ({value})")]
    NonFinite {
        /// Position in the sample.
        index: usize,
        /// The value.
        value: f64,
    },
}

impl Gumbel {
    /// Cumulative probability `F(x)`.
    pub fn cdf(&self, x: f64) -> f64 {
        (-(-(x - self.mu) / self.beta).exp()).exp()
    }

    /// The most probable value (the mode), `mu`.
    pub fn most_probable(&self) -> f64 {
        self.mu
    }

    /// The quantile of probability `p` in (0, 1): `mu - beta ln(-ln p)`.
    pub fn quantile(&self, p: f64) -> f64 {
        self.mu - self.beta * (-p.ln()).ln()
    }

    /// The mean, `mu + gamma_E beta`.
    pub fn mean(&self) -> f64 {
        self.mu + EULER_GAMMA * self.beta
    }

    /// The standard deviation, `pi beta / sqrt(6)`.
    pub fn std(&self) -> f64 {
        std::f64::consts::PI * self.beta / 6f64.sqrt()
    }

    /// The method-of-moments fit (module documentation).
    pub fn fit_moments(x: &[f64]) -> Result<Gumbel, FitError> {
        check(x)?;
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        let var = x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
        let beta = var.sqrt() * 6f64.sqrt() / std::f64::consts::PI;
        Ok(Gumbel {
            mu: mean - EULER_GAMMA * beta,
            beta,
        })
    }

    /// The maximum-likelihood fit (module documentation).
    pub fn fit_mle(x: &[f64]) -> Result<Gumbel, FitError> {
        check(x)?;
        let n = x.len() as f64;
        let lo = x.iter().copied().fold(f64::INFINITY, f64::min);
        // Shifted samples y >= 0; beta is unchanged by the shift.
        let y: Vec<f64> = x.iter().map(|v| v - lo).collect();
        let ybar = y.iter().sum::<f64>() / n;
        if ybar == 0.0 {
            // All equal: the likelihood grows without bound as beta -> 0.
            return Ok(Gumbel { mu: lo, beta: 0.0 });
        }
        // g(beta) = beta - ybar + sum y w / sum w, w = exp(-y / beta) in (0, 1].
        let g = |beta: f64| {
            let (mut sw, mut syw) = (0.0, 0.0);
            for &v in &y {
                let w = (-v / beta).exp();
                sw += w;
                syw += v * w;
            }
            beta - ybar + syw / sw
        };
        // g(0+) = -ybar + (mean of the y at the minimum, 0) < 0; g(ybar) >= 0.
        let (mut a, mut b) = (0.0_f64, ybar);
        loop {
            let m = 0.5 * (a + b);
            if m <= a || m >= b {
                break;
            }
            if g(m) < 0.0 {
                a = m;
            } else {
                b = m;
            }
        }
        let beta = if a > 0.0 && -g(a) < g(b) { a } else { b };
        let mean_w = y.iter().map(|v| (-v / beta).exp()).sum::<f64>() / n;
        Ok(Gumbel {
            mu: lo - beta * mean_w.ln(),
            beta,
        })
    }
}

fn check(x: &[f64]) -> Result<(), FitError> {
    if x.len() < 2 {
        return Err(FitError::TooFew(x.len()));
    }
    if let Some((index, &value)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(FitError::NonFinite { index, value });
    }
    Ok(())
}

/// Which fit gives a study's most probable maximum, quantile and design tension.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GumbelFit {
    /// Maximum likelihood (the default: the smaller sampling variance).
    #[default]
    Mle,
    /// Method of moments.
    Moments,
}

impl GumbelFit {
    /// `mle` or `moments`.
    pub fn name(self) -> &'static str {
        match self {
            GumbelFit::Mle => "mle",
            GumbelFit::Moments => "moments",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantile_and_most_probable_against_hand_values() {
        let g = Gumbel {
            mu: 100.0,
            beta: 10.0,
        };
        // -ln 0.9 = 0.105360516, ln of that = -2.250367327: 100 + 22.50367327.
        assert!((g.quantile(0.9) - 122.503_673_3).abs() < 1e-6);
        // p = exp(-1): -ln p = 1, ln 1 = 0: the quantile is mu itself.
        assert!((g.quantile((-1f64).exp()) - 100.0).abs() < 1e-12);
        // p = 0.5: the median, mu - beta ln(ln 2) = 100 + 3.665129206.
        assert!((g.quantile(0.5) - 103.665_129_2).abs() < 1e-6);
        assert_eq!(g.most_probable(), 100.0);
        // Mean 100 + 5.772156649, std 10 pi / sqrt 6 = 12.82549830.
        assert!((g.mean() - 105.772_156_65).abs() < 1e-7);
        assert!((g.std() - 12.825_498_30).abs() < 1e-7);
        // The quantile inverts the distribution function.
        for p in [0.01, 0.37, 0.9, 0.999] {
            assert!((g.cdf(g.quantile(p)) - p).abs() < 1e-12);
        }
    }

    #[test]
    fn moments_fit_against_hand_values() {
        // Sample 1, 2, 3: mean 2, s = 1; beta = sqrt(6) / pi = 0.7796968,
        // mu = 2 - 0.5772157 * 0.7796968 = 1.5499468.
        let g = Gumbel::fit_moments(&[1.0, 2.0, 3.0]).unwrap();
        assert!((g.beta - 0.779_696_801_2).abs() < 1e-9, "{g:?}");
        assert!((g.mu - 1.549_946_792_5).abs() < 1e-9, "{g:?}");
    }

    #[test]
    fn mle_solves_the_likelihood_equations() {
        // The two score equations at the fit: d lnL / d mu = 0 gives
        // sum exp(-(x - mu) / beta) = n, and d lnL / d beta = 0 gives
        // sum (x - mu) / beta (1 - exp(-(x - mu) / beta)) = n.
        let x = [
            812.0, 905.5, 860.1, 990.4, 845.2, 1012.9, 877.3, 930.0, 899.9, 850.6,
        ];
        let g = Gumbel::fit_mle(&x).unwrap();
        let n = x.len() as f64;
        let s1: f64 = x.iter().map(|v| (-(v - g.mu) / g.beta).exp()).sum();
        let s2: f64 = x
            .iter()
            .map(|v| {
                let z = (v - g.mu) / g.beta;
                z * (1.0 - (-z).exp())
            })
            .sum();
        assert!((s1 - n).abs() < 1e-9 * n, "{s1}");
        assert!((s2 - n).abs() < 1e-9 * n, "{s2}");
        // And the likelihood is lower a little away from the fit, in both parameters.
        let ll = |mu: f64, beta: f64| -> f64 {
            x.iter()
                .map(|v| {
                    let z = (v - mu) / beta;
                    -beta.ln() - z - (-z).exp()
                })
                .sum()
        };
        let best = ll(g.mu, g.beta);
        for (dm, db) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
            assert!(ll(g.mu + dm, g.beta + db) < best);
        }
    }

    #[test]
    fn fits_are_equivariant_under_shift_and_scale() {
        let x = [3.1, 4.7, 2.2, 5.9, 3.8, 4.1];
        let y: Vec<f64> = x.iter().map(|v| 1.0e6 + 2.5e4 * v).collect();
        for fit in [Gumbel::fit_mle, Gumbel::fit_moments] {
            let a = fit(&x).unwrap();
            let b = fit(&y).unwrap();
            assert!((b.beta - 2.5e4 * a.beta).abs() < 1e-9 * b.beta);
            assert!((b.mu - (1.0e6 + 2.5e4 * a.mu)).abs() < 1e-9 * b.mu);
        }
    }

    #[test]
    fn degenerate_and_bad_samples() {
        assert_eq!(Gumbel::fit_mle(&[5.0]), Err(FitError::TooFew(1)));
        assert_eq!(Gumbel::fit_moments(&[]), Err(FitError::TooFew(0)));
        assert!(matches!(
            Gumbel::fit_mle(&[1.0, f64::NAN]),
            Err(FitError::NonFinite { index: 1, .. })
        ));
        let g = Gumbel::fit_mle(&[7.0, 7.0, 7.0]).unwrap();
        assert_eq!((g.mu, g.beta), (7.0, 0.0));
        let g = Gumbel::fit_moments(&[7.0, 7.0, 7.0]).unwrap();
        assert_eq!((g.mu, g.beta), (7.0, 0.0));
    }
}
