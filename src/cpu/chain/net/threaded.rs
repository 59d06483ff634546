//! A network block stepped by all the pool's threads together (a net cage: thousands
//! of nodes), on the network path's passes over each thread's own elements and nodes.

use super::pieces::{owned, Piece};
use super::{
    element_tile, load, loads_len, node_pass, store, LoadsIn, LoadsOut, NetConsts, NetScratch,
    Work, TILE,
};
use crate::cpu::threaded::SpinBarrier;
use crate::math::V3;
use crate::model::Layout;
use crate::options::SolverOptions;
use crate::step::{diverged, StepFailure};
use std::ops::Range;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Raw views of the state and element loads shared by the threads of
/// [`advance_net_threaded`]. Within each phase of a step every element and every node
/// has exactly one writer and nothing reads what is being written (see the function),
/// which the barriers between the phases order.
#[derive(Clone, Copy)]
struct Shared {
    x: [*mut f64; 6],
    /// [`Loads`]: [`loads_len`] values.
    sum: *mut f64,
}
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

/// Steps a network block (still water) by `nsteps` with `threads` threads: each owns a
/// contiguous range of nodes and the elements whose node a is one of them (so that a
/// thread mostly reads what it wrote: across the threads go only the state and loads
/// of the elements that cross the border of two node ranges). Per step, phase 1: each
/// thread evaluates its elements (reading every node's state, which nobody writes in
/// this phase);
/// barrier; phase 2: each thread updates its nodes (reading every element's loads,
/// which nobody writes now, and its own nodes' state); barrier. The arithmetic per
/// element and per node is [`advance_net`]'s, so the result is the same bit for bit,
/// and a blow-up names the lowest failing node of the first failing step, as there.
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
    load(nc, sc, r, v);
    let NetScratch { x, eta, el, .. } = sc;
    let sh = Shared {
        x: x.each_mut().map(|q| q.as_mut_ptr()),
        sum: el.sum.as_mut_ptr(),
    };
    let eta: &[f64] = eta;
    let barrier = SpinBarrier::new(threads);
    // Lowest failing node of the current step (usize::MAX: none yet).
    let failed = AtomicUsize::new(usize::MAX);
    let range = |tid: usize, len: usize| (len * tid / threads)..(len * (tid + 1) / threads);
    let work = |tid: usize| {
        // Capture the whole `Shared` (Sync), not its raw-pointer fields one by one.
        #[allow(clippy::redundant_locals)]
        let sh = sh;
        let nr = range(tid, n);
        let pieces = owned(&nc.pieces, &nc.ends[0], &nr);
        let mut g = Work::default();
        g.size(&nc.c, ne.min(TILE), &nr);
        // SAFETY: `sh` holds this block's scratch, and each thread has its own nodes
        // and elements (each element has one node a).
        unsafe {
            step_threads(
                nc, lay, opts, sh, &barrier, &failed, &pieces, nr, eta, &mut g, step0, dt, nsteps,
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

/// One thread's steps of [`advance_net_threaded`] (compiled for AVX2 where the CPU has
/// it); the time its node failed at, if one did.
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
    pieces: &[Piece],
    nr: Range<usize>,
    eta: &[f64],
    g: &mut Work,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above; the rest as the body's.
            return unsafe {
                step_threads_avx2(
                    nc, lay, opts, sh, barrier, failed, pieces, nr, eta, g, step0, dt, nsteps,
                )
            };
        }
    }
    step_threads_body(
        nc, lay, opts, sh, barrier, failed, pieces, nr, eta, g, step0, dt, nsteps,
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
    pieces: &[Piece],
    nr: Range<usize>,
    eta: &[f64],
    g: &mut Work,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Option<f64> {
    step_threads_body(
        nc, lay, opts, sh, barrier, failed, pieces, nr, eta, g, step0, dt, nsteps,
    )
}

/// # Safety
/// `sh` points at the block's state (`n` nodes) and loads (`load`), and every thread of
/// `barrier` runs this with its own disjoint `pieces` and `nr`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn step_threads_body(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sh: Shared,
    barrier: &SpinBarrier,
    failed: &AtomicUsize,
    pieces: &[Piece],
    nr: Range<usize>,
    eta: &[f64],
    g: &mut Work,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Option<f64> {
    let (n, ne) = (nc.n(), nc.ne());
    let mut sense = false;
    for k in 0..nsteps {
        let time = (step0 + k) as f64 * dt;
        {
            // Phase 1 writes only the slots of this thread's elements (in its own
            // nodes and in the other threads' nodes across the border); the state is
            // only read (its last writes happened before the barrier).
            let xs: [&[f64]; 6] =
                sh.x.map(|p| unsafe { std::slice::from_raw_parts(p as *const f64, n) });
            // SAFETY: `sh.sum` is the block's loads; the threads' elements are disjoint
            // and each has its own slots, which nothing reads in this phase.
            let out = unsafe { LoadsOut::new(sh.sum, nc.width) };
            for p in pieces {
                assert!(p.elems.end <= ne);
                element_tile(nc, lay, p.clone(), xs, eta, &[], g, out);
            }
        }
        barrier.wait(&mut sense);
        {
            // Phase 2 only reads the element loads (written before the barrier) and
            // reads and writes this thread's own nodes.
            let lin = LoadsIn {
                sum: unsafe {
                    std::slice::from_raw_parts(sh.sum as *const f64, loads_len(n, nc.width))
                },
            };
            let xs: [&mut [f64]; 6] =
                sh.x.map(|p| unsafe { std::slice::from_raw_parts_mut(p.add(nr.start), nr.len()) });
            let bad = if nc.c.friction {
                node_pass::<true>(nc, lay, opts, time, dt, nr.clone(), xs, eta, &[], lin, g)
            } else {
                node_pass::<false>(nc, lay, opts, time, dt, nr.clone(), xs, eta, &[], lin, g)
            };
            if let Some(j) = bad {
                failed.fetch_min(nr.start + j, Ordering::AcqRel);
            }
        }
        barrier.wait(&mut sense);
        if failed.load(Ordering::Acquire) != usize::MAX {
            return Some(time + dt);
        }
    }
    None
}
