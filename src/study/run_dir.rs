//! A study run's output directory: what survives an interruption, and what `--resume`
//! reads back.
//!
//! ```text
//! DIR/status.json          the run's state: running, interrupted or complete
//! DIR/members/NNNNNN.json  one finished member each, written as it finishes
//! DIR/shard.json           the shard's result, once every member of it is done
//! ```
//!
//! A member file is written to a temporary name and renamed, so a run killed while
//! writing leaves either the whole file or none. Each file carries the study hash:
//! resuming with a changed study file, or into a directory of another study or
//! shard, is refused instead of mixing results.

use super::members::ShardSpec;
use super::results::MemberResult;
use super::StudyPlan;
use crate::error::Error;
use crate::scenario::err;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Where a run stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunState {
    /// Started and not ended (or killed without a chance to say so).
    Running,
    /// Stopped by Ctrl-C or SIGTERM: the finished members are kept, `--resume`
    /// continues.
    Interrupted,
    /// Every member of the shard finished (completed or failed).
    Complete,
}

/// `status.json`: the summary of a run for people and for `--resume`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunStatus {
    /// Where the run stands.
    pub state: RunState,
    /// The study hash.
    pub study_hash: String,
    /// The shard this directory holds.
    pub shard: ShardSpec,
    /// Members of the shard.
    pub members: usize,
    /// Members finished so far (completed or failed).
    pub finished: usize,
    /// Of those, members that failed (blew up).
    pub failed: usize,
}

#[derive(Serialize, Deserialize)]
struct MemberFile {
    study_hash: String,
    result: MemberResult,
}

/// A run directory (module documentation).
#[derive(Clone, Debug)]
pub struct RunDir {
    /// The directory.
    pub path: PathBuf,
}

fn io(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |source| Error::Output {
        path: path.to_path_buf(),
        source,
    }
}

fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let tmp = path.with_extension("json.part");
    std::fs::write(&tmp, bytes).map_err(io(&tmp))?;
    std::fs::rename(&tmp, path).map_err(io(path))
}

impl RunDir {
    /// Opens `path` for shard `shard` of `plan`. A fresh run needs a directory without
    /// results; `resume` reads the members already finished there (those of this study
    /// and shard) and returns them in member order.
    pub fn open(
        path: &Path,
        plan: &StudyPlan,
        shard: ShardSpec,
        resume: bool,
    ) -> Result<(RunDir, Vec<MemberResult>), Error> {
        let dir = RunDir {
            path: path.to_path_buf(),
        };
        let members_dir = dir.members_dir();
        std::fs::create_dir_all(&members_dir).map_err(io(&members_dir))?;
        let status_path = path.join("status.json");
        let has_results = status_path.exists()
            || std::fs::read_dir(&members_dir)
                .map_err(io(&members_dir))?
                .next()
                .is_some();
        if !resume {
            if has_results {
                return Err(err(
                    path,
                    "(directory)",
                    "holds a study run already: continue it with --resume, or choose \
                     another --out",
                ));
            }
            return Ok((dir, Vec::new()));
        }
        if status_path.exists() {
            let text = std::fs::read_to_string(&status_path).map_err(io(&status_path))?;
            let st: RunStatus = serde_json::from_str(&text).map_err(|e| {
                err(
                    &status_path,
                    "(file)",
                    format!("not a study status file: {e}"),
                )
            })?;
            if st.study_hash != plan.hash {
                return Err(err(
                    &status_path,
                    "study_hash",
                    "the run in this directory is of another study (or the study or its \
                     base scenario changed since): --resume only continues the same study",
                ));
            }
            if st.shard != shard {
                return Err(err(
                    &status_path,
                    "shard",
                    format!(
                        "the run in this directory is shard {}, not {shard}",
                        st.shard
                    ),
                ));
            }
        }
        let range = shard.range(plan.members.len());
        let mut found = Vec::new();
        let mut entries: Vec<PathBuf> = std::fs::read_dir(&members_dir)
            .map_err(io(&members_dir))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .collect();
        entries.sort();
        for p in entries {
            let text = std::fs::read_to_string(&p).map_err(io(&p))?;
            let f: MemberFile = serde_json::from_str(&text)
                .map_err(|e| err(&p, "(file)", format!("not a study member file: {e}")))?;
            if f.study_hash != plan.hash {
                return Err(err(
                    &p,
                    "study_hash",
                    "belongs to another study (or the study or its base scenario changed \
                     since): --resume only continues the same study",
                ));
            }
            let i = f.result.member.index;
            if !range.contains(&i) || plan.members[i] != f.result.member {
                return Err(err(
                    &p,
                    "result.member",
                    format!("member {i} is not one of shard {shard}'s members"),
                ));
            }
            found.push(f.result);
        }
        found.sort_by_key(|m| m.member.index);
        Ok((dir, found))
    }

    fn members_dir(&self) -> PathBuf {
        self.path.join("members")
    }

    /// Writes one finished member.
    pub fn write_member(&self, study_hash: &str, r: &MemberResult) -> Result<(), Error> {
        let path = self
            .members_dir()
            .join(format!("{:06}.json", r.member.index));
        let f = MemberFile {
            study_hash: study_hash.to_string(),
            result: r.clone(),
        };
        let mut bytes = serde_json::to_vec(&f).map_err(|e| io(&path)(e.into()))?;
        bytes.push(b'\n');
        write_atomic(&path, &bytes)
    }

    /// Writes `status.json`.
    pub fn write_status(&self, st: &RunStatus) -> Result<(), Error> {
        let path = self.path.join("status.json");
        let mut bytes = serde_json::to_vec_pretty(st).map_err(|e| io(&path)(e.into()))?;
        bytes.push(b'\n');
        write_atomic(&path, &bytes)
    }

    /// The shard file's path.
    pub fn shard_file(&self) -> PathBuf {
        self.path.join("shard.json")
    }
}
