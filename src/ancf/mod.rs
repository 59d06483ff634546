//! The ANCF reference cable model (docs/src/model/ancf.md;
//! paper Eqs. 37-44, 47, 49-50), CPU only, f64.
//!
//! The paper validates the GLMF against the absolute nodal coordinate formulation
//! (ANCF): a few long elements whose shape is a cubic curve, with bending stiffness.
//! This module is that reference, for cables of fixed length and, with a winch, of
//! varying length (ALE-ANCF, below); the ANCF backend of the run pipeline
//! ([`crate::sim`]) runs a scenario with it (`formulation = "ancf"`).
//!
//! # ALE-ANCF (winch cables)
//! [`AncfConfig::winch`] makes the cable's length follow a payout schedule with the
//! ALE-GLMF's physical coordinate (unstretched arc length from the far end; the winch
//! node's is `L(t)`) and remeshing rules ([`crate::ale::WinchTracker`], 1.5x / 0.5x the
//! standard length). Only the element next to the winch changes length, `l(t)`. A
//! material point in it keeps its distance `v` from the element's material node, so its
//! element coordinate `xi` and, through the slope shape functions, the shape functions
//! themselves depend on `l`: with `D = d/dl` at fixed `v`
//! ([`shape::ale_shape`], closed forms checked against finite differences) the material
//! velocity is `S qdot + ldot (D S) q` and the material acceleration
//! `S qddot + 2 ldot (D S) qdot + lddot (D S) q + ldot^2 (D^2 S) q` (paper Eqs. 35-36). The
//! last three terms give the mass-flow force `-int mbar S^T rddot_p dx` (Eq. 39, the
//! cable's own `mbar` as in [`crate::ale`]); drag, internal damping (strain and
//! curvature rates) and seabed contact use the material rates; the element's consistent
//! mass and Gauss rule follow `l(t)` at every evaluation. A test checks the momentum
//! balance `dP/dt = W - R + mbar Ldot v_w` of the deployed cable. An inserted node takes
//! the cubic's position and slope and the material velocity and slope rate at its
//! material point: the shape and the motion are unchanged (exact). A deleted node's
//! neighbours keep their coordinates, and the merged element is the cubic through them
//! (the one approximation of remeshing). The stable step is computed once for the worst
//! mesh (the variable element at 0.5 of the standard length).
//!
//! # The element
//! Gradient-deficient 3D cable element: per node the position `r` and the slope
//! `r' = dr/dx` (`x` the unstretched arc length), 6 coordinates per node, cubic Hermite
//! shape functions in `x` ([`shape`]). A cable of `n` equal elements has `6 (n + 1)`
//! coordinates ordered node by node, `[r_0, r'_0, r_1, r'_1, ...]`.
//!
//! * Axial strain: the Green strain `eps0 = (r'.r' - 1)/2` of the paper (Eq. 37), stress
//!   resultant `N = EA (g eps0 + c eps0dot)` with internal damping `c` (the line type's
//!   `damping`, s). `g` is the crate's slack rule: 0 in compression unless the line
//!   type allows compression. The tension reported is `N |r'|` (the magnitude of the
//!   section force `N r'`); it equals the GLMF's `EA eps` to first order in the strain
//!   (relative difference `1.5 eps`).
//! * Bending: the full curvature `kappa = |r'' x r'| / |r'|^3` of the paper (Eq. 47),
//!   not the simplified `|r''|`: the simplified form is the curvature only for a unit,
//!   uniformly stretched slope and adds a spurious stiffness against stretch varying
//!   along the element, while the full form costs a few cross products per Gauss point.
//!   Its gradient is `d kappa/d q_k = S_k' g1 - S_k'' g2` with two vectors per point, so
//!   the bending force and `kappadot` cost two dot products. The bending moment is
//!   `EI (kappa + c kappadot)` (same `c` as the axial damping, Eq. 47). At zero curvature
//!   the gradient is taken as zero: the elastic force `EI kappa dkappa/dq` is continuous
//!   there, only the damping term's direction is undefined.
//! * External loads per unit unstretched length (Eqs. 42, 49-50) with the GLMF's
//!   [`Coefs`](crate::physics::Coefs): normal and tangential drag on the relative
//!   velocity `U(r) - rdot` with the local tangent `r'/|r'|` (multiplied by the stretch
//!   `|r'|`, like the GLMF's drag on the stretched length `l`), the water-acceleration
//!   load `(1 + Cm) rho A P a_w`, weight less buoyancy, and seabed contact: the crate's
//!   [`seabed_force`](crate::physics::seabed_force) per metre of cable at each Gauss
//!   point (Eq. 49 with `zdot` for the paper's garbled damping term and the friction
//!   regularised below `v_eps`).
//! * Quadrature: `n`-point Gauss-Legendre per element, 5 by default
//!   ([`AncfConfig::gauss_points`]): exact for the mass matrix (degree 6) and for the
//!   elastic axial force of the Green strain (degree 8); the drag and the curvature
//!   terms are not polynomials and are integrated to the rule's accuracy. The elastic
//!   forces are the exact gradient of the quadrature's strain energy, so the discrete
//!   system is conservative when drag and damping are off.
//! * Mass: the consistent matrix `int S^T (mbar I + Cm rho A P) S dx` of Eqs. 43-44 with
//!   the normal projection `P = I - t t^T` evaluated with the current tangent at each
//!   Gauss point (exact, like the GLMF's tangent-dependent added mass). It is therefore
//!   re-assembled and re-factored at every evaluation when `Cm > 0`: a band Cholesky of
//!   half-bandwidth 11 ([`band`]). [`AddedMass::Isotropic`] takes `Cm rho A I` instead
//!   (tangential added mass the physics does not have, but a constant matrix factored
//!   once: 2-3x faster; on the GLMF comparison case, `Cm rho A / mbar = 0.05`, it
//!   changes the ANCF-GLMF difference from 1.16e-4 to 1.17e-4 of the length). With
//!   `Cm = 0` or no water the matrix is constant anyway. Point masses (with their isotropic added mass `Ca rho V`) add to
//!   the position coordinates of end nodes, with their buoyancy and isotropic drag as
//!   in the GLMF.
//!
//! # Constraints
//! An end on a [`Route`](crate::model::Route) (fixed or driven) has its three position
//! coordinates prescribed; its slope stays free (a pinned end) unless the end also
//! clamps it ([`AncfEnd::clamped`], a cantilever's root). Prescribed coordinates are
//! eliminated directly, not stabilised: their values and rates are set from the route at
//! every stage, their accelerations `a_p` are the route's, the free accelerations solve
//! `M_ff a_f = F_f - M_fp a_p`. No Baumgarte gains, no drift. The force an end exerts on
//! its support is `F_p - (M a)_p` over its position coordinates (docs/src/model/constraints.md, "End forces").
//!
//! # Time integration
//! Explicit, with the consistent mass solved by its Cholesky factor: symplectic Euler
//! (default, one evaluation per step, as the GLMF stepper), explicit midpoint (RK2) or
//! classical RK4 ([`crate::options::Scheme`]). Explicit because the fastest mode of a
//! 50 m element is slow. The stable step is computed, not guessed
//! ([`AncfCable::stable_dt`]): the largest eigenvalue of the scalar problem
//! `(EA K_a + EI K_b) x = omega^2 (mbar M_s + point masses) x` of a uniform chain with
//! the cable's end conditions (32 elements at most: the top of the spectrum is local),
//! with a strain allowance, plus seabed stiffness, with internal, seabed and friction
//! damping, turned into a step by [`mode_step`](crate::stability::mode_step). For cubic
//! elements it is `omega^2 = 42 EA / (mbar L^2)` in the bulk and `91 EA / (mbar L^2)` at
//! a free end without a point mass. A test shows the bound is the real limit: 0.95 of
//! it runs, 1.25 of it blows up. For the paper's Case 2 wire (`EA = 6.28e7 N`,
//! `mbar = 5.03 kg/m`) with 50 m elements it is 4.2 ms for symplectic Euler (5.9 ms for
//! RK4, at four evaluations a step): the default 0.8 of it takes 2000 s in 600 000
//! steps, 6 s of wall time for a 500 m line of 10 elements (1.1e6 node-steps/s; 2.4 s,
//! 2.8e6 node-steps/s, with [`AddedMass::Isotropic`]); the band Cholesky is half of it.
//! An implicit scheme would need a Newton solve (Jacobian and factorisation) per step
//! to gain a step that the explicit one does not need. Symplectic Euler is first order
//! and conserves a modified energy (no drift); halving its step changes the GLMF
//! comparison by 2 % of the difference.
//!
//! # Static equilibrium
//! [`AncfCable::solve_static`]: Newton's method on the free coordinates at rest, the
//! Jacobian from central differences of each element's force (exact seabed stiffness;
//! slack Gauss points may get their taut stiffness when the exact step fails), a dense
//! LU with Levenberg-Marquardt damping, a capped step backtracked on the potential
//! energy with the drag of the current frozen over the step, the current switched on in
//! steps. It converges from straight or parabolic first guesses on hanging lines and in
//! currents; with seabed contact on coarse elements (a 100 m element bending over the
//! touchdown point with no bending stiffness) it can stall, as Gauss points slip in and
//! out of contact: refine the mesh there.
//!
//! # Outputs
//! Node positions, slopes and velocities; position, velocity, curvature and tension
//! (from the strain) at any arc length; node section forces and tensions from the
//! elements' consistent nodal forces (the accurate tension: the strain of a stiff line
//! oscillates along a cubic element); end forces on supports; energies.
//!
//! # Use
//! ```
//! use cablesim::ancf::{AncfCable, AncfConfig, AncfEnd, StaticOptions};
//! use cablesim::model::{Current, Environment, LineType, PointMass, Route};
//!
//! let lt = LineType {
//!     name: "wire".into(), diameter: 0.04, mass_per_length: 5.0265, ea: 6.2832e7,
//!     damping: 1e-5, cn: 1.0, ct: 0.01, cm: 0.2, cat: 0.0, ei: 10.0, allow_compression: false,
//!     ea_curve: None,
//!     viscoelastic: None,
//! };
//! let top = Route::Circle {
//!     center: [-20.0, 0.0, 0.0], radius: 20.0, period: 62.8, axis: [0.0, 0.0, 1.0],
//!     phase: 0.0, advance: 0.0,
//! };
//! let env = Environment { depth: f64::INFINITY, ..Default::default() };
//! let mut cfg = AncfConfig::new(
//!     lt, 200.0, 4,
//!     AncfEnd::driven(top),
//!     AncfEnd::free([0.0, 0.0, -200.0]).with_point(PointMass { mass: 1000.0, ..Default::default() }),
//!     env,
//! );
//! cfg.current = Current::uniform([1.0, 0.0, 0.0]);
//! let mut cable = AncfCable::new(cfg).unwrap();
//! cable.solve_static(&StaticOptions::default()).unwrap(); // at rest in the current
//! cable.advance_time(1.0).unwrap();
//! let last = cable.node_positions()[4];
//! let top_force = cable.end_forces().unwrap()[0].unwrap(); // on the fairlead, N
//! let t_mid = cable.tension_at(100.0); // N
//! assert!(last[2] < -150.0 && top_force[2] < 0.0 && t_mid > 0.0);
//! ```

mod assembly;
pub mod band;
mod cable;
mod config;
pub mod element;
mod readback;
pub mod shape;
mod stable_step;
mod static_solver;

pub use crate::options::AddedMass;
pub use cable::AncfCable;
pub use config::{AncfConfig, AncfEnd, AUTO_SAFETY};
pub use readback::AncfEnergy;
pub use static_solver::{StaticOptions, StaticReport};
