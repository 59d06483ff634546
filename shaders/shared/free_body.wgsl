// Free and pinned rigid bodies and line failures on the GPU (Rust twins:
// body::free::FreeBody::accelerations and FreeBody::step, cpu::free::FreeRun::step,
// cpu::free::end_tension; the model is in docs/src/bodies.md, "Free bodies").
//
// Everything a free body needs lives in the flat `body_rows` buffer (no binding of its
// own), from `params.free_at` on, FREE_STRIDE values per body (offsets below), then
// the held routes' indices (as values of R), then from `params.fail_at` on FAIL_STRIDE
// values per line failure. Positions are relative to the body's initial reference
// point `Xr` (what its held routes' `p` is, relative to each route's block origin), so
// that only small displacements round in f32; the centre of gravity's displacement is
// a compensated pair.
//
// A step (the CPU path's order): the node pass of step n moves each held node onto its
// body's point at step n and leaves the node's force and mass block at step n in
// node_out (and reactions[c].x: the mass block's yz); then `free_bodies`, one
// invocation per body, lumps its held nodes in, solves the 6x6 (free) or 3x3 (pinned)
// equations about the centre of gravity or the pin, steps symplectic Euler, writes
// the body's row that the held nodes' targets read at the next step (body_point), and
// places its held nodes at their points with their points' velocities; then
// `line_failures`, one invocation per failure, fires the failures due and marks their
// constraints released (reactions[c].w = 1), after which node_accel treats the node as
// free and the body lumps it no more.

const FREE_STRIDE: u32 = 168u;
// The body's row (a BodyRow: displacement of the reference point since Xr, rotation
// R (not its change: the route's e1 is zero), velocity and acceleration of the
// reference point, angular velocity and acceleration).
const FREE_ROW: u32 = 0u;
// State: centre of gravity's displacement since its initial position (hi 0..3, lo
// 3..6), its velocity 6..9, quaternion (x, y, z, w) 9..13, angular velocity 13..16,
// the last step's acceleration of P 16..19 and angular acceleration 19..22.
const FREE_STATE: u32 = 24u;
// Constants: 0 kind (0 free, 1 pinned), 1 the pin's column of the per-step rows, 2 mass,
// 3 cg (3), 6 inertia (9, rows), 15 volume, 16 cb (3), 19 waterplane area, 20
// waterplane inertias (2), 22 added mass (36, rows), 58 drag areas (3), 61 rotational
// drag (3), 64 damping (36, rows), 100 force (3), 103 moment (3), 106 R0 cg (3: the
// initial centre of gravity less Xr), 109 Xr (3, absolute), 112 Xr.z less the reference
// pose's z, 113 where the held routes' list starts, 114 its length.
const FREE_CONST: u32 = 48u;
const FAIL_STRIDE: u32 = 12u;
const ROUTE_FREE: u32 = 5u;

// A BodyRow read from `body_rows` at value offset `o`.
fn body_row_at(o: u32) -> BodyRow {
    var b: BodyRow;
    b.dx = body_rows[o];
    b.dy = body_rows[o + 1u];
    b.dz = body_rows[o + 2u];
    b.dr00 = body_rows[o + 3u];
    b.dr01 = body_rows[o + 4u];
    b.dr02 = body_rows[o + 5u];
    b.dr10 = body_rows[o + 6u];
    b.dr11 = body_rows[o + 7u];
    b.dr12 = body_rows[o + 8u];
    b.dr20 = body_rows[o + 9u];
    b.dr21 = body_rows[o + 10u];
    b.dr22 = body_rows[o + 11u];
    b.vx = body_rows[o + 12u];
    b.vy = body_rows[o + 13u];
    b.vz = body_rows[o + 14u];
    b.ax = body_rows[o + 15u];
    b.ay = body_rows[o + 16u];
    b.az = body_rows[o + 17u];
    b.wx = body_rows[o + 18u];
    b.wy = body_rows[o + 19u];
    b.wz = body_rows[o + 20u];
    b.alx = body_rows[o + 21u];
    b.aly = body_rows[o + 22u];
    b.alz = body_rows[o + 23u];
    return b;
}

fn fb3(o: u32) -> vec3<R> {
    return vec3<R>(body_rows[o], body_rows[o + 1u], body_rows[o + 2u]);
}

fn fb_set3(o: u32, v: vec3<R>) {
    body_rows[o] = v.x;
    body_rows[o + 1u] = v.y;
    body_rows[o + 2u] = v.z;
}

