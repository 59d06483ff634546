//! Static equilibrium of free and pinned bodies with their lines
//! (docs/src/bodies.md, "Initial state").
//!
//! The unknowns are each body's pose: its reference point `X` and attitude `q` (a
//! pinned body: `q` only, its pin is prescribed). For a trial pose the nodes held on
//! the body are placed at its points `X + R p`, the blocks holding its lines are relaxed
//! to their static equilibrium with those nodes held ([`super::relax_blocks_held`], the
//! lines' own Newton solve, warm-started from the last pose), and the body's residual is
//! the load on it at rest about `X` ([`FreeBody::static_load`]): weight, buoyancy,
//! hydrostatics, stiffness, drag in the current, external loads, and the force each
//! held node's lines exert on it (the route reaction at rest, as `static_forces` gives
//! it, which includes a point mass's weight and buoyancy at that node).
//!
//! The outer solve is a Levenberg-Marquardt least-squares solve on the six (three) pose
//! coordinates: the Jacobian `dF/dpose` by forward differences (each a relaxation of the
//! lines; translations `1e-4` m, rotations `1e-4` rad, a rotation applied as
//! `exp(theta) q`, so there is no singular attitude), every body perturbed at once in
//! the same coordinate. Bodies whose lines share no block are independent, so this
//! block-diagonal Jacobian is exact for them; bodies joined by lines get a quasi-Newton
//! step, still globalised by the residual test. A step solves
//! `(H + mu diag H) d = -Jw^T W F` (`Jw = W dF/dpose`, `H = Jw^T Jw`, `W` dividing the
//! moments by `L`, the largest distance of a held point from the reference point, at
//! least 1 m), its translation capped at 2 m and its rotation at 0.2 rad, and is
//! accepted when `|W F|` falls; otherwise `mu` grows tenfold. Where no such step is
//! found (a slack line: the load does not change as the body moves), the body moves
//! along its load, 0.5 m and 0.05 rad, unless that makes the residual grow.
//! Converged when `|F| <= tol` and `|M| <= tol L` for every body, with
//! `tol = 1e-8` of the body's load scale (its weight, buoyancy and the held nodes'
//! forces at the first guess) or 1e-4 N, whichever is larger.

use super::{relax_blocks_held, seabed_coefs, RelaxOptions, Sys, V};
use crate::body::free::{Fluid, FreeBody, FreeKind};
use crate::body::{attachment, Body, Dynamic, MeanPose, Motion};
use crate::error::Error;
use crate::model::{Layout, Route};
use crate::physics::Coefs;
use nalgebra::{DMatrix, DVector, UnitQuaternion, Vector3};
use std::sync::Arc;

type Vec3 = Vector3<f64>;

/// One body's result.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyEquilibrium {
    /// The body's name.
    pub name: String,
    /// Its reference point at equilibrium, m.
    pub position: [f64; 3],
    /// Roll, pitch, yaw at equilibrium, rad.
    pub angles: [f64; 3],
    /// The largest force left, N, and moment left, N m.
    pub residual: (f64, f64),
    /// Whether it met the tolerance.
    pub converged: bool,
}

/// The outcome of [`relax_bodies`].
#[derive(Clone, Debug, PartialEq)]
pub struct BodiesReport {
    /// One entry per body relaxed.
    pub bodies: Vec<BodyEquilibrium>,
    /// Newton iterations of the body poses.
    pub iterations: usize,
}

struct Entry {
    body: Arc<Body>,
    state: FreeBody,
    /// (packed node, body coordinates) of each held node.
    held: Vec<(usize, [f64; 3])>,
    x: Vec3,
    q: UnitQuaternion<f64>,
    /// The body's degrees of freedom: 6, or 3 (pinned: rotation only).
    ndof: usize,
    /// Length for the moments in the residual norm, m.
    len: f64,
    tol: f64,
}

