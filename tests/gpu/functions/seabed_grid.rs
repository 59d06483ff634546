//! The seabed grid's WGSL functions (`seabed_height`, `seabed_slope_force`,
//! `seabed_slope_damping`, `seabed_slope_normal`) against their Rust twins, run by
//! `functions`'s `check_all`. The grid rides in the current profiles' buffer (bindings
//! 8 and 9) as the GPU path packs it (`gpu::engine::install`).

use super::*;
use cablesim::physics::{
    seabed_friction_axis, seabed_height, seabed_slope_damping, seabed_slope_force,
    seabed_slope_normal,
};

/// A random grid `nx` by `ny` (uneven ticks), packed, rounded to `R` and back.
fn random_grid<R: GpuReal>(rng: &mut ChaCha8Rng, nx: usize, ny: usize) -> Vec<f64> {
    let mut ticks = |n: usize, x0: f64| {
        let mut v = vec![x0];
        for _ in 1..n {
            let last = *v.last().unwrap();
            v.push(last + rng.gen_range(5.0..80.0));
        }
        v
    };
    let xs = ticks(nx, -150.0);
    let ys = ticks(ny, -60.0);
    let mut g = vec![nx as f64, ny as f64];
    g.extend(&xs);
    g.extend(&ys);
    for _ in 0..nx * ny {
        g.push(rng.gen_range(-160.0..-40.0));
    }
    to_r::<R>(&g).1
}

fn grid_buffers<R: GpuReal>(g: &[f64]) -> Vec<(u32, Vec<u8>)> {
    let pts: Vec<CurrentPoint<R>> = g
        .chunks(4)
        .map(|q| {
            let at = |k: usize| R::c(q.get(k).copied().unwrap_or(0.0));
            CurrentPoint {
                z: at(0),
                ux: at(1),
                uy: at(2),
                uz: at(3),
            }
        })
        .collect();
    let ranges = [CurrentRange {
        start: 0,
        len: pts.len() as u32,
    }];
    let prm = Params::<R> {
        seabed: 2, // the grid in range 0
        seabed_k: R::c(3e6),
        seabed_c: R::c(3e4),
        seabed_mu: R::c(0.6),
        seabed_v_eps: R::c(0.01),
        seabed_mu_axial: R::c(0.6),
        one: R::c(1.0),
        ..Default::default()
    };
    vec![
        (0, bytemuck::bytes_of(&prm).to_vec()),
        (8, bytemuck::cast_slice(&pts).to_vec()),
        (9, bytemuck::cast_slice(&ranges).to_vec()),
    ]
}

pub(super) fn check_seabed_grid<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    for (nx, ny) in [(7, 5), (1, 4), (3, 1)] {
        let g = random_grid::<R>(rng, nx, ny);
        let (x0, x1) = (g[2], g[2 + nx - 1]);
        let (y0, y1) = (g[2 + nx], g[2 + nx + ny - 1]);
        // Beyond the edges by a tenth of the extent (and a metre).
        let (mx, my) = (0.1 * (x1 - x0) + 1.0, 0.1 * (y1 - y0) + 1.0);
        let n = 400;
        let mut x = Vec::new();
        for i in 0..n {
            // Most inside, some beyond each edge, some on a grid point.
            if i % 10 == 0 {
                x.push(g[2 + rng.gen_range(0..nx)]);
                x.push(g[2 + nx + rng.gen_range(0..ny)]);
            } else {
                x.push(rng.gen_range(x0 - mx..x1 + mx));
                x.push(rng.gen_range(y0 - my..y1 + my));
            }
        }
        let (xr, x) = to_r::<R>(&x);
        let out = run::<R>(
            ctx,
            p,
            "t_seabed_height",
            &grid_buffers::<R>(&g),
            &xr,
            n,
            3 * n,
        );
        let mut w = Worst::new::<R>("seabed_height");
        let z_scale = g[2 + nx + ny..].iter().fold(0.0f64, |a, z| a.max(z.abs()));
        let mut sloped = 0;
        for i in 0..n {
            let h = seabed_height(&g[..], x[2 * i], x[2 * i + 1]);
            if h.y != 0.0 || h.z != 0.0 {
                sloped += 1;
            }
            let o: Vec<f64> = out[3 * i..3 * i + 3].iter().map(|v| v.f64()).collect();
            // The height's rounding: its scale, and the slope times the position's.
            let s = z_scale + (h.y.abs() + h.z.abs()) * (x[2 * i].abs() + x[2 * i + 1].abs());
            w.check("z", i, o[0], h.x, s);
            // A slope is a difference of heights over a cell width (>= 5 m).
            w.check("dz/dx", i, o[1], h.y, s);
            w.check("dz/dy", i, o[2], h.z, s);
        }
        assert!(sloped > n / 2, "{nx}x{ny}: {sloped} of {n} sloped");
        w.report(p);
    }
}

