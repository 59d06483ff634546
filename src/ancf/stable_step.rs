//! The stable step of an ANCF cable: the fastest mode of a uniform chain with the
//! cable's end conditions, turned into a step of the chosen scheme.

use super::config::AncfEnd;
use super::element::{gauss_points, AncfCoefs};
use crate::model::LineCoefs;
use crate::options::Scheme;
use crate::physics::SeabedCoefs;
use crate::stability::mode_step;
use nalgebra::DMatrix;

/// Strain allowance in the stable-step bound: the axial stiffness of a stretched
/// element grows with its strain (`EA (1 + 3 eps0)` along the tangent); the bound
/// allows strains up to 3 %.
const STRAIN_ALLOWANCE: f64 = 1.1;

/// Elements in the chain whose fastest mode bounds the stable step.
const EIG_ELEMENTS: usize = 32;

/// The fastest mode of the cable and the scheme's stable step for it.
///
/// The mass matrix is `M_s (x) I` plus the positive added mass and the point masses, and the
/// stiffness along any direction is at most `EA s K_a + EI K_b` (`K_a = int S' S'^T`,
/// `K_b = int S'' S''^T` assembled, `s` a strain allowance covering the stretched
/// line's `EA (1 + 3 eps0)` and the geometric stiffness `N K_a`), plus the seabed's
/// `K / mbar M_s`. So `omega_max^2` is at most the largest eigenvalue of the scalar
/// problem `(EA s K_a + EI K_b) x = omega^2 (mbar M_s + point masses) x` with the
/// cable's end conditions (the normal added mass only lowers it), computed densely for a
/// chain of `min(n, 32)` elements: the fastest modes are short waves in the bulk
/// (`omega^2 = 42 EA / (mbar L^2)`) or, at a free end without a point mass, a mode of
/// the end node (`91 EA / (mbar L^2)`), and a longer uniform chain has the same top of
/// the spectrum. The internal damping makes
/// the mode's damping `gamma = c omega^2`, plus `C / mbar` of the seabed and its
/// regularised friction, `mu w / (v_eps mbar)` (`w` the wet weight per length).
#[allow(clippy::too_many_arguments)]
pub(super) fn stable_step(
    c: &AncfCoefs,
    lc: &LineCoefs,
    lens: &[f64],
    n_gauss: usize,
    seabed: Option<SeabedCoefs<f64>>,
    scheme: Scheme,
    ends: [(&AncfEnd, f64); 2],
) -> (f64, String) {
    // The first and last elements of a long cable, keeping both ends' conditions.
    let chain: Vec<f64> = if lens.len() <= EIG_ELEMENTS {
        lens.to_vec()
    } else {
        let h = EIG_ELEMENTS / 2;
        lens[..h]
            .iter()
            .chain(&lens[lens.len() - h..])
            .copied()
            .collect()
    };
    let ne = chain.len();
    let l = chain.iter().copied().fold(f64::INFINITY, f64::min);
    let nd = 2 * (ne + 1);
    let mut ms = DMatrix::<f64>::zeros(nd, nd);
    let mut ka = DMatrix::<f64>::zeros(nd, nd);
    for (e, &le) in chain.iter().enumerate() {
        // A rule of at least 6 points integrates these degree <= 6 products exactly.
        for gp in &gauss_points(le, 6.max(n_gauss)) {
            let sh = &gp.shape;
            for i in 0..4 {
                for j in 0..4 {
                    let (gi, gj) = (2 * e + i, 2 * e + j);
                    ms[(gi, gj)] += gp.dx * lc.mass * sh.s[i] * sh.s[j];
                    ka[(gi, gj)] += gp.dx
                        * (c.line.ea * STRAIN_ALLOWANCE * sh.ds[i] * sh.ds[j]
                            + c.ei * sh.dds[i] * sh.dds[j]);
                }
            }
        }
    }
    // End conditions: point masses on the end positions; prescribed coordinates
    // removed (an identity row in the mass, nothing in the stiffness).
    for (k, (end, mass)) in ends.iter().enumerate() {
        let u = if k == 0 { 0 } else { nd - 2 };
        ms[(u, u)] += mass;
        let fixed = [end.route.is_some(), end.slope.is_some()];
        for (d, &f) in fixed.iter().enumerate() {
            if f {
                for j in 0..nd {
                    ms[(u + d, j)] = 0.0;
                    ms[(j, u + d)] = 0.0;
                    ka[(u + d, j)] = 0.0;
                    ka[(j, u + d)] = 0.0;
                }
                ms[(u + d, u + d)] = 1.0;
            }
        }
    }
    let ch = ms
        .cholesky()
        .expect("the consistent mass matrix is positive definite");
    let li = ch
        .l()
        .try_inverse()
        .expect("a Cholesky factor is invertible");
    let a = &li * ka * li.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let we = a.symmetric_eigenvalues().max();
    let ws = seabed.map_or(0.0, |s| s.k / lc.mass);
    // Seabed damping, and the regularised friction below v_eps: a damper of rate
    // mu F_N / (v_eps m) with F_N the wet weight it carries.
    let gamma = c.line.ea_c / c.line.ea * we
        + seabed.map_or(0.0, |s| {
            (s.c + s.mu * lc.wet_weight_z.abs() / s.v_eps.max(1e-300)) / lc.mass
        });
    let omega2 = we + ws;
    let dt = mode_step(scheme, omega2, gamma);
    let term = format!(
        "fastest mode of the cubic elements: elastic omega^2 {we:.4e} s^-2 (axial wave bound {:.4e}), seabed {ws:.4e} s^-2, damping {gamma:.4e} s^-1 ({} scheme)",
        4.0 * c.line.ea / (lc.mass * l * l),
        scheme.name()
    );
    (dt, term)
}
