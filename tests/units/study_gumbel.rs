//! `src/study/gumbel.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::study::gumbel::*;

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
