// Stage 1 of a step, `element_forces`: per element, the GLMF loads
// (shared/prelude.wgsl: element_step, glmf_element) from the state of its two nodes,
// and with BENDING its bending shear (shared/step.wgsl: element_shear) from the
// states of up to four nodes.
// CPU twin: cpu::stepper element_pass.

// The share of the panels of screen-net knot `i` (shared/step.wgsl: screen_corner,
// screen_panel_share) from the states of this step, for the node pass (node_out).
fn screen_knot_force(i: u32, nd: NodeParams, k: u32) -> vec3<R> {
    let blk = blocks[nd.block];
    let co = screen_coefs_at(nd.screen_net);
    var f = vec3<R>(R(0.0), R(0.0), R(0.0));
    for (var q = 0u; q < 4u; q += 1u) {
        let a = screen_corner(i, nd.screen, q, 0u);
        let b = screen_corner(i, nd.screen, q, 1u);
        let c = screen_corner(i, nd.screen, q, 2u);
        let d = screen_corner(i, nd.screen, q, 3u);
        if a == NO_KNOT || b == NO_KNOT || c == NO_KNOT || d == NO_KNOT {
            continue;
        }
        f += screen_panel_share(co, blk, nd.current, state[a], state[b], state[c], state[d], screen_waves(a, b, c, d, k));
    }
    return f;
}

// Invocation `e` also stands for node `e` where that is a screen net's knot (the host
// dispatches over the nodes too when there are such knots): the node pass cannot form
// the panels' loads, as it would read neighbours' states while their invocations
// overwrite them.
@compute @workgroup_size(64)
fn element_forces(@builtin(global_invocation_id) gid: vec3<u32>) {
    let e = gid.x;
    if atomicLoad(&status.failed) != 0u {
        return;
    }
    if e < params.n_nodes && nodes[e].screen != NO_KNOT {
        node_out[e].force = vec4<R>(screen_knot_force(e, nodes[e], step.k), R(0.0));
    }
    if e >= params.n_elems {
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
