//! Newton's method with a Levenberg-Marquardt shift on one block, and the block's
//! whole solve (first pass, stiffness continuation, dynamic relaxation, polish).

use super::linear::Lin;
use super::system::Sys;
use super::{BlockReport, Method, RelaxOptions, V};
use crate::error::Error;

impl Sys<'_> {
    pub(super) fn solve(
        &self,
        bi: usize,
        pos: &mut [[f64; 3]],
        opts: &RelaxOptions,
    ) -> Result<BlockReport, Error> {
        let mut r: Vec<V> = pos.iter().map(|p| V::from_f64(*p)).collect();
        let n_free = self.free.iter().filter(|&&f| f).count();
        let (load, kmax) = self.scales(&r);
        let rmax = r.iter().map(|p| p.max_abs()).fold(0.0, f64::max);
        let tol = (opts.rel_tol * load)
            .max(opts.abs_tol)
            .max(8.0 * f64::EPSILON * rmax * kmax);
        let method = if n_free == 0 {
            Method::Fixed
        } else if opts.force_dynamic_relaxation {
            Method::DynamicRelaxation
        } else if self.block.is_chain && self.hinges.is_empty() {
            // Bending couples a node with its neighbours' neighbours: no longer
            // block-tridiagonal, such a chain takes the dense solve.
            Method::Chain
        } else if 3 * n_free <= opts.max_dense_dof {
            Method::Dense
        } else {
            Method::DynamicRelaxation
        };
        let (mut iterations, mut dr_iterations) = (0, 0);
        match method {
            Method::Fixed => {}
            Method::Chain | Method::Dense => {
                let guess = r.clone();
                let first = opts.max_iterations.min(opts.newton_first_pass);
                let (its, mut fmax) = self.newton(&mut r, method, tol, kmax, first, opts);
                iterations = its;
                if fmax > tol {
                    // A poor first guess (slack lines): continuation in the axial
                    // stiffness from the first guess. Soft enough that the weight
                    // stretches the lines by some 20 %, slack and overstretch cost little
                    // and Newton finds the sagged shape; then ten times stiffer per
                    // stage, each stage starting from the last one's equilibrium.
                    r.copy_from_slice(&guess);
                    let ea_max = self.coefs.iter().map(|c| c.ea).fold(0.0, f64::max);
                    let mut s = (load / (0.2 * ea_max)).min(1.0);
                    loop {
                        let (its, fm) = if s >= 1.0 {
                            self.newton(&mut r, method, tol, kmax, opts.max_iterations, opts)
                        } else {
                            let soft = self.softened(s);
                            let stage_tol = (1e-6 * load).max(tol);
                            soft.newton(
                                &mut r,
                                method,
                                stage_tol,
                                kmax * s,
                                opts.max_iterations,
                                opts,
                            )
                        };
                        iterations += its;
                        fmax = fm;
                        log::debug!(
                            "relax block {bi}: stiffness x {s:.3e}, {its} Newton iterations, residual {fm:.3e} N"
                        );
                        if s >= 1.0 {
                            break;
                        }
                        s = (s * 10.0).min(1.0);
                    }
                }
                if fmax > tol {
                    // Far from equilibrium (slack lines, contact changing): let dynamic
                    // relaxation bring the block close, then polish with Newton.
                    let handoff = (opts.dr_handoff * load).max(tol);
                    dr_iterations = self.dynamic_relaxation(&mut r, handoff, opts);
                    log::debug!("relax block {bi}: dynamic relaxation, {dr_iterations} iterations");
                    let (its, _) =
                        self.newton(&mut r, method, tol, kmax, opts.max_iterations, opts);
                    iterations += its;
                }
            }
            Method::DynamicRelaxation => {
                dr_iterations = self.dynamic_relaxation(&mut r, tol, opts);
            }
        }
        let mut f = vec![V::zero(); self.nn];
        self.residual(&r, &mut f);
        let (fmax, worst, _) = self.measure(&f);
        if !fmax.is_finite() {
            let li = worst.unwrap_or_default();
            let (cable, k) = self.lay.describe_node(self.n0 + li);
            return Err(Error::Statics(format!(
                "non-finite static force at cable '{cable}', node {k}: {} (an input far out of range? check the values and their units)",
                self.why_not_finite(&r, li)
            )));
        }
        for (p, ri) in pos.iter_mut().zip(&r) {
            *p = ri.to_f64();
        }
        Ok(BlockReport {
            block: bi,
            method,
            free_nodes: n_free,
            iterations,
            dr_iterations,
            max_residual: fmax,
            tolerance: tol,
            converged: fmax <= tol,
            worst_node: worst.map(|w| self.n0 + w),
        })
    }

    /// Newton's method with a Levenberg-Marquardt shift (module doc). Returns the
    /// iterations done and the final largest residual.
    pub(super) fn newton(
        &self,
        r: &mut [V],
        method: Method,
        tol: f64,
        kmax: f64,
        max_iterations: usize,
        opts: &RelaxOptions,
    ) -> (usize, f64) {
        let nn = self.nn;
        let max_len = opts.max_step * self.mean_l0();
        let mut lin = match method {
            Method::Chain => Lin::chain(nn),
            _ => Lin::dense(&self.free),
        };
        let mut f = vec![V::zero(); nn];
        let mut ft = vec![V::zero(); nn];
        let mut trial = r.to_vec();
        self.residual(r, &mut f);
        let (mut fmax, _, mut merit) = self.measure(&f);
        // Shift relative to the stiffness scale, and its growth factor (Nielsen).
        let mut lambda: f64 = 1e-9;
        let mut nu = 2.0;
        const LAMBDA_MIN: f64 = 1e-12;
        for it in 0..max_iterations {
            if fmax <= tol {
                return (it, fmax);
            }
            lin.clear();
            self.stiffness(r, |i, j, m| {
                if self.free[i] && self.free[j] {
                    lin.add(i, j, m)
                }
            });
            // Slack lines have no stiffness at all: then the block's largest element
            // or seabed stiffness sets the scale of the shift.
            let kref = lin
                .diag_max(&self.free)
                .max(1e-3 * kmax)
                .max(f64::MIN_POSITIVE);
            let (ext, own) = self.frozen_loads(r);
            let mut accepted = false;
            for _attempt in 0..60 {
                let Some(mut dx) = lin.solve(lambda * kref, &f, &self.free) else {
                    lambda *= nu;
                    nu *= 2.0;
                    continue;
                };
                let big = dx.iter().map(|d| d.norm()).fold(0.0, f64::max);
                if big > max_len {
                    let s = max_len / big;
                    dx.iter_mut().for_each(|d| *d = *d * s);
                }
                // Decrease of the potential energy predicted by the quadratic model
                // (K and the frozen loads), and the actual one.
                let g0 = self.work(&f, &dx);
                let kd = lin.mul(&dx, &self.free);
                let pred = g0 - 0.5 * self.work(&kd, &dx);
                for li in 0..nn {
                    trial[li] = r[li] + dx[li];
                }
                self.residual(&trial, &mut ft);
                let (tmax, _, tmerit) = self.measure(&ft);
                let ok = if pred > 0.0 && g0 > 0.0 {
                    // The external loads averaged over the step's two ends (trapezoid):
                    // the buoyancy of what crosses the water surface changes along the
                    // step, and its work must be counted to second order like the
                    // elastic energy's, or steps near the surface are wrongly refused.
                    // Blocks wholly under water keep the loads at `r`.
                    let rho = if self.near_surface(r) || self.near_surface(&trial) {
                        let (ext1, own1) = self.frozen_loads(&trial);
                        let avg = |a: &[V], b: &[V]| -> Vec<V> {
                            a.iter().zip(b).map(|(x, y)| (*x + *y) * 0.5).collect()
                        };
                        let (ext_m, own_m) = (avg(&ext, &ext1), avg(&own, &own1));
                        -self.energy_change(r, &dx, &ext_m, &own_m) / pred
                    } else {
                        -self.energy_change(r, &dx, &ext, &own) / pred
                    };
                    if rho > 1e-4 {
                        lambda *= (1.0 / 3.0f64).max(1.0 - (2.0 * rho - 1.0).powi(3));
                        lambda = lambda.max(LAMBDA_MIN);
                        nu = 2.0;
                        true
                    } else {
                        // The bending energy's change is a difference of two angles'
                        // squares: near convergence its round-off swamps the decrease
                        // the model predicts, so a block with bending hinges also
                        // accepts a lower residual.
                        !self.hinges.is_empty() && tmerit < merit
                    }
                } else {
                    // Not a descent direction of the energy (drag): a lower residual.
                    tmerit < merit
                };
                if ok && tmax.is_finite() {
                    r.copy_from_slice(&trial);
                    std::mem::swap(&mut f, &mut ft);
                    fmax = tmax;
                    merit = tmerit;
                    accepted = true;
                    break;
                }
                lambda *= nu;
                nu *= 2.0;
            }
            log::trace!("relax: iteration {it}, residual {fmax:.3e} N, lambda {lambda:.1e}");
            if !accepted {
                return (it, fmax); // stalled: no step lowers the energy (or the residual)
            }
        }
        (max_iterations, fmax)
    }

    /// `sum_free f_i . dx_i`.
    pub(super) fn work(&self, f: &[V], dx: &[V]) -> f64 {
        f.iter()
            .zip(dx)
            .zip(&self.free)
            .filter(|(_, &fr)| fr)
            .map(|((fi, di), _)| fi.dot(*di))
            .sum()
    }
}
