//! The members of a study (sea state x seed), their wave seeds, and shards.
//!
//! Members are numbered condition by condition (the study's mooring conditions, the
//! intact one first), then sea state by sea state, seeds in the order given (a sea state
//! with its own `seeds` count runs the first ones); for a study of the intact mooring
//! alone, every sea state with every seed, `index = sea_state * seeds.len() + j`. A
//! damaged condition runs the sea states outside the fatigue scatter diagram only. That
//! number orders every table and every reduction, so results do not depend on which
//! thread or machine ran a member.
//!
//! A member's wave seed (the seed of its random phases) is the first 64-bit word of the
//! ChaCha20 stream whose 256-bit key is the study seed, the sea-state index and the seed
//! number (8 little-endian bytes each, then zeros), shifted right by one bit: a TOML
//! integer is signed, and a seed below 2^63 can be written as `environment.waves.seed`
//! of a scenario, which then runs the member alone. It is derived from what identifies the
//! member, never from time or thread order, so re-runs, thread counts and shards give the
//! same waves. Keying by the seed number rather than the flat index means that adding a
//! seed or a sea state at the end leaves the existing members' waves unchanged, and the
//! sea-state index in the key gives each sea state its own phases for the same seed number.
//! The condition is not in the key: a damaged condition meets the same seas as the
//! intact mooring.

use crate::error::Error;
use crate::scenario::err;
use rand::RngCore;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha20Rng;
use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::path::Path;

use super::definition::{Condition, StudyDef};

/// One member: a sea state run with one seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Member {
    /// Position in the study (module documentation).
    pub index: usize,
    /// Index of the mooring condition (0, the first, for a study without conditions).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub condition: usize,
    /// Index of the sea state in the study.
    pub sea_state: usize,
    /// The seed number (from the study's `seeds`).
    pub seed: u64,
    /// The seed of the member's random wave phases.
    pub wave_seed: u64,
}

/// The wave seed of the member with seed number `seed` in sea state `sea_state` of a
/// study with seed `study_seed` (module documentation).
pub fn wave_seed(study_seed: u64, sea_state: usize, seed: u64) -> u64 {
    let mut key = [0u8; 32];
    key[0..8].copy_from_slice(&study_seed.to_le_bytes());
    key[8..16].copy_from_slice(&(sea_state as u64).to_le_bytes());
    key[16..24].copy_from_slice(&seed.to_le_bytes());
    ChaCha20Rng::from_seed(key).next_u64() >> 1
}

fn is_zero(x: &usize) -> bool {
    *x == 0
}

/// Whether condition `c` runs sea state `s`: the intact mooring every sea state, a
/// damaged one those outside the fatigue scatter diagram.
pub fn runs(def: &StudyDef, c: &Condition, s: usize) -> bool {
    !c.is_damaged() || !def.sea_states[s].in_scatter()
}

/// Every member of a study with the mooring conditions `conditions`, in member order.
pub fn members(def: &StudyDef, conditions: &[Condition]) -> Vec<Member> {
    let mut out = Vec::new();
    for (c, cond) in conditions.iter().enumerate() {
        for s in 0..def.sea_states.len() {
            if !runs(def, cond, s) {
                continue;
            }
            for &seed in def.seeds_of(s) {
                out.push(Member {
                    index: out.len(),
                    condition: c,
                    sea_state: s,
                    seed,
                    wave_seed: wave_seed(def.seed, s, seed),
                });
            }
        }
    }
    out
}

/// A slice of a study's members, `K/N`: shard `K` (1 to `N`) of `N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardSpec {
    /// Which shard, from 1.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

impl ShardSpec {
    /// The whole study on one machine, `1/1`.
    pub const WHOLE: ShardSpec = ShardSpec { index: 1, count: 1 };

    /// Parses `K/N` (`1 <= K <= N`); `source` names where it came from in messages
    /// (`--shard`, or a shard file).
    pub fn parse(text: &str, source: &Path) -> Result<ShardSpec, Error> {
        let bad = |m: String| err(source, "shard", m);
        let (k, n) = text.split_once('/').ok_or_else(|| {
            bad(format!(
                "\"{text}\" is not K/N (shard K of N, e.g. 3/8, K from 1)"
            ))
        })?;
        let k: usize = k
            .trim()
            .parse()
            .map_err(|_| bad(format!("in \"{text}\", K is not a whole number")))?;
        let n: usize = n
            .trim()
            .parse()
            .map_err(|_| bad(format!("in \"{text}\", N is not a whole number")))?;
        if n == 0 {
            return Err(bad(format!("in \"{text}\", N must be at least 1")));
        }
        if k == 0 || k > n {
            return Err(bad(format!(
                "in \"{text}\", the shard index K is out of range: it runs from 1 to {n}"
            )));
        }
        Ok(ShardSpec { index: k, count: n })
    }

    /// Checks the shard against a study of `members` members: more shards than members
    /// would leave some empty, which is a mistake in the job array, not a plan.
    pub fn check(&self, members: usize, source: &Path) -> Result<(), Error> {
        if self.count > members {
            return Err(err(
                source,
                "shard",
                format!("{self}: the study has {members} members, so at most {members} shards"),
            ));
        }
        Ok(())
    }

    /// The members of this shard: a contiguous block of member indices; the `N` blocks
    /// cover `0..members` in order and differ in size by at most one.
    pub fn range(&self, members: usize) -> Range<usize> {
        let k = self.index - 1;
        (k * members / self.count)..((k + 1) * members / self.count)
    }
}

impl std::fmt::Display for ShardSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}
