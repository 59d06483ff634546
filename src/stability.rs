//! The stable explicit time step (docs/src/model/time_stepping.md).
//!
//! Each node is bounded with Gershgorin estimates of its fastest modes: axial waves
//! (`omega^2 <= sum_e 2 (EA/l0) / m`, which is `4 EA / (mbar l0^2)` for a uniform chain),
//! internal damping (`gamma = c omega^2`), seabed contact (`omega^2 = K lt / m`,
//! `gamma = C lt / m`) and, for constrained nodes, the Baumgarte gains
//! (`omega^2 = alpha`, `gamma = beta`); regularised seabed friction is a damper of
//! rate `mu F_N / (v_eps m)` with `F_N` the node's wet weight. The symplectic scheme
//! takes the seabed's damping and friction implicitly in the node solve
//! (`(M + dt diag(c)) a = F`, docs/src/model/seabed.md), so for it they bound nothing
//! and only the seabed stiffness counts; the Runge-Kutta schemes take them explicitly
//! and keep their bounds. `m` is the node's scalar mass without added
//! mass (the axial direction has only the tangential added mass `Cat rho A`, which
//! is zero by default and never negative, and nothing above the water surface has
//! any), so the estimate errs on the safe side. The
//! modes of a node are summed for the symplectic scheme (damping only shrinks its step);
//! RK2 and RK4 steps grow with damping, so there each mode counts only the damping acting
//! on it (axial waves with internal damping, seabed stiffness with seabed damping). The
//! scheme's own stability
//! region turns `(omega^2, gamma)` into a step.

use crate::model::{Layout, NO_CONSTRAINT};
use crate::options::{Baumgarte, Scheme};

/// Fraction of the stability limit that `dt = "auto"` uses.
pub const AUTO_SAFETY: f64 = 0.8;

/// Amplification per step accepted for a mode on a scheme whose stability region
/// does not contain the imaginary axis (RK2): `|R| <= 1 + RK2_GROWTH` keeps an
/// undamped mode's growth below e^0.1 over a million steps.
pub const RK2_GROWTH: f64 = 1e-7;

/// The largest stable step and what sets it.
#[derive(Clone, Debug, PartialEq)]
pub struct StepBound {
    /// Largest stable step, s (before any safety factor).
    pub dt: f64,
    /// The term that sets it, in words (which cable, node, mode).
    pub term: String,
    /// What sets that term and the scenario key that changes it, in words (empty when
    /// nothing bounds the step).
    pub fix: String,
}

/// What a mode comes from; put in words ([`Term::describe`]) only for the one that
/// sets the step, so that the search stays linear in the model's size.
#[derive(Clone, Copy, Debug)]
enum Term {
    Baumgarte,
    /// Axial waves, with the node's shortest element and its length.
    Axial(usize, f64),
    /// Internal damping, with the node's shortest element and its length.
    Internal(usize, f64),
    SeabedStiffness,
    SeabedDamping,
    Friction,
    /// Bending waves, with the node's shortest element and its length.
    Bending(usize, f64),
    /// The decay of a viscoelastic element's state, with the element and its length.
    Visco(usize, f64),
}

impl Term {
    /// The term at node `i` of `lay`, in words (which cable, node, mode).
    fn describe(self, lay: &Layout, i: usize) -> String {
        let (cable, node) = lay.describe_node(i);
        let sb = lay.env.seabed;
        let element = |e: usize, l0: f64| {
            let (_, ek) = lay.describe_element(e);
            if l0 >= 1e-3 {
                format!("(element {ek}, l0 = {l0:.4} m)")
            } else {
                format!("(element {ek}, l0 = {l0:.3e} m)")
            }
        };
        match self {
            Term::Baumgarte => format!("the Baumgarte gains at cable '{cable}' node {node}"),
            Term::Axial(e, l0) => format!(
                "axial waves at cable '{cable}' node {node} {}",
                element(e, l0)
            ),
            Term::Internal(e, l0) => format!(
                "internal damping at cable '{cable}' node {node} {}",
                element(e, l0)
            ),
            Term::Bending(e, l0) => format!(
                "bending waves at cable '{cable}' node {node} {}",
                element(e, l0)
            ),
            Term::Visco(e, l0) => format!(
                "the viscoelastic state's decay at cable '{cable}' node {node} {}",
                element(e, l0)
            ),
            Term::SeabedStiffness => format!("seabed stiffness at cable '{cable}' node {node}"),
            Term::SeabedDamping => format!("seabed damping at cable '{cable}' node {node}"),
            Term::Friction => format!(
                "seabed friction (mu = {}, v_eps = {} m/s) at cable '{cable}' node {node}",
                sb.friction.max(sb.mu_axial()),
                sb.friction_velocity
            ),
        }
    }
}

