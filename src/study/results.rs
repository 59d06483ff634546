//! What a shard hands over (`shard.json`), and the merge of shards into one study.
//!
//! A shard file holds everything the merge and the summary need: the study hash, the
//! validated definition, the resolved channels, and each member's full streaming state
//! (Welford's mean and `M2`, not only the rounded standard deviation), so the merge reads
//! no other file. JSON numbers are written in the shortest form that reads back to the
//! same `f64` bits, so a file round trip changes nothing.

use super::channel_stats::ChannelStats;
use super::channels::Channel;
use super::definition::{Condition, StudyDef};
use super::members::{self, Member, ShardSpec};
use crate::error::Error;
use crate::fatigue::{FatigueLocation, FatigueRecord};
use crate::scenario::err;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};

/// The version of the shard file layout.
pub const SHARD_FORMAT: u32 = 1;

/// How a member ended.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum MemberStatus {
    /// Ran to its duration.
    Completed,
    /// Stopped early (blew up): the statistics hold what it reached, and the extremes
    /// leave it out.
    Failed {
        /// What happened, with the cable, node and time.
        message: String,
    },
}

impl MemberStatus {
    /// `completed` or `failed`.
    pub fn name(&self) -> &'static str {
        match self {
            MemberStatus::Completed => "completed",
            MemberStatus::Failed { .. } => "failed",
        }
    }
}

/// One finished member.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MemberResult {
    /// Which member.
    pub member: Member,
    /// How it ended.
    pub status: MemberStatus,
    /// One per channel, in the study's channel order.
    pub stats: Vec<ChannelStats>,
    /// One per fatigue location, in the study's order (empty without fatigue).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fatigue: Vec<FatigueRecord>,
}

/// A shard's results, as written to `shard.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShardResult {
    /// Layout version ([`SHARD_FORMAT`]).
    pub format: u32,
    /// The study hash.
    pub study_hash: String,
    /// Which shard.
    pub shard: ShardSpec,
    /// The study definition.
    pub study: StudyDef,
    /// The channels.
    pub channels: Vec<Channel>,
    /// The fatigue locations (empty without fatigue).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fatigue: Vec<FatigueLocation>,
    /// The mooring conditions (empty: the intact mooring alone).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub conditions: Vec<Condition>,
    /// Its members, in member order.
    pub members: Vec<MemberResult>,
}

impl ShardResult {
    /// Writes the shard file.
    pub fn write(&self, path: &Path) -> Result<(), Error> {
        let io = |source| Error::Output {
            path: path.to_path_buf(),
            source,
        };
        let mut w = BufWriter::new(File::create(path).map_err(io)?);
        serde_json::to_writer(&mut w, self).map_err(|e| io(e.into()))?;
        w.write_all(b"\n").map_err(io)?;
        w.flush().map_err(io)
    }

    /// Reads a shard file.
    pub fn read(path: &Path) -> Result<ShardResult, Error> {
        let f = File::open(path).map_err(|e| err(path, "(file)", format!("cannot read: {e}")))?;
        let mut de = serde_json::Deserializer::from_reader(BufReader::new(f));
        let r: ShardResult = serde_path_to_error::deserialize(&mut de).map_err(|e| {
            err(
                path,
                e.path().to_string(),
                format!("not a cablesim shard file: {}", e.into_inner()),
            )
        })?;
        if r.format != SHARD_FORMAT {
            return Err(err(
                path,
                "format",
                format!(
                    "shard file layout {} where this cablesim reads {SHARD_FORMAT}: \
                     run the shard again with this version",
                    r.format
                ),
            ));
        }
        Ok(r)
    }
}

/// The members of a whole study, in member order, with what the summary needs.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyResults {
    /// The study hash.
    pub study_hash: String,
    /// The study definition.
    pub study: StudyDef,
    /// The channels.
    pub channels: Vec<Channel>,
    /// The fatigue locations (empty without fatigue).
    pub fatigue: Vec<FatigueLocation>,
    /// The mooring conditions, in condition order (at least the one, intact or not).
    pub conditions: Vec<Condition>,
    /// Every member, in member order.
    pub members: Vec<MemberResult>,
}

