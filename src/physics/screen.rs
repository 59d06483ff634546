//! Screen-model loads on net panels (docs/src/model/screen.md): the drag and lift on a
//! quadrilateral piece of netting from its solidity, its angle to the flow and the
//! Reynolds number of its twines, with the flow slowed for panels in the wake of the
//! net. Each function has a WGSL twin of the same name (`shaders/shared/prelude.wgsl`).

use crate::math::{Real, V3};

/// The coefficient set of Aarsnes (1990).
pub const SCREEN_AARSNES: u32 = 0;
/// The coefficient set of Løland (1991).
pub const SCREEN_LOLAND: u32 = 1;
/// The coefficient set of Kristiansen and Faltinsen (2012).
pub const SCREEN_KRISTIANSEN_FALTINSEN: u32 = 2;
/// No wake: every panel sees the undisturbed flow.
pub const WAKE_NONE: u32 = 0;
/// Løland's wake factor `r = 1 - 0.46 C_D(0)`.
pub const WAKE_LOLAND: u32 = 1;
/// The wake factor of Cheng et al. (2020), `r = (cos a + 0.05 - 0.38 Sn) / (cos a + 0.05)`.
pub const WAKE_CHENG: u32 = 2;

/// The constants of one screen net (WGSL `ScreenCoefs`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScreenCoefs<T> {
    /// The coefficient set ([`SCREEN_AARSNES`], [`SCREEN_LOLAND`],
    /// [`SCREEN_KRISTIANSEN_FALTINSEN`]).
    pub model: u32,
    /// The wake rule ([`WAKE_NONE`], [`WAKE_LOLAND`], [`WAKE_CHENG`]).
    pub wake: u32,
    /// Solidity `Sn` (0 < Sn < 1).
    pub sn: T,
    /// The twines' Reynolds number per unit speed, `d_w / (nu (1 - Sn))`, s/m.
    pub re_scale: T,
    /// Half the water density, kg/m^3.
    pub half_rho: T,
    /// The x of the vertical axis that decides which panels are downstream, m.
    pub axis_x: T,
    /// The y of that axis, m.
    pub axis_y: T,
}

/// The drag coefficient of a circular cylinder (a twine) at Reynolds number `re`: the
/// polynomial of degree 7 in `log10(Re)` that Cheng et al. (2020) use with the
/// Kristiansen and Faltinsen model (docs/src/model/screen.md), with `log10(Re)` held to
/// [1, 4], where the fit stays between 0.97 and 1.8. It is evaluated re-centred at
/// `log10(Re) = 2.5` (the same polynomial, its coefficients expanded exactly about
/// 2.5), whose terms are of the size of the result: the published form's terms reach
/// 7000 for a result near 1, which would cost f32 three digits.
#[inline(always)]
pub fn screen_cylinder_cd<T: Real>(re: T) -> T {
    let y = screen_log10(re.max(T::c(10.0)).min(T::c(1.0e4))) - T::c(2.5);
    let k = [
        1.244830859375,
        -0.39100046875,
        -0.4381015625,
        0.220573125,
        0.83019125,
        -0.3477225,
        -0.265115,
        0.12479,
    ];
    let mut p = T::c(k[7]);
    for j in (0..7).rev() {
        p = p * y + T::c(k[j]);
    }
    p
}

/// `log10(x)` for `x` in [10, 1e4] without a library logarithm (WGSL has none in f64):
/// `x = 2^k m` with `m` in (1/sqrt 2, sqrt 2] by five exact halvings by powers of two,
/// then `ln m = 2 atanh((m - 1) / (m + 1))` by its series to the 21st power (|z| <=
/// 0.172: the next term is below 1e-17).
#[inline(always)]
pub fn screen_log10<T: Real>(x: T) -> T {
    let sqrt2 = T::c(std::f64::consts::SQRT_2);
    let mut m = x;
    let mut k = T::zero();
    // (threshold over sqrt 2, divisor, its exponent)
    for (t, p, e) in [
        (256.0, 256.0, 8.0),
        (16.0, 16.0, 4.0),
        (4.0, 4.0, 2.0),
        (2.0, 2.0, 1.0),
        (1.0, 2.0, 1.0),
    ] {
        if m > T::c(t) * sqrt2 {
            m = m / T::c(p);
            k += T::c(e);
        }
    }
    let z = (m - T::one()) / (m + T::one());
    let w = z * z;
    let mut a = T::c(1.0 / 21.0);
    for j in (0..10).rev() {
        a = a * w + T::c(1.0 / (2 * j + 1) as f64);
    }
    let ln = k * T::c(std::f64::consts::LN_2) + T::c(2.0) * z * a;
    ln * T::c(std::f64::consts::LOG10_E)
}

