//! What is simulated: line types, environment, routes, and the packed layout.

mod bathymetry;
pub mod bending;
pub mod cage;
pub(crate) mod environment;
mod failure;
mod layout;
mod line_type;
pub mod net;
pub(crate) mod route;
pub mod screen;

pub use bathymetry::Bathymetry;
pub use bending::{block_hinges, Clamp, Hinge, Joint, NO_ELEM};
pub use environment::{Current, Environment, Seabed};
pub use failure::{EndFailure, FailureEvent, FailureSite};
pub use layout::{Block, CableDef, CableInfo, Layout, ModelDef, NodeDef, PointMass, NO_CONSTRAINT};
pub use line_type::{LineCoefs, LineType, Viscoelastic};
pub use net::{add_net, NetShape, NetSpec};
pub use route::{circle_basis, Route, RouteState};
pub use screen::{ScreenKnot, ScreenModel, ScreenNet, Screens, WakeModel, NO_KNOT};