// Whether constraint `c` still holds its node (not released by a line failure).
fn node_held(c: u32) -> bool {
    return c != NO_CONSTRAINT && !(params.n_fail != 0u && reactions[c].w != R(0.0));
}

// A node held on a free body leaves its force and mass block of this step for the body
// (free_bodies reads them after the node pass).
fn free_lump_store(i: u32, nd: NodeParams, nf: NodeForce) {
    if params.n_free != 0u && node_held(nd.constraint) && routes[nd.constraint].kind == ROUTE_FREE {
        node_out[i] = NodeOut(vec4<R>(nf.f, nf.m.xx), vec4<R>(nf.m.yy, nf.m.zz, nf.m.xy, nf.m.xz));
        reactions[nd.constraint].x = nf.m.yz;
    }
}

// 3x3 matrices as rows.
struct M3 {
    x: vec3<R>,
    y: vec3<R>,
    z: vec3<R>,
}

fn m3_vec(m: M3, v: vec3<R>) -> vec3<R> {
    return vec3<R>(dot(m.x, v), dot(m.y, v), dot(m.z, v));
}

fn m3_t(m: M3) -> M3 {
    return M3(vec3<R>(m.x.x, m.y.x, m.z.x), vec3<R>(m.x.y, m.y.y, m.z.y), vec3<R>(m.x.z, m.y.z, m.z.z));
}

fn m3_mul(a: M3, b: M3) -> M3 {
    let bt = m3_t(b);
    return M3(m3_vec(bt, a.x), m3_vec(bt, a.y), m3_vec(bt, a.z));
}

fn m3_add(a: M3, b: M3) -> M3 {
    return M3(a.x + b.x, a.y + b.y, a.z + b.z);
}

fn m3_neg(a: M3) -> M3 {
    return M3(-a.x, -a.y, -a.z);
}

// `[e x]`, the cross-product matrix.
fn skew(e: vec3<R>) -> M3 {
    let z = R(0.0);
    return M3(vec3<R>(z, -e.z, e.y), vec3<R>(e.z, z, -e.x), vec3<R>(-e.y, e.x, z));
}

fn m3_diag(d: vec3<R>) -> M3 {
    let z = R(0.0);
    return M3(vec3<R>(d.x, z, z), vec3<R>(z, d.y, z), vec3<R>(z, z, d.z));
}

// The 3x3 block (bi, bj) of the 6x6 matrix of rows at value offset `o` of body_rows.
fn fb_block(o: u32, bi: u32, bj: u32) -> M3 {
    let r = o + bi * 18u + bj * 3u;
    return M3(fb3(r), fb3(r + 6u), fb3(r + 12u));
}

// The rotation of unit quaternion q = (x, y, z, w) (nalgebra's formula).
fn quat_rot(q: vec4<R>) -> M3 {
    let ww = q.w * q.w;
    let ii = q.x * q.x;
    let jj = q.y * q.y;
    let kk = q.z * q.z;
    let ij = q.x * q.y * R(2.0);
    let wk = q.w * q.z * R(2.0);
    let wj = q.w * q.y * R(2.0);
    let ik = q.x * q.z * R(2.0);
    let jk = q.y * q.z * R(2.0);
    let wi = q.w * q.x * R(2.0);
    return M3(
        vec3<R>(ww + ii - jj - kk, ij - wk, wj + ik),
        vec3<R>(wk + ij, ww - ii + jj - kk, jk - wi),
        vec3<R>(ik - wj, wi + jk, ww - ii - jj + kk),
    );
}

// The Hamilton product a b of quaternions (x, y, z, w).
fn quat_mul(a: vec4<R>, b: vec4<R>) -> vec4<R> {
    let va = a.xyz;
    let vb = b.xyz;
    return vec4<R>(vb * a.w + va * b.w + cross(va, vb), a.w * b.w - dot(va, vb));
}

// The rotation by the scaled axis `v` as a quaternion (UnitQuaternion::from_scaled_axis).
fn quat_exp(v: vec3<R>) -> vec4<R> {
    let th = norm3(v);
    if th == R(0.0) {
        return vec4<R>(R(0.0), R(0.0), R(0.0), R(1.0));
    }
    let sc = sin_cos(th * R(0.5));
    return vec4<R>(v / th * sc.x, sc.y);
}

