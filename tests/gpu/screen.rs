//! Screen-model nets on the GPU against the CPU path (docs/src/model/screen.md): a
//! plane panel in a steady current at 45 degrees (each coefficient set) and a cage with
//! Cheng's wake in a current from an oblique direction, both kernels (two-pass, fused).
//! Contract: the loads at rest (the panels' drag and lift alone: neutrally buoyant
//! twines, no stretch) to 1e-12 of their size in f64 and 0.5 % in f32; after a short run
//! the positions to round-off (1e-9 m) in f64.

use super::common::*;
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::model::{
    add_net, Current, Environment, Layout, ModelDef, NetShape, NetSpec, PointMass, ScreenModel,
    ScreenNet, WakeModel,
};
use cablesim::options::{Baumgarte, Scheme, SolverOptions};
use cablesim::stability::stable_step;

fn net(shape: NetShape, u: [f64; 3], model: ScreenModel, wake: WakeModel) -> ModelDef {
    let mut lt = wire();
    lt.diameter = 0.004;
    lt.mass_per_length = 1.3 * 1025.0 * std::f64::consts::PI * 0.25 * 0.004 * 0.004;
    lt.ea = 2.0e4;
    lt.damping = 1e-3;
    let mut def = ModelDef {
        env: Environment {
            depth: 200.0,
            ..Environment::default()
        },
        line_types: vec![lt],
        currents: vec![Current {
            table: vec![(0.0, u)],
        }],
        ..Default::default()
    };
    add_net(
        &mut def,
        &NetSpec {
            name: "net".into(),
            line_type: 0,
            current: 0,
            shape,
            segments: 1,
            sinker: PointMass::default(),
            output_positions: false,
            screen: Some(ScreenNet {
                model,
                solidity: 0.3,
                twine_diameter: 1.5e-3,
                viscosity: 1e-6,
                wake,
                axis: [0.0, 0.0],
            }),
        },
    )
    .unwrap();
    def
}

fn cases() -> Vec<(&'static str, ModelDef)> {
    let h = 0.5 * std::f64::consts::FRAC_1_SQRT_2;
    let panel = NetShape::Panel {
        columns: 5,
        rows: 4,
        width: 2.0,
        depth: 1.5,
        top: [3.0, -2.0, -2.0],
    };
    let cage = NetShape::Cylinder {
        around: 16,
        rows: 4,
        radius: 2.0,
        depth: 2.0,
        top: [1.0, -3.0, -1.0],
    };
    vec![
        (
            "panel aarsnes",
            net(panel, [h, h, 0.0], ScreenModel::Aarsnes, WakeModel::None),
        ),
        (
            "panel loland",
            net(panel, [h, h, 0.0], ScreenModel::Loland, WakeModel::None),
        ),
        (
            "panel kristiansen_faltinsen",
            net(
                panel,
                [h, h, 0.0],
                ScreenModel::KristiansenFaltinsen,
                WakeModel::None,
            ),
        ),
        (
            "cage kristiansen_faltinsen, cheng wake",
            net(
                cage,
                [0.3, 0.4, 0.0],
                ScreenModel::KristiansenFaltinsen,
                WakeModel::Cheng,
            ),
        ),
        (
            "cage aarsnes, loland wake",
            net(
                cage,
                [-0.5, 0.1, 0.0],
                ScreenModel::Aarsnes,
                WakeModel::Loland,
            ),
        ),
    ]
}

fn check(p: Precision) {
    let name = format!("gpu_screen_net_in_{}", p.name());
    let Some(ctx) = gpu_context(&name, p == Precision::F64) else {
        return;
    };
    for (what, def) in cases() {
        let (lay, pos) = Layout::build(&def).unwrap();
        let dt = 0.8 * stable_step(&lay, Scheme::Symplectic, Baumgarte::default()).dt;
        let opts = SolverOptions {
            dt,
            ..Default::default()
        };
        let steps = (0.3 / dt) as u64;
        let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
        let ev = cpu.evaluate().unwrap();
        cpu.advance(steps).unwrap();
        for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
            let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
            gpu.set_kernel(kernel).unwrap();
            let eg = gpu.evaluate().unwrap();
            // The loads at rest: every free node's force (the held top row's force is
            // its reaction's business), and their sum.
            let mut scale = 0.0f64;
            let (mut sc, mut sg) = ([0.0; 3], [0.0; 3]);
            let mut worst = 0.0f64;
            for i in 0..lay.n_nodes() {
                let (fc, fg) = (ev.force[i], eg.force[i]);
                let m = (fc[0].powi(2) + fc[1].powi(2) + fc[2].powi(2)).sqrt();
                scale = scale.max(m);
                for q in 0..3 {
                    sc[q] += fc[q];
                    sg[q] += fg[q];
                    worst = worst.max((fc[q] - fg[q]).abs());
                }
            }
            let total = (sc[0].powi(2) + sc[1].powi(2) + sc[2].powi(2)).sqrt();
            let dtot =
                ((sc[0] - sg[0]).powi(2) + (sc[1] - sg[1]).powi(2) + (sc[2] - sg[2]).powi(2))
                    .sqrt();
            println!(
                "{what} ({}, {kernel:?}): total load {total:.5} N, GPU - CPU {dtot:.2e} N, \
                 worst node {worst:.2e} N of {scale:.3e}",
                p.name()
            );
            assert!(total > 0.1, "{what}: the net must be loaded: {total} N");
            match p {
                Precision::F64 => {
                    assert!(
                        worst <= 1e-12 * scale,
                        "{what}: node loads differ by {worst:e} N"
                    );
                    assert!(dtot <= 1e-12 * total, "{what}: total differs by {dtot:e} N");
                }
                _ => assert!(dtot <= 5e-3 * total, "{what}: total differs by {dtot:e} N"),
            }
            if p == Precision::F64 {
                gpu.advance(steps).unwrap();
                let (r, _) = gpu.state().unwrap();
                let mut dr = 0.0f64;
                let mut moved = 0.0f64;
                for i in 0..lay.n_nodes() {
                    let c = cpu.r[i].to_f64();
                    for q in 0..3 {
                        dr = dr.max((r[i][q] - c[q]).abs());
                        moved = moved.max((c[q] - pos[i][q]).abs());
                    }
                }
                println!("  {steps} steps: |dr| {dr:.2e} m, moved {moved:.4} m");
                assert!(moved > 1e-3, "{what}: the net must move: {moved} m");
                assert!(
                    dr < 1e-9,
                    "{what} ({kernel:?}): GPU and CPU differ by {dr:e} m"
                );
            }
        }
    }
}

#[test]
fn gpu_screen_net_matches_the_cpu_in_f64() {
    check(Precision::F64);
}

#[test]
fn gpu_screen_net_matches_the_cpu_in_f32() {
    check(Precision::F32);
}
