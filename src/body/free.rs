//! Free and pinned rigid bodies: six degrees of freedom (a pinned body: three, its
//! rotation about a prescribed reference point) that answer the loads on them, in f64.
//!
//! The model is in docs/src/bodies.md ("Free bodies"). In short: the state is the centre
//! of gravity (a free body) or the prescribed pin (a pinned body), the attitude as a unit
//! quaternion and the angular velocity in global axes; the equations of motion are
//! written about a point `P` (the centre of gravity, or the pin), with every 6x6 matrix
//! moved there; the nodes held on the body are lumped into it ([`Lump`]); a step is
//! symplectic Euler, velocities first, the quaternion turned by `exp(w dt)`.

use super::kinematics::{rotation, BodyState, MeanPose};
use crate::math::V3;
use nalgebra::{Matrix3, Matrix6, Quaternion, Rotation3, UnitQuaternion, Vector3, Vector6};

type V = V3<f64>;
type Vec3 = Vector3<f64>;

/// A free body's own properties, as a scenario gives them. Body coordinates are
/// relative to the reference point, along the body axes.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeSpec {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of gravity, body coordinates, m.
    pub cg: [f64; 3],
    /// Inertia tensor about the centre of gravity, body axes, kg m^2 (symmetric).
    pub inertia: [[f64; 3]; 3],
    /// Displaced volume (in the `reference` pose for a surface-piercing body), m^3.
    pub volume: f64,
    /// Centre of buoyancy, body coordinates, m.
    pub cb: [f64; 3],
    /// Waterplane area, m^2 (0: a body under water, or no heave stiffness).
    pub waterplane_area: f64,
    /// Second moments of the waterplane area about the body's x and y axes through
    /// the reference point, m^4.
    pub waterplane_inertia: [f64; 2],
    /// Added mass, 6x6, body axes about the reference point (kg, kg m, kg m^2).
    pub added_mass: [[f64; 6]; 6],
    /// Quadratic drag, drag coefficient times area per body axis, m^2.
    pub drag_area: [f64; 3],
    /// Quadratic rotational drag per body axis, m^5.
    pub rotational_drag: [f64; 3],
    /// Linear damping, 6x6, body axes about the reference point.
    pub damping: [[f64; 6]; 6],
    /// Linear stiffness, 6x6, global axes, about the reference pose.
    pub stiffness: [[f64; 6]; 6],
    /// Constant external force at the reference point, global axes, N.
    pub force: [f64; 3],
    /// Constant external moment, global axes, N m.
    pub moment: [f64; 3],
    /// External loads against time (added to `force` and `moment`).
    pub loads: Option<LoadTable>,
    /// Initial roll, pitch and yaw (rad; the yaw is added to the pose's heading).
    pub angles: [f64; 3],
}

impl Default for FreeSpec {
    fn default() -> Self {
        Self {
            mass: 0.0,
            cg: [0.0; 3],
            inertia: [[0.0; 3]; 3],
            volume: 0.0,
            cb: [0.0; 3],
            waterplane_area: 0.0,
            waterplane_inertia: [0.0; 2],
            added_mass: [[0.0; 6]; 6],
            drag_area: [0.0; 3],
            rotational_drag: [0.0; 3],
            damping: [[0.0; 6]; 6],
            stiffness: [[0.0; 6]; 6],
            force: [0.0; 3],
            moment: [0.0; 3],
            loads: None,
            angles: [0.0; 3],
        }
    }
}

/// External loads against time: rows `(t, [fx, fy, fz, mx, my, mz])`, linearly
/// interpolated, held before the first and after the last row.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadTable {
    /// Times, s, strictly increasing.
    pub t: Vec<f64>,
    /// Force (N) and moment (N m), global axes, at the reference point.
    pub loads: Vec<[f64; 6]>,
}

impl LoadTable {
    /// The loads at time `t`.
    pub fn eval(&self, t: f64) -> [f64; 6] {
        let n = self.t.len();
        if n == 0 {
            return [0.0; 6];
        }
        if t <= self.t[0] {
            return self.loads[0];
        }
        if t >= self.t[n - 1] {
            return self.loads[n - 1];
        }
        let i = self.t.partition_point(|&x| x <= t).max(1);
        let s = (t - self.t[i - 1]) / (self.t[i] - self.t[i - 1]);
        let (a, b) = (self.loads[i - 1], self.loads[i]);
        std::array::from_fn(|k| a[k] + s * (b[k] - a[k]))
    }
}

