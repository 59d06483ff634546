//! The vectorised path for network blocks (net cages, panels: any graph of elements)
//! without winch elements, GLMF, symplectic Euler. It shares the chain path's per-block
//! constants ([`ChainConsts`], which do not assume a chain) and its element loop
//! ([`element_kernel`]), behind a gather front-end:
//! - the element pass walks the elements in pieces ([`pieces`]): a run of elements
//!   whose ends are consecutive nodes (a net's rows and the twines between two rows)
//!   reads its ends in place, as the chain path does, and runs the chain's element
//!   arithmetic over them, in whole chunks of lanes where the run is under the
//!   surface (known from its tiles' flags, [`NetScratch::under`], else tested end by
//!   end) and long enough ([`element_chunks_net`], or with the fold below in the
//!   same loop, [`run_shares`]: the last chunk overlaps the one before it, so no scalar
//!   remainder), else element by element; other elements are read by index and
//!   computed one at a time, straight into their slots ([`gathered_shares`]);
//! - the element pass then folds each element's results into what its two nodes add
//!   (the six entries of its share of their mass block, `m/2 I + a (I - t t^T)`, and
//!   the force on the node: `f/2 + T t` on node a, `f/2 - T t` on node b) and writes
//!   them into the node's *slot*: each node has 4 or 8 slots (its incidence list,
//!   padded with zeros), each slot 9 columns over tiles of [`NT`] nodes, so that the
//!   node pass reads them contiguously, 4 nodes at a time (a run's elements write
//!   their slots with vector stores too: the pieces keep one slot per end);
//! - the node pass ([`node_pass`]) sums those slots in incidence order and solves each
//!   node's 3x3 mass block with the general path's adjugate
//!   ([`Sym3::solve`](crate::math::Sym3::solve)), in one loop vectorised over nodes,
//!   then updates and checks the tile's nodes in another;
//! - point-mass drag, a point's water-acceleration load and held nodes are done from
//!   short index lists, as on the chain path.
//!
//! The two passes alternate tile by tile ([`plan`]): the elements whose node a is in
//! tile `t`, then the update of every tile whose slots are complete, so that a tile's
//! slots are read while still in the core's cache and a few tile buffers hold them
//! all. They run over pieces of elements and tiles of nodes, so a big block is
//! stepped by all the pool's threads with the same arithmetic per element and per node
//! (the same bits), meeting twice per step at a spinning barrier
//! ([`advance_net_threaded`]).
//! A node with more than 8 incident elements sends its block to the general path.
//! A test checks it against the general path (`tests/cpu/net_kernel.rs`).

use super::consts::ChainConsts;
use super::elements::element_kernel;
use crate::cpu::screen::{BlockPanels, PanelScratch};
use crate::cpu::water::{node_water, BlockWaves, Water};
use crate::math::V3;
use crate::model::{Block, Layout};
use crate::options::SolverOptions;
use crate::step::{diverged, StepFailure};
use element_chunks::{all_under, element_chunks_net};
use std::sync::atomic::{AtomicBool, Ordering};

mod element_chunks;
mod fold;
mod gathered;
mod node_pass;
pub(crate) mod pieces;
pub(crate) mod plan;
mod threaded;
use fold::{node_shares, run_shares};
use gathered::gathered_shares;
use node_pass::{node_pass, node_pass_either};
use pieces::{pieces, Piece, TILE};
use plan::{plan, Op, Plan};
pub(crate) use threaded::advance_net_threaded;

/// Per-block constants of a network, built once.
#[derive(Clone, Debug)]
pub(crate) struct NetConsts {
    c: ChainConsts,
    /// Block-local end nodes `a`, `b` per element.
    ends: [Vec<u32>; 2],
    /// The element pass's pieces, in element order.
    pieces: Vec<Piece>,
    /// Slots per node: 4 or 8.
    width: usize,
    /// Per element: its place (slot) in the incidence list of its node a and of its
    /// node b, in the layout's order (the order the node pass sums in).
    eslot: [Vec<u8>; 2],
    /// The one-thread step's order and tile buffers.
    plan1: Plan,
    /// The block's screen-net panels (empty where it holds no knot of one).
    screen: BlockPanels,
}

