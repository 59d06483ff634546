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

use crate::math::V3;
use std::sync::Arc;

/// Insert a node when the variable element exceeds this many standard lengths.
pub const INSERT_RATIO: f64 = 1.5;
/// Delete a node when the variable element falls below this many standard lengths.
pub const DELETE_RATIO: f64 = 0.5;

/// The payout at one time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Payout {
    /// Deployed length paid out since `t = 0` (negative when hauled in), m.
    pub dl: f64,
    /// Payout rate `Ldot`, m/s (positive: payout).
    pub rate: f64,
    /// Payout acceleration `Lddot`, m/s^2.
    pub accel: f64,
}

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    Constant {
        rate: f64,
    },
    Rates {
        t: Vec<f64>,
        rate: Vec<f64>,
        /// Integral of the rate from `t[0]` to `t[i]`.
        cum: Vec<f64>,
        /// The integral from `t[0]` to `0`.
        at0: f64,
    },
    Table {
        t: Vec<f64>,
        length: Vec<f64>,
        at0: f64,
    },
}

/// How the deployed length `L(t)` changes: a constant rate, a rate table (piecewise
/// linear in time), or a table of deployed lengths (piecewise linear in time).
#[derive(Clone, Debug, PartialEq)]
pub struct PayoutSchedule {
    kind: Kind,
}

impl PayoutSchedule {
    /// A constant rate, m/s (positive: payout, negative: retrieval): `L = L0 + rate t`.
    pub fn constant(rate: f64) -> Result<Self, String> {
        if !rate.is_finite() {
            return Err(format!("the rate must be a finite number, got {rate}"));
        }
        Ok(Self {
            kind: Kind::Constant { rate },
        })
    }

    /// A rate table: rows `(t, rate)` with times not decreasing; the rate is linear in
    /// time between rows (two rows at the same time make a jump) and held at the first
    /// and last rows' values outside the table. `L = L0 + integral_0^t rate`.
    pub fn rates(rows: &[(f64, f64)]) -> Result<Self, String> {
        if rows.is_empty() {
            return Err("needs at least one row [t, rate]".into());
        }
        for (i, &(t, r)) in rows.iter().enumerate() {
            if !t.is_finite() || !r.is_finite() {
                return Err(format!(
                    "row {i}: [{t}, {r}] is not a pair of finite numbers"
                ));
            }
            if i > 0 && t < rows[i - 1].0 {
                return Err(format!(
                    "row {i}: time {t} s comes before the previous row's {} s (times must not decrease)",
                    rows[i - 1].0
                ));
            }
            if i > 1 && t == rows[i - 1].0 && t == rows[i - 2].0 {
                return Err(format!(
                    "row {i}: three rows at t = {t} s (two make a jump; a third is ambiguous)"
                ));
            }
        }
        let t: Vec<f64> = rows.iter().map(|r| r.0).collect();
        let rate: Vec<f64> = rows.iter().map(|r| r.1).collect();
        let mut cum = vec![0.0; t.len()];
        for i in 1..t.len() {
            cum[i] = cum[i - 1] + (t[i] - t[i - 1]) * 0.5 * (rate[i - 1] + rate[i]);
        }
        let mut s = Self {
            kind: Kind::Rates {
                t,
                rate,
                cum,
                at0: 0.0,
            },
        };
        let a = s.integral(0.0).0;
        if let Kind::Rates { at0, .. } = &mut s.kind {
            *at0 = a;
        }
        Ok(s)
    }

    /// A table of deployed lengths: rows `(t, L)` with strictly increasing times and
    /// `L >= 0`, linearly interpolated, held at the first and last rows outside. The
    /// rate is the slope of the current segment; `Lddot` is zero (a kink is a jump of
    /// the rate: use [`PayoutSchedule::rates`] for smooth ramps).
    pub fn table(rows: &[(f64, f64)]) -> Result<Self, String> {
        if rows.is_empty() {
            return Err("needs at least one row t,length".into());
        }
        for (i, &(t, l)) in rows.iter().enumerate() {
            if !t.is_finite() || !l.is_finite() {
                return Err(format!(
                    "row {i}: ({t}, {l}) is not a pair of finite numbers"
                ));
            }
            if l < 0.0 {
                return Err(format!("row {i}: deployed length {l} m is negative"));
            }
            if i > 0 && t <= rows[i - 1].0 {
                return Err(format!(
                    "row {i}: time {t} s does not increase (previous {} s)",
                    rows[i - 1].0
                ));
            }
        }
        let mut s = Self {
            kind: Kind::Table {
                t: rows.iter().map(|r| r.0).collect(),
                length: rows.iter().map(|r| r.1).collect(),
                at0: 0.0,
            },
        };
        let a = s.table_length(0.0);
        if let Kind::Table { at0, .. } = &mut s.kind {
            *at0 = a;
        }
        Ok(s)
    }

