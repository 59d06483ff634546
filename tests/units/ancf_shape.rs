//! `src/ancf/shape.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::ancf::shape::*;

#[test]
fn gauss_rules_integrate_their_degree_exactly() {
    for n in 1..=8 {
        let (x, w) = gauss_legendre(n);
        for deg in 0..2 * n {
            let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(deg as i32)).sum();
            let exact = 1.0 / (deg as f64 + 1.0);
            assert!(
                (q - exact).abs() < 1e-14,
                "n {n} degree {deg}: {q} vs {exact}"
            );
        }
        assert!(x.windows(2).all(|p| p[0] < p[1]));
    }
}

/// The ALE derivatives are the derivatives in `l` at a fixed distance from the
/// material node, by central differences.
#[test]
fn ale_shape_derivatives_match_finite_differences() {
    for &start in &[true, false] {
        for &(l, v) in &[(50.0, 12.0), (7.0, 6.5), (20.0, 0.3)] {
            let xi_of = |l: f64| if start { 1.0 - v / l } else { v / l };
            let at = |l: f64| hermite(l, xi_of(l));
            let a = ale_shape(l, xi_of(l), start, &at(l));
            let h = 1e-4 * l;
            let (m, c, p) = (at(l - h), at(l), at(l + h));
            let close = |x: f64, y: f64| (x - y).abs() <= 1e-6 * (1.0 + y.abs());
            for k in 0..4 {
                let d = (p.s[k] - m.s[k]) / (2.0 * h);
                let d2 = (p.s[k] - 2.0 * c.s[k] + m.s[k]) / (h * h);
                let dds = (p.ds[k] - m.ds[k]) / (2.0 * h);
                let ddds = (p.dds[k] - m.dds[k]) / (2.0 * h);
                assert!(
                    close(a.d[k], d),
                    "start {start} l {l} k {k}: D S {} vs {d}",
                    a.d[k]
                );
                assert!(
                    close(a.d2[k], d2),
                    "start {start} l {l} k {k}: D2 S {} vs {d2}",
                    a.d2[k]
                );
                assert!(
                    close(a.d_ds[k], dds),
                    "start {start} k {k}: D dS {} vs {dds}",
                    a.d_ds[k]
                );
                assert!(
                    close(a.d_dds[k], ddds),
                    "start {start} k {k}: D d2S {} vs {ddds}",
                    a.d_dds[k]
                );
            }
        }
    }
}

#[test]
fn hermite_interpolates_nodes_and_slopes_and_derivatives_agree() {
    let l = 7.0;
    let a = hermite(l, 0.0);
    let b = hermite(l, 1.0);
    assert_eq!(a.s, [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(b.s, [0.0, 0.0, 1.0, 0.0]);
    assert_eq!(a.ds, [0.0, 1.0, 0.0, 0.0]);
    assert_eq!(b.ds, [0.0, 0.0, 0.0, 1.0]);
    let h = 1e-6;
    for &xi in &[0.1, 0.37, 0.8] {
        let (m, c, p) = (hermite(l, xi - h), hermite(l, xi), hermite(l, xi + h));
        for k in 0..4 {
            let d = (p.s[k] - m.s[k]) / (2.0 * h * l);
            let dd = (p.ds[k] - m.ds[k]) / (2.0 * h * l);
            assert!((d - c.ds[k]).abs() < 1e-8, "dS_{k}");
            assert!((dd - c.dds[k]).abs() < 1e-8, "d2S_{k}");
        }
        // A straight line r = x reproduces exactly: positions 0, L; slopes 1.
        let r = c.s[1] + c.s[2] * l + c.s[3];
        assert!((r - xi * l).abs() < 1e-12);
    }
}
