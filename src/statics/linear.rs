//! The linear system of one Newton step: block-tridiagonal (a chain, block Thomas) or
//! dense (LU with partial pivoting).

use super::{M3, V};
use nalgebra::{DMatrix, DVector, Vector3};

/// The linear system of one Newton step: block-tridiagonal or dense.
pub(super) enum Lin {
    /// Diagonal, upper (row i, column i+1) and lower (row i, column i-1) 3x3 blocks.
    Chain { d: Vec<M3>, u: Vec<M3>, l: Vec<M3> },
    /// Dense matrix over the free coordinates; `dof[i]` is node i's first row
    /// (`usize::MAX` for held nodes).
    Dense { k: DMatrix<f64>, dof: Vec<usize> },
}

impl Lin {
    pub(super) fn chain(n: usize) -> Self {
        Lin::Chain {
            d: vec![M3::zeros(); n],
            u: vec![M3::zeros(); n],
            l: vec![M3::zeros(); n],
        }
    }

    pub(super) fn dense(free: &[bool]) -> Self {
        let mut dof = vec![usize::MAX; free.len()];
        let mut n = 0;
        for (i, &fr) in free.iter().enumerate() {
            if fr {
                dof[i] = n;
                n += 3;
            }
        }
        Lin::Dense {
            k: DMatrix::zeros(n, n),
            dof,
        }
    }

    pub(super) fn clear(&mut self) {
        match self {
            Lin::Chain { d, u, l } => {
                for x in d.iter_mut().chain(u.iter_mut()).chain(l.iter_mut()) {
                    *x = M3::zeros();
                }
            }
            Lin::Dense { k, .. } => k.fill(0.0),
        }
    }

    /// Adds a block at (row node i, column node j); both free.
    pub(super) fn add(&mut self, i: usize, j: usize, m: &M3) {
        match self {
            Lin::Chain { d, u, l } => {
                if i == j {
                    d[i] += m;
                } else if j == i + 1 {
                    u[i] += m;
                } else if i == j + 1 {
                    l[i] += m;
                } else {
                    unreachable!("a chain couples neighbours only");
                }
            }
            Lin::Dense { k, dof } => {
                let (r0, c0) = (dof[i], dof[j]);
                let mut view = k.fixed_view_mut::<3, 3>(r0, c0);
                view += m;
            }
        }
    }

    /// Largest diagonal entry over free nodes.
    pub(super) fn diag_max(&self, free: &[bool]) -> f64 {
        let mut best = 0.0f64;
        for (i, &fr) in free.iter().enumerate() {
            if !fr {
                continue;
            }
            for c in 0..3 {
                let x = match self {
                    Lin::Chain { d, .. } => d[i][(c, c)],
                    Lin::Dense { k, dof } => k[(dof[i] + c, dof[i] + c)],
                };
                best = best.max(x.abs());
            }
        }
        best
    }

    /// `K x` on the free nodes (zero on held nodes).
    pub(super) fn mul(&self, x: &[V], free: &[bool]) -> Vec<V> {
        let n = x.len();
        let v3 = |v: V| Vector3::new(v.x, v.y, v.z);
        let back = |v: Vector3<f64>| V::new(v[0], v[1], v[2]);
        let mut out = vec![V::zero(); n];
        match self {
            Lin::Chain { d, u, l } => {
                for i in 0..n {
                    if !free[i] {
                        continue;
                    }
                    let mut y = d[i] * v3(x[i]);
                    if i + 1 < n {
                        y += u[i] * v3(x[i + 1]);
                    }
                    if i > 0 {
                        y += l[i] * v3(x[i - 1]);
                    }
                    out[i] = back(y);
                }
            }
            Lin::Dense { k, dof } => {
                let mut xv = DVector::zeros(k.nrows());
                for (i, &di) in dof.iter().enumerate() {
                    if di != usize::MAX {
                        xv.fixed_rows_mut::<3>(di).copy_from(&v3(x[i]));
                    }
                }
                let y = k * xv;
                for (i, &di) in dof.iter().enumerate() {
                    if di != usize::MAX {
                        out[i] = V::new(y[di], y[di + 1], y[di + 2]);
                    }
                }
            }
        }
        out
    }

    /// Solves `(K + mu I) dx = f` on the free nodes; held nodes get `dx = 0`. `None`
    /// when the matrix is singular.
    pub(super) fn solve(&self, mu: f64, f: &[V], free: &[bool]) -> Option<Vec<V>> {
        let n = f.len();
        let shift = M3::identity() * mu;
        match self {
            Lin::Chain { d, u, l } => {
                // Block Thomas: forward elimination, then back substitution.
                let mut dinv = vec![M3::zeros(); n];
                let mut bp = vec![Vector3::zeros(); n];
                for i in 0..n {
                    let (mut di, mut bi) = if free[i] {
                        (d[i] + shift, Vector3::new(f[i].x, f[i].y, f[i].z))
                    } else {
                        (M3::identity(), Vector3::zeros())
                    };
                    if i > 0 {
                        let m = l[i] * dinv[i - 1];
                        di -= m * u[i - 1];
                        bi -= m * bp[i - 1];
                    }
                    dinv[i] = di.try_inverse()?;
                    bp[i] = bi;
                }
                let mut x = vec![Vector3::zeros(); n];
                x[n - 1] = dinv[n - 1] * bp[n - 1];
                for i in (0..n - 1).rev() {
                    x[i] = dinv[i] * (bp[i] - u[i] * x[i + 1]);
                }
                let out: Vec<V> = x.iter().map(|v| V::new(v[0], v[1], v[2])).collect();
                out.iter().all(|v| v.is_finite()).then_some(out)
            }
            Lin::Dense { k, dof } => {
                let m = k.nrows();
                let mut a = k.clone();
                for c in 0..m {
                    a[(c, c)] += mu;
                }
                let mut rhs = DVector::zeros(m);
                for (i, &di) in dof.iter().enumerate() {
                    if di != usize::MAX {
                        rhs[di] = f[i].x;
                        rhs[di + 1] = f[i].y;
                        rhs[di + 2] = f[i].z;
                    }
                }
                let x = a.lu().solve(&rhs)?;
                let out: Vec<V> = dof
                    .iter()
                    .map(|&di| {
                        if di == usize::MAX {
                            V::zero()
                        } else {
                            V::new(x[di], x[di + 1], x[di + 2])
                        }
                    })
                    .collect();
                out.iter().all(|v| v.is_finite()).then_some(out)
            }
        }
    }
}