/// The free and pinned bodies of `lay` that take their equilibrium (`initial =
/// "equilibrium"`) and whose held nodes are all in blocks `relaxed` marks.
fn entries(lay: &Layout, relaxed: &[bool]) -> Vec<Entry> {
    let mut out: Vec<Entry> = Vec::new();
    for (c, r) in lay.routes.iter().enumerate() {
        let Route::Body { body, at } = r else {
            continue;
        };
        let Some(d) = body.dynamic() else { continue };
        if !d.equilibrium {
            continue;
        }
        let node = lay.constraint_node[c] as usize;
        match out.iter_mut().find(|e| Arc::ptr_eq(&e.body, body)) {
            Some(e) => e.held.push((node, *at)),
            None => {
                let s = &d.body;
                out.push(Entry {
                    body: body.clone(),
                    state: s.clone(),
                    held: vec![(node, *at)],
                    x: s.reference(),
                    q: s.q,
                    ndof: if s.kind == FreeKind::Pinned { 3 } else { 6 },
                    len: 1.0,
                    tol: 0.0,
                })
            }
        }
    }
    out.retain(|e| e.held.iter().all(|&(n, _)| relaxed[block_of(lay, n)]));
    for e in &mut out {
        e.len = e
            .held
            .iter()
            .map(|(_, p)| Vec3::new(p[0], p[1], p[2]).norm())
            .fold(1.0, f64::max);
    }
    out
}

fn block_of(lay: &Layout, node: usize) -> usize {
    lay.blocks
        .partition_point(|b| (b.node_end as usize) <= node)
}

