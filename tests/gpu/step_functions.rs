//! The WGSL functions of a step's element and node passes against their Rust twins, on
//! random inputs, at f32 and f64: the variable element of a winch cable
//! (`variable_element`), the node's gather over its incidence list (`gather_node`:
//! `gather_begin`, `gather_add`, `gather_end`), the symplectic Euler update
//! (`node_advance`, through `node_accel`) and the blow-up check (`node_check`).
//!
//! As in `functions`, a test kernel calls one prelude function per invocation and the
//! Rust side runs in f64 on the very inputs the GPU received. The Rust twins are the
//! CPU stepper's: `ale::mass_flow_forces`, `physics::seabed_force`, `Sym3`,
//! `Current::at`, `Route::eval`, and the few lines of the stepper that compose them
//! (`cpu::stepper` `element_pass`, `node_accel_of`, `check` and the symplectic arm of
//! `advance_block_in`, which are private), written out below as the stepper has them.
//! Contract: every output within `16 eps_R * scale`, `scale` the sum of the magnitudes
//! of the terms that make the output (plus, where stated, what rounding an input that
//! the shader forms itself costs), so a missing, doubled or wrong-signed term, of the
//! size of its own magnitude, fails.

use super::common::*;
use super::functions::{run_kernels, rv, to_r, Worst};
use cablesim::gpu::layout::*;
use cablesim::gpu::solver::rebased_route;
use cablesim::gpu::{GpuContext, Precision};
use cablesim::math::{Sym3, V3};
use cablesim::model::{Current, Route};
use cablesim::physics::{seabed_damping, seabed_force, SeabedCoefs};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod node_update;
use node_update::*;

const KERNELS: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

fn v3in(k: u32) -> vec3<R> {
    return vec3<R>(tin[k], tin[k + 1u], tin[k + 2u]);
}

fn v3out(k: u32, v: vec3<R>) {
    tout[k] = v.x;
    tout[k + 1u] = v.y;
    tout[k + 2u] = v.z;
}

fn state_in(k: u32) -> NodeState {
    return NodeState(vec4<R>(v3in(k), R(0.0)), vec4<R>(v3in(k + 3u), R(0.0)), vec4<R>(v3in(k + 6u), R(0.0)));
}

// Element 2i + 0 of nodes 2i (a) and 2i + 1 (b); the winch node is b when the flag is 1.
@compute @workgroup_size(64)
fn t_variable(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 23u {
        return;
    }
    let b = i * 23u;
    // (The water-acceleration load and the added masses, tangential or not, are not
    // read here.)
    let lp = LineParams(tin[b], tin[b + 1u], tin[b + 2u], tin[b + 3u], tin[b + 4u], R(0.0),
        tin[b + 5u], tin[b + 6u], R(0.0), tin[b + 7u], tin[b + 8u], R(0.0), R(0.0), R(0.0), R(0.0), R(0.0));
    let ep = ElemParams(2u * i, 2u * i + 1u, 0u, 0u, 0u, u32(tin[b + 22u]), tin[b + 18u], R(0.0), R(0.0)); // l0_lo, diameter: unused here
    let py = Payout(tin[b + 18u], R(0.0), tin[b + 19u], tin[b + 20u], R(0.0));
    let ten = variable_element(ep, lp, py, v3in(b + 9u), v3in(b + 12u), v3in(b + 15u), tin[b + 21u]);
    let o = i * 7u;
    tout[o] = ten;
    v3out(o + 1u, node_out[2u * i].force.xyz);
    v3out(o + 4u, node_out[2u * i + 1u].force.xyz);
}

@compute @workgroup_size(64)
fn t_gather(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= params.n_nodes {
        return;
    }
    let b = i * 10u;
    let nf = gather_node(i, nodes[i], state_in(b), u32(tin[b + 9u]));
    let o = i * 12u;
    v3out(o + 9u, nf.c);
    v3out(o, nf.f);
    tout[o + 3u] = nf.m.xx;
    tout[o + 4u] = nf.m.yy;
    tout[o + 5u] = nf.m.zz;
    tout[o + 6u] = nf.m.xy;
    tout[o + 7u] = nf.m.xz;
    tout[o + 8u] = nf.m.yz;
}

