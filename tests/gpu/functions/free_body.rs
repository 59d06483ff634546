//! `free_body_accelerations` (shaders/shared/free_body.wgsl) against its Rust twin
//! `body::free::FreeBody::accelerations`, on random free and pinned bodies: inertia
//! with products, centre of gravity and buoyancy off the reference point, waterplane
//! heave and tilt, full added mass, linear damping, quadratic drag on a current,
//! constant loads, two lumped held nodes each, in random states (turned, moving,
//! spinning). The body's record is built here as the GPU path's host builds it
//! (`gpu::host::free_records`: state relative to the initial reference point, the
//! centre of gravity's displacement as a compensated pair). Contract: every
//! acceleration within `tol (|a| + |alpha| L + 1)` of the twin's, `L` the body's size
//! (about 1 m here), with `tol` 1e-10 in f64 (round-off of the differently ordered
//! 6x6 assembly and Cholesky solve of a mass matrix of condition number below 1e3)
//! and 2e-3 in f32.

use super::*;
use cablesim::body::free::{Fluid, FreeBody, FreeKind, FreeSpec, Lump, Pin};
use cablesim::body::MeanPose;

const KERNEL: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

@compute @workgroup_size(64)
fn t_free_acc(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= params.n_free {
        return;
    }
    let o = params.free_at + i * FREE_STRIDE;
    let b = i * 12u;
    var pin: BodyRow;
    pin.dx = tin[b];
    pin.dy = tin[b + 1u];
    pin.dz = tin[b + 2u];
    pin.ax = tin[b + 6u];
    pin.ay = tin[b + 7u];
    pin.az = tin[b + 8u];
    let u = vec3<R>(tin[b + 9u], tin[b + 10u], tin[b + 11u]);
    let a = free_body_accelerations(o, free_state(o), pin, u);
    let q = i * 6u;
    tout[q] = a[0].x;
    tout[q + 1u] = a[0].y;
    tout[q + 2u] = a[0].z;
    tout[q + 3u] = a[1].x;
    tout[q + 4u] = a[1].y;
    tout[q + 5u] = a[1].z;
}
"#;

const FREE_STRIDE: usize = 168;

fn sym3(rng: &mut ChaCha8Rng, diag: std::ops::Range<f64>, off: f64) -> [[f64; 3]; 3] {
    let d = rv(rng, 1.0).map(|x| diag.start + (x + 1.0) * 0.5 * (diag.end - diag.start));
    let o = rv(rng, off);
    [[d[0], o[0], o[1]], [o[0], d[1], o[2]], [o[1], o[2], d[2]]]
}

