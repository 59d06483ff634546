//! Whole vectors of lanes for the chain fast path's loops. The chain's columns are
//! padded to a multiple of [`MAX_LANES`] (plus one more chunk, for the element loop's
//! node `k + 1` and the node loop's padded element `i + 1`), so each loop runs over
//! whole `[f64; L]` chunks (`L` = 4 with AVX2, 8 with AVX-512): no scalar remainder,
//! and no run-time overlap checks (each chunk loads its inputs into locals before it
//! stores, which the compiler's straight-line (SLP) vectoriser turns into vector
//! loads, arithmetic and stores). The padding lanes compute on zeros and their
//! results are never read (or are reset: the end ghost element, the padding nodes'
//! accelerations). Every lane does the same arithmetic as a scalar loop would, so the
//! lane count does not change a bit of the results.

/// The most lanes per chunk (8 f64, one AVX-512 register); the padding is for it.
pub const MAX_LANES: usize = 8;

/// `KEEP[k]`: the bits that keep the first `k` lanes of a chunk and clear the rest
/// (`f64::from_bits(v.to_bits() & KEEP[k][l])`: `v` or `+0.0`). One AND a column on
/// a chain's last chunk zeroes its padding lanes whatever they hold (NaN included),
/// in vector code: the same select written as `if first + l < n { v } else { 0 }`
/// was compiled to a compare, a branch and a store per lane (about 55 instructions a
/// step with 4 lanes, about 140 with 8).
pub static KEEP: [[u64; MAX_LANES]; MAX_LANES + 1] = keep_table();

const fn keep_table() -> [[u64; MAX_LANES]; MAX_LANES + 1] {
    let mut t = [[0u64; MAX_LANES]; MAX_LANES + 1];
    let mut k = 0;
    while k <= MAX_LANES {
        let mut l = 0;
        while l < k {
            t[k][l] = u64::MAX;
            l += 1;
        }
        k += 1;
    }
    t
}

/// Chunks of `L` lanes that cover `n` entries.
#[inline(always)]
pub(super) fn chunks_for<const L: usize>(n: usize) -> usize {
    n.div_ceil(L)
}

/// The padded length of the columns of a chain of `n` nodes: the node chunks, plus
/// one chunk for the reads one entry further on.
#[inline(always)]
pub(crate) fn padded_len(n: usize) -> usize {
    (chunks_for::<MAX_LANES>(n) + 1) * MAX_LANES
}

/// The stride of a chain's column blocks ([`Columns`]): [`SHORT_STRIDE`] when its
/// [`padded_len`] fits, else the padded length. The chain's per-stage block and its
/// waves' cache columns (`cpu::water`) take the same, so that the element loop
/// reaches both by constant displacements.
#[inline(always)]
pub(crate) fn column_stride(n: usize) -> usize {
    padded_len(n).max(SHORT_STRIDE)
}

/// The first `nc` chunks of `s`.
///
/// # Safety
/// `s` has at least `nc * L` entries. The chain's columns are made
/// [`padded_len`]`(n)` long once per run of steps and never resized during it, and
/// `nc` is at most `chunks_for::<L>(n)`, so every column holds the chunks read here
/// and one more entry (what checking each column at each stage cost: about 250
/// instructions a step of Case 2, 6% of it).
#[inline(always)]
pub(super) unsafe fn lanes<const L: usize>(s: &[f64], nc: usize) -> &[[f64; L]] {
    debug_assert!(nc * L <= s.len(), "a column shorter than its chunks");
    // SAFETY: `[f64; L]` has the layout of `L` consecutive f64; the caller
    // guarantees the entries.
    unsafe { std::slice::from_raw_parts(s.as_ptr().cast::<[f64; L]>(), nc) }
}

