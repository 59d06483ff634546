// One element and one node of a step: the functions the element and node passes of the
// two-pass stages and the fused kernel compose (each computes exactly this, only from
// different memory). `gpu::shaders` appends this file to `prelude.wgsl` (whose structs,
// bindings and force functions it uses), before the wave kinematics.

// Depth of node state `s` (block origin height `oz`) under the water surface, m:
// negative in air. Still water: the surface is z = 0.
fn submergence(oz: R, s: NodeState) -> R {
    return -(oz + (s.r_hi.z + s.r_lo.z));
}

// The GLMF loads of element `e` (`ep`, line `lp`, its block's origin height `oz`) from
// the states `sa`, `sb` of its nodes a and b at step `k` of the submission (the row of
// `payout` of a winch cable's variable element) and its internal state `x` (a
// viscoelastic line's, returned advanced by the step by explicit Euler unless the pass
// evaluates; zero for every other line). CPU twin: cpu::passes element_pass.
fn element_step(e: u32, ep: ElemParams, lp: LineParams, oz: R, sa: NodeState, sb: NodeState, k: u32, sr: SeaRows, x: R) -> ElemLoads {
    // A winch cable's variable element takes l0_v(t) of this step (crate::ale).
    var l0 = ep.l0;
    var l0_lo = ep.l0_lo;
    var py = Payout(R(0.0), R(0.0), R(0.0), R(0.0), R(0.0));
    let var_elem = ep.winch != NO_WINCH;
    if var_elem {
        py = payout[k * params.n_winch + (ep.winch >> 1u)];
        l0 = py.l0;
        l0_lo = py.l0_lo;
    }
    // Compensated positions: the difference of the hi parts is made exact by a
    // two-sum, the lo parts add the rest: d = d_hi + d_lo to about eps^2.
    var stretch: R;
    var d: vec3<R>;
    if COMPENSATED {
        let x = two_sum(sb.r_hi.x, -sa.r_hi.x);
        let y = two_sum(sb.r_hi.y, -sa.r_hi.y);
        let z = two_sum(sb.r_hi.z, -sa.r_hi.z);
        let d_hi = vec3<R>(x.x, y.x, z.x);
        let d_lo = vec3<R>(x.y, y.y, z.y) + (sb.r_lo.xyz - sa.r_lo.xyz);
        d = d_hi + d_lo;
        stretch = element_stretch(d_hi, d_lo, l0, l0_lo);
    } else {
        d = (sb.r_hi.xyz - sa.r_hi.xyz) + (sb.r_lo.xyz - sa.r_lo.xyz);
        stretch = norm3(d) - l0;
    }
    let zmid = oz + ((sa.r_hi.z + sb.r_hi.z) + (sa.r_lo.z + sb.r_lo.z)) * R(0.5);
    var u = current_at(ep.current, zmid);
    // Still water: the surface is z = 0 and the water does not accelerate. Waves: the
    // mean of the two nodes' wave velocity and acceleration at the midpoint, the
    // surface over each node for the wetted fraction (cpu::stepper element_input),
    // from the element's cache entry (elem_waves) at its sea's rows `sr` of this step
    // (wave_sea_rows). WAVES (the generated header) is false in a still-water run's
    // fused pipeline: the waves branch folds away there.
    var aw = vec3<R>(R(0.0), R(0.0), R(0.0));
    var wet: R;
    if WAVES && sr.waves {
        let w = elem_waves(e, sr);
        u += w.u;
        aw = w.a;
        wet = wetted_fraction(w.eta_a + submergence(oz, sa), w.eta_b + submergence(oz, sb), ep.diameter);
    } else {
        wet = wetted_fraction(submergence(oz, sa), submergence(oz, sb), ep.diameter);
    }
    let el = glmf_element_wet(lp, d, stretch, sa.v.xyz, sb.v.xyz, l0, u, aw, wet, params.gravity);
    var tension = el.tension;
    if lp.table > R(0.0) {
        // A tabulated strain-tension curve: the elastic part from it, the damping as
        // before (cpu::passes tabulated_pass; no winch cable has one).
        let rg = current_ranges[u32(lp.table) - 1u];
        tension = tabulated_tension(rg, stretch / l0) + lp.ea_c * (dot(el.t, sb.v.xyz - sa.v.xyz) / l0);
    }
    var xn = x;
    if lp.ba_s > R(0.0) {
        // A viscoelastic line: the tension of the model at the state x, which advances
        // with the step's rate (cpu::passes visco_pass; no winch cable has one).
        let vt = visco_tension(lp.ea, lp.ea_d, lp.ea_d_slope, lp.ba_s, lp.ba_d, stretch / l0,
            dot(el.t, sb.v.xyz - sa.v.xyz) / l0, x);
        tension = vt.x;
        if params.evaluate == 0u {
            xn = x + vt.y * params.dt;
        }
    }
    if var_elem {
        tension = variable_element(ep, lp, py, d, sa.v.xyz, sb.v.xyz, tension);
    }
    return ElemLoads(
        el.t.x, el.t.y, el.t.z, tension,
        el.f_half.x, el.f_half.y, el.f_half.z, el.half_mass, el.half_added, xn,
    );
}

