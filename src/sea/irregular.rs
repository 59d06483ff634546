//! Irregular seas: a spectrum discretised into wave components with random phases
//! (and, optionally, random directions from a spreading function).
//!
//! # Frequencies: equal bins, a random frequency in each
//!
//! The band `[w_lo, w_hi]` that holds all but 0.2% of the energy below and 0.5% above
//! is cut into `N` bins of equal width `dw`. Component `j` has its bin's energy,
//! `A_j = sqrt(2 int_bin S dw)` (so `sum A_j^2 / 2` is the band's `m0` exactly,
//! wherever the frequency falls in the bin), and a frequency drawn uniformly within
//! its bin.
//!
//! Why not the bin centres: equally spaced frequencies `w_j = w_0 + j dw` make the
//! record repeat after `2 pi / dw` (exactly when `w_0` is a multiple of `dw`; otherwise
//! every component comes back with the same phase shift, the same wave groups again):
//! 200 components between 0.4 and 2.5 rad/s repeat after ten minutes. With a random frequency in each bin no two
//! frequencies are commensurate, so the sum is not periodic at any period; its
//! normalised autocorrelation `sum A_j^2 cos(w_j tau) / sum A_j^2`, which is 1 again at
//! `tau = 2 pi / dw` with equal spacing, stays at the level of the random sum of `N`
//! uncorrelated cosines (standard deviation `sqrt(sum A_j^4 / 2) / sum A_j^2`, about
//! 0.1 for 200 JONSWAP components), for every lag beyond the correlation time (the
//! test below checks it over three hours: at most 0.35 there). The record does not
//! repeat within any run.
//!
//! # Phases and directions
//!
//! Phases are uniform on `[0, 2 pi)`, drawn from ChaCha8 seeded with the sea state's
//! seed, one stream per wave train (so trains are independent and adding a train
//! does not change the others). Draws per component, in order: the position in its
//! bin, the phase, and (with spreading) the direction. Long-crested by default: every
//! component travels in the train's direction. With spreading, each component gets
//! its own direction drawn from the `cos^n` spreading function of DNV-RP-C205,
//! `D(b) ∝ cos^n(b - b_0)` for `|b - b_0| <= pi / 2` (the single-direction-per-
//! frequency method: `N` components still, and no two share a frequency).

use super::dispersion::wave_number;
use super::spectrum::Spectrum;
use super::WaveComponent;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Energy left out below the band, as a fraction of `m0`.
pub const TAIL_BELOW: f64 = 0.002;
/// Energy left out above the band, as a fraction of `m0`.
pub const TAIL_ABOVE: f64 = 0.005;
/// The default number of components of an irregular train.
pub const DEFAULT_COMPONENTS: usize = 200;

/// How one irregular train is discretised.
#[derive(Clone, Debug, PartialEq)]
pub struct Discretisation {
    /// Number of components `N`.
    pub components: usize,
    /// Mean direction of travel `b_0`, rad, from +x towards +y.
    pub direction: f64,
    /// Spreading exponent `n` of `cos^n`, or `None` for long-crested waves.
    pub spreading: Option<f64>,
    /// Seed of the sea state's random numbers.
    pub seed: u64,
    /// The train's stream (its index among the trains).
    pub stream: u64,
}

/// Inverts a cumulative table `(x, c)` (c nondecreasing) at level `level`.
fn invert(x: &[f64], c: &[f64], level: f64) -> f64 {
    let j = c.partition_point(|&v| v < level).clamp(1, c.len() - 1);
    let (c0, c1) = (c[j - 1], c[j]);
    if c1 > c0 {
        x[j - 1] + (level - c0) / (c1 - c0) * (x[j] - x[j - 1])
    } else {
        x[j]
    }
}

/// Interpolates a cumulative table `(x, c)` at `at`.
fn cumulative_at(x: &[f64], c: &[f64], at: f64) -> f64 {
    let j = x.partition_point(|&v| v <= at).clamp(1, x.len() - 1);
    let s = ((at - x[j - 1]) / (x[j] - x[j - 1])).clamp(0.0, 1.0);
    c[j - 1] + s * (c[j] - c[j - 1])
}

/// The band `[w_lo, w_hi]`, rad/s, holding all but [`TAIL_BELOW`] and [`TAIL_ABOVE`]
/// of the spectrum's energy.
pub fn band(spectrum: &Spectrum) -> (f64, f64) {
    let (w, c) = spectrum.cumulative(20_000);
    let total = c[c.len() - 1];
    (
        invert(&w, &c, TAIL_BELOW * total),
        invert(&w, &c, (1.0 - TAIL_ABOVE) * total),
    )
}

/// The components of `spectrum` discretised as the module doc states, in water of
/// depth `depth` (m, may be infinite) under gravity `g` (m/s^2).
pub fn discretise(
    spectrum: &Spectrum,
    d: &Discretisation,
    depth: f64,
    g: f64,
) -> Vec<WaveComponent> {
    let (w, c) = spectrum.cumulative(20_000);
    let total = c[c.len() - 1];
    let lo = invert(&w, &c, TAIL_BELOW * total);
    let hi = invert(&w, &c, (1.0 - TAIL_ABOVE) * total);
    let n = d.components;
    let dw = (hi - lo) / n as f64;
    let mut rng = ChaCha8Rng::seed_from_u64(d.seed);
    rng.set_stream(d.stream);
    let spread = d.spreading.map(spreading_table);
    (0..n)
        .map(|j| {
            let a = lo + dw * j as f64;
            let b = a + dw;
            let energy = cumulative_at(&w, &c, b) - cumulative_at(&w, &c, a);
            let omega = a + dw * rng.gen::<f64>();
            let phase = TAU * rng.gen::<f64>();
            let direction = match &spread {
                Some((x, cdf)) => d.direction + invert(x, cdf, rng.gen::<f64>()),
                None => d.direction,
            };
            WaveComponent {
                amplitude: (2.0 * energy.max(0.0)).sqrt(),
                omega,
                k: wave_number(omega, depth, g),
                direction,
                phase,
            }
        })
        .collect()
}

/// The cumulative distribution of `cos^n(b)` over `[-pi/2, pi/2]` on 4001 points:
/// `(b values, C values)` with `C` from 0 to 1.
fn spreading_table(n: f64) -> (Vec<f64>, Vec<f64>) {
    let m = 4000;
    let h = std::f64::consts::PI / m as f64;
    let x: Vec<f64> = (0..=m).map(|i| -FRAC_PI_2 + h * i as f64).collect();
    let f = |b: f64| b.cos().max(0.0).powf(n);
    let mut c = vec![0.0; m + 1];
    for i in 1..=m {
        c[i] = c[i - 1] + 0.5 * h * (f(x[i - 1]) + f(x[i]));
    }
    let total = c[m];
    c.iter_mut().for_each(|v| *v /= total);
    (x, c)
}
