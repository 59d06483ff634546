//! Winch cables (ALE-GLMF) on the GPU path against the CPU path.
//!
//! - GPU f64 against CPU f64 through payout and retrieval (nodes inserted, then
//!   deleted), winch at either end of the cable: the same mesh (node count, inserted
//!   and deleted counts, physical coordinates) after every remeshing, positions,
//!   velocities, tensions and the winch reaction to round-off, with the tolerances
//!   derived as in tests/gpu/parity.rs (`N` steps of a damped model perturbed by a few
//!   ulps per step: `|dr| <= 10 N eps L`, and from it the velocity and tension bounds);
//!   and the same with several cables in one packed layout, remeshing at different
//!   steps.
//! - GPU f32 against CPU f64 on `examples/winch_deploy.toml` (its whole 150 s) and on
//!   `examples/case2_circle.toml` shortened to 100 s: the last node within `1e-4` of
//!   the deployed length, both end forces within 1%, the same mesh throughout.
//! - The mass in the water from the GPU's own evaluation (twice the half masses it
//!   computed) equals `mbar L(t)`, and the read-back layout's fixed elements plus the
//!   variable element add up to `L(t)`.
//! - A winch that does not move leaves the GPU path bitwise the plain GPU path.
//! - `cablesim run examples/winch_deploy.toml --backend gpu` runs on the GPU and agrees
//!   with `--backend cpu`; `--backend auto` still picks the CPU on a software adapter.

use super::common::*;
use super::compare::{dist, end_forces, norm, Check, Place, RoundOff, Snapshot};
use cablesim::ale::{PayoutSchedule, Winch, WinchEnd};
use cablesim::cpu::{CpuSolver, Evaluation};
use cablesim::gpu::{GpuContext, GpuSolver, Precision};
use cablesim::model::{Layout, ModelDef, PointMass, Route};
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use std::process::Command;
use std::sync::Arc;

const EPS: f64 = f64::EPSILON;

const TOP: [f64; 3] = [0.0, 0.0, -2.0];

/// A cable of `n` elements of `l_s` hanging straight down from a winch held at `TOP`
/// in a current (so that it swings out), a clump at the far end; the winch is at the
/// cable's start or end node.
fn hanging(n: usize, l_s: f64, end: WinchEnd) -> ModelDef {
    let bottom = [TOP[0], TOP[1], TOP[2] - n as f64 * l_s];
    let held = Some(Route::Fixed { position: TOP });
    let clump = PointMass {
        mass: 20.0,
        volume: 20.0 / 7800.0,
        drag_area: 0.05,
        added_mass_coef: 1.0,
    };
    let current = [0.6, 0.2, 0.0];
    match end {
        WinchEnd::Start => straight_cable(
            water(),
            rope(),
            TOP,
            bottom,
            n as f64 * l_s,
            n,
            held,
            None,
            clump,
            current,
        ),
        WinchEnd::End => {
            let mut d = straight_cable(
                water(),
                rope(),
                bottom,
                TOP,
                n as f64 * l_s,
                n,
                None,
                held,
                PointMass::default(),
                current,
            );
            d.nodes[0].point = clump;
            d
        }
    }
}

/// Pays out 6 m (ramp to 3 m/s, hold, ramp down: `Lddot` nonzero on the ramps) and
/// hauls the same 6 m back in.
fn out_and_back() -> PayoutSchedule {
    PayoutSchedule::rates(&[
        (0.0, 0.0),
        (0.5, 3.0),
        (2.0, 3.0),
        (2.5, 0.0),
        (3.0, -3.0),
        (4.5, -3.0),
        (5.0, 0.0),
    ])
    .unwrap()
}

fn winch(end: WinchEnd, schedule: PayoutSchedule, l_s: f64) -> Winch {
    Winch {
        cable: 0,
        end,
        schedule: Arc::new(schedule),
        drum_length: 100.0,
        element_length: l_s,
    }
}

fn max_of(it: impl Iterator<Item = f64>) -> f64 {
    it.fold(0.0, f64::max)
}

