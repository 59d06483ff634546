//! Every WGSL stage parses and validates (naga, both precisions, no GPU needed), and
//! builds into compute pipelines on the adapter when there is one.

use super::common::*;
use cablesim::gpu::shaders::{self, Stage};
use cablesim::gpu::{GpuSolver, Precision};
use cablesim::model::{Layout, PointMass, Route};
use cablesim::options::SolverOptions;
use std::collections::HashSet;

/// Parses and validates `stage` at `p` with the waves' code in or out (`waves`), the
/// point masses' waves code in or out on its own (`wave_points`).
fn validate_points(stage: Stage, p: Precision, waves: bool, wave_points: bool) -> naga::Module {
    validate_bending(stage, p, waves, wave_points, false)
}

/// [`validate_points`] with bending stiffness's code in or out (`bending`).
fn validate_bending(
    stage: Stage,
    p: Precision,
    waves: bool,
    wave_points: bool,
    bending: bool,
) -> naga::Module {
    let src = shaders::source_with(
        stage,
        p,
        shaders::DEFAULT_FUSED_WORKGROUP,
        waves,
        wave_points,
        bending,
    );
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
        for (stage, waves, bending) in Stage::ALL.into_iter().flat_map(|s| {
            [
                (s, true, false),
                (s, false, false),
                (s, true, true),
                (s, false, true),
            ]
        }) {
            let m = validate_bending(stage, p, waves, waves, bending);
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

/// Whether expression `e` of function `f` is false whatever the run: a literal or
/// constant `false` (the header's `WAVES` in a still-water source) or a load of a local
/// that `false_locals` holds (naga lowers `a && b` to `if a { t = b } else { t = false }`).
fn is_false(
    m: &naga::Module,
    f: &naga::Function,
    e: naga::Handle<naga::Expression>,
    false_locals: &HashSet<naga::Handle<naga::LocalVariable>>,
) -> bool {
    use naga::{Expression as E, Literal};
    match f.expressions[e] {
        E::Literal(Literal::Bool(false)) => true,
        E::Constant(c) => matches!(
            m.global_expressions[m.constants[c].init],
            E::Literal(Literal::Bool(false))
        ),
        E::Load { pointer } => matches!(
            f.expressions[pointer],
            E::LocalVariable(v) if false_locals.contains(&v)
        ),
        _ => false,
    }
}

/// The local that `block` ends by storing a value [`is_false`] into (naga's
/// short-circuit temporary of `a && b`: `t = b` on one side, `t = false` on the
/// other), if any.
fn stored_false(
    m: &naga::Module,
    f: &naga::Function,
    block: &naga::Block,
    false_locals: &HashSet<naga::Handle<naga::LocalVariable>>,
) -> Option<naga::Handle<naga::LocalVariable>> {
    match block.last() {
        Some(naga::Statement::Store { pointer, value }) => match f.expressions[*pointer] {
            naga::Expression::LocalVariable(v) if is_false(m, f, *value, false_locals) => Some(v),
            _ => None,
        },
        _ => None,
    }
}

/// Adds to `reached` the names of the functions that `block` of `f` can call, leaving
/// out the `accept` side of every `if` whose condition [`is_false`]. (A local is taken
/// for false only from such an `if`'s `reject` side: naga's short-circuit temporaries
/// are stored once on each side.)
fn calls_in(
    m: &naga::Module,
    f: &naga::Function,
    block: &naga::Block,
    false_locals: &mut HashSet<naga::Handle<naga::LocalVariable>>,
    reached: &mut HashSet<String>,
) {
    use naga::{Expression as E, Literal, Statement as S};
    for st in block.iter() {
        match st {
            S::Block(b) => calls_in(m, f, b, false_locals, reached),
            S::If {
                condition,
                accept,
                reject,
            } => {
                if is_false(m, f, *condition, false_locals) {
                    // Only `reject` runs: a short-circuit temporary it sets `false`
                    // stays false.
                    for st in reject.iter() {
                        if let S::Store { pointer, value } = st {
                            if let (E::LocalVariable(v), E::Literal(Literal::Bool(false))) =
                                (&f.expressions[*pointer], &f.expressions[*value])
                            {
                                false_locals.insert(*v);
                            }
                        }
                    }
                } else {
                    calls_in(m, f, accept, false_locals, reached);
                    // `a && b` with `b` false whatever the run (`WAVES && WAVE_POINTS`
                    // with the latter false): the temporary is false on both sides.
                    if let (Some(v), Some(w)) = (
                        stored_false(m, f, accept, false_locals),
                        stored_false(m, f, reject, false_locals),
                    ) {
                        if v == w {
                            false_locals.insert(v);
                        }
                    }
                }
                calls_in(m, f, reject, false_locals, reached);
            }
            S::Switch { cases, .. } => {
                for c in cases {
                    calls_in(m, f, &c.body, false_locals, reached);
                }
            }
            S::Loop {
                body, continuing, ..
            } => {
                calls_in(m, f, body, false_locals, reached);
                calls_in(m, f, continuing, false_locals, reached);
            }
            S::Call { function, .. } => {
                let g = &m.functions[*function];
                let name = g.name.clone().unwrap_or_default();
                if reached.insert(name) {
                    calls_in(m, g, &g.body, &mut HashSet::new(), reached);
                }
            }
            _ => {}
        }
    }
}

/// The functions the fused kernel's entry point can reach, `if false` sides left out.
fn fused_reaches(p: Precision, waves: bool) -> HashSet<String> {
    fused_reaches_points(p, waves, waves)
}

/// [`fused_reaches`] with the point masses' waves code in or out (`wave_points`).
fn fused_reaches_points(p: Precision, waves: bool, wave_points: bool) -> HashSet<String> {
    let m = validate_points(Stage::FusedSteps, p, waves, wave_points);
    let ep = m
        .entry_points
        .iter()
        .find(|e| e.name == "fused_steps")
        .expect("fused_steps");
    let mut reached = HashSet::new();
    calls_in(
        &m,
        &ep.function,
        &ep.function.body,
        &mut HashSet::new(),
        &mut reached,
    );
    reached
}

#[test]
fn the_still_water_fused_kernel_carries_no_waves_code() {
    // shaders::header_with(.., waves = false) sets `WAVES = false`, and every waves
    // branch of the step is `if WAVES && ..`: no call into the waves' cache is left
    // where it could run, so the compiler drops it (lavapipe ran those branches masked,
    // 8-10% of the still-water step). With the waves' code in, the same walk finds the
    // cache reads (so it does look into the branches).
    let cache_reads = [
        "elem_waves",
        "node_waves",
        "wave_mid_hermite",
        "wave_cache_hermite",
    ];
    for p in [Precision::F32, Precision::F64] {
        let with = fused_reaches(p, true);
        for f in cache_reads {
            assert!(
                with.contains(f),
                "{}: the waves kernel does not reach {f}",
                p.name()
            );
        }
        let without = fused_reaches(p, false);
        assert!(without.contains("element_step") && without.contains("gather_end"));
        for f in cache_reads {
            assert!(
                !without.contains(f),
                "{}: the still-water fused kernel can still call {f}",
                p.name()
            );
        }
    }
}

#[test]
fn the_fused_waves_kernel_of_lines_without_points_reads_no_node_cache() {
    // `WAVE_POINTS = false` (a layout whose nodes have no point mass taking wave loads,
    // gpu::engine layout_has_wave_points): the node pass's own cache read
    // (`point_waves` -> `node_waves`) is out of reach, while the elements' cache reads
    // stay (lavapipe ran the point branch masked for every node). The mixed elements
    // interpolate node b's values (`wave_cache_hermite`) from copies in their entry's
    // vec4 rows (`wave_mixed_b_load`): no scalar read of the nodes' cache
    // (`wave_cache_load7`, 14 loads a side) is left in the step, each of which lavapipe
    // ran for every element.
    for p in [Precision::F32, Precision::F64] {
        let lines = fused_reaches_points(p, true, false);
        for f in [
            "elem_waves",
            "wave_mid_load",
            "wave_mid_hermite",
            "wave_mixed_b_load",
            "wave_cache_hermite",
            "wave_band_weights",
        ] {
            assert!(
                lines.contains(f),
                "{}: lines only, {f} not reached",
                p.name()
            );
        }
        for f in ["node_waves", "wave_cache_load7"] {
            assert!(
                !lines.contains(f),
                "{}: lines only, the node cache read {f} is still reachable",
                p.name()
            );
        }
        let points = fused_reaches_points(p, true, true);
        for f in ["node_waves", "wave_cache_load7"] {
            assert!(points.contains(f), "{}: points, {f} not reached", p.name());
        }
    }
}
