//! `[limits]`: the work budget of a run (docs/src/scenario.md, "\[limits\]"), and the
//! estimate of the model's size from the file as written, made before any cable,
//! node or net is built: an absurd `count`, `segments` or `knots` is refused with the
//! estimate instead of growing memory until the machine runs out.

use super::err;
use super::raw::{RawNet, RawScenario};
use crate::error::Error;
use std::path::Path;

/// The work budget of a run. Each figure is checked before the work it bounds starts;
/// beyond it the run (and `check`) is refused with the estimate and how to raise it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Most node-steps (nodes times steps; ANCF: element nodes times steps).
    pub node_steps: f64,
    /// Most memory the model may take, GiB (estimated from its node count).
    pub memory_gib: f64,
    /// Most output the files may take, GiB (estimated from frames times rows).
    pub output_gib: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            node_steps: DEFAULT_NODE_STEPS,
            memory_gib: DEFAULT_MEMORY_GIB,
            output_gib: DEFAULT_OUTPUT_GIB,
        }
    }
}

/// Default node-step budget: 1e12 node-steps, about an hour and a half of the CPU chain
/// path on one thread (2e8 node-steps/s, `sim::estimate`), fifteen minutes on eight,
/// and more than any example, benchmark or design-check study here needs (the 30-member,
/// 3-hour study packed into one GPU run: 1.6e10). A run a person means to be this long raises
/// it (`[limits] node_steps`, `--limit node_steps=...`).
pub const DEFAULT_NODE_STEPS: f64 = 1e12;
/// Default memory budget, GiB.
pub const DEFAULT_MEMORY_GIB: f64 = 16.0;
/// Default output budget, GiB.
pub const DEFAULT_OUTPUT_GIB: f64 = 20.0;

/// Bytes of memory per node of a lumped-mass model, all copies together (the node as
/// described, the packed layout, the stepper's state and output buffers), rounded up
/// from a measured peak (benchmarks/history/BENCHMARKS-2026-12.md, "Model size and check time").
pub const BYTES_PER_NODE: f64 = 2048.0;
/// Bytes per cable (name, description, per-cable buffers).
pub const BYTES_PER_CABLE: f64 = 2048.0;

pub use super::raw::LimitOverrides;

impl LimitOverrides {
    /// Sets one limit from `KEY=VALUE` (the command line's `--limit`).
    pub fn set(&mut self, kv: &str) -> Result<(), String> {
        let (k, v) = kv
            .split_once('=')
            .ok_or_else(|| format!("--limit {kv}: expected KEY=VALUE"))?;
        let x: f64 = v
            .trim()
            .parse()
            .ok()
            .filter(|x: &f64| *x > 0.0 && x.is_finite())
            .ok_or_else(|| format!("--limit {kv}: \"{v}\" is not a positive number"))?;
        match k.trim() {
            "node_steps" => self.node_steps = Some(x),
            "memory_gib" => self.memory_gib = Some(x),
            "output_gib" => self.output_gib = Some(x),
            other => {
                return Err(format!(
                    "--limit {kv}: unknown limit \"{other}\" (node_steps, memory_gib, output_gib)"
                ))
            }
        }
        Ok(())
    }

    /// These limits over `base`.
    pub fn over(&self, base: Limits) -> Limits {
        Limits {
            node_steps: self.node_steps.unwrap_or(base.node_steps),
            memory_gib: self.memory_gib.unwrap_or(base.memory_gib),
            output_gib: self.output_gib.unwrap_or(base.output_gib),
        }
    }
}

/// The file's `[limits]`, validated, with `cli` over them.
pub fn resolve(p: &Path, raw: &LimitOverrides, cli: &LimitOverrides) -> Result<Limits, Error> {
    for (k, v) in [
        ("node_steps", raw.node_steps),
        ("memory_gib", raw.memory_gib),
        ("output_gib", raw.output_gib),
    ] {
        if let Some(x) = v {
            super::positive(p, &format!("limits.{k}"), x)?;
        }
    }
    Ok(cli.over(raw.over(Limits::default())))
}

/// How to raise limit `key`, in words.
pub fn how_to_raise(key: &str) -> String {
    format!("raise it with `[limits] {key} = ...` in the scenario or `--limit {key}=...` on the command line if the machine can take it")
}

/// Refuses a model whose node count, estimated from the file as written, would take
/// more memory than `limits.memory_gib`; names the entry that contributes most.
pub fn check_model_size(p: &Path, raw: &RawScenario, limits: &Limits) -> Result<(), Error> {
    let mut nodes = raw.points.len() as f64;
    let mut cables = 0.0;
    let mut biggest = (0.0, String::from("cables"));
    let mut note = |n: f64, c: f64, field: String| {
        nodes += n;
        cables += c;
        if n > biggest.0 {
            biggest = (n, field);
        }
    };
    for (i, c) in raw.cables.iter().enumerate() {
        note(
            c.total_segments().max(1) as f64 + 1.0,
            1.0,
            format!("cables[{i}] (\"{}\").segments", c.name),
        );
    }
    for (i, t) in raw.cable_arrays.iter().enumerate() {
        let count = t
            .get("count")
            .and_then(|v| v.as_integer())
            .unwrap_or(1)
            .max(1) as f64;
        let segments = t.get("segments").and_then(largest).unwrap_or(1.0).max(1.0);
        let name = t.get("name").and_then(|v| v.as_str()).unwrap_or("");
        note(
            count * (segments + 1.0),
            count,
            format!("cable_arrays[{i}] (\"{name}\").count"),
        );
    }
    for (i, n) in raw.nets.iter().enumerate() {
        let (nodes, twines) = net_size(n);
        note(nodes, twines, format!("nets[{i}] (\"{}\").knots", n.name));
    }
    let bytes = nodes * BYTES_PER_NODE + cables * BYTES_PER_CABLE;
    let gib = bytes / GIB;
    if !(gib <= limits.memory_gib) {
        return Err(err(
            p,
            biggest.1,
            format!(
                "the model would have about {nodes:.3e} nodes in {cables:.3e} cables, about {gib:.3} GiB of memory ({BYTES_PER_NODE} bytes a node), over the budget of {} GiB: use fewer or coarser cables, or {}",
                limits.memory_gib,
                how_to_raise("memory_gib")
            ),
        ));
    }
    Ok(())
}

/// Bytes in a GiB.
pub const GIB: f64 = (1u64 << 30) as f64;

/// Nodes and twines of a net as written (`add_net`: a knot grid, every twine between
/// neighbouring knots cut into `segments`).
fn net_size(n: &RawNet) -> (f64, f64) {
    let [a, b] = n.knots.map(|k| k.max(1) as f64);
    let seg = n.segments.unwrap_or(1).max(1) as f64;
    let twines = 2.0 * a * b;
    (a * b + twines * (seg - 1.0), twines)
}

/// The largest number in a value as written (a number, a list, `{ from, to }`,
/// `{ random = [..] }`): the most a varying key can take.
fn largest(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Float(x) => Some(*x),
        toml::Value::Array(a) => a.iter().filter_map(largest).reduce(f64::max),
        toml::Value::Table(t) => t.values().filter_map(largest).reduce(f64::max),
        _ => None,
    }
}
