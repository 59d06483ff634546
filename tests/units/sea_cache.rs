//! `src/sea/cache.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.
//!
//! Unit tests of the kinematics cache (moved out of `cache.rs`: the cache itself is
//! one concept, its tests another file).

use cablesim::sea::cache::*;
use cablesim::sea::dispersion::wave_number;
use cablesim::sea::kinematics::WaveField;
use cablesim::sea::Stretching;
use cablesim::sea::{SeaState, WaveComponent};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// A broad sea: 60 components from 3 s to 20 s, Pierson-Moskowitz-like amplitudes
/// for Hs ~ 4 m, random directions and phases, in 80 m of water.
fn broad_sea() -> SeaState {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let h = 80.0;
    let wp: f64 = TAU / 10.0;
    let mut comps = Vec::new();
    for j in 0..60 {
        let w = 0.3 + (2.1 - 0.3) * (j as f64 + rng.gen::<f64>()) / 60.0;
        let s = 5.0 / 16.0 * 16.0 * wp.powi(4) * w.powi(-5) * (-1.25 * (wp / w).powi(4)).exp();
        comps.push(WaveComponent {
            amplitude: (2.0 * s * 0.03).sqrt(),
            omega: w,
            k: wave_number(w, h, 9.81),
            direction: rng.gen_range(-0.5..0.5),
            phase: rng.gen_range(0.0..TAU),
        });
    }
    SeaState {
        components: comps,
        ..SeaState::still(h)
    }
}

/// Nodes on a line from the seabed to just under the troughs, moving on circles
/// of 2 m radius with a 7 s period (a line heaving and surging with the waves).
fn node_path(i: usize, t: f64, radius: f64) -> ([f64; 3], [f64; 3]) {
    let n = i as f64;
    let om = TAU / 7.0;
    let (s, c) = (om * t + 0.3 * n).sin_cos();
    (
        [
            -30.0 + 4.0 * n + radius * c,
            1.5 * n,
            -75.0 + 3.5 * n + radius * s,
        ],
        [-radius * om * s, 0.0, radius * om * c],
    )
}

/// Root-mean-square interpolation error of `u` and `a` over nodes and steps,
/// relative to the root-mean-square of the exact values.
fn cache_error(sea: &SeaState, interval: f64, duration: f64, radius: f64) -> (f64, f64) {
    let n = 20;
    let mut cache = WaveCache::with_interval(sea, n, interval);
    let exact = WaveField::new(sea);
    let dt = 0.002;
    let (mut eu, mut nu, mut ea, mut na) = (0.0, 0.0, 0.0, 0.0);
    let mut pos = vec![0.0; 3 * n];
    let mut vel = vec![0.0; 3 * n];
    let steps = (duration / dt) as usize;
    for step in 0..steps {
        let t = 10.0 + step as f64 * dt;
        for i in 0..n {
            let (p, v) = node_path(i, t, radius);
            pos[3 * i..3 * i + 3].copy_from_slice(&p);
            vel[3 * i..3 * i + 3].copy_from_slice(&v);
        }
        cache.refresh_if_due(t, &pos, &vel);
        for i in 0..n {
            let c = cache.node(i, t);
            let e = exact.kinematics([pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]], t);
            for d in 0..3 {
                eu += (c.u[d] - e.u[d]).powi(2);
                nu += e.u[d].powi(2);
                ea += (c.a[d] - e.a[d]).powi(2);
                na += e.a[d].powi(2);
            }
        }
    }
    ((eu / nu).sqrt(), (ea / na).sqrt())
}