// A body's 6x6 mass matrix and load about a point P (body::free: `system`), in
// function memory.
struct Body6 {
    m: array<R, 36>,
    f: array<R, 6>,
}

fn b6_add_block(s: ptr<function, Body6>, bi: u32, bj: u32, a: M3) {
    let o = bi * 18u + bj * 3u;
    (*s).m[o] += a.x.x;
    (*s).m[o + 1u] += a.x.y;
    (*s).m[o + 2u] += a.x.z;
    (*s).m[o + 6u] += a.y.x;
    (*s).m[o + 7u] += a.y.y;
    (*s).m[o + 8u] += a.y.z;
    (*s).m[o + 12u] += a.z.x;
    (*s).m[o + 13u] += a.z.y;
    (*s).m[o + 14u] += a.z.z;
}

// Adds a force `fv` at `e` from P.
fn b6_force(s: ptr<function, Body6>, fv: vec3<R>, e: vec3<R>) {
    let mom = cross(e, fv);
    (*s).f[0] += fv.x;
    (*s).f[1] += fv.y;
    (*s).f[2] += fv.z;
    (*s).f[3] += mom.x;
    (*s).f[4] += mom.y;
    (*s).f[5] += mom.z;
}

fn b6_moment(s: ptr<function, Body6>, mv: vec3<R>) {
    (*s).f[3] += mv.x;
    (*s).f[4] += mv.y;
    (*s).f[5] += mv.z;
}

// Adds a point mass block `m` at `e` from P moving with angular velocity `w`, and its
// centripetal term (body::free: add_point_mass).
fn b6_point_mass(s: ptr<function, Body6>, m: M3, e: vec3<R>, w: vec3<R>) {
    let sk = skew(e);
    let ms = m3_mul(m, sk);
    b6_add_block(s, 0u, 0u, m);
    b6_add_block(s, 0u, 1u, m3_neg(ms));
    b6_add_block(s, 1u, 0u, m3_mul(sk, m));
    b6_add_block(s, 1u, 1u, m3_neg(m3_mul(sk, ms)));
    let c = m3_vec(m, cross(w, cross(w, e)));
    b6_force(s, -c, e);
}

// Solves (*s).m x = (*s).f in place of f (Cholesky; the matrix is symmetric positive
// definite for a body that passed body::free::check).
fn b6_solve(s: ptr<function, Body6>) -> array<R, 6> {
    var l: array<R, 36>;
    for (var j = 0u; j < 6u; j += 1u) {
        var d = (*s).m[j * 6u + j];
        for (var k = 0u; k < j; k += 1u) {
            d -= l[j * 6u + k] * l[j * 6u + k];
        }
        let ljj = sqrt(d);
        l[j * 6u + j] = ljj;
        for (var i = j + 1u; i < 6u; i += 1u) {
            var x = (*s).m[i * 6u + j];
            for (var k = 0u; k < j; k += 1u) {
                x -= l[i * 6u + k] * l[j * 6u + k];
            }
            l[i * 6u + j] = x / ljj;
        }
    }
    var y: array<R, 6>;
    for (var i = 0u; i < 6u; i += 1u) {
        var x = (*s).f[i];
        for (var k = 0u; k < i; k += 1u) {
            x -= l[i * 6u + k] * y[k];
        }
        y[i] = x / l[i * 6u + i];
    }
    var z: array<R, 6>;
    for (var ii = 0u; ii < 6u; ii += 1u) {
        let i = 5u - ii;
        var x = y[i];
        for (var k = i + 1u; k < 6u; k += 1u) {
            x -= l[k * 6u + i] * z[k];
        }
        z[i] = x / l[i * 6u + i];
    }
    return z;
}

// A free or pinned body's state as free_body_accelerations reads it.
struct FreeState {
    // The centre of gravity less Xr.
    g: vec3<R>,
    vg: vec3<R>,
    q: vec4<R>,
    w: vec3<R>,
}

