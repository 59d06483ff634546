//! Big networks (a net cage: one block of thousands of nodes) stepped by all the pool's
//! threads together, meeting at a spinning barrier twice per step.

use super::passes::{check, element_input, node_accel_of, Ctx, GeneralTopo};
use crate::math::V3;
use crate::model::Block;
use crate::physics::{glmf_element_wet, ElementLoads};
use crate::step::StepFailure;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

type V = V3<f64>;
// ------------------------------------------------------------------ big networks

/// A network block (a net cage) with at least this many nodes is stepped by all the
/// pool's threads together (symplectic GLMF without winch elements); smaller blocks
/// go one per thread as usual.
pub const THREADED_MIN_NODES: usize = 4096;

/// A sense-reversing barrier that spins (then yields): the threads of one block meet
/// twice per step, far more often than a sleeping barrier's wake-up allows.
pub(super) struct SpinBarrier {
    n: usize,
    count: AtomicUsize,
    sense: AtomicBool,
}

impl SpinBarrier {
    pub(super) fn new(n: usize) -> Self {
        Self {
            n,
            count: AtomicUsize::new(0),
            sense: AtomicBool::new(false),
        }
    }

    /// Waits for all `n` threads; `local` is the caller's sense, flipped each call.
    pub(super) fn wait(&self, local: &mut bool) {
        *local = !*local;
        if self.count.fetch_add(1, Ordering::AcqRel) + 1 == self.n {
            self.count.store(0, Ordering::Relaxed);
            self.sense.store(*local, Ordering::Release);
        } else {
            let mut spins = 0u32;
            while self.sense.load(Ordering::Acquire) != *local {
                spins += 1;
                if spins < 1 << 8 {
                    std::hint::spin_loop();
                } else {
                    std::thread::yield_now();
                }
            }
        }
    }
}

/// Raw views of a block's state shared by the threads of [`advance_block_threaded`].
/// Within each phase of a step every element and every node has exactly one writer and
/// nothing reads what is being written (see the function), which the barriers between
/// the phases order.
#[derive(Clone, Copy)]
struct Shared {
    r: *mut V,
    v: *mut V,
    el: *mut ElementLoads<f64>,
}
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

/// Steps one network block (no winch elements, GLMF, symplectic Euler) by `nsteps` with
/// `threads` threads: each owns a contiguous range of elements and of nodes. Per step,
/// phase 1: each thread evaluates its elements (reading every position and velocity,
/// which nobody writes in this phase); barrier; phase 2: each thread updates its nodes
/// (reading every element's loads, which nobody writes now, and its own nodes' state);
/// barrier. The arithmetic per element and per node is the single-thread path's, so
/// the result is the same bit for bit, and a blow-up names the lowest failing node of
/// the first failing step, as there.
#[allow(clippy::too_many_arguments)]
pub(super) fn advance_block_threaded(
    ctx: &Ctx,
    b: &Block,
    r: &mut [V],
    v: &mut [V],
    elems: &mut [ElementLoads<f64>],
    step0: u64,
    dt: f64,
    nsteps: u64,
    threads: usize,
) -> Result<(), StepFailure> {
    let (n, ne) = (r.len(), elems.len());
    let topo = GeneralTopo {
        lay: ctx.lay,
        n0: b.node_start as usize,
        e0: b.elem_start as usize,
    };
    let e0 = b.elem_start as usize;
    let l0s = &ctx.lay.elem_l0[e0..e0 + ne];
    let lines = &ctx.lay.elem_line[e0..e0 + ne];
    let curs = &ctx.lay.elem_current[e0..e0 + ne];
    let sh = Shared {
        r: r.as_mut_ptr(),
        v: v.as_mut_ptr(),
        el: elems.as_mut_ptr(),
    };
    let barrier = SpinBarrier::new(threads);
    // Lowest failing node of the current step (usize::MAX: none yet).
    let failed = AtomicUsize::new(usize::MAX);
    let range = |tid: usize, len: usize| (len * tid / threads)..(len * (tid + 1) / threads);
    let work = |tid: usize| {
        // Capture the whole `Shared` (Sync), not its raw-pointer fields one by one, as
        // the closure's disjoint field capture would.
        #[allow(clippy::redundant_locals)]
        let sh = sh;
        let (er, nr) = (range(tid, ne), range(tid, n));
        let mut sense = false;
        for k in 0..nsteps {
            let t = (step0 + k) as f64 * dt;
            {
                // SAFETY: phase 1 writes only this thread's elements; r and v are only
                // read (the last writes to them happened before the barrier).
                let (r, v) = unsafe {
                    (
                        std::slice::from_raw_parts(sh.r, n),
                        std::slice::from_raw_parts(sh.v, n),
                    )
                };
                let out = unsafe { std::slice::from_raw_parts_mut(sh.el.add(er.start), er.len()) };
                for (o, k) in out.iter_mut().zip(er.clone()) {
                    let d = ctx.lay.line_types[lines[k] as usize].diameter;
                    let (inp, wet) = element_input(ctx, &topo, r, v, &[], k, l0s[k], curs[k], d);
                    *o = glmf_element_wet(&ctx.coefs[lines[k] as usize], &inp, wet, ctx.gravity);
                }
            }
            barrier.wait(&mut sense);
            {
                // SAFETY: phase 2 only reads the elements (written before the barrier)
                // and reads and writes this thread's own nodes.
                let el = unsafe { std::slice::from_raw_parts(sh.el, ne) };
                let rs = unsafe { std::slice::from_raw_parts_mut(sh.r.add(nr.start), nr.len()) };
                let vs = unsafe { std::slice::from_raw_parts_mut(sh.v.add(nr.start), nr.len()) };
                for (j, (ri, vi)) in rs.iter_mut().zip(vs.iter_mut()).enumerate() {
                    let li = nr.start + j;
                    let (a, _, _) =
                        node_accel_of(ctx, &topo, b, li, *ri, *vi, t, None, el, |_, _| {});
                    let vn = *vi + a * dt;
                    let rn = *ri + vn * dt;
                    *vi = vn;
                    *ri = rn;
                    if check(ctx, rn, vn).is_some() {
                        failed.fetch_min(li, Ordering::AcqRel);
                        break;
                    }
                }
            }
            barrier.wait(&mut sense);
            if failed.load(Ordering::Acquire) != usize::MAX {
                return Some(t + dt);
            }
        }
        None
    };
    let stop = std::thread::scope(|sc| {
        let helpers: Vec<_> = (1..threads)
            .map(|tid| sc.spawn(move || work(tid)))
            .collect();
        let mine = work(0);
        for h in helpers {
            h.join().expect("a stepping thread panicked");
        }
        mine
    });
    match stop {
        None => Ok(()),
        Some(time) => {
            let li = failed.load(Ordering::Acquire);
            let what = check(ctx, r[li], v[li]).expect("the failing node fails its check");
            Err(StepFailure::Diverged {
                node: b.node_start as usize + li,
                time,
                what,
            })
        }
    }
}
