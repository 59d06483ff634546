//! The integration tests, in one binary: `cargo test` compiles and links the crate with
//! wgpu and naga once for them, instead of once for each of `tests/cpu`, `tests/gpu` and
//! `tests/cli` (Cargo.toml: those three are `test = false`, so `cargo test` builds and
//! runs only this one; each can still be built and run alone, `cargo test --release
//! --test cpu -- statics::`).
//!
//! Each module is one of the three, loaded from its own `main.rs` (their modules reach
//! each other through `super::`, which is the same path in both layouts). Filter by
//! module path: `cargo test --release --test all -- cpu::statics::`.

// Each of the three loads `tests/common` as its own `mod common` (each must, to build
// alone as its own target), so this binary holds three copies of it: on purpose.
#![allow(clippy::duplicate_mod)]

#[path = "cpu/main.rs"]
mod cpu;

#[path = "gpu/main.rs"]
mod gpu;

#[path = "cli/main.rs"]
mod cli;

#[path = "units/main.rs"]
mod units;