// The ALE additions of a winch cable's variable element (crate::ale; CPU twin:
// cpu::stepper element_pass and node_accel): the internal damping acts on the
// material strain rate, epsdot = (t . dv - (l / l0) Ldot) / l0, so the tension loses
// EA c l Ldot / l0^2; and the mass-flow forces of Eq. 39 on its material node m and
// winch node w, F_m = -mbar l0 g / 6, F_w = -mbar l0 g / 3 with
// g = -2 (Ldot / l0) (v_w - v_m) + (2 Ldot^2 / l0^2 - Lddot / l0) (r_w - r_m),
// left in node_out for the node pass. Returns the tension.
fn variable_element(ep: ElemParams, lp: LineParams, py: Payout, d: vec3<R>, va: vec3<R>, vb: vec3<R>, tension: R) -> R {
    var ten = tension;
    let l0 = py.l0;
    if py.rate != R(0.0) {
        let l = norm3(d);
        ten -= lp.ea_c * l * py.rate / (l0 * l0);
    }
    let w_is_b = (ep.winch & 1u) == 1u;
    let m = select(ep.b, ep.a, w_is_b);
    let w = select(ep.a, ep.b, w_is_b);
    var fm = vec3<R>(R(0.0), R(0.0), R(0.0));
    var fw = fm;
    if py.rate != R(0.0) || py.accel != R(0.0) {
        // r_w - r_m and v_w - v_m from the element's a-to-b difference.
        let e = select(-d, d, w_is_b);
        let dv = select(va - vb, vb - va, w_is_b);
        let il0 = R(1.0) / l0;
        let g = dv * (R(-2.0) * py.rate * il0) + e * ((R(2.0) * py.rate * py.rate * il0 - py.accel) * il0);
        let s = -lp.mass * l0;
        fm = g * (s / R(6.0));
        fw = g * (s / R(3.0));
    }
    node_out[m].force = vec4<R>(fm, R(0.0));
    node_out[w].force = vec4<R>(fw, R(0.0));
    return ten;
}

// Node b's position less node a's, from their compensated positions.
fn node_diff(sa: NodeState, sb: NodeState) -> vec3<R> {
    return (sb.r_hi.xyz - sa.r_hi.xyz) + (sb.r_lo.xyz - sa.r_lo.xyz);
}

// The held direction of a clamped end, row `row` of current_pts (ElemParams).
fn clamp_dir(row: u32) -> vec3<R> {
    let p = current_pts[row];
    return vec3<R>(p.ux, p.uy, p.uz);
}

// The node an element's hinge row `x` names on one side, or `own` without a hinge
// there (so that the state read is always in range).
fn hinge_node(x: u32, own: u32) -> u32 {
    return select(own, x, x != NO_HINGE);
}