/// Moves every free or pinned body that takes its equilibrium, and the lines of the
/// blocks `relaxed` marks, to their static equilibrium together (see the module doc).
/// `positions` is updated; the bodies in the layout's routes are replaced by bodies at
/// their equilibrium pose (their `offset` and `angles` changed), so that the run starts
/// there. A body that does not reach the tolerance is left at the best pose found,
/// with `converged: false` in the report.
pub fn relax_bodies(
    lay: &mut Layout,
    positions: &mut [[f64; 3]],
    opts: &RelaxOptions,
    relaxed: &[bool],
) -> Result<BodiesReport, Error> {
    let mut es = entries(lay, relaxed);
    if es.is_empty() {
        return Ok(BodiesReport {
            bodies: Vec::new(),
            iterations: 0,
        });
    }
    let mut which = vec![false; lay.blocks.len()];
    for e in &es {
        for &(n, _) in &e.held {
            which[block_of(lay, n)] = true;
        }
    }
    let opts = RelaxOptions {
        require_convergence: false,
        ..*opts
    };
    let ev = Eval {
        lay,
        which: &which,
        opts: &opts,
        coefs: lay.line_coefs.iter().map(Coefs::from_line).collect(),
    };
    let mut pos = positions.to_vec();
    let mut f = ev.residuals(&es, &mut pos)?;
    // Tolerances from the load scale at the first guess.
    for (e, fe) in es.iter_mut().zip(&f) {
        let s = &e.state.spec;
        let g = lay.env.gravity;
        let mut scale = s.mass * g + lay.env.water_density * g * s.volume;
        scale += ev.held_force_sum(e, &pos);
        e.tol = (1e-8 * scale).max(1e-4);
        let _ = fe;
    }
    let norm = |es: &[Entry], f: &[[f64; 6]]| -> f64 {
        es.iter()
            .zip(f)
            .map(|(e, r)| {
                let (fo, mo) = parts(e, r);
                fo * fo + (mo / e.len) * (mo / e.len)
            })
            .sum::<f64>()
            .sqrt()
    };
    let done = |es: &[Entry], f: &[[f64; 6]]| {
        es.iter().zip(f).all(|(e, r)| {
            let (fo, mo) = parts(e, r);
            fo <= e.tol && mo <= e.tol * e.len
        })
    };
    let mut mu = 1e-3;
    let mut iterations = 0;
    let max_iter = 200;
    while iterations < max_iter && !done(&es, &f) {
        iterations += 1;
        // Stiffness by forward differences, all bodies at once per coordinate.
        let h = 1e-4;
        let mut k: Vec<DMatrix<f64>> = es.iter().map(|e| DMatrix::zeros(e.ndof, e.ndof)).collect();
        for j in 0..6 {
            if es.iter().all(|e| j >= e.ndof) {
                continue;
            }
            let saved: Vec<(Vec3, UnitQuaternion<f64>)> = es.iter().map(|e| (e.x, e.q)).collect();
            for e in es.iter_mut().filter(|e| j < e.ndof) {
                perturb(e, j, h);
            }
            let mut p = pos.clone();
            let fp = ev.residuals(&es, &mut p)?;
            for (i, e) in es.iter_mut().enumerate() {
                (e.x, e.q) = saved[i];
                if j >= e.ndof {
                    continue;
                }
                let (a, b) = (dofs(e, &fp[i]), dofs(e, &f[i]));
                for r in 0..e.ndof {
                    k[i][(r, j)] = -(a[r] - b[r]) / h;
                }
            }
        }
        // Levenberg-Marquardt on the scaled least squares `|W F|^2` (`W` divides the
        // moments by the body's length): `(H + mu diag H) d = -g`, `H = Jw^T Jw`,
        // `g = Jw^T W F`, `Jw = W dF/dpose = -W K`; for a large `mu` a short step down
        // the gradient, so a step that lowers the residual exists unless it is at a
        // minimum. Translations capped at 2 m, rotations at 0.2 rad, each on its own.
        let n0 = norm(&es, &f);
        let mut accepted = false;
        let saved: Vec<(Vec3, UnitQuaternion<f64>)> = es.iter().map(|e| (e.x, e.q)).collect();
        for _ in 0..20 {
            let mut solved = true;
            for (i, e) in es.iter_mut().enumerate() {
                let n = e.ndof;
                let w = DVector::from_fn(n, |r, _| if n == 6 && r < 3 { 1.0 } else { 1.0 / e.len });
                let jw = DMatrix::from_fn(n, n, |r, c| -w[r] * k[i][(r, c)]);
                let rw = DVector::from_fn(n, |r, _| w[r] * dofs(e, &f[i])[r]);
                let h = jw.transpose() * &jw;
                let g = jw.transpose() * rw;
                let mut a = h.clone();
                let floor = 1e-12 * h.trace().max(1e-300);
                for d in 0..n {
                    a[(d, d)] += mu * h[(d, d)] + floor;
                }
                let Some(mut d) = a.lu().solve(&(-g)) else {
                    solved = false;
                    continue;
                };
                cap(&mut d, n);
                for j in 0..n {
                    perturb(e, j, d[j]);
                }
            }
            if !solved {
                for (i, e) in es.iter_mut().enumerate() {
                    (e.x, e.q) = saved[i];
                }
                mu *= 10.0;
                continue;
            }
            let mut p = pos.clone();
            let fnew = ev.residuals(&es, &mut p)?;
            if norm(&es, &fnew) < n0 {
                pos = p;
                f = fnew;
                mu = (mu / 10.0).max(1e-12);
                accepted = true;
                break;
            }
            for (i, e) in es.iter_mut().enumerate() {
                (e.x, e.q) = saved[i];
            }
            mu *= 10.0;
        }
        if !accepted {
            // No information in the stiffness (a line gone slack leaves a body whose
            // load does not change as it moves): a step along the load itself, 0.5 m
            // and 0.05 rad at most, taken unless the residual grows.
            for (i, e) in es.iter_mut().enumerate() {
                let r = dofs(e, &f[i]);
                let n = e.ndof;
                let (t, rot) = if n == 6 {
                    (&r[..3], &r[3..])
                } else {
                    (&r[..0], &r[..])
                };
                let nt = t.iter().map(|x| x * x).sum::<f64>().sqrt();
                let nr = rot.iter().map(|x| x * x).sum::<f64>().sqrt();
                let mut d = DVector::zeros(n);
                for (j, x) in t.iter().enumerate() {
                    d[j] = if nt > 0.0 { 0.5 * x / nt } else { 0.0 };
                }
                let off = t.len();
                for (j, x) in rot.iter().enumerate() {
                    d[off + j] = if nr > 0.0 { 0.05 * x / nr } else { 0.0 };
                }
                for j in 0..n {
                    perturb(e, j, d[j]);
                }
            }
            let mut p = pos.clone();
            let fnew = ev.residuals(&es, &mut p)?;
            if norm(&es, &fnew) <= n0 {
                pos = p;
                f = fnew;
                mu = 1e-3;
                accepted = true;
            } else {
                for (i, e) in es.iter_mut().enumerate() {
                    (e.x, e.q) = saved[i];
                }
            }
        }
        if !accepted {
            break;
        }
    }
    // The lines at the final pose.
    let f = ev.residuals(&es, &mut pos)?;
    positions.copy_from_slice(&pos);
    let mut report = Vec::with_capacity(es.len());
    let mut replaced: Vec<(Arc<Body>, Arc<Body>)> = Vec::with_capacity(es.len());
    for (e, r) in es.iter().zip(&f) {
        let (fo, mo) = parts(e, r);
        let angles = crate::body::free::euler_angles(&e.q);
        report.push(BodyEquilibrium {
            name: e.body.name.clone(),
            position: [e.x.x, e.x.y, e.x.z],
            angles,
            residual: (fo, mo),
            converged: fo <= e.tol && mo <= e.tol * e.len,
        });
        replaced.push((e.body.clone(), Arc::new(moved(&e.body, e.x, e.q))));
    }
    for r in lay.routes.iter_mut() {
        if let Route::Body { body, .. } = r {
            if let Some((_, new)) = replaced.iter().find(|(old, _)| Arc::ptr_eq(old, body)) {
                *body = new.clone();
            }
        }
    }
    Ok(BodiesReport {
        bodies: report,
        iterations,
    })
}