// The accelerations (a_P, alpha) of free body `b` (record at value offset `o`) in
// state `st` at step `k` (body::free::FreeBody::accelerations): P the centre of
// gravity of a free body, the pin of a pinned body (`pin`: its row of this step). `u`
// is the water velocity at the reference point; the lumps are the held nodes' loads
// the node pass left.
fn free_body_accelerations(o: u32, st: FreeState, pin: BodyRow, u: vec3<R>) -> array<vec3<R>, 2> {
    let c = o + FREE_CONST;
    let pinned = body_rows[c] != R(0.0);
    let rot = quat_rot(st.q);
    let rt = m3_t(rot);
    let w = st.w;
    let mass = body_rows[c + 2u];
    let cg = fb3(c + 3u);
    // The reference point less Xr, and P less Xr.
    let x = st.g - m3_vec(rot, cg);
    var p = st.g;
    let ap_pin = vec3<R>(pin.ax, pin.ay, pin.az);
    if pinned {
        p = vec3<R>(pin.dx, pin.dy, pin.dz);
    }
    let ex = x - p;
    let eg = st.g - p;
    var s: Body6;
    // The rigid body: its mass at the centre of gravity, its inertia, the gyroscopic
    // moment.
    let inertia = M3(fb3(c + 6u), fb3(c + 9u), fb3(c + 12u));
    let ig = m3_mul(m3_mul(rot, inertia), rt);
    b6_point_mass(&s, m3_diag(vec3<R>(mass, mass, mass)), eg, w);
    b6_add_block(&s, 1u, 1u, ig);
    b6_moment(&s, -cross(w, m3_vec(ig, w)));
    // Added mass (body axes, about the reference point), turned to global axes and
    // moved to P: S^T A S with S = [[1, -[ex x]], [0, 1]].
    let am = c + 22u;
    let a11 = m3_mul(m3_mul(rot, fb_block(am, 0u, 0u)), rt);
    let a12 = m3_mul(m3_mul(rot, fb_block(am, 0u, 1u)), rt);
    let a21 = m3_mul(m3_mul(rot, fb_block(am, 1u, 0u)), rt);
    let a22 = m3_mul(m3_mul(rot, fb_block(am, 1u, 1u)), rt);
    let sx = skew(ex);
    let b12 = m3_add(a12, m3_neg(m3_mul(a11, sx)));
    b6_add_block(&s, 0u, 0u, a11);
    b6_add_block(&s, 0u, 1u, b12);
    b6_add_block(&s, 1u, 0u, m3_add(a21, m3_mul(sx, a11)));
    b6_add_block(&s, 1u, 1u, m3_add(m3_add(a22, m3_neg(m3_mul(a21, sx))), m3_mul(sx, b12)));
    // Weight and buoyancy.
    let ez = vec3<R>(R(0.0), R(0.0), R(1.0));
    let rho = params.water_density;
    let rg = rho * params.gravity;
    b6_force(&s, ez * (-mass * params.gravity), eg);
    b6_force(&s, ez * (rg * body_rows[c + 15u]), ex + m3_vec(rot, fb3(c + 16u)));
    // Waterplane: heave and tilt.
    let awp = body_rows[c + 19u];
    if awp != R(0.0) {
        b6_force(&s, ez * (-rg * awp * (x.z + body_rows[c + 112u])), ex);
    }
    let iwx = body_rows[c + 20u];
    let iwy = body_rows[c + 21u];
    if iwx != R(0.0) || iwy != R(0.0) {
        let tilt = cross(ez, m3_vec(rot, ez));
        let iw = m3_mul(m3_mul(rot, m3_diag(vec3<R>(iwx, iwy, R(0.0)))), rt);
        b6_moment(&s, -(m3_vec(iw, tilt) * rg));
    }
    // Linear damping (body axes, about the reference point).
    let vx = st.vg + cross(w, x - st.g);
    let dm = c + 64u;
    let vb = m3_vec(rt, vx);
    let wb = m3_vec(rt, w);
    let lt = -(m3_vec(fb_block(dm, 0u, 0u), vb) + m3_vec(fb_block(dm, 0u, 1u), wb));
    let lr = -(m3_vec(fb_block(dm, 1u, 0u), vb) + m3_vec(fb_block(dm, 1u, 1u), wb));
    b6_force(&s, m3_vec(rot, lt), ex);
    b6_moment(&s, m3_vec(rot, lr));
    // Quadratic drag on the relative velocity at the reference point, and on the
    // rotation.
    let ur = u - vx;
    let cda = fb3(c + 58u);
    let fd = m3_vec(rot, cda * m3_vec(rt, ur)) * (R(0.5) * rho * norm3(ur));
    b6_force(&s, fd, ex);
    let cdr = fb3(c + 61u);
    b6_moment(&s, -(m3_vec(rot, cdr * m3_vec(rt, w)) * (R(0.5) * rho * norm3(w))));
    // External loads.
    b6_force(&s, fb3(c + 100u), ex);
    b6_moment(&s, fb3(c + 103u));
    // The held nodes, lumped into the body.
    let hs = u32(body_rows[c + 113u]);
    let hn = u32(body_rows[c + 114u]);
    for (var h = 0u; h < hn; h += 1u) {
        let rc = u32(body_rows[hs + h]);
        if !node_held(rc) {
            continue;
        }
        let q = routes[rc];
        let i = q.node;
        let sn = state[i];
        let d = (sn.r_hi.xyz - vec3<R>(q.p_hi_x, q.p_hi_y, q.p_hi_z)) + (sn.r_lo.xyz - vec3<R>(q.p_lo_x, q.p_lo_y, q.p_lo_z));
        let e = d - p;
        let no = node_out[i];
        let myz = reactions[rc].x;
        let m = M3(
            vec3<R>(no.force.w, no.acc.z, no.acc.w),
            vec3<R>(no.acc.z, no.acc.x, myz),
            vec3<R>(no.acc.w, myz, no.acc.y),
        );
        b6_point_mass(&s, m, e, w);
        b6_force(&s, no.force.xyz, e);
    }
    if pinned {
        // Translation prescribed: M_rr alpha = f_r - M_rt a_P, solved as the 6x6 system
        // [[1, 0], [0, M_rr]] (a_P, alpha) = (a_P, f_r - M_rt a_P).
        let mrt = M3(
            vec3<R>(s.m[18], s.m[19], s.m[20]),
            vec3<R>(s.m[24], s.m[25], s.m[26]),
            vec3<R>(s.m[30], s.m[31], s.m[32]),
        );
        let rhs = vec3<R>(s.f[3], s.f[4], s.f[5]) - m3_vec(mrt, ap_pin);
        var r: Body6;
        for (var i = 0u; i < 3u; i += 1u) {
            r.m[i * 7u] = R(1.0);
            for (var j = 3u; j < 6u; j += 1u) {
                r.m[(i + 3u) * 6u + j] = s.m[(i + 3u) * 6u + j];
            }
        }
        r.f[0] = ap_pin.x;
        r.f[1] = ap_pin.y;
        r.f[2] = ap_pin.z;
        r.f[3] = rhs.x;
        r.f[4] = rhs.y;
        r.f[5] = rhs.z;
        s = r;
    }
    let a = b6_solve(&s);
    return array<vec3<R>, 2>(vec3<R>(a[0], a[1], a[2]), vec3<R>(a[3], a[4], a[5]));
}

