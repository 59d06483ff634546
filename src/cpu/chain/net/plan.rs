//! The order of a network step's work (a wavefront over tiles of [`NT`] nodes) and
//! where each tile's slots live ([`super::Loads`]).
//!
//! Each thread owns whole tiles of nodes and the elements whose node a is in them, and
//! walks its tiles in order: the elements of tile `t` (their *group* `t`), then the node
//! update of every tile no later group touches. A net's elements join nodes a row or a
//! few rows apart, so tile `t` is done right after group `t`, while its slots are still
//! in the core's cache; and its slots need live only from the first group that writes
//! them to its update, so a few tile buffers serve all the tiles in turn (a net cage
//! of 16 tiles runs on 2 per thread). This keeps the step's working set in the core's
//! L2 (all the tiles' slots did not fit beside the state and the constants).
//!
//! With several threads, a tile that another thread's elements may read (its nodes in
//! the span of nodes that thread's elements reach) is updated after the step's middle
//! barrier instead, with a buffer of its own: phase 1 never writes a node another
//! thread reads. The arithmetic per element and node is the same in every order, so
//! the result is the same bit for bit for any number of threads.

use super::pieces::{owned, Piece};
use super::NT;
use std::ops::Range;

/// One piece of a thread's phase 1.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// Evaluate these elements and write their slots.
    Elems(Piece),
    /// Update tile `t`'s nodes from its slots.
    Nodes(usize),
}

/// One thread's share of a step.
#[derive(Clone, Debug, Default)]
pub struct ThreadPlan {
    /// Phase 1, in order.
    pub ops: Vec<Op>,
    /// Tiles updated in phase 2 (after the barrier), in order.
    pub late: Vec<usize>,
    /// The nodes its elements reach (empty without elements): its own tiles and the
    /// other threads' late tiles only.
    pub reach: Range<usize>,
}

/// A step's work over a block's tiles.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Per thread: its part of the step.
    pub threads: Vec<ThreadPlan>,
    /// Per tile: its buffer in the block's loads (`super::Loads`).
    pub buf: Vec<u32>,
    /// Tile buffers.
    pub nbuf: usize,
    /// Per tile: the slots to zero once its update has read its buffer: the empty
    /// slots (past the incidence list) of the next tile to use that buffer, which this
    /// tile's elements may have filled. Each entry `(i, len, s)` is slot `s` of the
    /// nodes `i .. i + len` (a net's rows of knots of one degree: one entry per row, so
    /// that each column is zeroed by one vector fill). Empty when the buffer is the
    /// tile's alone.
    pub clear: Vec<Vec<(u32, u32, u8)>>,
}

/// The plan for `n` nodes with `width` slots, elements with block-local ends `ea`,
/// `eb` cut into `pieces`, on `threads` threads.
pub fn plan(
    n: usize,
    width: usize,
    ea: &[u32],
    eb: &[u32],
    pieces: &[Piece],
    threads: usize,
) -> Plan {
    let nt = n.div_ceil(NT);
    let tiles = |th: usize| nt * th / threads..nt * (th + 1) / threads;
    let owner: Vec<usize> = (0..threads)
        .flat_map(|th| tiles(th).map(move |_| th))
        .collect();
    let nodes = |t: usize| t * NT..((t + 1) * NT).min(n);
    // The span of nodes each thread's elements reach.
    let mut reach = vec![(usize::MAX, 0usize); threads];
    for (&a, &b) in ea.iter().zip(eb) {
        let (a, b) = (a as usize, b as usize);
        let r = &mut reach[owner[a / NT]];
        *r = (r.0.min(a.min(b)), r.1.max(a.max(b) + 1));
    }
    let late: Vec<bool> = (0..nt)
        .map(|t| {
            let r = nodes(t);
            (0..threads)
                .filter(|&th| th != owner[t])
                .any(|th| reach[th].0 < r.end && r.start < reach[th].1)
        })
        .collect();
    // Per tile: the first and last group that writes its slots (its own group at least).
    let (mut first, mut last): (Vec<usize>, Vec<usize>) = ((0..nt).collect(), (0..nt).collect());
    for (&a, &b) in ea.iter().zip(eb) {
        let g = a as usize / NT;
        for t in [a as usize / NT, b as usize / NT] {
            first[t] = first[t].min(g);
            last[t] = last[t].max(g);
        }
    }
    let mut out = Plan {
        threads: vec![ThreadPlan::default(); threads],
        buf: vec![u32::MAX; nt],
        nbuf: 0,
        clear: vec![Vec::new(); nt],
    };
    // Each buffer's tiles, in the order they use it.
    let mut users: Vec<Vec<usize>> = Vec::new();
    for (th, tp) in out.threads.iter_mut().enumerate() {
        // A local tile's slots are written by its own thread's groups only (another
        // thread's element would have it in its reach).
        let local: Vec<usize> = tiles(th).filter(|&t| !late[t]).collect();
        for g in tiles(th) {
            let own = owned(pieces, ea, &nodes(g));
            tp.ops.extend(own.into_iter().map(Op::Elems));
            tp.ops.extend(
                local
                    .iter()
                    .filter(|&&t| last[t] == g)
                    .map(|&t| Op::Nodes(t)),
            );
        }
        tp.late = tiles(th).filter(|&t| late[t]).collect();
        tp.reach = if reach[th].0 < reach[th].1 {
            reach[th].0..reach[th].1
        } else {
            0..0
        };
        // Local tiles share buffers when their spans `first ..= last` do not overlap
        // (by first group: a greedy colouring of intervals).
        let mut by_first = local.clone();
        by_first.sort_by_key(|&t| (first[t], t));
        let mine0 = users.len();
        for t in by_first {
            let free = (mine0..users.len()).find(|&u| last[*users[u].last().unwrap()] < first[t]);
            let u = free.unwrap_or_else(|| {
                users.push(Vec::new());
                users.len() - 1
            });
            users[u].push(t);
        }
        for &t in &tp.late {
            users.push(vec![t]);
        }
    }
    // Incident elements per node: the slots past them are empty.
    let mut deg = vec![0usize; n];
    for &i in ea.iter().chain(eb) {
        deg[i as usize] += 1;
    }
    let pads = |t: usize| -> Vec<(u32, u32, u8)> {
        // Per slot, the stretches of consecutive nodes that leave it empty.
        let mut out: Vec<(u32, u32, u8)> = Vec::new();
        for s in 0..width {
            let mut i = nodes(t).start;
            while i < nodes(t).end {
                let i0 = i;
                while i < nodes(t).end && deg[i] <= s {
                    i += 1;
                }
                if i > i0 {
                    out.push((i0 as u32, (i - i0) as u32, s as u8));
                }
                i += 1;
            }
        }
        out
    };
    for (u, ts) in users.iter().enumerate() {
        for (k, &t) in ts.iter().enumerate() {
            out.buf[t] = u as u32;
            if ts.len() > 1 {
                out.clear[t] = pads(ts[(k + 1) % ts.len()]);
            }
        }
    }
    out.nbuf = users.len();
    out
}
