//! `src/study/channel_stats.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::study::channel_stats::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Samples `k / 1024` with integer `k`, so exact sums are integer sums.
fn fixed_point_series(n: usize, mean: f64, spread: f64, seed: u64) -> Vec<i64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| ((mean + spread * (rng.gen::<f64>() - 0.5)) * 1024.0).round() as i64)
        .collect()
}

#[test]
fn mean_and_std_equal_the_exact_two_pass_values_to_round_off() {
    // A large mean over a small spread (a pretensioned line: 10 MN +- 100 N) is where
    // a one-pass sum of squares loses everything; Welford's update must not.
    let n = 100_000;
    let k = fixed_point_series(n, 1.0e7, 400.0, 1);
    let mut s = ChannelStats::new(0.0);
    for (i, &ki) in k.iter().enumerate() {
        s.push(i as f64, ki as f64 / 1024.0);
    }
    // Exact: mean = sum k / (1024 n), variance = (n sum k^2 - (sum k)^2) / (1024 n)^2.
    let sk: i128 = k.iter().map(|&v| v as i128).sum();
    let skk: i128 = k.iter().map(|&v| (v as i128) * (v as i128)).sum();
    let nn = n as i128;
    let mean = sk as f64 / (1024.0 * n as f64);
    let var = (nn * skk - sk * sk) as f64 / (1024.0 * 1024.0 * (n * n) as f64);
    let std = var.sqrt();
    // Round-off of the streamed update: each step rounds at about eps relative to the
    // mean (for the mean) and to kappa = |mean| / std times the variance (for M2);
    // independent roundings add like a random walk, so the errors stay within a few
    // sqrt(n) eps and sqrt(n) kappa eps (the worst case, n times that, is a bound too
    // loose to tell a stable method from an unstable one).
    let eps = f64::EPSILON;
    let kappa = mean / std;
    let walk = (n as f64).sqrt();
    let e_mean = (s.mean().unwrap() - mean).abs() / mean;
    let e_std = (s.std().unwrap() - std).abs() / std;
    assert!(e_mean < 4.0 * walk * eps, "mean error {e_mean:e}");
    assert!(e_std < walk * kappa * eps, "std error {e_std:e}");
    // Negative control: the textbook one-pass formula sum x^2 / n - mean^2, on the
    // same data, misses that bound by orders of magnitude, so the bound has teeth.
    let (mut sx, mut sxx) = (0.0f64, 0.0f64);
    for &ki in &k {
        let x = ki as f64 / 1024.0;
        sx += x;
        sxx += x * x;
    }
    let naive = (sxx / n as f64 - (sx / n as f64).powi(2)).max(0.0).sqrt();
    let e_naive = (naive - std).abs() / std;
    assert!(
        e_naive > 100.0 * walk * kappa * eps,
        "naive error {e_naive:e}"
    );
}

#[test]
fn extremes_and_their_times_ignore_the_transient_and_keep_the_first_of_ties() {
    let mut s = ChannelStats::new(10.0);
    // A start-up spike in the transient must not count.
    s.push(0.0, 1.0e9);
    s.push(9.99, -1.0e9);
    let xs = [3.0, 7.0, 1.0, 7.0, 2.0, 1.0, 5.0];
    for (i, &x) in xs.iter().enumerate() {
        s.push(10.0 + i as f64, x);
    }
    assert_eq!(s.count(), 7);
    assert_eq!(
        s.max(),
        Some(Extreme {
            value: 7.0,
            time: 11.0
        })
    );
    assert_eq!(
        s.min(),
        Some(Extreme {
            value: 1.0,
            time: 12.0
        })
    );
    assert_eq!(s.duration(), 6.0);
    // Mean 26/7 and std sqrt(sum (x - mean)^2 / 7) by hand: sum x^2 = 138,
    // 138/7 - (26/7)^2 = 290/49.
    assert!((s.mean().unwrap() - 26.0 / 7.0).abs() < 1e-15);
    assert!((s.std().unwrap() - (290.0f64 / 49.0).sqrt()).abs() < 1e-14);
    assert_eq!(ChannelStats::new(0.0).max(), None);
    assert_eq!(ChannelStats::new(0.0).std(), None);
}

