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
    // Compensated positions: the hi parts of neighbours are close, so their
    // difference is exact or nearly so, and the lo parts add the rest.
    let d = (sb.r_hi.xyz - sa.r_hi.xyz) + (sb.r_lo.xyz - sa.r_lo.xyz);
    let oz = blocks[nodes[ep.a].block].oz;
    let zmid = oz + ((sa.r_hi.z + sb.r_hi.z) + (sa.r_lo.z + sb.r_lo.z)) * R(0.5);
    let u = current_at(ep.current, zmid);
    // No waves yet: the water-acceleration load waits for a wave model.
    let aw = vec3<R>(R(0.0), R(0.0), R(0.0));
    let el = glmf_element(lines[ep.line], d, sa.v.xyz, sb.v.xyz, ep.l0, u, aw);
    elem_loads[e] = ElemLoads(
        el.t.x, el.t.y, el.t.z, el.tension,
        el.f_half.x, el.f_half.y, el.f_half.z, el.half_mass, el.half_added,
    );
}
