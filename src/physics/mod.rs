//! Force laws as small functions, generic over the float type.

pub mod bending;
pub mod catenary;
pub mod element;
pub mod frames;
pub mod seabed;
pub mod surface;

pub use bending::{bending_angle, bending_energy, bending_hinge, hinge_stiffness};
pub use element::{
    axial_force, froude_krylov, glmf_element, glmf_element_wet, glmf_external, glmf_external_wet,
    Coefs, ElementInput, ElementLoads, ExternalLoads,
};
pub use seabed::{seabed_damping, seabed_force, SeabedCoefs};
pub use surface::{point_wetted_fraction, sphere_radius, wetted_fraction};