/// Mass of cable `c` in the water from an evaluation (twice each element's half mass),
/// and the deployed length from the layout's element lengths with the variable
/// element's `l0` now.
fn mass_and_length(lay: &Layout, ev: &Evaluation, c: usize, var: usize, var_l0: f64) -> (f64, f64) {
    let cab = &lay.cables[c];
    let mass = cab
        .elements
        .iter()
        .map(|&e| 2.0 * ev.elements[e as usize].half_mass)
        .sum();
    let len = cab
        .elements
        .iter()
        .map(|&e| {
            if e as usize == var {
                var_l0
            } else {
                lay.elem_l0[e as usize]
            }
        })
        .sum();
    (mass, len)
}

/// The packed index of the variable element of cable `c`, winch at `end`.
fn variable_element(lay: &Layout, c: usize, end: WinchEnd) -> usize {
    let e = &lay.cables[c].elements;
    match end {
        WinchEnd::Start => e[0] as usize,
        WinchEnd::End => e[e.len() - 1] as usize,
    }
}

/// Runs `def` with `winches` on the CPU (f64, general path) and the GPU (f64) for
/// `steps` steps of `dt`, comparing every 500 steps: the winch status of every winch
/// and the layout are identical, positions, velocities, tensions, end forces and
/// reactions within the round-off bounds of tests/gpu/parity.rs, and the mass in the
/// water of each winch cable from the GPU's half masses is `mbar L(t)`. Returns the
/// element counts each winch cable went through, and the final winch status.
fn compare_f64(
    ctx: &GpuContext,
    label: &str,
    def: ModelDef,
    winches: Vec<Winch>,
    dt: f64,
    steps: u64,
) -> (Vec<Vec<usize>>, Vec<cablesim::cpu::WinchStatus>, u64) {
    let chunk = 500u64;
    let mbar = rope().mass_per_length;
    let (lay0, pos) = Layout::build(&def).unwrap();
    let opts = SolverOptions {
        dt,
        ..Default::default()
    };
    // The fastest mode: every element at the shortest a variable one gets, 0.5 l_s.
    let l0_min = winches
        .iter()
        .map(|w| 0.5 * w.element_length)
        .fold(f64::INFINITY, f64::min);
    let mut worst = lay0.clone();
    worst.elem_l0.iter_mut().for_each(|l| *l = l0_min);
    let omega = 2.0 / cablesim::stability::stable_step(&worst, opts.scheme, opts.baumgarte).dt;
    let mut cpu = CpuSolver::with_winches(def.clone(), winches.clone(), &pos, opts).unwrap();
    cpu.use_chain_kernel = false;
    let mut gpu = GpuSolver::with_winches(
        ctx,
        def.clone(),
        winches.clone(),
        &pos,
        opts,
        Precision::F64,
    )
    .unwrap();
    let (mut worst_r, mut worst_v, mut worst_t, mut worst_f) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut ratio_r, mut ratio_v, mut ratio_t) = (0.0f64, 0.0f64, 0.0f64);
    let mut worst_mass = 0.0f64;
    let mut meshes: Vec<Vec<usize>> = cpu
        .winch_status()
        .iter()
        .map(|s| vec![s.elements])
        .collect();
    let mut done = 0;
    while done < steps {
        let n = chunk.min(steps - done);
        cpu.advance(n).unwrap();
        gpu.advance(n).unwrap();
        done += n;
        assert_eq!(gpu.steps(), cpu.steps());
        // The same mesh: the host remeshes both from the same schedules at the same
        // steps, so the mesh state is identical, not just close.
        let (sc, sg) = (cpu.winch_status(), gpu.winch_status());
        assert_eq!(sc, sg, "{label}: winch status at t = {} s", cpu.t());
        assert_eq!(gpu.layout().n_nodes(), cpu.layout().n_nodes());
        for (a, b) in gpu.layout().cables.iter().zip(&cpu.layout().cables) {
            assert_eq!(a.nodes, b.nodes, "{label}: cable {}", a.name);
        }
        assert_eq!(gpu.layout().elem_l0, cpu.layout().elem_l0);
        for (m, s) in meshes.iter_mut().zip(&sc) {
            if *m.last().unwrap() != s.elements {
                m.push(s.elements);
            }
        }
        // Round-off bounds after `done` steps (`compare`).
        let c = Snapshot::cpu("CPU f64", &mut cpu);
        let g = Snapshot::gpu("GPU f64", &mut gpu);
        let eg = &g.eval;
        let bounds = RoundOff::new(cpu.layout(), &c, done, EPS, rope().ea, l0_min, omega);
        let name = format!("{label} t = {} s", cpu.t());
        let d = bounds.check(&name, cpu.layout(), &g, &c);
        let df = Check::new(&name, cpu.layout(), &g, &c)
            .within(
                "end forces",
                "N",
                Place::CableEnd,
                &end_forces(gpu.layout(), &g.eval),
                &end_forces(cpu.layout(), &c.eval),
                |_| bounds.force,
            )
            .map_or(0.0, |w| w.diff);
        (worst_r, worst_v, worst_t, worst_f) = (
            worst_r.max(d.r.diff),
            worst_v.max(d.v.diff),
            worst_t.max(d.tension.diff),
            worst_f.max(df.max(d.reaction.diff)),
        );
        (ratio_r, ratio_v, ratio_t) = (
            ratio_r.max(d.r.ratio()),
            ratio_v.max(d.v.ratio()),
            ratio_t.max(d.tension.ratio()),
        );
        // Mass in the water from the GPU's own half masses: mbar L(t).
        for (w, st) in winches.iter().zip(&sg) {
            let var = variable_element(gpu.layout(), w.cable, w.end);
            let (mass, len) = mass_and_length(gpu.layout(), eg, w.cable, var, st.variable_l0);
            let l = st.deployed_length;
            assert!((len - l).abs() <= 1e-12 * l, "layout length {len} vs L {l}");
            worst_mass = worst_mass.max((mass - mbar * l).abs() / (mbar * l));
        }
    }
    eprintln!(
        "{label}: meshes {meshes:?} elements ({} GPU remeshings); \
         worst |dr| {worst_r:.2e} m, |dv| {worst_v:.2e} m/s, |dT| {worst_t:.2e} N, |dF_end|, |dReaction| {worst_f:.2e} N \
         (largest fraction of the round-off bound: r {ratio_r:.1e}, v {ratio_v:.1e}, T {ratio_t:.1e}); \
         GPU mass vs mbar L: {worst_mass:.1e}",
        gpu.remeshes()
    );
    assert!(
        worst_mass < 1e-13,
        "{label}: GPU mass vs mbar L: {worst_mass:e}"
    );
    // The cables moved: the check is not of cables at rest.
    let moved = max_of(cpu.r.iter().zip(&pos).map(|(a, b)| dist(a.to_f64(), *b)));
    assert!(moved > 0.5, "{label}: moved {moved} m");
    (meshes, gpu.winch_status(), gpu.remeshes())
}

