//! The older element frames (paper Sec. 2.1-2.3, 2.6): Euler, Frenet and RVEF.
//!
//! Each frame writes the GLMF loads (docs/src/model/glmf.md) through an orthonormal element frame
//! `A = [c0 c1 c2]` (columns in global components, one of them along the element):
//! the relative velocity `v_rel = U - (v_a + v_b)/2` and the water acceleration are
//! taken into the frame (`A^T v`), the drag and water-acceleration laws are applied to
//! the frame components, and the result comes back (`A f_local`). Weight, tension
//! (from [`axial_force`] along the element axis `E/|E|`) and the mass terms are those
//! of [`glmf_element`](super::element::glmf_element): the frame only carries the
//! hydrodynamic loads, as in the paper (Eqs. 11, 19, 31).
//!
//! # The frames
//! - **Euler** (Eqs. 7-9): `theta = atan(dx/dz)`, then `phi = atan(-dy cos(theta)/dz)`
//!   when `cos(theta) > sin(theta)`, else `phi = atan(-dy sin(theta)/dx)` (Eq. 9 is
//!   garbled in the paper; its `r_{i-1}` is read as `r_i`, so `-dy = r_i^y - r_{i+1}^y`).
//!   `A` is Eq. 7. Because `atan` returns angles in `(-pi/2, pi/2)`, the third column is
//!   `sign(dz) E/|E|`, not always `+E/|E|`; the loads do not depend on that sign (both
//!   drag terms are odd in the tangential component and the normal plane is the same).
//! - **Frenet** (Eqs. 13-16): `alpha = r_virtual - r_a`, `beta = r_b - r_virtual`,
//!   `t = (alpha + beta)/|alpha + beta|`, `n' = (I - t t^T)(alpha - beta)`,
//!   `n = n'/|n'|`, `b = t x n`, `A = [t n b]` (the tangent is the *first* column).
//!   The virtual node comes from [`frenet_virtual_node`].
//! - **RVEF** (Eqs. 17-19): `z = E/|E|`, `x = z x v_rel / |z x v_rel|`, `y = z x x`,
//!   `A = [x y z]`; the drag is Eq. 19 as printed: `-1/2 rho Cn d l |z x v_rel|^2` along
//!   `y` and `1/2 rho Ct pi d l |z.v_rel| (z.v_rel)` along `z`. Eq. 29 shows it equals
//!   the GLMF drag; the tests check that to round-off.
//!
//! # The drag law in frame components (Euler and Frenet)
//! With `v_t` the tangential and `v_n` the two normal frame components of `v_rel`, the
//! default law ([`NormalDrag::Vector`]) is `f_n = 1/2 rho Cn d l |v_n| v_n` (a 2-vector)
//! and `f_t = 1/2 rho Ct pi d l |v_t| v_t`. The paper's Eq. 11 prints a per-axis form,
//! `1/2 rho Cn d l |v_x| v_x` and the same in `y` ([`NormalDrag::PerAxis`]). The
//! per-axis form depends on the frame's roll about the element: for a given `v_n` its
//! magnitude `(v_x^4 + v_y^4)^(1/2)` swings between `|v_n|^2` (flow along `x` or `y`)
//! and `|v_n|^2 / sqrt 2` (flow at 45 degrees), and it is not parallel to `v_n`. The
//! Euler frame's roll is fixed by the Z-Y-X convention (first angle 0), the Frenet
//! frame's by the cable's curvature, neither by the flow, so the per-axis form makes
//! the drag an artefact of the convention; it also would not reduce to Eqs. 19-20,
//! whereas the paper reports that the Euler frame reproduces the RVEF and GLMF
//! (Figs. 8-10). The vector form is therefore the default, so that wherever a frame is
//! defined its loads equal the GLMF loads to round-off. The per-axis form is kept, via
//! [`frame_element_with`], only to measure that difference. The RVEF ignores the
//! choice: its `x` component of `v_rel` is zero by construction, where both forms
//! coincide with Eq. 19.
//!
//! # Singularities (paper Sec. 2.6, Table 2) and the threshold
//! A frame is reported singular (`Err(reason)`, never NaN) when the quantity it divides
//! by is zero *relative to its own scale*, with the one relative tolerance
//! [`singular_tolerance`] `= sqrt(eps)` (1.5e-8 in `f64`, 3.5e-4 in `f32`):
//!
//! - every frame: the element length `l = norm(E)` (zero-length element), scale `l0`;
//! - Euler: `dz`, the denominator of `theta` and of `phi`'s first branch, scale `l`
//!   (a horizontal element, including one along `y`); and `dx`, the denominator of
//!   `phi`'s second branch, scale `l` (only reached with `theta >= pi/4`, where
//!   `abs(dx) >= abs(dz)`, so in exact arithmetic the `dz` test already covers it);
//! - Frenet: `norm(n')`, scale `norm(alpha) + norm(beta)` (the element and its virtual
//!   node collinear: a straight cable);
//! - RVEF: `norm(z x v_rel)`, scale `norm(U) + norm((v_a + v_b)/2)` (`v_rel` parallel to
//!   the element, or zero: a cable at rest in still water, or drifting with the water).
//!
//! Why `sqrt(eps)`: the round-off in a frame's axes is about `eps` times scale over the
//! denominator (e.g. `cos(theta)` near `theta = -pi/2` carries a relative error
//! `eps l/|dz|`, which `phi` inherits; the direction of `z x v_rel` carries an error
//! `eps (|U| + |v_mid|)/|z x v_rel|`, since `v_rel` is itself a difference). Below `sqrt(eps)` the
//! frame would be determined to fewer than half the working digits, i.e. by round-off
//! rather than by the configuration; above it, at most half the digits are lost. The
//! RVEF scale is the velocities `v_rel` is computed from, not `|v_rel|`, so a `v_rel`
//! that is pure cancellation noise (a cable drifting with the current) counts as zero.
//!
//! Two round-off refinements that change nothing mathematically: the RVEF's `x` and
//! the Frenet `n` are projected once more onto the tangent's normal plane before being
//! normalised (Gram-Schmidt twice), so `A` is orthonormal to round-off even close to the
//! singularity; the RVEF loads then match the GLMF loads to round-off right up to the
//! threshold. The Euler frame, built from angles, is always orthonormal, but near
//! `dz = 0` its axis inherits the `l/|dz|` amplification above; this is intrinsic to
//! Eqs. 8-9 and is left as the paper has it.
//!
//! The GLMF itself has no frame; a zero-length element makes `t = E/0`, so
//! [`glmf_element`](super::element::glmf_element) returns non-finite loads, which the
//! steppers' blow-up check reports as a divergence naming the cable, node and time.