    /// For a table: the deployed length it gives at `t = 0` (which must be the
    /// cable's initial length); `None` for rate schedules.
    pub fn table_length_at_zero(&self) -> Option<f64> {
        match &self.kind {
            Kind::Table { at0, .. } => Some(*at0),
            _ => None,
        }
    }

    /// True when the schedule never changes the length (zero rates, a flat table).
    pub fn is_still(&self) -> bool {
        match &self.kind {
            Kind::Constant { rate } => *rate == 0.0,
            Kind::Rates { rate, .. } => rate.iter().all(|&r| r == 0.0),
            Kind::Table { length, .. } => length.iter().all(|&l| l == length[0]),
        }
    }

    fn table_length(&self, tq: f64) -> f64 {
        let Kind::Table { t, length, .. } = &self.kind else {
            return 0.0;
        };
        let n = t.len();
        if tq <= t[0] {
            return length[0];
        }
        if tq >= t[n - 1] {
            return length[n - 1];
        }
        let i = t.partition_point(|&x| x <= tq).max(1);
        let s = (tq - t[i - 1]) / (t[i] - t[i - 1]);
        length[i - 1] + s * (length[i] - length[i - 1])
    }

    /// For a rate table: `(integral from t[0] to tq, rate, accel)`.
    fn integral(&self, tq: f64) -> (f64, f64, f64) {
        let Kind::Rates { t, rate, cum, .. } = &self.kind else {
            return (0.0, 0.0, 0.0);
        };
        let n = t.len();
        if tq <= t[0] {
            return ((tq - t[0]) * rate[0], rate[0], 0.0);
        }
        if tq >= t[n - 1] {
            return (cum[n - 1] + (tq - t[n - 1]) * rate[n - 1], rate[n - 1], 0.0);
        }
        // The last row at or before tq; then t[i] <= tq < t[i + 1], so the segment
        // has a positive width (a jump's zero-width segment is never selected).
        let i = t.partition_point(|&x| x <= tq) - 1;
        let slope = (rate[i + 1] - rate[i]) / (t[i + 1] - t[i]);
        let s = tq - t[i];
        let r = rate[i] + slope * s;
        (cum[i] + s * 0.5 * (rate[i] + r), r, slope)
    }

    /// Payout at time `t`: length paid out since `t = 0`, rate and acceleration.
    pub fn eval(&self, t: f64) -> Payout {
        match &self.kind {
            Kind::Constant { rate } => Payout {
                dl: rate * t,
                rate: *rate,
                accel: 0.0,
            },
            Kind::Rates { at0, .. } => {
                let (f, rate, accel) = self.integral(t);
                Payout {
                    dl: f - at0,
                    rate,
                    accel,
                }
            }
            Kind::Table { t: ts, length, at0 } => {
                let n = ts.len();
                let rate = if n > 1 && t > ts[0] && t < ts[n - 1] {
                    let i = ts.partition_point(|&x| x <= t).max(1);
                    (length[i] - length[i - 1]) / (ts[i] - ts[i - 1])
                } else {
                    0.0
                };
                Payout {
                    dl: self.table_length(t) - at0,
                    rate,
                    accel: 0.0,
                }
            }
        }
    }
}

/// Which end of its cable a winch is at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WinchEnd {
    /// The cable's start node (its first node).
    Start,
    /// The cable's end node (its last node).
    End,
}