/// Nodes at rest: the rule's interval keeps the acceleration's interpolation error
/// within the tolerance, and not far inside it (the rule is not vacuous); halving
/// the interval divides the error by about sixteen (fourth order).
#[test]
fn interpolation_error_is_within_the_tolerance() {
    let sea = broad_sea();
    for &tol in &[1e-3, 1e-2] {
        let dt_r = hermite_rule_interval(&sea.components, tol);
        let (eu, ea) = cache_error(&sea, dt_r, 40.0, 0.0);
        let (_, ea2) = cache_error(&sea, dt_r / 2.0, 40.0, 0.0);
        let order = (ea / ea2).log2();
        eprintln!(
            "at rest, tolerance {tol:e}: interval {dt_r:.4} s, rms error u {eu:.3e}, \
             a {ea:.3e}; half the interval: a {ea2:.3e}, order {order:.2}"
        );
        assert!(
            ea <= tol,
            "acceleration error {ea:e} over tolerance {tol:e}"
        );
        assert!(eu <= tol, "velocity error {eu:e} over tolerance {tol:e}");
        assert!(
            ea >= 0.1 * tol,
            "acceleration error {ea:e}: the rule is far too strict"
        );
        assert!((3.5..4.5).contains(&order), "observed order {order}");
    }
}

/// Nodes moving on circles: the error of predicting each node's path over the
/// interval adds to the interpolation's and, at the rule's interval, dominates it
/// (the rule does not see the nodes' motion; see the module doc). Measured and
/// held to what it is: with the acceleration estimated from the velocity change
/// since the previous refresh, the path error is third order in the interval
/// (halving it divides the error by about seven), on circles of 0.5 m within twice
/// the tolerance, on circles of 2 m within ten times.
#[test]
fn moving_nodes_add_the_path_prediction_error() {
    let sea = broad_sea();
    for (radius, factor) in [(0.5, 2.0), (2.0, 10.0)] {
        for &tol in &[1e-3, 1e-2] {
            let dt_r = hermite_rule_interval(&sea.components, tol);
            let (eu, ea) = cache_error(&sea, dt_r, 40.0, radius);
            let (_, ea2) = cache_error(&sea, dt_r / 2.0, 40.0, radius);
            let order = (ea / ea2).log2();
            eprintln!(
                "circles of {radius} m, tolerance {tol:e}: interval {dt_r:.4} s, rms error \
                 u {eu:.3e}, a {ea:.3e}; half the interval: a {ea2:.3e}, order {order:.2}"
            );
            assert!(
                ea <= factor * tol && eu <= factor * tol,
                "error {ea:e} {eu:e}"
            );
            assert!(
                ea > 0.5 * tol,
                "the path error was expected to show: {ea:e}"
            );
            assert!((2.5..3.5).contains(&order), "observed order {order}");
        }
    }
}

