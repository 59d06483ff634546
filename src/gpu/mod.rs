//! The GPU path: every cable of a run stepped together by WGSL compute shaders.
//!
//! So far: [`context`] (adapter choice, device and queue).

pub mod context;

pub use context::GpuContext;

/// Floating-point precision of the GPU shaders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Precision {
    /// 32-bit floats (every adapter); positions kept as compensated pairs.
    #[default]
    F32,
    /// 64-bit floats (adapters with `SHADER_F64`).
    F64,
}

impl Precision {
    /// Parses `f32 | f64`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "f32" => Some(Precision::F32),
            "f64" => Some(Precision::F64),
            _ => None,
        }
    }
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}