impl Term {
    /// What to change in the scenario to lengthen the step this term sets at node `i`:
    /// the value behind it and its key.
    fn fix(self, lay: &Layout, i: usize) -> String {
        let (cable, _) = lay.describe_node(i);
        let sb = lay.env.seabed;
        let line = |e: usize| {
            let t = lay.elem_line[e] as usize;
            (&lay.line_types[t].name, lay.line_coefs[t])
        };
        match self {
            Term::Baumgarte => "the held-end constraints' gains: lower `[simulation] \
                               baumgarte_alpha` and `baumgarte_beta`"
                .into(),
            Term::Axial(e, l0) => {
                let (name, c) = line(e);
                format!(
                    "the axial wave crosses an element of {l0:.3e} m in {:.3e} s (the step \
                     scales with the element length, at the wave speed sqrt(EA / m) = \
                     {:.3e} m/s of line type '{name}'): give cable '{cable}' fewer \
                     `segments` (or a smaller `length`)",
                    l0 / (c.ea / c.mass).sqrt(),
                    (c.ea / c.mass).sqrt()
                )
            }
            Term::Internal(e, l0) => {
                let (name, c) = line(e);
                format!(
                    "the internal damping of line type '{name}' (`damping` = {:.3e} s) \
                     damps an element of {l0:.3e} m faster than any step can follow: the \
                     step is at most about l0^2 m / (2 EA c); lower that `damping` in \
                     [[line_types]], or give cable '{cable}' fewer `segments` (the step \
                     grows with the element length squared)",
                    c.ea_c / c.ea
                )
            }
            Term::Visco(e, _) => {
                let t = lay.elem_line[e] as usize;
                format!(
                    "the static branch of viscoelastic line type '{}' relaxes faster than \
                     the step can follow (in (ba_static + ba_dynamic) / (K1 + K2)): raise \
                     `ba_static` in [[line_types]]",
                    lay.line_types[t].name
                )
            }
            Term::Bending(e, l0) => {
                let t = lay.elem_line[e] as usize;
                let (name, ei) = (&lay.line_types[t].name, lay.line_types[t].ei);
                format!(
                    "the bending wave of line type '{name}' (`ei` = {ei:.3e} N m^2) crosses \
                     an element of {l0:.3e} m: the step is about l0^2 sqrt(m / EI) / 2 and \
                     grows with the element length squared: give cable '{cable}' fewer \
                     `segments`, or lower that `ei`"
                )
            }
            Term::SeabedStiffness => format!(
                "the seabed's stiffness ({:.3e} N/m per m): lower `[environment.seabed] \
                 stiffness`",
                sb.stiffness
            ),
            Term::SeabedDamping => format!(
                "the seabed's damping ({:.3e} N s/m per m), explicit in the Runge-Kutta \
                 schemes: lower `[environment.seabed] damping`, or use the symplectic scheme",
                sb.damping
            ),
            Term::Friction => "the seabed's regularised friction, explicit in the \
                               Runge-Kutta schemes: raise `[environment.seabed] \
                               friction_velocity`, or use the symplectic scheme"
                .into(),
        }
    }
}

/// One node's mode: frequency squared and damping rate.
#[derive(Clone, Copy, Debug)]
struct Mode {
    omega2: f64,
    gamma: f64,
}

