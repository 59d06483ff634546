//! `src/cpu/chain/lanes.rs`: the lane masks that zero the padding nodes of a chain's last chunk.

use cablesim::testing::cpu_chain_lanes::{KEEP, MAX_LANES};

/// Row `k` of `KEEP` keeps the first `k` lanes bit for bit (NaN, infinities, `-0.0`
/// and subnormals included) and turns every other lane into `+0.0`, whatever it held.
#[test]
fn keep_rows_keep_the_first_lanes_and_zero_the_rest() {
    let odd = [
        f64::NAN,
        f64::INFINITY,
        -0.0,
        f64::MIN_POSITIVE / 4.0,
        -1.5e300,
        f64::NEG_INFINITY,
        3.25,
        -f64::NAN,
    ];
    assert_eq!(KEEP.len(), MAX_LANES + 1);
    for (k, row) in KEEP.iter().enumerate() {
        for l in 0..MAX_LANES {
            let kept = f64::from_bits(odd[l].to_bits() & row[l]);
            if l < k {
                assert_eq!(kept.to_bits(), odd[l].to_bits(), "row {k}, lane {l}");
            } else {
                assert_eq!(kept.to_bits(), 0.0f64.to_bits(), "row {k}, lane {l}");
            }
        }
    }
}
