//! Seabed contact (docs/src/model/seabed.md, paper Eq. 48 with `zdot` for `z` and a
//! regularised friction law).

use crate::math::{Real, V3};

/// Seabed constants in the precision of the computation.
#[derive(Clone, Copy, Debug, Default)]
pub struct SeabedCoefs<T> {
    /// Seabed height `z_b = -depth`, m.
    pub z: T,
    /// Stiffness per metre of cable, N/m^2.
    pub k: T,
    /// Damping per metre of cable, N s/m^2.
    pub c: T,
    /// Friction coefficient: across the line (transverse), and in every direction
    /// where `mu_axial` equals it.
    pub mu: T,
    /// Friction coefficient along the line (axial); [`seabed_friction_axis`].
    pub mu_axial: T,
    /// Friction regularisation velocity, m/s.
    pub v_eps: T,
}

/// Contact force on a node at `r` moving at `v`, with tributary length `lt`
/// (half the sum of its elements' unstretched lengths). Zero above the seabed.
#[inline(always)]
pub fn seabed_force<T: Real>(s: &SeabedCoefs<T>, lt: T, r: V3<T>, v: V3<T>) -> V3<T> {
    let pen = s.z - r.z;
    if pen <= T::zero() {
        return V3::zero();
    }
    let fz = s.k * lt * pen - s.c * lt * v.z;
    let mut f = V3::new(T::zero(), T::zero(), fz);
    if s.mu > T::zero() {
        // |F_N| is the elastic normal force (paper Eq. 48); friction opposes the
        // sliding velocity and is linear below v_eps, so a node at rest feels none.
        let fnorm = s.k * lt * pen;
        let vh = V3::new(v.x, v.y, T::zero());
        let speed = vh.norm().max(s.v_eps);
        f += vh * (-s.mu * fnorm / speed);
    }
    f
}

/// The contact's damping slopes on a node at `r` moving at `v` (tributary length
/// `lt`): `(c_h, c_h, c_z)`, N s/m, with `c_z = C lt` (normal damping) and
/// `c_h = mu F_N / max(|v_h|, v_eps)` (the regularised friction as a damper, its slope
/// at the node's current speed), so that the damping part of [`seabed_force`] is
/// `-(c_h v_x, c_h v_y, c_z v_z)`. Zero above the seabed.
///
/// The symplectic stepper treats these terms implicitly: it solves
/// `(M + dt diag(c)) a = F` instead of `M a = F` (docs/src/model/seabed.md), so the
/// contact's damping does not bound the explicit step.
#[inline(always)]
pub fn seabed_damping<T: Real>(s: &SeabedCoefs<T>, lt: T, r: V3<T>, v: V3<T>) -> V3<T> {
    let pen = s.z - r.z;
    if pen <= T::zero() {
        return V3::zero();
    }
    let cz = s.c * lt;
    let mut ch = T::zero();
    if s.mu > T::zero() {
        let fnorm = s.k * lt * pen;
        let speed = V3::new(v.x, v.y, T::zero()).norm().max(s.v_eps);
        ch = s.mu * fnorm / speed;
    }
    V3::new(ch, ch, cz)
}

/// One axis of a seabed grid (`n` ticks at `grid[off..off + n]`, increasing): the cell
/// `i` whose ticks bracket `x`, the fraction `f` of the way from tick `i` to `i + 1`,
/// and `1 / (x_{i+1} - x_i)`, or 0 outside the ticks, where `f` is clamped to 0 or 1 and
/// the grid is continued by its edge values (no slope). A single tick: `(0, 0, 0)`.
#[inline(always)]
fn seabed_axis<T: Real>(grid: &[T], off: usize, n: usize, x: T) -> (usize, T, T) {
    if n < 2 {
        return (0, T::zero(), T::zero());
    }
    if x <= grid[off] {
        return (0, T::zero(), T::zero());
    }
    if x >= grid[off + n - 1] {
        return (n - 2, T::one(), T::zero());
    }
    // Bisection: ticks[lo] <= x < ticks[hi].
    let (mut lo, mut hi) = (0usize, n - 1);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if grid[off + mid] <= x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let inv = T::one() / (grid[off + hi] - grid[off + lo]);
    (lo, (x - grid[off + lo]) * inv, inv)
}

/// The seabed of a grid at `(x, y)`: `(z_b, dz_b/dx, dz_b/dy)`, bilinear between the
/// grid points, the edge values continued flat outside the grid. `grid` is packed as
/// `[nx, ny, x_0..x_{nx-1}, y_0..y_{ny-1}, z..]` with `z[i ny + j]` at `(x_i, y_j)`
/// (`model::Bathymetry::packed`).
#[inline]
pub fn seabed_height<T: Real>(grid: &[T], x: T, y: T) -> V3<T> {
    let nx = grid[0].f64() as usize;
    let ny = grid[1].f64() as usize;
    let (i, fx, ix) = seabed_axis(grid, 2, nx, x);
    let (j, fy, iy) = seabed_axis(grid, 2 + nx, ny, y);
    let z0 = 2 + nx + ny;
    let i1 = if nx > 1 { i + 1 } else { i };
    let j1 = if ny > 1 { j + 1 } else { j };
    let z00 = grid[z0 + i * ny + j];
    let z01 = grid[z0 + i * ny + j1];
    let z10 = grid[z0 + i1 * ny + j];
    let z11 = grid[z0 + i1 * ny + j1];
    let one = T::one();
    let zy0 = z00 + (z10 - z00) * fx; // along x at y_j
    let zy1 = z01 + (z11 - z01) * fx; // along x at y_{j+1}
    let z = zy0 + (zy1 - zy0) * fy;
    let dzdx = ((z10 - z00) * (one - fy) + (z11 - z01) * fy) * ix;
    let dzdy = (zy1 - zy0) * iy;
    V3::new(z, dzdx, dzdy)
}

