//! How long a lumped-mass run will take, estimated before it starts: its node-steps
//! over the measured rate of the path that will step them (docs/src/benchmarks.md,
//! "The rates behind the estimates").
//!
//! The rates are constants, not a calibration on the machine at hand: `cablesim check`
//! opens no GPU adapter and solves no statics, and a calibration would need both (a
//! run's set-up takes from milliseconds to minutes); the estimate is a guide to the
//! order of magnitude (a machine twice as fast halves it), and the work budget refuses
//! runs by their node-steps, which do not depend on the machine.

use crate::model::Layout;
use crate::options::{Formulation, Precision, Scheme, SolverOptions};

/// Node-steps per second of the vectorised CPU chain path on one thread, symplectic
/// scheme, still water: the catenary example's line, 1 to 100 lines, 1.91e8 to 2.16e8
/// (BENCHMARKS.md, peers re-run on an AMD EPYC (Zen 5) host, 2026-12-03).
pub const CPU_CHAIN_RATE: f64 = 2.0e8;
/// The same for the vectorised network path: the net cage (4,096 nodes) on one thread,
/// a median 7.46e7 (BENCHMARKS.md, the same host and day).
pub const CPU_NETWORK_RATE: f64 = 7.5e7;
/// The same for the general CPU passes (the formulations other than GLMF, networks
/// outside the network path): Case 1 with `--formulation rvef`, 1.1e7 (BENCHMARKS.md,
/// "Whole examples" of the history, 2026-11-22, an AMD EPYC host).
pub const CPU_GENERAL_RATE: f64 = 1.1e7;
/// How much slower a step in waves is than in still water on the CPU: 1.26x to 1.49x
/// (BENCHMARKS.md, the design member and the criterion bench, 2026-12-03).
pub const CPU_WAVES_FACTOR: f64 = 1.5;
/// Share of a thread a second thread adds on one big network (the net cage: 1.53x on
/// two threads, BENCHMARKS.md, 2026-12-03).
pub const CPU_THREAD_SHARE: f64 = 0.75;
/// Node-steps per second of the GPU path on a software adapter (lavapipe) for a large
/// fleet: 8e6 to 1.2e7 (BENCHMARKS.md, "GPU path against the CPU path", 2026-11-22).
pub const GPU_SOFTWARE_RATE: f64 = 1.0e7;
/// Node-steps per second of the GPU path on a datacenter GPU, f32 and f64: the
/// bandwidth limit **predicted** for an H100 for a large model (BENCHMARKS.md, "Bytes
/// and flops per node-step of the GPU step"); no hardware GPU was measured, and a small
/// model is bound by dispatch latency, so on the GPU the estimate is a lower bound.
pub const GPU_HARDWARE_RATE: [f64; 2] = [1.1e10, 6.2e9];

/// Where a run's steps go, for the estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Path {
    /// The CPU path on this many threads.
    Cpu(usize),
    /// The GPU path on a software adapter.
    GpuSoftware,
    /// The GPU path on a hardware adapter, at this precision.
    Gpu(Precision),
}

/// A run's work and the wall time it is estimated to take.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Nodes times steps.
    pub node_steps: f64,
    /// Estimated seconds of stepping.
    pub seconds: f64,
    /// The path and the rate it was estimated with, in words.
    pub how: String,
}

impl Estimate {
    /// The estimate as one clause: "1.1e13 node-steps, about 15 h on the CPU path (...)".
    pub fn describe(&self) -> String {
        format!(
            "{:.3e} node-steps, about {} {}",
            self.node_steps,
            duration_words(self.seconds),
            self.how
        )
    }
}

