//! `src/cpu/chain/elements.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::cpu_chain_elements::overlapped_chunks;

/// The chunks of a network piece cover each of its elements, stay inside it, and
/// overlap only in the last one (pieces of 4 to 300 elements, 4 and 8 lanes).
#[test]
fn overlapped_chunks_cover_every_entry_once_or_twice_inside() {
    fn check<const L: usize>(ne: usize) {
        let mut seen = vec![0usize; ne];
        let starts: Vec<usize> = overlapped_chunks::<L>(ne).collect();
        for &o in &starts {
            assert!(o + L <= ne, "chunk at {o} past {ne} elements");
            for s in &mut seen[o..o + L] {
                *s += 1;
            }
        }
        assert!(seen.iter().all(|&k| k >= 1), "{ne} elements, {L} lanes");
        // Only the last chunk overlaps: twice at most, and only when L does not
        // divide the piece.
        let twice = seen.iter().filter(|&&k| k == 2).count();
        assert!(seen.iter().all(|&k| k <= 2));
        assert_eq!(twice, (L - ne % L) % L);
        assert_eq!(starts.len(), ne.div_ceil(L));
    }
    for ne in 4..300 {
        check::<4>(ne);
        if ne >= 8 {
            check::<8>(ne);
        }
    }
}