use super::element::{axial_force, Coefs, ElementInput, ElementLoads, ExternalLoads};
use crate::math::{Real, V3};

/// An element frame used to express the hydrodynamic loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Frame {
    /// Two Euler angles from arctangents of node differences (Eqs. 7-9).
    Euler,
    /// Tangent/normal/binormal of a spline through the cable's nodes (Eqs. 13-16).
    Frenet,
    /// Relative-velocity element frame (Eqs. 17-19).
    Rvef,
}

impl Frame {
    /// Lower-case name, as in scenario files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Frame::Euler => "euler",
            Frame::Frenet => "frenet",
            Frame::Rvef => "rvef",
        }
    }
}

/// How the normal drag is written in frame components (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum NormalDrag {
    /// `1/2 rho Cn d l |v_n| v_n` on the normal 2-vector: independent of the frame's roll,
    /// equal to the GLMF drag. The default.
    #[default]
    Vector,
    /// `1/2 rho Cn d l |v_i| v_i` on each normal axis separately, as Eq. 11 prints it:
    /// depends on the frame's roll about the element. For comparison only.
    PerAxis,
}

/// The relative tolerance below which a frame's defining denominator counts as zero:
/// `sqrt(eps)` of the float type (see the module doc for the scales it multiplies).
#[inline(always)]
pub fn singular_tolerance<T: Real>() -> T {
    T::epsilon().sqrt()
}

/// An orthonormal element frame `A = [c0 c1 c2]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameAxes<T> {
    /// The columns of `A`, in global components.
    pub cols: [V3<T>; 3],
    /// Which column lies along the element: 2 for the Euler frame and the RVEF (their
    /// `z`), 0 for the Frenet frame (its `t`).
    pub tangent: usize,
}