/// The first `nc` chunks of `s` from entry 1 on (node `k + 1` of element `k`, padded
/// element `i + 1` of node `i`).
///
/// # Safety
/// `s` has at least `nc * L + 1` entries (see [`lanes`]).
#[inline(always)]
pub(super) unsafe fn lanes_next<const L: usize>(s: &[f64], nc: usize) -> &[[f64; L]] {
    debug_assert!(nc * L < s.len(), "a column shorter than its chunks");
    // SAFETY: as in `lanes`, one entry further on.
    unsafe { std::slice::from_raw_parts(s.as_ptr().add(1).cast::<[f64; L]>(), nc) }
}

/// The first `nc` chunks of `s`, mutable (from entry `off`, 0 or 1).
///
/// # Safety
/// `s` has at least `nc * L + off` entries (see [`lanes`]).
#[inline(always)]
pub(super) unsafe fn lanes_mut<const L: usize>(
    s: &mut [f64],
    off: usize,
    nc: usize,
) -> &mut [[f64; L]] {
    debug_assert!(nc * L + off <= s.len(), "a column shorter than its chunks");
    // SAFETY: as in `lanes`; `s` is borrowed mutably for the result's lifetime.
    unsafe { std::slice::from_raw_parts_mut(s.as_mut_ptr().add(off).cast::<[f64; L]>(), nc) }
}

/// Keeps the loop vectoriser off a loop over chunks, whose body the straight-line
/// vectoriser has already made vector code: it would otherwise vectorise across
/// chunks too (four chunks at a time, lanes shuffled, with run-time overlap checks
/// and a scalar remainder: slower at a chain's few chunks). An empty `asm!`: no
/// instruction.
#[inline(always)]
pub(super) fn keep_chunks() {
    #[cfg(any(target_arch = "x86_64", target_arch = "aarch64"))]
    // SAFETY: an empty asm statement that reads and writes nothing.
    unsafe {
        std::arch::asm!("", options(nomem, nostack, preserves_flags))
    }
}

/// The distance between two columns of a [`Columns`] block, in entries: known at
/// compile time ([`Fixed`]) for short chains, so that a loop reaches every column from
/// one base register by constant displacements, or at run time ([`Dyn`]) for long ones
/// (then the compiler keeps a pointer a column, as for separate `Vec`s).
pub(super) trait Stride: Copy {
    fn get(self) -> usize;
}

/// A stride known at compile time.
#[derive(Clone, Copy)]
pub(super) struct Fixed<const S: usize>;

impl<const S: usize> Stride for Fixed<S> {
    #[inline(always)]
    fn get(self) -> usize {
        S
    }
}

/// A stride known at run time.
#[derive(Clone, Copy)]
pub(super) struct Dyn(pub(super) usize);

impl Stride for Dyn {
    #[inline(always)]
    fn get(self) -> usize {
        self.0
    }
}

/// The fixed stride of the short chains' blocks: chains whose [`padded_len`] fits in
/// it (up to 128 nodes; Case 2's 21-61, the catenary's 51) take it. 136 entries, 1088
/// bytes: whole 64-byte lines, and not a divisor of 4096, so that two columns' same
/// entries do not fall 4 KiB apart (where a load after a store to the other column
/// would wait on a false dependence).
pub(crate) const SHORT_STRIDE: usize = 136;

/// Columns of one allocation, `stride` entries apart (each column [`padded_len`] long
/// or longer; the entries past it are zero and never read). The node loop reads 14
/// columns of per-stage results: as separate `Vec`s, 14 pointers for the 15 free
/// general registers, spilled to the stack and reloaded each chunk; here one base.
#[derive(Default)]
pub(super) struct Columns {
    data: Vec<f64>,
    stride: usize,
}

impl Columns {
    /// `ncols` columns of `stride` zeros.
    pub(super) fn reset(&mut self, ncols: usize, stride: usize) {
        self.stride = stride;
        self.data.clear();
        self.data.resize(ncols * stride, 0.0);
    }

