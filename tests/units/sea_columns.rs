//! `src/sea/columns.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::columns::*;
use cablesim::sea::dispersion::wave_number;
use cablesim::sea::kinematics::PackedComponent;
use cablesim::sea::kinematics::{wave_kinematics_rates_tau, wave_kinematics_tau};
use cablesim::sea::Stretching;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// `n` packed components from 2.5 s to 20 s with random amplitudes, directions and
/// phases in depth `h`.
fn packed(n: usize, h: f64, seed: u64) -> Vec<PackedComponent> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let hd = if h.is_finite() { h } else { 1e4 };
    (0..n)
        .map(|_| {
            let w = TAU / rng.gen_range(2.5..20.0);
            let k = wave_number(w, hd, 9.81);
            let den = -(-2.0 * k * h).exp_m1();
            let (amp, b) = (rng.gen_range(0.01..0.8), rng.gen_range(-1.5..1.5f64));
            PackedComponent {
                kx: k * b.cos(),
                ky: k * b.sin(),
                k,
                omega: w,
                phase_ref: rng.gen_range(0.0..TAU),
                amp,
                amp_u: amp * w / den,
                amp_a: amp * w * w / den,
                cos_b: b.cos(),
                sin_b: b.sin(),
                ..Default::default()
            }
        })
        .collect()
}

/// The AVX-512 body (8 components a vector) gives the same bits as the AVX2 body
/// (4), values alone and with rates, at points where the decay cut drops different
/// numbers of components (so that the prefix ends at every lane); skipped, with a
/// note, on a CPU without AVX-512.
#[test]
fn avx512_and_avx2_give_the_same_bits() {
    if !cablesim::lanes::avx512_present() {
        eprintln!("no AVX-512 here: only the AVX2 body runs");
        return;
    }
    let mut comps = packed(203, 320.0, 7);
    comps.sort_by(|a, b| a.k.total_cmp(&b.k));
    cablesim::sea::cut::decay_cut_bounds(&mut comps, 1e-3);
    let cols = ComponentColumns::new(&comps);
    let (mut s4, mut s8) = (KinematicsScratch::default(), KinematicsScratch::default());
    for i in 0..40 {
        let z = -0.5 - 8.0 * i as f64;
        for stretching in [Stretching::Wheeler, Stretching::Constant] {
            let at = Point {
                r: 0.9,
                r_rate: 0.01,
                p: [3.0 * i as f64, -2.0, z],
                v: [0.4, -0.3, 0.2],
                tau: 17.0 + 0.3 * i as f64,
            };
            let narrow = dispatch_at::<true>(false, &cols, 320.0, stretching, at, &mut s4);
            let wide = dispatch_at::<true>(true, &cols, 320.0, stretching, at, &mut s8);
            assert_eq!(narrow, wide, "rates at z = {z}");
            let narrow = dispatch_at::<false>(false, &cols, 320.0, stretching, at, &mut s4);
            let wide = dispatch_at::<false>(true, &cols, 320.0, stretching, at, &mut s8);
            assert_eq!(narrow, wide, "values at z = {z}");
        }
    }
}

