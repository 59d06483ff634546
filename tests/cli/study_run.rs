//! `cablesim study run | merge` end to end on the example study: shards merged equal
//! the one-machine run byte for byte, one thread equals two, an interrupted run keeps
//! its finished members and `--resume` completes it to the same files, and bad shard
//! and directory arguments are refused by name.

use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");
const STUDY: &str = "examples/study_spread_mooring.toml";
const TABLES: [&str; 3] = ["study.csv", "members.csv", "study.json"];

fn cablesim(threads: usize, args: &[&str]) -> Command {
    let mut c = Command::new(BIN);
    c.env("RAYON_NUM_THREADS", threads.to_string()).args(args);
    c
}

fn ok(out: Output) -> Output {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn run(threads: usize, args: &[&str], out: &Path) {
    ok(cablesim(threads, args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap());
}

fn same_tables(a: &Path, b: &Path) {
    for f in TABLES {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(
            x == y,
            "{f} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn shards_threads_and_resume_give_the_one_machine_files() {
    let tmp = tempfile::tempdir().unwrap();
    let whole = tmp.path().join("whole");
    run(2, &["study", "run", STUDY, "-q"], &whole);

    // What the run wrote: every member and channel, all completed, real waves (the
    // storm's seeds differ), and the summary's counts.
    let members = std::fs::read_to_string(whole.join("members.csv")).unwrap();
    let mut rows = csv::Reader::from_reader(members.as_bytes());
    let head = rows.headers().unwrap().clone();
    let col = |n: &str| head.iter().position(|h| h == n).unwrap();
    let rows: Vec<csv::StringRecord> = rows.records().map(|r| r.unwrap()).collect();
    assert_eq!(
        rows.len(),
        6 * 9,
        "2 sea states x 3 seeds x 9 default channels"
    );
    assert!(rows.iter().all(|r| &r[col("status")] == "completed"));
    let storm_maxima: Vec<&str> = rows
        .iter()
        .filter(|r| &r[col("sea_state")] == "1" && &r[col("channel")] == "line1.tension_max")
        .map(|r| &r[col("max")])
        .collect();
    assert_eq!(storm_maxima.len(), 3);
    assert!(
        storm_maxima[0] != storm_maxima[1] && storm_maxima[1] != storm_maxima[2],
        "seeds of one sea state must see different waves: {storm_maxima:?}"
    );
    // Samples after the 10 s transient to 40 s at 0.5 s: 61.
    assert!(rows.iter().all(|r| &r[col("samples")] == "61"));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(whole.join("study.json")).unwrap()).unwrap();
    assert_eq!(summary["members"], 6);
    assert_eq!(summary["failed"], 0);

    // One thread gives the same bytes as two.
    let one = tmp.path().join("one_thread");
    run(1, &["study", "run", STUDY, "-q"], &one);
    same_tables(&whole, &one);

    // Two shards, each on its own, merged in either order.
    let s1 = tmp.path().join("s1");
    let s2 = tmp.path().join("s2");
    run(1, &["study", "run", STUDY, "-q", "--shard", "1/2"], &s1);
    run(2, &["study", "run", STUDY, "-q", "--shard", "2/2"], &s2);
    assert!(!s1.join("study.csv").exists(), "a shard writes no tables");
    let merged = tmp.path().join("merged");
    ok(cablesim(1, &["study", "merge"])
        .arg(&s2)
        .arg(&s1)
        .arg("--out")
        .arg(&merged)
        .output()
        .unwrap());
    same_tables(&whole, &merged);

    // Interrupted by SIGTERM after its first member: the finished members stay, the
    // status says so, the merge refuses the shard, and --resume finishes it.
    let cut = tmp.path().join("cut");
    let child = cablesim(1, &["study", "run", STUDY, "-q", "--out"])
        .arg(&cut)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let members_dir = cut.join("members");
    let started = std::time::Instant::now();
    loop {
        let n = std::fs::read_dir(&members_dir)
            .map(|d| {
                d.filter(|e| {
                    e.as_ref()
                        .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "json"))
                })
                .count()
            })
            .unwrap_or(0);
        if n > 0 {
            break;
        }
        assert!(started.elapsed().as_secs() < 120, "no member finished");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    ok(Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .output()
        .unwrap());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("study interrupted"), "{err}");
    assert!(err.contains("--resume"), "{err}");
    let status: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(cut.join("status.json")).unwrap()).unwrap();
    assert_eq!(status["state"], "interrupted");
    let kept = status["finished"].as_u64().unwrap();
    assert!((1..6).contains(&kept), "{status}");
    assert!(!cut.join("study.csv").exists());
    let m = cablesim(1, &["study", "merge"]).arg(&cut).output().unwrap();
    assert!(!m.status.success());
    assert!(
        String::from_utf8_lossy(&m.stderr).contains("has not completed"),
        "{}",
        String::from_utf8_lossy(&m.stderr)
    );
    // A fresh run into it is refused; --resume continues it.
    let again = cablesim(1, &["study", "run", STUDY, "-q", "--out"])
        .arg(&cut)
        .output()
        .unwrap();
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("--resume"));
    run(2, &["study", "run", STUDY, "-q", "--resume"], &cut);
    same_tables(&whole, &cut);
}

