//! The viscoelastic rope's tension and state rate (`visco_tension`, physics::visco)
//! against its Rust twin, with constant and load-dependent dynamic stiffness, taut and
//! slack, the state above and below zero.

use super::*;
use cablesim::physics::visco_tension;

const VISCO_KERNELS: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

@compute @workgroup_size(64)
fn t_visco(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 8u {
        return;
    }
    let b = 8u * i;
    let o = visco_tension(tin[b], tin[b + 1u], tin[b + 2u], tin[b + 3u], tin[b + 4u],
        tin[b + 5u], tin[b + 6u], tin[b + 7u]);
    tout[2u * i] = o.x;
    tout[2u * i + 1u] = o.y;
}
"#;

pub(super) fn check_visco<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 800;
    let mut x = Vec::new();
    for i in 0..n {
        let ks = 10f64.powf(rng.gen_range(5.0..8.0));
        let kd = ks * rng.gen_range(1.2..5.0);
        // Half the cases with a load-dependent dynamic stiffness.
        let slope = if i % 2 == 0 {
            0.0
        } else {
            rng.gen_range(0.0..50.0)
        };
        let c1 = ks * rng.gen_range(0.01..10.0);
        let c2 = if i % 3 == 0 {
            0.0
        } else {
            c1 * rng.gen_range(0.0..1.0)
        };
        let eps = rng.gen_range(-0.01..0.1);
        let epsdot = rng.gen_range(-0.5..0.5);
        let s = eps * rng.gen_range(0.0..1.0) + rng.gen_range(-0.005..0.005);
        x.extend([ks, kd, slope, c1, c2, eps, epsdot, s]);
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run_kernels::<R>(ctx, p, VISCO_KERNELS, "t_visco", &[], &xr, n, 2 * n);
    let mut w = Worst::new::<R>("visco_tension");
    let (mut slack, mut loaded) = (false, false);
    for i in 0..n {
        let c = &x[8 * i..8 * i + 8];
        let (ks, kd, slope, c1, c2, eps, epsdot, s) =
            (c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]);
        let (t, rate) = visco_tension(ks, kd, slope, c1, c2, eps, epsdot, s);
        slack |= eps <= 0.0;
        loaded |= slope > 0.0 && s > 0.0;
        // The terms' magnitudes, times the cancellation in K1 = K2 ks / (K2 - ks).
        let k2 = cablesim::physics::visco_dynamic_stiffness(ks, kd, slope, s);
        let k1 = k2 * ks / (k2 - ks);
        let cond = 4.0 * (1.0 + k2 / (k2 - ks));
        let rate_scale = (k2 * eps.abs() + (k1 + k2) * s.abs() + c2 * epsdot.abs()) / (c1 + c2);
        w.check("rate", i, out[2 * i + 1].f64(), rate, cond * rate_scale);
        w.check(
            "T",
            i,
            out[2 * i].f64(),
            t,
            cond * (k1 * s.abs() + c1 * rate_scale),
        );
    }
    assert!(
        slack && loaded,
        "cases: slack {slack}, load-dependent {loaded}"
    );
    w.report(p);
}
