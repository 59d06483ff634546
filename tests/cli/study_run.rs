//! `cablesim study run | merge` end to end on the example study: shards merged equal
//! the one-machine run byte for byte, one thread equals two, an interrupted run keeps
//! its finished members and `--resume` completes it to the same files, and bad shard
//! and directory arguments are refused by name; the same for a short copy of the
//! design-check study, whose RAO-driven platform moves by knots shared across threads.

use super::common::study_with_a_failing_member;
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

/// The design-check study (`examples/study_design_check.toml`: an RAO-driven platform
/// with eight lines, its motion interpolated between knots) cut to members of 4 s with
/// a 2 s wave ramp (the platform in full motion for the last 2 s), two seeds per sea
/// state, in `dir`; returns its path.
fn short_design_study(dir: &Path) -> std::path::PathBuf {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let text = std::fs::read_to_string(base.join("study_design_check.toml")).unwrap();
    let rao = base.join("spread_mooring_rao.csv");
    let t = text
        .replace("duration = 10800.0", "duration = 4.0")
        .replace("transient = 300.0", "transient = 2.0")
        .replace("ramp = 60.0", "ramp = 2.0")
        .replace("seeds = 10\n", "seeds = 2\n")
        .replace(
            "rao_file = \"spread_mooring_rao.csv\"",
            &format!("rao_file = {:?}", rao.to_str().unwrap()),
        );
    assert_eq!(t.matches("duration = 4.0").count(), 2);
    assert!(t.contains("ramp = 2.0") && t.contains("seeds = 2\n"));
    assert!(!t.contains("\"spread_mooring_rao.csv\""));
    let out = dir.join("design.toml");
    std::fs::write(&out, t).unwrap();
    out
}

