//! The library's own modules tested from outside: one file per module of `src/` that
//! had unit tests (`sea_kinematics.rs` holds those of `src/sea/kinematics.rs`). They were
//! `#[cfg(test)]` modules in `src/`; here `cargo test` builds them into `tests/all.rs`
//! (module `units`) instead of compiling the whole library a second time with
//! `cfg(test)` (benchmarks/history/BENCHMARKS-2026-12.md, "Test build"). The items they reach that are not part of
//! the API come through `cablesim::testing` (hidden from the docs). Also a binary of
//! its own, built only when named: `cargo test --release --test units -- sea_kinematics::`.

mod ale_mass_flow;
mod ale_mesh;
mod ale_schedule;
mod ale_winch;
mod ancf;
mod ancf_band;
mod ancf_shape;
mod body_free;
mod body_kinematics;
mod body_motion;
mod body_rao;
mod cpu_chain_elements;
mod cpu_chain_lanes;
mod cpu_chain_net_pieces;
mod cpu_chain_net_plan;
mod fatigue;
mod gpu_wave_schedule;
mod math;
mod model_bathymetry;
mod model_cage;
mod model_environment;
mod model_net;
mod model_route;
mod moordyn_parse;
mod physics_frames;
mod physics_seabed;
mod physics_surface;
mod scenario_materials;
mod scenario_numbers;
mod scenario_warnings;
mod scenario_wave_inputs;
mod scenario_waves;
mod sea_bands;
mod sea_cache;
mod sea_columns;
mod sea_cut;
mod sea_dispersion;
mod sea_irregular;
mod sea_kinematics;
mod sea_measured;
mod sea_poly;
mod sea_schedule;
mod sea_spectrum;
mod sim_reach;
mod stability;
mod study_channel_stats;
mod study_channels;
mod study_design;
mod study_gumbel;
mod study_members;
mod study_run_sea_check;
mod study_sampling;
