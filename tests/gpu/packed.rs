//! Packed runs (`sim::pack`) on the GPU against the CPU: three members, each in its own
//! sea (its own components, refresh schedule and RAO-driven vessel), stepped in one
//! layout by both kernels in f64 and compared with the CPU path's packed run; and a
//! study run packed on the GPU against the CPU's one run per member, for two batch
//! sizes.

use super::common::{dist, gpu_context, short_study, wave_members};
use cablesim::cpu::CpuSolver;
use cablesim::gpu::{GpuKernel, GpuSolver, Precision};
use cablesim::options::{Backend, Overrides, SolverOptions};
use cablesim::sim::pack::pack;
use cablesim::sim::{prepare, Simulation};
use cablesim::study::{MemberResult, PackedRun, StudyFile, StudyRunner};
use std::sync::atomic::AtomicBool;

#[test]
fn gpu_matches_cpu_on_a_packed_run_of_three_seas_in_f64() {
    let name = "gpu_matches_cpu_on_a_packed_run_of_three_seas_in_f64";
    let Some(ctx) = gpu_context(name, true) else {
        return;
    };
    let packed = pack(&wave_members(3, 10)).unwrap();
    let sc = &packed.scenario;
    let seas = sc.sea_set();
    let (lay, pos, _) = prepare(sc).unwrap();
    let cpu_sim = Simulation::new(
        sc.clone(),
        &Overrides {
            backend: Some(Backend::Cpu),
            ..Overrides::default()
        },
    )
    .unwrap();
    let opts = SolverOptions {
        dt: cpu_sim.dt(),
        baumgarte: sc.sim.baumgarte,
        max_speed: sc.sim.max_speed,
        ..SolverOptions::default()
    };
    let steps = (3.0 / opts.dt).round() as u64;
    let mut cpu = CpuSolver::new(lay.clone(), &pos, opts);
    cpu.set_seas(&seas, false);
    cpu.advance(steps).unwrap();
    let cpu_r: Vec<[f64; 3]> = cpu.r.iter().map(|v| v.to_f64()).collect();
    let cpu_t = cpu.evaluate().unwrap().tension;
    // Member 0's and member 1's first lines (same geometry, other seas) must differ by
    // far more than the tolerance, or a member read in the wrong sea would pass.
    let (c0, c1) = (
        &lay.cables[packed.members[0].cables.start],
        &lay.cables[packed.members[1].cables.start],
    );
    let apart = c0
        .nodes
        .iter()
        .zip(&c1.nodes)
        .map(|(&a, &b)| dist(cpu_r[a as usize], cpu_r[b as usize]))
        .fold(0.0f64, f64::max);
    println!("{name}: {steps} steps; members 0 and 1 apart by up to {apart:.3e} m");
    assert!(apart > 1e-3, "the members' seas barely differ ({apart} m)");
    let tmax = cpu_t.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    for kernel in [GpuKernel::TwoPass, GpuKernel::Fused] {
        let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, Precision::F64).unwrap();
        gpu.set_kernel(kernel).unwrap();
        gpu.set_seas(&seas).unwrap();
        match kernel {
            // Uneven calls: refreshes of each sea fall inside and at the edges of
            // submissions.
            GpuKernel::TwoPass => {
                let first = steps / 3;
                for n in [1, first, steps - 1 - first] {
                    gpu.advance(n).unwrap();
                }
            }
            // Short submissions: in waves, the fused kernel on a layout of many blocks
            // drifts from the two-pass kernel by millimetres over submissions of some
            // hundreds of steps, with one sea as with several (the ignored test below
            // shows it); with 20 steps a submission it agrees to round-off.
            GpuKernel::Fused => {
                let mut done = 0;
                while done < steps {
                    let n = 20.min(steps - done);
                    gpu.advance(n).unwrap();
                    done += n;
                }
            }
        }
        let (r, _) = gpu.state().unwrap();
        let tension = gpu.evaluate().unwrap().tension;
        let dr = r
            .iter()
            .zip(&cpu_r)
            .map(|(a, b)| dist(*a, *b))
            .fold(0.0f64, f64::max);
        let dt = tension
            .iter()
            .zip(&cpu_t)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        println!("{name} {kernel:?}: |dr| {dr:.3e} m, |dT| {dt:.3e} N (largest {tmax:.1} N)");
        assert!(dr < 1e-7, "{kernel:?}: |dr| {dr} m");
        assert!(dt < 1e-6 * tmax, "{kernel:?}: |dT| {dt} N");
    }
}

