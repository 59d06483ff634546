//! Node-steps per second against the number of cables, for every path in one run:
//! the CPU path on one core and on all cores, and the GPU path at f32 and f64 on the
//! adapter at hand (wgpu's choice, honouring `WGPU_BACKEND` / `WGPU_ADAPTER_NAME`),
//! each with the fused kernel (one workgroup per cable, a whole submission of steps
//! per dispatch) and with the two-pass kernel (two dispatches per step).
//!
//! ```sh
//! cargo bench --bench gpu_vs_cpu                                  # the default table
//! cargo bench --bench gpu_vs_cpu -- --cables 1,10,100 --segments 100 --seconds 2
//! ```
//!
//! Options (after `--`): `--cables LIST` (default `1,10,100,1000,10000`), `--segments N`
//! (elements per cable, default 50: the catenary example's 51-node line, the line
//! `scripts/compare_peers.py` gives MoorDyn), `--seconds S` (wall time aimed at per
//! measurement, default 1), `--repeats N` (best of, default 3), `--paths LIST` (any of
//! `cpu1,cpu,gpu32,gpu64,gpu32tp,gpu64tp`: `gpu32`/`gpu64` the fused kernel, the `tp`
//! ones the two-pass kernel), `--gpu-max-nodes N` (skip GPU sizes above it, default
//! unlimited), `--dt S` (default 1e-4 s, as `benches/lib.rs`), `--steps N` (exactly `N`
//! steps per path, once, no warm-up: for instruction counts under callgrind, taken as
//! the difference of two step counts), `--waves` (every path in a 200-component
//! JONSWAP sea, Hs 4 m, Tp 9 s, in 100 m of water, as `benches/waves.rs`: through each
//! path's kinematics cache at its default tolerance).
//!
//! `--buoys LIST` (e.g. `--buoys 1000`) runs a fleet of moored buoys instead: each a free
//! rigid body (`motion = "free"`, the buoy of `examples/moored_buoy.toml`) on three
//! lines of `--segments` elements (default here 20), the buoys 200 m apart, every buoy
//! one body of the one dispatch of the GPU's body stage; each size is followed by a
//! row of the same lines with their fairleads fixed where the buoy holds them (the
//! `fixed` row), so that a free body's cost per step is the difference of the two
//! rows' wall times per step over the number of buoys (printed as "a body costs").
//!
//! The model is `benches/common`'s fleet: copies of the catenary example's line, each
//! between its anchor and fairlead, starting straight in a 0.5 m/s current, so tension,
//! drag and seabed contact are all active. Each figure is nodes x steps / wall seconds
//! of `advance` alone (the GPU's includes its one status read-back per call, i.e. the
//! full synchronisation), after a warm-up step, best of `--repeats`. The `us/step` columns
//! are wall time per step: at one cable that is the fixed cost of a step (for the GPU,
//! the dispatches' encoding, submission and execution overhead).

mod common;

use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuContext, GpuKernel, GpuSolver, GpuTimings, Precision};
use cablesim::options::SolverOptions;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::SeaState;
use std::time::Instant;

struct Args {
    cables: Vec<usize>,
    segments: usize,
    seconds: f64,
    repeats: usize,
    paths: Vec<String>,
    gpu_max_nodes: usize,
    dt: f64,
    /// Exactly this many steps per path, timed once (for instruction counts).
    steps: Option<u64>,
    /// Run in a 200-component JONSWAP sea.
    waves: bool,
    /// Fleets of moored free buoys (three lines each) instead of the cables.
    buoys: Vec<usize>,
}

