//! One ANCF cable: configuration, state, the assembled equations of motion, the time
//! schemes, static equilibrium and what users read back.

use super::band::{Band, BW};
use super::element::{
    ale_kinematics, element_forces, gauss_points, kinematics, strain_energy, AleLoad, AncfCoefs,
    ElementEnv, GaussPoint, PointKinematics,
};
use super::shape::{ale_shape, hermite, AleShapeAt};
use crate::ale::{MeshOp, Winch, WinchEnd, WinchTracker};
use crate::error::Error;
use crate::math::V3;
use crate::model::{Current, Environment, LineCoefs, LineType, PointMass, Route};
use crate::options::{AddedMass, Scheme};
use crate::physics::{Coefs, SeabedCoefs};
use crate::stability::mode_step;
use nalgebra::{DMatrix, DVector};

type V = V3<f64>;

/// Fraction of the stable step taken when no step is given.
pub const AUTO_SAFETY: f64 = 0.8;

/// Strain allowance in the stable-step bound: the axial stiffness of a stretched
/// element grows with its strain (`EA (1 + 3 eps0)` along the tangent); the bound
/// allows strains up to 3 %.
const STRAIN_ALLOWANCE: f64 = 1.1;

/// One end of an ANCF cable (node 0 or node `n`).
#[derive(Clone, Debug, PartialEq)]
pub struct AncfEnd {
    /// Initial position, m (an end on a route is put on it instead).
    pub position: [f64; 3],
    /// Prescribed motion of the end's position (held or driven); `None`: free.
    pub route: Option<Route>,
    /// Prescribed (clamped) slope `r'`, held constant; `None`: the slope is free (a
    /// pinned or free end). A cantilever's root has both.
    pub slope: Option<[f64; 3]>,
    /// A point mass at the end (mass, buoyancy, isotropic drag and added mass).
    pub point: PointMass,
    /// A constant applied force on the end, N (a tip load, a tow force).
    pub force: [f64; 3],
}

impl AncfEnd {
    /// A free end starting at `p`.
    pub fn free(p: [f64; 3]) -> Self {
        Self {
            position: p,
            route: None,
            slope: None,
            point: PointMass::default(),
            force: [0.0; 3],
        }
    }
    /// An end held at `p` (pinned: its slope is free).
    pub fn fixed(p: [f64; 3]) -> Self {
        Self::driven(Route::Fixed { position: p })
    }
    /// An end driven along `route`.
    pub fn driven(route: Route) -> Self {
        Self {
            position: route.eval(0.0).r,
            route: Some(route),
            ..Self::free([0.0; 3])
        }
    }
    /// An end held at `p` with its slope clamped to `slope` (a cantilever's root).
    pub fn clamped(p: [f64; 3], slope: [f64; 3]) -> Self {
        Self {
            slope: Some(slope),
            ..Self::fixed(p)
        }
    }
    /// The same end carrying point mass `pm`.
    pub fn with_point(mut self, pm: PointMass) -> Self {
        self.point = pm;
        self
    }
    /// The same end with a constant applied force `f`, N.
    pub fn with_force(mut self, f: [f64; 3]) -> Self {
        self.force = f;
        self
    }
}

/// Everything an [`AncfCable`] is built from.
#[derive(Clone, Debug, PartialEq)]
pub struct AncfConfig {
    /// Name used in error messages.
    pub name: String,
    /// The line type (`ei` is the bending stiffness; `damping` the time constant `c` of
    /// both the axial and the bending damping).
    pub line_type: LineType,
    /// Unstretched length, m.
    pub length: f64,
    /// Number of equal elements.
    pub elements: usize,
    /// The end at arc length 0 (node 0).
    pub start: AncfEnd,
    /// The end at arc length `length` (node `elements`).
    pub end: AncfEnd,
    /// Gravity, water density, seabed (`depth = f64::INFINITY`: none).
    pub env: Environment,
    /// Current.
    pub current: Current,
    /// Uniform water acceleration `a_w`, m/s^2.
    pub water_accel: [f64; 3],
    /// Gauss points per element for the loads and the normal added mass (default 5:
    /// exact for the elastic axial force of the Green strain, a polynomial of degree 8;
    /// drag, curvature and contact to the rule's accuracy). The constant mass matrix and
    /// weights always use at least 4 points, exact for them.
    pub gauss_points: usize,
    /// Time scheme (default symplectic Euler).
    pub scheme: Scheme,
    /// Time step, s; `None`: [`AUTO_SAFETY`] of the stable step.
    pub dt: Option<f64>,
    /// How the normal added mass enters the mass matrix (default: exactly, with the
    /// tangent at each Gauss point).
    pub added_mass: AddedMass,
    /// A node faster than this, m/s, stops the run as a blow-up.
    pub max_speed: f64,
    /// A winch at one end (ALE-ANCF): that end must be on a route; its `element_length`
    /// is the standard element length of the remeshing rules (`cable` is ignored).
    pub winch: Option<Winch>,
}