#[test]
fn gpu_f64_matches_cpu_f64_through_payout_and_retrieval() {
    let Some(ctx) = gpu_context("gpu_f64_matches_cpu_f64_through_payout_and_retrieval", true)
    else {
        return;
    };
    let (l_s, n0, dt) = (2.0, 4usize, 2e-4);
    for end in [WinchEnd::Start, WinchEnd::End] {
        let def = hanging(n0, l_s, end);
        let w = winch(end, out_and_back(), l_s);
        let label = format!("{end:?}");
        let (meshes, st, remeshes) = compare_f64(&ctx, &label, def, vec![w], dt, 27_500);
        // Both node insertion and deletion happened, and the mesh came back.
        assert_eq!((st[0].inserted, st[0].deleted), (3, 3), "{end:?}");
        assert_eq!(meshes[0], vec![4, 5, 6, 7, 6, 5, 4], "{end:?}");
        assert_eq!(remeshes, 6);
    }
}

/// Several cables in one packed layout (separate blocks): one paid out from its start
/// node, one hauled in (then paid out) at its end node at another rate, so that they
/// remesh at different steps, and one plain cable without a winch between them.
#[test]
fn gpu_f64_matches_cpu_f64_with_several_winch_cables() {
    let Some(ctx) = gpu_context("gpu_f64_matches_cpu_f64_with_several_winch_cables", true) else {
        return;
    };
    let (l_s, dt) = (2.0, 2e-4);
    let mut def = hanging(4, l_s, WinchEnd::Start);
    for (k, (n, end)) in [(5usize, WinchEnd::End), (6, WinchEnd::End)]
        .into_iter()
        .enumerate()
    {
        let mut d = hanging(n, l_s, end);
        let off = def.nodes.len();
        for nd in &mut d.nodes {
            nd.position[0] += 10.0 * (k + 1) as f64;
            if let Some(Route::Fixed { position }) = &mut nd.route {
                position[0] += 10.0 * (k + 1) as f64;
            }
        }
        def.nodes.extend(d.nodes);
        let mut c = d.cables.remove(0);
        c.nodes.iter_mut().for_each(|x| *x += off);
        c.name = format!("c{}", k + 1);
        def.cables.push(c);
    }
    // Cable 2 (the 6-element one) hauls 4.5 m in at up to 2.25 m/s, then pays 4.5 m
    // out (no remeshing falls on a step where the variable element is exactly at a
    // threshold: 1.5 m at the turn).
    let in_and_out = PayoutSchedule::rates(&[
        (0.0, 0.0),
        (0.5, -2.25),
        (2.0, -2.25),
        (2.5, 0.0),
        (3.0, 2.25),
        (4.5, 2.25),
        (5.0, 0.0),
    ])
    .unwrap();
    let winches = vec![
        winch(WinchEnd::Start, out_and_back(), l_s),
        Winch {
            cable: 2,
            ..winch(WinchEnd::End, in_and_out, l_s)
        },
    ];
    let (meshes, st, remeshes) = compare_f64(&ctx, "several", def, winches, dt, 27_500);
    assert_eq!(meshes[0], vec![4, 5, 6, 7, 6, 5, 4]);
    assert_eq!(meshes[1], vec![6, 5, 4, 5, 6]);
    assert_eq!(remeshes, 10, "{st:?}");
}