/// `n` buoys on three lines of `segments` elements each (free bodies), or, with
/// `free` false, the same lines with their fairleads fixed where the buoys hold them.
fn buoys(n: usize, segments: usize, free: bool) -> (cablesim::model::Layout, Vec<[f64; 3]>) {
    let mut s = String::from(
        r#"
[simulation]
duration = 1.0
output_interval = 1.0
backend = "cpu"

[environment]
depth = 50.0
current = [0.3, 0.0, 0.0]

[[line_types]]
name = "chain"
diameter = 0.05
mass_per_length = 2.5
ea = 1.0e7
damping = 2.0e-3
cn = 1.2
ct = 0.2
cm = 1.0
"#,
    );
    for j in 0..n {
        let (x0, y0) = ((j % 32) as f64 * 200.0, (j / 32) as f64 * 200.0);
        if free {
            s += &format!(
                r#"
[[bodies]]
name = "b{j}"
motion = "free"
reference = [{x0}, {y0}, -20.0]
offset = [1.0, 0.0, 0.0]
mass = 2000.0
cg = [0.0, 0.0, -0.5]
inertia = [2000.0, 2000.0, 3000.0]
volume = 3.0
ca = [1.0, 1.0, 1.0]
drag_area = [2.0, 2.0, 2.0]
rotational_drag = [20.0, 20.0, 10.0]
"#
            );
        }
        for k in 0..3 {
            let a = (120.0 * k as f64).to_radians();
            let (c, sn) = (a.cos(), a.sin());
            let end = if free {
                format!(
                    "{{ body = \"b{j}\", at = [{}, {}, -1.0] }}",
                    1.5 * c,
                    1.5 * sn
                )
            } else {
                format!(
                    "{{ fixed = [{}, {}, -21.0] }}",
                    x0 + 1.0 + 1.5 * c,
                    y0 + 1.5 * sn
                )
            };
            s += &format!(
                r#"
[[cables]]
name = "b{j}_{k}"
line_type = "chain"
length = 68.0
segments = {segments}
start = {{ fixed = [{}, {}, -50.0] }}
end = {end}
"#,
                x0 + 60.0 * c,
                y0 + 60.0 * sn
            );
        }
    }
    let sc = cablesim::scenario::Scenario::parse(&s, std::path::Path::new("buoys.toml")).unwrap();
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    (lay, pos)
}

/// The sea of `--waves` (the one of `benches/waves.rs`).
fn jonswap(depth: f64) -> SeaState {
    let spectrum = Spectrum::Jonswap {
        hs: 4.0,
        tp: 9.0,
        gamma: 3.3,
    };
    let d = Discretisation {
        components: 200,
        direction: 0.0,
        spreading: None,
        seed: 1,
        stream: 0,
    };
    SeaState {
        components: discretise(&spectrum, &d, depth, 9.81),
        ..SeaState::still(depth)
    }
}

fn args() -> Args {
    let mut a = Args {
        cables: vec![1, 10, 100, 1000, 10000],
        segments: 50,
        seconds: 1.0,
        repeats: 3,
        paths: ["cpu1", "cpu", "gpu32", "gpu64", "gpu32tp", "gpu64tp"]
            .map(String::from)
            .to_vec(),
        gpu_max_nodes: usize::MAX,
        dt: 1e-4,
        steps: None,
        waves: false,
        buoys: Vec::new(),
    };
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let mut i = 0;
    while i < argv.len() {
        let val = || argv.get(i + 1).cloned().unwrap_or_default();
        match argv[i].as_str() {
            "--cables" => a.cables = val().split(',').map(|x| x.parse().unwrap()).collect(),
            "--segments" => a.segments = val().parse().unwrap(),
            "--seconds" => a.seconds = val().parse().unwrap(),
            "--repeats" => a.repeats = val().parse().unwrap(),
            "--paths" => a.paths = val().split(',').map(String::from).collect(),
            "--gpu-max-nodes" => a.gpu_max_nodes = val().parse().unwrap(),
            "--dt" => a.dt = val().parse().unwrap(),
            "--steps" => a.steps = Some(val().parse().unwrap()),
            "--buoys" => a.buoys = val().split(',').map(|x| x.parse().unwrap()).collect(),
            "--waves" => {
                a.waves = true;
                i += 1;
                continue;
            }
            // `cargo bench` passes `--bench`; ignore it and anything unknown.
            _ => {
                i += 1;
                continue;
            }
        }
        i += 2;
    }
    a
}

