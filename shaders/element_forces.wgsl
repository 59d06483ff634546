// Stage 1 of a step, `element_forces`: per element, the GLMF loads
// (shared/prelude.wgsl: element_step, glmf_element) from the state of its two nodes,
// and with BENDING its bending shear (shared/step.wgsl: element_shear) from the
// states of up to four nodes.
// CPU twin: cpu::stepper element_pass.

@compute @workgroup_size(64)
fn element_forces(@builtin(global_invocation_id) gid: vec3<u32>) {
    let e = gid.x;
    if e >= params.n_elems || atomicLoad(&status.failed) != 0u {
        return;
    }
    let ep = elems[e];
    let blk = blocks[ep.block];
    var sr = SeaRows(0u, 0u, 0u, 0u, false);
    if WAVES {
        sr = wave_sea_rows(blk.wave_rows, step.k);
    }
    let sa = state[ep.a];
    let sb = state[ep.b];
    elem_loads[e] = element_step(e, ep, lines[ep.line], blk.oz, sa, sb, step.k, sr, elem_loads[e].visco);
    if BENDING {
        // The bending shear, left in the element's second row (shared/step.wgsl
        // element_shear, shear_of).
        let hr = elems[params.n_elems + e];
        let sh = element_shear(hr, state[hinge_node(hr.a, ep.a)], sa, sb, state[hinge_node(hr.b, ep.b)]);
        elem_loads[params.n_elems + e].tx = sh.x;
        elem_loads[params.n_elems + e].ty = sh.y;
        elem_loads[params.n_elems + e].tz = sh.z;
    }
}
