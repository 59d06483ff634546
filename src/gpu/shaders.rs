//! WGSL sources of the compute stages, assembled for one precision.
//!
//! One source serves both precisions: a short generated header defines the scalar
//! alias `R` (`f32` or `f64`), the two-part `pi/2` used by the shaders' own sine
//! and cosine, Veltkamp's splitting constant and whether element stretches are formed
//! from compensated pairs (f32 only), the fused kernel's workgroup size `FUSED_WG` and
//! whether the run has waves (`WAVES`: see [`header_with`]), then comes
//! `shaders/shared/prelude.wgsl` (structs, bindings, physics),
//! `shaders/shared/step.wgsl` (one element and one node of a step) and
//! `shaders/shared/waves.wgsl` (wave kinematics), then the stage file.

use crate::options::Precision;

/// The shared prelude: structs, bindings and force functions.
pub const PRELUDE: &str = include_str!("../../shaders/shared/prelude.wgsl");

/// One element and one node of a step (`shaders/shared/step.wgsl`), appended after the
/// prelude: the functions the element and node passes and the fused kernel compose.
pub const STEP: &str = include_str!("../../shaders/shared/step.wgsl");

/// The wave kinematics (`shaders/shared/waves.wgsl`), appended after the prelude.
pub const WAVES: &str = include_str!("../../shaders/shared/waves.wgsl");

/// Free and pinned bodies and line failures (`shaders/shared/free_body.wgsl`).
pub const FREE_BODY: &str = include_str!("../../shaders/shared/free_body.wgsl");

/// A compute stage: one WGSL file in `shaders/`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// `shaders/element_forces.wgsl`: per-element GLMF loads.
    ElementForces,
    /// `shaders/node_update.wgsl`: per-node gather, mass solve, constraints, time
    /// update (and the evaluate pass for output).
    NodeUpdate,
    /// `shaders/fused_chain.wgsl`: one workgroup steps one block through a whole
    /// submission (element and node work of every step, state in workgroup memory).
    FusedSteps,
}

/// The fused kernel's workgroup size in [`source`] (the solver picks its own with
/// [`source_with`]).
pub const DEFAULT_FUSED_WORKGROUP: u32 = 64;

impl Stage {
    /// Every stage.
    pub const ALL: [Stage; 3] = [Stage::ElementForces, Stage::NodeUpdate, Stage::FusedSteps];

    /// The file name under `shaders/`.
    pub fn file(self) -> &'static str {
        match self {
            Stage::ElementForces => "element_forces.wgsl",
            Stage::NodeUpdate => "node_update.wgsl",
            Stage::FusedSteps => "fused_chain.wgsl",
        }
    }

    /// The stage's own WGSL (without header and prelude).
    pub fn body(self) -> &'static str {
        match self {
            Stage::ElementForces => include_str!("../../shaders/element_forces.wgsl"),
            Stage::NodeUpdate => include_str!("../../shaders/node_update.wgsl"),
            Stage::FusedSteps => include_str!("../../shaders/fused_chain.wgsl"),
        }
    }

    /// The compute entry points the stage defines.
    pub fn entry_points(self) -> &'static [&'static str] {
        match self {
            Stage::ElementForces => &["element_forces"],
            Stage::NodeUpdate => &[
                "node_update",
                "node_evaluate",
                "wave_refresh",
                "wave_refresh_due",
                "wave_refresh_elems",
                "free_bodies",
                "line_failures",
            ],
            Stage::FusedSteps => &["fused_steps"],
        }
    }
}

/// The generated header: the scalar alias and precision-specific constants, with the
/// fused kernel's workgroup size [`DEFAULT_FUSED_WORKGROUP`] and all the waves' code in
/// (`WAVES = true`, `WAVE_POINTS = true`), without bending (`BENDING = false`).
pub fn header(p: Precision) -> String {
    header_with(p, DEFAULT_FUSED_WORKGROUP, true, true, false)
}

