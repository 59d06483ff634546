//! Winch cables (ALE-GLMF, [`crate::ale`]) on the chain fast path.
//!
//! The variable element goes through the vectorised element loop like every other
//! element: per stage, its entries of a working copy of the chain constants (`1/l0`,
//! half weight, buoyancy, water-acceleration coefficient, half masses, its nodes'
//! seabed constants) are set from its `l0` at that time, and only the damping term of
//! a paid-out element (`EA c l Ldot / l0^2`, crate::ale) is fixed up after the loop.
//! The mass-flow forces of Eq. 39 join the per-node extra forces that the node loop
//! adds before its solve. The schedule is evaluated once per stage, and whether each
//! variable element's nodes are held is found once per run of steps (a held node's
//! acceleration is its route's, so its mass-flow force is not needed there).

use super::ChainConsts;
use crate::ale::{mass_flow_forces, AleElem, Payout, PayoutSchedule};
use crate::math::V3;
use crate::model::Layout;
use std::sync::Arc;

/// What a run of steps keeps about one variable element: its indices, whether its
/// nodes are free, its constants folded once (per unit `l0`, and the block's own
/// values at the last remeshing), and its payout and `l0` at the current stage.
#[derive(Clone, Default)]
struct AleRun {
    k: usize,
    m: usize,
    w: usize,
    m_free: bool,
    w_free: bool,
    /// The rate of a constant-rate schedule (evaluated here, inline).
    rate: Option<f64>,
    sched: Option<Arc<PayoutSchedule>>,
    base_l0: f64,
    base_dl: f64,
    /// `mbar`, kg/m.
    mass: f64,
    /// `EA c` of its line.
    eac: f64,
    /// Per unit `l0`: half the weight less buoyancy, half the buoyancy, half the
    /// water-acceleration coefficients across and along, half the mass, half the
    /// tangential added mass, half the normal less the tangential added mass.
    per_l0: [f64; 7],
    /// The block's `1/l0`, `half_wz`, `half_bz`, `half_fk`, `half_fkt`, `hmd`, `hat`,
    /// `ha` of the element.
    base: [f64; 8],
    /// Tributary lengths of `m` and `w` at the last remeshing, m.
    trib: [f64; 2],
    /// Payout and `l0` at the current stage.
    pay: Payout,
    l0: f64,
}

/// What one run of steps keeps about its block's variable elements.
#[derive(Default)]
pub(super) struct AleScratch {
    runs: Vec<AleRun>,
    /// Whether the block has a seabed (only then do the variable element's nodes'
    /// seabed constants, read by the node loop's contact terms, need updating).
    seabed: bool,
    /// The nodes whose per-node extra forces a stage may write: the free ends of the
    /// variable elements ([`ale_mass_flow`]) and the nodes with point drag or a point's
    /// water-acceleration load (`nodes`), each once; what [`extra_forces_clear`] zeroes
    /// again (one loop, not one a list).
    extra_nodes: Vec<usize>,
}

