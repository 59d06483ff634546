// The fused kernel, `fused_steps`: one workgroup advances one block (a cable, or any
// connected component with at most FUSED_WG nodes and FUSED_WG elements) through the
// steps `step.k .. step.end` of a submission in one dispatch (all of them in still
// water; in waves the host cuts the submission at the cache's refresh steps and runs
// the refresh as its own `wave_refresh` dispatch before each piece: see below).
// Invocation `j` owns node
// `node_start + j` (its state in registers) and element `elem_start + j`; the node
// states its elements need and the element loads its nodes gather are exchanged
// through workgroup memory, with two barriers a step:
//   element: loads of element j from the published states of its two nodes (and
//            with BENDING its shear, from up to four: shared/step.wgsl element_shear);
//   barrier (with the blow-up flag of the previous step, read uniformly);
//   node: gather over node j's incidence list from the workgroup's loads, solve,
//         update, check, publish the new state;
//   barrier.
// The per-element and per-node arithmetic is that of the two-pass stages
// (shared/prelude.wgsl: element_step, gather_begin/gather_add/gather_end,
// node_advance, node_check), so the two paths agree to the last bit unless the
// compiler contracts differently. Global memory is read once per dispatch (state,
// parameters, the elements' internal states in elem_loads) and written once (state,
// those internal states), except current tables, routes and body rows,
// read per step. A blow-up stops the block at the failing step (its state stays there) and
// raises `status.failed` (see Status), after which later dispatches do nothing.
// FUSED_WG comes from the generated header.
//
// Why the refresh is not done in here: Mesa's llvmpipe (lavapipe, the software adapter
// the tests run on) counts the iterations of every loop of a shader invocation
// against one budget of 65535 (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS) and, once it
// is spent, ends each loop after its first iteration, silently. A refresh sums every
// wave component at a node (hundreds of iterations), so one invocation stepping a
// whole submission spent the budget after some twenty refreshes and computed wrong
// kinematics from then on. Without the refresh, an invocation's loops are the step
// loop, the incidence gathers and the current-profile and route-table searches; the
// host bounds the steps of one dispatch so that these stay within the budget
// (gpu::solver::fused_max_steps: a whole submission unless a current profile is long).

// A node state in workgroup memory (no vec3: 9 scalars, no padding).
struct WgState {
    hx: R,
    hy: R,
    hz: R,
    lx: R,
    ly: R,
    lz: R,
    vx: R,
    vy: R,
    vz: R,
}

// An element's loads in workgroup memory: ElemLoads less its internal state (which
// stays in the element's invocation), 9 scalars.
struct WgLoads {
    tx: R,
    ty: R,
    tz: R,
    tension: R,
    fx: R,
    fy: R,
    fz: R,
    half_mass: R,
    half_added: R,
}

var<workgroup> wg_state: array<WgState, FUSED_WG>;
var<workgroup> wg_loads: array<WgLoads, FUSED_WG>;
// Bending: element j's shear (shared/step.wgsl element_shear), FUSED_WG entries with
// BENDING, one unused entry without (BEND_WG from the generated header).
struct WgShear {
    x: R,
    y: R,
    z: R,
}
var<workgroup> wg_shear: array<WgShear, BEND_WG>;
// Set (atomically, any invocation) when a node of the block fails this step.
var<workgroup> wg_fail: atomic<u32>;
// Stop flag, written by invocation 0 and read with workgroupUniformLoad.
var<workgroup> wg_stop: u32;

fn wg_pack(s: NodeState) -> WgState {
    return WgState(s.r_hi.x, s.r_hi.y, s.r_hi.z, s.r_lo.x, s.r_lo.y, s.r_lo.z, s.v.x, s.v.y, s.v.z);
}

fn wg_pack_loads(l: ElemLoads) -> WgLoads {
    return WgLoads(l.tx, l.ty, l.tz, l.tension, l.fx, l.fy, l.fz, l.half_mass, l.half_added);
}

fn wg_unpack_loads(w: WgLoads) -> ElemLoads {
    return ElemLoads(w.tx, w.ty, w.tz, w.tension, w.fx, w.fy, w.fz, w.half_mass, w.half_added, R(0.0));
}

fn wg_unpack(w: WgState) -> NodeState {
    return NodeState(
        vec4<R>(w.hx, w.hy, w.hz, R(0.0)),
        vec4<R>(w.lx, w.ly, w.lz, R(0.0)),
        vec4<R>(w.vx, w.vy, w.vz, R(0.0)),
    );
}

// The share of the panels of screen-net knot `i` of block `blk` from the published
// states (element_forces.wgsl: screen_knot_force, from workgroup memory).
fn screen_knot_force_wg(i: u32, nd: NodeParams, blk: BlockParams, k: u32) -> vec3<R> {
    let co = screen_coefs_at(nd.screen_net);
    let n0 = blk.node_start;
    var f = vec3<R>(R(0.0), R(0.0), R(0.0));
    for (var q = 0u; q < 4u; q += 1u) {
        let a = screen_corner(i, nd.screen, q, 0u);
        let b = screen_corner(i, nd.screen, q, 1u);
        let c = screen_corner(i, nd.screen, q, 2u);
        let d = screen_corner(i, nd.screen, q, 3u);
        if a == NO_KNOT || b == NO_KNOT || c == NO_KNOT || d == NO_KNOT {
            continue;
        }
        f += screen_panel_share(co, blk, nd.current, wg_unpack(wg_state[a - n0]), wg_unpack(wg_state[b - n0]),
            wg_unpack(wg_state[c - n0]), wg_unpack(wg_state[d - n0]), screen_waves(a, b, c, d, k));
    }
    return f;
}