/// The water and gravity a body is in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fluid {
    /// Water density, kg/m^3.
    pub rho: f64,
    /// Gravity, m/s^2.
    pub g: f64,
}

/// A node held on the body, lumped into it: its position, its mass block (global
/// axes) and the force on it from everything but its constraint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lump {
    /// Position, m.
    pub r: [f64; 3],
    /// Mass block, kg (symmetric).
    pub m: [[f64; 3]; 3],
    /// Force, N.
    pub f: [f64; 3],
}

/// The prescribed motion of a pinned body's reference point at one time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pin {
    /// Position, m.
    pub x: [f64; 3],
    /// Velocity, m/s.
    pub v: [f64; 3],
    /// Acceleration, m/s^2.
    pub a: [f64; 3],
}

/// The time derivative of a free body's state ([`FreeBody::rates`]), and weighted
/// sums of them (the Runge-Kutta schemes' combination).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rates {
    /// Velocity of the centre of gravity, m/s.
    pub v_g: Vec3,
    /// Acceleration of the centre of gravity, m/s^2.
    pub a_g: Vec3,
    /// Rate of the attitude quaternion, 1/s.
    pub dq: Quaternion<f64>,
    /// Angular acceleration, global axes, rad/s^2.
    pub alpha: Vec3,
}

impl Default for Rates {
    fn default() -> Self {
        Self {
            v_g: Vec3::zeros(),
            a_g: Vec3::zeros(),
            dq: Quaternion::new(0.0, 0.0, 0.0, 0.0),
            alpha: Vec3::zeros(),
        }
    }
}

impl Rates {
    /// `self += w k`.
    pub fn add_scaled(&mut self, k: &Rates, w: f64) {
        self.v_g += k.v_g * w;
        self.a_g += k.a_g * w;
        self.dq += k.dq * w;
        self.alpha += k.alpha * w;
    }
}

/// Whether all six degrees of freedom are free, or the translation is prescribed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FreeKind {
    /// Six free degrees of freedom.
    Free,
    /// Translation prescribed, rotation free about the reference point.
    Pinned,
}

/// A free or pinned body and its state.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeBody {
    /// Its properties.
    pub spec: FreeSpec,
    /// Free or pinned.
    pub kind: FreeKind,
    /// The reference point in the reference pose (where `volume` is displaced), m.
    pub x0: [f64; 3],
    /// The reference attitude's yaw (the heading), rad.
    pub heading: f64,
    /// Centre of gravity, m.
    pub x_g: Vec3,
    /// Velocity of the centre of gravity, m/s.
    pub v_g: Vec3,
    /// Attitude, body to global.
    pub q: UnitQuaternion<f64>,
    /// Angular velocity, global axes, rad/s.
    pub w: Vec3,
    /// Acceleration of `P` and angular acceleration of the last step (global axes).
    pub last_acc: (Vec3, Vec3),
}

fn v3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

fn m3(a: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| a[i][j])
}

fn m6(a: &[[f64; 6]; 6]) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| a[i][j])
}

fn vv(a: Vec3) -> V {
    V::new(a.x, a.y, a.z)
}

/// `[e x]`, the cross-product matrix.
fn skew(e: Vec3) -> Matrix3<f64> {
    e.cross_matrix()
}

/// The added mass `A` (body axes, about a point `Q`) in global axes about `P = Q - e`,
/// `S^T blockdiag(R, R) A blockdiag(R, R)^T S` with `S = [[1, -[e x]], [0, 1]]`, by 3x3
/// blocks (twelve 3x3 products where the 6x6 ones take the work of thirty-two): with `B = blockdiag(R, R) A blockdiag(R, R)^T` and
/// `E = [e x]`, `S^T B S = [[B11, B12 - B11 E], [B21 + E B11, B22 + E B12 - (B21 + E
/// B11) E]]`.
fn added_about(a: &[[f64; 6]; 6], r: &Matrix3<f64>, e: Vec3) -> Matrix6<f64> {
    let blk = |i0: usize, j0: usize| Matrix3::from_fn(|i, j| a[i0 + i][j0 + j]);
    let rt = r.transpose();
    let b11 = r * blk(0, 0) * rt;
    let b12 = r * blk(0, 3) * rt;
    let b21 = r * blk(3, 0) * rt;
    let b22 = r * blk(3, 3) * rt;
    let ee = skew(e);
    let c21 = b21 + ee * b11;
    let mut out = Matrix6::zeros();
    out.fixed_view_mut::<3, 3>(0, 0).copy_from(&b11);
    out.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&(b12 - b11 * ee));
    out.fixed_view_mut::<3, 3>(3, 0).copy_from(&c21);
    out.fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&(b22 + ee * b12 - c21 * ee));
    out
}

