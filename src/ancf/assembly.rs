//! The assembled equations of motion of an ANCF cable: the constant part of the model
//! built from a configuration, prescribed coordinates and their elimination, the
//! winch's variable element, the generalized forces and the accelerations from the
//! consistent mass.

use super::band::{Band, BW};
use super::config::{bad, AncfConfig};
use super::element::{
    element_forces, gauss_points, kinematics, strain_energy, AleLoad, AncfCoefs, ElementEnv,
    GaussPoint,
};
use super::shape::{ale_shape, AleShapeAt};
use crate::ale::{Winch, WinchTracker};
use crate::error::Error;
use crate::math::V3;
use crate::model::{Current, LineCoefs, Route};
use crate::options::{AddedMass, Scheme};
use crate::physics::{Coefs, SeabedCoefs};

type V = V3<f64>;

/// A prescribed group of three coordinates (a node's position or slope).
#[derive(Clone, Debug)]
pub struct Prescribed {
    /// First of the three coordinates.
    pub dof: usize,
    pub motion: Motion,
}

#[derive(Clone, Debug)]
pub enum Motion {
    Route(Route),
    Constant(V),
}

impl Motion {
    /// Value, rate and second rate at `t`.
    pub fn eval(&self, t: f64) -> (V, V, V) {
        match self {
            Motion::Route(r) => {
                let s = r.eval(t);
                (V::from_f64(s.r), V::from_f64(s.v), V::from_f64(s.a))
            }
            Motion::Constant(x) => (*x, V::zero(), V::zero()),
        }
    }
}

/// A point mass (and applied force) at an end node, folded.
#[derive(Clone, Copy, Debug, Default)]
pub struct EndLoad {
    pub node: usize,
    /// Mass plus isotropic added mass, kg.
    pub mass: f64,
    /// Weight less buoyancy (z) plus the applied force, N.
    pub force: V,
    /// `1/2 rho Cd A`, kg/m.
    pub drag: f64,
}

/// The constant part of the model.
#[derive(Clone, Debug)]
pub struct Model {
    pub name: String,
    pub n_el: usize,
    /// Standard element length (the winch's `l_s` with a winch), m: scales only.
    pub l_el: f64,
    /// Unstretched length of each element, m (the variable element's at the last
    /// remeshing: its length now is [`Model::ale_now`]'s).
    pub lens: Vec<f64>,
    pub coefs: AncfCoefs,
    /// Gauss points per element.
    pub n_gauss: usize,
    /// The Gauss rule of each element.
    pub egps: Vec<Vec<GaussPoint>>,
    /// The winch of an ALE-ANCF cable.
    pub ale: Option<AleWinch>,
    pub current: Current,
    pub uniform_current: Option<V>,
    pub water_accel: V,
    pub seabed: Option<SeabedCoefs<f64>>,
    pub ends: Vec<EndLoad>,
    pub prescribed: Vec<Prescribed>,
    pub is_prescribed: Vec<bool>,
    /// Ends with a route: (end index 0/1, node).
    pub supported: [Option<usize>; 2],
    /// `int S S^T (mbar + Cm rho A) dx (x) I` plus the point masses: the whole mass
    /// matrix when `Cm = 0`, else the part the tangent-dependent term is taken from.
    pub mass_base: Band,
    /// Added mass per length `Cm rho A` in `mass_base` (isotropic), kg/m.
    pub added_iso: f64,
    /// The part of it subtracted along the tangent, kg/m: `Cm rho A` for the normal
    /// added mass, 0 for the isotropic approximation (then the mass matrix is constant).
    pub added: f64,
    /// The eliminated, factored mass matrix when it is constant.
    pub chol_const: Option<Band>,
    /// Constant generalized force of weights and applied forces (for the potential).
    pub const_force: Vec<f64>,
    pub scheme: Scheme,
    pub max_speed: f64,
    pub stable_dt: f64,
    pub stable_term: String,
}