// The bending shear of an element with hinge row `hr` (ElemParams) from the states of
// its nodes a (`sa`) and b (`sb`), of the far node of the element before it (`sp`)
// and of the far node of the element after it (`sn`): the force f2 of the hinge at
// its node a (where it is the element after) less the force f1 of the hinge at its
// node b (where it is the element before), each from bending_hinge. Node b receives
// +shear, node a -shear (gather_add). CPU twin: cpu::passes bending_pass, which adds
// each hinge's f2 and -f1 to the shears of its two elements.
fn element_shear(hr: ElemParams, sp: NodeState, sa: NodeState, sb: NodeState, sn: NodeState) -> vec3<R> {
    var shear = vec3<R>(R(0.0), R(0.0), R(0.0));
    if hr.a == NO_HINGE && hr.b == NO_HINGE {
        return shear;
    }
    let d = node_diff(sa, sb);
    let l = norm3(d);
    let t = d / l;
    if hr.a != NO_HINGE {
        var q1: vec3<R>;
        var l1 = R(1.0);
        if hr.line != NO_HINGE {
            q1 = clamp_dir(hr.line);
        } else {
            let d1 = node_diff(sp, sa);
            l1 = norm3(d1);
            q1 = d1 / l1;
        }
        shear += bending_hinge(q1, l1, t, l, hr.l0)[1];
    }
    if hr.b != NO_HINGE {
        var q2: vec3<R>;
        var l2 = R(1.0);
        if hr.current != NO_HINGE {
            q2 = clamp_dir(hr.current);
        } else {
            let d2 = node_diff(sb, sn);
            l2 = norm3(d2);
            q2 = d2 / l2;
        }
        shear -= bending_hinge(t, l, q2, l2, hr.l0_lo)[0];
    }
    return shear;
}

// The bending shear of element `e` as the two-pass element stage left it: the first
// three values of elem_loads[params.n_elems + e] (zero without BENDING).
fn shear_of(e: u32) -> vec3<R> {
    if BENDING {
        let x = elem_loads[params.n_elems + e];
        return vec3<R>(x.tx, x.ty, x.tz);
    }
    return vec3<R>(R(0.0), R(0.0), R(0.0));
}

struct NodeForce {
    f: vec3<R>,
    m: Sym3,
    // The seabed's damping slopes (seabed_damping), which node_advance takes
    // implicitly; zero off the seabed.
    c: vec3<R>,
    // The friction split along the line: the sum of the node's elements' unit tangents
    // while gathering (gather_add), then (q, d) of seabed_friction_axis (gather_end),
    // which node_advance adds as dt d q q^T; zero where the friction is isotropic.
    ax: vec4<R>,
}

// The waves over node `i` at step `k` as its point mass's loads read them
// (node_waves), or zeros when the point has no drag, no displaced mass and no added
// mass: gather_begin and gather_end then multiply every wave value by zero, so the
// node pass skips the cache read (14 scalars per node-step) for the plain nodes of a
// line. CPU twin: the chain kernel (cpu::chain) interpolates per-node values only for
// blocks with such points. Zeros too without WAVES (a still-water pipeline; node_waves
// would return zeros there anyway).
fn point_waves(i: u32, nd: NodeParams, k: u32) -> WaveKin {
    if WAVES && WAVE_POINTS && (nd.point_drag != R(0.0) || nd.point_displaced != R(0.0) || nd.point_added != R(0.0)) {
        return node_waves(i, k);
    }
    return WaveKin(R(0.0), vec3<R>(R(0.0)), vec3<R>(R(0.0)));
}

// The start of node `nd`'s gather (state `s`, block `blk`, waves `w` over it: see
// node_waves): its point mass and the point's weight less buoyancy, less the added
// mass and buoyancy of the share of the point out of the water (nothing under water:
// dry = 0).
fn gather_begin(nd: NodeParams, s: NodeState, blk: BlockParams, w: WaveKin) -> NodeForce {
    let dry = R(1.0) - point_wetted_fraction(w.eta + submergence(blk.oz, s), nd.point_radius);
    let wz = nd.point_weight_z - dry * (nd.point_displaced * params.gravity);
    let zero = vec3<R>(R(0.0), R(0.0), R(0.0));
    return NodeForce(vec3<R>(R(0.0), R(0.0), wz), sym3_scalar(nd.point_mass - dry * nd.point_added), zero, vec4<R>(R(0.0)));
}

