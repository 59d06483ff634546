//! Symmetric banded matrices and their Cholesky factor (the ANCF mass matrix).
//!
//! A cable's coordinates are ordered node by node (`r_k`, then `r'_k`), so an element
//! couples 12 consecutive coordinates and the global mass matrix has half-bandwidth 11.
//! Storage is the lower band, row by row: entry `(i, j)` with `i - BW <= j <= i` lives at
//! `i * (BW + 1) + (j + BW - i)`. Factorisation costs `n BW^2 / 2` multiply-adds, a
//! solve `2 n BW`.

/// Half-bandwidth of the ANCF cable's matrices.
pub const BW: usize = 11;
const W: usize = BW + 1;

/// A symmetric band matrix of half-bandwidth [`BW`] (lower band stored).
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    n: usize,
    a: Vec<f64>,
}

impl Band {
    /// The `n x n` zero matrix.
    pub fn zeros(n: usize) -> Self {
        Self {
            n,
            a: vec![0.0; n * W],
        }
    }
    /// Dimension.
    pub fn n(&self) -> usize {
        self.n
    }
    /// Sets every entry to zero.
    pub fn clear(&mut self) {
        self.a.iter_mut().for_each(|x| *x = 0.0);
    }
    #[inline(always)]
    fn idx(i: usize, j: usize) -> usize {
        debug_assert!(j <= i && i - j <= BW);
        i * W + (j + BW - i)
    }
    /// Entry `(i, j)` (either triangle; zero outside the band).
    #[inline(always)]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        if i - j > BW {
            0.0
        } else {
            self.a[Self::idx(i, j)]
        }
    }
    /// Adds `x` to entry `(i, j)` with `j <= i` (lower triangle).
    #[inline(always)]
    pub fn add_lower(&mut self, i: usize, j: usize, x: f64) {
        self.a[Self::idx(i, j)] += x;
    }
    /// Copies another matrix of the same size into this one.
    pub fn copy_from(&mut self, o: &Band) {
        self.a.copy_from_slice(&o.a);
    }
    /// `y = A x`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let j0 = i.saturating_sub(BW);
            let j1 = (i + BW).min(self.n - 1);
            let mut s = 0.0;
            for (j, xj) in x.iter().enumerate().take(j1 + 1).skip(j0) {
                s += self.get(i, j) * xj;
            }
            *yi = s;
        }
    }
    /// Replaces row and column `p` by those of the identity (direct elimination of a
    /// prescribed coordinate: the caller moves `A[:, p] x_p` to the right-hand side and
    /// sets `b_p = x_p`).
    pub fn eliminate(&mut self, p: usize) {
        let j0 = p.saturating_sub(BW);
        let j1 = (p + BW).min(self.n - 1);
        for i in j0..=j1 {
            let (r, c) = if i >= p { (i, p) } else { (p, i) };
            self.a[Self::idx(r, c)] = if i == p { 1.0 } else { 0.0 };
        }
    }
    /// Factorises in place into the lower Cholesky factor `L` (`A = L L^T`). Fails with
    /// the row index when the matrix is not positive definite.
    pub fn cholesky(&mut self) -> Result<(), usize> {
        let n = self.n;
        for i in 0..n {
            let j0 = i.saturating_sub(BW);
            for j in j0..=i {
                // Row i and row j of L overlap on columns k0..j, contiguous in storage.
                let k0 = j0.max(j.saturating_sub(BW));
                let len = j - k0;
                let (ri, rj) = (Self::idx(i, k0), Self::idx(j, k0));
                let dot: f64 = if len == 0 {
                    0.0
                } else {
                    self.a[ri..ri + len]
                        .iter()
                        .zip(&self.a[rj..rj + len])
                        .map(|(x, y)| x * y)
                        .sum()
                };
                let s = self.a[Self::idx(i, j)] - dot;
                if j == i {
                    if s.is_nan() || s <= 0.0 {
                        return Err(i);
                    }
                    self.a[Self::idx(i, i)] = s.sqrt();
                } else {
                    self.a[Self::idx(i, j)] = s / self.a[Self::idx(j, j)];
                }
            }
        }
        Ok(())
    }
    /// Solves `L L^T x = b` in place (after [`Band::cholesky`]).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let n = self.n;
        for i in 0..n {
            let j0 = i.saturating_sub(BW);
            let mut s = b[i];
            for (j, bj) in b.iter().enumerate().take(i).skip(j0) {
                s -= self.a[Self::idx(i, j)] * bj;
            }
            b[i] = s / self.a[Self::idx(i, i)];
        }
        for i in (0..n).rev() {
            let j1 = (i + BW).min(n - 1);
            let mut s = b[i];
            for (j, bj) in b.iter().enumerate().take(j1 + 1).skip(i + 1) {
                s -= self.a[Self::idx(j, i)] * bj;
            }
            b[i] = s / self.a[Self::idx(i, i)];
        }
    }
}
