//! The script of `cablesim study slurm` run through a stand-in `sbatch` (a shell script
//! on PATH that runs each job script with bash at once), with paths that hold spaces,
//! quotes, `$`, backticks, backslashes, `%`, a newline and a line that could end a
//! here-document: each must reach cablesim as given and run nothing.

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");
const STUDY: &str = "examples/study_spread_mooring.toml";

/// A stand-in for sbatch: takes the options the script passes (`--array=1-N`,
/// `--chdir=`, `--output=`, `--dependency=afterok:ID`, `--parsable`), reads the job
/// script from standard input, runs it with bash in the `--chdir` folder (each array
/// task with its SLURM_ARRAY_TASK_ID and SLURM_ARRAY_JOB_ID), its output in the
/// `--output` file (`%A`, `%a`, `%j` replaced; the script gives `/dev/null` for a path
/// like these, whose jobs write their own logs), and prints the job id. A job whose
/// dependency failed does not run.
const SBATCH: &str = r#"#!/bin/bash
set -u
state=${FAKE_SBATCH_STATE:?}
array= ; chdir=. ; output=slurm-%j.out ; after=
for a in "$@"; do
  case "$a" in
    --array=*) array=${a#--array=} ;;
    --chdir=*) chdir=${a#--chdir=} ;;
    --output=*) output=${a#--output=} ;;
    --dependency=afterok:*) after=${a#--dependency=afterok:} ;;
    -*) ;;
    *) echo "stand-in sbatch: a script file ($a) instead of standard input" >&2; exit 2 ;;
  esac
done
n=$(( $(cat "$state/next" 2>/dev/null || echo 100) + 1 ))
echo "$n" > "$state/next"
job="$state/job-$n.sh"
cat > "$job"
if [ -n "$after" ] && [ -e "$state/failed-$after" ]; then
  echo "$n"
  exit 0
fi
name() { # the --output pattern for task $1
  local f=$output
  f=${f//\%A/$n}; f=${f//\%a/$1}; f=${f//\%j/$n}
  printf '%s' "$f"
}
run() { # task $1 ("" outside an array); the log relative to the --chdir folder
  ( cd "$chdir" && SLURM_JOB_ID=$n SLURM_ARRAY_JOB_ID=$n SLURM_ARRAY_TASK_ID=$1 \
    bash "$job" > "$(name "$1")" 2>&1 ) \
    || touch "$state/failed-$n"
}
if [ -n "$array" ]; then
  for k in $(seq "${array%-*}" "${array#*-}"); do run "$k"; done
else
  run ""
fi
echo "$n"
"#;

/// Every file or folder under `dir` whose name contains `needle`.
fn find(dir: &Path, needle: &str, hits: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if e.file_name().to_string_lossy().contains(needle) {
            hits.push(p.clone());
        }
        if e.file_type().unwrap().is_dir() {
            find(&p, needle, hits);
        }
    }
}

fn logs(dir: &Path) -> String {
    let mut text = String::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        if p.extension().is_some_and(|x| x == "out") {
            text += &format!(
                "--- {}\n{}\n",
                p.display(),
                std::fs::read_to_string(&p).unwrap_or_default()
            );
        }
    }
    text
}

#[test]
fn the_slurm_script_passes_odd_paths_as_given_and_runs_nothing_in_them() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    // Each injection, if it ran, leaves a file named PWNED... in the folder it ran in
    // (the script's, a job's) or at the absolute path `root/PWNED...`.
    let mark = root.join("PWNED");
    let m = mark.display();
    let odd = format!(
        "a b 'q' \"dq\";$(touch {m}1);`touch {m}2`;$(touch PWNED3) \\n\\\\ $HOME ${{X}} %A %% \
         \nCABLESIM_JOB\ntouch PWNED4\n!x"
    );
    // The study file, the binary and the results folder all in such folders.
    let dir = root.join(format!("study {odd}"));
    std::fs::create_dir_all(&dir).unwrap();
    let study = dir.join("st'u dy.toml");
    let text = std::fs::read_to_string(STUDY).unwrap();
    // 2 sea states x 3 seeds of 4 s: a short run.
    let short = text
        .replace("duration = 40.0          # s per member", "duration = 4.0")
        .replace("transient = 10.0", "transient = 1.0")
        .replace("ramp = 8.0 ", "ramp = 1.0 ");
    assert!(short.contains("duration = 4.0") && short.contains("transient = 1.0"));
    std::fs::write(&study, short).unwrap();
    let exe = dir.join("cable $sim");
    std::os::unix::fs::symlink(BIN, &exe).unwrap();
    let out = root.join("runs").join(&odd);

    let sbin = root.join("bin");
    std::fs::create_dir_all(&sbin).unwrap();
    let sbatch = sbin.join("sbatch");
    std::fs::write(&sbatch, SBATCH).unwrap();
    std::fs::set_permissions(&sbatch, std::fs::Permissions::from_mode(0o755)).unwrap();
    let state = root.join("sbatch-state");
    std::fs::create_dir_all(&state).unwrap();

    let wrote = Command::new(BIN)
        .args(["study", "slurm"])
        .arg(&study)
        .args(["--shards", "2", "--cablesim"])
        .arg(&exe)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        wrote.status.success(),
        "{}",
        String::from_utf8_lossy(&wrote.stderr)
    );
    let script = out.join("submit.sh");
    let work = root.join("submitted from here");
    std::fs::create_dir_all(&work).unwrap();
    let path = format!(
        "{}:{}",
        sbin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let submit = Command::new("bash")
        .arg(&script)
        .arg("--wait")
        .current_dir(&work)
        .env("PATH", path)
        .env("FAKE_SBATCH_STATE", &state)
        .env("RAYON_NUM_THREADS", "1")
        .env_remove("SBATCH_ARGS")
        .output()
        .unwrap();
    let said = format!(
        "{}\n{}\n{}\nscript:\n{}",
        String::from_utf8_lossy(&submit.stdout),
        String::from_utf8_lossy(&submit.stderr),
        logs(&out),
        std::fs::read_to_string(&script).unwrap()
    );
    let mut hits = Vec::new();
    find(root, "PWNED", &mut hits);
    // The folder names hold the text "PWNED" (as written, not run): only a file counts.
    hits.retain(|p| p.is_file());
    assert!(hits.is_empty(), "injected commands ran: {hits:?}\n{said}");
    assert!(submit.status.success(), "{said}");
    // Every output in the folder named: the shards' and the merged tables, the logs.
    for k in 1..=2 {
        let shard = out.join(format!("shard-{k}-of-2"));
        assert!(
            shard.join("shard.json").is_file(),
            "{}\n{said}",
            shard.display()
        );
    }
    for f in ["study.csv", "members.csv", "study.json"] {
        assert!(out.join(f).is_file(), "{f}\n{said}");
    }
    assert!(out.join("slurm-101_1.out").is_file(), "{said}");
    assert!(out.join("slurm-merge-102.out").is_file(), "{said}");
}