#[test]
fn a_study_run_packed_on_the_gpu_matches_the_cpu_for_any_batch_size() {
    let name = "a_study_run_packed_on_the_gpu_matches_the_cpu_for_any_batch_size";
    if gpu_context(name, true).is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    // Per depth band on both paths (the default, `sea::bands`): the comparison is to
    // round-off.
    let study = short_study(dir.path(), 2.0, 2);
    let file = StudyFile::load(study).unwrap();
    let runner = StudyRunner::new(&file).unwrap();
    let members = runner.plan().members.clone();
    let stop = AtomicBool::new(false);
    let none = |_: f64| {};
    let keep = |_: &MemberResult| Ok(());
    let cpu = runner.run(&members, &stop, &none, &keep).unwrap();
    let gpu = |batch| {
        let how = PackedRun {
            backend: Backend::Gpu,
            precision: Some(Precision::F64),
            batch,
        };
        runner
            .run_packed(&members, &how, &stop, &none, &keep)
            .unwrap()
    };
    let all = gpu(None);
    let json = |r: &[MemberResult]| serde_json::to_string(r).unwrap();
    // A member's blocks step the same whatever else is packed with them.
    assert_eq!(json(&gpu(Some(3))), json(&all));
    assert_eq!(all.len(), cpu.len());
    let mut worst = 0.0f64;
    for (g, c) in all.iter().zip(&cpu) {
        assert_eq!(g.member, c.member);
        assert_eq!(g.status, c.status);
        for (a, b) in g.stats.iter().zip(&c.stats) {
            assert_eq!(a.count(), b.count());
            let (Some(amax), Some(bmax), Some(amin), Some(bmin)) =
                (a.max(), b.max(), a.min(), b.min())
            else {
                panic!("a channel without samples");
            };
            // Every statistic within 1e-6 of the channel's range of values (f64 on
            // both sides; the GPU's sums and sines are its own, so not bit for bit).
            let scale = amax.value.abs().max(amin.value.abs()).max(1.0);
            for (x, y) in [
                (amax.value, bmax.value),
                (amin.value, bmin.value),
                (a.mean().unwrap(), b.mean().unwrap()),
                (a.std().unwrap(), b.std().unwrap()),
            ] {
                worst = worst.max((x - y).abs() / scale);
            }
        }
    }
    println!("{name}: worst difference {worst:.3e} of the channel's scale");
    assert!(worst < 1e-6, "GPU and CPU studies differ by {worst}");
}

/// The fused kernel in waves on a layout of many blocks (the spread mooring's eight
/// lines, 11 nodes each) agrees with the two-pass kernel to round-off over long
/// submissions (600 steps: one of 512 and one of 88), in f64 and f32, at the sea's own
/// cache tolerance (a refresh every 6.4 steps) and at a fine one (1e-4: every 2 steps).
///
/// It once did not: the fused kernel refreshed the cache inside its step loop, and on
/// lavapipe every loop of a shader invocation counts against one budget of 65535
/// iterations (Mesa gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), after which each loop ends
/// after one iteration without a word. The refresh's sums over the 200 components (and
/// the bit loop of `wave_exp`) spent it some twenty refreshes into a submission; from
/// there the cache held wrong velocities and accelerations (the elevation, summed first,
/// still right) and the kernels drifted apart by centimetres. Now the host cuts the
/// fused dispatch at each refresh step and refreshes in a `wave_refresh` dispatch, as the
/// two-pass kernel does.
#[test]
fn fused_kernel_in_waves_matches_two_pass_over_long_submissions() {
    let name = "fused_kernel_in_waves_matches_two_pass_over_long_submissions";
    let Some(ctx) = gpu_context(name, true) else {
        return;
    };
    let (_, sc) = wave_members(1, 10).remove(0);
    let (lay, pos, _) = prepare(&sc).unwrap();
    let cpu_sim = Simulation::new(
        sc.clone(),
        &Overrides {
            backend: Some(Backend::Cpu),
            ..Overrides::default()
        },
    )
    .unwrap();
    let opts = SolverOptions {
        dt: cpu_sim.dt(),
        baumgarte: sc.sim.baumgarte,
        max_speed: sc.sim.max_speed,
        ..SolverOptions::default()
    };
    let steps = 600u64;
    // The round-off bound of the other kernel comparisons: 10 N eps L, L the longest line.
    let longest = lay
        .cables
        .iter()
        .map(|c| {
            c.elements
                .iter()
                .map(|&e| lay.elem_l0[e as usize])
                .sum::<f64>()
        })
        .fold(0.0f64, f64::max);
    for tolerance in [None, Some(1e-4)] {
        let mut seas = sc.sea_set();
        if let Some(t) = tolerance {
            seas.seas.iter_mut().for_each(|s| s.cache_tolerance = t);
        }
        for p in [Precision::F64, Precision::F32] {
            let run = |kernel| {
                let mut gpu = GpuSolver::new(&ctx, lay.clone(), &pos, opts, p).unwrap();
                gpu.set_kernel(kernel).unwrap();
                gpu.set_seas(&seas).unwrap();
                gpu.advance(steps).unwrap();
                assert_eq!(gpu.kernel(), kernel);
                gpu.state().unwrap()
            };
            let ((ra, va), (rb, vb)) = (run(GpuKernel::TwoPass), run(GpuKernel::Fused));
            let worst = |a: &Vec<[f64; 3]>, b: &Vec<[f64; 3]>| {
                a.iter()
                    .zip(b)
                    .map(|(x, y)| dist(*x, *y))
                    .fold(0.0f64, f64::max)
            };
            let (dr, dv) = (worst(&ra, &rb), worst(&va, &vb));
            let eps = match p {
                Precision::F64 => f64::EPSILON,
                Precision::F32 => f32::EPSILON as f64,
            };
            let bound = 10.0 * steps as f64 * eps * longest;
            println!(
                "{name} ({}, cache tolerance {tolerance:?}): |dr| {dr:.3e} m, |dv| {dv:.3e} m/s \
                 after {steps} steps (bound {bound:.1e} m)",
                p.name()
            );
            assert!(
                dr <= bound,
                "{} {tolerance:?}: fused and two-pass differ by {dr} m",
                p.name()
            );
        }
    }
}
