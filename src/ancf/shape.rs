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

/// How the shape functions of the variable (winch) element of an ALE-ANCF cable change
/// with the element's unstretched length `l` at a fixed **material** point (paper
/// Eqs. 35-36).
///
/// A material point keeps its unstretched distance `v` from the element's material node
/// `m`; the winch is at the other end. With the winch at the element's start (`xi = 0`)
/// the point's coordinate is `xi = 1 - v / l`, at the end `xi = v / l`, so
/// `dxi/dl = c = (1 - xi) / l` or `-xi / l`, and in both cases `D c = -2 c / l`, where
/// `D = d/dl` at fixed `v`. Each shape function is `S_k = l^a_k g_k(xi)` (`a_k = 0` for
/// positions, 1 for slopes), so, with primes for `d/dx`:
///
/// ```text
/// D S_k     = a_k S_k / l + c l dS_k
/// D^2 S_k   = 2 c (a_k - 1) dS_k + c^2 l^2 d2S_k
/// D dS_k    = (a_k - 1) dS_k / l + c l d2S_k
/// D d2S_k   = (a_k - 2) d2S_k / l + c l d3S_k
/// ```
///
/// The material velocity is `S qdot + ldot (D S) q`, and the part of the material
/// acceleration the coordinates' accelerations do not carry is
/// `2 ldot (D S) qdot + lddot (D S) q + ldot^2 (D^2 S) q` (the mass-flow term of Eq. 39).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AleShapeAt {
    /// `D S_k`.
    pub d: [f64; 4],
    /// `D^2 S_k`.
    pub d2: [f64; 4],
    /// `D dS_k`.
    pub d_ds: [f64; 4],
    /// `D d2S_k`.
    pub d_dds: [f64; 4],
}

/// [`AleShapeAt`] of an element of length `l` at `xi`, whose winch node is its start
/// (`winch_at_start`) or its end; `sh` is [`hermite`]`(l, xi)`.
pub fn ale_shape(l: f64, xi: f64, winch_at_start: bool, sh: &ShapeAt) -> AleShapeAt {
    let c = if winch_at_start {
        (1.0 - xi) / l
    } else {
        -xi / l
    };
    let a = [0.0, 1.0, 0.0, 1.0];
    let (l2, l3) = (l * l, l * l * l);
    let d3s = [12.0 / l3, 6.0 / l2, -12.0 / l3, 6.0 / l2];
    let mut out = AleShapeAt::default();
    for k in 0..4 {
        out.d[k] = a[k] * sh.s[k] / l + c * l * sh.ds[k];
        out.d2[k] = 2.0 * c * (a[k] - 1.0) * sh.ds[k] + c * c * l2 * sh.dds[k];
        out.d_ds[k] = (a[k] - 1.0) * sh.ds[k] / l + c * l * sh.dds[k];
        out.d_dds[k] = (a[k] - 2.0) * sh.dds[k] / l + c * l * d3s[k];
    }
    out
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
