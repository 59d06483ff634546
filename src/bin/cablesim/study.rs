//! `cablesim study run | merge | slurm`: Monte Carlo sea-state studies from the command
//! line (the study files are described in docs/src/studies.md).

use crate::RunOutcome;
use anyhow::{bail, Context, Result};
use cablesim::options::{Backend, Precision};
use cablesim::study::{
    merge, summarise, tables, MemberResult, MemberStatus, PackedRun, RunDir, RunState, RunStatus,
    ShardResult, ShardSpec, StudyFile, StudyRunner,
};
use clap::{Subcommand, ValueEnum};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

#[derive(Subcommand)]
pub enum StudyCmd {
    /// Run a study's members (all, or one shard): on the CPU across all threads
    /// (RAYON_NUM_THREADS sets how many), or packed into one run on the GPU.
    Run {
        /// Study file (a `[study]` table, inside a scenario or naming one).
        file: PathBuf,
        /// Run only shard K of N (`K/N`, K from 1): a deterministic slice of the members.
        #[arg(long, value_name = "K/N")]
        shard: Option<String>,
        /// Output directory (default: out/<study name>, or out/<study name>/shard-K-of-N).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Continue an interrupted run in the output directory: members already finished
        /// there are kept and not run again.
        #[arg(long)]
        resume: bool,
        /// Where the members run: cpu (each member its own run, members in parallel
        /// across the threads), gpu (members packed into one run on the GPU, all in
        /// one layout, in batches of --batch), or auto (packed, on the backend the
        /// packed model picks). The GPU adapter can be picked with WGPU_BACKEND and
        /// WGPU_ADAPTER_NAME.
        #[arg(long, value_enum, default_value = "cpu")]
        backend: Backend,
        /// GPU shader precision of packed runs (default: the scenario's, else f32;
        /// f64 needs an adapter with SHADER_F64).
        #[arg(long, value_enum)]
        precision: Option<Precision>,
        /// Members per packed run (gpu or auto; default: every member of the shard in
        /// one run). The results do not depend on it; a smaller batch needs less GPU
        /// memory.
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
        batch: Option<u64>,
    },
    /// Merge the shards of one study (their run directories or shard.json files) into
    /// study.csv, members.csv and study.json.
    Merge {
        /// Shard run directories (or their shard.json files), in any order.
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Where to write the tables (default: the folder holding the first shard's
        /// directory).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Write a Slurm submission script: a job array of N shard tasks, and a merge job
    /// that runs when every task has succeeded.
    Slurm {
        /// Study file.
        file: PathBuf,
        /// Number of shards (array tasks).
        #[arg(long)]
        shards: usize,
        /// Results folder: shard K runs in OUT/shard-K-of-N, the merged tables land in
        /// OUT (default: out/<study name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Script to write (default: OUT/submit.sh).
        #[arg(long)]
        script: Option<PathBuf>,
        /// The cablesim binary the jobs run (default: this one).
        #[arg(long)]
        cablesim: Option<PathBuf>,
        /// Where each task runs its members (as `study run --backend`; gpu needs a GPU
        /// on the nodes: ask for it in SBATCH_ARGS, e.g. --gres=gpu:1).
        #[arg(long, value_enum, default_value = "cpu")]
        backend: Backend,
        /// GPU shader precision of the tasks' packed runs (as `study run --precision`).
        #[arg(long, value_enum)]
        precision: Option<Precision>,
        /// Members per packed run in each task (as `study run --batch`).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
        batch: Option<u64>,
    },
}

/// Runs a study command; `study run` stopped by Ctrl-C or SIGTERM ends as
/// [`RunOutcome::Interrupted`] (exit status 130, as a single run).
/// `quiet` (the global `-q`): no progress bar, no estimate, no per-sea-state or closing
/// lines (a failed member and an interruption are still reported).
pub fn main(cmd: StudyCmd, quiet: bool) -> Result<RunOutcome> {
    match cmd {
        StudyCmd::Run {
            file,
            shard,
            out,
            resume,
            backend,
            precision,
            batch,
        } => {
            let how = (backend != Backend::Cpu).then_some(PackedRun {
                backend,
                precision,
                batch: batch.map(|b| b as usize),
            });
            run(&file, shard.as_deref(), out, resume, quiet, how)
        }
        StudyCmd::Merge { dirs, out } => merge_dirs(&dirs, out).map(|()| RunOutcome::Done),
        StudyCmd::Slurm {
            file,
            shards,
            out,
            script,
            cablesim,
            backend,
            precision,
            batch,
        } => {
            // The options each task's `study run` gets, as the command line spells them.
            fn name(v: impl ValueEnum) -> String {
                v.to_possible_value()
                    .map(|p| p.get_name().to_owned())
                    .unwrap_or_default()
            }
            let mut run_args = format!(" --backend {}", name(backend));
            if let Some(p) = precision {
                run_args += &format!(" --precision {}", name(p));
            }
            if let Some(b) = batch {
                run_args += &format!(" --batch {b}");
            }
            slurm(&file, shards, out, script, cablesim, &run_args).map(|()| RunOutcome::Done)
        }
    }
}

fn study_name(file: &Path) -> String {
    file.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "study".into())
}

fn shard_dir_name(s: ShardSpec) -> String {
    format!("shard-{}-of-{}", s.index, s.count)
}

fn run(
    file: &Path,
    shard: Option<&str>,
    out: Option<PathBuf>,
    resume: bool,
    quiet: bool,
    packed: Option<PackedRun>,
) -> Result<RunOutcome> {
    let shard = match shard {
        Some(s) => ShardSpec::parse(s, Path::new("--shard"))?,
        None => ShardSpec::WHOLE,
    };
    let study = StudyFile::load(file)?;
    let runner = StudyRunner::new(&study)?;
    let plan = runner.plan();
    let members = plan.shard_members(shard, Path::new("--shard"))?;
    let out = out.unwrap_or_else(|| {
        let base = PathBuf::from("out").join(study_name(file));
        if shard == ShardSpec::WHOLE {
            base
        } else {
            base.join(shard_dir_name(shard))
        }
    });
    let (dir, done) = RunDir::open(&out, plan, shard, resume)?;
    let remaining: Vec<_> = members
        .iter()
        .filter(|m| !done.iter().any(|d| d.member.index == m.index))
        .copied()
        .collect();
    let status = |state, finished: &[MemberResult]| RunStatus {
        state,
        study_hash: plan.hash.clone(),
        shard,
        members: members.len(),
        finished: finished.len(),
        failed: finished
            .iter()
            .filter(|m| m.status != MemberStatus::Completed)
            .count(),
    };
    dir.write_status(&status(RunState::Running, &done))?;

    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = stop.clone();
        // Ctrl-C and SIGTERM (Slurm's cancel and time limit) stop the run between output
        // times: finished members are already on disk, running ones are dropped.
        ctrlc::set_handler(move || stop.store(true, Ordering::SeqCst))
            .context("cannot install the Ctrl-C / SIGTERM handler")?;
    }