@compute @workgroup_size(64)
fn t_advance(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= params.n_nodes {
        return;
    }
    let b = i * 22u;
    let m = Sym3(tin[b + 12u], tin[b + 13u], tin[b + 14u], tin[b + 15u], tin[b + 16u], tin[b + 17u]);
    let sn = node_advance(nodes[i], state_in(b), NodeForce(v3in(b + 9u), m, v3in(b + 19u), vec4<R>(R(0.0))), tin[b + 18u], 0u); // step 0 of a submission: no body rows here
    let o = i * 9u;
    v3out(o, sn.r_hi.xyz);
    v3out(o + 3u, sn.r_lo.xyz);
    v3out(o + 6u, sn.v.xyz);
}

@compute @workgroup_size(64)
fn t_check(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 12u {
        return;
    }
    let b = i * 12u;
    let blk = BlockParams(tin[b], tin[b + 1u], tin[b + 2u], R(0.0), 0u, 0u, 0u, 0u, 0u, 0u);
    tout[i] = R(node_check(blk, state_in(b + 3u)));
}
"#;

fn run<R: GpuReal>(
    ctx: &GpuContext,
    p: Precision,
    entry: &str,
    group0: &[(u32, Vec<u8>)],
    input: &[R],
    n_threads: usize,
    n_out: usize,
) -> Vec<f64> {
    run_kernels(ctx, p, KERNELS, entry, group0, input, n_threads, n_out)
        .iter()
        .map(|x| x.f64())
        .collect()
}

fn bytes<T: bytemuck::Pod>(x: &[T]) -> Vec<u8> {
    bytemuck::cast_slice(x).to_vec()
}

fn v3(a: &[f64]) -> V3<f64> {
    V3::new(a[0], a[1], a[2])
}

/// A random unit vector.
fn unit(rng: &mut ChaCha8Rng) -> V3<f64> {
    loop {
        let v = v3(&rv(rng, 1.0));
        if v.norm() > 0.1 && v.norm() <= 1.0 {
            return v / v.norm();
        }
    }
}

/// `x` as a compensated pair of `R` (hi, lo) and their exact sum in f64.
fn pair<R: GpuReal>(x: f64) -> (R, R, f64) {
    let hi = R::c(x);
    let lo = R::c(x - hi.f64());
    (hi, lo, hi.f64() + lo.f64())
}

/// A node state relative to its block origin: `r` split into compensated pairs, `v`;
/// the row as `R` and, in f64, what the GPU got (`r_hi + r_lo` exact, `v`).
fn state_row<R: GpuReal>(r: V3<f64>, v: V3<f64>) -> (Vec<R>, V3<f64>, V3<f64>) {
    let (mut hi, mut lo, mut sum) = (Vec::new(), Vec::new(), [0.0; 3]);
    for (k, x) in [r.x, r.y, r.z].into_iter().enumerate() {
        let (h, l, s) = pair::<R>(x);
        hi.push(h);
        lo.push(l);
        sum[k] = s;
    }
    let vr: Vec<R> = [v.x, v.y, v.z].iter().map(|&x| R::c(x)).collect();
    let vb = v3(&vr.iter().map(|x| x.f64()).collect::<Vec<_>>());
    let mut row = hi;
    row.extend(lo);
    row.extend(vr);
    (row, v3(&sum), vb)
}