/// `body` (free or pinned) at rest with its reference point at `x` and attitude `q`:
/// its pose's offset and its `angles` changed to match.
fn moved(body: &Body, x: Vec3, q: UnitQuaternion<f64>) -> Body {
    let d = body.dynamic().expect("a free or pinned body");
    let mut spec = d.body.spec.clone();
    let [roll, pitch, yaw] = crate::body::free::euler_angles(&q);
    spec.angles = [roll, pitch, yaw - body.pose.heading];
    let mut pose: MeanPose = body.pose;
    if d.body.kind == FreeKind::Free {
        pose.offset = [0, 1, 2].map(|k| x[k] - pose.reference[k]);
    }
    let mut state = FreeBody::new(spec, d.body.kind, &pose);
    // The exact attitude (the angles round-trip to within round-off).
    state = state.placed(state.reference(), q);
    Body::new(
        body.name.clone(),
        pose,
        Motion::Dynamic(Box::new(Dynamic {
            body: state,
            pin: d.pin.clone(),
            equilibrium: d.equilibrium,
        })),
    )
}

/// Caps a step: its translation at 2 m, its rotation at 0.2 rad, each on its own.
fn cap(d: &mut DVector<f64>, n: usize) {
    let (t, r) = if n == 6 { (0..3, 3..6) } else { (0..0, 0..3) };
    let nt = t.clone().map(|j| d[j] * d[j]).sum::<f64>().sqrt();
    let nr = r.clone().map(|j| d[j] * d[j]).sum::<f64>().sqrt();
    if nt > 2.0 {
        for j in t {
            d[j] *= 2.0 / nt;
        }
    }
    if nr > 0.2 {
        for j in r {
            d[j] *= 0.2 / nr;
        }
    }
}