@compute @workgroup_size(FUSED_WG)
fn fused_steps(@builtin(workgroup_id) wid: vec3<u32>, @builtin(local_invocation_index) j: u32) {
    let b = wid.x;
    let blk = blocks[b];
    let nn = blk.node_end - blk.node_start;
    let ne = blk.elem_end - blk.elem_start;
    let has_node = j < nn;
    let has_elem = j < ne;
    let i = blk.node_start + j;
    let e = blk.elem_start + j;
    if j == 0u {
        // A blow-up in an earlier dispatch stops every block.
        wg_stop = atomicLoad(&status.failed);
        atomicStore(&wg_fail, 0u);
    }
    var nd: NodeParams;
    var s: NodeState;
    if has_node {
        nd = nodes[i];
        s = state[i];
        wg_state[j] = wg_pack(s);
    }
    var ep: ElemParams;
    var hr: ElemParams;
    var lp: LineParams;
    var oz = R(0.0);
    var la = 0u;
    var lb = 0u;
    // Bending: the far nodes of the hinges at the element's two ends (its own nodes
    // where there is none).
    var lp_a = 0u;
    var lp_b = 0u;
    // The element's internal state (viscoelastic lines), in a register for the dispatch.
    var xv = R(0.0);
    if has_elem {
        xv = elem_loads[e].visco;
        ep = elems[e];
        lp = lines[ep.line];
        oz = blocks[ep.block].oz;
        la = ep.a - blk.node_start;
        lb = ep.b - blk.node_start;
        if BENDING {
            hr = elems[params.n_elems + e];
            lp_a = hinge_node(hr.a, ep.a) - blk.node_start;
            lp_b = hinge_node(hr.b, ep.b) - blk.node_start;
        }
    }
    // The block's sea's rows at the dispatch's first step (read once: whether the sea
    // has waves and the rows between bands are the same at every step; wave_sea_rows).
    var sr = SeaRows(0u, 0u, 0u, 0u, false);
    if WAVES {
        sr = wave_sea_rows(blk.wave_rows, step.k);
    }
    if workgroupUniformLoad(&wg_stop) != 0u {
        return;
    }
    for (var k = step.k; k < step.end; k += 1u) {
        if has_elem {
            sr.r = blk.wave_rows + k;
            let sa = wg_unpack(wg_state[la]);
            let sb = wg_unpack(wg_state[lb]);
            let el = element_step(e, ep, lp, oz, sa, sb, k, sr, xv);
            xv = el.visco;
            wg_loads[j] = wg_pack_loads(el);
            if BENDING {
                let sh = element_shear(hr, wg_unpack(wg_state[lp_a]), sa, sb, wg_unpack(wg_state[lp_b]));
                wg_shear[j] = WgShear(sh.x, sh.y, sh.z);
            }
        }
        // A screen net's knot: its panels' share, from the states this step starts from.
        var fs = vec3<R>(R(0.0), R(0.0), R(0.0));
        if has_node && nd.screen != NO_KNOT {
            fs = screen_knot_force_wg(i, nd, blk, k);
        }
        if j == 0u {
            wg_stop = atomicLoad(&wg_fail);
        }
        // Loads ready, states read; stop after a failed step (its state is kept).
        if workgroupUniformLoad(&wg_stop) != 0u {
            break;
        }
        if has_node {
            let w = point_waves(i, nd, k);
            var nf = gather_begin(nd, s, blk, w);
            for (var q = nd.inc_start; q < nd.inc_end; q += 1u) {
                let entry = inc[q];
                let le = (entry >> 1u) - blk.elem_start;
                var sh = vec3<R>(R(0.0), R(0.0), R(0.0));
                if BENDING {
                    sh = vec3<R>(wg_shear[le].x, wg_shear[le].y, wg_shear[le].z);
                }
                nf = gather_add(nf, wg_unpack_loads(wg_loads[le]), sh, entry);
            }
            nf.f += fs;
            nf = gather_end(i, nd, s, nf, blk, k, w);
            free_lump_store(i, nd, nf);
            s = node_advance(nd, s, nf, R(k) * params.dt, k);
            wg_state[j] = wg_pack(s);
            let what = node_check(blk, s);
            if what != 0u && atomicExchange(&wg_fail, 1u) == 0u {
                // Earliest step first, then lowest block (see Status).
                atomicMax(&status.failed, FUSED_FAILED | ((0x7fffu - k) << 16u) | (0xffffu - b));
                atomicMax(&status.step, params.step_base);
            }
        }
        workgroupBarrier();
    }
    if has_node {
        state[i] = s;
    }
    if has_elem {
        elem_loads[e].visco = xv;
    }
}
