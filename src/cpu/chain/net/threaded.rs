//! A network block stepped by all the pool's threads together (a net cage: thousands
//! of nodes), on the network path's passes over each thread's own elements and nodes.

use super::plan::{plan, Op, Plan, ThreadPlan};
use super::{
    element_tile, load, node_pass, node_pass_either, store, LoadsOut, NetConsts, NetScratch, Work,
    NT, TILE,
};
use crate::cpu::threaded::SpinBarrier;
use crate::math::V3;
use crate::model::Layout;
use crate::options::SolverOptions;
use crate::step::{diverged, StepFailure};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Raw views of the state and element loads shared by the threads of
/// [`advance_net_threaded`]. Within each phase of a step every element and every node
/// has exactly one writer and nothing reads what is being written (see the function),
/// which the barriers between the phases order.
#[derive(Clone, Copy)]
struct Shared {
    x: [*mut f64; 6],
    /// [`super::Loads`]: [`super::loads_len`] values.
    sum: *mut f64,
}
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

/// Steps a network block (still water) by `nsteps` with `threads` threads: each owns a
/// contiguous range of tiles of nodes and the elements whose node a is in them (so that
/// a thread mostly reads what it wrote: across the threads go only the state and loads
/// of the elements that cross the border of two node ranges), in the order of
/// [`plan`]. Per step, phase 1: each thread evaluates its elements tile by tile and
/// updates the tiles no other thread's elements reach as soon as their slots are
/// complete (it reads only nodes nobody updates in this phase: its own, and the other
/// threads' border tiles); barrier; phase 2: each thread updates its border tiles
/// (reading their slots, which nobody writes now, and their state); barrier. The
/// arithmetic per element and per node is [`super::advance_net`]'s, so the result is
/// the same bit for bit, and a blow-up names the lowest failing node of the first
/// failing step, as there.
#[allow(clippy::too_many_arguments)]
pub(crate) fn advance_net_threaded(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut NetScratch,
    r: &mut [V3<f64>],
    v: &mut [V3<f64>],
    n0: usize,
    step0: u64,
    dt: f64,
    nsteps: u64,
    threads: usize,
) -> Result<(), StepFailure> {
    let (n, ne) = (nc.n(), nc.ne());
    let plan = plan(n, nc.width, &nc.ends[0], &nc.ends[1], &nc.pieces, threads);
    load(nc, &plan, sc, r, v);
    let NetScratch {
        x, eta, el, under, ..
    } = sc;
    let sh = Shared {
        x: x.each_mut().map(|q| q.as_mut_ptr()),
        sum: el.start(),
    };
    let (eta, under): (&[f64], &[_]) = (eta, under);
    let barrier = SpinBarrier::new(threads);
    // Lowest failing node of the current step (usize::MAX: none yet).
    let failed = AtomicUsize::new(usize::MAX);
    let plan = &plan;
    let work = |tid: usize| {
        // Capture the whole `Shared` (Sync), not its raw-pointer fields one by one.
        #[allow(clippy::redundant_locals)]
        let sh = sh;
        let mut g = Work::default();
        g.size(ne.min(TILE));
        // SAFETY: `sh` holds this block's scratch in `plan`'s buffers, and each thread
        // has its own tiles and elements (each element has one node a).
        unsafe {
            step_threads(
                nc, lay, opts, sh, &barrier, &failed, plan, tid, eta, under, &mut g, step0, dt,
                nsteps,
            )
        }
    };
    let stop = std::thread::scope(|s| {
        let helpers: Vec<_> = (1..threads).map(|tid| s.spawn(move || work(tid))).collect();
        let mine = work(0);
        for h in helpers {
            h.join().expect("a stepping thread panicked");
        }
        mine
    });
    store(sc, r, v);
    match stop {
        None => Ok(()),
        Some(time) => {
            let i = failed.load(Ordering::Acquire);
            Err(diverged(opts, r[i], v[i], n0 + i, time))
        }
    }
}