/// Moves pose coordinate `j` of `e` by `d` (0-2 translation of a free body, then
/// rotation about the global axes; a pinned body's 0-2 are its rotation).
fn perturb(e: &mut Entry, j: usize, d: f64) {
    let rot = if e.ndof == 6 {
        j.checked_sub(3)
    } else {
        Some(j)
    };
    match rot {
        None => e.x[j] += d,
        Some(a) => {
            let mut v = Vec3::zeros();
            v[a] = d;
            e.q = UnitQuaternion::from_scaled_axis(v) * e.q;
        }
    }
}

/// The residual's components for `e`'s degrees of freedom.
fn dofs(e: &Entry, r: &[f64; 6]) -> Vec<f64> {
    if e.ndof == 6 {
        r.to_vec()
    } else {
        r[3..].to_vec()
    }
}

/// The force and moment magnitudes left on `e` (a pinned body: no force).
fn parts(e: &Entry, r: &[f64; 6]) -> (f64, f64) {
    let fo = if e.ndof == 6 {
        Vec3::new(r[0], r[1], r[2]).norm()
    } else {
        0.0
    };
    (fo, Vec3::new(r[3], r[4], r[5]).norm())
}

struct Eval<'a> {
    lay: &'a Layout,
    which: &'a [bool],
    opts: &'a RelaxOptions,
    coefs: Vec<Coefs<f64>>,
}

impl Eval<'_> {
    /// Places every body's held nodes at their points, relaxes the lines, and returns
    /// each body's load at rest about its reference point. A pinned body's moment is
    /// about its pin.
    fn residuals(&self, es: &[Entry], pos: &mut [[f64; 3]]) -> Result<Vec<[f64; 6]>, Error> {
        for e in es {
            let s = e.state.placed(e.x, e.q).body_state();
            for &(n, at) in &e.held {
                pos[n] = attachment(&s, at).r;
            }
        }
        relax_blocks_held(self.lay, pos, self.opts, self.which)?;
        let forces = self.held_forces(pos);
        let lay = self.lay;
        let fluid = Fluid {
            rho: lay.env.water_density,
            g: lay.env.gravity,
        };
        Ok(es
            .iter()
            .map(|e| {
                let b = e.state.placed(e.x, e.q);
                let held: Vec<([f64; 3], [f64; 3])> =
                    e.held.iter().map(|&(n, _)| (pos[n], forces[n])).collect();
                let u = lay
                    .currents
                    .first()
                    .map_or([0.0; 3], |c| c.at(e.x.z).to_f64());
                b.static_load(0.0, fluid, u, &held)
            })
            .collect())
    }

    /// The static force on every node of the relaxed blocks (zero elsewhere).
    fn held_forces(&self, pos: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let lay = self.lay;
        let seabed = seabed_coefs(lay);
        let mut out = vec![[0.0; 3]; lay.n_nodes()];
        let hinges = lay.hinges();
        for (bi, b) in lay.blocks.iter().enumerate() {
            if !self.which[bi] {
                continue;
            }
            let sys = Sys::new(lay, &self.coefs, seabed, *b, &hinges);
            let (n0, n1) = (b.node_start as usize, b.node_end as usize);
            let r: Vec<V> = pos[n0..n1].iter().map(|p| V::from_f64(*p)).collect();
            let mut f = vec![V::zero(); r.len()];
            sys.residual(&r, &mut f);
            for (o, fi) in out[n0..n1].iter_mut().zip(&f) {
                *o = fi.to_f64();
            }
        }
        out
    }

    /// The sum of the magnitudes of the forces on `e`'s held nodes.
    fn held_force_sum(&self, e: &Entry, pos: &[[f64; 3]]) -> f64 {
        let forces = self.held_forces(pos);
        e.held
            .iter()
            .map(|&(n, _)| {
                let f = forces[n];
                (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt()
            })
            .sum()
    }
}