    /// A view of the block whose stride is `st`'s (a constant when `St` is [`Fixed`]).
    ///
    /// # Panics
    /// If `st` is not the block's stride.
    #[inline(always)]
    pub(super) fn view<St: Stride>(&mut self, st: St) -> ColumnsView<'_, St> {
        assert_eq!(st.get(), self.stride, "a view of another stride");
        ColumnsView {
            base: self.data.as_mut_ptr(),
            st,
            _block: std::marker::PhantomData,
        }
    }
}

/// The columns of a [`Columns`] block through one base pointer. Its accessors hand
/// out column slices of any lifetime up to the block's borrow: the caller keeps a
/// column it writes from being read or written through another slice at the same time.
pub(super) struct ColumnsView<'a, St> {
    base: *mut f64,
    st: St,
    _block: std::marker::PhantomData<&'a mut [f64]>,
}

impl<'a, St: Stride> ColumnsView<'a, St> {
    /// The block's stride.
    #[inline(always)]
    pub(super) fn stride(&self) -> St {
        self.st
    }

    /// Column `q`, whole.
    ///
    /// # Safety
    /// `q` is a column of the block, not written through another slice while this one lives.
    #[inline(always)]
    pub(super) unsafe fn col(&self, q: usize) -> &'a [f64] {
        // SAFETY: the block holds its columns `stride` apart; the caller's `q`.
        unsafe { std::slice::from_raw_parts(self.base.add(q * self.st.get()), self.st.get()) }
    }

    /// Column `q`, whole, mutable.
    ///
    /// # Safety
    /// `q` is a column of the block, not reached through another slice while this one lives.
    #[inline(always)]
    #[allow(clippy::mut_from_ref)] // the view stands for the block's `&mut` borrow
    pub(super) unsafe fn col_mut(&self, q: usize) -> &'a mut [f64] {
        // SAFETY: as in `col`.
        unsafe { std::slice::from_raw_parts_mut(self.base.add(q * self.st.get()), self.st.get()) }
    }

    /// The first `nc` chunks of column `q` from entry `off` (0 or 1).
    ///
    /// # Safety
    /// As [`ColumnsView::col`], and `nc * L + off` entries fit in the stride.
    #[inline(always)]
    pub(super) unsafe fn lanes<const L: usize>(
        &self,
        q: usize,
        off: usize,
        nc: usize,
    ) -> &'a [[f64; L]] {
        debug_assert!(nc * L + off <= self.st.get(), "chunks past the column");
        // SAFETY: the caller's bounds; `[f64; L]` has the layout of `L` consecutive f64.
        unsafe { std::slice::from_raw_parts(self.base.add(q * self.st.get() + off).cast(), nc) }
    }

    /// The same, mutable.
    ///
    /// # Safety
    /// As [`ColumnsView::col_mut`], and `nc * L + off` entries fit in the stride.
    #[inline(always)]
    #[allow(clippy::mut_from_ref)] // as `col_mut`
    pub(super) unsafe fn lanes_mut<const L: usize>(
        &self,
        q: usize,
        off: usize,
        nc: usize,
    ) -> &'a mut [[f64; L]] {
        debug_assert!(nc * L + off <= self.st.get(), "chunks past the column");
        // SAFETY: as in `lanes`.
        unsafe { std::slice::from_raw_parts_mut(self.base.add(q * self.st.get() + off).cast(), nc) }
    }
}

/// The columns of a chain's per-stage results in its [`Columns`] block: the padded
/// elements' unit tangents, tensions and forces (half drag plus half weight less
/// buoyancy), the nodes' extra forces (point drag, a point's water acceleration, mass
/// flow; zero but at the few nodes that have them), point masses and weights (less
/// what a point partly out of the water loses), and accelerations.
pub(super) mod col {
    pub(in super::super) const TX: usize = 0;
    pub(in super::super) const TEN: usize = 3;
    pub(in super::super) const FX: usize = 4;
    pub(in super::super) const XFX: usize = 7;
    pub(in super::super) const PM: usize = 10;
    pub(in super::super) const PWZ: usize = 11;
    pub(in super::super) const AX: usize = 12;
    /// How many.
    pub(in super::super) const COUNT: usize = 15;
}