    let duration = plan.def.duration;
    // Position in member-milliseconds of simulated time.
    let ms = |s: f64| (s * 1e3).round() as u64;
    let bar = if !crate::show_progress(quiet) {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::new(ms(duration) * members.len() as u64)
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {percent}% {msg} (eta {eta})",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    bar.set_position(ms(duration) * done.len() as u64);
    let members_msg = |finished: usize| {
        format!(
            "{finished} of {} members ({} member-s each)",
            members.len(),
            duration
        )
    };
    bar.set_message(members_msg(done.len()));
    if !quiet {
        let how = match &packed {
            None => format!("{} threads", rayon::current_num_threads()),
            Some(p) => format!(
                "packed on backend {}, {} members per run",
                p.backend.name(),
                p.batch
                    .unwrap_or(remaining.len())
                    .min(remaining.len().max(1))
            ),
        };
        eprintln!(
            "study {}: {} members in shard {shard} ({} already done), {how}; output in {}",
            file.display(),
            members.len(),
            done.len(),
            out.display()
        );
        let est = runner.estimate(remaining.len())?;
        match &packed {
            None => eprintln!("work: {}", est.describe()),
            // Packed: one run of every member's nodes, on a backend chosen when it
            // starts; the GPU's figure is a predicted lower bound (sim::estimate).
            Some(p) => {
                use cablesim::sim::estimate::{duration_words, GPU_HARDWARE_RATE};
                let rate = GPU_HARDWARE_RATE[(p.precision == Some(Precision::F64)) as usize];
                eprintln!(
                    "work: {:.3e} node-steps; packed on a datacenter GPU at least {} (its predicted bandwidth limit, {rate:.1e} node-steps/s, not measured); {}",
                    est.node_steps,
                    duration_words(est.node_steps / rate),
                    est.how.replacen("on the CPU path", &format!("about {} on the CPU path", duration_words(est.seconds)), 1)
                )
            }
        }
    } else {
        // The budget is checked all the same (a member beyond it is refused here).
        runner.estimate(remaining.len())?;
    }

    // Per sea state of this shard: members in it, and members finished and failed.
    let n_states = plan.def.sea_states.len();
    let mut in_shard = vec![0usize; n_states];
    for m in members {
        in_shard[m.sea_state] += 1;
    }
    let tally = Mutex::new((vec![0usize; n_states], vec![0usize; n_states], done.len()));
    {
        let mut t = tally.lock().unwrap();
        for d in &done {
            t.0[d.member.sea_state] += 1;
            if d.status != MemberStatus::Completed {
                t.1[d.member.sea_state] += 1;
            }
        }
    }
    let progress = |dt: f64| bar.inc(ms(dt));
    // A line above the bar. `ProgressBar::println` prints nothing when the bar is hidden
    // (--quiet, or stderr not a terminal: a Slurm log, a pipe), and a failed member must
    // be reported there too; `suspend` clears the bar, if drawn, around the line.
    let say = |line: String| bar.suspend(|| eprintln!("{line}"));
    let on_done = |r: &MemberResult| -> Result<(), cablesim::Error> {
        dir.write_member(&plan.hash, r)?;
        let mut t = tally.lock().unwrap();
        let s = r.member.sea_state;
        t.0[s] += 1;
        t.2 += 1;
        if let MemberStatus::Failed { message } = &r.status {
            t.1[s] += 1;
            say(format!("failed: {message}"));
        }
        bar.set_message(members_msg(t.2));
        if t.0[s] == in_shard[s] && !quiet {
            let ss = &plan.def.sea_states[s];
            say(format!(
                "sea state {s}{}: Hs {} m, Tp {} s: {} members done, {} failed",
                ss.name
                    .as_deref()
                    .map(|n| format!(" ({n})"))
                    .unwrap_or_default(),
                ss.hs,
                ss.tp,
                t.0[s],
                t.1[s]
            ));
        }
        Ok(())
    };
    let result = match &packed {
        None => runner.run(&remaining, &stop, &progress, &on_done),
        Some(how) => runner.run_packed(&remaining, how, &stop, &progress, &on_done),
    };
    bar.finish_and_clear();
    let new = result.with_context(|| format!("study {}", file.display()))?;
    let mut all = done;
    all.extend(new);
    all.sort_by_key(|m| m.member.index);
    if all.len() < members.len() {
        dir.write_status(&status(RunState::Interrupted, &all))?;
        // Printed even with --quiet: the exit status alone does not say how to go on.
        eprintln!(
            "study interrupted: {} of {} members of shard {shard} finished and kept in {}; \
             continue with `cablesim study run {} {}--out {} --resume`",
            all.len(),
            members.len(),
            out.display(),
            file.display(),
            if shard == ShardSpec::WHOLE {
                String::new()
            } else {
                format!("--shard {shard} ")
            },
            out.display()
        );
        return Ok(RunOutcome::Interrupted);
    }
    let st = status(RunState::Complete, &all);
    let shard_result = plan.shard_result(shard, all);
    shard_result.write(&dir.shard_file())?;
    dir.write_status(&st)?;
    if quiet {
        if shard == ShardSpec::WHOLE {
            write_tables(&out, vec![(dir.shard_file(), shard_result)])?;
        }
        return Ok(RunOutcome::Done);
    }
    if shard == ShardSpec::WHOLE {
        let files = write_tables(&out, vec![(dir.shard_file(), shard_result)])?;
        eprintln!(
            "done: {} members ({} failed); {} in {}",
            st.members,
            st.failed,
            files.join(", "),
            out.display()
        );
    } else {
        eprintln!(
            "done: shard {shard}, {} members ({} failed) in {}; merge the shards with \
             `cablesim study merge`",
            st.members,
            st.failed,
            dir.shard_file().display()
        );
    }
    Ok(RunOutcome::Done)
}

/// Merges `shards` and writes the study's tables into `out`; returns the files written.
fn write_tables(out: &Path, shards: Vec<(PathBuf, ShardResult)>) -> Result<Vec<&'static str>> {
    let results = merge(shards)?;
    let summary = summarise(&results);
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    Ok(tables::write_all(out, &results, &summary)?)
}