/// The vectorised values and rates agree with the one-at-a-time reference to
/// round-off (component counts that are and are not multiples of four; deep points
/// where short components drop out; in air; inside the ramp), and its values with
/// [`wave_kinematics_columns`].
#[test]
fn rates_columns_match_the_scalar_reference() {
    let mut scratch = KinematicsScratch::default();
    let mut checked = 0;
    for (n, h, stretching) in [
        (37, 40.0, Stretching::Wheeler),
        (64, f64::INFINITY, Stretching::Wheeler),
        (5, 300.0, Stretching::Constant),
        (200, 60.0, Stretching::Wheeler),
    ] {
        let mut comps = packed(n, h, n as u64);
        // The 200 components sorted with the decay cut's bounds (a tolerance of
        // 0.1, so that the cut drops components at the deep points): the twins
        // cut alike.
        let cut = n == 200;
        if cut {
            comps.sort_by(|a, b| a.k.total_cmp(&b.k));
            cablesim::sea::cut::decay_cut_bounds(&mut comps, 0.1);
        }
        let cols = ComponentColumns::new(&comps);
        for (z, r, r_rate) in [
            (-1.5f64, 1.0, 0.0),
            (-35.0, 1.0, 0.0),
            (-280.0, 0.4, 0.07),
            (2.5, 0.8, -0.02),
        ] {
            let z = if h.is_finite() { z.max(-h) } else { z };
            let (p, v, tau) = ([3.0, -8.0, z], [0.8, 1.1, -0.6], 41.3);
            let (a, da) = wave_kinematics_rates_tau(&comps, h, stretching, r, r_rate, p, v, tau);
            let (b, db) = wave_kinematics_rates_columns(
                &cols,
                h,
                stretching,
                r,
                r_rate,
                p,
                v,
                tau,
                &mut scratch,
            );
            let c = wave_kinematics_columns(&cols, h, stretching, r, p, tau, &mut scratch);
            if cut {
                assert_eq!(b.eta, c.eta, "the elevation pass is whole");
            } else {
                assert_eq!(b, c, "values with and without rates");
            }
            let plain = wave_kinematics_tau(&comps, h, stretching, r, p, tau);
            assert_eq!(c, plain);
            let close = |x: f64, y: f64, scale: f64| (x - y).abs() <= 1e-12 * scale.max(1e-6);
            let norm = |x: [f64; 3]| x.iter().map(|q| q * q).sum::<f64>().sqrt();
            let what = format!("{n} components, h {h}, z {z}");
            assert!(close(a.eta, b.eta, a.eta.abs()), "{what}");
            assert!(close(da.eta, db.eta, da.eta.abs()), "{what}");
            for q in 0..3 {
                assert!(close(a.u[q], b.u[q], norm(a.u)), "u {what}");
                assert!(close(a.a[q], b.a[q], norm(a.a)), "a {what}");
                assert!(close(da.u[q], db.u[q], norm(da.u)), "u rate {what}");
                assert!(close(da.a[q], db.a[q], norm(da.a)), "a rate {what}");
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 16);
}

/// The four lane sums in one AVX register give the bits of the plain four-lane sum
/// (lengths that are and are not multiples of four, values of mixed sign and size,
/// so that the order of additions shows); skipped, with a note, without AVX.
#[test]
fn lane_sums_in_a_register_give_the_same_bits() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for n in 0..70 {
        let v: Vec<f64> = (0..n)
            .map(|_| rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-8..8)))
            .collect();
        let Some(wide) = sum_lanes_wide(&v) else {
            eprintln!("no AVX here: only the plain lane sum runs");
            return;
        };
        assert_eq!(wide.to_bits(), sum_lanes(&v).to_bits(), "{n} values");
    }
}

/// The decay pass that leaves the seabed term out of the components whose term is
/// below round-off (a suffix, `k` ascending) gives the same bits as the one that
/// computes it for every component and selects 0: from the surface, where most of
/// the components drop it, to the seabed, where none does, in finite and infinite
/// depth, values and rates.
#[test]
fn the_seabed_term_left_out_gives_the_same_bits() {
    for h in [320.0, 60.0, f64::INFINITY] {
        let mut comps = packed(203, h, 11);
        comps.sort_by(|a, b| a.k.total_cmp(&b.k));
        cablesim::sea::cut::decay_cut_bounds(&mut comps, 1e-3);
        let split = ComponentColumns::new(&comps);
        let whole = split.clone().without_order();
        let (mut s1, mut s2) = (KinematicsScratch::default(), KinematicsScratch::default());
        let bottom = if h.is_finite() { -h } else { -400.0 };
        for i in 0..=40 {
            let z = 1.0 + (bottom - 1.0) * i as f64 / 40.0;
            for stretching in [Stretching::Wheeler, Stretching::Constant] {
                let (p, v) = ([2.0 * i as f64, -5.0, z], [0.4, -0.3, 0.2]);
                let a = wave_kinematics_rates_columns(
                    &split, h, stretching, 0.9, 0.01, p, v, 23.0, &mut s1,
                );
                let b = wave_kinematics_rates_columns(
                    &whole, h, stretching, 0.9, 0.01, p, v, 23.0, &mut s2,
                );
                assert_eq!(a, b, "h {h}, z {z}");
                let a = wave_kinematics_columns(&split, h, stretching, 0.9, p, 23.0, &mut s1);
                let b = wave_kinematics_columns(&whole, h, stretching, 0.9, p, 23.0, &mut s2);
                assert_eq!(a, b, "values, h {h}, z {z}");
            }
        }
    }
}