/// Merges the shard files of one study (given in any order) into the whole study.
/// Refuses shards of another study (a different hash), a missing or repeated shard,
/// and a shard that lacks some of its members (an interrupted run).
pub fn merge(shards: Vec<(PathBuf, ShardResult)>) -> Result<StudyResults, Error> {
    let Some((first_path, first)) = shards.first() else {
        return Err(err(Path::new("(merge)"), "shards", "no shard file given"));
    };
    let first_path = first_path.clone();
    let (hash, count) = (first.study_hash.clone(), first.shard.count);
    let mut by_index: BTreeMap<usize, (PathBuf, ShardResult)> = BTreeMap::new();
    for (path, s) in shards {
        if s.study_hash != hash {
            return Err(err(
                &path,
                "study_hash",
                format!(
                    "belongs to another study (hash {}) than {} (hash {hash}): \
                     merge only the shards of one study",
                    s.study_hash,
                    first_path.display()
                ),
            ));
        }
        if s.shard.count != count {
            return Err(err(
                &path,
                "shard",
                format!(
                    "is shard {} of a {}-shard run, while {} is of a {count}-shard run",
                    s.shard,
                    s.shard.count,
                    first_path.display()
                ),
            ));
        }
        if let Some((other, _)) = by_index.get(&s.shard.index) {
            return Err(err(
                &path,
                "shard",
                format!("shard {} is also given by {}", s.shard, other.display()),
            ));
        }
        by_index.insert(s.shard.index, (path, s));
    }
    let missing: Vec<String> = (1..=count)
        .filter(|k| !by_index.contains_key(k))
        .map(|k| format!("{k}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(err(
            &first_path,
            "shard",
            format!(
                "the merge needs all {count} shards of the study; missing: {}",
                missing.join(", ")
            ),
        ));
    }
    let (_, first) = &by_index[&1];
    let conditions = if first.conditions.is_empty() {
        vec![Condition::intact()]
    } else {
        first.conditions.clone()
    };
    let all = members::members(&first.study, &conditions);
    let (study, channels) = (first.study.clone(), first.channels.clone());
    let fatigue = first.fatigue.clone();
    let mut members = Vec::with_capacity(all.len());
    for (path, s) in by_index.into_values() {
        let expect = &all[s.shard.range(all.len())];
        let got: Vec<usize> = s.members.iter().map(|m| m.member.index).collect();
        let lacking: Vec<String> = expect
            .iter()
            .filter(|m| !got.contains(&m.index))
            .map(|m| m.index.to_string())
            .collect();
        if !lacking.is_empty() {
            return Err(err(
                &path,
                "members",
                format!(
                    "shard {} is incomplete: members {} are missing (an interrupted run: \
                     resume it before merging)",
                    s.shard,
                    lacking.join(", ")
                ),
            ));
        }
        for (i, m) in s.members.into_iter().enumerate() {
            let field = format!("members[{i}]");
            if !expect.contains(&m.member) {
                return Err(err(
                    &path,
                    field,
                    format!(
                        "member {:?} is not one of shard {}'s members",
                        m.member, s.shard
                    ),
                ));
            }
            if m.stats.len() != channels.len() {
                return Err(err(
                    &path,
                    format!("{field}.stats"),
                    format!(
                        "{} channels where the study has {}",
                        m.stats.len(),
                        channels.len()
                    ),
                ));
            }
            if m.fatigue.len() != fatigue.len() {
                return Err(err(
                    &path,
                    format!("{field}.fatigue"),
                    format!(
                        "{} fatigue records where the study has {} fatigue locations",
                        m.fatigue.len(),
                        fatigue.len()
                    ),
                ));
            }
            members.push(m);
        }
    }
    // Shards were taken in shard order, each in member order; a shard file written by
    // hand in another order is put right here.
    members.sort_by_key(|m| m.member.index);
    if let Some(w) = members
        .windows(2)
        .find(|w| w[0].member.index == w[1].member.index)
    {
        return Err(err(
            &first_path,
            "members",
            format!("member {} appears twice", w[0].member.index),
        ));
    }
    Ok(StudyResults {
        study_hash: hash,
        study,
        channels,
        fatigue,
        conditions,
        members,
    })
}