/// The winch of an ALE-ANCF cable: its schedule and the mesh state.
#[derive(Clone, Debug)]
pub struct AleWinch {
    pub winch: Winch,
    pub tracker: WinchTracker,
    /// Index of the variable element (next to the winch).
    pub elem: usize,
    /// The winch is node 0 (else the last node).
    pub at_start: bool,
    /// Payout rates taken as zero (static solutions).
    pub frozen: bool,
}

/// The variable element at one time: its length, rates and Gauss rule.
#[derive(Clone, Debug)]
pub struct AleNow {
    pub elem: usize,
    pub l: f64,
    pub ldot: f64,
    pub lddot: f64,
    pub gps: Vec<GaussPoint>,
    pub shapes: Vec<AleShapeAt>,
}

/// Work arrays of one evaluation.
#[derive(Clone, Debug)]
pub struct Ws {
    pub f: Vec<f64>,
    pub m: Band,
    pub chol: Band,
    pub acc: Vec<f64>,
    pub tangents: Vec<V>,
}
impl Ws {
    pub fn new(nd: usize, ng: usize) -> Self {
        Self {
            f: vec![0.0; nd],
            m: Band::zeros(nd),
            chol: Band::zeros(nd),
            acc: vec![0.0; nd],
            tangents: vec![V::zero(); ng],
        }
    }
}

impl Model {
    /// The model of `cfg` on a mesh of element lengths `lens` (node 0 to the end), with
    /// the winch state `ale`, and the given stable step.
    pub fn build(
        cfg: &AncfConfig,
        lens: Vec<f64>,
        ale: Option<AleWinch>,
        stable: (f64, String),
    ) -> Result<Model, Error> {
        let name = cfg.name.clone();
        let lt = &cfg.line_type;
        let n_el = lens.len();
        let l_el = match &ale {
            Some(a) => a.winch.element_length,
            None => cfg.length / cfg.elements as f64,
        };
        let nd = 6 * (n_el + 1);
        let env = &cfg.env;
        let lc = LineCoefs::new(lt, env.water_density, env.gravity);
        let coefs = AncfCoefs {
            line: Coefs::from_line(&lc),
            ei: lt.ei,
            ei_c: lt.ei * lt.damping,
        };
        let egps: Vec<Vec<GaussPoint>> = lens
            .iter()
            .map(|&l| gauss_points(l, cfg.gauss_points))
            .collect();
        let seabed = env.depth.is_finite().then(|| SeabedCoefs {
            z: -env.depth,
            k: env.seabed.stiffness,
            c: env.seabed.damping,
            mu: env.seabed.friction,
            mu_axial: env.seabed.mu_axial(),
            v_eps: env.seabed.friction_velocity,
        });

        // Ends: point masses, applied forces, constraints.
        let rho = env.water_density;
        let mut ends = Vec::new();
        let mut prescribed = Vec::new();
        let mut supported = [None, None];
        for (k, e) in [&cfg.start, &cfg.end].into_iter().enumerate() {
            let node = if k == 0 { 0 } else { n_el };
            let p = e.point;
            let mut force = V::from_f64(e.force);
            force.z += -(p.mass - rho * p.volume) * env.gravity;
            ends.push(EndLoad {
                node,
                mass: p.mass + p.added_mass_coef * rho * p.volume,
                force,
                drag: 0.5 * rho * p.drag_area,
            });
            if let Some(r) = &e.route {
                prescribed.push(Prescribed {
                    dof: 6 * node,
                    motion: Motion::Route(r.clone()),
                });
                supported[k] = Some(node);
            }
            if let Some(s) = e.slope {
                prescribed.push(Prescribed {
                    dof: 6 * node + 3,
                    motion: Motion::Constant(V::from_f64(s)),
                });
            }
        }
        let mut is_prescribed = vec![false; nd];
        for p in &prescribed {
            for a in 0..3 {
                is_prescribed[p.dof + a] = true;
            }
        }

        // Constant mass: line mass and (isotropic part of) added mass, point masses.
        // The variable element of a winch cable adds its own at every evaluation.
        let added_iso = lc.added_mass;
        let added = match cfg.added_mass {
            AddedMass::Normal => added_iso,
            AddedMass::Isotropic => 0.0,
        };
        let mut mass_base = Band::zeros(nd);
        let mbar = lc.mass + added_iso;
        let variable = ale.as_ref().map(|a| a.elem);
        for (e, &l) in lens.iter().enumerate() {
            if Some(e) != variable {
                add_element_mass(&mut mass_base, e, l, cfg.gauss_points, mbar);
            }
        }
        for el in &ends {
            for a in 0..3 {
                mass_base.add_lower(6 * el.node + a, 6 * el.node + a, el.mass);
            }
        }

        // Constant generalized force of weights and applied forces (the variable
        // element's at its length at the last remeshing).
        let mut const_force = vec![0.0; nd];
        for (e, &l) in lens.iter().enumerate() {
            for gp in &gauss_points(l, cfg.gauss_points.max(4)) {
                for k in 0..4 {
                    const_force[6 * e + 3 * k + 2] += gp.dx * gp.shape.s[k] * lc.wet_weight_z;
                }
            }
        }
        for el in &ends {
            for a in 0..3 {
                const_force[6 * el.node + a] += [el.force.x, el.force.y, el.force.z][a];
            }
        }

        let uniform_current = (cfg.current.table.len() <= 1).then(|| cfg.current.at(0.0));
        let mut m = Model {
            name: name.clone(),
            n_el,
            l_el,
            lens,
            coefs,
            n_gauss: cfg.gauss_points,
            egps,
            ale,
            current: cfg.current.clone(),
            uniform_current,
            water_accel: V::from_f64(cfg.water_accel),
            seabed,
            ends,
            prescribed,
            is_prescribed,
            supported,
            mass_base,
            added_iso,
            added,
            chol_const: None,
            const_force,
            scheme: cfg.scheme,
            max_speed: cfg.max_speed,
            stable_dt: stable.0,
            stable_term: stable.1,
        };
        if !m.mass_varies() {
            let mut c = m.mass_base.clone();
            m.eliminate(&mut c);
            c.cholesky().map_err(|i| {
                bad(
                    &name,
                    format!("mass matrix not positive definite at row {i}"),
                )
            })?;
            m.chol_const = Some(c);
        }
        Ok(m)
    }