impl<T: Real> FrameAxes<T> {
    /// Frame components `A^T v` of a global vector.
    #[inline(always)]
    pub fn to_local(&self, v: V3<T>) -> V3<T> {
        V3::new(
            self.cols[0].dot(v),
            self.cols[1].dot(v),
            self.cols[2].dot(v),
        )
    }
    /// Global components `A f` of a vector given in the frame.
    #[inline(always)]
    pub fn to_global(&self, f: V3<T>) -> V3<T> {
        self.cols[0] * f.x + self.cols[1] * f.y + self.cols[2] * f.z
    }
    /// The two normal column indices, in increasing order.
    #[inline(always)]
    fn normals(&self) -> (usize, usize) {
        match self.tangent {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        }
    }
}

/// `!(x > threshold)`: true when `x` is at or below the threshold, and for NaN.
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn not_above<T: Real>(x: T, threshold: T) -> bool {
    !(x > threshold)
}

#[inline(always)]
fn arr<T: Real>(v: V3<T>) -> [T; 3] {
    [v.x, v.y, v.z]
}

#[inline(always)]
fn vec3<T: Real>(a: [T; 3]) -> V3<T> {
    V3::new(a[0], a[1], a[2])
}

/// The element frame `A` of `frame` for element `e`, or why it is singular.
/// `virtual_mid` is the Frenet frame's virtual node; the other frames ignore it.
pub fn element_frame<T: Real>(
    frame: Frame,
    e: &ElementInput<T>,
    virtual_mid: V3<T>,
) -> Result<FrameAxes<T>, String> {
    let tol = singular_tolerance::<T>();
    let d = e.rb - e.ra;
    let l = d.norm();
    if not_above(l, tol * e.l0) || not_above(l, T::zero()) {
        return Err(format!(
            "zero-length element (l = {:.3e} m, l0 = {:.3e} m): its axis is undefined",
            l.f64(),
            e.l0.f64()
        ));
    }
    match frame {
        Frame::Euler => euler_frame(d, l, tol),
        Frame::Frenet => frenet_frame(e, virtual_mid, tol),
        Frame::Rvef => rvef_frame(e, d / l, tol),
    }
}

/// Eqs. 7-9 (with Eq. 9's `r_{i-1}` read as `r_i`).
fn euler_frame<T: Real>(d: V3<T>, l: T, tol: T) -> Result<FrameAxes<T>, String> {
    let (dx, dy, dz) = (d.x, d.y, d.z);
    if not_above(dz.abs(), tol * l) {
        return Err(format!(
            "Euler angle theta = atan(dx/dz) undefined: horizontal element \
             (dz = {:.3e} m, |dz|/l = {:.3e} <= {:.1e})",
            dz.f64(),
            (dz.abs() / l).f64(),
            tol.f64()
        ));
    }
    let theta = (dx / dz).atan();
    let (st, ct) = theta.sin_cos();
    let phi = if ct > st {
        // First branch: the denominator is dz, checked above.
        (-dy * ct / dz).atan()
    } else {
        // Second branch (theta >= pi/4, so |dx| >= |dz| mathematically; checked anyway).
        if not_above(dx.abs(), tol * l) {
            return Err(format!(
                "Euler angle phi = atan(-dy sin(theta)/dx) undefined \
                 (dx = {:.3e} m, |dx|/l = {:.3e} <= {:.1e}, theta = {:.6} rad)",
                dx.f64(),
                (dx.abs() / l).f64(),
                tol.f64(),
                theta.f64()
            ));
        }
        (-dy * st / dx).atan()
    };
    let (sp, cp) = phi.sin_cos();
    Ok(FrameAxes {
        cols: [
            V3::new(ct, T::zero(), -st),
            V3::new(st * sp, cp, ct * sp),
            V3::new(st * cp, -sp, ct * cp),
        ],
        tangent: 2,
    })
}