fn merge_dirs(dirs: &[PathBuf], out: Option<PathBuf>) -> Result<()> {
    let mut shards = Vec::new();
    for d in dirs {
        let path = if d.is_dir() {
            d.join("shard.json")
        } else {
            d.clone()
        };
        if !path.exists() && d.join("status.json").exists() {
            bail!(
                "{}: the shard's run has not completed (see its status.json): resume it \
                 (`cablesim study run ... --shard K/N --out {} --resume`) before merging",
                d.display(),
                d.display()
            );
        }
        let s = ShardResult::read(&path)?;
        shards.push((path, s));
    }
    let out = out.unwrap_or_else(|| {
        let first = if dirs[0].is_dir() {
            dirs[0].clone()
        } else {
            dirs[0].parent().map(Path::to_path_buf).unwrap_or_default()
        };
        first
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."))
    });
    let n = shards.len();
    let files = write_tables(&out, shards)?;
    eprintln!(
        "merged {n} shards: {} in {}",
        files.join(", "),
        out.display()
    );
    Ok(())
}

/// Quotes a string for a POSIX shell: single quotes, in which nothing is special, and
/// each `'` as `'\''`. The result is one word whatever the string holds (spaces, `$`,
/// backticks, backslashes, double quotes, newlines).
fn sh(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

/// A path as UTF-8 for the script, or an error naming the flag: a path that is not
/// UTF-8 would reach the jobs changed (`to_string_lossy`).
fn utf8<'a>(p: &'a Path, what: &str) -> Result<&'a str> {
    p.to_str().with_context(|| {
        format!(
            "{what} {}: not UTF-8, which the script cannot hold",
            p.display()
        )
    })
}

