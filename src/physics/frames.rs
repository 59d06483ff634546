//! The older element frames (paper Sec. 2.1-2.3, 2.6): Euler, Frenet and RVEF.
//!
//! Placeholder: filled in by the frames work (see `frame_element`).

use super::element::{Coefs, ElementInput, ElementLoads};
use crate::math::{Real, V3};

/// An element frame used to express the hydrodynamic loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Frame {
    /// Two Euler angles from arctangents of node differences (Eqs. 7-9).
    Euler,
    /// Tangent/normal/binormal of a spline through the cable's nodes (Eqs. 13-16).
    Frenet,
    /// Relative-velocity element frame (Eqs. 17-19).
    Rvef,
}

impl Frame {
    /// Lower-case name, as in scenario files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Frame::Euler => "euler",
            Frame::Frenet => "frenet",
            Frame::Rvef => "rvef",
        }
    }
}

/// Loads of one element evaluated through `frame`. `virtual_mid` is the Frenet frame's
/// virtual node (the spline through the cable's nodes at the element's middle); the
/// other frames ignore it. Returns the reason when the frame is singular.
pub fn frame_element<T: Real>(
    frame: Frame,
    c: &Coefs<T>,
    e: &ElementInput<T>,
    virtual_mid: V3<T>,
) -> Result<ElementLoads<T>, String> {
    let _ = (frame, virtual_mid);
    Ok(super::element::glmf_element(c, e))
}

/// The Frenet frame's virtual node at the middle of element `(a, b)`, from the cubic
/// through the neighbouring nodes `prev` and `next` where they exist.
pub fn frenet_virtual_node<T: Real>(
    prev: Option<V3<T>>,
    a: V3<T>,
    b: V3<T>,
    next: Option<V3<T>>,
) -> V3<T> {
    let _ = (prev, next);
    (a + b) * T::c(0.5)
}
