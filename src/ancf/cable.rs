//! One ANCF cable: its state, construction, the time schemes and the winch's
//! remeshing. What users read back is in `readback.rs`, static equilibrium in
//! `static_solver.rs`, the equations of motion in `assembly.rs`.

use super::assembly::{AleWinch, Model, Ws};
use super::config::{bad, AncfConfig, AUTO_SAFETY};
use super::element::{ale_kinematics, kinematics};
use super::shape::{ale_shape, hermite};
use super::stable_step::stable_step;
use crate::ale::{MeshOp, WinchEnd, WinchTracker};
use crate::error::Error;
use crate::math::V3;
use crate::model::LineCoefs;
use crate::options::Scheme;

type V = V3<f64>;

/// A 3D gradient-deficient ANCF cable (see the module doc of [`crate::ancf`]).
#[derive(Clone, Debug)]
pub struct AncfCable {
    #[doc(hidden)]
    pub m: Model,
    #[doc(hidden)]
    pub ws: Ws,
    /// Coordinates, node by node `[r_k, r'_k]` (m, and 1 for slopes).
    #[doc(hidden)]
    pub q: Vec<f64>,
    /// Their rates.
    #[doc(hidden)]
    pub qd: Vec<f64>,
    #[doc(hidden)]
    pub t: f64,
    pub(super) steps: u64,
    pub(super) dt: f64,
    pub(super) rk: Vec<Vec<f64>>,
    /// What the cable was built from (a remeshing rebuilds the model from it).
    #[doc(hidden)]
    pub cfg: AncfConfig,
}
impl AncfCable {
    /// Builds the cable, straight between the two ends' initial positions (slopes
    /// `(end - start) / length`), at rest at `t = 0`.
    ///
    /// Errors (`Error::Model`): a non-positive length, mass, `EA` or diameter, no
    /// elements, fewer than 1 Gauss point, a negative `EI`, or a non-positive step.
    pub fn new(cfg: AncfConfig) -> Result<Self, Error> {
        let name = cfg.name.clone();
        let lt = &cfg.line_type;
        if !(cfg.length.is_finite() && cfg.length > 0.0) {
            return Err(bad(
                &name,
                format!("length must be positive, got {}", cfg.length),
            ));
        }
        if cfg.elements == 0 {
            return Err(bad(&name, "needs at least one element"));
        }
        if cfg.gauss_points == 0 {
            return Err(bad(&name, "needs at least one Gauss point"));
        }
        if !(lt.mass_per_length > 0.0 && lt.ea > 0.0 && lt.diameter > 0.0) {
            return Err(bad(
                &name,
                "line type needs positive mass_per_length, ea and diameter",
            ));
        }
        if !(lt.ei >= 0.0 && lt.damping >= 0.0) {
            return Err(bad(&name, "ei and damping must not be negative"));
        }
        let n_el = cfg.elements;
        let l_init = cfg.length / n_el as f64;
        let lens = vec![l_init; n_el];
        let ale = match &cfg.winch {
            None => None,
            Some(w) => {
                let at_start = w.end == WinchEnd::Start;
                let end = if at_start { &cfg.start } else { &cfg.end };
                if end.route.is_none() {
                    return Err(bad(
                        &name,
                        "the winch's end must be held (fixed or on a route)",
                    ));
                }
                if !(w.element_length.is_finite() && w.element_length > 0.0) {
                    return Err(bad(
                        &name,
                        format!(
                            "the winch's element length must be positive, got {}",
                            w.element_length
                        ),
                    ));
                }
                Some(AleWinch {
                    winch: w.clone(),
                    tracker: WinchTracker::new(w, &lens, w.schedule.eval(0.0).dl),
                    elem: if at_start { 0 } else { n_el - 1 },
                    at_start,
                    frozen: false,
                })
            }
        };
        // The stable step of the worst mesh the run can reach: with a winch, the
        // variable element at 0.5 l_s next to the winch, the others no longer than l_s.
        let eig_lens: Vec<f64> = match &ale {
            None => lens.clone(),
            Some(a) => {
                let l_s = a.winch.element_length;
                let n = n_el.max(2);
                let mut v = vec![l_init.min(l_s); n];
                let k = if a.at_start { 0 } else { n - 1 };
                v[k] = crate::ale::DELETE_RATIO * l_s;
                v
            }
        };
        let mut m = Model::build(&cfg, lens, ale, (0.0, String::new()))?;
        let lc = LineCoefs::new(lt, cfg.env.water_density, cfg.env.gravity);
        let (stable_dt, stable_term) = stable_step(
            &m.coefs,
            &lc,
            &eig_lens,
            cfg.gauss_points,
            m.seabed,
            cfg.scheme,
            [(&cfg.start, m.ends[0].mass), (&cfg.end, m.ends[1].mass)],
        );
        m.stable_dt = stable_dt;
        m.stable_term = stable_term;
        let dt = match cfg.dt {
            Some(dt) if dt > 0.0 && dt.is_finite() => dt,
            Some(dt) => return Err(bad(&name, format!("time step must be positive, got {dt}"))),
            None => AUTO_SAFETY * stable_dt,
        };
        let nd = m.n_dofs();
        let mut cable = Self {
            ws: Ws::new(nd, m.n_gauss),
            m,
            q: vec![0.0; nd],
            qd: vec![0.0; nd],
            t: 0.0,
            steps: 0,
            dt,
            rk: Vec::new(),
            cfg,
        };
        let (a, b) = (
            V::from_f64(cable.cfg.start.position),
            V::from_f64(cable.cfg.end.position),
        );
        let length = cable.cfg.length;
        cable.set_shape(|s| (a + (b - a) * (s / length)).to_f64());
        cable.remesh()?;
        Ok(cable)
    }

