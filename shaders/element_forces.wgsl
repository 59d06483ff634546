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
        stretch = element_stretch(d_hi, d_lo, ep.l0, ep.l0_lo);
    } else {
        d = (sb.r_hi.xyz - sa.r_hi.xyz) + (sb.r_lo.xyz - sa.r_lo.xyz);
        stretch = norm3(d) - ep.l0;
    }
    let oz = blocks[ep.block].oz;
    let zmid = oz + ((sa.r_hi.z + sb.r_hi.z) + (sa.r_lo.z + sb.r_lo.z)) * R(0.5);
    let u = current_at(ep.current, zmid);
    // No waves yet: the water-acceleration load waits for a wave model.
    let aw = vec3<R>(R(0.0), R(0.0), R(0.0));
    let el = glmf_element(lines[ep.line], d, stretch, sa.v.xyz, sb.v.xyz, ep.l0, u, aw);
    elem_loads[e] = ElemLoads(
        el.t.x, el.t.y, el.t.z, el.tension,
        el.f_half.x, el.f_half.y, el.f_half.z, el.half_mass, el.half_added,
    );
}
