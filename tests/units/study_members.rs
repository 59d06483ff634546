//! `src/study/members.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::study::members::*;
use std::path::Path;

#[test]
fn shards_partition_the_members_in_order() {
    for members in [1usize, 7, 30, 31] {
        for count in 1..=members.min(9) {
            let mut next = 0;
            for index in 1..=count {
                let r = ShardSpec { index, count }.range(members);
                assert_eq!(r.start, next);
                assert!(r.len() == members / count || r.len() == members / count + 1);
                next = r.end;
            }
            assert_eq!(next, members);
        }
    }
}

#[test]
fn shard_specs_parse_and_bad_ones_are_named() {
    let p = Path::new("--shard");
    assert_eq!(
        ShardSpec::parse("3/8", p).unwrap(),
        ShardSpec { index: 3, count: 8 }
    );
    for (bad, says) in [
        ("0/4", "out of range"),
        ("5/4", "out of range"),
        ("1/0", "at least 1"),
        ("x/4", "K is not"),
        ("2", "is not K/N"),
    ] {
        let m = ShardSpec::parse(bad, p).unwrap_err().to_string();
        assert!(m.starts_with("--shard: shard: "), "{m}");
        assert!(m.contains(says), "{bad}: {m}");
    }
    let m = ShardSpec { index: 1, count: 5 }
        .check(4, p)
        .unwrap_err()
        .to_string();
    assert!(m.contains("at most 4 shards"), "{m}");
}

#[test]
fn wave_seeds_depend_on_every_part_of_the_key_and_on_nothing_else() {
    let a = wave_seed(7, 2, 11);
    assert_eq!(a, wave_seed(7, 2, 11));
    assert_ne!(a, wave_seed(8, 2, 11));
    assert_ne!(a, wave_seed(7, 3, 11));
    assert_ne!(a, wave_seed(7, 2, 12));
    // Swapping the parts of the key changes the seed: each has its own place.
    assert_ne!(wave_seed(1, 2, 3), wave_seed(3, 2, 1));
    // The derivation is the standard ChaCha20 key stream (RFC 8439 block function,
    // nonce and counter 0): this value came from an independent implementation
    // (Python's `cryptography`, the first 8 bytes of the key stream for the key
    // 7, 2, 11, 12_421_236_344_289_732_729, halved as the module doc says), so a
    // change of the derivation or of the generator crate's output, which would change
    // every study's waves, cannot pass unseen.
    assert_eq!(a, 12_421_236_344_289_732_729 >> 1);
}