/// The seabed's unit normal (upward) where its slopes are `(g.y, g.z) = (dz/dx, dz/dy)`,
/// and `n_z = 1 / sqrt(1 + |grad z|^2)`.
#[inline(always)]
fn slope_normal<T: Real>(g: V3<T>) -> V3<T> {
    let nz = T::one() / (T::one() + g.y * g.y + g.z * g.z).sqrt();
    V3::new(-g.y * nz, -g.z * nz, nz)
}

/// Contact force on a node at `r` moving at `v` (tributary length `lt`) with a sloped
/// seabed whose height and slopes at the node are `g = (z_b, dz/dx, dz/dy)`
/// ([`seabed_height`]): along the seabed's normal `n`, the penetration
/// `p = (z_b - z) n_z` (the depth below the local tangent plane) gives `K lt p n`, the
/// normal velocity `v.n` the damping `-C lt (v.n) n`, and the sliding velocity
/// `v_t = v - (v.n) n` the regularised friction `-mu K lt p v_t / max(|v_t|, v_eps)`.
/// On a flat seabed (`g = (z_b, 0, 0)`) it is [`seabed_force`]. Zero above the seabed.
#[inline]
pub fn seabed_slope_force<T: Real>(
    s: &SeabedCoefs<T>,
    lt: T,
    r: V3<T>,
    v: V3<T>,
    g: V3<T>,
) -> V3<T> {
    let gap = g.x - r.z;
    if gap <= T::zero() {
        return V3::zero();
    }
    let n = slope_normal(g);
    let fnorm = s.k * lt * gap * n.z;
    let vn = v.dot(n);
    let mut f = n * (fnorm - s.c * lt * vn);
    if s.mu > T::zero() {
        let vt = v - n * vn;
        let speed = vt.norm().max(s.v_eps);
        f += vt * (-s.mu * fnorm / speed);
    }
    f
}

/// The damping slopes of [`seabed_slope_force`]: `(c_n, c_t)` with `c_n = C lt` along
/// the normal and `c_t = mu F_N / max(|v_t|, v_eps)` along the seabed, so that its
/// damping part is `-(c_t I + (c_n - c_t) n n^T) v`; zero above the seabed. The
/// symplectic stepper adds `dt` times that matrix to the node's mass block.
#[inline]
pub fn seabed_slope_damping<T: Real>(
    s: &SeabedCoefs<T>,
    lt: T,
    r: V3<T>,
    v: V3<T>,
    g: V3<T>,
) -> (T, T) {
    let gap = g.x - r.z;
    if gap <= T::zero() {
        return (T::zero(), T::zero());
    }
    let n = slope_normal(g);
    let mut ct = T::zero();
    if s.mu > T::zero() {
        let fnorm = s.k * lt * gap * n.z;
        let vt = v - n * v.dot(n);
        ct = s.mu * fnorm / vt.norm().max(s.v_eps);
    }
    (s.c * lt, ct)
}

/// The seabed's normal at slopes `g` ([`seabed_height`]), for the implicit damping.
#[inline]
pub fn seabed_slope_normal<T: Real>(g: V3<T>) -> V3<T> {
    slope_normal(g)
}

/// The axial part of an anisotropic seabed friction (docs/src/model/seabed.md): on a
/// node of a line whose tangent is `t` (any length; the sum of its elements' unit
/// tangents), in contact with elastic normal force `fnorm` (`K lt p`, 0 off the
/// seabed) along the seabed's unit normal `n`, moving at `v`. Returns `(q, d)`: `q`
/// the line's direction within the seabed plane (unit; zero where the line stands
/// normal to the seabed) and `d = (mu_a - mu_t) F_N / max(|v_t|, v_eps)`, with
/// `v_t = v - (v.n) n` the sliding velocity. The friction is then the isotropic law
/// of [`seabed_force`] / [`seabed_slope_force`] with `mu = mu_t` plus `-d (v.q) q`, and
/// its implicit damping matrix gains `d q q^T`: together
/// `-F_N (mu_a v_a + mu_t v_T) / max(|v_t|, v_eps)` (`v_a = (v.q) q`, `v_T = v_t - v_a`),
/// which is `mu_a F_N` when sliding along the line, `mu_t F_N` across it, and today's
/// isotropic law when `mu_a = mu_t` (`d = 0`).
#[inline]
pub fn seabed_friction_axis<T: Real>(
    s: &SeabedCoefs<T>,
    fnorm: T,
    n: V3<T>,
    v: V3<T>,
    t: V3<T>,
) -> (V3<T>, T) {
    let zero = (V3::zero(), T::zero());
    if !(fnorm > T::zero()) {
        return zero;
    }
    let qp = t - n * t.dot(n);
    let ql = qp.norm();
    if !(ql > T::c(1e-4) * t.norm()) {
        return zero;
    }
    let q = qp * (T::one() / ql);
    let vt = v - n * v.dot(n);
    let d = (s.mu_axial - s.mu) * fnorm / vt.norm().max(s.v_eps);
    (q, d)
}