/// Refresh per depth band (`sea::bands`) on the line of [`node_path`] (nodes from
/// 75 m down to the troughs, on circles): after the first decisions the nodes are
/// in several bands, each refreshing on its own rung; a node's interpolant stays
/// within its band's `[t0, t1]` and is continuous across refreshes and band
/// changes; the power-basis cubics the chain kernel reads
/// ([`WaveCache::power_coefficients`]) equal the Hermite interpolation to
/// round-off; and the acceleration's error against exact evaluation, over the
/// scale of the shallowest node's (the sea's scale as near the surface as this line
/// goes: the deeper bands hold every node's error to the tolerance of the sea's
/// scale, `sea::bands`), is of the order of the tolerance (each band refreshes near
/// the rule's interval at its top, so its error is the rule's plus the path's, as
/// in `moving_nodes_add_the_path_prediction_error`), where the one band at the
/// surface's interval is far inside it.
#[test]
fn banded_cache_follows_its_bands_and_its_cubics() {
    let sea = broad_sea();
    let dt = 0.002;
    let plan = cablesim::sea::bands::band_plan(&sea, f64::INFINITY, dt);
    assert!(plan.len() >= 3, "{plan:?}");
    let n = 20;
    let mut banded = WaveCache::with_bands(&sea, n, &plan);
    let mut one =
        WaveCache::with_bands(&sea, n, &cablesim::sea::bands::BandPlan::single(plan.base));
    let exact = WaveField::new(&sea);
    let (mut pos, mut vel) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
    let (mut e_b, mut e_1, mut norm) = (0.0, 0.0, vec![0.0; n]);
    let mut last: Option<Vec<f64>> = None;
    let mut p = Default::default();
    let mut seen = vec![false; plan.len()];
    for step in 0..(30.0 / dt) as usize {
        let t = step as f64 * dt;
        for i in 0..n {
            let (r, v) = node_path(i, t, 1.0);
            pos[3 * i..3 * i + 3].copy_from_slice(&r);
            vel[3 * i..3 * i + 3].copy_from_slice(&v);
        }
        banded.refresh_if_due(t, &pos, &vel);
        one.refresh_if_due(t, &pos, &vel);
        let mut out = vec![0.0; n * CACHE_STRIDE];
        banded.interpolate(t, &mut out);
        banded.power_coefficients(banded.power_ref(), &mut p);
        let tau = t - banded.power_ref();
        for i in 0..n {
            let b = banded.band_of(i);
            seen[b] = true;
            let c = &banded.clocks[b];
            assert!(t >= c.t0 && t <= c.t1, "node {i} band {b} at {t}: {c:?}");
            let e = exact.kinematics([pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]], t);
            let (kb, k1) = (banded.node(i, t), one.node(i, t));
            for d in 0..3 {
                e_b += (kb.a[d] - e.a[d]).powi(2);
                e_1 += (k1.a[d] - e.a[d]).powi(2);
                norm[i] += e.a[d].powi(2);
            }
            for j in i * CACHE_STRIDE..(i + 1) * CACHE_STRIDE {
                let cubic = p[0][j] + tau * (p[1][j] + tau * (p[2][j] + tau * p[3][j]));
                assert!(
                    (cubic - out[j]).abs() <= 1e-9 * (1.0 + out[j].abs()),
                    "node {i} value {j}: cubic {cubic} against {}",
                    out[j]
                );
            }
        }
        // Continuous in time: no jump at a refresh or a band change (a step of
        // 2 ms moves the values by little).
        if let Some(prev) = &last {
            for (j, (a, b)) in out.iter().zip(prev).enumerate() {
                assert!(
                    (a - b).abs() < 0.05,
                    "jump at t = {t} in value {j}: {b} to {a}"
                );
            }
        }
        last = Some(out);
    }
    assert_eq!(banded.breaches, 0);
    // Relative to the shallowest node's root-mean-square acceleration, and (for the
    // record) to the nodes' own.
    let whole: f64 = norm.iter().sum();
    let scale = n as f64 * norm.iter().fold(0.0f64, |a, &b| a.max(b));
    let (own_b, own_1) = ((e_b / whole).sqrt(), (e_1 / whole).sqrt());
    let (e_b, e_1) = ((e_b / scale).sqrt(), (e_1 / scale).sqrt());
    eprintln!(
        "bands {:?}, tops {:?}; rms error of a over the shallowest node's rms a: banded \
         {e_b:.3e}, one band {e_1:.3e} (over the nodes' own: {own_b:.3e}, {own_1:.3e})",
        plan.steps, plan.tops
    );
    assert!(seen.iter().filter(|&&s| s).count() >= 3, "{seen:?}");
    let tol = sea.cache_tolerance;
    assert!(e_b <= 3.0 * tol, "banded {e_b:e} against tolerance {tol:e}");
    assert!(e_1 < e_b, "one band {e_1:e}, banded {e_b:e}");
}

