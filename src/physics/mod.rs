//! Force laws as small functions, generic over the float type.

pub mod axial;
pub mod bending;
pub mod catenary;
pub mod element;
pub mod frames;
pub mod screen;
pub mod seabed;
pub mod surface;
pub mod visco;

pub use axial::{tabulated_max_slope, tabulated_slope, tabulated_tension, tabulated_work};
pub use bending::{bending_angle, bending_energy, bending_hinge, hinge_stiffness};
pub use element::{
    axial_force, froude_krylov, glmf_element, glmf_element_wet, glmf_external, glmf_external_wet,
    Coefs, ElementInput, ElementLoads, ExternalLoads,
};
pub use screen::{
    screen_coefficients, screen_cylinder_cd, screen_panel_force, screen_wake_factor, ScreenCoefs,
};
pub use seabed::{
    seabed_damping, seabed_force, seabed_friction_axis, seabed_height, seabed_slope_damping,
    seabed_slope_force, seabed_slope_normal, SeabedCoefs,
};
pub use surface::{point_wetted_fraction, sphere_radius, wetted_fraction};
pub use visco::{visco_dynamic_stiffness, visco_rest_state, visco_tension};