/// A path for a `#` comment of the script: on one line whatever it holds (a newline in
/// it would end the comment and make the rest a command).
fn comment(s: &str) -> String {
    s.escape_debug().to_string()
}

/// A here-document of `body`, read as is (`<<'DELIM'`: no expansion, no command
/// substitution), ended by a delimiter that is no line of the body.
fn here_doc(body: &str) -> (String, String) {
    let mut delim = String::from("CABLESIM_JOB");
    while body.lines().any(|l| l == delim) {
        delim.push('_');
    }
    (format!("<<'{delim}'"), format!("{body}{delim}"))
}

/// Writes the Slurm submission script. Every path is embedded as a single-quoted word,
/// both in the script and in the job scripts it submits (quoted here-documents, which
/// the shell copies without expanding anything), so a path reaches `cablesim` as given
/// and runs nothing, whatever characters it holds. The jobs run in OUT (`--chdir`). Their
/// logs are sbatch's `--output` pattern, but sbatch reads `%` in the whole path as a
/// pattern (the working directory included) and a `\` as "no pattern at all": with
/// either in OUT, sbatch gets `--output=/dev/null` and each job sends its own output to
/// its log, by a redirection with the path single-quoted (Slurm's own messages about a
/// job, such as a time limit, are then lost).
fn slurm(
    file: &Path,
    shards: usize,
    out: Option<PathBuf>,
    script: Option<PathBuf>,
    cablesim: Option<PathBuf>,
    run_args: &str,
) -> Result<()> {
    let study = StudyFile::load(file)?;
    let runner = StudyRunner::new(&study)?;
    let plan = runner.plan();
    if shards == 0 {
        bail!("--shards: must be at least 1");
    }
    ShardSpec {
        index: 1,
        count: shards,
    }
    .check(plan.members.len(), Path::new("--shards"))?;
    let abs = |p: &Path| std::path::absolute(p).with_context(|| format!("{}", p.display()));
    let out = abs(&out.unwrap_or_else(|| PathBuf::from("out").join(study_name(file))))?;
    let file = abs(file)?;
    let exe = match cablesim {
        Some(c) => abs(&c)?,
        None => std::env::current_exe().context("cannot tell where this cablesim is")?,
    };
    let script = script.unwrap_or_else(|| out.join("submit.sh"));
    let (exe_s, file_s, out_s) = (
        utf8(&exe, "--cablesim")?,
        utf8(&file, "the study file")?,
        utf8(&out, "--out")?,
    );
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let (exe_q, file_q, out_q) = (sh(exe_s), sh(file_s), sh(out_s));
    let shard_dirs: Vec<String> = (1..=shards)
        .map(|k| {
            sh(&format!(
                "{out_s}/{}",
                shard_dir_name(ShardSpec {
                    index: k,
                    count: shards
                })
            ))
        })
        .collect();
    // The job scripts, with the paths as single-quoted words; `$SLURM_ARRAY_TASK_ID` is
    // expanded on the compute node, where it is a number.
    // Logs: sbatch's pattern, or (a `%` or `\` in OUT) the job's own redirection.
    let plain = !out_s.contains(['%', '\\']);
    let (shard_log, merge_log, shard_redirect, merge_redirect) = if plain {
        (
            "slurm-%A_%a.out",
            "slurm-merge-%j.out",
            String::new(),
            String::new(),
        )
    } else {
        (
            "/dev/null",
            "/dev/null",
            format!(
                "exec >{out_q}/\"slurm-${{SLURM_ARRAY_JOB_ID}}_${{SLURM_ARRAY_TASK_ID}}.out\" 2>&1\n"
            ),
            format!("exec >{out_q}/\"slurm-merge-${{SLURM_JOB_ID}}.out\" 2>&1\n"),
        )
    };
    let (shard_open, shard_body) = here_doc(&format!(
        "#!/bin/bash\n{shard_redirect}exec {exe_q} study run {file_q} --resume{run_args} \\\n  \
         --shard \"$SLURM_ARRAY_TASK_ID/{shards}\" \\\n  \
         --out {out_q}/\"shard-$SLURM_ARRAY_TASK_ID-of-{shards}\"\n"
    ));
    let (merge_open, merge_body) = here_doc(&format!(
        "#!/bin/bash\n{merge_redirect}exec {exe_q} study merge {} --out {out_q}\n",
        shard_dirs.join(" ")
    ));
    let text = format!(
        r#"#!/bin/bash
# Written by `cablesim study slurm`: study {file_c}, {members} members in {shards} shards.
# Submit it with `bash submit.sh` (extra arguments go to the merge job's sbatch, e.g.
# --wait to return when the study is merged, with exit status 1 if it was not: the
# cluster should then cancel a merge job whose shards failed, kill_invalid_depend in
# DependencyParameters, or the wait never ends). Shard K runs in $OUT/shard-K-of-{shards};
# a task that is cancelled or hits its time limit keeps its finished members, and
# resubmitting resumes it. The merged study.csv, members.csv and study.json (and
# fatigue.csv for a study with fatigue) land in $OUT.
# Add sbatch options (partition, time limit, CPUs per task) in SBATCH_ARGS.
# The paths are single-quoted words, in the job scripts too (here-documents that are
# not expanded): they reach cablesim as written.
set -euo pipefail
CABLESIM={exe_q}
STUDY={file_q}
OUT={out_q}
mkdir -p "$OUT"
# sbatch's answer goes through a file: a here-document inside $(...) is parsed
# differently by older shells.
ids="$OUT/.sbatch-$$"
sbatch --parsable ${{SBATCH_ARGS:-}} --job-name=cablesim-study \
  --array=1-{shards} --chdir="$OUT" --output={shard_log} >"$ids" {shard_open}
{shard_body}
array_job=$(cat "$ids")
array_job=${{array_job%%;*}}
echo "shards: job array $array_job"
# With --wait, sbatch returns 0 also when the merge job never ran (cancelled because a
# shard failed): the merged study.json, newer than this submission, says it did.
stamp="$OUT/.submitted-$array_job"
touch "$stamp"
sbatch --parsable ${{SBATCH_ARGS:-}} --job-name=cablesim-merge \
  --dependency=afterok:"$array_job" --chdir="$OUT" --output={merge_log} "$@" \
  >"$ids" {merge_open}
{merge_body}
merge_job=$(cat "$ids")
rm -f "$ids"
echo "merge: job ${{merge_job%%;*}}"
for a in "$@"; do
  if [ "$a" = --wait ] || [ "$a" = -W ]; then
    if [ ! "$OUT/study.json" -nt "$stamp" ]; then
      echo "the study was not merged: a shard failed or was cancelled (see" \
        "$OUT/slurm-${{array_job}}_K.out); submit again to resume it" >&2
      rm -f "$stamp"
      exit 1
    fi
    files="study.csv, members.csv, study.json"
    if [ -f "$OUT/fatigue.csv" ]; then files="$files, fatigue.csv"; fi
    echo "merged: $files in $OUT"
  fi
done
rm -f "$stamp"
"#,
        file_c = comment(file_s),
        members = plan.members.len(),
    );
    std::fs::write(&script, text).with_context(|| format!("cannot write {}", script.display()))?;
    eprintln!(
        "wrote {}: submit it with `bash {}`",
        script.display(),
        sh(&script.to_string_lossy())
    );
    Ok(())
}