impl NetConsts {
    /// Folds the layout's constants for network block `b`; `None` when a node has
    /// more than 8 incident elements (the block takes the general path).
    pub(crate) fn new(lay: &Layout, b: &Block) -> Option<Self> {
        // Tabulated strain-tension curves: the general passes.
        if lay.block_has_curves(b) {
            return None;
        }
        let (n0, e0) = (b.node_start as usize, b.elem_start as usize);
        let n = (b.node_end - b.node_start) as usize;
        let deg = (0..n).map(|i| lay.incidence(n0 + i).len()).max()?;
        let width = match deg {
            0..=4 => 4,
            5..=8 => 8,
            _ => return None,
        };
        let elems = b.elem_start as usize..b.elem_end as usize;
        let ne = elems.len();
        // Side 0 of an incidence is the element's node a, side 1 its node b.
        let mut eslot = [vec![u8::MAX; ne], vec![u8::MAX; ne]];
        for i in 0..n {
            for (s, &inc) in lay.incidence(n0 + i).iter().enumerate() {
                eslot[(inc & 1) as usize][(inc >> 1) as usize - e0] = s as u8;
            }
        }
        let ends: [Vec<u32>; 2] = [
            elems.clone().map(|e| lay.elem_a[e] - n0 as u32).collect(),
            elems.map(|e| lay.elem_b[e] - n0 as u32).collect(),
        ];
        // The passes index by these without bounds checks; every element sits in one
        // slot of each of its nodes.
        assert!(ends.iter().flatten().all(|&i| (i as usize) < n));
        assert!(eslot.iter().flatten().all(|&s| (s as usize) < width));
        let c = ChainConsts::new(lay, b);
        // The node pass takes each tile's share of these lists by binary search.
        assert!(c.constrained.is_sorted_by_key(|p| p.0));
        assert!(c.point_drag.is_sorted_by_key(|p| p.0));
        assert!(c.point_volume.is_sorted_by_key(|p| p.0));
        let pieces = pieces(&ends[0], &ends[1], &eslot[0], &eslot[1]);
        let plan1 = plan(n, width, &ends[0], &ends[1], &pieces, 1);
        Some(Self {
            c,
            pieces,
            ends,
            width,
            eslot,
            plan1,
            screen: BlockPanels::new(lay, n0, n0 + n),
        })
    }

    /// Re-reads the constraint numbers of block `b` of `lay` (the same network,
    /// possibly renumbered by a rebuild).
    pub(crate) fn refresh_constraints(&mut self, lay: &Layout, b: &Block) {
        self.c.refresh_constraints(lay, b);
    }

    fn n(&self) -> usize {
        self.c.n
    }

    fn ne(&self) -> usize {
        self.ends[0].len()
    }
}

/// A network's state and scratch, reused across blocks.
#[derive(Default)]
pub(crate) struct NetScratch {
    /// Node state, `[x, y, z, vx, vy, vz]`.
    x: [Vec<f64>; 6],
    /// Surface elevation over each node, m (zero in still water).
    eta: Vec<f64>,
    /// Per tile of [`NT`] nodes: whether every node is at or below the surface in the
    /// state the next element pass reads ([`flag_tiles`]; in still water the node
    /// pass sets its tile's as it updates it). Atomic: the threads of
    /// [`advance_net_threaded`] set their tiles' and read the others' (across the
    /// barriers).
    under: Vec<AtomicBool>,
    el: Loads,
    /// One thread's work of either pass (the first thread's when threaded).
    work: Work,
}

/// Columns per slot in [`Loads`].
const COLS: usize = 9;

/// Nodes per tile of the block's loads (`Loads`).
pub const NT: usize = 256;

/// Distance between two columns of a tile: [`NT`] values and a cache line. At `NT`
/// (2 KiB) the 36 or 72 columns the node loop reads at once would fall in 2 of the 64
/// sets of a 48 KiB, 12-way L1 (a set every 4 KiB) and evict each other; 33 lines
/// apart (odd), 64 columns in a row fall in 64 different sets.
const CS: usize = NT + 8;