/// `s` seconds in words at a useful precision ("0.4 s", "12 min", "3.2 h", "41 days").
pub fn duration_words(s: f64) -> String {
    if !s.is_finite() {
        return "for ever".into();
    }
    if s < 0.01 {
        "under 0.01 s".into()
    } else if s < 60.0 {
        format!("{s:.2} s")
    } else if s < 3600.0 {
        format!("{:.1} min", s / 60.0)
    } else if s < 172_800.0 {
        format!("{:.1} h", s / 3600.0)
    } else if s < 3.15e9 {
        format!("{:.1} days", s / 86_400.0)
    } else {
        format!("{:.1e} years", s / 3.156e7)
    }
}

/// Force evaluations per step of a scheme.
fn evaluations(scheme: Scheme) -> f64 {
    match scheme {
        Scheme::Symplectic => 1.0,
        Scheme::Rk2 => 2.0,
        Scheme::Rk4 => 4.0,
    }
}

/// The estimate of `steps` steps of `lay` on `path` (`waves`: a sea that is not still).
pub fn lumped(lay: &Layout, opts: &SolverOptions, steps: u64, waves: bool, path: Path) -> Estimate {
    let nodes = lay.n_nodes() as f64;
    let node_steps = nodes * steps as f64;
    let evals = evaluations(opts.scheme);
    let sea = if waves { " in waves" } else { "" };
    let (seconds, how) = match path {
        Path::Cpu(threads) => {
            let threads = threads.max(1);
            let glmf = opts.formulation == Formulation::Glmf;
            // Seconds of one thread per step, over the blocks; the blocks run in
            // parallel (a big network on every thread).
            let (mut serial, mut biggest) = (0.0f64, 0.0f64);
            let mut paths = Vec::new();
            for b in &lay.blocks {
                let n = (b.node_end - b.node_start) as f64;
                let (rate, name) = if b.is_chain && glmf {
                    (CPU_CHAIN_RATE, "chain")
                } else if !b.is_chain && glmf && opts.scheme == Scheme::Symplectic {
                    (CPU_NETWORK_RATE, "network")
                } else {
                    (CPU_GENERAL_RATE, "general")
                };
                if !paths.contains(&name) {
                    paths.push(name);
                }
                let t = n / rate;
                serial += t;
                biggest = biggest.max(t);
            }
            let blocks = lay.blocks.len().max(1);
            let per_step = if blocks == 1 {
                // One block: a network is split over the threads, a chain is not.
                let split = !lay.blocks.first().is_some_and(|b| b.is_chain);
                if split && threads > 1 {
                    serial / (1.0 + CPU_THREAD_SHARE * (threads - 1) as f64)
                } else {
                    serial
                }
            } else {
                (serial / threads.min(blocks) as f64).max(biggest)
            };
            let waves_factor = if waves { CPU_WAVES_FACTOR } else { 1.0 };
            let seconds = per_step * evals * waves_factor * steps as f64;
            (
                seconds,
                format!(
                    "on the CPU path ({} path{}, {threads} thread{}{sea}; {} node-steps/s)",
                    paths.join(" and "),
                    if paths.len() > 1 { "s" } else { "" },
                    if threads > 1 { "s" } else { "" },
                    rate_words(node_steps, seconds),
                ),
            )
        }
        Path::GpuSoftware => {
            let seconds = node_steps * evals / GPU_SOFTWARE_RATE;
            (
                seconds,
                format!(
                    "on the GPU path on a software adapter ({} node-steps/s as measured on lavapipe)",
                    rate_words(node_steps, seconds)
                ),
            )
        }
        Path::Gpu(p) => {
            let rate = GPU_HARDWARE_RATE[(p == Precision::F64) as usize];
            let seconds = node_steps * evals / rate;
            (
                seconds,
                format!(
                    "at least, on the GPU path at {} ({rate:.1e} node-steps/s: the bandwidth limit predicted for a datacenter GPU, not measured; a small model runs slower)",
                    p.name()
                ),
            )
        }
    };
    Estimate {
        node_steps,
        seconds,
        how,
    }
}

fn rate_words(node_steps: f64, seconds: f64) -> String {
    if seconds > 0.0 {
        format!("{:.1e}", node_steps / seconds)
    } else {
        "-".into()
    }
}
