//! `src/sea/cut.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::sea::cut::*;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::kinematics::PackedComponent;
use cablesim::sea::kinematics::{wave_kinematics_rates_tau, wave_ramp_rate, WaveField};
use cablesim::sea::poly;
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaState, Stretching};

/// A 200-component JONSWAP sea (Hs 9 m, Tp 13 s, spread) in 320 m: the design
/// check's design sea.
fn field(tolerance: f64) -> WaveField {
    let depth = 320.0;
    let comps = discretise(
        &Spectrum::Jonswap {
            hs: 9.0,
            tp: 13.0,
            gamma: 2.5,
        },
        &Discretisation {
            components: 200,
            direction: 0.5,
            spreading: Some(4.0),
            seed: 3,
            stream: 0,
        },
        depth,
        9.81,
    );
    WaveField::new(&SeaState {
        components: comps,
        cache_tolerance: tolerance,
        ramp_duration: 60.0,
        ..SeaState::still(depth)
    })
}

/// The cut's error against the full sum, at nodes from the surface to the seabed,
/// moving and inside the ramp, is within the stated bound of each quantity; the
/// cut drops components at the deep nodes (so the test could fail). The tolerance
/// here is 0.1, a hundred times the default, so that the cut is aggressive and its
/// errors large enough to see against round-off.
#[test]
fn the_cuts_error_is_within_its_bound() {
    let tol = 0.1;
    let f = field(tol);
    assert!(f.comps.windows(2).all(|w| w[0].k <= w[1].k), "sorted by k");
    let whole: Vec<PackedComponent> = f
        .comps
        .iter()
        .map(|c| PackedComponent {
            cut0: f64::INFINITY,
            cut1: f64::INFINITY,
            cut2: f64::INFINITY,
            ..*c
        })
        .collect();
    let sigma = |p: i32| {
        (f.comps
            .iter()
            .map(|c| (c.amp * c.omega.powi(p)).powi(2))
            .sum::<f64>()
            / 2.0)
            .sqrt()
    };
    let lim = |p: i32| CUT_FRACTION * tol * sigma(p);
    let (l_u, l_a, l_du, l_da) = (lim(1), lim(2), lim(2), lim(3));
    let norm = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    let (mut cut_somewhere, mut worst) = (0, 0.0f64);
    for (i, z) in [-1.0, -5.0, -18.0, -40.0, -80.0, -150.0, -250.0, -319.0]
        .into_iter()
        .enumerate()
    {
        for (t, v) in [
            (200.0, [0.0, 0.0, 0.0]),
            (30.0, [1.5, -0.7, 0.4]),
            (611.3, [-0.3, 2.0, -1.1]),
        ] {
            let p = [10.0 * i as f64, -4.0, z];
            let r = cablesim::sea::kinematics::wave_ramp(t, f.ramp_duration);
            let rr = wave_ramp_rate(t, f.ramp_duration);
            let tau = t - f.t_ref;
            let args = (f.depth, Stretching::Wheeler, r, rr, p, v, tau);
            let (kc, dc) = wave_kinematics_rates_tau(
                &f.comps, args.0, args.1, args.2, args.3, args.4, args.5, args.6,
            );
            let (kw, dw) = wave_kinematics_rates_tau(
                &whole, args.0, args.1, args.2, args.3, args.4, args.5, args.6,
            );
            assert_eq!(kc.eta, kw.eta, "the elevation pass is whole");
            let errs = [
                norm(kc.u, kw.u) / l_u,
                norm(kc.a, kw.a) / l_a,
                norm(dc.u, dw.u) / l_du,
                norm(dc.a, dw.a) / l_da,
            ];
            for (q, e) in errs.iter().enumerate() {
                assert!(*e <= 1.0, "z {z} t {t} quantity {q}: {e} of its bound");
                worst = worst.max(*e);
            }
            if kc != kw {
                cut_somewhere += 1;
            }
        }
    }
    // Deep nodes lose components (and errors are seen), the bound is not vacuous.
    assert!(cut_somewhere >= 9, "cut at {cut_somewhere} nodes");
    assert!(worst > 1e-4, "worst error {worst} of the bound");
}

/// The prefix: all at the surface (and at a NaN depth), fewer and fewer with
/// depth, and each the smallest whose bound is at most 1.
#[test]
fn the_prefix_shrinks_with_depth() {
    let f = field(1e-3);
    let n = f.comps.len();
    let bound = |m: usize, zs: f64, s: f64| {
        let c = &f.comps[m];
        poly::exp_neg(c.k * zs) * (c.cut0 + c.cut1 * s + c.cut2 * 0.01)
    };
    assert_eq!(wave_decay_prefix(&f.comps, 0.0, 1.0, 0.01), n);
    assert_eq!(wave_decay_prefix(&f.comps, f64::NAN, 1.0, 0.01), n);
    let mut last = n;
    for zs in [-10.0, -30.0, -60.0, -120.0, -200.0, -320.0] {
        let m = wave_decay_prefix(&f.comps, zs, 1.0, 0.01);
        assert!(m <= last, "{zs}: {m} after {last}");
        assert!(m == n || bound(m, zs, 1.0) <= 1.0);
        assert!(m == 0 || bound(m - 1, zs, 1.0) > 1.0);
        last = m;
    }
    assert!(last < n / 3, "{last} of {n} at the seabed");
}