/// What each element adds to each of its nodes, in the node's slot for it: slot `s`
/// of node `i` is columns `COLS s .. COLS (s + 1)`. The nodes go in tiles of [`NT`]
/// (the last padded), each tile's slots in a tile buffer ([`Plan::buf`]; tiles whose
/// slots are not live at once share one) that holds all `width COLS` columns of its
/// nodes one after the other, [`CS`] apart: node `i`'s column `c` is at
/// `sum[buf[i / NT] width COLS CS + c CS + i % NT]`,
/// so that within a tile every column is at a fixed offset from the others (one base
/// address for all of them in the node loop). A column holds the element's share of
/// the node's mass block `xx, yy, zz, xy, xz, yz`, then its force on the node. Slots
/// past a node's incidence list are zero when its tile's elements start
/// ([`Plan::clear`]).
#[derive(Default)]
struct Loads {
    /// The values from `sum[off]` on ([`Loads::start`]).
    sum: Vec<f64>,
    /// The first value at a 64-byte boundary: with [`CS`] a whole number of cache
    /// lines, every column then starts on one, and the node loop's loads of a chunk of
    /// nodes do not straddle two lines.
    off: usize,
}

impl Loads {
    /// Sized for [`loads_len`] values, zero, from a 64-byte boundary.
    fn reset(&mut self, len: usize) {
        self.sum.clear();
        self.sum.resize(len + 8, 0.0);
        self.off = self.sum.as_ptr().align_offset(64);
        assert!(self.off + len <= self.sum.len());
    }

    /// The first of the [`loads_len`] values.
    fn start(&mut self) -> *mut f64 {
        // SAFETY: `off` is within the buffer (`reset`).
        unsafe { self.sum.as_mut_ptr().add(self.off) }
    }
}

/// Values of [`Loads`] with `nbuf` tile buffers of `width` slots.
fn loads_len(nbuf: usize, width: usize) -> usize {
    nbuf * width * COLS * CS
}

/// One thread's scratch: element work over a piece of its elements, node work over a
/// tile of its nodes.
#[derive(Default)]
struct Work {
    /// Water velocity (current, plus waves) and wave acceleration per element.
    u: [Vec<f64>; 3],
    aw: [Vec<f64>; 3],
    /// The element loop's results: tangent, tension, half external load, the wetted
    /// half masses (along the tangent, and what the normal plane has more: `hmw`
    /// written only by the loop over elements, `element_kernel`).
    t: [Vec<f64>; 3],
    ten: Vec<f64>,
    f: [Vec<f64>; 3],
    hmw: Vec<f64>,
    haw: Vec<f64>,
    /// Per node of the tile being updated ([`NT`] each): point mass and weight (less
    /// what the dry share of a point loses), point loads (drag, water acceleration;
    /// zero but at the tile's listed nodes while it is updated), acceleration.
    pm: Vec<f64>,
    pwz: Vec<f64>,
    ex: [Vec<f64>; 3],
    acc: [Vec<f64>; 3],
    /// Screen-model nets: each knot's share of its panels' loads at the step's start
    /// (block-local node, sorted), added to `ex` by the node pass.
    screen: Vec<(usize, [f64; 3])>,
    /// Screen-model nets: the panel pass's scratch ([`BlockPanels::panel_forces`]).
    panel: PanelScratch,
}

impl Work {
    /// Sized for `ne` elements and a tile of nodes.
    fn size(&mut self, ne: usize) {
        let per_elem = (self.u.iter_mut().chain(&mut self.aw))
            .chain(self.t.iter_mut().chain(&mut self.f))
            .chain([&mut self.ten, &mut self.hmw, &mut self.haw]);
        for v in per_elem {
            // Zero: the surface columns stay so in still water.
            v.clear();
            v.resize(ne, 0.0);
        }
        let per_node = [&mut self.pm, &mut self.pwz].into_iter();
        for v in per_node.chain(&mut self.ex).chain(&mut self.acc) {
            v.clear();
            v.resize(NT, 0.0);
        }
    }
}

/// A block's [`Loads`] seen through a raw pointer: the element pass writes each
/// element's two slots, the node pass reads a tile's buffer, while the threads of
/// [`advance_net_threaded`] do the same in other buffers (each slot of each node has
/// one element, so one writer).
#[derive(Clone, Copy)]
struct LoadsOut<'a> {
    sum: *mut f64,
    /// Values per tile buffer: `width COLS CS`.
    per_tile: usize,
    /// Per tile: its buffer.
    buf: &'a [u32],
}

impl<'a> LoadsOut<'a> {
    /// # Safety
    /// `sum` points at the [`loads_len`] values of a block's [`Loads`] with `width`
    /// slots ([`NetConsts::width`]) in the buffers of `plan`, and while this is used
    /// nothing else reads or writes the slots it is used on.
    unsafe fn new(sum: *mut f64, width: usize, plan: &'a Plan) -> Self {
        Self {
            sum,
            per_tile: width * COLS * CS,
            buf: &plan.buf,
        }
    }