/// The generated header with the fused kernel's workgroup size `fused_wg` and
/// `const WAVES: bool = waves`. The shared functions the step calls guard their waves
/// branches with `if WAVES && ...`, so a pipeline built with `waves = false` (the fused
/// kernel of a still-water run) has those branches folded away by the compiler rather
/// than carried: a software adapter such as lavapipe runs a branch no lane takes
/// through its masked code, which cost the still-water fused step 8-10% there
/// (BENCHMARKS.md, "The GPU step in waves: a per-element cache"). `waves = true` is
/// right for either kind of run (still water then takes the branches' still side at
/// run time), so the two-pass stages, built once per engine, always have it.
///
/// `const WAVE_POINTS: bool = wave_points` does the same for the waves' loads of point
/// masses (a node's own cache read, `point_waves`, and the water-acceleration load of
/// `gather_end`): false only where no node of the layout has a point mass with drag,
/// displaced or added mass (a chain's lines), where those branches are never taken.
/// It counts only with `waves`.
///
/// `const BENDING: bool = bending`: whether the run has bending stiffness, whose
/// hinge rows and shears then follow the elements' rows in `elems` and `elem_loads`
/// (`shaders/shared/step.wgsl`: `element_shear`); `BEND_WG`, the fused kernel's
/// shears in workgroup memory, is `fused_wg` with bending and 1 without, so a run
/// without bending keeps its workgroup memory and its code.
pub fn header_with(
    p: Precision,
    fused_wg: u32,
    waves: bool,
    wave_points: bool,
    bending: bool,
) -> String {
    let pio2 = std::f64::consts::FRAC_PI_2;
    let (ty, hi, lo, splitter, compensated, least_exp2) = match p {
        Precision::F32 => {
            let hi = pio2 as f32;
            (
                "f32",
                hi as f64,
                (pio2 - hi as f64) as f32 as f64,
                4097.0,
                true,
                -149.0,
            )
        }
        Precision::F64 => (
            "f64",
            pio2,
            6.123233995736766e-17,
            134217729.0,
            false,
            -1074.0,
        ),
    };
    // `{:e}` prints the shortest string that reads back to the same f64; the
    // abstract-float literal then converts exactly (f64) or to the same f32.
    format!(
        "// Generated by cablesim::gpu::shaders for {ty}.\n\
         alias R = {ty};\n\
         const PIO2_HI: R = {hi:e};\n\
         const PIO2_LO: R = {lo:e};\n\
         // Veltkamp's splitting constant, 2^(p/2) + 1 for a p-bit significand.\n\
         const SPLITTER: R = {splitter:e};\n\
         // Element stretches from compensated pairs (f32; f64 needs no help).\n\
         const COMPENSATED: bool = {compensated};\n\
         // The exponent of the least subnormal R, 2^-149 (f32) or 2^-1074 (f64).\n\
         const R_LEAST_EXP2: R = {least_exp2:?};\n\
         // Invocations per workgroup of the fused kernel (nodes per block at most).\n\
         const FUSED_WG: u32 = {fused_wg}u;\n\
         // Whether the run has waves (false: the waves branches fold away).\n\
         const WAVES: bool = {waves};\n\
         // Whether some node's point mass takes wave loads (false: those fold away).\n\
         const WAVE_POINTS: bool = {wave_points};\n\
         // Whether the run has bending stiffness (its hinge rows and shears).\n\
         const BENDING: bool = {bending};\n\
         const BEND_WG: u32 = {bend_wg}u;\n\n",
        bend_wg = if bending { fused_wg } else { 1 }
    )
}

/// The complete WGSL of `stage` at precision `p`: header (waves' code in, no
/// bending), prelude, stage body.
pub fn source(stage: Stage, p: Precision) -> String {
    source_with(stage, p, DEFAULT_FUSED_WORKGROUP, true, true, false)
}

/// The complete WGSL of `stage` at precision `p` with the fused kernel's workgroup
/// size `fused_wg` and the waves' branches in (`waves`; the point masses' with
/// `wave_points`) or folded away, with or without bending (see [`header_with`]).
pub fn source_with(
    stage: Stage,
    p: Precision,
    fused_wg: u32,
    waves: bool,
    wave_points: bool,
    bending: bool,
) -> String {
    let mut s = header_with(p, fused_wg, waves, wave_points, bending);
    s.push_str(PRELUDE);
    s.push('\n');
    s.push_str(STEP);
    s.push('\n');
    s.push_str(WAVES);
    s.push('\n');
    s.push_str(FREE_BODY);
    s.push('\n');
    s.push_str(stage.body());
    s
}

/// The prelude alone at precision `p` (header, prelude, a step's functions and wave
/// kinematics), for tests that add their own entry points.
pub fn prelude(p: Precision) -> String {
    let mut s = header(p);
    s.push_str(PRELUDE);
    s.push('\n');
    s.push_str(STEP);
    s.push('\n');
    s.push_str(WAVES);
    s.push('\n');
    s.push_str(FREE_BODY);
    s
}
