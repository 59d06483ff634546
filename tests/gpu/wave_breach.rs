//! A node more than the margin above its depth band's top (`sea::bands`), on both
//! paths: a short line lying under the coarsest band's top is lifted by both ends,
//! faster than the band decision foresaw (it saw the line at rest), right after the
//! coarsest band's first refresh put it in that band (a node is decided again only at
//! its band's refreshes, so between two of them the lift goes unforeseen). The CPU path counts the breaches beyond the margin and warns of the
//! first (`sea::bands::warn_beyond_margin`); the GPU path must report the same: the
//! same count, and the same first breach (time, height, top) that its warning prints.
//! The same line not lifted must report none on either path.

use super::common::*;
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::model::{Layout, PointMass, Route};
use cablesim::options::SolverOptions;
use cablesim::sea::bands::{BandCensus, BAND_MARGIN};
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaSet, SeaState};

/// Hs 3 m, Tp 9 s, 200 components along +x, in 30 m of water, no ramp.
fn sea() -> SeaState {
    let depth = 30.0;
    let components = discretise(
        &Spectrum::Jonswap {
            hs: 3.0,
            tp: 9.0,
            gamma: 3.3,
        },
        &Discretisation {
            components: 200,
            direction: 0.0,
            spreading: None,
            seed: 5,
            stream: 0,
        },
        depth,
        9.81,
    );
    SeaState {
        components,
        ..SeaState::still(depth)
    }
}

/// A 4 m line of 2 elements, level at `z0`, both ends on a table that holds them
/// until `t_lift` and then raises them by `lift` m over `dur` s. The ends follow their
/// routes exactly (at rest before the lift: the band decision sees them still; the
/// middle node's vibration, whatever band it takes, does not matter).
fn line(z0: f64, t_lift: f64, lift: f64, dur: f64) -> (Layout, Vec<[f64; 3]>) {
    let end = |x: f64| Route::Table {
        t: vec![0.0, t_lift, t_lift + dur],
        p: vec![[x, 0.0, z0], [x, 0.0, z0], [x, 0.0, z0 + lift]],
    };
    let a = [-4.0, 0.0, z0];
    let b = [0.0, 0.0, z0];
    let def = straight_cable(
        water(),
        rope(),
        a,
        b,
        4.0,
        2,
        Some(end(a[0])),
        Some(end(b[0])),
        PointMass::default(),
        [0.0; 3],
    );
    Layout::build(&def).unwrap()
}

/// The CPU's census and each GPU kernel's after 1.9 coarsest intervals of the line,
/// `lifted` or not.
fn run(p: Precision, lifted: bool) -> Option<(BandCensus, Vec<BandCensus>)> {
    let ctx = gpu_context(
        &format!("band_breach_{lifted}_{}", p.name()),
        p == Precision::F64,
    )?;
    let opts = SolverOptions {
        dt: 2e-4,
        ..SolverOptions::default()
    };
    let mut set = SeaSet::single(&sea());
    set.banded = true;
    let plan = set.band_plan(0, opts.dt);
    assert!(plan.len() >= 2, "one band only: {plan:?}");
    let h = plan.horizon();
    // Under the coarsest band's top by more than the margin, so that the ends at rest
    // go one band deeper at each deeper band's first refresh (a node is decided among
    // the bands refreshing then) and into the coarsest at its first, time h; lifted
    // from 1.05 h to 1.55 h to 2.5 margins over that top, before their band's next
    // refresh and decision (2 h), while band 0 refreshes (and watches) several times.
    let top = plan.tops[plan.len() - 1];
    let z0 = top - BAND_MARGIN - 1.0;
    assert!(
        z0 > -28.0,
        "the coarsest band's top {top} m is too deep for the line"
    );
    let lift = if lifted { 4.0 * BAND_MARGIN } else { 0.0 };
    let (lay, pos) = line(z0, 1.05 * h, lift, 0.5 * h);
    let steps = (1.9 * h / opts.dt).ceil() as u64;
    println!(
        "band breach, lift {lift} m: {} bands, tops {:?}, horizon {h} s, line at {z0:.2} m, {steps} steps",
        plan.len(),
        plan.tops
    );
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.set_seas(&set, false);
    cpu.advance(steps).unwrap();
    let c = cpu.wave_band_census();
    println!("CPU: {c:?}");
    let mut g = Vec::new();
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
        gpu.set_kernel(kernel).unwrap();
        gpu.set_seas(&set).unwrap();
        // Uneven calls, an evaluation between two (it refreshes where the next step
        // would, and watches the bands as that step does).
        gpu.advance(steps / 3).unwrap();
        gpu.evaluate().unwrap();
        gpu.advance(steps - steps / 3).unwrap();
        let census = gpu.wave_band_census().unwrap();
        println!("GPU {kernel:?}: {census:?}");
        g.push(census);
    }
    Some((c, g))
}

fn check_lifted(p: Precision) {
    let Some((cpu, gpus)) = run(p, true) else {
        return;
    };
    assert!(
        cpu.beyond_margin > 0,
        "the CPU saw no breach beyond the margin: {cpu:?}"
    );
    let [t, z, top] = cpu.first_beyond_margin.expect("the CPU's first breach");
    assert!(z - top > BAND_MARGIN, "{cpu:?}");
    for g in &gpus {
        assert!(
            g.beyond_margin > 0,
            "the GPU saw no breach beyond the margin: {g:?}"
        );
        let [gt, gz, gtop] = g.first_beyond_margin.expect("the GPU's first breach");
        assert!(gz - gtop > BAND_MARGIN, "{g:?}");
        // The same refresh (the same step), the same band's top; the height to the
        // precision's round-off of the run.
        assert!(
            (gt - t).abs() < 1e-9,
            "first breach at {gt} s on the GPU, {t} s on the CPU"
        );
        assert!(
            (gtop - top).abs() < 1e-5 * top.abs(),
            "top {gtop} against {top}"
        );
        let tol = if p == Precision::F64 { 1e-9 } else { 1e-3 };
        assert!((gz - z).abs() < tol, "height {gz} against {z}");
        if p == Precision::F64 {
            assert_eq!(g.nodes, cpu.nodes);
            assert_eq!(g.breaches, cpu.breaches);
            assert_eq!(g.beyond_margin, cpu.beyond_margin);
        }
    }
}

#[test]
fn a_node_beyond_its_bands_margin_is_reported_on_both_paths_in_f64() {
    check_lifted(Precision::F64);
}

#[test]
fn a_node_beyond_its_bands_margin_is_reported_on_both_paths_in_f32() {
    check_lifted(Precision::F32);
}

#[test]
fn a_line_that_stays_in_its_band_reports_no_breach_beyond_the_margin() {
    let Some((cpu, gpus)) = run(Precision::F32, false) else {
        return;
    };
    assert!(
        cpu.nodes.iter().skip(1).sum::<usize>() > 0,
        "no node in a deeper band: {cpu:?}"
    );
    assert_eq!((cpu.beyond_margin, cpu.first_beyond_margin), (0, None));
    for g in gpus {
        assert_eq!((g.beyond_margin, g.first_beyond_margin), (0, None), "{g:?}");
        assert_eq!(g.nodes, cpu.nodes);
    }
}