/// `variable_element`: the variable element's tension loses `EA c l Ldot / l0^2` while
/// paying out or hauling in (the internal damping acts on the material strain rate),
/// and its two nodes get the mass-flow forces of Eq. 39 (`ale::mass_flow_forces`),
/// winch node at either end, with the payout rate and acceleration each zero or not.
fn check_variable<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 800;
    let mut x = Vec::new();
    for i in 0..n {
        let ea = 10f64.powf(rng.gen_range(5.0..9.0));
        x.extend([
            ea,
            ea * rng.gen_range(0.0..1e-2),
            rng.gen_range(0.0..30.0),
            rng.gen_range(0.0..3.0),
            rng.gen_range(0.0..5.0),
            rng.gen_range(0.1..100.0),
            rng.gen_range(0.0..5.0),
            rng.gen_range(-500.0..50.0),
            0.0,
        ]);
        // A variable element between half and one and a half nominal lengths.
        let l0 = rng.gen_range(0.2..6.0);
        let d = unit(rng) * (l0 * (1.0 + rng.gen_range(-0.01..0.01)));
        x.extend(d.to_f64());
        x.extend(rv(rng, 2.0));
        x.extend(rv(rng, 2.0));
        x.push(l0);
        let (rate, accel) = match i % 4 {
            0 => (0.0, 0.0),
            1 => (rng.gen_range(-3.0..3.0), 0.0),
            2 => (0.0, rng.gen_range(-2.0..2.0)),
            _ => (rng.gen_range(-3.0..3.0), rng.gen_range(-2.0..2.0)),
        };
        x.extend([rate, accel, rng.gen_range(0.0..1e5), ((i / 4) % 2) as f64]);
    }
    let (xr, x) = to_r::<R>(&x);
    let node_out = vec![NodeOut::<R>::default(); 2 * n];
    let out = run(
        ctx,
        p,
        "t_variable",
        &[(12, bytes(&node_out))],
        &xr,
        n,
        7 * n,
    );
    let mut w = Worst::new::<R>("variable_element");
    let mut moving = 0;
    for i in 0..n {
        let a = &x[23 * i..23 * (i + 1)];
        let (ea_c, mbar) = (a[1], a[5]);
        let (d, va, vb) = (v3(&a[9..12]), v3(&a[12..15]), v3(&a[15..18]));
        let (l0, rate, accel, tension) = (a[18], a[19], a[20], a[21]);
        let w_is_b = a[22] == 1.0;
        let l = d.norm();
        // cpu::stepper element_pass.
        let damping = if rate != 0.0 {
            ea_c * l * rate / (l0 * l0)
        } else {
            0.0
        };
        w.check(
            "tension",
            i,
            out[7 * i],
            tension - damping,
            tension + damping.abs(),
        );
        // cpu::stepper node_accel: r_w - r_m and v_w - v_m from the element's ends.
        let zero = V3::zero();
        let (rm, rw, vm, vw) = if w_is_b {
            (zero, d, va, vb)
        } else {
            (d, zero, vb, va)
        };
        let (fm, fw) = if rate != 0.0 || accel != 0.0 {
            moving += 1;
            cablesim::ale::mass_flow_forces(mbar, l0, rate, accel, rm, rw, vm, vw)
        } else {
            (zero, zero)
        };
        let g = 2.0 * rate.abs() / l0 * (vw - vm).norm()
            + (2.0 * rate * rate / l0 + accel.abs()) / l0 * d.norm();
        let (fa, fb, sa, sb) = if w_is_b {
            (fm, fw, mbar * l0 * g / 6.0, mbar * l0 * g / 3.0)
        } else {
            (fw, fm, mbar * l0 * g / 3.0, mbar * l0 * g / 6.0)
        };
        w.v(
            "force on a",
            i,
            &out[7 * i + 1..7 * i + 4],
            fa,
            sa.max(f64::MIN_POSITIVE),
        );
        w.v(
            "force on b",
            i,
            &out[7 * i + 4..7 * i + 7],
            fb,
            sb.max(f64::MIN_POSITIVE),
        );
    }
    assert!(moving >= 3 * n / 4 - 1);
    w.report(p);
}

/// The run constants the node kernels read.
fn run_params<R: GpuReal>(
    n_nodes: usize,
    n_winch: usize,
    dt: f64,
    sb: &SeabedCoefs<f64>,
) -> Vec<u8> {
    let q = Params::<R> {
        n_nodes: n_nodes as u32,
        seabed: 1,
        n_winch: n_winch as u32,
        dt: R::c(dt),
        alpha: R::c(400.0),
        beta: R::c(40.0),
        max_speed: R::c(100.0),
        max_distance: R::c(1e4),
        seabed_k: R::c(sb.k),
        seabed_c: R::c(sb.c),
        seabed_mu: R::c(sb.mu),
        seabed_v_eps: R::c(sb.v_eps),
        seabed_mu_axial: R::c(sb.mu_axial),
        one: R::c(1.0),
        ..Default::default()
    };
    bytes(std::slice::from_ref(&q))
}