// Adds the loads `el` and bending shear `shear` (element_shear; zero without
// bending) of the element of incidence entry `entry` (element * 2 + side): node a
// takes f_half + (T t - shear), node b f_half - (T t - shear).
fn gather_add(nf: NodeForce, el: ElemLoads, shear: vec3<R>, entry: u32) -> NodeForce {
    var f = nf.f;
    let sign = select(R(1.0), R(-1.0), (entry & 1u) == 1u);
    let t = vec3<R>(el.tx, el.ty, el.tz);
    if BENDING {
        f += vec3<R>(el.fx, el.fy, el.fz) + (t * el.tension - shear) * sign;
    } else {
        f += vec3<R>(el.fx, el.fy, el.fz) + t * (sign * el.tension);
    }
    var ax = nf.ax;
    if params.seabed_mu_axial != params.seabed_mu {
        ax += vec4<R>(t, R(1.0));
    }
    return NodeForce(f, sym3_add_element(nf.m, el.half_mass, el.half_added, t), nf.c, ax);
}

// The end of node `i`'s gather (block `blk`, state `s`, step `k` of the submission,
// waves `w` over it): point drag on the relative water velocity, the water-
// acceleration load (1 + Ca) rho V a of the point's wet share in waves, a winch
// node's mass-flow force and tributary change, seabed contact.
fn gather_end(i: u32, nd: NodeParams, s: NodeState, nf: NodeForce, blk: BlockParams, k: u32, w: WaveKin) -> NodeForce {
    var f = nf.f;
    let v = s.v.xyz;
    let wet = point_wetted_fraction(w.eta + submergence(blk.oz, s), nd.point_radius);
    if nd.point_drag > R(0.0) {
        let z = blk.oz + (s.r_hi.z + s.r_lo.z);
        let vr = (current_at(nd.current, z) + w.u) - v;
        f += vr * (nd.point_drag * norm3(vr) * wet);
    }
    let m_fk = nd.point_displaced + nd.point_added;
    if WAVES && WAVE_POINTS && wave_steps[blk.wave_rows + k].n != 0u && m_fk > R(0.0) {
        f += w.a * (m_fk * wet);
    }
    var trib = nd.tributary;
    if nd.winch != NO_WINCH {
        // A node of a variable element: its tributary length follows l0_v, and the
        // element pass left the mass-flow force of Eq. 39 in node_out (crate::ale).
        let py = payout[k * params.n_winch + nd.winch];
        trib += py.trib;
        if py.rate != R(0.0) || py.accel != R(0.0) {
            f += node_out[i].force.xyz;
        }
    }
    var c = nf.c;
    // The friction split along the line, on a node of one or two elements (a net's
    // knot has no line direction: isotropic, mu_t): cpu::passes node_accel_of.
    let split = params.seabed_mu_axial != params.seabed_mu && nf.ax.w < R(2.5);
    var ax = vec4<R>(R(0.0));
    if params.seabed == 1u {
        let pen = (blk.zb - s.r_hi.z) - s.r_lo.z;
        f += seabed_force(pen, trib, v);
        c = seabed_damping(pen, trib, v);
        if split {
            ax = seabed_friction_axis(params.seabed_k * trib * pen, vec3<R>(R(0.0), R(0.0), R(1.0)), v, nf.ax.xyz);
        }
    } else if params.seabed > 1u {
        // The seabed grid: along its normal; c carries (c_n, c_t, 0), which
        // node_advance turns into the damping matrix with the normal looked up again.
        let g = seabed_height(blk.ox + (s.r_hi.x + s.r_lo.x), blk.oy + (s.r_hi.y + s.r_lo.y));
        let gap = ((g.x - blk.oz) - s.r_hi.z) - s.r_lo.z;
        f += seabed_slope_force(gap, trib, v, g);
        c = vec3<R>(seabed_slope_damping(gap, trib, v, g), R(0.0));
        if split {
            let n = seabed_slope_normal(g);
            ax = seabed_friction_axis(params.seabed_k * trib * gap * n.z, n, v, nf.ax.xyz);
        }
    }
    f -= ax.xyz * (ax.w * dot(v, ax.xyz));
    return NodeForce(f, nf.m, c, ax);
}