/// One thread's steps of [`advance_net_threaded`] (compiled for AVX-512 or AVX2 where
/// the CPU has it, as [`super::advance_net`]); the time its node failed at, if one did.
///
/// # Safety
/// As [`step_threads_body`].
#[allow(clippy::too_many_arguments)]
unsafe fn step_threads(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sh: Shared,
    barrier: &SpinBarrier,
    failed: &AtomicUsize,
    plan: &Plan,
    tid: usize,
    eta: &[f64],
    under: &[AtomicBool],
    g: &mut Work,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    {
        if super::avx512() {
            // SAFETY: the CPU has AVX-512 (F, DQ, VL), checked just above; the rest as
            // the body's.
            return unsafe {
                step_threads_avx512(
                    nc, lay, opts, sh, barrier, failed, plan, tid, eta, under, g, step0, dt, nsteps,
                )
            };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above; the rest as the body's.
            return unsafe {
                step_threads_avx2(
                    nc, lay, opts, sh, barrier, failed, plan, tid, eta, under, g, step0, dt, nsteps,
                )
            };
        }
    }
    step_threads_body::<4>(
        nc, lay, opts, sh, barrier, failed, plan, tid, eta, under, g, step0, dt, nsteps,
    )
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn step_threads_avx2(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sh: Shared,
    barrier: &SpinBarrier,
    failed: &AtomicUsize,
    plan: &Plan,
    tid: usize,
    eta: &[f64],
    under: &[AtomicBool],
    g: &mut Work,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Option<f64> {
    step_threads_body::<4>(
        nc, lay, opts, sh, barrier, failed, plan, tid, eta, under, g, step0, dt, nsteps,
    )
}

/// The same, compiled for AVX-512 (8 lanes to a vector).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512dq,avx512vl")]
#[allow(clippy::too_many_arguments)]
unsafe fn step_threads_avx512(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sh: Shared,
    barrier: &SpinBarrier,
    failed: &AtomicUsize,
    plan: &Plan,
    tid: usize,
    eta: &[f64],
    under: &[AtomicBool],
    g: &mut Work,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Option<f64> {
    step_threads_body::<8>(
        nc, lay, opts, sh, barrier, failed, plan, tid, eta, under, g, step0, dt, nsteps,
    )
}

/// # Safety
/// `sh` points at the block's state (`n` nodes) and loads (`load`, in `plan`'s buffers),
/// and every thread of `barrier` runs this with its own `tid` of `plan`.
/// `L` as in [`super::advance_net`]'s body.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn step_threads_body<const L: usize>(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sh: Shared,
    barrier: &SpinBarrier,
    failed: &AtomicUsize,
    plan: &Plan,
    tid: usize,
    eta: &[f64],
    under: &[AtomicBool],
    g: &mut Work,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Option<f64> {
    let n = nc.n();
    let ThreadPlan { ops, late, reach } = &plan.threads[tid];
    // SAFETY: `sh.sum` is the block's loads; the threads' elements are disjoint and
    // each has its own slots, in buffers of tiles no other thread reads or writes in
    // the same phase.
    let out = unsafe { LoadsOut::new(sh.sum, nc.width, plan) };
    // Updates tile `t` (this thread's alone in this phase) and clears what the next
    // user of its buffer needs zero.
    let update = |t: usize, time: f64, g: &mut Work| {
        let nr = t * NT..((t + 1) * NT).min(n);
        // SAFETY: tile `t`'s nodes and buffer are this thread's alone in this phase.
        let xs: [&mut [f64]; 6] =
            sh.x.map(|p| unsafe { std::slice::from_raw_parts_mut(p.add(nr.start), nr.len()) });
        let sum = unsafe { out.tile(t) };
        let bad = node_pass_either!(
            nc,
            lay,
            opts,
            time,
            dt,
            nr.clone(),
            xs,
            eta,
            &[],
            sum,
            g,
            &under[t],
        );
        unsafe { out.clear(&plan.clear[t]) };
        if let Some(j) = bad {
            failed.fetch_min(nr.start + j, Ordering::AcqRel);
        }
    };
    let mut sense = false;
    for k in 0..nsteps {
        let time = (step0 + k) as f64 * dt;
        for op in ops {
            match op {
                Op::Elems(p) => {
                    // The state of the nodes this thread's elements reach: nobody
                    // updates them in this phase (`plan`: they are this thread's own
                    // tiles or the others' border tiles).
                    // SAFETY: as just said; `reach` is within the block.
                    let xs: [&[f64]; 6] = sh.x.map(|p| unsafe {
                        std::slice::from_raw_parts(p.add(reach.start) as *const f64, reach.len())
                    });
                    let eta = &eta[reach.clone()];
                    let (p, base) = (p.clone(), reach.start);
                    element_tile::<L>(nc, lay, p, xs, base, eta, &[], under, g, out);
                }
                &Op::Nodes(t) => update(t, time, g),
            }
        }
        barrier.wait(&mut sense);
        for &t in late {
            update(t, time, g);
        }
        barrier.wait(&mut sense);
        if failed.load(Ordering::Acquire) != usize::MAX {
            return Some(time + dt);
        }
    }
    None
}