    /// Column `c` of the nodes `i0 .. i0 + len`, all in one tile.
    ///
    /// # Safety
    /// The nodes are in the block and in one tile (`i0 % NT + len <= NT`), `c` below
    /// `width COLS`, and no other live slice covers them.
    #[inline(always)]
    // A view through the raw pointer, not a borrow of `self` (the safety contract above).
    #[allow(clippy::mut_from_ref)]
    unsafe fn column(&self, c: usize, i0: usize, len: usize) -> &mut [f64] {
        debug_assert!(i0 % NT + len <= NT && c * CS < self.per_tile);
        let b = unsafe { *self.buf.get_unchecked(i0 / NT) } as usize;
        let o = b * self.per_tile + c * CS + i0 % NT;
        unsafe { std::slice::from_raw_parts_mut(self.sum.add(o), len) }
    }

    /// Tile `t`'s buffer, to read.
    ///
    /// # Safety
    /// `t` is a tile of the block and nothing writes its buffer while this lives.
    #[inline(always)]
    unsafe fn tile(&self, t: usize) -> &'a [f64] {
        let o = self.buf[t] as usize * self.per_tile;
        unsafe { std::slice::from_raw_parts(self.sum.add(o) as *const f64, self.per_tile) }
    }

    /// Zeroes the slots `pads` ([`Plan::clear`]: slot `s` of nodes `i .. i + len`, all
    /// of them in one tile).
    ///
    /// # Safety
    /// As [`LoadsOut::column`] for each of their columns.
    #[inline(always)]
    unsafe fn clear(&self, pads: &[(u32, u32, u8)]) {
        for &(i, len, s) in pads {
            for q in 0..COLS {
                unsafe {
                    self.column(COLS * s as usize + q, i as usize, len as usize)
                        .fill(0.0)
                };
            }
        }
    }
}

