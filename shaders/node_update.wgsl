// Stage 2 of a step, `node_update`: per node, gather the element loads over the
// incidence list, add point-mass and seabed loads, solve the 3x3 mass block (or take
// the route's Baumgarte acceleration), and advance by symplectic Euler:
// v += a dt; r += v dt (r kept as a compensated pair) (shared/prelude.wgsl:
// gather_node, node_advance, node_check).
// CPU twin: cpu::stepper node_accel and the Symplectic arm of advance_block_in.
//
// `node_evaluate` is the same gather without the update, for output: per node force
// and acceleration, per constraint the reaction `F_k - M_k a_k`.

@compute @workgroup_size(64)
fn node_update(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= params.n_nodes || atomicLoad(&status.failed) != 0u {
        return;
    }
    let nd = nodes[i];
    let s = state[i];
    let tau = R(step.k) * params.dt;
    let nf = gather_node(i, nd, s, step.k);
    free_lump_store(i, nd, nf);
    let sn = node_advance(nd, s, nf, tau, step.k);
    state[i] = sn;
    let what = node_check(blocks[nd.block], sn);
    if what != 0u {
        // The first node to fail in a submission reports; the passes of later steps see
        // the flag and do nothing, so the state stays at the blow-up.
        if atomicExchange(&status.failed, 1u) == 0u {
            atomicStore(&status.step, params.step_base + step.k);
            status.node = i;
            status.what = what;
        }
    }
}

@compute @workgroup_size(64)
fn node_evaluate(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= params.n_nodes {
        return;
    }
    let nd = nodes[i];
    let s = state[i];
    let tau = R(step.k) * params.dt;
    let nf = gather_node(i, nd, s, step.k);
    let a = node_accel(nd, s, nf, tau, step.k);
    node_out[i] = NodeOut(vec4<R>(nf.f, R(0.0)), vec4<R>(a, R(0.0)));
    if node_held(nd.constraint) {
        reactions[nd.constraint] = vec4<R>(nf.f - sym3_mul(nf.m, a), R(0.0));
    } else if nd.constraint != NO_CONSTRAINT {
        // Released by a line failure: no reaction (as on the CPU path), still released.
        reactions[nd.constraint] = vec4<R>(R(0.0), R(0.0), R(0.0), R(1.0));
    }
}

// The waves' refresh, dispatched by the host before the element pass of a step whose
// WaveStep row has `refresh` set, in three passes. First, per node, the band
// decision, the t1 -> t0 copy and the node's evaluations put on the work list
// (shared/waves.wgsl: wave_refresh_node) at its absolute position.
@compute @workgroup_size(64)
fn wave_refresh(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= params.n_nodes {
        return;
    }
    let s = state[i];
    let blk = blocks[nodes[i].block];
    wave_refresh_node(i, step.k, vec3<R>(blk.ox, blk.oy, blk.oz) + (s.r_hi.xyz + s.r_lo.xyz), s.v.xyz);
}

// Second, per entry of the work list (dispatched over two per node, the most a list
// holds; those past its length return at once), the evaluation
// (shared/waves.wgsl: wave_refresh_due).
@compute @workgroup_size(64)
fn wave_refresh_due(@builtin(global_invocation_id) gid: vec3<u32>) {
    wave_refresh_due_entry(gid.x, step.k);
}

// Third, per element, its midpoint cache entry formed again from its nodes' new
// values where one of them refreshed (shared/waves.wgsl: wave_elem_form). The work
// list is emptied here, after the second pass read its length (every dispatch of a
// pass sees the previous one's writes).
@compute @workgroup_size(64)
fn wave_refresh_elems(@builtin(global_invocation_id) gid: vec3<u32>) {
    let e = gid.x;
    if e == 0u {
        atomicStore(&status.refresh_due, 0u);
    }
    if e >= params.n_elems {
        return;
    }
    wave_elem_form(e, step.k);
}

// Free and pinned bodies, after the node pass of a step: one invocation per body
// (shared/free_body.wgsl: free_body_step).
@compute @workgroup_size(64)
fn free_bodies(@builtin(global_invocation_id) gid: vec3<u32>) {
    let b = gid.x;
    if b >= params.n_free || atomicLoad(&status.failed) != 0u {
        return;
    }
    free_body_step(b, step.k);
}

// Line failures, after the bodies of a step: one invocation per failure
// (shared/free_body.wgsl: line_failure_check).
@compute @workgroup_size(64)
fn line_failures(@builtin(global_invocation_id) gid: vec3<u32>) {
    let f = gid.x;
    if f >= params.n_fail || atomicLoad(&status.failed) != 0u {
        return;
    }
    line_failure_check(f, step.k);
}
