//! Cubic Hermite shape functions of the ANCF cable element and Gauss-Legendre rules.
//!
//! An element of unstretched length `L` has the arc-length coordinate `x` in `[0, L]`,
//! `xi = x / L`, and four vector coordinates `[r_a, r'_a, r_b, r'_b]` (position and
//! slope `dr/dx` at its two nodes). The position along it is
//! `r(x) = S_0 r_a + S_1 r'_a + S_2 r_b + S_3 r'_b` with
//!
//! ```text
//! S_0 = 1 - 3 xi^2 + 2 xi^3        S_1 = L (xi - 2 xi^2 + xi^3)
//! S_2 = 3 xi^2 - 2 xi^3            S_3 = L (-xi^2 + xi^3)
//! ```
//!
//! Each `S_k` multiplies a whole 3-vector (the element's shape matrix is `S (x) I_3`),
//! which is why the mass matrix and the loads below are written per vector coordinate.

/// The four shape functions and their first and second arc-length derivatives at one
/// point of an element.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShapeAt {
    /// `S_k(x)`: 1 for position coordinates, m for slope coordinates.
    pub s: [f64; 4],
    /// `dS_k/dx`: 1/m for positions, 1 for slopes.
    pub ds: [f64; 4],
    /// `d^2 S_k/dx^2`: 1/m^2 for positions, 1/m for slopes.
    pub dds: [f64; 4],
}

/// Shape functions of an element of length `l` (m) at `xi = x / l` in `[0, 1]`.
pub fn hermite(l: f64, xi: f64) -> ShapeAt {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    ShapeAt {
        s: [
            1.0 - 3.0 * x2 + 2.0 * x3,
            l * (xi - 2.0 * x2 + x3),
            3.0 * x2 - 2.0 * x3,
            l * (x3 - x2),
        ],
        ds: [
            (6.0 * x2 - 6.0 * xi) / l,
            1.0 - 4.0 * xi + 3.0 * x2,
            (6.0 * xi - 6.0 * x2) / l,
            3.0 * x2 - 2.0 * xi,
        ],
        dds: [
            (12.0 * xi - 6.0) / (l * l),
            (6.0 * xi - 4.0) / l,
            (6.0 - 12.0 * xi) / (l * l),
            (6.0 * xi - 2.0) / l,
        ],
    }
}

/// The `n`-point Gauss-Legendre rule on `[0, 1]`: `(points, weights)`, weights summing
/// to 1. Exact for polynomials of degree `2 n - 1`. Nodes are the roots of the Legendre
/// polynomial `P_n`, found by Newton's method from Chebyshev first guesses (converged
/// to round-off for any `n` this crate uses).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1, "a Gauss rule needs at least one point");
    let mut xs = Vec::with_capacity(n);
    let mut ws = Vec::with_capacity(n);
    for i in 0..n {
        // Root i of P_n on [-1, 1], in decreasing order.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { x } else { p1 };
            let pm = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (x * pn - pm) / (x * x - 1.0);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        xs.push(0.5 * (1.0 - x)); // increasing on [0, 1]
        ws.push(1.0 / ((1.0 - x * x) * dp * dp)); // 2 / ((1-x^2) P'^2), halved for [0, 1]
    }
    (xs, ws)
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