/// The element pass over the elements of `piece`: reads their ends' state `x` and
/// surface `eta` (both from block node `base` on: the nodes the elements reach) in
/// place (a run) or by index (gathered elements: [`gathered_shares`], element by
/// element), their water velocity and acceleration (`w`: per-node water values, empty
/// in still water), runs the chain path's element loop, and folds its results into
/// what the elements add to their nodes (`out`): a submerged run in one loop
/// ([`run_shares`]), other runs in two. `under`: the block's tile flags
/// ([`NetScratch::under`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn element_tile<const L: usize>(
    nc: &NetConsts,
    lay: &Layout,
    piece: Piece,
    x: [&[f64]; 6],
    base: usize,
    eta: &[f64],
    w: &[f64],
    under: &[AtomicBool],
    g: &mut Work,
    out: LoadsOut,
) {
    let c = &nc.c;
    let er = piece.elems.clone();
    let ne = er.len();
    let (ea, eb) = (&nc.ends[0][er.clone()], &nc.ends[1][er.clone()]);
    let waves = !w.is_empty();
    let src: [&[f64]; 7] = [x[0], x[1], x[2], x[3], x[4], x[5], eta];
    let n = x[0].len();
    assert!(src.iter().all(|q| q.len() == n));
    let Some((a0, b0)) = piece.ends else {
        if waves {
            gathered_shares::<true>(nc, lay, er, src, base, w, out);
        } else {
            gathered_shares::<false>(nc, lay, er, src, base, w, out);
        }
        return;
    };
    let Work {
        u,
        aw,
        t,
        ten,
        f,
        hmw,
        haw,
        ..
    } = g;
    // Every end at or below the surface makes every wetted fraction exactly 1, as on
    // the chain path: known at once where the ends' tiles are all under (the net
    // cage's every piece), else tested end by end. In still water the surface is at
    // zero (`eta` stays so), where `0 - z >= 0` is `z <= 0`: the surface's columns
    // need not be read.
    let flagged = tiles_under(under, a0, ne) && tiles_under(under, b0, ne);
    // A run: the ends are consecutive nodes, read in place as on the chain path.
    let (a0, b0) = (a0 - base, b0 - base);
    let (a, b) = (cut(src, a0..a0 + ne), cut(src, b0..b0 + ne));
    let submerged = flagged
        || if waves {
            all_under::<true, L>(a, b, ne)
        } else {
            all_under::<false, L>(a, b, ne)
        };
    // Such a piece of `L` elements or more takes the loop in whole chunks of lanes,
    // which reads a uniform current in still water as a constant.
    let chunked = submerged && ne >= L;
    let uniform = c.uniform.filter(|_| !waves);
    match c.uniform {
        Some(_) if chunked && uniform.is_some() => {}
        Some(un) => {
            for (q, uq) in u.iter_mut().enumerate() {
                uq[..ne].fill(un[q]);
            }
        }
        None => {
            for k in 0..ne {
                let v = lay.currents[c.current[er.start + k] as usize]
                    .at::<f64>(0.5 * (a[2][k] + b[2][k]))
                    .to_f64();
                for q in 0..3 {
                    u[q][k] = v[q];
                }
            }
        }
    }
    if waves {
        // The mean of the two ends' wave velocity and acceleration.
        for k in 0..ne {
            let (_, ua, aa) = node_water(w, ea[k] as usize);
            let (_, ub, ab) = node_water(w, eb[k] as usize);
            for q in 0..3 {
                u[q][k] += 0.5 * (ua[q] + ub[q]);
                aw[q][k] = 0.5 * (aa[q] + ab[q]);
            }
        }
    }
    if chunked {
        // A run: the element loop and the fold in one loop, where it can.
        let (us, aws) = (u.each_ref().map(|q| &q[..]), aw.each_ref().map(|q| &q[..]));
        let (es, p, v) = (&nc.eslot, &piece, ([a0, b0], x));
        let fused = match (waves, uniform) {
            (true, _) => run_shares::<true, false, L>(c, es, p, a, b, us, [0.0; 3], aws, v, out),
            (false, Some(un)) => run_shares::<false, true, L>(c, es, p, a, b, us, un, aws, v, out),
            (false, None) => {
                run_shares::<false, false, L>(c, es, p, a, b, us, [0.0; 3], aws, v, out)
            }
        };
        if fused {
            return;
        }
    }
    let (ten, hmw, haw) = (&mut ten[..ne], &mut hmw[..ne], &mut haw[..ne]);
    {
        let [tx, ty, tz] = t.each_mut().map(|q| &mut q[..ne]);
        let [fx, fy, fz] = f.each_mut().map(|q| &mut q[..ne]);
        if chunked {
            // Whole chunks of lanes (the same bits as the loop below).
            let (u, aw) = (u.each_ref().map(|q| &q[..]), aw.each_ref().map(|q| &q[..]));
            let out = [tx, ty, tz, ten, fx, fy, fz, haw];
            match (waves, uniform) {
                (true, _) => {
                    element_chunks_net::<true, false, L>(a, b, u, [0.0; 3], aw, c, er.start, out)
                }
                (false, Some(un)) => {
                    element_chunks_net::<false, true, L>(a, b, u, un, aw, c, er.start, out)
                }
                (false, None) => {
                    element_chunks_net::<false, false, L>(a, b, u, [0.0; 3], aw, c, er.start, out)
                }
            }
        } else {
            macro_rules! kernel {
                ($waves:literal, $submerged:literal) => {
                    element_kernel::<$waves, $submerged>(
                        a, b, &u[0], &u[1], &u[2], &aw[0], &aw[1], &aw[2], c, er.start, tx, ty, tz,
                        &mut *ten, fx, fy, fz, &mut *hmw, &mut *haw,
                    )
                };
            }
            match (waves, submerged) {
                (true, true) => kernel!(true, true),
                (true, false) => kernel!(true, false),
                (false, true) => kernel!(false, true),
                (false, false) => kernel!(false, false),
            }
        }
    }
    // Submerged in whole chunks: the block's half masses along the tangents (what the
    // loop over elements writes to `hmw` wholly wet, bit for bit).
    let hm = if chunked {
        &c.hm[er.start + 1..er.start + 1 + ne]
    } else {
        &hmw[..]
    };
    node_shares::<L>(nc, &piece, t, ten, f, hm, haw, out);
}

/// Whether the tiles of block nodes `i0 .. i0 + len` (`len` at least 1) are all
/// flagged under the surface ([`NetScratch::under`]): one load per tile, where testing
/// the run's ends cost 14 instructions a chunk of 4 elements (7 a node-step of the
/// cage, 5% of its step).
#[inline(always)]
fn tiles_under(under: &[AtomicBool], i0: usize, len: usize) -> bool {
    (i0 / NT..=(i0 + len - 1) / NT).all(|t| under[t].load(Ordering::Relaxed))
}