/// `blockdiag(R, R) A blockdiag(R, R)^T`: body axes to global.
fn rotate6(a: &Matrix6<f64>, r: &Matrix3<f64>) -> Matrix6<f64> {
    let mut rr = Matrix6::zeros();
    rr.fixed_view_mut::<3, 3>(0, 0).copy_from(r);
    rr.fixed_view_mut::<3, 3>(3, 3).copy_from(r);
    rr * a * rr.transpose()
}

/// Adds a point mass block `m` at `e` from `P` moving with angular velocity `w` to the
/// mass matrix and its centripetal term to the load.
fn add_point_mass(mm: &mut Matrix6<f64>, f: &mut Vector6<f64>, m: &Matrix3<f64>, e: Vec3, w: Vec3) {
    let s = skew(e);
    let ms = m * s;
    let mut blk = Matrix6::zeros();
    blk.fixed_view_mut::<3, 3>(0, 0).copy_from(m);
    blk.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-ms));
    blk.fixed_view_mut::<3, 3>(3, 0).copy_from(&(s * m));
    blk.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-(s * ms)));
    *mm += blk;
    let c = m * w.cross(&w.cross(&e));
    add_force(f, -c, e);
}

/// Adds a force `fv` at `e` from `P`.
fn add_force(f: &mut Vector6<f64>, fv: Vec3, e: Vec3) {
    let mom = e.cross(&fv);
    for k in 0..3 {
        f[k] += fv[k];
        f[3 + k] += mom[k];
    }
}

/// The roll, pitch and yaw (rad) of `R = Rz(yaw) Ry(pitch) Rx(roll)`.
pub fn euler_angles(q: &UnitQuaternion<f64>) -> [f64; 3] {
    let (r, p, y) = q.euler_angles();
    [r, p, y]
}

impl FreeBody {
    /// A body of properties `spec` at rest in pose `pose` (its reference point at
    /// `pose.position()`, turned by the heading and `spec.angles`); `pose.reference`
    /// is the reference pose's point.
    pub fn new(spec: FreeSpec, kind: FreeKind, pose: &MeanPose) -> Self {
        let [roll, pitch, yaw] = spec.angles;
        let q = UnitQuaternion::from_euler_angles(roll, pitch, yaw + pose.heading);
        let x = v3(pose.position());
        let x_g = x + q * v3(spec.cg);
        Self {
            kind,
            x0: pose.reference,
            heading: pose.heading,
            x_g,
            v_g: Vec3::zeros(),
            q,
            w: Vec3::zeros(),
            last_acc: (Vec3::zeros(), Vec3::zeros()),
            spec,
        }
    }

    /// The rotation body to global.
    pub fn rot(&self) -> Matrix3<f64> {
        *self.q.to_rotation_matrix().matrix()
    }

    /// The reference point, m.
    pub fn reference(&self) -> Vec3 {
        self.x_g - self.q * v3(self.spec.cg)
    }

    /// The reference point's velocity, m/s.
    pub fn reference_velocity(&self) -> Vec3 {
        self.v_g + self.w.cross(&(self.reference() - self.x_g))
    }

    /// Roll, pitch, yaw, rad (reported, not integrated).
    pub fn angles(&self) -> [f64; 3] {
        euler_angles(&self.q)
    }

    /// The body's kinematic state at its reference point (what attached points
    /// follow, [`super::kinematics::attachment`]), with the last step's accelerations.
    pub fn body_state(&self) -> BodyState {
        let r = self.rot();
        let x = self.reference();
        let (ap, alpha) = self.last_acc;
        // The acceleration of the reference point from that of P (the centre of
        // gravity, or the reference point itself for a pinned body).
        let p = match self.kind {
            FreeKind::Free => self.x_g,
            FreeKind::Pinned => x,
        };
        let e = x - p;
        let a = ap + alpha.cross(&e) + self.w.cross(&self.w.cross(&e));
        BodyState {
            x: vv(x),
            v: vv(self.reference_velocity()),
            a: vv(a),
            rot: [0, 1, 2].map(|i| [r[(i, 0)], r[(i, 1)], r[(i, 2)]]),
            omega: vv(self.w),
            alpha: vv(alpha),
        }
    }