/// Drag coefficient `C_D` and lift factor `g` of coefficient set `model` for solidity
/// `sn`, twine Reynolds number `re` and `c = cos(theta)`, `theta` the angle between the
/// panel's normal and the flow (0 when the flow meets the panel head on). The lift
/// coefficient is `C_L = g sin(2 theta)`.
#[inline(always)]
pub fn screen_coefficients<T: Real>(model: u32, sn: T, re: T, c: T) -> [T; 2] {
    let (s2, s3) = (sn * sn, sn * sn * sn);
    let k = T::c;
    if model == SCREEN_AARSNES {
        let cd = k(0.04) + (k(-0.04) + sn - k(1.24) * s2 + k(13.7) * s3) * c;
        let g = k(0.57) * sn - k(3.54) * s2 + k(10.1) * s3;
        [cd, g]
    } else if model == SCREEN_LOLAND {
        let cd = k(0.04) + (k(-0.04) + k(0.33) * sn + k(6.54) * s2 - k(4.88) * s3) * c;
        let g = k(-0.05) * sn + k(2.3) * s2 - k(1.76) * s3;
        [cd, g]
    } else {
        let cdc = screen_cylinder_cd(re);
        let q = k(1.0) - sn;
        let cd0 = cdc * sn * (k(2.0) - sn) / (k(2.0) * q * q);
        let cn45 = cdc * sn / (k(2.0) * q * q);
        let cl45 = k(std::f64::consts::PI) * cn45 / (k(8.0) + cn45);
        let cl0 = (k(0.5) * cd0 - cl45) * k(std::f64::consts::FRAC_1_SQRT_2);
        // cos 3t = 4c^3 - 3c; sin 4t = 2 sin 2t cos 2t, cos 2t = 2c^2 - 1.
        let cd = cd0 * (k(0.9) * c + k(0.1) * (k(4.0) * c * c * c - k(3.0) * c));
        let g = cl0 * (k(1.0) + k(0.2) * (k(2.0) * c * c - k(1.0)));
        [cd, g]
    }
}

/// The flow-reduction factor `r` (0 to 1) behind the net under rule `co.wake` for a
/// panel whose normal makes `c = cos(theta)` with the flow, twine Reynolds number `re`.
#[inline(always)]
pub fn screen_wake_factor<T: Real>(co: &ScreenCoefs<T>, re: T, c: T) -> T {
    let one = T::one();
    let r = if co.wake == WAKE_LOLAND {
        one - T::c(0.46) * screen_coefficients(co.model, co.sn, re, one)[0]
    } else if co.wake == WAKE_CHENG {
        (c + T::c(0.05) - T::c(0.38) * co.sn) / (c + T::c(0.05))
    } else {
        one
    };
    r.max(T::zero()).min(one)
}

/// The screen-model force on the panel with corners `p` (in order around it) moving
/// with corner velocities `v`, in water moving at `u` (current and waves at its centre):
/// drag `1/2 rho C_D A |U| U` along the relative flow `U = r u - vbar` and lift
/// `1/2 rho C_L A |U|^2` across it, towards the side the panel faces (`A` the panel's
/// area `|(p2 - p0) x (p3 - p1)| / 2`, `vbar` the mean corner velocity, `r` the wake
/// factor where the panel is downstream of the axis `(axis_x, axis_y)`, else 1).
#[inline(always)]
pub fn screen_panel_force<T: Real>(
    co: &ScreenCoefs<T>,
    p: [V3<T>; 4],
    v: [V3<T>; 4],
    u: V3<T>,
) -> V3<T> {
    let zero = V3::zero();
    let quarter = T::c(0.25);
    let vbar = (v[0] + v[1] + v[2] + v[3]) * quarter;
    let nv = (p[2] - p[0]).cross(p[3] - p[1]) * T::c(0.5);
    let area = nv.norm();
    if area <= T::zero() {
        return zero;
    }
    let n = nv * (T::one() / area);
    let mut w = u;
    if co.wake != WAKE_NONE {
        let cx = (p[0].x + p[1].x + p[2].x + p[3].x) * quarter;
        let cy = (p[0].y + p[1].y + p[2].y + p[3].y) * quarter;
        if (cx - co.axis_x) * u.x + (cy - co.axis_y) * u.y > T::zero() {
            let u0 = u - vbar;
            let s0 = u0.norm();
            if s0 > T::zero() {
                let c0 = (n.dot(u0).abs() / s0).min(T::one());
                w = u * screen_wake_factor(co, co.re_scale * s0, c0);
            }
        }
    }
    let ur = w - vbar;
    let s = ur.norm();
    if s <= T::zero() {
        return zero;
    }
    let nu = n.dot(ur);
    let c = (nu.abs() / s).min(T::one());
    // The normal turned to face downstream.
    let nd = if nu < T::zero() { -n } else { n };
    let [cd, g] = screen_coefficients(co.model, co.sn, co.re_scale * s, c);
    // Lift C_L = g sin 2t along (nd |U|^2 - U |U| c) / (|U|^2 sin t):
    // 1/2 rho A |U|^2 C_L times that is 1/2 rho A 2 c g (nd |U|^2 - U |U| c).
    let lift = (nd * (s * s) - ur * (s * c)) * (T::c(2.0) * c * g);
    (ur * (cd * s) + lift) * (co.half_rho * area)
}