/// A scenario run on the CPU (f64) and the GPU (f32), compared every `every` s.
fn f32_against_cpu(ctx: &GpuContext, path: &str, duration: f64, every: f64) {
    let sc = Scenario::load(path).unwrap();
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let mut opts = SolverOptions {
        formulation: sc.sim.formulation,
        scheme: sc.sim.scheme,
        baumgarte: sc.sim.baumgarte,
        max_speed: sc.sim.max_speed,
        ..SolverOptions::default()
    };
    let plan = cablesim::sim::plan_steps(&sc, &lay, &opts, duration, sc.sim.dt).unwrap();
    opts.dt = plan.dt;
    let mut cpu =
        CpuSolver::with_winches(sc.model.clone(), sc.winches.clone(), &pos, opts).unwrap();
    let mut gpu = GpuSolver::with_winches(
        ctx,
        sc.model.clone(),
        sc.winches.clone(),
        &pos,
        opts,
        Precision::F32,
    )
    .unwrap();
    let ci = sc.winches[0].cable;
    let end = sc.winches[0].end;
    let mbar = sc.model.line_types[sc.model.cables[ci].line_type].mass_per_length;
    let per = (every / plan.dt).round() as u64;
    let (mut worst_pos, mut worst_force, mut worst_mass) = (0.0f64, 0.0f64, 0.0f64);
    let mut done = 0;
    while done < plan.total_steps {
        let n = per.min(plan.total_steps - done);
        cpu.advance(n).unwrap();
        gpu.advance(n).unwrap();
        done += n;
        let (sc_, sg) = (&cpu.winch_status()[0], &gpu.winch_status()[0]);
        assert_eq!(sc_, sg, "{path}: winch status at t = {} s", cpu.t());
        let l = sg.deployed_length;
        let c = Snapshot::cpu("CPU f64", &mut cpu);
        let g = Snapshot::gpu("GPU f32", &mut gpu);
        let name = format!("{path} t = {} s (L = {l} m)", cpu.t());
        let check = Check::new(&name, cpu.layout(), &g, &c);
        let last = |nodes: &[u32]| nodes[nodes.len() - 1] as usize;
        let (ig, ic) = (
            last(&gpu.layout().cables[ci].nodes),
            last(&cpu.layout().cables[ci].nodes),
        );
        let w = check.one(
            "last node positions",
            "m",
            Place::Node,
            ic,
            g.r[ig],
            c.r[ic],
            1e-4 * l,
        );
        worst_pos = worst_pos.max(w.diff / l);
        let (fg, fc) = (
            end_forces(gpu.layout(), &g.eval),
            end_forces(cpu.layout(), &c.eval),
        );
        for k in [2 * ci, 2 * ci + 1] {
            let f = norm(fc[k]);
            let w = check.one(
                "end forces",
                "N",
                Place::CableEnd,
                k,
                fg[k],
                fc[k],
                0.01 * f,
            );
            worst_force = worst_force.max(w.diff / f);
        }
        let eg = g.eval;
        let var = variable_element(gpu.layout(), ci, end);
        let (mass, len) = mass_and_length(gpu.layout(), &eg, ci, var, sg.variable_l0);
        assert!((len - l).abs() <= 1e-12 * l, "layout length {len} vs L {l}");
        worst_mass = worst_mass.max((mass - mbar * l).abs() / (mbar * l));
    }
    let st = &gpu.winch_status()[0];
    eprintln!(
        "{path}, {duration} s ({} steps of {:.3e} s), GPU f32 vs CPU f64: last node within {worst_pos:.1e} L, \
         end forces within {worst_force:.1e}; {} -> {} elements ({} GPU remeshings); GPU f32 mass vs mbar L: {worst_mass:.1e}",
        plan.total_steps,
        plan.dt,
        sc.model.cables[ci].l0.len(),
        st.elements,
        gpu.remeshes()
    );
    assert!(st.inserted >= 2, "{path}: the run should remesh ({st:?})");
    assert_eq!(gpu.remeshes(), st.inserted + st.deleted);
    // The masses are f32 sums of f32 half masses.
    assert!(
        worst_mass < 1e-5,
        "{path}: GPU f32 mass vs mbar L: {worst_mass:e}"
    );
}

