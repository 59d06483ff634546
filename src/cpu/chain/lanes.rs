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
pub(super) const MAX_LANES: usize = 8;

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