// Force and mass block of node `i`: its elements' loads and half masses gathered over
// the incidence list from `elem_loads` (no atomics), a screen net's knot's share of
// its panels (left in node_out by the element pass: element_forces), point-mass
// weight and drag, seabed contact.
fn gather_node(i: u32, nd: NodeParams, s: NodeState, k: u32) -> NodeForce {
    let blk = blocks[nd.block];
    let w = point_waves(i, nd, k);
    var nf = gather_begin(nd, s, blk, w);
    for (var j = nd.inc_start; j < nd.inc_end; j += 1u) {
        let entry = inc[j];
        nf = gather_add(nf, elem_loads[entry >> 1u], shear_of(entry >> 1u), entry);
    }
    if nd.screen != NO_KNOT {
        nf.f += node_out[i].force.xyz;
    }
    return gather_end(i, nd, s, nf, blk, k, w);
}

// ---- Screen-model nets: a knot's share of the panels it is a corner of (CPU twin:
// cpu::screen screen_knot_force). The stages gather it from their own memory of the
// states (element_forces.wgsl, fused_chain.wgsl) with these.

// The constants of the net whose two rows start at row q of current_pts
// (gpu::engine::install packs them).
fn screen_coefs_at(q: u32) -> ScreenCoefs {
    let a = current_pts[q];
    let b = current_pts[q + 1u];
    return ScreenCoefs(u32(a.z), u32(a.ux), a.uy, a.uz, b.z, b.ux, b.uy);
}

// Corner c (0 top-left, 1 top-right, 2 bottom-right, 3 bottom-left) of grid cell q
// (0 up-left, 1 up-right, 2 down-right, 3 down-left) of knot `i`, whose 8 neighbours
// start at inc[rec]; NO_KNOT where the grid has none (model::screen KNOT_PANELS).
fn screen_corner(i: u32, rec: u32, q: u32, c: u32) -> u32 {
    var t = array<u32, 16>(0u, 1u, 8u, 7u, 1u, 2u, 3u, 8u, 8u, 3u, 4u, 5u, 7u, 8u, 5u, 6u);
    let j = t[q * 4u + c];
    if j == 8u {
        return i;
    }
    return inc[rec + j];
}

// A quarter of the force of the panel whose corners have states s0..s3 (relative to
// the origin of block `blk`), in current profile `cur` at the height of its centre
// plus `uw`, the mean of its corners' wave velocities.
fn screen_panel_share(co: ScreenCoefs, blk: BlockParams, cur: u32, s0: NodeState, s1: NodeState,
        s2: NodeState, s3: NodeState, uw: vec3<R>) -> vec3<R> {
    let p0 = s0.r_hi.xyz + s0.r_lo.xyz;
    let p1 = s1.r_hi.xyz + s1.r_lo.xyz;
    let p2 = s2.r_hi.xyz + s2.r_lo.xyz;
    let p3 = s3.r_hi.xyz + s3.r_lo.xyz;
    let zc = blk.oz + (p0.z + p1.z + p2.z + p3.z) * R(0.25);
    let u = current_at(cur, zc) + uw;
    return screen_panel_force(co, p0, p1, p2, p3, s0.v.xyz, s1.v.xyz, s2.v.xyz, s3.v.xyz, u) * R(0.25);
}

// The mean wave velocity at step k over the four nodes a..d (zero without waves; a
// layout with screen knots has WAVE_POINTS set: gpu::engine layout_has_wave_points).
fn screen_waves(a: u32, b: u32, c: u32, d: u32, k: u32) -> vec3<R> {
    var uw = vec3<R>(R(0.0), R(0.0), R(0.0));
    if WAVES && WAVE_POINTS {
        uw = (((node_waves(a, k).u + node_waves(b, k).u) + node_waves(c, k).u) + node_waves(d, k).u) * R(0.25);
    }
    return uw;
}

