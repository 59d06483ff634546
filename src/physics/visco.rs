//! The static-dynamic (viscoelastic) axial model of a fibre rope
//! (docs/src/model/axial.md#viscoelastic-fibre-rope).
//!
//! An element is two Kelvin-Voigt elements in series: a spring `K1` with a dashpot
//! `c1` (the static branch, strain `s`: the element's one internal state) and a
//! spring `K2` with a dashpot `c2` (the dynamic branch, strain `eps - s`). `K2` is the
//! dynamic stiffness `EA_d` and `K1 = K2 EA_s / (K2 - EA_s)`, so that the two springs
//! in series have the static stiffness `EA_s`. The force is the same in both branches:
//!
//! ```text
//! T = K1 s + c1 sdot = K2 (eps - s) + c2 (epsdot - sdot)
//! (c1 + c2) sdot = K2 eps - (K1 + K2) s + c2 epsdot
//! ```
//!
//! With a load-dependent dynamic stiffness `EA_d = EA_Dc + EA_D_Lm T_m`, the mean
//! tension `T_m` is the static branch's spring force `K1 s` (it follows the slow part
//! of the load), which with `K1 = K2 EA_s / (K2 - EA_s)` gives `K2` as the larger root
//! of `K2^2 - (a + EA_s (1 + b s)) K2 + a EA_s = 0` (`a = EA_Dc`, `b = EA_D_Lm`):
//!
//! ```text
//! K2 = (a + EA_s (1 + b s) + sqrt((a - EA_s (1 + b s))^2 + 4 a EA_s b s)) / 2,  s >= 0
//! K2 = a,                                                                     s < 0
//! ```
//!
//! (MoorDyn's `Line.cpp`, `ELASTIC_VISCO_MEAN`). The elastic part `K1 s` vanishes
//! when the element is slack (`eps <= 0`); the damping part `c1 sdot` does not.

use crate::math::Real;

/// The dynamic stiffness `K2`, N, of a line with static stiffness `ks`, dynamic
/// stiffness `kd` (its value at zero mean tension when `slope` is not zero) and the
/// slope `slope` of the dynamic stiffness against the mean tension, at static-branch
/// strain `s` (see the module doc).
#[inline(always)]
pub fn visco_dynamic_stiffness<T: Real>(ks: T, kd: T, slope: T, s: T) -> T {
    if slope == T::zero() || s < T::zero() {
        return kd;
    }
    let q = ks * (T::one() + slope * s);
    let d = kd - q;
    T::c(0.5) * (kd + q + (d * d + T::c(4.0) * kd * ks * slope * s).sqrt())
}

/// The axial force (N) and the rate of the state `sdot` (1/s) of a viscoelastic
/// element at strain `eps`, strain rate `epsdot` and state `s` (module doc): static
/// stiffness `ks`, dynamic `kd` and its slope `slope` against the mean tension, the
/// static branch's damping `c1` and the dynamic's `c2` (N s). WGSL twin:
/// `visco_tension` in `shaders/shared/prelude.wgsl`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn visco_tension<T: Real>(
    ks: T,
    kd: T,
    slope: T,
    c1: T,
    c2: T,
    eps: T,
    epsdot: T,
    s: T,
) -> (T, T) {
    let k2 = visco_dynamic_stiffness(ks, kd, slope, s);
    let k1 = k2 * ks / (k2 - ks);
    let rate = (k2 * eps - (k1 + k2) * s + c2 * epsdot) / (c1 + c2);
    let elastic = if eps > T::zero() { k1 * s } else { T::zero() };
    (elastic + c1 * rate, rate)
}

/// The state at rest at strain `eps`: the static branch's strain `s` at which the
/// element's tension is `ks eps` and the state does not change,
/// `s = eps (1 - ks / K2)` with `K2` the dynamic stiffness at the mean tension
/// `ks max(eps, 0)`. The initial state of a run (statics take the static stiffness).
pub fn visco_rest_state(ks: f64, kd: f64, slope: f64, eps: f64) -> f64 {
    let k2 = kd + slope * ks * eps.max(0.0);
    eps * (1.0 - ks / k2)
}

/// What bounds the explicit step of a viscoelastic element at the dynamic stiffness
/// `k2`: its stiffness at high frequency `(K1 c2^2 + K2 c1^2) / (c1 + c2)^2` (at least
/// the static `ks`; `K2` when `c2 = 0`), N; its damping there, the two dashpots in
/// series `c1 c2 / (c1 + c2)`, N s; and the decay rate of its state,
/// `(K1 + K2) / (c1 + c2)`, 1/s (an explicit scheme needs a step below about twice
/// its inverse).
pub fn visco_step_bounds(ks: f64, k2: f64, c1: f64, c2: f64) -> (f64, f64, f64) {
    let k1 = k2 * ks / (k2 - ks);
    let c = c1 + c2;
    let k_high = (k1 * c2 * c2 + k2 * c1 * c1) / (c * c);
    (k_high.max(ks), c1 * c2 / c, (k1 + k2) / c)
}

/// The dynamic stiffness the stable step takes for a line with a load-dependent one:
/// its value at a mean tension of `ks` times a strain of 0.1 (more than a fibre rope
/// reaches in service), N.
pub fn visco_step_stiffness(ks: f64, kd: f64, slope: f64) -> f64 {
    kd + slope * ks * 0.1
}

/// The viscoelastic elements' states at rest at the element lengths `len(e)`
/// ([`visco_rest_state`]; zero for every other element): the initial state of both
/// paths. Empty without a viscoelastic line.
pub fn visco_rest_states(lay: &crate::model::Layout, len: impl Fn(usize) -> f64) -> Vec<f64> {
    if !lay.has_visco() {
        return Vec::new();
    }
    (0..lay.n_elements())
        .map(|e| {
            let lt = &lay.line_types[lay.elem_line[e] as usize];
            match lt.viscoelastic {
                Some(v) => visco_rest_state(
                    lt.ea,
                    v.ea_dynamic,
                    v.ea_dynamic_slope,
                    len(e) / lay.elem_l0[e] - 1.0,
                ),
                None => 0.0,
            }
        })
        .collect()
}