fn check<R: GpuReal>(ctx: &GpuContext, p: Precision) {
    let mut rng = ChaCha8Rng::seed_from_u64(34);
    let n = 96;
    let fluid = Fluid {
        rho: 1025.0,
        g: 9.81,
    };
    let mut rec: Vec<f64> = vec![0.0; n * FREE_STRIDE];
    let mut lists: Vec<f64> = Vec::new();
    let list_at = n * FREE_STRIDE;
    let mut routes: Vec<RouteParams<R>> = Vec::new();
    let mut states: Vec<NodeState<R>> = Vec::new();
    let mut outs: Vec<NodeOut<R>> = Vec::new();
    let mut reactions: Vec<[R; 4]> = Vec::new();
    let mut tin: Vec<f64> = Vec::new();
    let mut want = Vec::new();
    let mut split_at: Vec<(usize, f64)> = Vec::new();
    for i in 0..n {
        let pinned = i % 3 == 2;
        let mass = rng.gen_range(500.0..3000.0);
        let mut added = [[0.0; 6]; 6];
        let am = sym3(&mut rng, 200.0..2000.0, 100.0);
        let ai = sym3(&mut rng, 100.0..800.0, 30.0);
        for r in 0..3 {
            for c in 0..3 {
                added[r][c] = am[r][c];
                added[3 + r][3 + c] = ai[r][c];
            }
        }
        let cross = rv(&mut rng, 50.0);
        for k in 0..3 {
            added[k][3 + (k + 1) % 3] = cross[k];
            added[3 + (k + 1) % 3][k] = cross[k];
        }
        let mut damping = [[0.0; 6]; 6];
        for row in damping.iter_mut() {
            for x in row.iter_mut() {
                *x = rng.gen_range(-200.0..2000.0);
            }
        }
        let spec = FreeSpec {
            mass,
            cg: rv(&mut rng, 0.6),
            inertia: sym3(&mut rng, 0.5 * mass..1.5 * mass, 0.05 * mass),
            volume: rng.gen_range(0.0..4.0),
            cb: rv(&mut rng, 0.3),
            waterplane_area: if i % 2 == 0 {
                rng.gen_range(0.5..3.0)
            } else {
                0.0
            },
            waterplane_inertia: [rng.gen_range(0.0..2.0), rng.gen_range(0.0..2.0)],
            added_mass: added,
            drag_area: rv(&mut rng, 1.0).map(|x| x.abs() * 3.0),
            rotational_drag: rv(&mut rng, 1.0).map(|x| x.abs() * 30.0),
            damping,
            force: rv(&mut rng, 2000.0),
            moment: rv(&mut rng, 2000.0),
            angles: rv(&mut rng, 0.3),
            ..Default::default()
        };
        let kind = if pinned {
            FreeKind::Pinned
        } else {
            FreeKind::Free
        };
        let pose = MeanPose {
            reference: [
                rng.gen_range(-500.0..500.0),
                rng.gen_range(-500.0..500.0),
                rng.gen_range(-30.0..0.0),
            ],
            ..Default::default()
        };
        let init = FreeBody::new(spec, kind, &pose);
        let xr = init.reference();
        let mut b = init.clone();
        b.x_g += nalgebra::Vector3::from(rv(&mut rng, 2.0));
        b.v_g = nalgebra::Vector3::from(rv(&mut rng, 1.0));
        b.w = nalgebra::Vector3::from(rv(&mut rng, 0.5));
        b.q =
            nalgebra::UnitQuaternion::from_scaled_axis(nalgebra::Vector3::from(rv(&mut rng, 0.4)))
                * b.q;
        let pin = Pin {
            x: (xr + nalgebra::Vector3::from(rv(&mut rng, 1.0))).into(),
            v: rv(&mut rng, 1.0),
            a: rv(&mut rng, 2.0),
        };
        let u = rv(&mut rng, 1.0);
        // Two held nodes near the body.
        let mut lumps = Vec::new();
        let hs = list_at + lists.len();
        for _ in 0..2 {
            let r: [f64; 3] = (b.x_g + nalgebra::Vector3::from(rv(&mut rng, 2.0))).into();
            let m = sym3(&mut rng, 50.0..300.0, 10.0);
            let f = rv(&mut rng, 3000.0);
            lumps.push(Lump { r, m, f });
            let node = states.len();
            let mut q = RouteParams::<R> {
                node: node as u32,
                kind: 5,
                ..Default::default()
            };
            // Origin 0: the route's point is Xr, the node's state absolute.
            (q.p_hi_x, q.p_lo_x) = pair2::<R>(xr.x);
            (q.p_hi_y, q.p_lo_y) = pair2::<R>(xr.y);
            (q.p_hi_z, q.p_lo_z) = pair2::<R>(xr.z);
            lists.push(routes.len() as f64);
            routes.push(q);
            let mut s = NodeState::<R>::default();
            for d in 0..3 {
                (s.r_hi[d], s.r_lo[d]) = pair2::<R>(r[d]);
            }
            states.push(s);
            let c = |x: f64| R::c(x);
            outs.push(NodeOut {
                force: [c(f[0]), c(f[1]), c(f[2]), c(m[0][0])],
                acc: [c(m[1][1]), c(m[2][2]), c(m[0][1]), c(m[0][2])],
            });
            reactions.push([c(m[1][2]), c(0.0), c(0.0), c(0.0)]);
        }
        let (a, alpha) = b
            .accelerations(0.0, fluid, u, &lumps, pinned.then_some(pin))
            .unwrap();
        want.push((a, alpha));
        // The record (gpu::host::free_records' layout).
        let o = i * FREE_STRIDE;
        let s = o + 24;
        for d in 0..3 {
            split_at.push((s + d, b.x_g[d] - init.x_g[d]));
            rec[s + 6 + d] = b.v_g[d];
            rec[s + 13 + d] = b.w[d];
        }
        let q = b.q.quaternion();
        rec[s + 9] = q.i;
        rec[s + 10] = q.j;
        rec[s + 11] = q.k;
        rec[s + 12] = q.w;
        let c = o + 48;
        let sp = &b.spec;
        rec[c] = pinned as u8 as f64;
        rec[c + 2] = sp.mass;
        rec[c + 3..c + 6].copy_from_slice(&sp.cg);
        for r in 0..3 {
            rec[c + 6 + 3 * r..c + 9 + 3 * r].copy_from_slice(&sp.inertia[r]);
        }
        rec[c + 15] = sp.volume;
        rec[c + 16..c + 19].copy_from_slice(&sp.cb);
        rec[c + 19] = sp.waterplane_area;
        rec[c + 20..c + 22].copy_from_slice(&sp.waterplane_inertia);
        for r in 0..6 {
            rec[c + 22 + 6 * r..c + 28 + 6 * r].copy_from_slice(&sp.added_mass[r]);
            rec[c + 64 + 6 * r..c + 70 + 6 * r].copy_from_slice(&sp.damping[r]);
        }
        rec[c + 58..c + 61].copy_from_slice(&sp.drag_area);
        rec[c + 61..c + 64].copy_from_slice(&sp.rotational_drag);
        rec[c + 100..c + 103].copy_from_slice(&sp.force);
        rec[c + 103..c + 106].copy_from_slice(&sp.moment);
        for d in 0..3 {
            rec[c + 106 + d] = init.x_g[d] - xr[d];
            rec[c + 109 + d] = xr[d];
        }
        rec[c + 112] = xr[2] - b.x0[2];
        rec[c + 113] = hs as f64;
        rec[c + 114] = 2.0;
        // The pin's row: its displacement since Xr, its acceleration; the water.
        tin.extend([pin.x[0] - xr[0], pin.x[1] - xr[1], pin.x[2] - xr[2]]);
        tin.extend(pin.v);
        tin.extend(pin.a);
        tin.extend(u);
    }
    let mut body: Vec<R> = rec.iter().map(|&x| R::c(x)).collect();
    for (at, x) in split_at {
        let (h, l) = pair2::<R>(x);
        body[at] = h;
        body[at + 3] = l;
    }
    body.extend(lists.iter().map(|&x| R::c(x)));
    let params = Params::<R> {
        n_free: n as u32,
        free_at: 0,
        gravity: R::c(fluid.g),
        water_density: R::c(fluid.rho),
        one: R::c(1.0),
        ..Default::default()
    };
    let bytes = |x: &[u8]| x.to_vec();
    let group0 = [
        (0, bytes(bytemuck::bytes_of(&params))),
        (6, bytes(bytemuck::cast_slice(&routes))),
        (10, bytes(bytemuck::cast_slice(&states))),
        (12, bytes(bytemuck::cast_slice(&outs))),
        (13, bytes(bytemuck::cast_slice(&reactions))),
        (18, bytes(bytemuck::cast_slice(&body))),
    ];
    let tin_r: Vec<R> = tin.iter().map(|&x| R::c(x)).collect();
    let out = run_kernels(ctx, p, KERNEL, "t_free_acc", &group0, &tin_r, n, 6 * n);
    let tol = match p {
        Precision::F32 => 2e-3,
        Precision::F64 => 1e-10,
    };
    let mut worst = 0.0f64;
    for (i, (a, alpha)) in want.iter().enumerate() {
        let g: Vec<f64> = out[6 * i..6 * i + 6].iter().map(|x| x.f64()).collect();
        let scale = a.norm() + alpha.norm() + 1.0;
        for k in 0..3 {
            let d = ((g[k] - a[k]).abs()).max((g[3 + k] - alpha[k]).abs());
            worst = worst.max(d / scale);
            assert!(
                d <= tol * scale,
                "free_body_accelerations ({}), body {i} ({}): GPU {g:?} against a {a:?}, alpha {alpha:?}",
                p.name(),
                if i % 3 == 2 { "pinned" } else { "free" }
            );
        }
    }
    eprintln!(
        "free_body_accelerations ({}): {n} bodies, worst {worst:.3e} of |a| + |alpha| + 1 (tol {tol:e})",
        p.name()
    );
}

/// `x` as a compensated pair of `R`.
fn pair2<R: GpuReal>(x: f64) -> (R, R) {
    let h = R::c(x);
    (h, R::c(x - h.f64()))
}

#[test]
fn wgsl_free_body_accelerations_match_rust_in_f32() {
    let Some(ctx) = gpu_context("wgsl_free_body_accelerations_match_rust_in_f32", false) else {
        return;
    };
    check::<f32>(&ctx, Precision::F32);
}

#[test]
fn wgsl_free_body_accelerations_match_rust_in_f64() {
    let Some(ctx) = gpu_context("wgsl_free_body_accelerations_match_rust_in_f64", true) else {
        return;
    };
    check::<f64>(&ctx, Precision::F64);
}
