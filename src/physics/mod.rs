//! Force laws as small functions, generic over the float type.

pub mod catenary;
pub mod element;
pub mod frames;
pub mod seabed;

pub use element::{
    axial_force, glmf_element, glmf_external, Coefs, ElementInput, ElementLoads, ExternalLoads,
};
pub use seabed::{seabed_force, SeabedCoefs};