/// Sets each tile's flag of `under` ([`NetScratch::under`]) to whether every node of
/// it is at or below the surface: `eta - z >= 0` (the wetted fraction's test; `z <= 0`
/// in still water, whose `eta` is zero), false for a NaN.
fn flag_tiles(z: &[f64], eta: &[f64], under: &[AtomicBool]) {
    for (t, u) in under.iter().enumerate() {
        let r = t * NT..((t + 1) * NT).min(z.len());
        u.store(
            r.into_iter().all(|i| eta[i] - z[i] >= 0.0),
            Ordering::Relaxed,
        );
    }
}

/// Entries `r` of each of the columns `cols`. (A loop, not `array::map`: the map over
/// 7 slices stayed a call of 60 instructions, about 1 a node-step per use on the cage.)
#[inline(always)]
fn cut<const K: usize>(cols: [&[f64]; K], r: std::ops::Range<usize>) -> [&[f64]; K] {
    let mut out: [&[f64]; K] = [&[]; K];
    for (o, c) in out.iter_mut().zip(cols) {
        *o = &c[r.clone()];
    }
    out
}

/// Copies the block's AoS state into the scratch's SoA arrays and sizes the element
/// results (the tile buffers of `plan`), surface (zero: still water until the waves
/// fill it) and tile flags (set from the state).
fn load(nc: &NetConsts, plan: &Plan, sc: &mut NetScratch, r: &[V3<f64>], v: &[V3<f64>]) {
    let n = nc.n();
    for (q, xq) in sc.x.iter_mut().enumerate() {
        xq.clear();
        xq.extend((0..n).map(|i| {
            if q < 3 {
                r[i].to_f64()[q]
            } else {
                v[i].to_f64()[q - 3]
            }
        }));
    }
    sc.eta.clear();
    sc.eta.resize(n, 0.0);
    sc.under.clear();
    sc.under.resize_with(n.div_ceil(NT), AtomicBool::default);
    flag_tiles(&sc.x[2], &sc.eta, &sc.under);
    // Zero: the slots past a node's incidence list stay so.
    sc.el.reset(loads_len(plan.nbuf, nc.width));
}

/// Copies the SoA state back to `r`, `v`.
fn store(sc: &NetScratch, r: &mut [V3<f64>], v: &mut [V3<f64>]) {
    let x = &sc.x;
    for i in 0..r.len() {
        r[i] = V3::new(x[0][i], x[1][i], x[2][i]);
        v[i] = V3::new(x[3][i], x[4][i], x[5][i]);
    }
}