/// Best node-steps/s and seconds per step of `step(n)` over `repeats` timed runs of
/// about `seconds` each (after a probe that also warms up).
fn measure(
    nodes: usize,
    seconds: f64,
    repeats: usize,
    exact: Option<u64>,
    mut step: impl FnMut(u64),
) -> (f64, f64) {
    if let Some(n) = exact {
        let t0 = Instant::now();
        step(n);
        let s = t0.elapsed().as_secs_f64();
        return (nodes as f64 * n as f64 / s, s / n.max(1) as f64);
    }
    // Warm-up (the first GPU submission compiles and uploads), then probe: grow the
    // step count until a call takes 50 ms or more.
    step(1);
    let mut n = 1u64;
    let per_step = loop {
        let t0 = Instant::now();
        step(n);
        let s = t0.elapsed().as_secs_f64();
        if s >= 0.05 || n >= 1 << 24 {
            break s / n as f64;
        }
        n *= 4;
    };
    let n = ((seconds / per_step).round() as u64).max(1);
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let t0 = Instant::now();
        step(n);
        best = best.min(t0.elapsed().as_secs_f64());
    }
    (nodes as f64 * n as f64 / best, best / n as f64)
}

/// `b - a`, field by field.
fn since(b: GpuTimings, a: GpuTimings) -> GpuTimings {
    GpuTimings {
        steps: b.steps - a.steps,
        dispatches: b.dispatches - a.dispatches,
        submissions: b.submissions - a.submissions,
        encode_seconds: b.encode_seconds - a.encode_seconds,
        submit_seconds: b.submit_seconds - a.submit_seconds,
        wait_seconds: b.wait_seconds - a.wait_seconds,
        advance_seconds: b.advance_seconds - a.advance_seconds,
    }
}

fn sci(x: f64) -> String {
    if x.is_nan() {
        "-".into()
    } else {
        format!("{x:.2e}")
    }
}