impl AleScratch {
    /// Sets up a run of steps of a block with the constants `c` and variable elements
    /// `ale`.
    ///
    /// # Panics
    /// If a variable element or one of its nodes is not in the block: the per-stage
    /// functions below index the block's columns without checks on that ground.
    pub fn prepare(&mut self, c: &ChainConsts, lay: &Layout, ale: &[AleElem]) {
        let held = |i: usize| c.constrained.iter().any(|&(j, _)| j == i);
        // Friction needs a seabed; the node loop's own test (`nodes`).
        self.seabed = c.friction || c.zb.is_finite();
        self.extra_nodes.clear();
        let points = c.point_drag.iter().map(|pd| pd.0);
        let points = points.chain(c.point_volume.iter().map(|pv| pv.0));
        let flow = ale.iter().flat_map(|ae| [ae.m, ae.w]).filter(|&i| !held(i));
        for i in flow.chain(points) {
            assert!(i < c.n, "node {i} outside its chain of {} nodes", c.n);
            if !self.extra_nodes.contains(&i) {
                self.extra_nodes.push(i);
            }
        }
        self.runs.clear();
        self.runs.extend(ale.iter().map(|ae| {
            let k = ae.elem;
            assert!(
                k + 1 < c.n && ae.m < c.n && ae.w < c.n,
                "variable element {k} (nodes {}, {}) outside its chain of {} nodes",
                ae.m,
                ae.w,
                c.n
            );
            let lc = &lay.line_coefs[c.line[k] as usize];
            AleRun {
                k,
                m: ae.m,
                w: ae.w,
                m_free: !held(ae.m),
                w_free: !held(ae.w),
                rate: ae.sched.constant_rate(),
                sched: Some(ae.sched.clone()),
                base_l0: ae.base_l0,
                base_dl: ae.base_dl,
                mass: ae.mass,
                eac: c.eac[k],
                // The products of `ChainConsts::new`, `0.5 * x * l0`, as `(0.5 * x) * l0`.
                per_l0: [
                    0.5 * lc.wet_weight_z,
                    0.5 * (lc.wet_weight_z + lc.mass * lay.env.gravity),
                    0.5 * lc.froude_krylov,
                    0.5 * lc.froude_krylov_t,
                    0.5 * lc.mass,
                    0.5 * lc.added_mass_t,
                    0.5 * (lc.added_mass - lc.added_mass_t),
                ],
                base: [
                    c.il0[k],
                    c.half_wz[k],
                    c.half_bz[k],
                    c.half_fk[k],
                    c.half_fkt[k],
                    c.hmd[k],
                    c.hat[k],
                    c.ha[k + 1],
                ],
                trib: [c.trib[ae.m], c.trib[ae.w]],
                pay: Payout::default(),
                l0: ae.base_l0,
            }
        }));
    }
}

/// Sets the variable elements' entries of the working constants `wc` (a copy of the
/// block's constants) for time `time`. When nothing has been paid out since the last
/// remeshing and the rate is zero, they are the block's own, bit for bit (the plain
/// GLMF); otherwise they follow the current `l0`, with the formulas of
/// [`ChainConsts::new`].
///
/// # Safety
/// `sc` was prepared for `wc`'s block ([`AleScratch::prepare`] checked the indices
/// against its `n`), and every column of `wc` has at least `wc.n + 1` entries (the
/// padded columns of a run of steps: [`super::lanes::padded_len`]).
#[inline(always)]
pub(super) unsafe fn ale_constants(sc: &mut AleScratch, time: f64, wc: &mut ChainConsts) {
    // SAFETY (every use): indices below `wc.n + 1`, as the contract says.
    macro_rules! set {
        ($col:expr, $i:expr, $v:expr) => {
            unsafe { *$col.get_unchecked_mut($i) = $v }
        };
    }
    for r in sc.runs.iter_mut() {
        let pay = match (r.rate, &r.sched) {
            (Some(rate), _) => Payout::of_constant(rate, time),
            (None, Some(s)) => s.eval(time),
            (None, None) => Payout::default(),
        };
        // `AleElem::l0`.
        let l0 = r.base_l0 + (pay.dl - r.base_dl);
        (r.pay, r.l0) = (pay, l0);
        let [il0, hw, hb, hfk, hfkt, hmd, hat, ha] = if l0 != r.base_l0 || pay.rate != 0.0 {
            let q = r.per_l0;
            [
                1.0 / l0,
                q[0] * l0,
                q[1] * l0,
                q[2] * l0,
                q[3] * l0,
                q[4] * l0,
                q[5] * l0,
                q[6] * l0,
            ]
        } else {
            r.base
        };
        let k = r.k;
        set!(wc.il0, k, il0);
        set!(wc.half_wz, k, hw);
        set!(wc.half_bz, k, hb);
        set!(wc.half_fk, k, hfk);
        set!(wc.half_fkt, k, hfkt);
        set!(wc.hmd, k, hmd);
        set!(wc.hat, k, hat);
        // Wholly wet, the half mass along the tangent (`ChainConsts::new`).
        set!(wc.hm, k + 1, hmd + hat);
        set!(wc.ha, k + 1, ha);
        // Without a seabed `sb_k = sb_c = 0`, and the node loop does not read these.
        if sc.seabed {
            for (i, trib) in [(r.m, r.trib[0]), (r.w, r.trib[1])] {
                let lt = trib + 0.5 * (l0 - r.base_l0);
                set!(wc.kl, i, wc.sb_k * lt);
                set!(wc.cl, i, wc.sb_c * lt);
                set!(wc.mukl, i, wc.sb_mu * wc.sb_k * lt);
            }
        }
    }
}

