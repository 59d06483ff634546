//! Every WGSL stage parses and validates (naga, both precisions, no GPU needed), and
//! builds into compute pipelines on the adapter when there is one.

use super::common::*;
use cablesim::gpu::shaders::{self, Stage};
use cablesim::gpu::{GpuSolver, Precision};
use cablesim::model::{Layout, PointMass, Route};
use cablesim::options::SolverOptions;

fn validate(stage: Stage, p: Precision) -> naga::Module {
    let src = shaders::source(stage, p);
    let module = naga::front::wgsl::parse_str(&src).unwrap_or_else(|e| {
        panic!(
            "{} ({}) does not parse:\n{}",
            stage.file(),
            p.name(),
            e.emit_to_string(&src)
        )
    });
    let caps = match p {
        Precision::F32 => naga::valid::Capabilities::empty(),
        Precision::F64 => naga::valid::Capabilities::FLOAT64,
    };
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), caps)
        .validate(&module)
        .unwrap_or_else(|e| {
            panic!(
                "{} ({}) does not validate:\n{}",
                stage.file(),
                p.name(),
                e.emit_to_string(&src)
            )
        });
    module
}

#[test]
fn every_stage_validates_at_both_precisions() {
    for p in [Precision::F32, Precision::F64] {
        for stage in Stage::ALL {
            let m = validate(stage, p);
            let entries: Vec<&str> = m.entry_points.iter().map(|e| e.name.as_str()).collect();
            for want in stage.entry_points() {
                assert!(
                    entries.contains(want),
                    "{}: no entry point {want} in {entries:?}",
                    stage.file()
                );
            }
        }
    }
}

#[test]
fn f64_shaders_need_the_f64_capability() {
    // The substitution really switches the scalar type: without FLOAT64 the f64
    // source must be refused.
    let src = shaders::source(Stage::NodeUpdate, Precision::F64);
    let module = naga::front::wgsl::parse_str(&src).unwrap();
    let r = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module);
    assert!(r.is_err(), "f64 shader validated without FLOAT64");
}

#[test]
fn every_stage_builds_on_the_adapter() {
    let Some(ctx) = gpu_context("every_stage_builds_on_the_adapter", false) else {
        return;
    };
    let def = straight_cable(
        vacuum(),
        wire(),
        [0.0; 3],
        [10.0, 0.0, 0.0],
        10.0,
        4,
        Some(Route::Fixed { position: [0.0; 3] }),
        None,
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, pos) = Layout::build(&def).unwrap();
    for p in [Precision::F32, Precision::F64] {
        if !ctx.supports(p) {
            eprintln!(
                "{} has no SHADER_F64: f64 pipelines not built",
                ctx.describe()
            );
            continue;
        }
        // GpuSolver::new builds every pipeline inside a validation error scope.
        GpuSolver::new(&ctx, lay.clone(), &pos, SolverOptions::default(), p)
            .unwrap_or_else(|e| panic!("{}: {e}", p.name()));
    }
}
