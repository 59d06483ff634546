//! The study hash: which study a shard's results belong to.
//!
//! SHA-256 (a stable, specified hash: the same on every machine and compiler, unlike
//! std's `DefaultHasher`) of a version tag, the canonical JSON of the validated
//! definition and the base scenario's text. The canonical JSON is the definition after
//! validation (defaults filled in, sea states read from their CSV), so two files that
//! differ only in layout, comments, key order or defaults written out hash the same, and a changed sea
//! state, seed, channel or factor changes the hash. The base scenario is hashed as
//! text: any change to the model makes a different study. Files the scenario reads in
//! turn (route or motion tables) are not hashed here; a runner that wants them covered
//! appends their text to `scenario_text`.

use super::definition::StudyDef;
use sha2::{Digest, Sha256};

/// Bumped when the meaning of a study's results changes, so old shards are refused.
const TAG: &[u8] = b"cablesim study 1\n";

/// The hex SHA-256 study hash (module documentation).
pub fn study_hash(def: &StudyDef, scenario_text: &str) -> String {
    let mut h = Sha256::new();
    h.update(TAG);
    h.update(serde_json::to_vec(def).expect("a study definition serialises"));
    h.update(b"\n");
    h.update(scenario_text.as_bytes());
    format!("{:x}", h.finalize())
}