    /// The total mass matrix about `P` (global axes) and the load about `P` at time
    /// `t`, with the water velocity `u` at the reference point and the lumps, where `P`
    /// is `p`.
    fn system(
        &self,
        t: f64,
        fluid: Fluid,
        u: [f64; 3],
        lumps: &[Lump],
        p: Vec3,
    ) -> (Matrix6<f64>, Vector6<f64>) {
        let s = &self.spec;
        let r = self.rot();
        let w = self.w;
        let x = self.reference();
        let ex = x - p;
        let mut mm = Matrix6::zeros();
        let mut f = Vector6::zeros();
        // The rigid body: its mass at the centre of gravity, its inertia, and the
        // gyroscopic moment.
        let ig = r * m3(&s.inertia) * r.transpose();
        add_point_mass(
            &mut mm,
            &mut f,
            &(Matrix3::identity() * s.mass),
            self.x_g - p,
            w,
        );
        {
            let mut rr = mm.fixed_view_mut::<3, 3>(3, 3);
            rr += ig;
        }
        let gyro = w.cross(&(ig * w));
        for k in 0..3 {
            f[3 + k] -= gyro[k];
        }
        // Added mass (body axes, about the reference point).
        if s.added_mass != [[0.0; 6]; 6] {
            mm += added_about(&s.added_mass, &r, ex);
        }
        // Weight and buoyancy.
        let ez = Vec3::z();
        add_force(&mut f, ez * (-s.mass * fluid.g), self.x_g - p);
        let rg = fluid.rho * fluid.g;
        add_force(&mut f, ez * (rg * s.volume), ex + r * v3(s.cb));
        // Waterplane: heave and tilt.
        if s.waterplane_area != 0.0 {
            add_force(
                &mut f,
                ez * (-rg * s.waterplane_area * (x.z - self.x0[2])),
                ex,
            );
        }
        let [iwx, iwy] = s.waterplane_inertia;
        if iwx != 0.0 || iwy != 0.0 {
            let tilt = ez.cross(&(r * ez));
            let mw = -rg
                * (r * Matrix3::from_diagonal(&Vec3::new(iwx, iwy, 0.0)) * r.transpose())
                * tilt;
            for k in 0..3 {
                f[3 + k] += mw[k];
            }
        }
        // Linear stiffness about the reference pose (global axes).
        let k6 = m6(&s.stiffness);
        if k6 != Matrix6::zeros() {
            let r_ref = Rotation3::from_axis_angle(&Vector3::z_axis(), self.heading);
            let theta = (Rotation3::from_matrix_unchecked(r) * r_ref.inverse()).scaled_axis();
            let mut d = Vector6::zeros();
            d.fixed_rows_mut::<3>(0).copy_from(&(x - v3(self.x0)));
            d.fixed_rows_mut::<3>(3).copy_from(&theta);
            let l = -(k6 * d);
            add_force(&mut f, l.fixed_rows::<3>(0).into_owned(), ex);
            for k in 0..3 {
                f[3 + k] += l[3 + k];
            }
        }
        // Linear damping (body axes, about the reference point).
        let vx = self.reference_velocity();
        let d6 = m6(&s.damping);
        if d6 != Matrix6::zeros() {
            let mut vel = Vector6::zeros();
            vel.fixed_rows_mut::<3>(0).copy_from(&(r.transpose() * vx));
            vel.fixed_rows_mut::<3>(3).copy_from(&(r.transpose() * w));
            let lb = -(d6 * vel);
            let fg = r * lb.fixed_rows::<3>(0);
            let mg = r * lb.fixed_rows::<3>(3);
            add_force(&mut f, fg, ex);
            for k in 0..3 {
                f[3 + k] += mg[k];
            }
        }
        // Quadratic drag on the relative velocity at the reference point, and on the
        // rotation.
        let ur = v3(u) - vx;
        let cda = v3(s.drag_area);
        if cda != Vec3::zeros() {
            let fd = r
                * Matrix3::from_diagonal(&cda)
                * r.transpose()
                * ur
                * (0.5 * fluid.rho * ur.norm());
            add_force(&mut f, fd, ex);
        }
        let cdr = v3(s.rotational_drag);
        if cdr != Vec3::zeros() {
            let md = -(r * Matrix3::from_diagonal(&cdr) * r.transpose() * w)
                * (0.5 * fluid.rho * w.norm());
            for k in 0..3 {
                f[3 + k] += md[k];
            }
        }
        // External loads.
        let mut ext = [0.0; 6];
        ext[..3].copy_from_slice(&s.force);
        ext[3..].copy_from_slice(&s.moment);
        if let Some(tab) = &s.loads {
            let l = tab.eval(t);
            for k in 0..6 {
                ext[k] += l[k];
            }
        }
        add_force(&mut f, v3([ext[0], ext[1], ext[2]]), ex);
        for k in 0..3 {
            f[3 + k] += ext[3 + k];
        }
        // The held nodes, lumped into the body.
        for l in lumps {
            let e = v3(l.r) - p;
            add_point_mass(&mut mm, &mut f, &m3(&l.m), e, w);
            add_force(&mut f, v3(l.f), e);
        }
        (mm, f)
    }