#[test]
fn bad_shards_and_foreign_directories_are_refused_by_name() {
    let tmp = tempfile::tempdir().unwrap();
    let e = cablesim(1, &["study", "run", STUDY, "--shard", "3/2"])
        .output()
        .unwrap();
    assert!(!e.status.success());
    let m = String::from_utf8_lossy(&e.stderr);
    assert!(
        m.contains("--shard: shard:") && m.contains("out of range"),
        "{m}"
    );
    let e = cablesim(1, &["study", "run", STUDY, "--shard", "7/7"])
        .output()
        .unwrap();
    let m = String::from_utf8_lossy(&e.stderr);
    assert!(m.contains("at most 6 shards"), "{m}");

    // --resume into a directory of another study: change the study seed.
    let other = tmp.path().join("other.toml");
    let text = std::fs::read_to_string(STUDY).unwrap();
    std::fs::write(&other, text.replace("seed = 2026", "seed = 7")).unwrap();
    let dir = tmp.path().join("d");
    std::fs::create_dir_all(dir.join("members")).unwrap();
    let status = r#"{"state":"interrupted","study_hash":"0000","shard":{"index":1,"count":1},"members":6,"finished":0,"failed":0}"#;
    std::fs::write(dir.join("status.json"), status).unwrap();
    let e = cablesim(1, &["study", "run", "--resume", "-q", "--out"])
        .arg(&dir)
        .arg(&other)
        .output()
        .unwrap();
    let m = String::from_utf8_lossy(&e.stderr);
    assert!(!e.status.success());
    assert!(
        m.contains("status.json: study_hash:") && m.contains("another study"),
        "{m}"
    );
}

/// A stand-in for Slurm's `sbatch` that runs a submitted script at once: each task of a
/// job array (`--array=1-N`) with its `SLURM_ARRAY_TASK_ID`, and prints a job id as
/// `--parsable` does. It checks the submission script's logic (shard arguments, output
/// folders, the merge job and its dependency); a real cluster is not needed for that.
const FAKE_SBATCH: &str = r#"#!/bin/bash
set -euo pipefail
array=""; dep=""
for a in "$@"; do
  case "$a" in
    --array=*) array="${a#--array=}" ;;
    --dependency=*) dep="${a#--dependency=}" ;;
  esac
done
script=$(mktemp); cat > "$script"
if [ -n "$array" ]; then
  for k in $(seq "${array%-*}" "${array#*-}"); do SLURM_ARRAY_TASK_ID=$k bash "$script"; done
  echo 4242
else
  [ "$dep" = "afterok:4242" ] || { echo "merge job depends on '$dep'" >&2; exit 1; }
  bash "$script"; echo 4243
fi
"#;

#[test]
fn slurm_script_runs_shards_and_merges_to_the_one_machine_files() {
    let tmp = tempfile::tempdir().unwrap();
    let bin = tmp.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let sbatch = bin.join("sbatch");
    std::fs::write(&sbatch, FAKE_SBATCH).unwrap();
    ok(Command::new("chmod")
        .arg("+x")
        .arg(&sbatch)
        .output()
        .unwrap());
    let runs = tmp.path().join("runs");
    ok(
        cablesim(2, &["study", "slurm", STUDY, "--shards", "4", "--out"])
            .arg(&runs)
            .output()
            .unwrap(),
    );
    let script = runs.join("submit.sh");
    let text = std::fs::read_to_string(&script).unwrap();
    assert!(text.contains("--array=1-4"), "{text}");
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap());
    ok(Command::new("bash")
        .arg(&script)
        .arg("--wait")
        .env("PATH", path)
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap());
    for k in 1..=4 {
        assert!(runs.join(format!("shard-{k}-of-4/shard.json")).exists());
    }
    let whole = tmp.path().join("whole");
    run(2, &["study", "run", STUDY, "-q"], &whole);
    same_tables(&whole, &runs);
}
