//! The vector width the CPU path's vectorised loops run at: 8 f64 lanes (AVX-512)
//! where the CPU has AVX-512 F, DQ and VL, else 4 (AVX2), unless the environment
//! variable `CABLESIM_CHAIN_LANES` is `4` (to compare the two widths on one machine).
//!
//! The network path has a switch of its own ([`net_avx512_wanted`]), 4 lanes unless
//! asked for 8.
//!
//! Who reads it: the chain fast path (`cpu::chain`, whose loops run over whole chunks
//! of 4 or 8 lanes) and the waves' component sums (`sea::columns`, the kinematics
//! cache's refresh). Both give the same bits at either width: each lane does a scalar
//! loop's arithmetic, and the waves' sums keep four partial sums at both widths.

/// Whether the CPU path should run its loops at 8 lanes: the CPU has AVX-512 (F, DQ,
/// VL) and `CABLESIM_CHAIN_LANES` is not `4`. Read once per process.
pub fn avx512_wanted() -> bool {
    static WANTED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *WANTED.get_or_init(|| lanes_wanted() == 8 && avx512_present())
}

/// Whether the network loops (`cpu::chain::net`) take 8 lanes: where the CPU has
/// AVX-512 (F, DQ, VL) and the environment variable `CABLESIM_NET_LANES` is `8`. By
/// default they take 4 (AVX2): on the development machine 8 lanes were not faster
/// (benchmarks/history/BENCHMARKS-2026-12.md, "Networks: whole chunks of lanes"). Every loop's lanes are
/// independent (no sum across elements or nodes), so the results are the same bits
/// with 8 lanes or 4. Read once per process.
pub fn net_avx512_wanted() -> bool {
    static WANTED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *WANTED.get_or_init(|| {
        let wanted = match std::env::var("CABLESIM_NET_LANES").as_deref() {
            Ok("8") => true,
            Ok("4") | Err(_) => false,
            Ok(other) => {
                log::warn!(
                    "CABLESIM_NET_LANES = {other:?} is neither 4 nor 8: the network path \
                     uses 4 lanes"
                );
                false
            }
        };
        wanted && avx512_present()
    })
}

/// Whether this CPU has AVX-512 F, DQ and VL (whatever `CABLESIM_CHAIN_LANES` says).
pub fn avx512_present() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512dq")
            && std::arch::is_x86_feature_detected!("avx512vl")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The lanes asked for: 8 unless `CABLESIM_CHAIN_LANES` is `4`; any other value is
/// warned of and taken as 8.
fn lanes_wanted() -> usize {
    match std::env::var("CABLESIM_CHAIN_LANES").as_deref() {
        Ok("4") => 4,
        Ok("8") | Err(_) => 8,
        Ok(other) => {
            log::warn!(
                "CABLESIM_CHAIN_LANES = {other:?} is neither 4 nor 8: the CPU path uses 8 \
                 lanes where the CPU has AVX-512, else 4"
            );
            8
        }
    }
}