fn main() {
    let a = args();
    let threads = rayon::current_num_threads();
    let ctx = GpuContext::new(false).ok();
    let device = ctx
        .as_ref()
        .map_or("no adapter".to_string(), |c| c.describe());
    let f64_ok = ctx.as_ref().is_some_and(|c| c.supports(Precision::F64));
    eprintln!(
        "CPU: {} ({threads} threads); GPU: {device}",
        cablesim::sim::cpu_name()
    );
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let want = |p: &str| a.paths.iter().any(|x| x == p);
    let mut split: Vec<(usize, usize, Precision, GpuKernel, GpuTimings)> = Vec::new();
    println!(
        "| cables | nodes | CPU 1 core | CPU {threads} cores | GPU f32 fused | GPU f32 two-pass | GPU f64 fused | GPU f64 two-pass | \
         CPU 1 core us/step | f32 fused us/step | f32 two-pass us/step | f64 fused us/step | f64 two-pass us/step |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    // The cases: cables of the fleet, or buoys (free, then their lines fixed).
    let cases: Vec<(usize, Option<bool>)> = if a.buoys.is_empty() {
        a.cables.iter().map(|&n| (n, None)).collect()
    } else {
        a.buoys
            .iter()
            .flat_map(|&n| [(n, Some(true)), (n, Some(false))])
            .collect()
    };
    let segments = if a.buoys.is_empty() || std::env::args().any(|x| x == "--segments") {
        a.segments
    } else {
        20
    };
    // Per buoy count: us/step of the free buoys and of their fixed lines, per path.
    let mut per_step: Vec<(usize, bool, [f64; 5])> = Vec::new();
    for &(nc, buoy) in &cases {
        let (lay, pos) = match buoy {
            None => common::fleet(nc, segments),
            Some(free) => buoys(nc, segments, free),
        };
        let nodes = lay.n_nodes();
        let opts = SolverOptions {
            dt: a.dt,
            ..Default::default()
        };
        let nan = (f64::NAN, f64::NAN);
        let sea = if a.waves {
            jonswap(lay.env.depth)
        } else {
            SeaState::still(lay.env.depth)
        };
        let cpu1 = if want("cpu1") {
            let mut s = CpuSolver::new(lay.clone(), &pos, opts);
            s.set_sea(&sea, false);
            one.install(|| {
                measure(nodes, a.seconds, a.repeats, a.steps, |n| {
                    s.advance(n).unwrap()
                })
            })
        } else {
            nan
        };
        let cpu = if want("cpu") {
            let mut s = CpuSolver::new(lay.clone(), &pos, opts);
            s.set_sea(&sea, false);
            measure(nodes, a.seconds, a.repeats, a.steps, |n| {
                s.advance(n).unwrap()
            })
        } else {
            nan
        };
        let mut gpu = |p: Precision, k: GpuKernel| {
            let tp = if k == GpuKernel::TwoPass { "tp" } else { "" };
            let ok = match p {
                Precision::F32 => want(&format!("gpu32{tp}")),
                Precision::F64 => want(&format!("gpu64{tp}")) && f64_ok,
            };
            match (&ctx, ok && nodes <= a.gpu_max_nodes) {
                (Some(ctx), true) => {
                    let mut s = GpuSolver::new(ctx, lay.clone(), &pos, opts, p).unwrap();
                    if let Err(e) = s.set_kernel(k) {
                        eprintln!("{nc} cables, {}: {e}", p.name());
                        return nan;
                    }
                    s.set_sea(&sea).unwrap();
                    s.advance(1).unwrap();
                    let t0 = s.timings();
                    let m = measure(nodes, a.seconds, a.repeats, a.steps, |n| {
                        s.advance(n).unwrap()
                    });
                    split.push((nc, nodes, p, k, since(s.timings(), t0)));
                    m
                }
                _ => nan,
            }
        };
        let g32 = gpu(Precision::F32, GpuKernel::Fused);
        let g32tp = gpu(Precision::F32, GpuKernel::TwoPass);
        let g64 = gpu(Precision::F64, GpuKernel::Fused);
        let g64tp = gpu(Precision::F64, GpuKernel::TwoPass);
        let label = match buoy {
            None => format!("{nc}"),
            Some(true) => format!("{nc} buoys"),
            Some(false) => format!("{nc} buoys' lines, fixed"),
        };
        if let Some(free) = buoy {
            per_step.push((nc, free, [cpu.1, g32.1, g32tp.1, g64.1, g64tp.1]));
        }
        println!(
            "| {label} | {nodes} | {} | {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
            sci(cpu1.0),
            sci(cpu.0),
            sci(g32.0),
            sci(g32tp.0),
            sci(g64.0),
            sci(g64tp.0),
            cpu1.1 * 1e6,
            g32.1 * 1e6,
            g32tp.1 * 1e6,
            g64.1 * 1e6,
            g64tp.1 * 1e6
        );
    }
    for (nc, free, t) in &per_step {
        if !free {
            continue;
        }
        let Some((_, _, f)) = per_step.iter().find(|(m, fr, _)| m == nc && !fr) else {
            continue;
        };
        let nodes = nc * 3 * (segments + 1);
        let names = [
            "CPU all cores",
            "GPU f32 fused",
            "GPU f32 two-pass",
            "GPU f64 fused",
            "GPU f64 two-pass",
        ];
        for k in 0..5 {
            if t[k].is_nan() || f[k].is_nan() {
                continue;
            }
            let body = (t[k] - f[k]) / *nc as f64;
            let node = f[k] / nodes as f64;
            println!(
                "{nc} buoys, {}: a body costs {:.3e} us/step, a line node {:.3e} us/step: a body = {:.1} nodes",
                names[k],
                body * 1e6,
                node * 1e6,
                body / node
            );
        }
    }
    if !split.is_empty() {
        println!();
        println!(
            "GPU path: where the host's wall time went, per step, over every `advance` call above \
             (record: route/parameter writes and encoding the dispatches; wait: device work the \
             host could not overlap, and the status read-back)"
        );
        println!();
        println!("| cables | nodes | precision | kernel | us/step | record us/step | submit us/step | wait us/step | steps | dispatches |");
        println!("|---:|---:|---|---|---:|---:|---:|---:|---:|---:|");
        for (nc, nodes, p, k, t) in &split {
            let per = |x: f64| 1e6 * x / t.steps.max(1) as f64;
            println!(
                "| {nc} | {nodes} | {} | {} | {:.1} | {:.2} | {:.2} | {:.1} | {} | {} |",
                p.name(),
                k.name(),
                per(t.advance_seconds),
                per(t.encode_seconds),
                per(t.submit_seconds),
                per(t.wait_seconds),
                t.steps,
                t.dispatches
            );
        }
    }
}
