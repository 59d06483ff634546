//! The screen-model functions (`screen_log10`, `screen_cylinder_cd`,
//! `screen_coefficients`, `screen_wake_factor`, `screen_panel_force`,
//! shaders/shared/prelude.wgsl) against their Rust twins (`physics::screen`), run by
//! `functions`'s `check_all`, on random panels (skewed, moving, at any angle to the
//! flow, each coefficient set and wake rule, downstream of the axis or not).

use super::*;
use cablesim::physics::screen::screen_log10;
use cablesim::physics::{
    screen_coefficients, screen_cylinder_cd, screen_panel_force, screen_wake_factor, ScreenCoefs,
};

const KERNEL: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

fn v3in(k: u32) -> vec3<R> {
    return vec3<R>(tin[k], tin[k + 1u], tin[k + 2u]);
}

// Case i: 36 inputs (coefficients 0..7, corners 7..19, velocities 19..31, water
// 31..34, Reynolds number and cos theta 34..36); 8 outputs.
@compute @workgroup_size(64)
fn t_screen(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 36u {
        return;
    }
    let b = i * 36u;
    let co = ScreenCoefs(u32(tin[b]), u32(tin[b + 1u]), tin[b + 2u], tin[b + 3u], tin[b + 4u], tin[b + 5u], tin[b + 6u]);
    let f = screen_panel_force(co, v3in(b + 7u), v3in(b + 10u), v3in(b + 13u), v3in(b + 16u),
        v3in(b + 19u), v3in(b + 22u), v3in(b + 25u), v3in(b + 28u), v3in(b + 31u));
    let re = tin[b + 34u];
    let c = tin[b + 35u];
    let k = screen_coefficients(co.model, co.sn, re, c);
    let o = i * 8u;
    tout[o] = f.x;
    tout[o + 1u] = f.y;
    tout[o + 2u] = f.z;
    tout[o + 3u] = k.x;
    tout[o + 4u] = k.y;
    tout[o + 5u] = screen_wake_factor(co, re, c);
    tout[o + 6u] = screen_cylinder_cd(re);
    tout[o + 7u] = screen_log10(min(max(re, R(10.0)), R(1.0e4)));
}
"#;

pub(super) fn check_screen<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 600;
    let mut x = Vec::with_capacity(36 * n);
    for i in 0..n {
        let model = (i % 3) as f64;
        let wake = ((i / 3) % 3) as f64;
        let sn = rng.gen_range(0.05..0.5);
        let dw = rng.gen_range(0.5e-3..5e-3);
        x.extend([model, wake, sn, dw / (1e-6 * (1.0 - sn)), 512.5]);
        // The axis a few metres off the panel, either side.
        x.extend([rng.gen_range(-5.0..5.0), rng.gen_range(-5.0..5.0)]);
        // A skewed quadrilateral about a centre, about 1 m across, turned at random.
        let c = rv(rng, 10.0);
        let (a, bb) = (rv(rng, 1.0), rv(rng, 1.0));
        for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let d = rv(rng, 0.1);
            x.extend([0, 1, 2].map(|q| c[q] + 0.5 * (s * a[q] + t * bb[q]) + d[q]));
        }
        for _ in 0..4 {
            x.extend(rv(rng, 0.3));
        }
        x.extend(rv(rng, 1.5));
        x.push(10f64.powf(rng.gen_range(0.5..4.5)));
        x.push(rng.gen_range(0.0..1.0));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run_kernels::<R>(ctx, p, KERNEL, "t_screen", &[], &xr, n, 8 * n);
    let mut w = Worst::new::<R>("screen");
    let mut downstream = 0;
    for i in 0..n {
        let a = &x[36 * i..36 * (i + 1)];
        let co = ScreenCoefs {
            model: a[0] as u32,
            wake: a[1] as u32,
            sn: a[2],
            re_scale: a[3],
            half_rho: a[4],
            axis_x: a[5],
            axis_y: a[6],
        };
        let v3 = |k: usize| V3::new(a[k], a[k + 1], a[k + 2]);
        let pts = [v3(7), v3(10), v3(13), v3(16)];
        let vel = [v3(19), v3(22), v3(25), v3(28)];
        let u = v3(31);
        // Skip a panel too near the wake's edge (the test there is a comparison).
        let cx = 0.25 * (pts[0].x + pts[1].x + pts[2].x + pts[3].x);
        let cy = 0.25 * (pts[0].y + pts[1].y + pts[2].y + pts[3].y);
        let side = (cx - co.axis_x) * u.x + (cy - co.axis_y) * u.y;
        let o: Vec<f64> = out[8 * i..8 * i + 8].iter().map(|v| v.f64()).collect();
        let (re, c) = (a[34], a[35]);
        let k = screen_coefficients(co.model, co.sn, re, c);
        // Coefficients: their polynomials' terms are below 20 (the cylinder's below 16).
        w.check("C_D", i, o[3], k[0], 20.0);
        w.check("g", i, o[4], k[1], 20.0);
        w.check("r", i, o[5], screen_wake_factor(&co, re, c), 20.0);
        w.check("C_d cylinder", i, o[6], screen_cylinder_cd(re), 20.0);
        w.check("log10", i, o[7], screen_log10(re.clamp(10.0, 1.0e4)), 5.0);
        if co.wake != 0 && side.abs() < 1e-3 * (u.norm() + 1.0) {
            continue;
        }
        if co.wake != 0 && side > 0.0 {
            downstream += 1;
        }
        let f = screen_panel_force(&co, pts, vel, u);
        // Scale: 1/2 rho A |U|^2 (|C_D| + 2 |g| + 1), and the positions' size (10 m)
        // over the panel's (1 m) for the area and normal formed from differences.
        let ur = (u - (vel[0] + vel[1] + vel[2] + vel[3]) * 0.25).norm();
        let area = 0.5 * (pts[2] - pts[0]).cross(pts[3] - pts[1]).norm();
        let scale = co.half_rho * area * ur * ur * (k[0].abs() + 2.0 * k[1].abs() + 1.0) * 20.0;
        w.v("force", i, &o[..3], f, scale);
    }
    assert!(downstream > n / 10, "{downstream} panels downstream");
    w.report(p);
}