/// A winch paying out or hauling in a cable (docs/src/model/winches.md).
#[derive(Clone, Debug, PartialEq)]
pub struct Winch {
    /// Index of the cable (into `ModelDef::cables`, the same order as `Layout::cables`).
    pub cable: usize,
    /// The end the winch is at; that node must be held (fixed or on a route).
    pub end: WinchEnd,
    /// The payout schedule.
    pub schedule: Arc<PayoutSchedule>,
    /// Drum capacity: the largest deployed length, m (`f64::INFINITY`: no limit).
    pub drum_length: f64,
    /// Standard element length `l_s` of the remeshing rules, m.
    pub element_length: f64,
}

/// Why a winch cannot follow its schedule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WinchLimit {
    /// The schedule pays out more than the drum holds.
    Drum {
        /// Deployed length asked for, m.
        length: f64,
        /// The drum's capacity, m.
        drum: f64,
    },
    /// The schedule hauls in past the cable's last node.
    LastNode {
        /// Deployed length asked for, m.
        length: f64,
        /// The shortest the last element may be (`0.5 l_s`), m.
        min: f64,
    },
}

impl std::fmt::Display for WinchLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            WinchLimit::Drum { length, drum } => write!(
                f,
                "payout past the drum's capacity: the schedule asks for {length:.6} m deployed, the drum holds drum_length = {drum} m"
            ),
            WinchLimit::LastNode { length, min } => write!(
                f,
                "hauled in past the cable's last node: the schedule asks for {length:.6} m deployed, but with one element left it cannot be shorter than 0.5 x the standard element length = {min} m"
            ),
        }
    }
}

/// One change of a winch cable's mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeshOp {
    /// Insert a material node on the variable element at `xi = l_s / l0_v` from the
    /// material node `m` towards the winch.
    Insert {
        /// Where, as a fraction of the variable element from `m`.
        xi: f64,
        /// The variable element's unstretched length before the insertion, m.
        l0_before: f64,
    },
    /// Delete the material node `m` next to the winch; the variable element absorbs
    /// its neighbour.
    Delete,
}

/// The kinematic mesh state of one winch cable: the unstretched lengths of its fixed
/// elements and the variable element's length as a function of the payout. It makes
/// every remeshing decision; the stepper moves nodes accordingly.
#[derive(Clone, Debug, PartialEq)]
pub struct WinchTracker {
    /// Standard element length `l_s`, m.
    pub l_std: f64,
    /// Drum capacity, m.
    pub drum: f64,
    /// Deployed length at `t = 0` (sum of the initial `l0`), m.
    pub length0: f64,
    /// Unstretched lengths of the fixed elements, from the far end towards the winch
    /// (the last one is next to the variable element), m.
    pub fixed: Vec<f64>,
    /// The variable element's `l0` at the last remeshing, m.
    pub base_l0: f64,
    /// The payout `dL` at the last remeshing, m.
    pub base_dl: f64,
    /// Nodes inserted so far.
    pub inserted: u64,
    /// Nodes deleted so far.
    pub deleted: u64,
}

impl WinchTracker {
    /// The state at `t = 0` of a cable whose element lengths, start to end, are
    /// `l0s`, with payout `dl0` at `t = 0` (zero for every schedule).
    pub fn new(w: &Winch, l0s: &[f64], dl0: f64) -> Self {
        let mut fixed: Vec<f64> = l0s.to_vec();
        let base_l0 = match w.end {
            WinchEnd::Start => {
                let v = fixed.remove(0);
                fixed.reverse();
                v
            }
            WinchEnd::End => fixed.pop().expect("a cable has an element"),
        };
        let length0 = l0s.iter().sum();
        Self {
            l_std: w.element_length,
            drum: w.drum_length,
            length0,
            fixed,
            base_l0,
            base_dl: dl0,
            inserted: 0,
            deleted: 0,
        }
    }

    /// Number of elements of the cable now.
    pub fn n_elements(&self) -> usize {
        self.fixed.len() + 1
    }

    /// The variable element's unstretched length at payout `dl`, m.
    #[inline]
    pub fn variable_l0(&self, dl: f64) -> f64 {
        self.base_l0 + (dl - self.base_dl)
    }

    /// Deployed length at payout `dl`, m.
    #[inline]
    pub fn deployed(&self, dl: f64) -> f64 {
        self.length0 + dl
    }