    /// Number of coordinates.
    pub fn n_dofs(&self) -> usize {
        6 * (self.n_el + 1)
    }

    /// True when the mass matrix is assembled at every evaluation: the normal added
    /// mass follows the tangent, or a winch changes the variable element's length.
    pub fn mass_varies(&self) -> bool {
        self.added > 0.0 || self.ale.is_some()
    }

    /// The variable element at `t` (a winch cable only).
    pub fn ale_now(&self, t: f64) -> Option<AleNow> {
        let a = self.ale.as_ref()?;
        let pay = a.winch.schedule.eval(t);
        let l = a.tracker.variable_l0(pay.dl);
        let (ldot, lddot) = if a.frozen {
            (0.0, 0.0)
        } else {
            (pay.rate, pay.accel)
        };
        let gps = gauss_points(l, self.n_gauss);
        let shapes = gps
            .iter()
            .map(|gp| ale_shape(l, gp.xi, a.at_start, &gp.shape))
            .collect();
        Some(AleNow {
            elem: a.elem,
            l,
            ldot,
            lddot,
            gps,
            shapes,
        })
    }

    /// Element `e`'s Gauss rule and ALE terms (given the variable element now).
    #[inline]
    pub fn element_rule<'a>(
        &'a self,
        e: usize,
        now: &'a Option<AleNow>,
    ) -> (&'a [GaussPoint], Option<AleLoad<'a>>) {
        match now {
            Some(a) if a.elem == e => (
                &a.gps,
                Some(AleLoad {
                    shapes: &a.shapes,
                    ldot: a.ldot,
                    lddot: a.lddot,
                }),
            ),
            _ => (&self.egps[e], None),
        }
    }

    /// Unstretched element lengths at `t`, m.
    pub fn lens_at(&self, t: f64) -> Vec<f64> {
        let mut l = self.lens.clone();
        if let Some(a) = self.ale_now(t) {
            l[a.elem] = a.l;
        }
        l
    }

    /// The same model with its current (and water acceleration) scaled by `s`.
    pub fn with_flow(&self, s: f64) -> Model {
        let mut m = self.clone();
        for row in &mut m.current.table {
            row.1 = row.1.map(|u| u * s);
        }
        m.uniform_current = m.uniform_current.map(|u| u * s);
        m.water_accel = m.water_accel * s;
        m
    }

    /// Potential energy of the static loads at rest (strain, weights and applied
    /// forces, seabed stiffness), J: the static forces in still water are its negative
    /// gradient.
    pub fn potential_energy(&self, q: &[f64]) -> f64 {
        let mut e = -self
            .const_force
            .iter()
            .zip(q)
            .map(|(f, x)| f * x)
            .sum::<f64>();
        let zero = [0.0; 12];
        for el in 0..self.n_el {
            let qe = &q[6 * el..6 * el + 12];
            let gps = &self.egps[el];
            e += strain_energy(&self.coefs, gps, qe);
            if let Some(s) = &self.seabed {
                for gp in gps {
                    let p = kinematics(&gp.shape, qe, &zero);
                    let pen = s.z - p.r.z;
                    if pen > 0.0 {
                        e += gp.dx * 0.5 * s.k * pen * pen;
                    }
                }
            }
        }
        e
    }

    pub fn env(&self) -> ElementEnv<'_> {
        ElementEnv {
            current: &self.current,
            uniform_current: self.uniform_current,
            water_accel: self.water_accel,
            seabed: self.seabed,
        }
    }

    pub fn diverged(&self, node: usize, time: f64, what: String) -> Error {
        Error::Diverged {
            cable: self.name.clone(),
            node,
            time,
            what,
        }
    }

    /// Sum of the magnitudes of the external loads on the cable at rest, N.
    pub fn load_scale(&self, q: &[f64]) -> f64 {
        let c = &self.coefs.line;
        let u = self
            .uniform_current
            .unwrap_or_else(|| self.current.at(q[2]))
            .norm();
        let per_length = c.wet_weight_z.abs()
            + (c.drag_n + c.drag_t) * u * u
            + c.froude_krylov.max(c.froude_krylov_t) * self.water_accel.norm();
        let mut s = per_length * self.lens.iter().sum::<f64>();
        for e in &self.ends {
            s += e.force.norm() + e.drag * u * u;
        }
        s
    }

    /// Sets prescribed coordinates and their rates to their values at `t`.
    pub fn apply_prescribed(&self, q: &mut [f64], qd: &mut [f64], t: f64) {
        for p in &self.prescribed {
            let (x, v, _) = p.motion.eval(t);
            q[p.dof..p.dof + 3].copy_from_slice(&x.to_f64());
            qd[p.dof..p.dof + 3].copy_from_slice(&v.to_f64());
        }
    }

    /// Replaces the prescribed rows and columns of `m` by the identity's.
    pub fn eliminate(&self, m: &mut Band) {
        for p in &self.prescribed {
            for a in 0..3 {
                m.eliminate(p.dof + a);
            }
        }
    }

    /// Generalized force into `ws.f`; with `with_mass` also the mass matrix into `ws.m`.
    pub fn forces(&self, q: &[f64], qd: &[f64], t: f64, ws: &mut Ws, with_mass: bool) {
        ws.f.iter_mut().for_each(|x| *x = 0.0);
        let now = self.ale_now(t);
        if with_mass {
            ws.m.copy_from(&self.mass_base);
            if let Some(a) = &now {
                let mbar = self.coefs.line.mass + self.added_iso;
                add_element_mass(&mut ws.m, a.elem, a.l, self.n_gauss, mbar);
            }
        }
        let env = self.env();
        for e in 0..self.n_el {
            let b = 6 * e;
            let (gps, ale) = self.element_rule(e, &now);
            element_forces(
                &self.coefs,
                gps,
                &env,
                &q[b..b + 12],
                &qd[b..b + 12],
                &mut ws.f[b..b + 12],
                with_mass.then_some(&mut ws.tangents[..]),
                ale.as_ref(),
            );
            if with_mass && self.added > 0.0 {
                // Normal added mass: subtract Cm rho A int S_k S_l t t^T from the
                // isotropic part already in `mass_base`.
                for (gp, t) in gps.iter().zip(&ws.tangents) {
                    let s = &gp.shape.s;
                    let tv = [t.x, t.y, t.z];
                    for k in 0..4 {
                        for l in 0..=k {
                            let x = self.added * gp.dx * s[k] * s[l];
                            for a in 0..3 {
                                let bmax = if k == l { a } else { 2 };
                                for bb in 0..=bmax {
                                    ws.m.add_lower(
                                        b + 3 * k + a,
                                        b + 3 * l + bb,
                                        -x * tv[a] * tv[bb],
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
        for el in &self.ends {
            let i = 6 * el.node;
            let mut f = el.force;
            if el.drag > 0.0 {
                let r = V::new(q[i], q[i + 1], q[i + 2]);
                let v = V::new(qd[i], qd[i + 1], qd[i + 2]);
                let u = self.uniform_current.unwrap_or_else(|| self.current.at(r.z));
                let vr = u - v;
                f += vr * (el.drag * vr.norm());
            }
            ws.f[i] += f.x;
            ws.f[i + 1] += f.y;
            ws.f[i + 2] += f.z;
        }
    }

    /// Accelerations `ws.acc` of state `(q, qd)` at `t`: forces, mass, prescribed
    /// accelerations by direct elimination, Cholesky solve.
    pub fn accelerations(&self, q: &[f64], qd: &[f64], t: f64, ws: &mut Ws) -> Result<(), String> {
        let variable = self.mass_varies();
        self.forces(q, qd, t, ws, variable);
        ws.acc.copy_from_slice(&ws.f);
        let mfull = if variable { &ws.m } else { &self.mass_base };
        let n = q.len();
        // Move M[:, p] a_p to the right-hand side, then set the prescribed values.
        let mut pa = [[0.0; 3]; 4];
        for (pi, p) in self.prescribed.iter().enumerate() {
            let a = p.motion.eval(t).2.to_f64();
            pa[pi] = a;
            for (c, ac) in a.iter().enumerate() {
                let dof = p.dof + c;
                if *ac == 0.0 {
                    continue;
                }
                for j in dof.saturating_sub(BW)..=(dof + BW).min(n - 1) {
                    if !self.is_prescribed[j] {
                        ws.acc[j] -= mfull.get(j, dof) * ac;
                    }
                }
            }
        }
        for (pi, p) in self.prescribed.iter().enumerate() {
            ws.acc[p.dof..p.dof + 3].copy_from_slice(&pa[pi]);
        }
        if variable {
            ws.chol.copy_from(&ws.m);
            self.eliminate(&mut ws.chol);
            ws.chol
                .cholesky()
                .map_err(|i| format!("mass matrix not positive definite at row {i}"))?;
            ws.chol.solve_in_place(&mut ws.acc);
        } else {
            self.chol_const
                .as_ref()
                .expect("constant mass is factored at construction")
                .solve_in_place(&mut ws.acc);
        }
        if ws.acc.iter().all(|a| a.is_finite()) {
            Ok(())
        } else {
            Err("non-finite acceleration".into())
        }
    }
}

/// Adds the consistent mass `mbar int S_k S_l dx (x) I` of element `e` of length `l`
/// to `m` (a rule of at least 4 points: exact for the degree-6 products).
pub fn add_element_mass(m: &mut Band, e: usize, l: f64, n_gauss: usize, mbar: f64) {
    for gp in &gauss_points(l, n_gauss.max(4)) {
        let s = &gp.shape.s;
        for k in 0..4 {
            for j in 0..=k {
                let x = mbar * gp.dx * s[k] * s[j];
                for a in 0..3 {
                    m.add_lower(6 * e + 3 * k + a, 6 * e + 3 * j + a, x);
                }
            }
        }
    }
}