#[test]
fn up_crossings_of_an_alternating_signal_by_hand() {
    // -1, 1, -1, 1, ...: the first rise goes from -1 to the running mean -1 itself,
    // which is not a crossing from below; every later rise crosses the running mean
    // (between -1/3 and 0). 2N samples give N - 1 up-crossings.
    let mut s = ChannelStats::new(0.0);
    for i in 0..200 {
        s.push(i as f64, if i % 2 == 0 { -1.0 } else { 1.0 });
    }
    assert_eq!(s.up_crossings(), 99);
    assert_eq!(s.mean_up_crossing_period(), Some(199.0 / 99.0));
}

#[test]
fn up_crossings_match_a_two_pass_count_about_the_final_mean() {
    // A narrow-band random signal (a wave-frequency tension): 40 components around
    // 0.1 Hz with random phases, on a mean far from zero, sampled at 4 Hz for 3 h.
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let comps: Vec<(f64, f64, f64)> = (0..40)
        .map(|_| {
            let f = 0.08 + 0.04 * rng.gen::<f64>();
            (
                rng.gen::<f64>(),
                2.0 * std::f64::consts::PI * f,
                6.3 * rng.gen::<f64>(),
            )
        })
        .collect();
    let dt = 0.25;
    let x: Vec<f64> = (0..43_200)
        .map(|i| {
            let t = i as f64 * dt;
            2.0e6
                + 1.0e5
                    * comps
                        .iter()
                        .map(|(a, w, p)| a * (w * t + p).cos())
                        .sum::<f64>()
        })
        .collect();
    let mut s = ChannelStats::new(0.0);
    for (i, &v) in x.iter().enumerate() {
        s.push(i as f64 * dt, v);
    }
    let m = x.iter().sum::<f64>() / x.len() as f64;
    let two_pass = x.windows(2).filter(|w| w[0] < m && w[1] >= m).count() as u64;
    // About 1000 cycles; the running mean settles within the first few.
    assert!(two_pass > 900 && two_pass < 1300, "{two_pass}");
    let diff = s.up_crossings().abs_diff(two_pass);
    assert!(
        diff <= 3,
        "streamed {} vs two-pass {two_pass}",
        s.up_crossings()
    );
    // Negative control: a level fixed at the first sample (one choice of "a level
    // fixed at the start") is off by far more, which is why it was not chosen.
    let fixed = x.windows(2).filter(|w| w[0] < x[0] && w[1] >= x[0]).count() as u64;
    assert!(
        fixed.abs_diff(two_pass) > 10 * diff.max(1),
        "{fixed} vs {two_pass}"
    );
}

#[test]
fn pooling_equals_one_stream_over_the_union() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let records: Vec<Vec<f64>> = (0..5)
        .map(|r| {
            (0..1000 + 37 * r)
                .map(|_| 5.0e5 + 1.0e4 * r as f64 + 3.0e3 * rng.gen::<f64>())
                .collect()
        })
        .collect();
    let mut pooled = ChannelStats::new(0.0);
    let mut union = ChannelStats::new(0.0);
    let mut crossings = 0;
    for rec in &records {
        let mut s = ChannelStats::new(0.0);
        for (i, &x) in rec.iter().enumerate() {
            s.push(i as f64, x);
            union.push(i as f64, x);
        }
        crossings += s.up_crossings();
        pooled.pool(&s);
    }
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    assert!(rel(pooled.mean().unwrap(), union.mean().unwrap()) < 1e-14);
    assert!(rel(pooled.std().unwrap(), union.std().unwrap()) < 1e-10);
    assert_eq!(pooled.count(), union.count());
    assert_eq!(pooled.max().unwrap().value, union.max().unwrap().value);
    assert_eq!(pooled.min().unwrap().value, union.min().unwrap().value);
    assert_eq!(pooled.up_crossings(), crossings);
    let durations: f64 = records.iter().map(|r| (r.len() - 1) as f64).sum();
    assert_eq!(pooled.duration(), durations);
}

#[test]
fn json_round_trip_keeps_every_bit() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut s = ChannelStats::new(0.5);
    for i in 0..1000 {
        s.push(i as f64 * 0.01, rng.gen::<f64>() * 1.0e6 / 3.0);
    }
    let back: ChannelStats = serde_json::from_str(&serde_json::to_string(&s).unwrap()).unwrap();
    assert_eq!(back, s);
    assert_eq!(back.std().unwrap().to_bits(), s.std().unwrap().to_bits());
}
