// Stage 1 of a step, `element_forces`: per element, the GLMF loads
// (shared/prelude.wgsl: element_step, glmf_element) from the state of its two nodes.
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
    elem_loads[e] = element_step(e, ep, lines[ep.line], blk.oz, state[ep.a], state[ep.b], step.k, sr, elem_loads[e].visco);
}