    /// The accelerations `(a_P, alpha)` (global axes) at time `t`: `P` the centre of
    /// gravity of a free body, the pin `pin` of a pinned body (whose acceleration is
    /// the pin's). `u` is the water velocity at the reference point.
    pub fn accelerations(
        &self,
        t: f64,
        fluid: Fluid,
        u: [f64; 3],
        lumps: &[Lump],
        pin: Option<Pin>,
    ) -> Result<(Vec3, Vec3), String> {
        match (self.kind, pin) {
            (FreeKind::Free, _) => {
                let (mm, f) = self.system(t, fluid, u, lumps, self.x_g);
                let a = solve6(mm, f)?;
                Ok((
                    a.fixed_rows::<3>(0).into_owned(),
                    a.fixed_rows::<3>(3).into_owned(),
                ))
            }
            (FreeKind::Pinned, Some(pin)) => {
                let (mm, f) = self.system(t, fluid, u, lumps, v3(pin.x));
                let ap = v3(pin.a);
                let mrr = mm.fixed_view::<3, 3>(3, 3).into_owned();
                let mrt = mm.fixed_view::<3, 3>(3, 0).into_owned();
                let rhs = f.fixed_rows::<3>(3).into_owned() - mrt * ap;
                let alpha = mrr
                    .cholesky()
                    .map(|c| c.solve(&rhs))
                    .or_else(|| mrr.lu().solve(&rhs))
                    .ok_or("the rotational mass matrix is singular")?;
                Ok((ap, alpha))
            }
            (FreeKind::Pinned, None) => Err("a pinned body needs its pin's motion".into()),
        }
    }

