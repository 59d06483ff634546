//! The tabulated strain-tension curve (`tabulated_tension`, physics::axial) against its
//! Rust twin: the curves' rows packed in `current_pts` as the GPU path packs them.

use super::*;

const AXIAL_KERNELS: &str = r#"
@group(1) @binding(0) var<storage, read> tin: array<R>;
@group(1) @binding(1) var<storage, read_write> tout: array<R>;

@compute @workgroup_size(64)
fn t_tabulated(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&tin) / 2u {
        return;
    }
    tout[i] = tabulated_tension(current_ranges[u32(tin[2u * i])], tin[2u * i + 1u]);
}
"#;

pub(super) fn check_tabulated<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let r = |x: f64| R::c(x).f64();
    // A polyester-like stiffening curve that starts at a positive strain, one from
    // (0, 0), and a two-row one.
    let curves: Vec<Vec<[f64; 2]>> = vec![
        vec![[0.01, 1.0e5], [0.02, 3.0e5], [0.04, 9.0e5], [0.08, 2.5e6]],
        vec![[0.0, 0.0], [0.005, 2.0e4], [0.03, 4.0e5]],
        vec![[0.002, 5.0e3], [0.01, 6.0e4]],
    ]
    .into_iter()
    .map(|c| c.into_iter().map(|[x, y]| [r(x), r(y)]).collect())
    .collect();
    let mut pts = Vec::new();
    let mut ranges = Vec::new();
    for c in &curves {
        ranges.push(CurrentRange {
            start: pts.len() as u32,
            len: c.len() as u32,
        });
        for row in c {
            pts.push(CurrentPoint::<R> {
                z: R::c(row[0]),
                ux: R::c(row[1]),
                uy: R::c(0.0),
                uz: R::c(0.0),
            });
        }
    }
    let n = 600;
    let mut x = Vec::new();
    for i in 0..n {
        x.push((i % curves.len()) as f64);
        // Slack, inside the table, and past its last row.
        x.push(rng.gen_range(-0.02..0.12));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run_kernels::<R>(
        ctx,
        p,
        AXIAL_KERNELS,
        "t_tabulated",
        &[
            (8, bytemuck::cast_slice(&pts).to_vec()),
            (9, bytemuck::cast_slice(&ranges).to_vec()),
        ],
        &xr,
        n,
        n,
    );
    let mut w = Worst::new::<R>("tabulated_tension");
    let mut seen_past = false;
    for i in 0..n {
        let rows = &curves[x[2 * i] as usize];
        let eps = x[2 * i + 1];
        seen_past |= eps > rows[rows.len() - 1][0];
        let t = tabulated_tension(rows, eps);
        // The slope times the strain bounds the interpolation's rounding.
        let scale = 1.0 + tabulated_max_slope(rows) * eps.abs().max(1e-3) * 4.0;
        w.check("T", i, out[i].f64(), t, scale);
    }
    assert!(seen_past, "no case past the last row");
    w.report(p);
}