/// Eqs. 14-16.
fn frenet_frame<T: Real>(
    e: &ElementInput<T>,
    virtual_mid: V3<T>,
    tol: T,
) -> Result<FrameAxes<T>, String> {
    if !virtual_mid.is_finite() {
        return Err(format!(
            "non-finite virtual node {:?}",
            virtual_mid.to_f64()
        ));
    }
    let alpha = virtual_mid - e.ra;
    let beta = e.rb - virtual_mid;
    let s = alpha + beta;
    let sn = s.norm();
    let scale = alpha.norm() + beta.norm();
    if not_above(sn, tol * scale) {
        return Err(format!(
            "|alpha + beta| = {:.3e} m is zero: tangent undefined",
            sn.f64()
        ));
    }
    let t = s / sn;
    let dab = alpha - beta;
    let np = dab - t * t.dot(dab);
    let npn = np.norm();
    if not_above(npn, tol * scale) {
        return Err(format!(
            "element and its virtual node collinear (straight cable): \
             |n'| = {:.3e} m <= {:.1e} x (|alpha| + |beta|) = {:.3e} m",
            npn.f64(),
            tol.f64(),
            (tol * scale).f64()
        ));
    }
    let n1 = np / npn;
    let n2 = n1 - t * t.dot(n1); // second projection: n orthogonal to t to round-off
    let n = n2 / n2.norm();
    let b = t.cross(n);
    Ok(FrameAxes {
        cols: [t, n, b],
        tangent: 0,
    })
}

/// Eqs. 17-18; `z` is the unit element axis.
fn rvef_frame<T: Real>(e: &ElementInput<T>, z: V3<T>, tol: T) -> Result<FrameAxes<T>, String> {
    let half = T::c(0.5);
    let vm = (e.va + e.vb) * half;
    let vrel = e.current - vm; // the very expression of glmf_external
    let w = z.cross(vrel);
    let wn = w.norm();
    let scale = e.current.norm() + vm.norm();
    if not_above(wn, tol * scale) {
        let vn = vrel.norm();
        return Err(if not_above(vn, tol * scale) {
            format!(
                "relative velocity zero (|v_rel| = {:.3e} m/s, |U| + |v_mid| = {:.3e} m/s): \
                 an element at rest in still water has no RVEF",
                vn.f64(),
                scale.f64()
            )
        } else {
            format!(
                "relative velocity parallel to the element (|z x v_rel| = {:.3e} m/s \
                 <= {:.1e} x (|U| + |v_mid|) = {:.3e} m/s, |v_rel| = {:.3e} m/s)",
                wn.f64(),
                tol.f64(),
                (tol * scale).f64(),
                vn.f64()
            )
        });
    }
    let x0 = w / wn;
    let x1 = x0 - z * z.dot(x0); // second projection: x orthogonal to z to round-off
    let x = x1 / x1.norm();
    let y = z.cross(x);
    Ok(FrameAxes {
        cols: [x, y, z],
        tangent: 2,
    })
}

/// External loads (drag, water acceleration, wet weight) of element `e` evaluated
/// through `frame`, with the normal drag written as `law` says (the RVEF always uses
/// Eq. 19). Returns the reason when the frame is singular.
pub fn frame_external<T: Real>(
    frame: Frame,
    law: NormalDrag,
    c: &Coefs<T>,
    e: &ElementInput<T>,
    virtual_mid: V3<T>,
) -> Result<ExternalLoads<T>, String> {
    let ax = element_frame(frame, e, virtual_mid)?;
    let l = (e.rb - e.ra).norm();
    let half = T::c(0.5);
    let vrel = e.current - (e.va + e.vb) * half;
    let k = ax.tangent;
    let (i, j) = ax.normals();
    let vl = arr(ax.to_local(vrel));
    let vt = vl[k];
    let mut fn_local = [T::zero(); 3];
    let mut ft_local = [T::zero(); 3];
    ft_local[k] = c.drag_t * l * vt.abs() * vt;
    match (frame, law) {
        (Frame::Rvef, _) => {
            // Eq. 19: nothing along x; -1/2 rho Cn d l |z x v_rel|^2 along y.
            let w2 = ax.cols[2].cross(vrel).norm2();
            fn_local[j] = -(c.drag_n * l * w2);
        }
        (_, NormalDrag::Vector) => {
            let vn = (vl[i] * vl[i] + vl[j] * vl[j]).sqrt();
            fn_local[i] = c.drag_n * l * vn * vl[i];
            fn_local[j] = c.drag_n * l * vn * vl[j];
        }
        (_, NormalDrag::PerAxis) => {
            fn_local[i] = c.drag_n * l * vl[i].abs() * vl[i];
            fn_local[j] = c.drag_n * l * vl[j].abs() * vl[j];
        }
    }
    // Eq. 11: (1 + Cm) rho A l0 A diag(normal, normal, 0) A^T a_w, plus the axial part
    // (1 + Cat) rho A l0 A diag(0, 0, axial) A^T a_w.
    let mut al = arr(ax.to_local(e.water_accel));
    let mut at = [T::zero(); 3];
    at[k] = al[k];
    al[k] = T::zero();
    Ok(ExternalLoads {
        drag_n: ax.to_global(vec3(fn_local)),
        drag_t: ax.to_global(vec3(ft_local)),
        froude_krylov: ax.to_global(vec3(al)) * (c.froude_krylov * e.l0)
            + ax.to_global(vec3(at)) * (c.froude_krylov_t * e.l0),
        wet_weight: V3::new(T::zero(), T::zero(), c.wet_weight_z * e.l0),
    })
}