// Acceleration of node `i`: free (mass block solve) or driven onto its route with
// Baumgarte stabilisation `a = a_d - beta (v - v_d) - alpha (r - r_d)`, at `tau`
// into the submission, its step `k`.
fn node_accel(nd: NodeParams, s: NodeState, nf: NodeForce, tau: R, k: u32) -> vec3<R> {
    // A constraint released by a line failure leaves its node free (node_held).
    if !node_held(nd.constraint) {
        return sym3_solve(nf.m, nf.f);
    }
    let d = constraint_target(nd.constraint, tau, k);
    let dr = (s.r_hi.xyz - d.r_hi) + (s.r_lo.xyz - d.r_lo);
    return d.a - (s.v.xyz - d.v) * params.beta - dr * params.alpha;
}

// Symplectic Euler from state `s` under `nf` at `tau` into the submission (its step
// `k`): v += a dt; r += v dt (r kept as a compensated pair). The seabed's damping is
// taken implicitly, linearised at this state: (M + dt diag(c)) a = F (CPU twin:
// cpu::stepper node_accel_of with implicit_dt), so it does not bound the step.
fn node_advance(nd: NodeParams, s: NodeState, nf: NodeForce, tau: R, k: u32) -> NodeState {
    var nfi = nf;
    if params.seabed > 1u {
        // The seabed grid: (M + dt (c_t I + (c_n - c_t) n n^T)) a = F, c = (c_n, c_t, 0)
        // from gather_end (cpu::passes node_accel_of).
        if nf.c.x > R(0.0) || nf.c.y > R(0.0) {
            let blk = blocks[nd.block];
            let n = seabed_slope_normal(seabed_height(blk.ox + (s.r_hi.x + s.r_lo.x), blk.oy + (s.r_hi.y + s.r_lo.y)));
            let ct = params.dt * nf.c.y;
            let d = params.dt * (nf.c.x - nf.c.y);
            nfi.m.xx += ct + d * n.x * n.x;
            nfi.m.yy += ct + d * n.y * n.y;
            nfi.m.zz += ct + d * n.z * n.z;
            nfi.m.xy += d * n.x * n.y;
            nfi.m.xz += d * n.x * n.z;
            nfi.m.yz += d * n.y * n.z;
        }
    } else {
        nfi.m.xx += params.dt * nf.c.x;
        nfi.m.yy += params.dt * nf.c.y;
        nfi.m.zz += params.dt * nf.c.z;
    }
    if nf.ax.w != R(0.0) {
        // The axial friction's slope: + dt d q q^T (cpu::passes node_accel_of).
        let q = nf.ax.xyz;
        let d = params.dt * nf.ax.w;
        nfi.m.xx += d * q.x * q.x;
        nfi.m.yy += d * q.y * q.y;
        nfi.m.zz += d * q.z * q.z;
        nfi.m.xy += d * q.x * q.y;
        nfi.m.xz += d * q.x * q.z;
        nfi.m.yz += d * q.y * q.z;
    }
    let a = node_accel(nd, s, nfi, tau, k);
    let vn = s.v.xyz + a * params.dt;
    let r = add_compensated(s.r_hi.xyz, s.r_lo.xyz, opaque3(vn * params.dt));
    return NodeState(vec4<R>(r[0], R(0.0)), vec4<R>(r[1], R(0.0)), vec4<R>(vn, R(0.0)));
}

// Blow-up check of a node's new state in block `blk`, written so that NaN fails the
// comparisons (cpu::stepper check): 0, FAIL_SPEED or FAIL_DISTANCE.
fn node_check(blk: BlockParams, s: NodeState) -> u32 {
    let ra = vec3<R>(blk.ox, blk.oy, blk.oz) + (s.r_hi.xyz + s.r_lo.xyz);
    if !all(abs(s.v.xyz) < vec3<R>(params.max_speed)) {
        return FAIL_SPEED;
    } else if !all(abs(ra) < vec3<R>(params.max_distance)) {
        return FAIL_DISTANCE;
    }
    return 0u;
}