    /// Physical coordinates `p` of the nodes, from the far end (`p = 0`) to the winch
    /// node (`p = L`), at payout `dl`, m.
    pub fn physical_coordinates(&self, dl: f64) -> Vec<f64> {
        let mut p = Vec::with_capacity(self.fixed.len() + 2);
        let mut s = 0.0;
        p.push(s);
        for &l in &self.fixed {
            s += l;
            p.push(s);
        }
        p.push(s + self.variable_l0(dl));
        p
    }

    /// True when the mesh must change (or a limit is passed) at payout `dl`.
    #[inline]
    pub fn needs_action(&self, dl: f64) -> bool {
        let l = self.variable_l0(dl);
        // Written so that NaN asks for action (and then fails).
        !(l <= INSERT_RATIO * self.l_std
            && l >= DELETE_RATIO * self.l_std
            && self.deployed(dl) <= self.drum_limit())
    }

    fn drum_limit(&self) -> f64 {
        self.drum * (1.0 + 1e-12)
    }

    /// Applies the remeshing rules at payout `dl`; returns the operations in order, or
    /// the limit the schedule passes (the mesh is then left as it was).
    pub fn remesh(&mut self, dl: f64) -> Result<Vec<MeshOp>, WinchLimit> {
        let length = self.deployed(dl);
        if length > self.drum_limit() || length.is_nan() {
            return Err(WinchLimit::Drum {
                length,
                drum: self.drum,
            });
        }
        let mut ops = Vec::new();
        loop {
            let l = self.variable_l0(dl);
            if l > INSERT_RATIO * self.l_std {
                ops.push(MeshOp::Insert {
                    xi: self.l_std / l,
                    l0_before: l,
                });
                self.fixed.push(self.l_std);
                self.base_l0 = l - self.l_std;
                self.base_dl = dl;
                self.inserted += 1;
            } else if l < DELETE_RATIO * self.l_std {
                let Some(f) = self.fixed.pop() else {
                    return Err(WinchLimit::LastNode {
                        length,
                        min: DELETE_RATIO * self.l_std,
                    });
                };
                ops.push(MeshOp::Delete);
                self.base_l0 = l + f;
                self.base_dl = dl;
                self.deleted += 1;
            } else {
                return Ok(ops);
            }
        }
    }

    /// Follows the schedule over the step times `(step0 + k) dt`, `k = 1..=nsteps`,
    /// without dynamics: the mesh sequence the stepper will go through. Returns the
    /// fewest elements reached, or the first step time at which a limit is passed.
    pub fn scan(
        &mut self,
        schedule: &PayoutSchedule,
        dt: f64,
        step0: u64,
        nsteps: u64,
    ) -> Result<usize, (f64, WinchLimit)> {
        let mut fewest = self.n_elements();
        for k in 1..=nsteps {
            let t = (step0 + k) as f64 * dt;
            let dl = schedule.eval(t).dl;
            if self.needs_action(dl) {
                self.remesh(dl).map_err(|e| (t, e))?;
                fewest = fewest.min(self.n_elements());
            }
        }
        Ok(fewest)
    }
}

/// The mass-flow forces of Eq. 39 on the variable element's material node `m` and
/// winch node `w` (see the module doc): `(-mbar l0 g / 6, -mbar l0 g / 3)` with
/// `g = -2 (Ldot / l0) (v_w - v_m) + (2 Ldot^2 / l0^2 - Lddot / l0) (r_w - r_m)`.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn mass_flow_forces(
    mbar: f64,
    l0: f64,
    rate: f64,
    accel: f64,
    rm: V3<f64>,
    rw: V3<f64>,
    vm: V3<f64>,
    vw: V3<f64>,
) -> (V3<f64>, V3<f64>) {
    let il0 = 1.0 / l0;
    let g = (vw - vm) * (-2.0 * rate * il0) + (rw - rm) * ((2.0 * rate * rate * il0 - accel) * il0);
    let s = -mbar * l0;
    (g * (s / 6.0), g * (s / 3.0))
}

