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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sea::spectrum::dnv_peak_factor;

    const G: f64 = 9.81;

    fn train(seed: u64, stream: u64) -> Discretisation {
        Discretisation {
            components: DEFAULT_COMPONENTS,
            direction: 0.3,
            spreading: None,
            seed,
            stream,
        }
    }

    fn jonswap(hs: f64, tp: f64) -> Spectrum {
        Spectrum::Jonswap {
            hs,
            tp,
            gamma: dnv_peak_factor(hs, tp),
        }
    }

    /// The components hold `Hs^2 / 16` within 1% (the tails left out are 0.7%), one
    /// per bin, every frequency inside its own bin.
    #[test]
    fn components_hold_the_spectrum_energy() {
        for spec in [
            jonswap(6.0, 10.0),
            Spectrum::PiersonMoskowitz { hs: 3.0, tp: 7.0 },
        ] {
            let hs = match spec {
                Spectrum::Jonswap { hs, .. } | Spectrum::PiersonMoskowitz { hs, .. } => hs,
                _ => unreachable!(),
            };
            let comps = discretise(&spec, &train(1, 0), 300.0, G);
            assert_eq!(comps.len(), DEFAULT_COMPONENTS);
            let m0: f64 = comps.iter().map(|c| 0.5 * c.amplitude * c.amplitude).sum();
            let r = m0 / (hs * hs / 16.0);
            assert!((r - 1.0).abs() < 0.01, "m0 ratio {r}");
            let (lo, hi) = band(&spec);
            let dw = (hi - lo) / comps.len() as f64;
            for (j, c) in comps.iter().enumerate() {
                let a = lo + dw * j as f64;
                assert!(
                    c.omega >= a && c.omega <= a + dw,
                    "component {j} outside its bin"
                );
                assert_eq!(c.direction, 0.3);
                assert_eq!(c.k, wave_number(c.omega, 300.0, G));
            }
        }
    }

    /// The same seed gives the same components; another seed or another train's
    /// stream gives other phases and frequencies.
    #[test]
    fn seeds_are_reproducible() {
        let spec = jonswap(4.0, 9.0);
        let a = discretise(&spec, &train(42, 0), 100.0, G);
        let b = discretise(&spec, &train(42, 0), 100.0, G);
        assert_eq!(a, b);
        for other in [train(43, 0), train(42, 1)] {
            let c = discretise(&spec, &other, 100.0, G);
            let same = a.iter().zip(&c).filter(|(x, y)| x.phase == y.phase).count();
            assert_eq!(same, 0);
        }
    }

    /// Simulates the elevation at a point for three hours at 0.25 s, and recovers
    /// `Hs = 4 std(eta)` within 3% and `Tp` within 5% (from a Welch estimate of the
    /// spectrum, nine 20-minute segments, and the `S^4`-weighted peak frequency).
    #[test]
    fn hs_and_tp_recovered_from_an_elevation_record() {
        let (hs, tp) = (5.0, 11.0);
        let comps = discretise(&jonswap(hs, tp), &train(7, 0), f64::INFINITY, G);
        let dt = 0.25;
        let n = (3.0 * 3600.0 / dt) as usize;
        let eta: Vec<f64> = (0..n)
            .map(|i| {
                let t = i as f64 * dt;
                comps
                    .iter()
                    .map(|c| c.amplitude * c.theta(0.0, 0.0, t).cos())
                    .sum()
            })
            .collect();
        let mean = eta.iter().sum::<f64>() / n as f64;
        let var = eta.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / n as f64;
        let hs_rec = 4.0 * var.sqrt();
        assert!((hs_rec / hs - 1.0).abs() < 0.03, "Hs {hs_rec} for {hs}");
        // Welch: segments of 4800 samples, periodogram on a frequency grid.
        let seg = 4800;
        let freqs: Vec<f64> = (1..700).map(|i| 0.2 + i as f64 * 0.002).collect();
        let mut s = vec![0.0; freqs.len()];
        for chunk in eta.chunks_exact(seg) {
            for (fi, &w) in freqs.iter().enumerate() {
                let (mut re, mut im) = (0.0, 0.0);
                for (i, e) in chunk.iter().enumerate() {
                    let (sn, cs) = (w * i as f64 * dt).sin_cos();
                    re += e * cs;
                    im += e * sn;
                }
                s[fi] += re * re + im * im;
            }
        }
        let w4: f64 = s.iter().map(|v| v.powi(4)).sum();
        let wp: f64 = freqs
            .iter()
            .zip(&s)
            .map(|(w, v)| w * v.powi(4))
            .sum::<f64>()
            / w4;
        let tp_rec = TAU / wp;
        assert!((tp_rec / tp - 1.0).abs() < 0.05, "Tp {tp_rec} for {tp}");
    }

    /// The record does not repeat: with frequencies at multiples of `dw` the
    /// normalised autocorrelation is 1 again at `2 pi / dw`; with a random frequency in each bin
    /// it stays at the level of a random sum (standard deviation about 0.1 for 200
    /// JONSWAP components, whose energies are unequal) at every lag from one minute to
    /// three hours: below 0.5 and below five standard deviations.
    #[test]
    fn record_does_not_repeat() {
        let spec = jonswap(6.0, 10.0);
        let comps = discretise(&spec, &train(3, 0), f64::INFINITY, G);
        let e: Vec<f64> = comps.iter().map(|c| c.amplitude * c.amplitude).collect();
        let total: f64 = e.iter().sum();
        let (lo, hi) = band(&spec);
        let rho = |tau: f64, spaced: bool| {
            let dw = (hi - lo) / comps.len() as f64;
            comps
                .iter()
                .enumerate()
                .map(|(j, c)| {
                    let w = if spaced {
                        dw * ((lo / dw).floor() + j as f64 + 1.0)
                    } else {
                        c.omega
                    };
                    e[j] * (w * tau).cos()
                })
                .sum::<f64>()
                / total
        };
        let repeat = TAU / ((hi - lo) / comps.len() as f64);
        assert!(repeat < 3600.0);
        assert!(rho(repeat, true) > 0.999, "equal spacing repeats");
        // The level of a sum of N cosines of random phase: its standard deviation.
        let noise = (e.iter().map(|v| v * v).sum::<f64>() / 2.0).sqrt() / total;
        let (mut worst, mut at): (f64, f64) = (0.0, 0.0);
        let mut tau = 60.0;
        while tau < 3.0 * 3600.0 {
            let r = rho(tau, false).abs();
            if r > worst {
                (worst, at) = (r, tau);
            }
            tau += 0.5;
        }
        eprintln!("largest |autocorrelation| beyond one minute: {worst:.3} at {at} s; noise level {noise:.3}");
        assert!(
            worst < 0.5 && worst < 5.0 * noise,
            "autocorrelation {worst} at {at} s"
        );
    }

    /// Spreading: directions within `+-pi/2` of the mean, spread as `cos^n`: the mean
    /// of `cos^2(b - b_0)` over the components is `(n + 1) / (n + 2)` for `cos^n`
    /// (within sampling error); long-crested without.
    #[test]
    fn spreading_follows_cos_n() {
        let spec = jonswap(4.0, 9.0);
        let n = 4.0;
        let d = Discretisation {
            components: 2000,
            spreading: Some(n),
            ..train(9, 0)
        };
        let comps = discretise(&spec, &d, 100.0, G);
        let mut c2 = 0.0;
        for c in &comps {
            let rel = c.direction - 0.3;
            assert!(rel.abs() <= FRAC_PI_2 + 1e-12);
            c2 += rel.cos().powi(2);
        }
        c2 /= comps.len() as f64;
        assert!((c2 - (n + 1.0) / (n + 2.0)).abs() < 0.01, "mean cos^2 {c2}");
    }
}