/// Advances a network block by `nsteps` symplectic steps on one thread; `r`, `v` are
/// its AoS state (block-local), `n0` its first packed node.
#[allow(clippy::too_many_arguments)]
pub(crate) fn advance_net(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut NetScratch,
    r: &mut [V3<f64>],
    v: &mut [V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    #[cfg(target_arch = "x86_64")]
    {
        if avx512() {
            // SAFETY: the CPU has AVX-512 (F, DQ, VL), checked just above.
            return unsafe {
                advance_net_avx512(nc, lay, opts, sc, r, v, n0, waves, wbuf, step0, dt, nsteps)
            };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            return unsafe {
                advance_net_avx2(nc, lay, opts, sc, r, v, n0, waves, wbuf, step0, dt, nsteps)
            };
        }
    }
    advance_net_body::<4>(nc, lay, opts, sc, r, v, n0, waves, wbuf, step0, dt, nsteps)
}

/// Whether the network loops take 8 lanes ([`crate::lanes::net_avx512_wanted`]).
#[cfg(target_arch = "x86_64")]
fn avx512() -> bool {
    crate::lanes::net_avx512_wanted()
}

/// The same, compiled for AVX-512 (8 lanes to a vector).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512dq,avx512vl")]
#[allow(clippy::too_many_arguments)]
unsafe fn advance_net_avx512(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut NetScratch,
    r: &mut [V3<f64>],
    v: &mut [V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    advance_net_body::<8>(nc, lay, opts, sc, r, v, n0, waves, wbuf, step0, dt, nsteps)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn advance_net_avx2(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut NetScratch,
    r: &mut [V3<f64>],
    v: &mut [V3<f64>],
    n0: usize,
    waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    advance_net_body::<4>(nc, lay, opts, sc, r, v, n0, waves, wbuf, step0, dt, nsteps)
}

/// The screen-net knot forces of the block from its columns `x` (block-local), into
/// `out` (`Work::screen`): the panels' forces into `sc`, then each knot's share.
#[inline(never)]
fn screen_tile_forces(
    nc: &NetConsts,
    lay: &Layout,
    x: &[Vec<f64>; 6],
    w: &[f64],
    sc: &mut PanelScratch,
    out: &mut Vec<(usize, [f64; 3])>,
) {
    let col = |q: usize, i: usize| V3::new(x[q][i], x[q + 1][i], x[q + 2][i]);
    nc.screen.panel_forces(
        lay,
        sc,
        |i| col(0, i),
        |i| col(3, i),
        |i| (!w.is_empty()).then(|| node_water(w, i).1),
    );
    nc.screen.gather(sc, out, |f| f.to_f64());
}

/// `L`: the lanes of the element and fold loops' chunks (4 with AVX2, 8 with AVX-512).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn advance_net_body<const L: usize>(
    nc: &NetConsts,
    lay: &Layout,
    opts: &SolverOptions,
    sc: &mut NetScratch,
    r: &mut [V3<f64>],
    v: &mut [V3<f64>],
    n0: usize,
    mut waves: Option<&mut BlockWaves>,
    wbuf: &mut Water,
    step0: u64,
    dt: f64,
    nsteps: u64,
) -> Result<(), StepFailure> {
    let n = nc.n();
    let plan = &nc.plan1;
    load(nc, plan, sc, r, v);
    if waves.is_none() {
        wbuf.clear();
    }
    let NetScratch {
        x,
        eta,
        under,
        el,
        work,
    } = sc;
    work.size(nc.ne().min(TILE));
    work.screen.clear();
    let mut result = Ok(());
    for k in 0..nsteps {
        let time = (step0 + k) as f64 * dt;
        if let Some(wb) = waves.as_deref_mut() {
            let st = |i: usize| ([x[0][i], x[1][i], x[2][i]], [x[3][i], x[4][i], x[5][i]]);
            wb.fill(time, n, st, wbuf);
            for (i, e) in eta.iter_mut().enumerate() {
                *e = node_water(wbuf, i).0;
            }
            // The surface moved: the node pass's flags were for still water's.
            flag_tiles(&x[2], eta, under);
        }
        if !nc.screen.is_empty() {
            screen_tile_forces(nc, lay, x, wbuf, &mut work.panel, &mut work.screen);
        }
        // SAFETY: `el` is this block's loads in `plan`'s buffers (`load`), and only
        // this loop uses them, one op at a time.
        let out = unsafe { LoadsOut::new(el.start(), nc.width, plan) };
        // The lowest node over the limits in this step.
        let mut bad = None::<usize>;
        for op in &plan.threads[0].ops {
            match op {
                Op::Elems(p) => {
                    let xs: [&[f64]; 6] = std::array::from_fn(|q| &x[q][..]);
                    element_tile::<L>(nc, lay, p.clone(), xs, 0, eta, wbuf, under, work, out);
                }
                &Op::Nodes(t) => {
                    let nr = t * NT..((t + 1) * NT).min(n);
                    let xs = x.each_mut().map(|q| &mut q[nr.clone()]);
                    // SAFETY: nothing writes tile `t`'s buffer during its update.
                    let sum = unsafe { out.tile(t) };
                    let b = node_pass_either!(
                        nc,
                        lay,
                        opts,
                        time,
                        dt,
                        nr.clone(),
                        xs,
                        eta,
                        wbuf,
                        sum,
                        work,
                        &under[t],
                    );
                    // SAFETY: the next user of this buffer has not started.
                    unsafe { out.clear(&plan.clear[t]) };
                    if let Some(j) = b {
                        bad = Some(bad.map_or(nr.start + j, |b| b.min(nr.start + j)));
                    }
                }
            }
        }
        if let Some(i) = bad {
            result = Err((i, time + dt));
            break;
        }
    }
    store(sc, r, v);
    result.map_err(|(i, time)| diverged(opts, r[i], v[i], n0 + i, time))
}
