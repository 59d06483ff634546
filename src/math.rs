//! Small fixed-size vector and symmetric-matrix types, generic over the float type.
//!
//! The physics functions are written once over [`Real`] so the CPU reference path runs
//! them in `f64` and tests can run the very same code in `f32` (the GPU's precision).
//! `glam` and `nalgebra` are not generic in the way these hot loops need (glam has no
//! generic vector; nalgebra's generic `Vector3` pulls `RealField` bounds everywhere),
//! so the handful of operations the loops use live here.

use num_traits::Float;
use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// The float type of a computation: `f64` on the reference path, `f32` for parity
/// checks against the GPU.
pub trait Real: Float + Default + Debug + Send + Sync + AddAssign + SubAssign + 'static {
    /// Converts an `f64` constant or parameter into this type.
    fn c(x: f64) -> Self;
    /// Converts back to `f64` (for output and error reporting).
    fn f64(self) -> f64;
}

impl Real for f64 {
    #[inline(always)]
    fn c(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn f64(self) -> f64 {
        self
    }
}

impl Real for f32 {
    #[inline(always)]
    fn c(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn f64(self) -> f64 {
        self as f64
    }
}

/// A 3-vector (laid out as `[T; 3]`, so that a slice of them can be read as one of
/// arrays without a copy: [`as_arrays`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct V3<T> {
    /// x component.
    pub x: T,
    /// y component.
    pub y: T,
    /// z component (up).
    pub z: T,
}

// SAFETY: `V3<f64>` is `repr(C)` with three `f64` fields and no padding: every bit
// pattern is valid, as for `[f64; 3]`.
unsafe impl bytemuck::Zeroable for V3<f64> {}
unsafe impl bytemuck::Pod for V3<f64> {}

/// `v` as `[x, y, z]` arrays, without a copy (an output time of a large fleet reads
/// the CPU solver's state this way).
pub fn as_arrays(v: &[V3<f64>]) -> &[[f64; 3]] {
    bytemuck::cast_slice(v)
}

impl<T: Real> V3<T> {
    /// A vector from its components.
    #[inline(always)]
    pub fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
    /// The zero vector.
    #[inline(always)]
    pub fn zero() -> Self {
        Self::new(T::zero(), T::zero(), T::zero())
    }
    /// From an `f64` array (converting).
    #[inline(always)]
    pub fn from_f64(a: [f64; 3]) -> Self {
        Self::new(T::c(a[0]), T::c(a[1]), T::c(a[2]))
    }
    /// To an `f64` array.
    #[inline(always)]
    pub fn to_f64(self) -> [f64; 3] {
        [self.x.f64(), self.y.f64(), self.z.f64()]
    }
    /// Dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product.
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Squared Euclidean norm.
    #[inline(always)]
    pub fn norm2(self) -> T {
        self.dot(self)
    }
    /// Euclidean norm.
    #[inline(always)]
    pub fn norm(self) -> T {
        self.norm2().sqrt()
    }
    /// True when every component is finite.
    #[inline(always)]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
    /// Largest absolute component; NaN when any component is NaN (`max` alone drops a
    /// NaN operand, and the blow-up checks rely on NaN failing their comparisons).
    #[inline(always)]
    pub fn max_abs(self) -> T {
        if self.x.is_nan() || self.y.is_nan() || self.z.is_nan() {
            return T::nan();
        }
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }
}

impl<T: Real> Add for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}
impl<T: Real> Sub for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}
impl<T: Real> Neg for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}
impl<T: Real> Mul<T> for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: T) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
}
impl<T: Real> Div<T> for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn div(self, s: T) -> Self {
        Self::new(self.x / s, self.y / s, self.z / s)
    }
}
impl<T: Real> AddAssign for V3<T> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        self.x += o.x;
        self.y += o.y;
        self.z += o.z;
    }
}
impl<T: Real> SubAssign for V3<T> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        self.x -= o.x;
        self.y -= o.y;
        self.z -= o.z;
    }
}

/// A symmetric 3x3 matrix, stored as its six independent entries.
///
/// A node's lumped mass block is `m I + sum_e a_e (I - t_e t_e^T)`: symmetric and
/// positive definite, so it is kept and inverted in this form.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sym3<T> {
    /// Entry (0,0).
    pub xx: T,
    /// Entry (1,1).
    pub yy: T,
    /// Entry (2,2).
    pub zz: T,
    /// Entry (0,1) = (1,0).
    pub xy: T,
    /// Entry (0,2) = (2,0).
    pub xz: T,
    /// Entry (1,2) = (2,1).
    pub yz: T,
}

impl<T: Real> Sym3<T> {
    /// `s I`.
    #[inline(always)]
    pub fn scalar(s: T) -> Self {
        Self {
            xx: s,
            yy: s,
            zz: s,
            xy: T::zero(),
            xz: T::zero(),
            yz: T::zero(),
        }
    }
    /// Adds `a (I - t t^T)` (added mass normal to a unit tangent `t`).
    #[inline(always)]
    pub fn add_normal_projection(&mut self, a: T, t: V3<T>) {
        self.xx += a - a * t.x * t.x;
        self.yy += a - a * t.y * t.y;
        self.zz += a - a * t.z * t.z;
        self.xy -= a * t.x * t.y;
        self.xz -= a * t.x * t.z;
        self.yz -= a * t.y * t.z;
    }
    /// Matrix-vector product.
    #[inline(always)]
    pub fn mul_vec(&self, v: V3<T>) -> V3<T> {
        V3::new(
            self.xx * v.x + self.xy * v.y + self.xz * v.z,
            self.xy * v.x + self.yy * v.y + self.yz * v.z,
            self.xz * v.x + self.yz * v.y + self.zz * v.z,
        )
    }
    /// Determinant.
    #[inline(always)]
    pub fn det(&self) -> T {
        self.xx * (self.yy * self.zz - self.yz * self.yz)
            - self.xy * (self.xy * self.zz - self.yz * self.xz)
            + self.xz * (self.xy * self.yz - self.yy * self.xz)
    }
    /// Solves `self x = b` by the adjugate (the block is small and well conditioned:
    /// its eigenvalues are node mass, node mass plus added mass).
    #[inline(always)]
    pub fn solve(&self, b: V3<T>) -> V3<T> {
        let c_xx = self.yy * self.zz - self.yz * self.yz;
        let c_xy = self.xz * self.yz - self.xy * self.zz;
        let c_xz = self.xy * self.yz - self.xz * self.yy;
        let c_yy = self.xx * self.zz - self.xz * self.xz;
        let c_yz = self.xy * self.xz - self.xx * self.yz;
        let c_zz = self.xx * self.yy - self.xy * self.xy;
        let det = self.xx * c_xx + self.xy * c_xy + self.xz * c_xz;
        let inv = T::one() / det;
        V3::new(
            (c_xx * b.x + c_xy * b.y + c_xz * b.z) * inv,
            (c_xy * b.x + c_yy * b.y + c_yz * b.z) * inv,
            (c_xz * b.x + c_yz * b.y + c_zz * b.z) * inv,
        )
    }
}