/// [`frame_element`] with a chosen normal-drag law.
pub fn frame_element_with<T: Real>(
    frame: Frame,
    law: NormalDrag,
    c: &Coefs<T>,
    e: &ElementInput<T>,
    virtual_mid: V3<T>,
) -> Result<ElementLoads<T>, String> {
    let ext = frame_external(frame, law, c, e, virtual_mid)?;
    let d = e.rb - e.ra;
    let l = d.norm();
    let t = d / l;
    let half = T::c(0.5);
    let out = ElementLoads {
        t,
        tension: axial_force(c, l, e.l0, t, e.vb - e.va),
        f_half: ext.total() * half,
        half_mass: (c.mass + c.added_mass_t) * e.l0 * half,
        half_added: (c.added_mass - c.added_mass_t) * e.l0 * half,
        shear: V3::zero(),
        rate: T::zero(),
    };
    if !(out.t.is_finite()
        && out.tension.is_finite()
        && out.f_half.is_finite()
        && out.half_mass.is_finite()
        && out.half_added.is_finite())
    {
        return Err(format!(
            "non-finite loads (tension {:.3e} N, half load {:?} N): non-finite input or overflow",
            out.tension.f64(),
            out.f_half.to_f64()
        ));
    }
    Ok(out)
}

/// Loads of one element evaluated through `frame` (vector normal-drag law, see the
/// module doc): the same [`ElementLoads`] as the GLMF, with the hydrodynamic loads
/// computed in the frame. `virtual_mid` is the Frenet frame's virtual node (from
/// [`frenet_virtual_node`]); the other frames ignore it. Returns a human-readable
/// reason when the frame is singular (never NaN loads).
pub fn frame_element<T: Real>(
    frame: Frame,
    c: &Coefs<T>,
    e: &ElementInput<T>,
    virtual_mid: V3<T>,
) -> Result<ElementLoads<T>, String> {
    frame_element_with(frame, NormalDrag::Vector, c, e, virtual_mid)
}

/// The Frenet frame's virtual node at the middle of element `(a, b)`.
///
/// The paper evaluates a spline through all the cable's nodes, parametrised by span
/// length, at the element's middle (Eq. 13). This is a local stand-in of the same
/// order: the cubic through `prev, a, b, next` at equal parameter spacing (the span
/// length of a uniformly meshed cable), evaluated at the middle,
/// `(-prev + 9 a + 9 b - next) / 16`; at a cable end, the quadratic through the three
/// nodes there, `(-prev + 6 a + 3 b) / 8` or `(3 a + 6 b - next) / 8`; for a
/// one-element cable, the chord midpoint. It differs from the global spline's value by
/// terms of fourth order in the element length. Collinear nodes give a point on their
/// line, so a straight cable makes the Frenet frame singular, as Sec. 2.6 says.
///
/// Written as the chord midpoint plus a correction built from node differences, so the
/// result does not lose digits to large coordinates.
pub fn frenet_virtual_node<T: Real>(
    prev: Option<V3<T>>,
    a: V3<T>,
    b: V3<T>,
    next: Option<V3<T>>,
) -> V3<T> {
    let mid = a + (b - a) * T::c(0.5);
    match (prev, next) {
        // (-p + 9a + 9b - n)/16 = mid + ((a - p) - (n - b))/16
        (Some(p), Some(n)) => mid + ((a - p) - (n - b)) * T::c(1.0 / 16.0),
        // (-p + 6a + 3b)/8 = mid + ((a - p) - (b - a))/8
        (Some(p), None) => mid + ((a - p) - (b - a)) * T::c(0.125),
        // (3a + 6b - n)/8 = mid + ((b - a) - (n - b))/8
        (None, Some(n)) => mid + ((b - a) - (n - b)) * T::c(0.125),
        (None, None) => mid,
    }
}