impl AncfConfig {
    /// A configuration with the defaults: no current, no water acceleration, 5 Gauss
    /// points, symplectic Euler, automatic step.
    pub fn new(
        line_type: LineType,
        length: f64,
        elements: usize,
        start: AncfEnd,
        end: AncfEnd,
        env: Environment,
    ) -> Self {
        Self {
            name: "ancf".into(),
            line_type,
            length,
            elements,
            start,
            end,
            env,
            current: Current::uniform([0.0; 3]),
            water_accel: [0.0; 3],
            gauss_points: 5,
            scheme: Scheme::Symplectic,
            dt: None,
            added_mass: AddedMass::Normal,
            max_speed: 1e4,
            winch: None,
        }
    }
}

/// A prescribed group of three coordinates (a node's position or slope).
#[derive(Clone, Debug)]
struct Prescribed {
    /// First of the three coordinates.
    dof: usize,
    motion: Motion,
}

#[derive(Clone, Debug)]
enum Motion {
    Route(Route),
    Constant(V),
}

impl Motion {
    /// Value, rate and second rate at `t`.
    fn eval(&self, t: f64) -> (V, V, V) {
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
struct EndLoad {
    node: usize,
    /// Mass plus isotropic added mass, kg.
    mass: f64,
    /// Weight less buoyancy (z) plus the applied force, N.
    force: V,
    /// `1/2 rho Cd A`, kg/m.
    drag: f64,
}

/// The constant part of the model.
#[derive(Clone, Debug)]
struct Model {
    name: String,
    n_el: usize,
    /// Standard element length (the winch's `l_s` with a winch), m: scales only.
    l_el: f64,
    /// Unstretched length of each element, m (the variable element's at the last
    /// remeshing: its length now is [`Model::ale_now`]'s).
    lens: Vec<f64>,
    coefs: AncfCoefs,
    /// Gauss points per element.
    n_gauss: usize,
    /// The Gauss rule of each element.
    egps: Vec<Vec<GaussPoint>>,
    /// The winch of an ALE-ANCF cable.
    ale: Option<AleWinch>,
    current: Current,
    uniform_current: Option<V>,
    water_accel: V,
    seabed: Option<SeabedCoefs<f64>>,
    ends: Vec<EndLoad>,
    prescribed: Vec<Prescribed>,
    is_prescribed: Vec<bool>,
    /// Ends with a route: (end index 0/1, node).
    supported: [Option<usize>; 2],
    /// `int S S^T (mbar + Cm rho A) dx (x) I` plus the point masses: the whole mass
    /// matrix when `Cm = 0`, else the part the tangent-dependent term is taken from.
    mass_base: Band,
    /// Added mass per length `Cm rho A` in `mass_base` (isotropic), kg/m.
    added_iso: f64,
    /// The part of it subtracted along the tangent, kg/m: `Cm rho A` for the normal
    /// added mass, 0 for the isotropic approximation (then the mass matrix is constant).
    added: f64,
    /// The eliminated, factored mass matrix when it is constant.
    chol_const: Option<Band>,
    /// Constant generalized force of weights and applied forces (for the potential).
    const_force: Vec<f64>,
    scheme: Scheme,
    max_speed: f64,
    stable_dt: f64,
    stable_term: String,
}

/// The winch of an ALE-ANCF cable: its schedule and the mesh state.
#[derive(Clone, Debug)]
struct AleWinch {
    winch: Winch,
    tracker: WinchTracker,
    /// Index of the variable element (next to the winch).
    elem: usize,
    /// The winch is node 0 (else the last node).
    at_start: bool,
    /// Payout rates taken as zero (static solutions).
    frozen: bool,
}

/// The variable element at one time: its length, rates and Gauss rule.
#[derive(Clone, Debug)]
struct AleNow {
    elem: usize,
    l: f64,
    ldot: f64,
    lddot: f64,
    gps: Vec<GaussPoint>,
    shapes: Vec<AleShapeAt>,
}

/// Work arrays of one evaluation.
#[derive(Clone, Debug)]
struct Ws {
    f: Vec<f64>,
    m: Band,
    chol: Band,
    acc: Vec<f64>,
    tangents: Vec<V>,
}

/// Kinetic, strain and potential energy of a cable, J.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AncfEnergy {
    /// `1/2 qd^T M qd` with the consistent mass (and point masses).
    pub kinetic: f64,
    /// Axial and bending strain energy.
    pub strain: f64,
    /// Potential of the weights and applied forces, `-Q_const . q`.
    pub potential: f64,
}

impl AncfEnergy {
    /// The sum.
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.potential
    }
}

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

/// A 3D gradient-deficient ANCF cable (see the module doc of [`crate::ancf`]).
#[derive(Clone, Debug)]
pub struct AncfCable {
    m: Model,
    ws: Ws,
    /// Coordinates, node by node `[r_k, r'_k]` (m, and 1 for slopes).
    q: Vec<f64>,
    /// Their rates.
    qd: Vec<f64>,
    t: f64,
    steps: u64,
    dt: f64,
    rk: Vec<Vec<f64>>,
    /// What the cable was built from (a remeshing rebuilds the model from it).
    cfg: AncfConfig,
}

