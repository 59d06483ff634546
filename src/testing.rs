//! Internals that the tests in `tests/units/` reach into: the modules of `src/` that are
//! private, re-exported whole. Not part of the API (hidden from the docs); it may change
//! with any commit. A module's items that its tests use are `pub` in it, so that they
//! come through here; the module stays private to the crate.

pub mod ale_mass_flow {
    pub use crate::ale::mass_flow::*;
}

pub mod ale_mesh {
    pub use crate::ale::mesh::*;
}

pub mod ale_schedule {
    pub use crate::ale::schedule::*;
}

pub mod ale_winch {
    pub use crate::ale::winch::*;
}

pub mod cpu_chain_elements {
    pub use crate::cpu::chain::elements::*;
}

pub mod cpu_chain_lanes {
    pub use crate::cpu::chain::lanes::{KEEP, MAX_LANES};
}

pub mod cpu_chain_net_pieces {
    pub use crate::cpu::chain::net::pieces::*;
    pub use crate::cpu::chain::net::NT;
}

pub mod cpu_chain_net_plan {
    pub use crate::cpu::chain::net::plan::*;
    pub use crate::cpu::chain::net::NT;
}

pub mod gpu_wave_schedule {
    pub use crate::gpu::wave_schedule::*;
}

pub mod model_environment {
    pub use crate::model::environment::*;
}

pub mod model_route {
    pub use crate::model::route::*;
}

pub mod scenario_numbers {
    pub use crate::scenario::numbers::*;
}

pub mod scenario_warnings {
    pub use crate::scenario::warnings::*;
}

pub mod study_run_sea_check {
    pub use crate::study::run::sea_check::*;
}
