//! `src/sea/irregular.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::dispersion::wave_number;
use cablesim::sea::irregular::*;
use cablesim::sea::spectrum::dnv_peak_factor;
use cablesim::sea::spectrum::Spectrum;
use std::f64::consts::{FRAC_PI_2, TAU};

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
    eprintln!(
        "largest |autocorrelation| beyond one minute: {worst:.3} at {at} s; noise level {noise:.3}"
    );
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
