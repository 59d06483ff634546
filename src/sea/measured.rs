//! Measured seas: an evenly sampled wave-elevation record decomposed into wave
//! components by a real FFT, and components placed so that they pass a reference
//! point with the record's phases.
//!
//! # The decomposition (docs/src/sea_states.md, "Measured and tabulated seas")
//!
//! A record of `N` samples `eta_n` at `t_n = t_0 + n dt` has the period `T = N dt`
//! (the FFT's: the sample after the last is the first again). Its mean is removed
//! (the mean water level is `z = 0`), and the real FFT `X_k = sum_n (eta_n - mean)
//! e^{-2 pi i k n / N}` gives, for every bin `1 <= k <= N / 2`, one component of
//! angular frequency `w_k = 2 pi k / T`, amplitude `A_k = 2 |X_k| / N` (`|X_k| / N`
//! for the Nyquist bin `k = N / 2` of an even `N`, which has no partner) and phase
//! `psi_k = arg X_k`:
//!
//! ```text
//! eta_n - mean = sum_k A_k cos(w_k (t_n - t_0) + psi_k)
//! ```
//!
//! exactly (the inverse transform written with real cosines). So the components
//! reproduce the record at its sample times, to round-off, and repeat it with period
//! `T` before and after.

use super::dispersion::wave_number;
use super::WaveComponent;
use realfft::RealFftPlanner;
use std::f64::consts::TAU;

/// One harmonic of a record: `A cos(w (t - t_0) + psi)` at the reference point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Harmonic {
    /// Angular frequency `w_k = 2 pi k / T`, rad/s.
    pub omega: f64,
    /// Amplitude `A_k`, m.
    pub amplitude: f64,
    /// Phase `psi_k = arg X_k`, rad, referred to the record's first sample.
    pub phase: f64,
}

/// A record's decomposition (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Decomposition {
    /// The record's mean, m (removed: not a component).
    pub mean: f64,
    /// The period `T = N dt`, s.
    pub period: f64,
    /// The harmonics of bins `1 ..= N / 2`, in order of frequency.
    pub harmonics: Vec<Harmonic>,
}

/// Decomposes the record `eta` (m), sampled every `dt` s, as the module doc states.
/// `eta` must hold at least two samples.
pub fn decompose(eta: &[f64], dt: f64) -> Decomposition {
    let n = eta.len();
    assert!(n >= 2, "a record of {n} samples has no harmonic");
    let mean = eta.iter().sum::<f64>() / n as f64;
    let mut input: Vec<f64> = eta.iter().map(|e| e - mean).collect();
    let mut planner = RealFftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(n);
    let mut spectrum = fft.make_output_vec();
    fft.process(&mut input, &mut spectrum)
        .expect("buffers made by the plan have its lengths");
    let period = n as f64 * dt;
    let harmonics = spectrum
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, x)| {
            let share = if 2 * k == n { 1.0 } else { 2.0 };
            Harmonic {
                omega: TAU * k as f64 / period,
                amplitude: share * x.norm() / n as f64,
                phase: x.im.atan2(x.re),
            }
        })
        .collect();
    Decomposition {
        mean,
        period,
        harmonics,
    }
}

/// The wave components of `harmonics` travelling in `direction` (rad, from +x towards
/// +y) in water `depth` deep (m, may be infinite) under gravity `g`, phased so that at
/// the horizontal point `reference` (m) the elevation is `sum A cos(w (t - t0) + psi)`:
/// with `eta = A cos(k (x cos b + y sin b) - w t + phi)`,
/// `phi = w t0 - psi - k (x_r cos b + y_r sin b)` (taken modulo `2 pi`).
pub fn place(
    harmonics: &[Harmonic],
    t0: f64,
    reference: [f64; 2],
    direction: f64,
    depth: f64,
    g: f64,
) -> Vec<WaveComponent> {
    let (sin_b, cos_b) = direction.sin_cos();
    let along = reference[0] * cos_b + reference[1] * sin_b;
    harmonics
        .iter()
        .map(|h| {
            let k = wave_number(h.omega, depth, g);
            WaveComponent {
                amplitude: h.amplitude,
                omega: h.omega,
                k,
                direction,
                phase: (h.omega * t0 - h.phase - k * along).rem_euclid(TAU),
            }
        })
        .collect()
}
