//! Scenario files and the command line: parsing and its errors, every example,
//! end-to-end runs of the `cablesim` binary (studies among them), and the ANCF model
//! chosen from a scenario.
//!
//! One test binary (see `tests/cpu/main.rs` for why); shared helpers are in
//! `tests/common`.

#[path = "../common/mod.rs"]
mod common;

mod ancf_scenario;
mod end_to_end;
mod estimates;
mod examples;
mod fatigue;
mod fish_farm;
mod fuzz_scenarios;
mod logging;
mod moordyn_bending;
mod moordyn_bodies;
mod moordyn_curves;
mod moordyn_input;
mod moordyn_visco;
mod moordyn_waves;
mod output_formats;
mod robust_inputs;
mod robust_runs;
mod scenario;
mod simulation_api;
mod slurm;
mod study_conditions;
mod study_run;
mod viz_output;
mod wave_inputs;