#[test]
fn gpu_f32_matches_cpu_f64_on_the_winch_deploy_example() {
    let Some(ctx) = gpu_context("gpu_f32_matches_cpu_f64_on_the_winch_deploy_example", false)
    else {
        return;
    };
    f32_against_cpu(&ctx, "examples/winch_deploy.toml", 150.0, 10.0);
}

#[test]
fn gpu_f32_matches_cpu_f64_on_case2_circle() {
    let Some(ctx) = gpu_context("gpu_f32_matches_cpu_f64_on_case2_circle", false) else {
        return;
    };
    f32_against_cpu(&ctx, "examples/case2_circle.toml", 100.0, 10.0);
}

/// A winch that does not move (zero rate) leaves the GPU path bitwise the plain GPU
/// path, at both precisions, winch at either end.
#[test]
fn still_winch_is_bitwise_the_plain_gpu_path() {
    let Some(ctx) = gpu_context("still_winch_is_bitwise_the_plain_gpu_path", false) else {
        return;
    };
    let (l_s, n) = (2.0, 5usize);
    let opts = SolverOptions {
        dt: 2e-4,
        ..Default::default()
    };
    for p in [Precision::F32, Precision::F64] {
        if !ctx.supports(p) {
            continue;
        }
        for end in [WinchEnd::Start, WinchEnd::End] {
            let def = hanging(n, l_s, end);
            let (lay, pos) = Layout::build(&def).unwrap();
            let mut plain = GpuSolver::new(&ctx, lay, &pos, opts, p).unwrap();
            let w = winch(end, PayoutSchedule::constant(0.0).unwrap(), l_s);
            let mut ale = GpuSolver::with_winches(&ctx, def, vec![w], &pos, opts, p).unwrap();
            plain.advance(1500).unwrap();
            ale.advance(1500).unwrap();
            let (a, b) = (plain.state().unwrap(), ale.state().unwrap());
            let moved = dist(a.0[n / 2], pos[n / 2]);
            assert!(moved > 0.01, "the current moves the cable ({moved} m)");
            assert_eq!(a, b, "{} {end:?}: states differ", p.name());
            let (ea, eb) = (plain.evaluate().unwrap(), ale.evaluate().unwrap());
            assert_eq!(ea.tension, eb.tension);
            assert_eq!(ea.reaction, eb.reaction);
            assert_eq!(ale.remeshes(), 0);
        }
    }
}