/// The material velocity of the point at `xi` (from `m`, 0, to the winch, 1) of the
/// variable element: `(1 - xi) v_m + xi v_w - xi (Ldot / l0) (r_w - r_m)`.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn material_velocity(
    xi: f64,
    l0: f64,
    rate: f64,
    rm: V3<f64>,
    rw: V3<f64>,
    vm: V3<f64>,
    vw: V3<f64>,
) -> V3<f64> {
    vm * (1.0 - xi) + vw * xi - (rw - rm) * (xi * rate / l0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_integrate_exactly() {
        let s =
            PayoutSchedule::rates(&[(0.0, 0.0), (10.0, 1.0), (20.0, 1.0), (20.0, -1.0)]).unwrap();
        let p = s.eval(5.0);
        assert!((p.dl - 1.25).abs() < 1e-12 && (p.rate - 0.5).abs() < 1e-12);
        assert!((p.accel - 0.1).abs() < 1e-12);
        let p = s.eval(15.0);
        assert!((p.dl - 10.0).abs() < 1e-12 && p.rate == 1.0 && p.accel == 0.0);
        let p = s.eval(25.0);
        assert!((p.dl - 10.0).abs() < 1e-12 && p.rate == -1.0, "{p:?}");
        // Derivatives agree with finite differences.
        for &t in &[3.0, 12.0, 30.0] {
            let h = 1e-5;
            let fd = (s.eval(t + h).dl - s.eval(t - h).dl) / (2.0 * h);
            assert!((fd - s.eval(t).rate).abs() < 1e-8);
        }
        assert_eq!(
            PayoutSchedule::rates(&[(0.0, 0.0)]).unwrap().eval(7.0).dl,
            0.0
        );
    }

    #[test]
    fn table_interpolates_and_holds() {
        let s = PayoutSchedule::table(&[(0.0, 10.0), (10.0, 20.0), (20.0, 15.0)]).unwrap();
        assert_eq!(s.table_length_at_zero(), Some(10.0));
        let p = s.eval(5.0);
        assert_eq!((p.dl, p.rate), (5.0, 1.0));
        assert_eq!(s.eval(15.0).rate, -0.5);
        assert_eq!(s.eval(30.0).dl, 5.0);
        assert_eq!(s.eval(30.0).rate, 0.0);
    }

    #[test]
    fn tracker_keeps_the_variable_element_in_band() {
        let w = Winch {
            cable: 0,
            end: WinchEnd::Start,
            schedule: Arc::new(PayoutSchedule::constant(1.0).unwrap()),
            drum_length: 100.0,
            element_length: 2.0,
        };
        let mut tr = WinchTracker::new(&w, &[2.0; 5], 0.0);
        for k in 1..=500 {
            let dl = 0.1 * k as f64;
            tr.remesh(dl).unwrap();
            let l = tr.variable_l0(dl);
            assert!((1.0..=3.0).contains(&l), "{l}");
            let total: f64 = tr.fixed.iter().sum::<f64>() + l;
            assert!((total - tr.deployed(dl)).abs() < 1e-9);
        }
        assert!(matches!(tr.remesh(95.0), Err(WinchLimit::Drum { .. })));
    }

    #[test]
    fn mass_flow_vanishes_in_steady_payout() {
        let (l0, eps, rate) = (3.0, 0.01, 0.7);
        let t = V3::new(0.0, 0.0, 1.0);
        let rw = V3::new(0.0, 0.0, 0.0);
        let rm = rw - t * (l0 * (1.0 + eps));
        let vw = V3::zero();
        let vm = t * (-rate * (1.0 + eps));
        let (fm, fw) = mass_flow_forces(5.0, l0, rate, 0.0, rm, rw, vm, vw);
        assert!(fm.norm() < 1e-12 && fw.norm() < 1e-12, "{fm:?} {fw:?}");
        // Material velocity is uniform along the element.
        for xi in [0.0, 0.3, 1.0] {
            let v = material_velocity(xi, l0, rate, rm, rw, vm, vw);
            assert!((v - vm).norm() < 1e-12);
        }
        // A stopping payout pushes the material node away from the winch.
        let (fm, _) = mass_flow_forces(5.0, l0, rate, -1.0, rm, rw, vm, vw);
        assert!(fm.z < 0.0);
    }
}
