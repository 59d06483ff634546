// Stage 1 of a step, `element_forces`: per element, the GLMF loads
// (shared/prelude.wgsl: glmf_element) from the state of its two nodes.
// CPU twin: cpu::stepper element_pass.

@compute @workgroup_size(64)
fn element_forces(@builtin(global_invocation_id) gid: vec3<u32>) {
    let e = gid.x;
    if e >= params.n_elems || atomicLoad(&status.failed) != 0u {
        return;
    }
    let ep = elems[e];
    let sa = state[ep.a];
    let sb = state[ep.b];
    // A winch cable's variable element takes l0_v(t) of this step (crate::ale).
    var l0 = ep.l0;
    var l0_lo = ep.l0_lo;
    var py = Payout(R(0.0), R(0.0), R(0.0), R(0.0), R(0.0));
    let var_elem = ep.winch != NO_WINCH;
    if var_elem {
        py = payout[step.k * params.n_winch + (ep.winch >> 1u)];
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
    let oz = blocks[ep.block].oz;
    let zmid = oz + ((sa.r_hi.z + sb.r_hi.z) + (sa.r_lo.z + sb.r_lo.z)) * R(0.5);
    let u = current_at(ep.current, zmid);
    // No waves yet: the water-acceleration load waits for a wave model.
    let aw = vec3<R>(R(0.0), R(0.0), R(0.0));
    let lp = lines[ep.line];
    let el = glmf_element(lp, d, stretch, sa.v.xyz, sb.v.xyz, l0, u, aw);
    var tension = el.tension;
    if var_elem {
        tension = variable_element(ep, lp, py, d, sa.v.xyz, sb.v.xyz, tension);
    }
    elem_loads[e] = ElemLoads(
        el.t.x, el.t.y, el.t.z, tension,
        el.f_half.x, el.f_half.y, el.f_half.z, el.half_mass, el.half_added,
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
