//! ALE-GLMF: cables of varying length (winch payout and retrieval), paper Sec. 3.1.
//!
//! This module holds what does not depend on the stepper: payout schedules
//! ([`PayoutSchedule`]), the winch description ([`Winch`]), the kinematic mesh state
//! of a winch cable and its remeshing rules ([`WinchTracker`], paper Fig. 14), and
//! the mass-flow force ([`mass_flow_forces`], paper Eq. 39). The CPU stepper applies
//! them (`cpu::CpuSolver::with_winches`), and so does the GPU path
//! (`gpu::GpuSolver::with_winches`): its shaders evaluate the variable element and the
//! mass-flow force from per-step rows the host computes from the schedule, and its
//! remeshing is the CPU path's own code, run on the host at the steps the schedule
//! fixes in advance, with one state read-back per remeshing.
//!
//! # Physical coordinate
//! Every node of a winch cable carries a physical coordinate `p`: the *unstretched*
//! arc length measured **from the cable's far end** (the end opposite the winch). The
//! far end has `p = 0`, the winch node has `p = L(t)`, the deployed length. Measured
//! this way a material node keeps its `p` for ever (the material between it and the
//! far end never changes), so only the winch node's `p` moves, driven by the payout
//! schedule: the ALE constraint `p_w - L(t) = 0` of Eq. 45, which is solved in closed
//! form (`p_w`, `pdot_w = Ldot`, `pddot_w = Lddot` are all known from the schedule; no
//! Lagrange multiplier is needed). Measured from the winch, every node's `p` would
//! change with the payout. An element's unstretched length is `p_{i+1} - p_i`; the
//! only element whose `l0` changes is the *variable element* between the winch node
//! `w` and the first material node `m`:
//!
//! ```text
//!     l0_v(t) = L(t) - p_m
//! ```
//!
//! and with it its mass `mbar l0_v`, its weight, its normal added mass and the seabed
//! tributary lengths of `m` and `w`, all through the ordinary GLMF element
//! (`physics::glmf_element`) evaluated with `l0_v(t)` at the time of each stage.
//!
//! # Kinematics of the variable element (Eqs. 33-36)
//! A material point `p` of the variable element sits at the element-local coordinate
//! `xi = (p - p_m) / (p_w - p_m)` in `[0, 1]` (0 at `m`, 1 at the winch) and at
//! `r = (1 - xi) r_m + xi r_w` (Eq. 34, linear shape functions). With `E = r_w - r_m`
//! and `p_m` fixed, `xidot = -xi Ldot / l0` and its velocity is (Eq. 35)
//!
//! ```text
//!     rdot = (1 - xi) v_m + xi v_w - xi (Ldot / l0) E
//! ```
//!
//! (at the winch, `v_w - Ldot (1 + eps) t`: the paid-out material leaves the winch
//! along the cable at the stretched payout speed). Differentiating again,
//! `rddot = (1 - xi) a_m + xi a_w + rddot_p` with the convective part
//!
//! ```text
//!     rddot_p = xi g,    g = -2 (Ldot / l0) (v_w - v_m) + (2 Ldot^2 / l0^2 - Lddot / l0) E
//! ```
//!
//! The first two terms of `g` are Eq. 36's `2 dN/dp pdot qdot` and `d2N/dp2 pdot^2 q`.
//! The `Lddot` term is Eq. 35's column `dN/dp_w q` times `pddot_w`: the paper keeps it
//! inside `N qddot` because `p` is one of its unknowns; here `pddot_w = Lddot` is
//! prescribed, so it is known and moves to the right-hand side with the rest.
//!
//! # Internal damping (Eq. 40)
//! The damping term `EA c epsdot` acts on the rate of the material strain
//! `eps = l / l0 - 1`. For a fixed element that is `t . (v_b - v_a) / l0`, as in the
//! GLMF; for the variable element `l0` changes too (`l0dot = Ldot`), so
//!
//! ```text
//!     epsdot = (t . (v_b - v_a) - (l / l0) Ldot) / l0
//! ```
//!
//! Without the second term a steadily paid-out element, which lengthens at
//! `Ldot (1 + eps)` at constant strain, would feel a spurious damping force
//! `EA c Ldot / l0` (420 N in `examples/winch_deploy.toml`) and hang at the wrong strain.
//!
//! # Mass-flow force (Eq. 39)
//! The part of the element's inertia `integral mbar N^T rddot dp` that is not carried by
//! the node accelerations becomes a force on the two nodes:
//!
//! ```text
//!     [F_m; F_w] = -integral_{p_m}^{p_w} mbar [1 - xi; xi] rddot_p dp
//!                = -mbar l0 integral_0^1 [1 - xi; xi] xi g dxi
//!     F_m = -mbar l0 g / 6,      F_w = -mbar l0 g / 3
//! ```
//!
//! integrated exactly (the integrand is a polynomial in `xi`). It is added to the
//! GLMF force of `m` (a free node, so it moves it) and of `w` (held, so it only enters
//! the reported winch reaction).
//!
//! *Density.* The paper prints `rho_f A` in Eq. 39; this is read as the **cable's**
//! density, `rho_c A = mbar`. Eq. 39 is the remainder of the cable's own inertia term,
//! whose coefficient in the mass matrix (Eq. 43) is `rho_c A I`; `rddot_p` is the
//! acceleration of cable material sliding along the cable's own shape, which moves no
//! water (a cylinder sliding along its axis displaces nothing), so the fluid enters
//! only through the added mass `Cm rho_f A P` acting on the node (shape) accelerations,
//! as Eqs. 43-44 already have it. With `rho_f` a cable paid out in air (no water)
//! would feel no mass flow at all, which cannot be right.
//!
//! *Lumping.* The node masses are lumped (half of `mbar l0_v` at each end, as
//! everywhere in the GLMF); Eq. 39 is integrated with the consistent `N^T`, as the paper
//! prints it. Row-sum lumping of the same term would put all of `-mbar l0 g / 2` on the
//! winch node and none on `m`; both give the same total, and the split differs by a
//! term of order `l0`.
//!
//! *When it acts.* With zero payout (`Ldot = Lddot = 0`) `g = 0` and the force vanishes
//! (the stepper then skips it, so the ALE path is bitwise the plain GLMF). In steady
//! payout from a still winch, with the material moving as a whole
//! (`v_w - v_m = Ldot (1 + eps) t`, `E = l0 (1 + eps) t`), `g = 0` as well: the force
//! only acts while the payout rate changes or the winch moves relative to the paid-out
//! material.
//!
//! # Remeshing (Fig. 14)
//! The standard element length is `l_s = length / segments` of the scenario. Between
//! steps, at the state's time:
//! - `l0_v > 1.5 l_s`: a material node is inserted at `p = p_m + l_s` (a new element of
//!   exactly `l_s` next to `m`; the variable element keeps `l0_v - l_s > 0.5 l_s`). It is
//!   placed on the chord, at `xi = l_s / l0_v`, with the *material* velocity of that
//!   point (the formula above, convective term included): it is a material node, and
//!   the plain interpolation `(1 - xi) v_m + xi v_w` would jolt it by `xi Ldot`.
//! - `l0_v < 0.5 l_s`: `m` is deleted and the variable element absorbs its neighbour
//!   (`l0_v + l_s < 1.5 l_s`), joining the next material node to the winch.
//!
//! Either way the variable element lands inside `[0.5 l_s, 1.5 l_s]`, so the rules
//! cannot chatter. The cable mass in the water is `mbar (sum of fixed l0 + l0_v) =
//! mbar L(t)` through every insertion and deletion, to round-off.
//!
//! Limits: the deployed length cannot exceed the drum's capacity
//! ([`Winch::drum_length`]), and a cable cannot be hauled in past its last node: with
//! one element left the variable element cannot shrink below `0.5 l_s` (the far-end
//! node would have to be deleted). Both stop the run with an error naming the cable
//! and the time.
//!
//! # Zero payout is exactly GLMF
//! `l0_v` is computed as `l0_base + (dL(t) - dL_base)` from the payout `dL` since
//! `t = 0` and the values at the last remeshing; with zero payout `dL = 0` exactly, so
//! `l0_v` is bitwise the plain element's `l0`, the tributary lengths are unchanged,
//! the mass-flow force is skipped and no remeshing happens.

mod drive;
pub(crate) mod mass_flow;
pub(crate) mod mesh;
pub(crate) mod schedule;
pub(crate) mod winch;

pub(crate) use drive::{advance_with_winches, MeshStepper};
pub use mass_flow::{mass_flow_forces, material_velocity};
pub(crate) use mesh::{AleElem, AleState};

pub use schedule::{Payout, PayoutSchedule};
pub use winch::{MeshOp, Winch, WinchEnd, WinchLimit, WinchTracker, DELETE_RATIO, INSERT_RATIO};