/// A regular wave: the interval is `(384 eps)^(1/4) / w`, and the cache is exact at the
/// refresh times themselves.
#[test]
fn single_component_interval_and_exact_ends() {
    let w = TAU / 9.0;
    let c = WaveComponent {
        amplitude: 1.0,
        omega: w,
        k: wave_number(w, 50.0, 9.81),
        direction: 0.0,
        phase: 0.0,
    };
    let dt_r = hermite_rule_interval(&[c], 1e-3);
    assert!((w * dt_r - (0.384f64).powf(0.25)).abs() < 1e-14);
    let sea = SeaState {
        components: vec![c],
        stretching: Stretching::Wheeler,
        ..SeaState::still(50.0)
    };
    let mut cache = WaveCache::new(&sea, 1);
    let p = [3.0, 0.0, -10.0];
    cache.refresh_if_due(1.0, &p, &[0.0; 3]);
    cache.refresh_if_due(1.0 + 1.5 * dt_r, &p, &[0.0; 3]);
    let exact = WaveField::new(&sea);
    for &t in &[cache.t0(), cache.t1()] {
        assert_eq!(cache.node(0, t), exact.kinematics(p, t));
    }
    assert!(hermite_rule_interval(&[], 1e-3).is_infinite());
}

/// The Hermite weights are exact at both ends, sum to one (a constant is kept) and
/// reproduce a cubic exactly.
#[test]
fn hermite_weights_are_exact_at_the_ends_and_on_cubics() {
    assert_eq!(hermite_weights(0.0, 0.37), [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(hermite_weights(1.0, 0.37), [0.0, 0.0, 1.0, 0.0]);
    let f = |t: f64| 0.3 - 1.2 * t + 0.7 * t * t - 2.1 * t * t * t;
    let df = |t: f64| -1.2 + 1.4 * t - 6.3 * t * t;
    let (t0, t1) = (0.4, 0.95);
    for i in 0..=10 {
        let s = i as f64 / 10.0;
        let w = hermite_weights(s, t1 - t0);
        assert!((w[0] + w[2] - 1.0).abs() < 1e-15);
        let mut o = [0.0];
        wave_cache_hermite(&[f(t0)], &[df(t0)], &[f(t1)], &[df(t1)], w, &mut o);
        let t = t0 + s * (t1 - t0);
        assert!((o[0] - f(t)).abs() < 1e-14, "s = {s}: {} {}", o[0], f(t));
    }
}

/// A single cosine interpolated over the interval of the rule: within the bound
/// `(w dt_r)^4 / 384` of its amplitude, and the bound is nearly reached (it is the
/// error, not a loose bound); the rule's single-component interval is
/// `(384 eps)^(1/4) / w`.
#[test]
fn hermite_interpolation_of_a_cosine_is_within_the_bound() {
    let w = TAU / 6.0;
    let c = WaveComponent {
        amplitude: 1.0,
        omega: w,
        k: wave_number(w, 50.0, 9.81),
        direction: 0.0,
        phase: 0.0,
    };
    let dt_r = hermite_rule_interval(&[c], 1e-3);
    assert!((w * dt_r - (0.384f64).powf(0.25)).abs() < 1e-14);
    let bound = (w * dt_r).powi(4) / 384.0;
    let mut worst = 0.0f64;
    for start in 0..20 {
        let t0 = 0.173 * start as f64;
        let t1 = t0 + dt_r;
        let (f0, f1) = ((w * t0).cos(), (w * t1).cos());
        let (d0, d1) = (-w * (w * t0).sin(), -w * (w * t1).sin());
        for i in 0..=100 {
            let s = i as f64 / 100.0;
            let mut o = [0.0];
            wave_cache_hermite(&[f0], &[d0], &[f1], &[d1], hermite_weights(s, dt_r), &mut o);
            worst = worst.max((o[0] - (w * (t0 + s * dt_r)).cos()).abs());
        }
    }
    eprintln!("worst {worst:.3e}, bound {bound:.3e}");
    assert!(worst <= bound, "error {worst:e} over the bound {bound:e}");
    assert!(
        worst >= 0.5 * bound,
        "error {worst:e} far under the bound {bound:e}"
    );
    assert!(hermite_rule_interval(&[], 1e-3).is_infinite());
    assert_eq!(refresh_interval(&[c], 1e-3), HERMITE_INTERVAL_FACTOR * dt_r);
}
