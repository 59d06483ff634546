//! Kernel choice: the fused kernel or the two-pass one ([`GpuKernel`]), whether the
//! fused one applies to a layout ([`fused_workgroup`]), and the constants their
//! dispatches share (steps per submission, workgroup sizes).
//!
//! Split out of `solver.rs` so that the solver holds its API and this file the one
//! decision every engine and test makes first: which kernel steps this layout.

use crate::error::Error;
use crate::model::Layout;
use crate::options::Precision;

/// `Status::failed` of a blow-up found by the fused kernel (WGSL `FUSED_FAILED`).
pub(super) const FUSED_FAILED: u32 = 0x8000_0000;

/// Steps recorded in one command buffer (one submission).
pub const STEPS_PER_SUBMISSION: u32 = 512;

/// Invocations per workgroup of the two-pass stages (the shaders' `@workgroup_size`).
pub(super) const WORKGROUP: u32 = 64;

/// The largest workgroup the fused kernel uses (nodes or elements of a block at most).
pub const MAX_FUSED_WORKGROUP: u32 = 256;

/// Bytes of workgroup memory the fused kernel needs per invocation at precision `p`:
/// a node state and an element's loads, 9 scalars each, and with `bending` the
/// element's shear, 3 more.
pub(super) fn fused_bytes_per_lane(p: Precision, bending: bool) -> u32 {
    let r = match p {
        Precision::F32 => 4,
        Precision::F64 => 8,
    };
    (2 * 9 + if bending { 3 } else { 0 }) * r
}

/// How [`GpuSolver::advance`](super::solver::GpuSolver::advance) steps the layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GpuKernel {
    /// One workgroup per block advances it through a whole submission in one
    /// dispatch (`shaders/fused_chain.wgsl`), with the block's state in workgroup
    /// memory: for layouts whose blocks all have at most [`MAX_FUSED_WORKGROUP`]
    /// nodes and elements (and fit the adapter's workgroup memory), without winches.
    Fused,
    /// Two dispatches per step over the whole packed layout (`element_forces`, then
    /// `node_update`): any layout.
    TwoPass,
}

impl GpuKernel {
    /// `fused` or `two-pass`.
    pub fn name(self) -> &'static str {
        match self {
            GpuKernel::Fused => "fused",
            GpuKernel::TwoPass => "two-pass",
        }
    }
    /// Parses `fused | two-pass`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "fused" => Some(GpuKernel::Fused),
            "two-pass" => Some(GpuKernel::TwoPass),
            _ => None,
        }
    }
}

/// The fused kernel's workgroup size for this layout at precision `p` under `limits`,
/// or why the fused kernel cannot step it: the smallest multiple of 8 that holds the
/// nodes and the elements of every block, at most [`MAX_FUSED_WORKGROUP`] and what
/// the adapter's workgroup limits allow; no winch cables.
pub fn fused_workgroup(
    lay: &Layout,
    p: Precision,
    limits: &wgpu::Limits,
    winches: bool,
) -> Result<u32, String> {
    if winches {
        return Err("winch cables (their payout rows are per step and per dispatch)".into());
    }
    if lay.blocks.is_empty() {
        return Err("no blocks".into());
    }
    if lay.blocks.len() > limits.max_compute_workgroups_per_dimension as usize {
        return Err(format!(
            "{} blocks, more than the {} workgroups of one dispatch dimension",
            lay.blocks.len(),
            limits.max_compute_workgroups_per_dimension
        ));
    }
    let need = lay
        .blocks
        .iter()
        .map(|b| (b.node_end - b.node_start).max(b.elem_end - b.elem_start))
        .max()
        .unwrap_or(1);
    let per_lane = fused_bytes_per_lane(p, lay.has_bending());
    let cap = MAX_FUSED_WORKGROUP
        .min(limits.max_compute_invocations_per_workgroup)
        .min(limits.max_compute_workgroup_size_x)
        .min(limits.max_compute_workgroup_storage_size.saturating_sub(16) / per_lane / 8 * 8);
    // A multiple of 8 (a software adapter's SIMD width; a GPU runs whole warps anyway).
    let wg = need.max(1).div_ceil(8) * 8;
    if wg > cap {
        return Err(format!(
            "a block of {need} nodes or elements, more than the {cap} invocations the fused \
             kernel may use ({} bytes of workgroup memory each, {} available)",
            per_lane, limits.max_compute_workgroup_storage_size
        ));
    }
    Ok(wg)
}

/// The kernel the environment variable `CABLESIM_GPU_KERNEL` asks for (`fused`,
/// `two-pass`; unset, empty or `auto`: none).
pub(super) fn kernel_from_env() -> Result<Option<GpuKernel>, Error> {
    match std::env::var("CABLESIM_GPU_KERNEL") {
        Err(_) => Ok(None),
        Ok(v) if v.is_empty() || v == "auto" => Ok(None),
        Ok(v) => GpuKernel::parse(&v).map(Some).ok_or_else(|| {
            Error::Gpu(format!(
                "CABLESIM_GPU_KERNEL={v}: expected fused, two-pass or auto"
            ))
        }),
    }
}