fn bad(name: &str, msg: impl std::fmt::Display) -> Error {
    Error::Model(format!("ANCF cable '{name}': {msg}"))
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

    /// Kinematics at unstretched arc length `s` from node 0 (clamped to the cable):
    /// material velocity and rates (convective parts included on a winch's variable
    /// element).
    fn point_at(&self, s: f64) -> PointKinematics {
        let lens = self.m.lens_at(self.t);
        let mut e = 0;
        let mut x = s.max(0.0);
        while e + 1 < lens.len() && x > lens[e] {
            x -= lens[e];
            e += 1;
        }
        let l = lens[e];
        let xi = (x / l).clamp(0.0, 1.0);
        let sh = hermite(l, xi);
        let (q, qd) = (&self.q[6 * e..6 * e + 12], &self.qd[6 * e..6 * e + 12]);
        let mut p = kinematics(&sh, q, qd);
        if let (Some(a), Some(now)) = (&self.m.ale, self.m.ale_now(self.t)) {
            if now.elem == e {
                let al = ale_shape(l, xi, a.at_start, &sh);
                ale_kinematics(&al, now.ldot, now.lddot, q, qd, &mut p);
            }
        }
        p
    }

    /// Position at unstretched arc length `s` from the start, m.
    pub fn position_at(&self, s: f64) -> [f64; 3] {
        self.point_at(s).r.to_f64()
    }

    /// Velocity at unstretched arc length `s` from the start, m/s (of the material
    /// there).
    pub fn velocity_at(&self, s: f64) -> [f64; 3] {
        self.point_at(s).rd.to_f64()
    }

    /// Axial force (tension) at unstretched arc length `s`, N: `|r'| EA (g eps0 + c
    /// eps0dot)`, the magnitude of the force `N r'` across the section (bending shear
    /// not included). The strain of a stiff line oscillates along a cubic element, so
    /// this pointwise value converges slowly (about 0.3 % of the tension with 16
    /// elements on a 1000 m catenary); [`AncfCable::node_tensions`] is the accurate one
    /// (1e-6 there).
    pub fn tension_at(&self, s: f64) -> f64 {
        let p = self.point_at(s);
        let (_, _, n) = super::element::axial(&self.m.coefs.line, &p);
        n * p.r1.norm()
    }

    /// Curvature at unstretched arc length `s`, 1/m.
    pub fn curvature_at(&self, s: f64) -> f64 {
        super::element::curvature(&self.point_at(s)).0
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

    // ------------------------------------------------------------------ evaluation

    /// Section force at every node, N: the force the cable beyond the node (towards the
    /// end) exerts on the cable before it, `T t` for a line in tension. It is taken from
    /// the elements' consistent nodal forces, `-(Q_e - M_e a_e)` over the node's position
    /// coordinates (internal, external and inertial forces of the adjacent element,
    /// averaged over the two elements at an interior node), the same construction as the
    /// end reactions: in a converged static state these are the element's exact
    /// equilibrium with its loads, and far more accurate than the tension from the strain
    /// at a point ([`AncfCable::tension_at`]), which oscillates along stiff elements.
    pub fn node_section_forces(&mut self) -> Result<Vec<[f64; 3]>, Error> {
        let (q, qd, t) = (self.q.clone(), self.qd.clone(), self.t);
        self.m
            .accelerations(&q, &qd, t, &mut self.ws)
            .map_err(|e| self.m.diverged(0, t, e))?;
        let n_el = self.m.n_el;
        let env = self.m.env();
        let c = &self.m.coefs.line;
        let now = self.m.ale_now(t);
        let mut out = vec![V::zero(); n_el + 1];
        let mut count = vec![0.0; n_el + 1];
        for e in 0..n_el {
            let b = 6 * e;
            let mut f = [0.0; 12];
            let (gps, ale) = self.m.element_rule(e, &now);
            element_forces(
                &self.m.coefs,
                gps,
                &env,
                &q[b..b + 12],
                &qd[b..b + 12],
                &mut f,
                Some(&mut self.ws.tangents[..]),
                ale.as_ref(),
            );
            // Consistent inertia forces (M_e a_e) on the element's two position coordinates.
            let acc = &self.ws.acc[b..b + 12];
            let (mut ia, mut ib) = (V::zero(), V::zero());
            for (gp, tg) in gps.iter().zip(&self.ws.tangents) {
                let sh = &gp.shape;
                let a = kinematics(sh, acc, &[0.0; 12]).r;
                let ma = a * (c.mass + self.m.added_iso) - *tg * (self.m.added * tg.dot(a));
                ia += ma * (gp.dx * sh.s[0]);
                ib += ma * (gp.dx * sh.s[2]);
            }
            let fa = V::new(f[0], f[1], f[2]) - ia;
            let fb = V::new(f[6], f[7], f[8]) - ib;
            // The element pulls its end b back with -T t: the section force is -fb.
            out[e + 1] -= fb;
            out[e] += fa;
            count[e] += 1.0;
            count[e + 1] += 1.0;
        }
        Ok(out
            .iter()
            .zip(&count)
            .map(|(v, n)| (*v / *n).to_f64())
            .collect())
    }

    /// Tension at every node, N: the magnitude of [`AncfCable::node_section_forces`].
    pub fn node_tensions(&mut self) -> Result<Vec<f64>, Error> {
        Ok(self
            .node_section_forces()?
            .iter()
            .map(|f| V::from_f64(*f).norm())
            .collect())
    }

    /// The force each supported end (one on a route) exerts on its support at the
    /// current state, `F_k - (M a)_k` over the end's position coordinates, N
    /// (docs/src/model/constraints.md, "End forces"); `None` for an end without a route.
    pub fn end_forces(&mut self) -> Result<[Option<[f64; 3]>; 2], Error> {
        let (q, qd, t) = (self.q.clone(), self.qd.clone(), self.t);
        self.m
            .accelerations(&q, &qd, t, &mut self.ws)
            .map_err(|e| self.m.diverged(0, t, e))?;
        let mfull = if self.m.mass_varies() {
            &self.ws.m
        } else {
            &self.m.mass_base
        };
        let mut out = [None, None];
        for (k, sup) in self.m.supported.iter().enumerate() {
            if let Some(node) = sup {
                let mut r = [0.0; 3];
                for (a, ra) in r.iter_mut().enumerate() {
                    let i = 6 * node + a;
                    let j0 = i.saturating_sub(BW);
                    let j1 = (i + BW).min(q.len() - 1);
                    let ma: f64 = (j0..=j1).map(|j| mfull.get(i, j) * self.ws.acc[j]).sum();
                    *ra = self.ws.f[i] - ma;
                }
                out[k] = Some(r);
            }
        }
        Ok(out)
    }

    /// Kinetic, strain and potential energy at the current state (the potential counts
    /// weights and applied forces; drag, seabed and damping are not conservative).
    pub fn energy(&mut self) -> AncfEnergy {
        let mfull = if self.m.mass_varies() {
            let (q, qd, t) = (self.q.clone(), self.qd.clone(), self.t);
            self.m.forces(&q, &qd, t, &mut self.ws, true);
            &self.ws.m
        } else {
            &self.m.mass_base
        };
        let mut mv = vec![0.0; self.q.len()];
        mfull.mul_vec(&self.qd, &mut mv);
        let kinetic = 0.5 * mv.iter().zip(&self.qd).map(|(a, b)| a * b).sum::<f64>();
        let now = self.m.ale_now(self.t);
        let strain = (0..self.m.n_el)
            .map(|e| {
                let (gps, _) = self.m.element_rule(e, &now);
                strain_energy(&self.m.coefs, gps, &self.q[6 * e..6 * e + 12])
            })
            .sum();
        let potential = -self
            .m
            .const_force
            .iter()
            .zip(&self.q)
            .map(|(f, q)| f * q)
            .sum::<f64>();
        AncfEnergy {
            kinetic,
            strain,
            potential,
        }
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
    fn remesh(&mut self) -> Result<(), Error> {
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

    fn check(&self) -> Result<(), Error> {
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

    // ---------------------------------------------------------------------- statics

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

impl Ws {
    fn new(nd: usize, ng: usize) -> Self {
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
    fn build(
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
    fn n_dofs(&self) -> usize {
        6 * (self.n_el + 1)
    }

    /// True when the mass matrix is assembled at every evaluation: the normal added
    /// mass follows the tangent, or a winch changes the variable element's length.
    fn mass_varies(&self) -> bool {
        self.added > 0.0 || self.ale.is_some()
    }

    /// The variable element at `t` (a winch cable only).
    fn ale_now(&self, t: f64) -> Option<AleNow> {
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
    fn element_rule<'a>(
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
    fn lens_at(&self, t: f64) -> Vec<f64> {
        let mut l = self.lens.clone();
        if let Some(a) = self.ale_now(t) {
            l[a.elem] = a.l;
        }
        l
    }

    /// The same model with its current (and water acceleration) scaled by `s`.
    fn with_flow(&self, s: f64) -> Model {
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
    fn potential_energy(&self, q: &[f64]) -> f64 {
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

    fn env(&self) -> ElementEnv<'_> {
        ElementEnv {
            current: &self.current,
            uniform_current: self.uniform_current,
            water_accel: self.water_accel,
            seabed: self.seabed,
        }
    }

    fn diverged(&self, node: usize, time: f64, what: String) -> Error {
        Error::Diverged {
            cable: self.name.clone(),
            node,
            time,
            what,
        }
    }

    /// Sum of the magnitudes of the external loads on the cable at rest, N.
    fn load_scale(&self, q: &[f64]) -> f64 {
        let c = &self.coefs.line;
        let u = self
            .uniform_current
            .unwrap_or_else(|| self.current.at(q[2]))
            .norm();
        let per_length = c.wet_weight_z.abs()
            + (c.drag_n + c.drag_t) * u * u
            + c.froude_krylov * self.water_accel.norm();
        let mut s = per_length * self.lens.iter().sum::<f64>();
        for e in &self.ends {
            s += e.force.norm() + e.drag * u * u;
        }
        s
    }

    /// Sets prescribed coordinates and their rates to their values at `t`.
    fn apply_prescribed(&self, q: &mut [f64], qd: &mut [f64], t: f64) {
        for p in &self.prescribed {
            let (x, v, _) = p.motion.eval(t);
            q[p.dof..p.dof + 3].copy_from_slice(&x.to_f64());
            qd[p.dof..p.dof + 3].copy_from_slice(&v.to_f64());
        }
    }

    /// Replaces the prescribed rows and columns of `m` by the identity's.
    fn eliminate(&self, m: &mut Band) {
        for p in &self.prescribed {
            for a in 0..3 {
                m.eliminate(p.dof + a);
            }
        }
    }

    /// Generalized force into `ws.f`; with `with_mass` also the mass matrix into `ws.m`.
    fn forces(&self, q: &[f64], qd: &[f64], t: f64, ws: &mut Ws, with_mass: bool) {
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
    fn accelerations(&self, q: &[f64], qd: &[f64], t: f64, ws: &mut Ws) -> Result<(), String> {
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
fn add_element_mass(m: &mut Band, e: usize, l: f64, n_gauss: usize, mbar: f64) {
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

/// Elements in the chain whose fastest mode bounds the stable step.
const EIG_ELEMENTS: usize = 32;

/// The fastest mode of the cable and the scheme's stable step for it.
///
/// The mass matrix is `M_s (x) I` plus the positive added mass and the point masses, and the
/// stiffness along any direction is at most `EA s K_a + EI K_b` (`K_a = int S' S'^T`,
/// `K_b = int S'' S''^T` assembled, `s` a strain allowance covering the stretched
/// line's `EA (1 + 3 eps0)` and the geometric stiffness `N K_a`), plus the seabed's
/// `K / mbar M_s`. So `omega_max^2` is at most the largest eigenvalue of the scalar
/// problem `(EA s K_a + EI K_b) x = omega^2 (mbar M_s + point masses) x` with the
/// cable's end conditions (the normal added mass only lowers it), computed densely for a
/// chain of `min(n, 32)` elements: the fastest modes are short waves in the bulk
/// (`omega^2 = 42 EA / (mbar L^2)`) or, at a free end without a point mass, a mode of
/// the end node (`91 EA / (mbar L^2)`), and a longer uniform chain has the same top of
/// the spectrum. The internal damping makes
/// the mode's damping `gamma = c omega^2`, plus `C / mbar` of the seabed and its
/// regularised friction, `mu w / (v_eps mbar)` (`w` the wet weight per length).
#[allow(clippy::too_many_arguments)]
fn stable_step(
    c: &AncfCoefs,
    lc: &LineCoefs,
    lens: &[f64],
    n_gauss: usize,
    seabed: Option<SeabedCoefs<f64>>,
    scheme: Scheme,
    ends: [(&AncfEnd, f64); 2],
) -> (f64, String) {
    // The first and last elements of a long cable, keeping both ends' conditions.
    let chain: Vec<f64> = if lens.len() <= EIG_ELEMENTS {
        lens.to_vec()
    } else {
        let h = EIG_ELEMENTS / 2;
        lens[..h]
            .iter()
            .chain(&lens[lens.len() - h..])
            .copied()
            .collect()
    };
    let ne = chain.len();
    let l = chain.iter().copied().fold(f64::INFINITY, f64::min);
    let nd = 2 * (ne + 1);
    let mut ms = DMatrix::<f64>::zeros(nd, nd);
    let mut ka = DMatrix::<f64>::zeros(nd, nd);
    for (e, &le) in chain.iter().enumerate() {
        // A rule of at least 6 points integrates these degree <= 6 products exactly.
        for gp in &gauss_points(le, 6.max(n_gauss)) {
            let sh = &gp.shape;
            for i in 0..4 {
                for j in 0..4 {
                    let (gi, gj) = (2 * e + i, 2 * e + j);
                    ms[(gi, gj)] += gp.dx * lc.mass * sh.s[i] * sh.s[j];
                    ka[(gi, gj)] += gp.dx
                        * (c.line.ea * STRAIN_ALLOWANCE * sh.ds[i] * sh.ds[j]
                            + c.ei * sh.dds[i] * sh.dds[j]);
                }
            }
        }
    }
    // End conditions: point masses on the end positions; prescribed coordinates
    // removed (an identity row in the mass, nothing in the stiffness).
    for (k, (end, mass)) in ends.iter().enumerate() {
        let u = if k == 0 { 0 } else { nd - 2 };
        ms[(u, u)] += mass;
        let fixed = [end.route.is_some(), end.slope.is_some()];
        for (d, &f) in fixed.iter().enumerate() {
            if f {
                for j in 0..nd {
                    ms[(u + d, j)] = 0.0;
                    ms[(j, u + d)] = 0.0;
                    ka[(u + d, j)] = 0.0;
                    ka[(j, u + d)] = 0.0;
                }
                ms[(u + d, u + d)] = 1.0;
            }
        }
    }
    let ch = ms
        .cholesky()
        .expect("the consistent mass matrix is positive definite");
    let li = ch
        .l()
        .try_inverse()
        .expect("a Cholesky factor is invertible");
    let a = &li * ka * li.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let we = a.symmetric_eigenvalues().max();
    let ws = seabed.map_or(0.0, |s| s.k / lc.mass);
    // Seabed damping, and the regularised friction below v_eps: a damper of rate
    // mu F_N / (v_eps m) with F_N the wet weight it carries.
    let gamma = c.line.ea_c / c.line.ea * we
        + seabed.map_or(0.0, |s| {
            (s.c + s.mu * lc.wet_weight_z.abs() / s.v_eps.max(1e-300)) / lc.mass
        });
    let omega2 = we + ws;
    let dt = mode_step(scheme, omega2, gamma);
    let term = format!(
        "fastest mode of the cubic elements: elastic omega^2 {we:.4e} s^-2 (axial wave bound {:.4e}), seabed {ws:.4e} s^-2, damping {gamma:.4e} s^-1 ({} scheme)",
        4.0 * c.line.ea / (lc.mass * l * l),
        scheme.name()
    );
    (dt, term)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Seabed;

    fn line(ei: f64, compression: bool) -> LineType {
        LineType {
            name: "l".into(),
            diameter: 0.04,
            mass_per_length: 5.0,
            ea: 6e7,
            damping: 0.0,
            cn: 1.0,
            ct: 0.01,
            cm: 0.0,
            ei,
            allow_compression: compression,
        }
    }

    /// The static forces in still water are the negative gradient of the potential
    /// energy (strain, weights, seabed) that the static solver descends.
    #[test]
    fn static_forces_are_the_energy_gradient() {
        let env = Environment {
            depth: 95.0,
            seabed: Seabed::default(),
            ..Default::default()
        };
        let cfg = AncfConfig::new(
            line(50.0, false),
            120.0,
            3,
            AncfEnd::fixed([0.0, 0.0, -90.0]),
            AncfEnd::free([100.0, 5.0, 0.0]).with_point(PointMass {
                mass: 100.0,
                ..Default::default()
            }),
            env,
        );
        let mut c = AncfCable::new(cfg).unwrap();
        c.set_shape(|s| {
            let u = s / 120.0;
            [
                100.0 * u,
                5.0 * u * u,
                -90.0 + 90.0 * u - 10.0 * (3.0 * u).sin(),
            ]
        });
        let q = c.q.clone();
        let zero = vec![0.0; q.len()];
        c.m.forces(&q, &zero, 0.0, &mut c.ws, false);
        let f = c.ws.f.clone();
        let n = q.len();
        for trial in 0..4 {
            let d: Vec<f64> = (0..n)
                .map(|i| {
                    if c.m.is_prescribed[i] {
                        0.0
                    } else {
                        ((i * 7 + trial * 13) as f64 * 0.618).sin()
                            * if i % 6 < 3 { 1.0 } else { 0.01 }
                    }
                })
                .collect();
            let h = 1e-5;
            let plus: Vec<f64> = q.iter().zip(&d).map(|(a, b)| a + h * b).collect();
            let minus: Vec<f64> = q.iter().zip(&d).map(|(a, b)| a - h * b).collect();
            let de = (c.m.potential_energy(&plus) - c.m.potential_energy(&minus)) / (2.0 * h);
            let fd: f64 = f.iter().zip(&d).map(|(a, b)| a * b).sum();
            assert!(
                (de + fd).abs() <= 1e-6 * fd.abs().max(1.0),
                "trial {trial}: dE {de} vs -F.d {}",
                -fd
            );
        }
    }

    /// A winch cable hanging from a moving top with a clump at its far end, curved and
    /// moving (so every ALE term is non-zero), element length 10 m.
    fn winch_cable(at_start: bool, schedule: crate::ale::PayoutSchedule) -> AncfCable {
        use crate::ale::{Winch, WinchEnd};
        let mut lt = line(200.0, false);
        lt.cm = 0.2;
        lt.damping = 1e-4;
        let top = Route::Circle {
            center: [0.0, 0.0, 0.0],
            radius: 5.0,
            period: 20.0,
            axis: [0.0, 0.0, 1.0],
            phase: 0.0,
            advance: 0.0,
        };
        let clump = PointMass {
            mass: 200.0,
            ..Default::default()
        };
        let (held, free) = (
            AncfEnd::driven(top),
            AncfEnd::free([5.0, 0.0, -40.0]).with_point(clump),
        );
        let (start, end) = if at_start { (held, free) } else { (free, held) };
        let mut cfg = AncfConfig::new(
            lt,
            40.0,
            4,
            start,
            end,
            Environment {
                depth: f64::INFINITY,
                ..Default::default()
            },
        );
        cfg.current = Current::uniform([0.5, 0.2, 0.0]);
        cfg.winch = Some(Winch {
            cable: 0,
            end: if at_start {
                WinchEnd::Start
            } else {
                WinchEnd::End
            },
            schedule: std::sync::Arc::new(schedule),
            drum_length: 200.0,
            element_length: 10.0,
        });
        AncfCable::new(cfg).unwrap()
    }

    /// Translational mass in the assembled mass matrix: the position blocks' diagonal
    /// directions summed. The position shape functions sum to one, so it is
    /// `int (3 mbar + 3 Cm rho A - Cm rho A t.t) dx` = `(3 mbar + 2 Cm rho A) L` plus
    /// three times the point masses.
    fn assembled_mass(c: &mut AncfCable) -> f64 {
        let (q, qd, t) = (c.q.clone(), c.qd.clone(), c.t);
        c.m.forces(&q, &qd, t, &mut c.ws, true);
        let n = c.n_nodes();
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                for a in 0..3 {
                    s += c.ws.m.get(6 * i + a, 6 * j + a);
                }
            }
        }
        s
    }

    /// An inserted node carries the cubic's position and slope and the material
    /// velocity and slope rate: shape and motion of the cable are unchanged by the
    /// insertion (positions everywhere, velocities on the new fixed element).
    #[test]
    fn ale_insertion_keeps_shape_and_material_motion() {
        for at_start in [true, false] {
            let mut c = winch_cable(at_start, crate::ale::PayoutSchedule::constant(0.8).unwrap());
            c.set_shape(|s| [5.0 + 3.0 * (s / 13.0).sin(), 0.5 * s / 40.0, -s]);
            if !at_start {
                c.set_shape(|s| [5.0 + 3.0 * (s / 13.0).sin(), 0.5 * s / 40.0, s - 40.0]);
            }
            for (k, v) in c.qd.iter_mut().enumerate() {
                *v = 0.3 * ((k * 7) as f64).sin();
            }
            let t = c.t;
            c.m.apply_prescribed(&mut c.q, &mut c.qd, t);
            // Just past the 1.5 l_s threshold: 40 m + 5.5 m, variable element 15.5 m.
            c.t = 5.5 / 0.8;
            let len = c.length();
            let far = |s_from_far: f64| {
                if at_start {
                    len - s_from_far
                } else {
                    s_from_far
                }
            };
            let before: Vec<PointKinematics> =
                (0..=90).map(|k| c.point_at(far(k as f64 * 0.5))).collect();
            let n0 = c.n_nodes();
            c.remesh().unwrap();
            assert_eq!(c.n_nodes(), n0 + 1, "one node inserted");
            assert!((c.length() - len).abs() < 1e-12);
            for (k, b) in before.iter().enumerate() {
                let s = k as f64 * 0.5;
                let a = c.point_at(far(s));
                assert!(
                    (a.r - b.r).norm() < 1e-10,
                    "at {s} m from the far end: {:?} vs {:?}",
                    a.r,
                    b.r
                );
                // The new fixed element spans 30..40 m from the far end.
                if (30.0..=40.0).contains(&s) {
                    assert!(
                        (a.rd - b.rd).norm() < 1e-10,
                        "velocity at {s} m: {:?} vs {:?}",
                        a.rd,
                        b.rd
                    );
                }
            }
        }
    }

    /// The mass in the water is `mbar` times the deployed length at every step, through
    /// insertions and deletions; a payout and an equal retrieval return to the starting
    /// mesh.
    #[test]
    fn ale_mass_follows_the_deployed_length_through_remeshing() {
        for at_start in [true, false] {
            let sched = crate::ale::PayoutSchedule::rates(&[
                (0.0, 2.0),
                (30.0, 2.0),
                (30.0, -2.0),
                (60.0, -2.0),
                (60.0, 0.0),
            ])
            .unwrap();
            let mut c = winch_cable(at_start, sched);
            let per_length = 3.0 * c.m.coefs.line.mass + 2.0 * c.m.added_iso;
            let n0 = c.n_elements();
            let mut max_err = 0.0f64;
            let (mut most, mut fewest) = (n0, n0);
            while c.t() < 60.0 {
                c.advance(200).unwrap();
                let expect = per_length * c.length() + 3.0 * 200.0;
                max_err = max_err.max((assembled_mass(&mut c) - expect).abs() / expect);
                let lens = c.element_lengths();
                let sum: f64 = lens.iter().sum();
                let deployed = 40.0 + 2.0 * c.t().min(60.0 - c.t()).max(0.0);
                assert!(
                    (sum - deployed).abs() < 1e-9,
                    "t {}: {sum} vs {deployed}",
                    c.t()
                );
                most = most.max(c.n_elements());
                fewest = fewest.min(c.n_elements());
            }
            assert!(max_err < 1e-13, "mass error {max_err:e}");
            assert_eq!(most, 4 + 6, "60 m paid out in 10 m elements");
            assert_eq!(c.n_elements(), n0, "back to the starting mesh");
            let (ins, del) = c.remeshes();
            assert_eq!((ins, del), (6, 6));
            assert!(fewest >= 4);
        }
    }

    /// With a still schedule the ALE-ANCF cable moves as the plain one, to round-off
    /// (the mass matrix is summed in another order, so not bitwise).
    #[test]
    fn ale_with_zero_payout_is_the_plain_cable() {
        let mut a = winch_cable(true, crate::ale::PayoutSchedule::constant(0.0).unwrap());
        let mut cfg = a.cfg.clone();
        cfg.winch = None;
        cfg.dt = Some(a.dt());
        let mut b = AncfCable::new(cfg).unwrap();
        a.advance(3000).unwrap();
        b.advance(3000).unwrap();
        let d = a
            .node_positions()
            .iter()
            .zip(b.node_positions())
            .map(|(x, y)| (V::from_f64(*x) - V::from_f64(y)).norm())
            .fold(0.0, f64::max);
        assert_eq!(a.n_nodes(), b.n_nodes());
        assert!(d < 1e-9, "zero payout moved the cable by {d} m");
    }

    /// Momentum of the deployed cable (material velocities, the variable element's
    /// convective part included) and point masses, N s.
    fn momentum(c: &AncfCable) -> V {
        let now = c.m.ale_now(c.t);
        let mut p = V::zero();
        for e in 0..c.n_elements() {
            let (gps, ale) = c.m.element_rule(e, &now);
            let (q, qd) = (&c.q[6 * e..6 * e + 12], &c.qd[6 * e..6 * e + 12]);
            for (g, gp) in gps.iter().enumerate() {
                let mut k = kinematics(&gp.shape, q, qd);
                if let Some(a) = &ale {
                    ale_kinematics(&a.shapes[g], a.ldot, a.lddot, q, qd, &mut k);
                }
                p += k.rd * (c.m.coefs.line.mass * gp.dx);
            }
        }
        for el in &c.m.ends {
            let i = 6 * el.node;
            p += V::new(c.qd[i], c.qd[i + 1], c.qd[i + 2]) * el.mass;
        }
        p
    }

    /// Momentum balance of a paid-out cable in vacuum (no water: no drag, buoyancy or
    /// added mass), its winch on a circle, the payout rate changing: the momentum of the
    /// deployed cable changes at `W - R + mbar Ldot v_w` (weight, the reaction the cable
    /// puts on the winch, and the momentum the paid-out material brings in with its
    /// velocity at the winch, `v_w + Ldot r'_w`). This holds for the continuum; it
    /// checks the ALE kinematics, the mass-flow force, the varying mass matrix and the
    /// reported reaction together.
    #[test]
    fn ale_momentum_balance_holds() {
        use crate::ale::{PayoutSchedule, Winch, WinchEnd};
        for at_start in [true, false] {
            let mut lt = line(500.0, false);
            lt.damping = 1e-3;
            let top = Route::Circle {
                center: [0.0, 0.0, 0.0],
                radius: 5.0,
                period: 15.0,
                axis: [0.0, 0.0, 1.0],
                phase: 0.0,
                advance: 0.0,
            };
            let clump = PointMass {
                mass: 300.0,
                ..Default::default()
            };
            let held = AncfEnd::driven(top);
            let free = AncfEnd::free([5.0, 0.0, -30.0]).with_point(clump);
            let (start, end) = if at_start { (held, free) } else { (free, held) };
            let env = Environment {
                water_density: 0.0,
                depth: f64::INFINITY,
                ..Default::default()
            };
            let mut cfg = AncfConfig::new(lt, 30.0, 3, start, end, env);
            cfg.winch = Some(Winch {
                cable: 0,
                end: if at_start {
                    WinchEnd::Start
                } else {
                    WinchEnd::End
                },
                schedule: std::sync::Arc::new(
                    PayoutSchedule::rates(&[(0.0, 0.0), (10.0, 3.0), (20.0, -1.0)]).unwrap(),
                ),
                drum_length: 200.0,
                element_length: 10.0,
            });
            let mut c = AncfCable::new(cfg).unwrap();
            let g = V::new(0.0, 0.0, -9.81);
            let we = if at_start { 0 } else { 1 };
            // Rate of change of momentum vs the balance, over windows of 0.2 s.
            let (mut worst, mut scale) = (0.0f64, 0.0f64);
            c.advance_time(1.0).unwrap();
            for _ in 0..60 {
                let p0 = momentum(&c);
                let mut impulse = V::zero();
                let n = (0.2 / c.dt()).round() as usize;
                for k in 0..n {
                    // Trapezoid in time of the balance's right-hand side.
                    let w = if k == 0 { 0.5 } else { 1.0 };
                    impulse += balance(&mut c, g, we, at_start) * (w * c.dt());
                    c.step().unwrap();
                }
                impulse += balance(&mut c, g, we, at_start) * (0.5 * c.dt());
                let dp = momentum(&c) - p0;
                worst = worst.max((dp - impulse).norm());
                scale = scale.max(impulse.norm());
            }
            assert!(c.remeshes().0 > 0, "the run must remesh");
            assert!(
                worst < 2e-4 * scale,
                "winch at start {at_start}: momentum change off the balance by {worst:.3e} N s (impulses up to {scale:.3e})"
            );
        }
    }

    /// `W - R + mbar Ldot v_mat` at the current state.
    fn balance(c: &mut AncfCable, g: V, we: usize, at_start: bool) -> V {
        let r = V::from_f64(c.end_forces().unwrap()[we].unwrap());
        let pay = c.m.ale.as_ref().unwrap().winch.schedule.eval(c.t);
        let mass: f64 =
            c.m.ends.iter().map(|e| e.mass).sum::<f64>() + c.m.coefs.line.mass * c.length();
        let node = if at_start { 0 } else { c.n_nodes() - 1 };
        let i = 6 * node;
        let vw = V::new(c.qd[i], c.qd[i + 1], c.qd[i + 2]);
        let slope = V::new(c.q[i + 3], c.q[i + 4], c.q[i + 5]);
        // The paid-out material leaves the winch into the cable: along +r' at the start,
        // along -r' at the end.
        let dir = if at_start { 1.0 } else { -1.0 };
        let v_mat = vw + slope * (dir * pay.rate);
        g * mass - r + v_mat * (c.m.coefs.line.mass * pay.rate)
    }
}