/// The current profiles of the gather test and their buffers (values exact in `R`).
fn currents<R: GpuReal>() -> (Vec<Current>, Vec<CurrentPoint<R>>, Vec<CurrentRange>) {
    let r = |x: f64| R::c(x).f64();
    let profiles = vec![
        Current::uniform([r(0.3), r(-0.2), r(0.05)]),
        Current {
            table: vec![
                (r(-100.0), [r(0.1), r(0.0), r(0.0)]),
                (r(-50.0), [r(0.4), r(0.2), r(0.0)]),
                (r(0.0), [r(0.8), r(0.3), r(0.0)]),
            ],
        },
    ];
    let (mut pts, mut ranges) = (Vec::new(), Vec::new());
    for c in &profiles {
        ranges.push(CurrentRange {
            start: pts.len() as u32,
            len: c.table.len() as u32,
        });
        for (z, u) in &c.table {
            pts.push(CurrentPoint::<R> {
                z: R::c(*z),
                ux: R::c(u[0]),
                uy: R::c(u[1]),
                uz: R::c(u[2]),
            });
        }
    }
    (profiles, pts, ranges)
}

/// `gather_node`: a node's force and mass block gathered over its incidence list (the
/// layout's CSR `inc[inc_start..inc_end]`, entries `element * 2 + side`, the tension
/// pulling side a towards b), point weight, mass and drag in the current, a winch
/// node's tributary change and mass-flow force, seabed contact with friction. Random
/// nodes of 0 to 6 entries into a shared pool of element loads, in three blocks of
/// different origins, about half of them touching the seabed.
fn check_gather<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 600;
    let n_loads = 400;
    let (n_winch, rows) = (5usize, 3usize);
    let r = |x: f64| R::c(x).f64();
    let sb = SeabedCoefs {
        z: 0.0,
        k: r(3e6),
        c: r(3e4),
        mu: r(0.6),
        mu_axial: r(0.6),
        v_eps: r(0.01),
    };
    let (profiles, pts, ranges) = currents::<R>();
    // Block origins (whole metres) and seabed heights relative to them (depth 60 m).
    let origin = [
        [0.0, 0.0, -20.0],
        [500.0, -300.0, -55.0],
        [-80.0, 40.0, 0.0],
    ];
    let blocks: Vec<BlockParams<R>> = origin
        .iter()
        .map(|o| BlockParams::<R> {
            ox: R::c(o[0]),
            oy: R::c(o[1]),
            oz: R::c(o[2]),
            zb: R::c(-60.0 - o[2]),
            ..Default::default()
        })
        .collect();
    let loads: Vec<ElemLoads<R>> = (0..n_loads)
        .map(|_| {
            let t = unit(rng);
            let f = rv(rng, 100.0);
            ElemLoads::<R> {
                tx: R::c(t.x),
                ty: R::c(t.y),
                tz: R::c(t.z),
                tension: R::c(rng.gen_range(-1e3..1e5)),
                fx: R::c(f[0]),
                fy: R::c(f[1]),
                fz: R::c(f[2]),
                half_mass: R::c(rng.gen_range(0.5..50.0)),
                visco: R::c(0.0),
                half_added: R::c(rng.gen_range(0.0..50.0)),
            }
        })
        .collect();
    let payout: Vec<Payout<R>> = (0..rows * n_winch)
        .map(|j| {
            // Every third row still (no mass-flow force, only the tributary change).
            let still = j % 3 == 0;
            Payout::<R> {
                trib: R::c(rng.gen_range(-0.5..0.5)),
                rate: R::c(if still { 0.0 } else { rng.gen_range(-3.0..3.0) }),
                accel: R::c(if still || j % 3 == 1 {
                    0.0
                } else {
                    rng.gen_range(-2.0..2.0)
                }),
                ..Default::default()
            }
        })
        .collect();
    let node_out: Vec<NodeOut<R>> = (0..n)
        .map(|_| {
            let f = rv(rng, 50.0);
            NodeOut::<R> {
                force: [R::c(f[0]), R::c(f[1]), R::c(f[2]), R::c(0.0)],
                ..Default::default()
            }
        })
        .collect();
    let (mut nodes, mut inc, mut x) = (Vec::new(), Vec::new(), Vec::new());
    let mut states = Vec::new();
    for i in 0..n {
        let start = inc.len() as u32;
        for _ in 0..i % 7 {
            inc.push(rng.gen_range(0..n_loads as u32) * 2 + rng.gen_range(0..2u32));
        }
        let block = i % 3;
        let nd = NodeParams::<R> {
            // No displaced volume: the point's share above the water changes nothing here
            // (tests/gpu/surface.rs covers the surface terms).
            point_added: R::c(0.0),
            point_displaced: R::c(0.0),
            point_radius: R::c(0.0),
            inc_start: start,
            inc_end: inc.len() as u32,
            constraint: u32::MAX,
            block: block as u32,
            current: (i % 2) as u32,
            screen: u32::MAX,
            screen_net: u32::MAX,
            winch: if i % 4 == 1 {
                rng.gen_range(0..n_winch as u32)
            } else {
                u32::MAX
            },
            point_mass: R::c(if i % 3 == 0 {
                rng.gen_range(0.0..500.0)
            } else {
                0.0
            }),
            point_weight_z: R::c(if i % 5 < 2 {
                rng.gen_range(-2000.0..500.0)
            } else {
                0.0
            }),
            point_drag: R::c(if i % 5 == 1 || i % 5 == 2 {
                rng.gen_range(0.0..300.0)
            } else {
                0.0
            }),
            tributary: R::c(rng.gen_range(0.5..5.0)),
        };
        nodes.push(nd);
        // Half the nodes (the winch nodes among them) within 0.1 m of the seabed (into
        // it or just above), the rest anywhere in the water column; creeping (below
        // v_eps) or sliding.
        let zb = -60.0 - origin[block][2];
        let z = if i % 4 < 2 {
            zb + rng.gen_range(-0.1..0.1)
        } else {
            rng.gen_range(zb..-origin[block][2])
        };
        let rr = V3::new(rng.gen_range(-50.0..50.0), rng.gen_range(-50.0..50.0), z);
        let v = v3(&rv(rng, if i % 6 < 2 { 0.005 } else { 1.0 }));
        let (row, rg, vg) = state_row::<R>(rr, v);
        x.extend(row);
        let k = rng.gen_range(0..rows);
        x.push(R::c(k as f64));
        states.push((rg, vg, k));
    }
    let group0 = [
        (0, run_params::<R>(n, n_winch, 1e-3, &sb)),
        (4, bytes(&nodes)),
        (5, bytes(&inc)),
        (7, bytes(&blocks)),
        (8, bytes(&pts)),
        (9, bytes(&ranges)),
        (11, bytes(&loads)),
        (12, bytes(&node_out)),
        (16, bytes(&payout)),
        // Still water: the waves' rows say no components (the cache is not read).
        (19, bytes(&[R::c(0.0)])),
        (20, bytes(&vec![WaveStep::<R>::default(); rows])),
    ];
    let out = run(ctx, p, "t_gather", &group0, &x, n, 12 * n);
    let mut w = Worst::new::<R>("gather_node (gather_begin, gather_add, gather_end)");
    let v3r = |a: [R; 4]| V3::new(a[0].f64(), a[1].f64(), a[2].f64());
    let (mut contact, mut drag, mut flow) = (0, 0, 0);
    for (i, (nd, &(ri, vi, k))) in nodes.iter().zip(&states).enumerate() {
        // cpu::stepper node_accel_of and node_accel, in the same order.
        let mut f = V3::new(0.0, 0.0, nd.point_weight_z.f64());
        let mut m = Sym3::scalar(nd.point_mass.f64());
        let mut f_scale = nd.point_weight_z.f64().abs();
        let mut m_scale = nd.point_mass.f64();
        for &entry in &inc[nd.inc_start as usize..nd.inc_end as usize] {
            let el = &loads[(entry >> 1) as usize];
            let sign = if entry & 1 == 0 { 1.0 } else { -1.0 };
            let t = V3::new(el.tx.f64(), el.ty.f64(), el.tz.f64());
            let fh = V3::new(el.fx.f64(), el.fy.f64(), el.fz.f64());
            f += fh + t * (sign * el.tension.f64());
            let (hm, ha) = (el.half_mass.f64(), el.half_added.f64());
            m.xx += hm;
            m.yy += hm;
            m.zz += hm;
            m.add_normal_projection(ha, t);
            f_scale += fh.norm() + el.tension.f64().abs();
            m_scale += hm + ha;
        }
        let blk = &blocks[nd.block as usize];
        let pd = nd.point_drag.f64();
        if pd > 0.0 {
            drag += 1;
            let z = blk.oz.f64() + ri.z;
            let u = profiles[nd.current as usize].at::<f64>(z);
            let vr = u - vi;
            f += vr * (pd * vr.norm());
            // The current's own rounding (`functions`: 1 + 0.01 |z|), doubled by the
            // quadratic law.
            let s = u.norm() + vi.norm();
            f_scale += pd * s * (s + 2.0 * (1.0 + 0.01 * z.abs()));
        }
        let mut trib = nd.tributary.f64();
        if nd.winch != u32::MAX {
            let py = &payout[k * n_winch + nd.winch as usize];
            trib += py.trib.f64();
            if py.rate.f64() != 0.0 || py.accel.f64() != 0.0 {
                flow += 1;
                let fo = v3r(node_out[i].force);
                f += fo;
                f_scale += fo.norm();
            }
        }
        // Contact relative to the block origin, as the shader forms it: near the
        // seabed `zb - r_hi` is exact (Sterbenz), so `pen` rounds only with itself.
        let zb = blk.zb.f64();
        let sbi = SeabedCoefs { z: zb, ..sb };
        let fs = seabed_force(&sbi, trib, ri, vi);
        if fs.norm() > 0.0 {
            contact += 1;
        }
        f += fs;
        f_scale += sb.k * trib * (zb - ri.z).abs() * (1.0 + sb.mu) + sb.c * trib * vi.z.abs();
        // The damping slopes node_advance takes implicitly (physics::seabed_damping).
        let cd = seabed_damping(&sbi, trib, ri, vi);
        let c_scale = sb.c * trib + sb.mu * sb.k * trib * (zb - ri.z).abs() / sb.v_eps;
        let o = &out[12 * i..12 * i + 12];
        w.v("damping", i, &o[9..12], cd, c_scale.max(f64::MIN_POSITIVE));
        w.v("force", i, &o[0..3], f, f_scale.max(f64::MIN_POSITIVE));
        for (q, r) in [m.xx, m.yy, m.zz, m.xy, m.xz, m.yz].into_iter().enumerate() {
            w.check("mass", i, o[3 + q], r, m_scale.max(f64::MIN_POSITIVE));
        }
    }
    // The cases the test is for happened.
    assert!(
        contact > n / 5 && drag > n / 5 && flow > n / 40,
        "{contact} {drag} {flow}"
    );
    w.report(p);
}

fn check_all<R: GpuReal>(ctx: &GpuContext, p: Precision) {
    let mut rng = ChaCha8Rng::seed_from_u64(20261201);
    check_variable::<R>(ctx, p, &mut rng);
    check_gather::<R>(ctx, p, &mut rng);
    check_advance::<R>(ctx, p, &mut rng);
    check_node_check::<R>(ctx, p, &mut rng);
}

#[test]
fn wgsl_step_functions_match_their_rust_twins_in_f32() {
    let Some(ctx) = gpu_context("wgsl_step_functions_match_their_rust_twins_in_f32", false) else {
        return;
    };
    check_all::<f32>(&ctx, Precision::F32);
}

#[test]
fn wgsl_step_functions_match_their_rust_twins_in_f64() {
    let Some(ctx) = gpu_context("wgsl_step_functions_match_their_rust_twins_in_f64", true) else {
        return;
    };
    check_all::<f64>(&ctx, Precision::F64);
}