#[test]
fn a_study_with_rao_vessels_gives_the_same_files_on_any_threads_and_shards() {
    // The platform's motion is shared by its eight fairleads, whose cables step on
    // several threads: it must not depend on which thread asked first.
    let tmp = tempfile::tempdir().unwrap();
    let study = short_design_study(tmp.path());
    let study = study.to_str().unwrap();
    let two = tmp.path().join("two");
    run(2, &["study", "run", study, "-q"], &two);
    let one = tmp.path().join("one");
    run(1, &["study", "run", study, "-q"], &one);
    same_tables(&two, &one);
    let (s1, s2) = (tmp.path().join("s1"), tmp.path().join("s2"));
    run(2, &["study", "run", study, "-q", "--shard", "1/2"], &s1);
    run(1, &["study", "run", study, "-q", "--shard", "2/2"], &s2);
    let merged = tmp.path().join("merged");
    ok(cablesim(1, &["study", "merge"])
        .arg(&s1)
        .arg(&s2)
        .arg("--out")
        .arg(&merged)
        .output()
        .unwrap());
    same_tables(&two, &merged);
    // Real motion: every member completed, and the two seeds of a sea state see
    // different fairlead tensions.
    let members = std::fs::read_to_string(two.join("members.csv")).unwrap();
    let rows: Vec<Vec<&str>> = members.lines().map(|l| l.split(',').collect()).collect();
    let col = |n: &str| rows[0].iter().position(|h| *h == n).unwrap();
    assert!(rows[1..].iter().all(|r| r[col("status")] == "completed"));
    let maxima: Vec<&str> = rows[1..]
        .iter()
        .filter(|r| r[col("sea_state")] == "0" && r[col("channel")] == "line1.tension_max")
        .map(|r| r[col("max")])
        .collect();
    assert_eq!(maxima.len(), 2);
    assert_ne!(maxima[0], maxima[1]);
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
    // As an interrupted single run: exit status 130.
    assert_eq!(out.status.code(), Some(130), "{err}");
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
fn a_member_that_blows_up_is_reported_and_left_out_of_the_extremes() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_with_a_failing_member(tmp.path());
    let out = tmp.path().join("out");
    // Not quiet: the per-sea-state lines and the failure reach a log that is not a
    // terminal (the progress bar is then hidden).
    let o = ok(cablesim(2, &["study", "run"])
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    let err = String::from_utf8_lossy(&o.stderr);
    let failure = "member 3 (sea state 1 \"violent\", seed 1, wave seed ";
    let line = err
        .lines()
        .find(|l| l.starts_with(&format!("failed: {failure}")))
        .unwrap_or_else(|| panic!("no failure reported: {err}"));
    assert!(
        line.contains("simulation diverged at t = ")
            && line.contains("cable 'line")
            && line.contains("node ")
            && line.contains("over the limit 7.5e-1 m/s"),
        "{line}"
    );
    // One line per sea state, once all its members are done.
    for head in [
        "sea state 0 (calm): Hs 1 m, Tp 8 s: 3 members done, 0 failed",
        "sea state 1 (violent): Hs 8 m, Tp 10 s: 3 members done, 1 failed",
    ] {
        assert_eq!(err.matches(head).count(), 1, "{head}: {err}");
    }
    assert!(err.contains("done: 6 members (1 failed)"), "{err}");

    // members.csv: member 3 failed with the message, the others completed.
    let members = std::fs::read_to_string(out.join("members.csv")).unwrap();
    let mut rows = csv::Reader::from_reader(members.as_bytes());
    let head = rows.headers().unwrap().clone();
    let col = |n: &str| head.iter().position(|h| h == n).unwrap();
    let rows: Vec<csv::StringRecord> = rows.records().map(|r| r.unwrap()).collect();
    for r in &rows {
        let failed = &r[col("member")] == "3";
        assert_eq!(
            &r[col("status")],
            if failed { "failed" } else { "completed" }
        );
        assert_eq!(r[col("error")].starts_with(failure), failed, "{r:?}");
    }
    // study.json: counted and listed with its sea state, seed and wave seed.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("study.json")).unwrap()).unwrap();
    assert_eq!(summary["failed"], 1);
    let listed = &summary["failed_members"];
    assert_eq!(listed.as_array().unwrap().len(), 1, "{listed}");
    assert_eq!(
        (
            &listed[0]["index"],
            &listed[0]["sea_state"],
            &listed[0]["seed"]
        ),
        (&3.into(), &1.into(), &1.into())
    );
    assert!(listed[0]["error"].as_str().unwrap().starts_with(failure));
    // The violent sea state's extremes come from its two completed seeds.
    let ch = &summary["sea_states"][1]["channels"][0];
    assert_eq!(ch["channel"], "line1.tension_max");
    assert_eq!((&ch["seeds"], &ch["failed"]), (&2.into(), &1.into()));
    let maxima: Vec<f64> = rows
        .iter()
        .filter(|r| {
            &r[col("sea_state")] == "1"
                && &r[col("status")] == "completed"
                && &r[col("channel")] == "line1.tension_max"
        })
        .map(|r| r[col("max")].parse().unwrap())
        .collect();
    assert_eq!(maxima.len(), 2);
    let max_mean = ch["max_mean"].as_f64().unwrap();
    assert!((max_mean - (maxima[0] + maxima[1]) / 2.0).abs() <= 1e-9 * max_mean);
    assert_eq!(
        ch["max_largest"].as_f64().unwrap(),
        maxima[0].max(maxima[1])
    );
    // The calm sea state lost nothing.
    assert_eq!(summary["sea_states"][0]["channels"][0]["seeds"], 3);
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
    for (args, says) in [
        (
            &["study", "run", STUDY, "--shard", "0/2"][..],
            "--shard: shard: in \"0/2\", the shard index K is out of range",
        ),
        (
            &["study", "slurm", STUDY, "--shards", "0"][..],
            "--shards: must be at least 1",
        ),
        (
            &["study", "slurm", STUDY, "--shards", "9"][..],
            "at most 6 shards",
        ),
    ] {
        let e = cablesim(1, args)
            .arg("--out")
            .arg(tmp.path().join("never"))
            .output()
            .unwrap();
        let m = String::from_utf8_lossy(&e.stderr);
        assert!(!e.status.success() && m.contains(says), "{args:?}: {m}");
    }

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
pub(crate) const FAKE_SBATCH: &str = r#"#!/bin/bash
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

/// `study slurm --backend/--precision/--batch` hands those options to every task's
/// `study run` (and only those given); the default is the CPU.
#[test]
fn slurm_tasks_get_the_backend_options() {
    let tmp = tempfile::tempdir().unwrap();
    let task_line = |extra: &[&str]| {
        let out = tmp.path().join(format!("runs{}", extra.len()));
        let mut args = vec!["study", "slurm", STUDY, "--shards", "2"];
        args.extend_from_slice(extra);
        ok(cablesim(1, &args).arg("--out").arg(&out).output().unwrap());
        let text = std::fs::read_to_string(out.join("submit.sh")).unwrap();
        text.lines()
            .find(|l| l.contains("study run"))
            .unwrap_or_else(|| panic!("no study run line in {text}"))
            .to_string()
    };
    let gpu = task_line(&["--backend", "gpu", "--precision", "f64", "--batch", "3"]);
    assert!(
        gpu.contains("--resume --backend gpu --precision f64 --batch 3 "),
        "{gpu}"
    );
    let cpu = task_line(&[]);
    assert!(cpu.contains("--resume --backend cpu "), "{cpu}");
    assert!(
        !cpu.contains("--precision") && !cpu.contains("--batch"),
        "{cpu}"
    );
}

/// The example study with its first sea state row replaced by `row` (inline table
/// fields after the name), one seed of 2 s.
fn study_with_row(dir: &Path, row: &str, seeds: u32) -> std::path::PathBuf {
    let text = std::fs::read_to_string(STUDY).unwrap();
    let first = "{ name = \"operating\", hs = 2.0, tp = 8.0, heading = 0.0, current_speed = 0.3,";
    assert!(
        text.contains(first),
        "the example's first sea state changed"
    );
    let text = text
        .replace(first, &format!("{{ name = \"operating\", {row},"))
        .replace("seeds = 3", &format!("seeds = {seeds}"))
        .replace("duration = 40.0          # s per member", "duration = 2.0")
        .replace("transient = 10.0", "transient = 1.0");
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_sea_state_the_waves_cannot_take_is_named_by_its_study_field_before_any_member_runs() {
    let tmp = tempfile::tempdir().unwrap();
    for (row, says) in [
        (
            "hs = 1e200, tp = 8.0, heading = 0.0, current_speed = 0.3",
            "study.sea_states[0].hs: hs = 1e200 m",
        ),
        (
            "hs = 2.0, tp = 8.0, heading = 0.0, current_speed = 1e200",
            "study.sea_states[0].current_speed: current [1e200",
        ),
        (
            "hs = 2.0, tp = 8.0, gamma = 40.0, heading = 0.0, current_speed = 0.3",
            "study.sea_states[0].gamma: a JONSWAP peak factor of at most 7",
        ),
    ] {
        let study = study_with_row(tmp.path(), row, 2);
        let out = tmp.path().join("out");
        let e = cablesim(1, &["study", "run"])
            .arg(&study)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let m = String::from_utf8_lossy(&e.stderr);
        assert!(!e.status.success(), "{row}: {m}");
        assert!(m.contains(&format!("study.toml: {says}")), "{row}: {m}");
        // Nothing ran: no member's record was written.
        assert!(!out.join("members").exists(), "{row}: {m}");
    }
}

#[test]
fn a_steep_sea_states_warning_is_printed_once_under_its_study_field() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_with_row(
        tmp.path(),
        "hs = 90.0, tp = 3.0, heading = 0.0, current_speed = 0.3",
        3,
    );
    let out = ok(cablesim(2, &["study", "run"])
        .arg(&study)
        .arg("--out")
        .arg(tmp.path().join("out"))
        .output()
        .unwrap());
    let m = String::from_utf8_lossy(&out.stderr);
    let warnings: Vec<&str> = m.lines().filter(|l| l.contains("breaking limit")).collect();
    assert_eq!(warnings.len(), 1, "{m}");
    assert!(
        warnings[0].contains("study.toml: study.sea_states[0].hs: Hs/L")
            && warnings[0].contains("sea state 0 \"operating\""),
        "{m}"
    );
}
