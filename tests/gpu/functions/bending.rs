//! The bending hinge (`bending_angle`, `bending_hinge`, `bending_energy`,
//! physics::bending) against its Rust twins: random pairs of unit tangents at angles
//! from 1e-7 rad to 3 rad (the WGSL angle comes from its own arctangent,
//! `bending_atan2`, as the shaders have no f64 one), random lengths and stiffnesses.

use super::*;
use cablesim::physics::{bending_angle, bending_energy, bending_hinge};

const BENDING_KERNELS: &str = r#"
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

// Case i: q1, l1, q2, l2, k; out: phi, phi / sin(phi), f1, f2, the energy.
@compute @workgroup_size(64)
fn t_bending(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 9u {
        return;
    }
    let b = i * 9u;
    let q1 = v3in(b);
    let q2 = v3in(b + 4u);
    let a = bending_angle(q1, q2);
    let f = bending_hinge(q1, tin[b + 3u], q2, tin[b + 7u], tin[b + 8u]);
    tout[b] = a.x;
    tout[b + 1u] = a.y;
    v3out(b + 2u, f[0]);
    v3out(b + 5u, f[1]);
    tout[b + 8u] = bending_energy(q1, q2, tin[b + 8u]);
}
"#;

/// A unit vector at angle `phi` from the unit vector `q` (about a random axis).
fn turned(q: V3<f64>, phi: f64, rng: &mut ChaCha8Rng) -> V3<f64> {
    let r = V3::<f64>::from_f64(rv(rng, 1.0));
    let n = q.cross(r);
    let n = n / n.norm();
    q * phi.cos() + n * phi.sin()
}

/// Contract: `16 eps` of each output's scale. The cross product that makes
/// `sin(phi)` rounds to `eps` absolute, so the angle is held to `eps`,
/// `phi / sin(phi)` to `eps / sin(phi)` relative, the forces to `eps k (1 + g) / l`
/// and the energy to `eps k (phi + phi^2)`.
pub(super) fn check_bending<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1200;
    let mut x = Vec::new();
    for i in 0..n {
        let phi = match i % 4 {
            0 => 10f64.powf(rng.gen_range(-7.0..-3.0)),
            1 => rng.gen_range(1e-3..0.3),
            2 => rng.gen_range(0.3..1.6),
            _ => rng.gen_range(1.6..3.0),
        };
        let q1 = V3::<f64>::from_f64(rv(rng, 1.0));
        let q1 = q1 / q1.norm();
        let q2 = turned(q1, phi, rng);
        x.extend(q1.to_f64());
        x.push(rng.gen_range(0.05..20.0));
        x.extend(q2.to_f64());
        x.push(rng.gen_range(0.05..20.0));
        x.push(10f64.powf(rng.gen_range(0.0..9.0)));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run_kernels::<R>(ctx, p, BENDING_KERNELS, "t_bending", &[], &xr, n, 9 * n);
    let mut w = Worst::new::<R>("bending_hinge");
    let mut seen = [false; 2];
    for i in 0..n {
        let a = &x[9 * i..9 * (i + 1)];
        let o: Vec<f64> = out[9 * i..9 * (i + 1)].iter().map(|v| v.f64()).collect();
        let v = |k: usize| V3::new(a[k], a[k + 1], a[k + 2]);
        let (q1, l1, q2, l2, k) = (v(0), a[3], v(4), a[7], a[8]);
        let (phi, g) = bending_angle(q1, q2);
        let s = q1.cross(q2).norm();
        seen[(s < 1e-4) as usize] = true;
        w.check("phi", i, o[0], phi, 1.0);
        w.check("g", i, o[1], g, g / s.max(1e-4));
        let (f1, f2) = bending_hinge(q1, l1, q2, l2, k);
        w.v("f1", i, &o[2..5], f1, k * (1.0 + g) / l1);
        w.v("f2", i, &o[5..8], f2, k * (1.0 + g) / l2);
        w.check(
            "energy",
            i,
            o[8],
            bending_energy(q1, q2, k),
            k * (phi + phi * phi),
        );
    }
    assert!(
        seen[0] && seen[1],
        "both branches of phi / sin(phi): {seen:?}"
    );
    w.report(p);
}
