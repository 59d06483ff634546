//! Static equilibrium of an ANCF cable ([`AncfCable::solve_static`]): Newton's method
//! with Levenberg-Marquardt damping on the free coordinates.

use super::assembly::{Model, Ws};
use super::cable::AncfCable;
use super::element::{element_forces, kinematics, ElementEnv};
use crate::error::Error;
use nalgebra::{DMatrix, DVector};

/// Options of [`AncfCable::solve_static`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticOptions {
    /// Residual tolerance relative to the load scale (the sum of the magnitudes of the
    /// external loads).
    pub rel_tol: f64,
    /// Newton iterations at most.
    pub max_iterations: usize,
    /// Largest position change of a node per iteration, in element lengths.
    pub max_step: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            rel_tol: 1e-10,
            max_iterations: 100,
            max_step: 0.5,
        }
    }
}

/// What [`AncfCable::solve_static`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticReport {
    /// Newton iterations done.
    pub iterations: usize,
    /// Largest residual generalized force on a free coordinate at the end, N (slope
    /// coordinates' residuals, N m, divided by the element length).
    pub max_residual: f64,
    /// The tolerance it was held to, N.
    pub tolerance: f64,
}
impl AncfCable {
    /// Moves the free coordinates to static equilibrium at the current time (every
    /// velocity zero; routes at their current positions; drag of the current included).
    /// Afterwards free coordinates are at rest and prescribed ones move with their routes
    /// (a driven end starts moving at once, as the GLMF's does).
    ///
    /// Newton's method with Levenberg-Marquardt damping: the Jacobian `K = -dF/dq` is
    /// assembled from central differences of each element's generalized force (steps
    /// `1e-6` element lengths for positions, `1e-6` for slopes) and solved by a dense LU
    /// as `(K + mu diag|K|) dq = F`; `mu` starts at 0 (pure Newton) and grows tenfold
    /// whenever a step fails. A step is capped at `max_step` element lengths and
    /// backtracked. In still water it must lower the potential energy (strain, weights,
    /// applied forces, seabed), the function the static forces are the gradient of, or,
    /// where energy differences are below round-off, the residual norm. With a current
    /// (drag has no potential) the current is switched on in steps (0, 1/4, ..., 1 of
    /// its speed), each solved from the last with the residual norm as the merit.
    ///
    /// Converged when the largest residual on a free coordinate (N; slope coordinates'
    /// N m divided by the element length) is at most `rel_tol` times the load scale, or
    /// the round-off floor `64 eps (EA + EI / L^2)`.
    ///
    /// Errors (`Error::Statics`): no convergence within `max_iterations` per stage.
    pub fn solve_static(&mut self, opts: &StaticOptions) -> Result<StaticReport, Error> {
        // The payout stands still in a static solution (the variable element keeps its
        // length now); restored afterwards, whatever the outcome.
        let frozen = self.m.ale.as_ref().map(|a| a.frozen);
        if let Some(a) = self.m.ale.as_mut() {
            a.frozen = true;
        }
        let rep = self.solve_static_frozen(opts);
        if let (Some(a), Some(f)) = (self.m.ale.as_mut(), frozen) {
            a.frozen = f;
        }
        rep
    }

    fn solve_static_frozen(&mut self, opts: &StaticOptions) -> Result<StaticReport, Error> {
        let t = self.t;
        self.m.apply_prescribed(&mut self.q, &mut self.qd, t);
        self.qd.iter_mut().for_each(|x| *x = 0.0);
        let flow = !self.m.current.is_still() || self.m.water_accel.norm() > 0.0;
        let stages: &[f64] = if flow {
            &[0.0, 0.25, 0.5, 0.75, 1.0]
        } else {
            &[1.0]
        };
        let still = self.m.with_flow(0.0);
        let mut total = 0;
        let mut last = None;
        for &s in stages {
            let m = if flow {
                self.m.with_flow(s)
            } else {
                self.m.clone()
            };
            let mut rep = newton(&m, &still, &mut self.q, &self.qd, t, &mut self.ws, opts)?;
            total += rep.iterations;
            rep.iterations = total;
            last = Some(rep);
        }
        // At rest, but a driven end moves with its route from the start.
        self.m.apply_prescribed(&mut self.q, &mut self.qd, t);
        Ok(last.expect("at least one stage"))
    }
}

