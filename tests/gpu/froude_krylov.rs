//! The water-acceleration load on the GPU against its equations (the case of
//! tests/cpu/froude_krylov.rs, `froude_krylov_case`): a free, fully submerged
//! horizontal element in a wave carries `rho V (1 + cm) a` across and `rho V (1 + cat)
//! a` along, and accelerates by that over its mass block; both kernels, f64 to
//! round-off (the load and accelerations of an evaluation, and the velocity `dt a(0)`
//! of a first symplectic step from rest) and f32 to its precision (1e-5 of the
//! acceleration's scale; the evaluation only: a first step's velocity is `dt a` in f32).

use super::common::*;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::options::SolverOptions;

fn close(what: &str, got: [f64; 3], want: [f64; 3], scale: f64, tol: f64) {
    for q in 0..3 {
        assert!(
            (got[q] - want[q]).abs() <= tol * scale,
            "{what}: component {q}: {} against {} (scale {scale:e})",
            got[q],
            want[q]
        );
    }
}

fn check(p: Precision) {
    let name = format!("gpu_froude_krylov_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    let tol = match p {
        Precision::F64 => 1e-10,
        _ => 1e-5,
    };
    for (cm, cat) in [(1.0, 0.0), (1.0, 0.5), (0.8, 2.0)] {
        let (lay, pos, sea) = froude_krylov_case(cm, cat);
        let (force, acc, scale) = froude_krylov_expected(&lay, &pos, &sea);
        let fscale = scale * (lay.line_types[0].mass_per_length + 3.0 * 8.05) * 2.0;
        let dt = 1e-4;
        let opts = SolverOptions {
            dt,
            ..SolverOptions::default()
        };
        for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
            let what = format!("{name}: cm {cm}, cat {cat}, {kernel:?}");
            let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
            gpu.set_kernel(kernel).unwrap();
            gpu.set_sea(&sea).unwrap();
            let ev = gpu.evaluate().unwrap();
            let total: [f64; 3] = std::array::from_fn(|q| ev.force[0][q] + ev.force[1][q]);
            close(&format!("{what}: load"), total, force, fscale, tol);
            for i in 0..2 {
                close(&format!("{what}: node {i} acc"), ev.acc[i], acc, scale, tol);
            }
            if p == Precision::F64 {
                gpu.advance(1).unwrap();
                let (_, v) = gpu.state().unwrap();
                for (i, vi) in v.iter().enumerate() {
                    let a = vi.map(|x| x / dt);
                    close(&format!("{what}: node {i} first step"), a, acc, scale, tol);
                }
            }
        }
    }
}

#[test]
fn gpu_submerged_element_carries_the_full_froude_krylov_load_in_f64() {
    check(Precision::F64);
}

#[test]
fn gpu_submerged_element_carries_the_full_froude_krylov_load_in_f32() {
    check(Precision::F32);
}