/// After the element loop: the damping of a paid-out variable element acts on the
/// material strain rate, `epsdot = (t . dv - (l / l0) Ldot) / l0` (crate::ale), so
/// its tension (padded array `ten`) loses `EA c l Ldot / l0^2`.
///
/// # Safety
/// As [`ale_constants`], for the columns of `p` and `ten`.
#[inline(always)]
pub(super) unsafe fn ale_tension(sc: &AleScratch, p: &[Vec<f64>; 6], ten: &mut [f64]) {
    for r in &sc.runs {
        let rate = r.pay.rate;
        if rate != 0.0 {
            let k = r.k;
            // SAFETY: `k + 1` is a node of the block, as the contract says.
            let d = |q: usize| unsafe { p[q].get_unchecked(k + 1) - p[q].get_unchecked(k) };
            let (dx, dy, dz) = (d(0), d(1), d(2));
            let l = (dx * dx + dy * dy + dz * dz).sqrt();
            // SAFETY: as above.
            unsafe { *ten.get_unchecked_mut(k + 1) -= r.eac * l * rate / (r.l0 * r.l0) };
        }
    }
}

/// The mass-flow forces of Eq. 39 on the variable elements' free nodes, added to the
/// per-node extra forces `xf`; returns whether any was added.
///
/// # Safety
/// As [`ale_constants`], for the columns of `p` and `xf`.
#[inline(always)]
pub(super) unsafe fn ale_mass_flow(
    sc: &AleScratch,
    p: &[Vec<f64>; 6],
    xf: &mut [&mut [f64]; 3],
) -> bool {
    let mut any = false;
    for r in &sc.runs {
        let pay = r.pay;
        if pay.rate == 0.0 && pay.accel == 0.0 {
            continue;
        }
        let (m, w) = (r.m, r.w);
        // SAFETY: `m` and `w` are nodes of the block, as the contract says.
        let at = |q: usize, i: usize| unsafe { *p[q].get_unchecked(i) };
        let (fm, fw) = mass_flow_forces(
            r.mass,
            r.l0,
            pay.rate,
            pay.accel,
            V3::new(at(0, m), at(1, m), at(2, m)),
            V3::new(at(0, w), at(1, w), at(2, w)),
            V3::new(at(3, m), at(4, m), at(5, m)),
            V3::new(at(3, w), at(4, w), at(5, w)),
        );
        for (free, i, f) in [(r.m_free, m, fm), (r.w_free, w, fw)] {
            if free {
                for (x, fq) in xf.iter_mut().zip([f.x, f.y, f.z]) {
                    // SAFETY: as above.
                    unsafe { *x.get_unchecked_mut(i) += fq };
                }
                any = true;
            }
        }
    }
    any
}

/// Clears the per-node extra forces a stage wrote (the mass flow's, the points').
///
/// # Safety
/// As [`ale_constants`], for the columns of `xf`.
#[inline(always)]
pub(super) unsafe fn extra_forces_clear(sc: &AleScratch, xf: &mut [&mut [f64]; 3]) {
    for &i in &sc.extra_nodes {
        for x in xf.iter_mut() {
            // SAFETY: `i` is a node of the block, as the contract says.
            unsafe { *x.get_unchecked_mut(i) = 0.0 };
        }
    }
}