pub(super) fn check_seabed_slope<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let r = |x: f64| R::c(x).f64();
    let sc = SeabedCoefs {
        z: 0.0,
        k: r(3e6),
        c: r(3e4),
        mu: r(0.6),
        mu_axial: r(0.6),
        v_eps: r(0.01),
    };
    let n = 500;
    let mut x = Vec::new();
    for i in 0..n {
        x.push(rng.gen_range(-0.05..0.1));
        x.push(rng.gen_range(0.5..50.0));
        let vs = if i % 5 == 0 { 0.005 } else { 1.0 };
        x.extend(rv(rng, vs));
        // The seabed at z = 0 here (so the Rust twin's node at z = -gap is exact).
        x.push(0.0);
        x.push(rng.gen_range(-0.4..0.4));
        x.push(rng.gen_range(-0.4..0.4));
    }
    let (xr, x) = to_r::<R>(&x);
    // No grid is read: the Params of the plain seabed test (seabed = 1), whose
    // constants are these.
    let out = run::<R>(
        ctx,
        p,
        "t_seabed_slope",
        &[(0, params::<R>(3e6, 3e4, 0.6, 0.01))],
        &xr,
        n,
        8 * n,
    );
    let mut w = Worst::new::<R>("seabed_slope_force");
    let mut contact = 0;
    for i in 0..n {
        let a = &x[8 * i..8 * (i + 1)];
        let (gap, lt) = (a[0], a[1]);
        let v = V3::new(a[2], a[3], a[4]);
        let g = V3::new(a[5], a[6], a[7]);
        let rn = V3::new(0.0, 0.0, -gap);
        let f = seabed_slope_force(&sc, lt, rn, v, g);
        let (cn, ct) = seabed_slope_damping(&sc, lt, rn, v, g);
        let nrm = seabed_slope_normal(g);
        if cn > 0.0 {
            contact += 1;
        }
        let o: Vec<f64> = out[8 * i..8 * (i + 1)].iter().map(|v| v.f64()).collect();
        let scale = sc.k * lt * gap.abs() * (1.0 + sc.mu) + sc.c * lt * norm(v);
        w.v("force", i, &o[0..3], f, scale);
        w.check("c_n", i, o[3], cn, sc.c * lt);
        w.check("c_t", i, o[4], ct, sc.mu * sc.k * lt * gap.abs() / sc.v_eps);
        w.v("normal", i, &o[5..8], nrm, 1.0);
    }
    assert!(contact > n / 2, "{contact} of {n} in contact");
    w.report(p);
}

/// `seabed_friction_axis` (the friction's axial split) against its Rust twin: random
/// normal forces (some zero or negative: off the seabed), seabed normals, velocities
/// (some below `v_eps`) and line tangents (some normal to the seabed: no axis).
pub(super) fn check_seabed_friction_axis<R: GpuReal>(
    ctx: &GpuContext,
    p: Precision,
    rng: &mut ChaCha8Rng,
) {
    let r = |x: f64| R::c(x).f64();
    let (mu_t, mu_a, v_eps) = (0.6, 0.3, 0.01);
    let sc = SeabedCoefs {
        z: 0.0,
        k: r(3e6),
        c: r(3e4),
        mu: r(mu_t),
        mu_axial: r(mu_a),
        v_eps: r(v_eps),
    };
    let n = 500;
    let mut x = Vec::new();
    for i in 0..n {
        x.push(if i % 7 == 0 {
            -rng.gen_range(0.0..1e3)
        } else {
            rng.gen_range(0.0..1e4)
        });
        let g = V3::new(0.0, rng.gen_range(-0.4..0.4), rng.gen_range(-0.4..0.4));
        let nrm = seabed_slope_normal(g);
        x.extend([nrm.x, nrm.y, nrm.z]);
        let vs = if i % 5 == 0 { 0.005 } else { 1.0 };
        x.extend(rv(rng, vs));
        if i % 11 == 0 {
            x.extend([nrm.x * 2.0, nrm.y * 2.0, nrm.z * 2.0]);
        } else {
            x.extend(rv(rng, 2.0));
        }
    }
    let (xr, x) = to_r::<R>(&x);
    let mut prm = params_struct::<R>(3e6, 3e4, mu_t, v_eps);
    prm.seabed_mu_axial = R::c(mu_a);
    let out = run::<R>(
        ctx,
        p,
        "t_seabed_friction_axis",
        &[(0, bytemuck::bytes_of(&prm).to_vec())],
        &xr,
        n,
        4 * n,
    );
    let mut w = Worst::new::<R>("seabed_friction_axis");
    let (mut split, mut none) = (0, 0);
    for i in 0..n {
        let a = &x[10 * i..10 * (i + 1)];
        let v3 = |k: usize| V3::new(a[k], a[k + 1], a[k + 2]);
        let (q, d) = seabed_friction_axis(&sc, a[0], v3(1), v3(4), v3(7));
        if d != 0.0 {
            split += 1;
        } else {
            none += 1;
        }
        let o: Vec<f64> = out[4 * i..4 * (i + 1)].iter().map(|v| v.f64()).collect();
        w.v("q", i, &o[0..3], q, 1.0);
        w.check("d", i, o[3], d, (mu_t - mu_a) * a[0].abs() / v_eps);
    }
    assert!(
        split > n / 2 && none > n / 20,
        "{split} split, {none} without"
    );
    w.report(p);
}
