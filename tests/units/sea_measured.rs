//! `src/sea/measured.rs`: an elevation record decomposed by FFT and placed at its
//! reference point gives back the record at its sample times through cablesim's own
//! wave kinematics (`WaveField`), to round-off, and repeats it with its period.

use cablesim::sea::kinematics::WaveField;
use cablesim::sea::measured::{decompose, place};
use cablesim::sea::{SeaState, WaveComponent};
use std::f64::consts::TAU;

/// A synthetic record of `n` samples every `dt` s: three waves off the FFT's bins, a
/// sawtooth (a wide band of harmonics), a component at the Nyquist frequency and a
/// mean of 0.4 m, plus deterministic noise.
fn record(n: usize, dt: f64) -> Vec<f64> {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    (0..n)
        .map(|i| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let noise = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let t = i as f64 * dt;
            0.4 + 1.3 * (0.61 * t + 0.2).cos()
                + 0.5 * (1.37 * t - 1.0).sin()
                + 0.2 * (2.9 * t).cos()
                + 0.1 * ((t % 7.3) / 7.3 - 0.5)
                + 0.03 * if i % 2 == 0 { 1.0 } else { -1.0 }
                + 0.02 * noise
        })
        .collect()
}

/// The sea of `comps` in `depth`, no ramp.
fn sea(comps: Vec<WaveComponent>, depth: f64) -> SeaState {
    SeaState {
        components: comps,
        ..SeaState::still(depth)
    }
}

/// The largest difference between the sea's elevation at `reference` at the record's
/// sample times shifted by `shift` and the record less its mean, over the record's
/// largest value.
fn round_trip(
    n: usize,
    dt: f64,
    t0: f64,
    reference: [f64; 2],
    direction: f64,
    depth: f64,
    shift: f64,
) -> f64 {
    let eta = record(n, dt);
    let d = decompose(&eta, dt);
    assert_eq!(d.harmonics.len(), n / 2);
    assert!((d.period - n as f64 * dt).abs() < 1e-12 * d.period);
    let comps = place(&d.harmonics, t0, reference, direction, depth, 9.81);
    let field = WaveField::new(&sea(comps, depth));
    let scale = eta.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    eta.iter()
        .enumerate()
        .map(|(i, e)| {
            let t = t0 + i as f64 * dt + shift;
            (field.elevation(reference[0], reference[1], t) - (e - d.mean)).abs() / scale
        })
        .fold(0.0f64, f64::max)
}

#[test]
fn a_record_comes_back_at_its_sample_times_from_cablesims_kinematics() {
    // Even and odd lengths (the Nyquist bin only in the first), a record that starts at
    // t0 != 0 measured away from the origin, finite and infinite depth.
    for (n, dt, t0, reference, direction, depth) in [
        (1000usize, 0.1, 12.5, [30.0, -10.0], 0.4, 50.0),
        (257, 0.25, 0.0, [0.0, 0.0], 0.0, f64::INFINITY),
        (64, 0.5, -3.0, [-120.0, 45.0], 2.5, 200.0),
    ] {
        let err = round_trip(n, dt, t0, reference, direction, depth, 0.0);
        println!("{n} samples: largest difference {err:.2e} of the largest elevation");
        assert!(err < 1e-12, "{n} samples: {err:e}");
    }
}

#[test]
fn the_components_repeat_the_record_with_its_period() {
    let (n, dt) = (400usize, 0.2);
    let period = n as f64 * dt;
    for k in [-1.0, 1.0, 3.0] {
        let err = round_trip(n, dt, 5.0, [10.0, 20.0], 1.0, 80.0, k * period);
        assert!(err < 1e-11, "{k} periods on: {err:e}");
    }
}

#[test]
fn a_cosine_on_a_bin_is_one_component_of_its_amplitude_and_phase() {
    let (n, dt) = (128usize, 0.5);
    let period = n as f64 * dt;
    let (a, bin, psi) = (0.75, 5usize, 0.3);
    let eta: Vec<f64> = (0..n)
        .map(|i| 2.0 + a * (TAU * bin as f64 * i as f64 / n as f64 + psi).cos())
        .collect();
    let d = decompose(&eta, dt);
    assert!((d.mean - 2.0).abs() < 1e-14);
    for (k, h) in d.harmonics.iter().enumerate() {
        assert!((h.omega - TAU * (k + 1) as f64 / period).abs() < 1e-14);
        if k + 1 == bin {
            assert!((h.amplitude - a).abs() < 1e-14, "{h:?}");
            assert!((h.phase - psi).abs() < 1e-13, "{h:?}");
        } else {
            assert!(h.amplitude < 1e-14, "bin {}: {h:?}", k + 1);
        }
    }
    // The Nyquist bin of an even record has no partner: its amplitude is |X| / N.
    let alt: Vec<f64> = (0..n)
        .map(|i| if i % 2 == 0 { 0.3 } else { -0.3 })
        .collect();
    let d = decompose(&alt, dt);
    let last = d.harmonics.last().unwrap();
    assert!((last.amplitude - 0.3).abs() < 1e-14, "{last:?}");
    assert!((last.omega - std::f64::consts::PI / dt).abs() < 1e-12);
}

#[test]
fn a_placed_component_passes_its_reference_point_with_the_records_phase() {
    // One harmonic A cos(w (t - t0) + psi) placed at (x_r, y_r): the sea's elevation there
    // is that cosine; a quarter wavelength further along the direction it lags by 90
    // degrees.
    let h = cablesim::sea::measured::Harmonic {
        omega: 0.8,
        amplitude: 1.1,
        phase: -0.7,
    };
    let (t0, r, b, depth) = (7.0, [40.0, -25.0], 0.9, 60.0);
    let comps = place(&[h], t0, r, b, depth, 9.81);
    let field = WaveField::new(&sea(comps.clone(), depth));
    let quarter = TAU / comps[0].k / 4.0;
    for t in [0.0, 3.3, 10.0, 41.7] {
        let want = h.amplitude * (h.omega * (t - t0) + h.phase).cos();
        assert!((field.elevation(r[0], r[1], t) - want).abs() < 1e-13);
        let (x, y) = (r[0] + quarter * b.cos(), r[1] + quarter * b.sin());
        let lag = h.amplitude * (h.omega * (t - t0) + h.phase - TAU / 4.0).cos();
        assert!((field.elevation(x, y, t) - lag).abs() < 1e-12);
    }
}
