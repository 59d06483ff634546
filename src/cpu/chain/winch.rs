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
use crate::ale::{mass_flow_forces, AleElem, Payout};
use crate::math::V3;
use crate::model::Layout;

/// A variable element's payout and `l0` at the time of one stage.
#[derive(Clone, Copy, Default)]
pub(super) struct AleStage {
    pub pay: Payout,
    pub l0: f64,
}

/// What one run of steps keeps about its block's variable elements.
#[derive(Default)]
pub(super) struct AleScratch {
    /// Per variable element: whether its material node and its winch node are held.
    held: Vec<(bool, bool)>,
    /// Per variable element: its payout and `l0` at the current stage.
    pub stage: Vec<AleStage>,
}

impl AleScratch {
    /// Sets up a run of steps of a block with the constants `c` and variable elements
    /// `ale`.
    pub fn prepare(&mut self, c: &ChainConsts, ale: &[AleElem]) {
        let held = |i: usize| c.constrained.iter().any(|&(j, _)| j == i);
        self.held.clear();
        self.held
            .extend(ale.iter().map(|ae| (held(ae.m), held(ae.w))));
        self.stage.clear();
        self.stage.resize(ale.len(), AleStage::default());
    }
}

/// Sets the variable elements' entries of the working constants `wc` (a copy of the
/// block's `c`) for time `time`. When nothing has been paid out since the last
/// remeshing and the rate is zero, they are the block's own, bit for bit (the plain
/// GLMF); otherwise they follow the current `l0`, with the formulas of
/// [`ChainConsts::new`].
pub(super) fn ale_constants(
    c: &ChainConsts,
    lay: &Layout,
    ale: &[AleElem],
    time: f64,
    stage: &mut [AleStage],
    wc: &mut ChainConsts,
) {
    for (ae, st) in ale.iter().zip(stage.iter_mut()) {
        let pay = ae.sched.eval(time);
        let l0 = ae.l0(pay.dl);
        *st = AleStage { pay, l0 };
        let k = ae.elem;
        if l0 != ae.base_l0 || pay.rate != 0.0 {
            let lc = &lay.line_coefs[c.line[k] as usize];
            wc.il0[k] = 1.0 / l0;
            wc.half_wz[k] = 0.5 * lc.wet_weight_z * l0;
            wc.half_bz[k] = 0.5 * (lc.wet_weight_z + lc.mass * lay.env.gravity) * l0;
            wc.half_fk[k] = 0.5 * lc.froude_krylov * l0;
            wc.hm[k + 1] = 0.5 * lc.mass * l0;
            wc.ha[k + 1] = 0.5 * lc.added_mass * l0;
        } else {
            wc.il0[k] = c.il0[k];
            wc.half_wz[k] = c.half_wz[k];
            wc.half_bz[k] = c.half_bz[k];
            wc.half_fk[k] = c.half_fk[k];
            wc.hm[k + 1] = c.hm[k + 1];
            wc.ha[k + 1] = c.ha[k + 1];
        }
        for i in [ae.m, ae.w] {
            // Without a seabed `sb_k = sb_c = 0`, so the tributary length does not matter.
            let lt = c.trib[i] + 0.5 * (l0 - ae.base_l0);
            wc.kl[i] = c.sb_k * lt;
            wc.cl[i] = c.sb_c * lt;
            wc.mukl[i] = c.sb_mu * c.sb_k * lt;
        }
    }
}

/// After the element loop: the damping of a paid-out variable element acts on the
/// material strain rate, `epsdot = (t . dv - (l / l0) Ldot) / l0` (crate::ale), so
/// its tension (padded array `ten`) loses `EA c l Ldot / l0^2`.
pub(super) fn ale_tension(
    c: &ChainConsts,
    ale: &[AleElem],
    stage: &[AleStage],
    p: &[Vec<f64>; 6],
    ten: &mut [f64],
) {
    for (ae, st) in ale.iter().zip(stage) {
        let rate = st.pay.rate;
        if rate != 0.0 {
            let k = ae.elem;
            let (dx, dy, dz) = (
                p[0][k + 1] - p[0][k],
                p[1][k + 1] - p[1][k],
                p[2][k + 1] - p[2][k],
            );
            let l = (dx * dx + dy * dy + dz * dz).sqrt();
            ten[k + 1] -= c.eac[k] * l * rate / (st.l0 * st.l0);
        }
    }
}

/// The mass-flow forces of Eq. 39 on the variable elements' free nodes, added to the
/// per-node extra forces `xf`; returns whether any was added.
pub(super) fn ale_mass_flow(
    ale: &[AleElem],
    sc: &AleScratch,
    p: &[Vec<f64>; 6],
    xf: &mut [Vec<f64>; 3],
) -> bool {
    let mut any = false;
    for ((ae, st), &(m_held, w_held)) in ale.iter().zip(&sc.stage).zip(&sc.held) {
        let pay = st.pay;
        if pay.rate == 0.0 && pay.accel == 0.0 {
            continue;
        }
        let node = |i: usize| {
            (
                V3::new(p[0][i], p[1][i], p[2][i]),
                V3::new(p[3][i], p[4][i], p[5][i]),
            )
        };
        let ((rm, vm), (rw, vw)) = (node(ae.m), node(ae.w));
        let (fm, fw) = mass_flow_forces(ae.mass, st.l0, pay.rate, pay.accel, rm, rw, vm, vw);
        for (i, f, held) in [(ae.m, fm, m_held), (ae.w, fw, w_held)] {
            if !held {
                xf[0][i] += f.x;
                xf[1][i] += f.y;
                xf[2][i] += f.z;
                any = true;
            }
        }
    }
    any
}

/// Clears the entries [`ale_mass_flow`] wrote.
pub(super) fn ale_mass_flow_clear(ale: &[AleElem], xf: &mut [Vec<f64>; 3]) {
    for ae in ale {
        for i in [ae.m, ae.w] {
            for x in xf.iter_mut() {
                x[i] = 0.0;
            }
        }
    }
}