    /// One symplectic Euler step of `dt` from time `t`: the accelerations at the state
    /// now, the velocities, then the position and attitude. A pinned body takes its
    /// reference point from `pin_next` (the pin at `t + dt`).
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        t: f64,
        dt: f64,
        fluid: Fluid,
        u: [f64; 3],
        lumps: &[Lump],
        pin: Option<Pin>,
        pin_next: Option<Pin>,
    ) -> Result<(), String> {
        let (ap, alpha) = self.accelerations(t, fluid, u, lumps, pin)?;
        self.last_acc = (ap, alpha);
        self.w += alpha * dt;
        self.q = UnitQuaternion::from_scaled_axis(self.w * dt) * self.q;
        self.q.renormalize();
        match (self.kind, pin_next) {
            (FreeKind::Free, _) => {
                self.v_g += ap * dt;
                self.x_g += self.v_g * dt;
            }
            (FreeKind::Pinned, Some(pn)) => {
                let c = self.q * v3(self.spec.cg);
                self.x_g = v3(pn.x) + c;
                self.v_g = v3(pn.v) + self.w.cross(&c);
            }
            (FreeKind::Pinned, None) => return Err("a pinned body needs its pin's motion".into()),
        }
        if !(self.x_g.iter().all(|x| x.is_finite())
            && self.v_g.iter().all(|x| x.is_finite())
            && self.w.iter().all(|x| x.is_finite()))
        {
            return Err(format!("its state is not finite at t = {} s", t + dt));
        }
        Ok(())
    }

    /// The time derivative of the state at time `t` (a Runge-Kutta stage's rates):
    /// the velocity and acceleration of the centre of gravity, the quaternion's rate
    /// `q' = (0, w) q / 2` (`w` in global axes) and the angular acceleration. Also sets
    /// [`Self::last_acc`]. A pinned body's translation rates are not used
    /// ([`Self::advanced`] takes it from the pin).
    pub fn rates(
        &mut self,
        t: f64,
        fluid: Fluid,
        u: [f64; 3],
        lumps: &[Lump],
        pin: Option<Pin>,
    ) -> Result<Rates, String> {
        let (ap, alpha) = self.accelerations(t, fluid, u, lumps, pin)?;
        self.last_acc = (ap, alpha);
        let a_g = match self.kind {
            FreeKind::Free => ap,
            FreeKind::Pinned => Vec3::zeros(),
        };
        Ok(Rates {
            v_g: self.v_g,
            a_g,
            dq: Quaternion::from_imag(self.w) * self.q.into_inner() * 0.5,
            alpha,
        })
    }

    /// The state `h` along the rates `k` from this one (a Runge-Kutta stage, or the
    /// step's end with `k` the weighted sum of the stages' rates): the quaternion
    /// normalised, a pinned body's translation from its pin `pin` at the stage's time.
    /// `Err` when the state is not finite.
    pub fn advanced(&self, k: &Rates, h: f64, pin: Option<Pin>) -> Result<Self, String> {
        let mut b = self.clone();
        b.w = self.w + k.alpha * h;
        b.q = UnitQuaternion::new_normalize(self.q.into_inner() + k.dq * h);
        match (self.kind, pin) {
            (FreeKind::Free, _) => {
                b.x_g = self.x_g + k.v_g * h;
                b.v_g = self.v_g + k.a_g * h;
            }
            (FreeKind::Pinned, Some(pn)) => {
                let c = b.q * v3(self.spec.cg);
                b.x_g = v3(pn.x) + c;
                b.v_g = v3(pn.v) + b.w.cross(&c);
            }
            (FreeKind::Pinned, None) => return Err("a pinned body needs its pin's motion".into()),
        }
        let q = b.q.into_inner();
        if !(b.x_g.iter().all(|x| x.is_finite())
            && b.v_g.iter().all(|x| x.is_finite())
            && b.w.iter().all(|x| x.is_finite())
            && q.coords.iter().all(|x| x.is_finite()))
        {
            return Err("its state is not finite".into());
        }
        Ok(b)
    }

    /// The load on the body at rest (every velocity zero) at time `t`, about its
    /// reference point, global axes: weight, buoyancy, hydrostatics, linear stiffness,
    /// drag in the current `u`, external loads, and the forces `f` at the points `r`
    /// of the nodes held on it (`(r, f)`, the lines' pull). The residual of the
    /// statics with body degrees of freedom (docs/src/bodies.md, "Initial state").
    pub fn static_load(
        &self,
        t: f64,
        fluid: Fluid,
        u: [f64; 3],
        held: &[([f64; 3], [f64; 3])],
    ) -> [f64; 6] {
        let mut still = self.clone();
        still.v_g = Vec3::zeros();
        still.w = Vec3::zeros();
        let lumps: Vec<Lump> = held
            .iter()
            .map(|(r, f)| Lump {
                r: *r,
                m: [[0.0; 3]; 3],
                f: *f,
            })
            .collect();
        let x = still.reference();
        let (_, f) = still.system(t, fluid, u, &lumps, x);
        std::array::from_fn(|k| f[k])
    }

    /// The body placed with its reference point at `x` and attitude `q`, at rest.
    pub fn placed(&self, x: Vec3, q: UnitQuaternion<f64>) -> Self {
        let mut b = self.clone();
        b.q = q;
        b.x_g = x + q * v3(self.spec.cg);
        b.v_g = Vec3::zeros();
        b.w = Vec3::zeros();
        b.last_acc = (Vec3::zeros(), Vec3::zeros());
        b
    }

    /// The highest natural frequency squared and damping rate of the body's own
    /// stiffness and linear damping, per degree of freedom (`(omega^2, gamma)`, the
    /// diagonal terms over the diagonal of the mass matrix at rest, without lumps).
    pub fn modes(&self, fluid: Fluid) -> Vec<(f64, f64)> {
        let s = &self.spec;
        let p = match self.kind {
            FreeKind::Free => self.x_g,
            FreeKind::Pinned => self.reference(),
        };
        let mut still = self.clone();
        still.w = Vec3::zeros();
        let (mm, _) = still.system(0.0, fluid, [0.0; 3], &[], p);
        let rg = fluid.rho * fluid.g;
        let mut k = m6(&s.stiffness);
        k[(2, 2)] += rg * s.waterplane_area;
        k[(3, 3)] += rg * s.waterplane_inertia[0];
        k[(4, 4)] += rg * s.waterplane_inertia[1];
        let d = rotate6(&m6(&s.damping), &self.rot());
        let first = if self.kind == FreeKind::Pinned { 3 } else { 0 };
        (first..6)
            .filter(|&i| mm[(i, i)] > 0.0)
            .map(|i| (k[(i, i)].abs() / mm[(i, i)], d[(i, i)].abs() / mm[(i, i)]))
            .collect()
    }
}