fn run_cli(dir: &std::path::Path, backend: &str, env: &str) -> (serde_json::Value, String) {
    let out = dir.join(format!("out-{backend}"));
    let o = Command::new(env!("CARGO_BIN_EXE_cablesim"))
        .arg("run")
        .arg("examples/winch_deploy.toml")
        .args(["--out", out.to_str().unwrap(), "-q", "--duration", "25"])
        .args(["--backend", backend])
        .env("WGPU_BACKEND", env)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{backend}: {err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let csv = std::fs::read_to_string(out.join("winches.csv")).unwrap();
    (s, csv)
}

/// `cablesim run examples/winch_deploy.toml --backend gpu` runs the winch on the GPU:
/// summary and winches.csv match the CPU run's (the same mesh at every output time,
/// the top force within 1%); `--backend auto` on a software adapter runs the CPU path.
#[test]
fn winch_example_runs_on_the_gpu_from_the_command_line() {
    let Some(ctx) = gpu_context("winch_example_runs_on_the_gpu_from_the_command_line", false)
    else {
        return;
    };
    let env = format!("{:?}", ctx.info.backend).to_lowercase();
    let dir = tempfile::tempdir().unwrap();
    let (gpu, gcsv) = run_cli(dir.path(), "gpu", &env);
    let (cpu, ccsv) = run_cli(dir.path(), "cpu", &env);
    assert_eq!(gpu["backend"], "gpu");
    assert_eq!(gpu["status"], "completed");
    assert_eq!(gpu["steps"], cpu["steps"]);
    let (wg, wc) = (&gpu["cables"][0]["winch"], &cpu["cables"][0]["winch"]);
    assert_eq!(wg, wc, "winch summary");
    assert!(wg["nodes_inserted"].as_u64().unwrap() >= 1, "{wg}");
    // winches.csv: the same rows (time, cable, deployed length, elements, ...).
    assert_eq!(gcsv.lines().count(), ccsv.lines().count());
    assert_eq!(gcsv, ccsv, "winches.csv");
    let f = |s: &serde_json::Value| -> Vec<f64> {
        s["cables"][0]["end_forces"]["start"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (g, c) = (f(&gpu), f(&cpu));
    let d = dist([g[0], g[1], g[2]], [c[0], c[1], c[2]]);
    let n = dist([c[0], c[1], c[2]], [0.0; 3]);
    eprintln!("winch_deploy 25 s: top force GPU {g:?} N, CPU {c:?} N");
    assert!(d < 0.01 * n, "top force {g:?} vs CPU {c:?}");
    let (auto, _) = run_cli(dir.path(), "auto", &env);
    if ctx.info.device_type == wgpu::DeviceType::Cpu {
        assert_eq!(auto["backend"], "cpu", "auto on a software adapter");
    } else {
        assert_eq!(auto["backend"], "gpu", "auto on a hardware adapter");
    }
}