/// Newton-Levenberg-Marquardt on the free coordinates of `q` (see
/// [`AncfCable::solve_static`]). `still` is `m` without current: the potential energy
/// of its loads, plus the work of the rest of `m`'s loads frozen at the iterate, is the
/// merit function of the line search.
fn newton(
    m: &Model,
    still: &Model,
    q: &mut [f64],
    qd: &[f64],
    t: f64,
    ws: &mut Ws,
    opts: &StaticOptions,
) -> Result<StaticReport, Error> {
    let nd = q.len();
    let free: Vec<usize> = (0..nd).filter(|&i| !m.is_prescribed[i]).collect();
    let nf = free.len();
    let l_el = m.l_el;
    let scale = |i: usize| if i % 6 < 3 { 1.0 } else { 1.0 / l_el };
    // Residual (free generalized forces, in ws.f) and its max and 2-norm (scaled).
    let residual = |q: &[f64], ws: &mut Ws| -> (f64, f64) {
        m.forces(q, qd, t, ws, false);
        let mut mx = 0.0f64;
        let mut n2 = 0.0;
        for &i in &free {
            let r = ws.f[i] * scale(i);
            mx = mx.max(r.abs());
            n2 += r * r;
        }
        (mx, n2.sqrt())
    };
    let tol = (opts.rel_tol * m.load_scale(q))
        .max(64.0 * f64::EPSILON * (m.coefs.line.ea + m.coefs.ei / (l_el * l_el)))
        .max(1e-12);
    let mut pos = vec![usize::MAX; nd];
    for (k, &i) in free.iter().enumerate() {
        pos[i] = k;
    }
    let (mut mx, mut n2) = residual(q, ws);
    let mut energy = still.potential_energy(q);
    let mut it = 0;
    let (mut mu_exact, mut mu_taut) = (0.0f64, 0.0f64);
    let mut qtry = q.to_vec();
    // The Jacobian's finite differences leave the seabed out (its penetrations, w/K,
    // are far below any useful step); its stiffness is added exactly below.
    let env = ElementEnv {
        seabed: None,
        ..m.env()
    };
    let now = m.ale_now(t);
    while mx.is_nan() || mx > tol {
        if it >= opts.max_iterations || !mx.is_finite() {
            return Err(Error::Statics(format!(
                "ANCF cable '{}': Newton did not converge in {it} iterations: residual {mx:.3e} N, tolerance {tol:.3e} N",
                m.name
            )));
        }
        it += 1;
        let f: Vec<f64> = free.iter().map(|&i| ws.f[i]).collect();
        // The loads without potential (drag of the current), frozen over the step.
        still.forces(q, qd, t, ws, false);
        let f_nc: Vec<f64> = free.iter().zip(&f).map(|(&i, fi)| fi - ws.f[i]).collect();
        // K = -dF/dq over the free coordinates, element by element.
        let mut kmat = DMatrix::<f64>::zeros(nf, nf);
        for e in 0..m.n_el {
            let base = 6 * e;
            let mut qe = [0.0; 12];
            qe.copy_from_slice(&q[base..base + 12]);
            let qde = &qd[base..base + 12];
            let (gps, ale) = m.element_rule(e, &now);
            for j in 0..12 {
                if pos[base + j] == usize::MAX {
                    continue;
                }
                let h = if j % 6 < 3 { 1e-6 * l_el } else { 1e-6 };
                let (mut fp, mut fm) = ([0.0; 12], [0.0; 12]);
                let x0 = qe[j];
                qe[j] = x0 + h;
                element_forces(&m.coefs, gps, &env, &qe, qde, &mut fp, None, ale.as_ref());
                qe[j] = x0 - h;
                element_forces(&m.coefs, gps, &env, &qe, qde, &mut fm, None, ale.as_ref());
                qe[j] = x0;
                for i in 0..12 {
                    let pi = pos[base + i];
                    if pi != usize::MAX {
                        kmat[(pi, pos[base + j])] -= (fp[i] - fm[i]) / (2.0 * h);
                    }
                }
            }
        }
        // Seabed contact: K int S_k S_l e_z e_z^T over the penetrating points (at rest
        // the damping and the regularised friction vanish).
        if let Some(sb) = &m.seabed {
            for e in 0..m.n_el {
                let base = 6 * e;
                for gp in m.element_rule(e, &now).0 {
                    let sh = &gp.shape;
                    let p = kinematics(sh, &q[base..base + 12], &[0.0; 12]);
                    if p.r.z >= sb.z {
                        continue;
                    }
                    for k in 0..4 {
                        for l in 0..4 {
                            let (pi, pj) = (pos[base + 3 * k + 2], pos[base + 3 * l + 2]);
                            if pi != usize::MAX && pj != usize::MAX {
                                kmat[(pi, pj)] += sb.k * gp.dx * sh.s[k] * sh.s[l];
                            }
                        }
                    }
                }
            }
        }
        // Slack points have no axial stiffness: should the exact Jacobian's step fail,
        // give them their taut material stiffness `EA (S_k' S_l') r' r'^T` (in the
        // Jacobian, not in the residual), so Newton's model of a slack stretch is the
        // taut line's, not a free drift (a straight, unstretched first guess).
        let mut ktaut = kmat.clone();
        if m.coefs.line.compression == 0.0 {
            for e in 0..m.n_el {
                let base = 6 * e;
                let qe = &q[base..base + 12];
                for gp in m.element_rule(e, &now).0 {
                    let sh = &gp.shape;
                    let p = kinematics(sh, qe, &[0.0; 12]);
                    if p.r1.norm2() > 1.0 {
                        continue;
                    }
                    let r1 = [p.r1.x, p.r1.y, p.r1.z];
                    let ea = m.coefs.line.ea * gp.dx;
                    for k in 0..4 {
                        for l in 0..4 {
                            let x = ea * sh.ds[k] * sh.ds[l];
                            for a in 0..3 {
                                for b in 0..3 {
                                    let (pi, pj) = (pos[base + 3 * k + a], pos[base + 3 * l + b]);
                                    if pi != usize::MAX && pj != usize::MAX {
                                        ktaut[(pi, pj)] += x * r1[a] * r1[b];
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        // Levenberg-Marquardt scaling: |K_kk|, floored per kind of coordinate (a
        // slack, unbent stretch of line has no stiffness at all).
        let mut kmax = [0.0f64; 2];
        for (k, &i) in free.iter().enumerate() {
            let c = usize::from(i % 6 >= 3);
            kmax[c] = kmax[c].max(ktaut[(k, k)].abs());
        }
        let diag: Vec<f64> = free
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let c = usize::from(i % 6 >= 3);
                ktaut[(k, k)].abs().max(1e-6 * kmax[c]).max(1e-300)
            })
            .collect();
        let rhs = DVector::from_vec(f.clone());
        // Damped steps until one is accepted: the exact Jacobian with its damping grown
        // tenfold up to three times, then (if it differs) the taut one with its own
        // damping grown until a step is accepted.
        let has_taut = ktaut != kmat;
        let mut exact = true;
        let mut tries = 0;
        let mut mu = mu_exact;
        loop {
            let mut a = if exact { kmat.clone() } else { ktaut.clone() };
            for k in 0..nf {
                a[(k, k)] += mu * diag[k];
            }
            let dq = a.lu().solve(&rhs);
            let accepted = match dq {
                Some(dq) if dq.iter().all(|x| x.is_finite()) => {
                    let mut big = 0.0f64;
                    for (k, &i) in free.iter().enumerate() {
                        big = big.max(dq[k].abs() * scale(i));
                    }
                    let mut alpha = if big > opts.max_step * l_el {
                        opts.max_step * l_el / big
                    } else {
                        1.0
                    };
                    let slope: f64 = f.iter().zip(dq.iter()).map(|(a, b)| a * b).sum();
                    let mut ok = false;
                    for _ in 0..6 {
                        qtry.copy_from_slice(q);
                        for (k, &i) in free.iter().enumerate() {
                            qtry[i] += alpha * dq[k];
                        }
                        let (mx1, n21) = residual(&qtry, ws);
                        let work: f64 = f_nc.iter().zip(dq.iter()).map(|(a, b)| a * b).sum();
                        let e1 = still.potential_energy(&qtry) - alpha * work;
                        let noise = 1e-13 * (energy.abs() + e1.abs());
                        let better = (slope > 0.0 && e1 - energy <= -1e-4 * alpha * slope)
                            || ((e1 - energy).abs() <= noise && n21 < n2);
                        if better && mx1.is_finite() {
                            q.copy_from_slice(&qtry);
                            mx = mx1;
                            n2 = n21;
                            energy = still.potential_energy(q);
                            ok = true;
                            break;
                        }
                        alpha *= 0.5;
                    }
                    ok
                }
                _ => false,
            };
            if accepted {
                let next = if mu < 1e-9 { 0.0 } else { mu * 0.1 };
                if exact {
                    mu_exact = next;
                } else {
                    mu_taut = next;
                }
                break;
            }
            if mu > 1e12 {
                // Nothing moves: let the iteration limit report it.
                residual(q, ws);
                break;
            }
            tries += 1;
            if exact && has_taut && tries > 3 {
                exact = false;
                mu = mu_taut;
            } else {
                mu = if mu == 0.0 { 1e-6 } else { mu * 10.0 };
            }
        }
        // ws.f must hold the residual of q for the next Jacobian's right-hand side.
        residual(q, ws);
    }
    Ok(StaticReport {
        iterations: it,
        max_residual: mx,
        tolerance: tol,
    })
}