/// Solves the symmetric 6x6 system (Cholesky; LU if it is not positive definite).
fn solve6(mm: Matrix6<f64>, f: Vector6<f64>) -> Result<Vector6<f64>, String> {
    if let Some(c) = mm.cholesky() {
        return Ok(c.solve(&f));
    }
    mm.lu()
        .solve(&f)
        .ok_or_else(|| "the mass matrix is singular (no mass in some degree of freedom)".into())
}

/// Checks a body's properties: every value finite, the mass positive, the inertia
/// symmetric with positive principal moments, the 6x6 mass matrix (with the added
/// mass) positive definite. `Err` says which key and what is wrong.
pub fn check(spec: &FreeSpec, kind: FreeKind) -> Result<(), (String, String)> {
    let bad = |k: &str, m: String| Err((k.to_string(), m));
    if !(spec.mass.is_finite() && spec.mass > 0.0) {
        return bad(
            "mass",
            format!("must be positive and finite, got {}", spec.mass),
        );
    }
    let i = m3(&spec.inertia);
    if (i - i.transpose()).abs().max() > 1e-9 * i.abs().max().max(1e-300) {
        return bad(
            "inertia",
            format!("must be symmetric, got {:?}", spec.inertia),
        );
    }
    let eig = i.symmetric_eigenvalues();
    if kind == FreeKind::Free || kind == FreeKind::Pinned {
        if let Some(e) = eig.iter().find(|e| **e < 0.0) {
            return bad(
                "inertia",
                format!("must have no negative principal moment, got {e} kg m^2"),
            );
        }
    }
    let a = m6(&spec.added_mass);
    if (a - a.transpose()).abs().max() > 1e-9 * a.abs().max().max(1e-300) {
        return bad("added_mass", "must be symmetric".to_string());
    }
    // The whole mass matrix about the centre of gravity, reference pose.
    let body = FreeBody::new(spec.clone(), kind, &MeanPose::default());
    let p = match kind {
        FreeKind::Free => body.x_g,
        FreeKind::Pinned => body.reference(),
    };
    let (mm, _) = body.system(0.0, Fluid { rho: 0.0, g: 0.0 }, [0.0; 3], &[], p);
    let (first, names) = match kind {
        FreeKind::Free => (0, ["surge", "sway", "heave", "roll", "pitch", "yaw"]),
        FreeKind::Pinned => (3, ["surge", "sway", "heave", "roll", "pitch", "yaw"]),
    };
    for k in first..6 {
        if mm[(k, k)] <= 0.0 {
            return bad(
                if k < 3 { "mass" } else { "inertia" },
                format!(
                    "no mass in {} (the mass matrix with the added mass has {} there)",
                    names[k],
                    mm[(k, k)]
                ),
            );
        }
    }
    let sub = mm.view((first, first), (6 - first, 6 - first)).into_owned();
    if sub.cholesky().is_none() {
        return bad(
            "inertia",
            "the mass matrix with the added mass is not positive definite".to_string(),
        );
    }
    Ok(())
}

/// A prescribed rotation for tests and callers: `rotation` of the kinematics module
/// as a quaternion.
pub fn quaternion(roll: f64, pitch: f64, yaw: f64) -> UnitQuaternion<f64> {
    let r = rotation(roll, pitch, yaw);
    UnitQuaternion::from_matrix(&Matrix3::from_fn(|i, j| r[i][j]))
}