/// Largest stable step of `x'' + gamma x' + omega^2 x = 0` under `scheme`.
pub fn mode_step(scheme: Scheme, omega2: f64, gamma: f64) -> f64 {
    if omega2 <= 0.0 && gamma <= 0.0 {
        return f64::INFINITY;
    }
    match scheme {
        // (omega dt)^2 + 2 gamma dt < 4  (docs/src/model/time_stepping.md)
        // Written as 4 / (gamma + sqrt(gamma^2 + 4 omega^2)): no cancellation, and a
        // huge term gives a step near zero instead of overflowing to inf / inf.
        Scheme::Symplectic => 4.0 / (gamma + gamma.hypot(2.0 * omega2.sqrt())),
        Scheme::Rk2 | Scheme::Rk4 => {
            // Eigenvalues of the mode; bisection on |R(h lambda)| <= 1 (+ tolerance).
            let disc = 0.25 * gamma * gamma - omega2;
            let lams: Vec<(f64, f64)> = if disc >= 0.0 {
                let s = disc.sqrt();
                vec![(-0.5 * gamma + s, 0.0), (-0.5 * gamma - s, 0.0)]
            } else {
                vec![(-0.5 * gamma, (-disc).sqrt())]
            };
            let tol = if scheme == Scheme::Rk2 {
                RK2_GROWTH
            } else {
                1e-12
            };
            let stable = |h: f64| {
                lams.iter()
                    .all(|&(re, im)| amplification(scheme, h * re, h * im) <= 1.0 + tol)
            };
            let mag = lams
                .iter()
                .map(|&(re, im)| (re * re + im * im).sqrt())
                .fold(0.0, f64::max);
            let (mut lo, mut hi) = (0.0, 4.0 / mag);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if stable(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            // The region is not always an interval in h; the bisection finds a stable
            // step below the first crossing for the modes that matter here.
            lo
        }
    }
}

/// `|R(z)|` of an explicit Runge-Kutta scheme at `z = x + i y`.
fn amplification(scheme: Scheme, x: f64, y: f64) -> f64 {
    // Complex powers by hand: z^2, z^3, z^4.
    let (z2r, z2i) = (x * x - y * y, 2.0 * x * y);
    let (re, im) = match scheme {
        Scheme::Rk2 => (1.0 + x + 0.5 * z2r, y + 0.5 * z2i),
        _ => {
            let (z3r, z3i) = (z2r * x - z2i * y, z2r * y + z2i * x);
            let (z4r, z4i) = (z2r * z2r - z2i * z2i, 2.0 * z2r * z2i);
            (
                1.0 + x + 0.5 * z2r + z3r / 6.0 + z4r / 24.0,
                y + 0.5 * z2i + z3i / 6.0 + z4i / 24.0,
            )
        }
    };
    (re * re + im * im).sqrt()
}

/// The stable step of a whole layout, in time linear in its size: each node's modes
/// are bounded in turn and only the one setting the step is put in words.
pub fn stable_step(lay: &Layout, scheme: Scheme, bg: Baumgarte) -> StepBound {
    // (step, node, term) of the smallest step so far.
    let mut best: Option<(f64, usize, Term)> = None;
    let mut body_best: Option<(f64, String)> = None;
    let sb = lay.env.seabed;
    // The symplectic node solve takes the seabed's damping and friction implicitly
    // (cpu::stepper::implicit_dt and node_advance in shared/prelude.wgsl).
    let contact_damping_bounds = scheme != Scheme::Symplectic;
    // Without a seabed (infinite depth) no node can touch one.
    let has_seabed = lay.env.depth.is_finite();
    let mut parts: Vec<(Mode, Term, u8)> = Vec::with_capacity(7);
    let bend = bending_stiffness(lay);
    for i in 0..lay.n_nodes() {
        parts.clear();
        if lay.node_constraint[i] != NO_CONSTRAINT {
            parts.push((
                Mode {
                    omega2: bg.alpha,
                    gamma: bg.beta,
                },
                Term::Baumgarte,
                3,
            ));
        } else {
            // A point mass out of the water loses its added mass: bound with its dry
            // mass (the elements' masses below have no added mass either).
            let mut m = lay.node_point_mass[i] - lay.node_point_added[i];
            let (mut k, mut kc, mut lt) = (0.0, 0.0, 0.0);
            // Weight the node would rest on the seabed with, for the friction term.
            let mut wet = (-lay.node_point_weight_z[i]).max(0.0);
            let mut shortest = (f64::INFINITY, 0usize);
            // The fastest decay of a viscoelastic element's state here (rate, element, l0).
            let mut visco_rate = (0.0, 0usize, 0.0);
            for &inc in lay.incidence(i) {
                let e = (inc >> 1) as usize;
                let l0 = lay.elem_l0[e];
                let c = &lay.line_coefs[lay.elem_line[e] as usize];
                m += 0.5 * c.mass * l0;
                match lay.line_types[lay.elem_line[e] as usize].viscoelastic {
                    None => {
                        k += 2.0 * c.ea / l0;
                        kc += 2.0 * c.ea_c / l0;
                    }
                    Some(vm) => {
                        // A viscoelastic element: its stiffness and damping at high
                        // frequency, and its state's decay (physics::visco).
                        let ks = lay.line_types[lay.elem_line[e] as usize].ea;
                        let k2 = crate::physics::visco::visco_step_stiffness(
                            ks,
                            vm.ea_dynamic,
                            vm.ea_dynamic_slope,
                        );
                        let (kh, ch, rate) = crate::physics::visco::visco_step_bounds(
                            ks,
                            k2,
                            vm.ba_static,
                            vm.ba_dynamic,
                        );
                        k += 2.0 * kh / l0;
                        kc += 2.0 * ch / l0;
                        if rate > visco_rate.0 {
                            visco_rate = (rate, e, l0);
                        }
                    }
                }
                lt += 0.5 * l0;
                wet += (-0.5 * c.wet_weight_z * l0).max(0.0);
                if l0 < shortest.0 {
                    shortest = (l0, e);
                }
            }
            if m <= 0.0 {
                continue;
            }
            if k > 0.0 {
                parts.push((
                    Mode {
                        omega2: k / m,
                        gamma: 0.0,
                    },
                    Term::Axial(shortest.1, shortest.0),
                    0,
                ));
                if kc > 0.0 {
                    parts.push((
                        Mode {
                            omega2: 0.0,
                            gamma: kc / m,
                        },
                        Term::Internal(shortest.1, shortest.0),
                        0,
                    ));
                }
            }
            if visco_rate.0 > 0.0 {
                parts.push((
                    Mode {
                        omega2: 0.0,
                        gamma: visco_rate.0,
                    },
                    Term::Visco(visco_rate.1, visco_rate.2),
                    0,
                ));
            }
            if bend[i] > 0.0 {
                parts.push((
                    Mode {
                        omega2: bend[i] / m,
                        gamma: 0.0,
                    },
                    Term::Bending(shortest.1, shortest.0),
                    4,
                ));
            }
            if has_seabed && lt > 0.0 && sb.stiffness > 0.0 {
                parts.push((
                    Mode {
                        omega2: sb.stiffness * lt / m,
                        gamma: 0.0,
                    },
                    Term::SeabedStiffness,
                    1,
                ));
            }
            if contact_damping_bounds && has_seabed && lt > 0.0 && sb.damping > 0.0 {
                parts.push((
                    Mode {
                        omega2: 0.0,
                        gamma: sb.damping * lt / m,
                    },
                    Term::SeabedDamping,
                    1,
                ));
            }
            // Regularised friction is a viscous damper of slope mu F_N / v_eps below
            // v_eps; F_N is about the node's wet weight when it rests on the seabed.
            // With the friction split, the larger of the two coefficients.
            let mu = sb.friction.max(sb.mu_axial());
            if contact_damping_bounds && has_seabed && lt > 0.0 && mu > 0.0 && wet > 0.0 {
                parts.push((
                    Mode {
                        omega2: 0.0,
                        gamma: mu * wet / (sb.friction_velocity * m),
                    },
                    Term::Friction,
                    2,
                ));
            }
        }
        if parts.is_empty() {
            continue;
        }
        let sum = |group: Option<u8>| {
            parts
                .iter()
                .filter(|(_, _, g)| group.is_none_or(|x| x == *g))
                .fold(
                    Mode {
                        omega2: 0.0,
                        gamma: 0.0,
                    },
                    |a, (p, _, _)| Mode {
                        omega2: a.omega2 + p.omega2,
                        gamma: a.gamma + p.gamma,
                    },
                )
        };
        let dt = match scheme {
            // Damping only shrinks the symplectic step: summing every term is safe.
            Scheme::Symplectic => {
                let total = sum(None);
                mode_step(scheme, total.omega2, total.gamma)
            }
            // Runge-Kutta steps grow with damping, so a mode may only count the damping
            // that acts on it: axial waves with internal damping, seabed stiffness with
            // seabed damping (another direction), friction, the constraint gains.
            Scheme::Rk2 | Scheme::Rk4 => (0..5u8)
                .filter(|g| parts.iter().any(|(_, _, x)| x == g))
                .map(|g| {
                    let m = sum(Some(g));
                    mode_step(scheme, m.omega2, m.gamma)
                })
                .fold(f64::INFINITY, f64::min),
        };
        // A step that is not a number (an overflowing stiffness) is the worst of all:
        // it must not be dropped by the comparison.
        let smaller = match best {
            None => true,
            Some((b, _, _)) => !b.is_nan() && (dt < b || dt.is_nan()),
        };
        if smaller {
            // Name the term that alone would set the smallest step.
            let (_, term) = parts
                .iter()
                .map(|(p, t, _)| (mode_step(scheme, p.omega2, p.gamma), *t))
                .fold((f64::INFINITY, parts[0].1), |a, b| {
                    if b.0 < a.0 || b.0.is_nan() {
                        b
                    } else {
                        a
                    }
                });
            best = Some((dt, i, term));
        }
    }
    // Free and pinned bodies: their own stiffness and linear damping per degree of
    // freedom (the held nodes are lumped into them, which only lowers the lines'
    // frequencies: docs/src/bodies.md, "Free bodies").
    let fluid = crate::body::free::Fluid {
        rho: lay.env.water_density,
        g: lay.env.gravity,
    };
    let mut seen: Vec<*const crate::body::Body> = Vec::new();
    for r in &lay.routes {
        let crate::model::Route::Body { body, .. } = r else {
            continue;
        };
        let Some(d) = body.dynamic() else { continue };
        if seen.contains(&std::sync::Arc::as_ptr(body)) {
            continue;
        }
        seen.push(std::sync::Arc::as_ptr(body));
        for (k, (omega2, gamma)) in d.body.modes(fluid).into_iter().enumerate() {
            if omega2 == 0.0 && gamma == 0.0 {
                continue;
            }
            let dt = mode_step(scheme, omega2, gamma);
            if best.is_none_or(|(b, _, _)| dt < b)
                && dt
                    < body_best
                        .as_ref()
                        .map_or(f64::INFINITY, |b: &(f64, String)| b.0)
            {
                body_best = Some((
                    dt,
                    format!(
                        "the stiffness or damping of free body '{}' (degree of freedom {k})",
                        body.name
                    ),
                ));
            }
        }
    }
    if let Some((dt, term)) = body_best {
        if best.is_none_or(|(b, _, _)| dt < b) {
            return StepBound {
                dt,
                term,
                fix: "a free body's `mass`, `inertia`, `stiffness` or `damping` in `[[bodies]]`"
                    .to_string(),
            };
        }
    }
    match best {
        Some((dt, i, term)) if dt < f64::INFINITY || dt.is_nan() => StepBound {
            dt,
            term: term.describe(lay, i),
            fix: term.fix(lay, i),
        },
        _ => StepBound {
            dt: f64::INFINITY,
            term: "nothing (no stiff term)".into(),
            fix: String::new(),
        },
    }
}

/// Per node: a Gershgorin bound of its bending stiffness, N/m. A hinge of stiffness
/// `k = EI / lbar` (`crate::model::Hinge`) turns small transverse displacements `w`
/// of its nodes into the angle `b . w`, `b = (1/l1, -(1/l1 + 1/l2), 1/l2)` (the
/// held side of a clamp left out), and has the stiffness `k b b^T`; each node's row
/// of it sums in absolute value to `2 k s |b_i|` with `s = 1/l1 + 1/l2`. For a
/// uniform cable the sum over a node's three hinges is `16 EI / l0^3`, so that
/// `omega^2 = 16 EI / (m l0^4)`: the highest bending mode of the chain.
fn bending_stiffness(lay: &Layout) -> Vec<f64> {
    let mut out = vec![0.0; lay.n_nodes()];
    for h in lay.hinges() {
        let side = |e: u32| {
            (e != crate::model::NO_ELEM).then(|| {
                let e = e as usize;
                (
                    lay.elem_l0[e],
                    lay.elem_a[e] as usize,
                    lay.elem_b[e] as usize,
                )
            })
        };
        let (p, n) = (side(h.prev), side(h.next));
        let s = p.map_or(0.0, |x| 1.0 / x.0) + n.map_or(0.0, |x| 1.0 / x.0);
        let hinge_node = match (p, n) {
            (Some(p), _) => p.2,
            (None, Some(n)) => n.1,
            (None, None) => continue,
        };
        out[hinge_node] += 2.0 * h.k * s * s;
        if let Some((l, a, _)) = p {
            out[a] += 2.0 * h.k * s / l;
        }
        if let Some((l, _, b)) = n {
            out[b] += 2.0 * h.k * s / l;
        }
    }
    out
}