// Free body `b`'s state (record at value offset `o`).
fn free_state(o: u32) -> FreeState {
    let s = o + FREE_STATE;
    let c = o + FREE_CONST;
    let q = vec4<R>(body_rows[s + 9u], body_rows[s + 10u], body_rows[s + 11u], body_rows[s + 12u]);
    return FreeState((fb3(s) + fb3(s + 3u)) + fb3(c + 106u), fb3(s + 6u), q, fb3(s + 13u));
}

// One symplectic Euler step of free body `b` at step `k` of the submission
// (body::free::FreeBody::step, cpu::free::FreeRun::step): the accelerations at the
// state now, the velocities, then the position and attitude; then the body's row the
// held nodes' targets read (body::free::FreeBody::body_state).
fn free_body_step(b: u32, k: u32) {
    let o = params.free_at + b * FREE_STRIDE;
    let s = o + FREE_STATE;
    let c = o + FREE_CONST;
    let pinned = body_rows[c] != R(0.0);
    let col = u32(body_rows[c + 1u]);
    let dt = params.dt;
    let st = free_state(o);
    let cg = fb3(c + 3u);
    var pin: BodyRow;
    var pin_next: BodyRow;
    if pinned {
        pin = body_row_at((k * params.n_bodies + col) * 24u);
        pin_next = body_row_at(((k + 1u) * params.n_bodies + col) * 24u);
    }
    // The water velocity at the reference point (the first current profile).
    let xr = fb3(c + 109u);
    let x = st.g - m3_vec(quat_rot(st.q), cg);
    let u = current_at(0u, xr.z + x.z);
    let acc = free_body_accelerations(o, st, pin, u);
    let ap = acc[0];
    let alpha = acc[1];
    let w = st.w + alpha * dt;
    var q = quat_mul(quat_exp(w * dt), st.q);
    q = q / sqrt(dot(q, q));
    let rot = quat_rot(q);
    let r0cg = fb3(c + 106u);
    var vg = st.vg;
    if pinned {
        let cv = m3_vec(rot, cg);
        let dg = (vec3<R>(pin_next.dx, pin_next.dy, pin_next.dz) + cv) - r0cg;
        fb_set3(s, dg);
        fb_set3(s + 3u, vec3<R>(R(0.0)));
        vg = vec3<R>(pin_next.vx, pin_next.vy, pin_next.vz) + cross(w, cv);
    } else {
        vg = st.vg + ap * dt;
        let dg = add_compensated(fb3(s), fb3(s + 3u), opaque3(vg * dt));
        fb_set3(s, dg[0]);
        fb_set3(s + 3u, dg[1]);
    }
    fb_set3(s + 6u, vg);
    body_rows[s + 9u] = q.x;
    body_rows[s + 10u] = q.y;
    body_rows[s + 11u] = q.z;
    body_rows[s + 12u] = q.w;
    fb_set3(s + 13u, w);
    fb_set3(s + 16u, ap);
    fb_set3(s + 19u, alpha);
    // The row: the reference point and its motion.
    let g = (fb3(s) + fb3(s + 3u)) + r0cg;
    let xn = g - m3_vec(rot, cg);
    var e = xn - g;
    if pinned {
        e = vec3<R>(R(0.0));
    }
    let vref = vg + cross(w, xn - g);
    let aref = ap + cross(alpha, e) + cross(w, cross(w, e));
    fb_set3(o, xn);
    fb_set3(o + 3u, rot.x);
    fb_set3(o + 6u, rot.y);
    fb_set3(o + 9u, rot.z);
    fb_set3(o + 12u, vref);
    fb_set3(o + 15u, aref);
    fb_set3(o + 18u, w);
    fb_set3(o + 21u, alpha);
    // The held nodes placed rigidly at their points with the points' velocities
    // (cpu::free::FreeRun::step): the next step's element pass reads them there.
    let row = body_row_at(o + FREE_ROW);
    let hs = u32(body_rows[c + 113u]);
    let hn = u32(body_rows[c + 114u]);
    for (var h = 0u; h < hn; h += 1u) {
        let rc = u32(body_rows[hs + h]);
        if !node_held(rc) {
            continue;
        }
        let q = routes[rc];
        let t = body_point(q, row);
        let rr = add_compensated(t.r_hi, vec3<R>(R(0.0)), t.r_lo);
        state[q.node] = NodeState(vec4<R>(rr[0], R(0.0)), vec4<R>(rr[1], R(0.0)), vec4<R>(t.v, R(0.0)));
    }
}