    // ----------------------------------------------------------------- state access

    /// Simulated time, s.
    pub fn t(&self) -> f64 {
        self.t
    }
    /// Time step, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }
    /// Sets the time step, s.
    pub fn set_dt(&mut self, dt: f64) {
        self.dt = dt;
    }
    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.m.n_el
    }
    /// Number of nodes (`n_elements + 1`).
    pub fn n_nodes(&self) -> usize {
        self.m.n_el + 1
    }
    /// Standard element length, m: that of every element of a cable without a winch,
    /// the winch's `l_s` with one ([`AncfCable::element_lengths`] has each one's).
    pub fn element_length(&self) -> f64 {
        self.m.l_el
    }
    /// The largest stable step of the chosen scheme (no safety factor), s, from the
    /// element eigenvalue bound (see the module doc), and the term that sets it.
    pub fn stable_dt(&self) -> (f64, &str) {
        (self.m.stable_dt, &self.m.stable_term)
    }
    /// All coordinates, node by node `[x, y, z, x', y', z']`.
    pub fn coordinates(&self) -> &[f64] {
        &self.q
    }
    /// Node positions, m.
    pub fn node_positions(&self) -> Vec<[f64; 3]> {
        (0..self.n_nodes())
            .map(|k| [self.q[6 * k], self.q[6 * k + 1], self.q[6 * k + 2]])
            .collect()
    }
    /// Node slopes `r'` (their length is the local stretch `1 + eps`).
    pub fn node_slopes(&self) -> Vec<[f64; 3]> {
        (0..self.n_nodes())
            .map(|k| [self.q[6 * k + 3], self.q[6 * k + 4], self.q[6 * k + 5]])
            .collect()
    }
    /// Node velocities, m/s.
    pub fn node_velocities(&self) -> Vec<[f64; 3]> {
        (0..self.n_nodes())
            .map(|k| [self.qd[6 * k], self.qd[6 * k + 1], self.qd[6 * k + 2]])
            .collect()
    }

    /// Unstretched length of each element now, node 0 to the end, m (with a winch the
    /// variable element's follows the payout; the sum is the deployed length).
    pub fn element_lengths(&self) -> Vec<f64> {
        self.m.lens_at(self.t)
    }

    /// Unstretched (deployed) length of the cable now, m.
    pub fn length(&self) -> f64 {
        self.element_lengths().iter().sum()
    }

    /// The cable's name.
    pub fn name(&self) -> &str {
        &self.m.name
    }

    /// Unstretched length of the variable element next to the winch now, m (`None`
    /// without a winch).
    pub fn variable_length(&self) -> Option<f64> {
        self.m.ale_now(self.t).map(|a| a.l)
    }

    /// Physical coordinate `p` of each node, node 0 to the end: unstretched arc length
    /// from the far end (the end opposite the winch), m (`None` without a winch).
    pub fn physical_coordinates(&self) -> Option<Vec<f64>> {
        let a = self.m.ale.as_ref()?;
        let lens = self.element_lengths();
        let mut p = vec![0.0];
        if a.at_start {
            for l in lens.iter().rev() {
                p.push(p[p.len() - 1] + l);
            }
            p.reverse();
        } else {
            for l in &lens {
                p.push(p[p.len() - 1] + l);
            }
        }
        Some(p)
    }

    /// Nodes inserted and deleted by the winch's remeshing so far.
    pub fn remeshes(&self) -> (u64, u64) {
        self.m
            .ale
            .as_ref()
            .map_or((0, 0), |a| (a.tracker.inserted, a.tracker.deleted))
    }

    /// Sets the shape from a function of unstretched arc length giving the position;
    /// slopes are its central differences (step `1e-4` element lengths). Velocities are
    /// set to zero, prescribed coordinates to their values at the current time.
    pub fn set_shape(&mut self, f: impl Fn(f64) -> [f64; 3]) {
        let h = 1e-4 * self.m.l_el;
        let lens = self.m.lens_at(self.t);
        let mut s = 0.0;
        for k in 0..self.n_nodes() {
            let r = f(s);
            let (p, m) = (V::from_f64(f(s + h)), V::from_f64(f(s - h)));
            let d = (p - m) / (2.0 * h);
            self.q[6 * k..6 * k + 3].copy_from_slice(&r);
            self.q[6 * k + 3..6 * k + 6].copy_from_slice(&d.to_f64());
            s += lens.get(k).copied().unwrap_or(0.0);
        }
        self.qd.iter_mut().for_each(|x| *x = 0.0);
        let t = self.t;
        self.m.apply_prescribed(&mut self.q, &mut self.qd, t);
    }

    /// Sets node positions and slopes (one per node); velocities zero, prescribed
    /// coordinates to their values at the current time.
    pub fn set_state(&mut self, positions: &[[f64; 3]], slopes: &[[f64; 3]]) {
        assert_eq!(positions.len(), self.n_nodes());
        assert_eq!(slopes.len(), self.n_nodes());
        for k in 0..self.n_nodes() {
            self.q[6 * k..6 * k + 3].copy_from_slice(&positions[k]);
            self.q[6 * k + 3..6 * k + 6].copy_from_slice(&slopes[k]);
        }
        self.qd.iter_mut().for_each(|x| *x = 0.0);
        let t = self.t;
        self.m.apply_prescribed(&mut self.q, &mut self.qd, t);
    }
    // ----------------------------------------------------------------- time stepping

    /// Advances one step of [`AncfCable::dt`] with the configured scheme.
    pub fn step(&mut self) -> Result<(), Error> {
        let dt = self.dt;
        let t = self.t;
        let nd = self.q.len();
        match self.m.scheme {
            Scheme::Symplectic => {
                self.m
                    .accelerations(&self.q, &self.qd, t, &mut self.ws)
                    .map_err(|e| self.m.diverged(0, t, e))?;
                for i in 0..nd {
                    self.qd[i] += dt * self.ws.acc[i];
                    self.q[i] += dt * self.qd[i];
                }
            }
            Scheme::Rk2 | Scheme::Rk4 => {
                // Explicit RK with a sub-diagonal tableau (midpoint, classical RK4).
                let (c, b): (&[f64], &[f64]) = if self.m.scheme == Scheme::Rk2 {
                    (&[0.0, 0.5], &[0.0, 1.0])
                } else {
                    (
                        &[0.0, 0.5, 0.5, 1.0],
                        &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
                    )
                };
                if self.rk.len() != 6 {
                    self.rk = vec![vec![0.0; nd]; 6];
                }
                let [q0, v0, sq, sv, kq, kv] = &mut self.rk[..] else {
                    unreachable!()
                };
                q0.copy_from_slice(&self.q);
                v0.copy_from_slice(&self.qd);
                sq.iter_mut().for_each(|x| *x = 0.0);
                sv.iter_mut().for_each(|x| *x = 0.0);
                for s in 0..c.len() {
                    let ts = t + c[s] * dt;
                    if s > 0 {
                        let h = c[s] * dt; // a_{s,s-1} = c_s for these tableaux
                        for i in 0..nd {
                            self.q[i] = q0[i] + h * kq[i];
                            self.qd[i] = v0[i] + h * kv[i];
                        }
                        self.m.apply_prescribed(&mut self.q, &mut self.qd, ts);
                    }
                    self.m
                        .accelerations(&self.q, &self.qd, ts, &mut self.ws)
                        .map_err(|e| self.m.diverged(0, ts, e))?;
                    kq.copy_from_slice(&self.qd);
                    kv.copy_from_slice(&self.ws.acc);
                    for i in 0..nd {
                        sq[i] += b[s] * kq[i];
                        sv[i] += b[s] * kv[i];
                    }
                }
                for i in 0..nd {
                    self.q[i] = q0[i] + dt * sq[i];
                    self.qd[i] = v0[i] + dt * sv[i];
                }
            }
        }
        self.t = t + dt;
        self.steps += 1;
        let t1 = self.t;
        self.m.apply_prescribed(&mut self.q, &mut self.qd, t1);
        self.check()?;
        self.remesh()
    }

    /// Advances `n` steps.
    pub fn advance(&mut self, n: u64) -> Result<(), Error> {
        for _ in 0..n {
            self.step()?;
        }
        Ok(())
    }

    /// Advances by `duration` seconds (rounded to whole steps).
    pub fn advance_time(&mut self, duration: f64) -> Result<(), Error> {
        self.advance((duration / self.dt).round() as u64)
    }

    /// Applies the winch's remeshing rules at the current time (paper Fig. 14, the
    /// same [`WinchTracker`] as the ALE-GLMF): a material node inserted on the variable
    /// element at `l_s` from its material node takes the position and slope of the
    /// cubic there and the material velocity and slope rate (so the shape and the
    /// motion of the new fixed element are exactly those of the old element's part); a
    /// deleted node's neighbours keep their coordinates (the merged element is the
    /// cubic through them: the one approximation of remeshing). The model is then
    /// rebuilt on the new mesh; the time step is kept (it was set for the worst mesh).
    #[doc(hidden)]
    pub fn remesh(&mut self) -> Result<(), Error> {
        let Some(a) = self.m.ale.as_ref() else {
            return Ok(());
        };
        let pay = a.winch.schedule.eval(self.t);
        if !a.tracker.needs_action(pay.dl) {
            return Ok(());
        }
        let (at_start, frozen) = (a.at_start, a.frozen);
        let mut tracker = a.tracker.clone();
        let ops = tracker.remesh(pay.dl).map_err(|lim| Error::Winch {
            cable: self.m.name.clone(),
            time: self.t,
            message: lim.to_string(),
        })?;
        let (ldot, lddot) = (pay.rate, pay.accel);
        for op in ops {
            let n_el = self.q.len() / 6 - 1;
            let e = if at_start { 0 } else { n_el - 1 };
            match op {
                MeshOp::Insert { xi, l0_before } => {
                    // `xi` runs from the material node towards the winch.
                    let x = if at_start { 1.0 - xi } else { xi };
                    let sh = hermite(l0_before, x);
                    let al = ale_shape(l0_before, x, at_start, &sh);
                    let (qe, qde) = (&self.q[6 * e..6 * e + 12], &self.qd[6 * e..6 * e + 12]);
                    let mut p = kinematics(&sh, qe, qde);
                    ale_kinematics(&al, ldot, lddot, qe, qde, &mut p);
                    let at = 6 * (e + 1);
                    let (nq, nqd) = ([p.r, p.r1], [p.rd, p.r1d]);
                    for (k, (x, xd)) in nq.iter().zip(&nqd).enumerate() {
                        let i = at + 3 * k;
                        for (c, (v, vd)) in [(x.x, xd.x), (x.y, xd.y), (x.z, xd.z)]
                            .into_iter()
                            .enumerate()
                        {
                            self.q.insert(i + c, v);
                            self.qd.insert(i + c, vd);
                        }
                    }
                }
                MeshOp::Delete => {
                    let node = if at_start { 1 } else { n_el - 1 };
                    self.q.drain(6 * node..6 * node + 6);
                    self.qd.drain(6 * node..6 * node + 6);
                }
            }
        }
        let mut lens = tracker.fixed.clone(); // far end to the winch
        if at_start {
            lens.reverse();
            lens.insert(0, tracker.base_l0);
        } else {
            lens.push(tracker.base_l0);
        }
        let winch = self.m.ale.as_ref().expect("checked above").winch.clone();
        let elem = if at_start { 0 } else { lens.len() - 1 };
        let ale = AleWinch {
            winch,
            tracker,
            elem,
            at_start,
            frozen,
        };
        let stable = (self.m.stable_dt, self.m.stable_term.clone());
        self.m = Model::build(&self.cfg, lens, Some(ale), stable)?;
        self.ws = Ws::new(self.q.len(), self.m.n_gauss);
        self.rk.clear();
        debug_assert_eq!(self.q.len(), self.m.n_dofs());
        Ok(())
    }

    pub(super) fn check(&self) -> Result<(), Error> {
        for k in 0..self.n_nodes() {
            let r = V::new(self.q[6 * k], self.q[6 * k + 1], self.q[6 * k + 2]);
            let v = V::new(self.qd[6 * k], self.qd[6 * k + 1], self.qd[6 * k + 2]);
            // Written so that NaN fails.
            if !(v.max_abs() < self.m.max_speed && r.max_abs() < 1e9) {
                let what = if !(r.is_finite() && v.is_finite()) {
                    "non-finite state".to_string()
                } else {
                    format!("speed {:.3e} m/s", v.norm())
                };
                return Err(self.m.diverged(k, self.t, what));
            }
        }
        Ok(())
    }
}