// The elastic tension of element `e` (cpu::free::end_tension): EA times its strain,
// zero in slack.
fn end_tension(e: u32) -> R {
    let ep = elems[e];
    let sa = state[ep.a];
    let sb = state[ep.b];
    let d = (sb.r_hi.xyz - sa.r_hi.xyz) + (sb.r_lo.xyz - sa.r_lo.xyz);
    let l0 = ep.l0 + ep.l0_lo;
    return max(lines[ep.line].ea * (norm3(d) - l0) / l0, R(0.0));
}

// Line failure `f` after step `k` of the submission (cpu::CpuSolver's
// check_failures): fires when the step count reaches its time's step or the end
// element's tension reaches its threshold, records the step (counted from the start of
// the advance call) and the tension, and releases the end's constraint.
// Record: 0 node, 1 element, 2 constraint, 3 the time's step counted from the advance
// call's start (negative: none), 4 tension threshold (0: none), 5 fired (0, 1 time,
// 2 tension), 6 the step it fired (counted from the advance call's start), 7 tension.
fn line_failure_check(f: u32, k: u32) {
    let o = params.fail_at + f * FAIL_STRIDE;
    if body_rows[o + 5u] != R(0.0) {
        return;
    }
    let n = R(params.step_base + k + 1u);
    let ten = end_tension(u32(body_rows[o + 1u]));
    var how = R(0.0);
    let ts = body_rows[o + 3u];
    let tt = body_rows[o + 4u];
    if ts >= R(0.0) && n >= ts {
        how = R(1.0);
    } else if tt > R(0.0) && ten >= tt {
        how = R(2.0);
    }
    if how != R(0.0) {
        body_rows[o + 5u] = how;
        body_rows[o + 6u] = n;
        body_rows[o + 7u] = ten;
        reactions[u32(body_rows[o + 2u])].w = R(1.0);
    }
}
