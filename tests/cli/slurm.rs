//! `cablesim study slurm` on a real Slurm cluster: the script it writes is submitted
//! with `sbatch`, its job array runs the shards as Slurm jobs, the merge job waits for
//! them, and the merged tables equal the one-machine run byte for byte.
//!
//! The cluster is the machine's own (`sbatch` on PATH, `sinfo` answering), or the
//! single-node one `scripts/slurm_local.sh start` brings up (its config is used when
//! `SLURM_CONF` is unset). Without a cluster the test says it skipped and passes,
//! unless `CABLESIM_REQUIRE_SLURM=1` (set by `.ci/run`, which starts the cluster): then
//! a missing cluster is a failure. On the local cluster a study whose shards fail is
//! submitted too: the script must end with an error, not hang.

mod quoting;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");
const STUDY: &str = "examples/study_spread_mooring.toml";
const TABLES: [&str; 3] = ["study.csv", "members.csv", "study.json"];
/// Where `scripts/slurm_local.sh` writes its config.
const LOCAL_CONF: &str = "/tmp/cablesim-slurm/slurm.conf";
/// How long the submitted study may take before the test gives up (it takes seconds).
const WAIT: Duration = Duration::from_secs(600);

/// The `SLURM_CONF` for Slurm's commands: the environment's, else the local cluster's.
fn slurm_conf() -> Option<PathBuf> {
    match std::env::var_os("SLURM_CONF") {
        Some(c) => Some(PathBuf::from(c)),
        None => Some(PathBuf::from(LOCAL_CONF)).filter(|p| p.exists()),
    }
}

fn slurm_command(exe: &str) -> Command {
    let mut c = Command::new(exe);
    if let Some(conf) = slurm_conf() {
        c.env("SLURM_CONF", conf);
    }
    c
}

/// Why no cluster can be used, or `None` when one answers.
fn no_cluster() -> Option<String> {
    match slurm_command("sbatch").arg("--version").output() {
        Err(e) => return Some(format!("no sbatch on PATH ({e})")),
        Ok(o) if !o.status.success() => return Some("sbatch --version fails".into()),
        Ok(_) => {}
    }
    // `timeout`: sinfo retries for a minute when the controller is down.
    match Command::new("timeout")
        .arg("10")
        .arg("sinfo")
        .args(["-h", "-o", "%T"])
        .envs(slurm_conf().map(|c| ("SLURM_CONF", c)))
        .output()
    {
        Ok(o) if o.status.success() && !o.stdout.is_empty() => None,
        Ok(o) => Some(format!(
            "sinfo does not answer ({}): start a local cluster with \
             `scripts/slurm_local.sh start` (root, apt-get install slurm-wlm munge)",
            String::from_utf8_lossy(&o.stderr).trim()
        )),
        Err(e) => Some(format!("cannot run sinfo: {e}")),
    }
}

fn ok(what: &str, out: std::process::Output) {
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every Slurm log the jobs left in `dir`, for a failure message.
fn job_logs(dir: &Path) -> String {
    let mut text = String::new();
    let mut names: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "out"))
        .collect();
    names.sort();
    for p in names {
        text += &format!(
            "--- {}\n{}\n",
            p.display(),
            std::fs::read_to_string(&p).unwrap_or_default()
        );
    }
    text
}

#[test]
fn a_real_slurm_runs_the_submission_script_to_the_one_machine_files() {
    if let Some(why) = no_cluster() {
        if std::env::var("CABLESIM_REQUIRE_SLURM").is_ok_and(|v| v == "1") {
            panic!("CABLESIM_REQUIRE_SLURM=1 but {why}");
        }
        eprintln!(
            "\n*** SKIPPED a_real_slurm_runs_the_submission_script_to_the_one_machine_files: \
             {why}\n*** (set CABLESIM_REQUIRE_SLURM=1 to make this a failure)\n"
        );
        return;
    }
    // The example study made shorter (its 6 members, 15 s each): seconds on the cluster.
    let tmp = tempfile::tempdir().unwrap();
    let study = tmp.path().join("study.toml");
    let text = std::fs::read_to_string(STUDY).unwrap();
    let short = text
        .replace("duration = 40.0          # s per member", "duration = 15.0")
        .replace("transient = 10.0", "transient = 5.0");
    assert!(short.contains("duration = 15.0") && short.contains("transient = 5.0"));
    std::fs::write(&study, short).unwrap();

    let runs = tmp.path().join("runs");
    ok(
        "cablesim study slurm",
        Command::new(BIN)
            .args(["study", "slurm"])
            .arg(&study)
            .args(["--shards", "4", "--out"])
            .arg(&runs)
            .output()
            .unwrap(),
    );
    // Submitted from another folder: the script's paths are absolute.
    let script = runs.join("submit.sh");
    let submit = slurm_command("timeout")
        .arg(WAIT.as_secs().to_string())
        .arg("bash")
        .arg(&script)
        .arg("--wait")
        .current_dir(tmp.path())
        // One thread per task: the shards share the node's CPUs.
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap();
    assert!(
        submit.status.success(),
        "bash submit.sh --wait failed ({}):\n{}\n{}\n{}",
        submit.status,
        String::from_utf8_lossy(&submit.stdout),
        String::from_utf8_lossy(&submit.stderr),
        job_logs(&runs)
    );
    // The shards ran as the array's tasks, each in its own folder and with its own log.
    let array = String::from_utf8_lossy(&submit.stdout);
    let array = array
        .lines()
        .find_map(|l| l.strip_prefix("shards: job array "))
        .unwrap_or_else(|| panic!("no array job id in: {array}"))
        .trim()
        .to_string();
    for k in 1..=4 {
        let shard = runs.join(format!("shard-{k}-of-4"));
        assert!(
            shard.join("shard.json").exists(),
            "{}\n{}",
            shard.display(),
            job_logs(&runs)
        );
        assert!(
            runs.join(format!("slurm-{array}_{k}.out")).exists(),
            "{}",
            job_logs(&runs)
        );
    }

    let whole = tmp.path().join("whole");
    ok(
        "cablesim study run",
        Command::new(BIN)
            .args(["study", "run"])
            .arg(&study)
            .args(["-q", "--out"])
            .arg(&whole)
            .output()
            .unwrap(),
    );
    for f in TABLES {
        let (a, b) = (
            std::fs::read(whole.join(f)).unwrap(),
            std::fs::read(runs.join(f))
                .unwrap_or_else(|e| panic!("{f} not merged ({e}):\n{}", job_logs(&runs))),
        );
        assert!(
            a == b,
            "{f} of the Slurm run differs from the one-machine run"
        );
    }

    // Shards that fail (a "cablesim" that exits 1): the merge job never runs, and the
    // script says so with exit status 1. Checked on the local cluster, which cancels a
    // merge job whose dependency cannot be met (kill_invalid_depend); a cluster without
    // that leaves it pending, and `--wait` would not return.
    if slurm_conf().as_deref() != Some(Path::new(LOCAL_CONF)) {
        eprintln!("a failing study is not submitted: not the local cluster");
        return;
    }
    let bad = tmp.path().join("bad");
    ok(
        "cablesim study slurm --cablesim /bin/false",
        Command::new(BIN)
            .args(["study", "slurm"])
            .arg(&study)
            .args(["--shards", "2", "--cablesim", "/bin/false", "--out"])
            .arg(&bad)
            .output()
            .unwrap(),
    );
    let submit = slurm_command("timeout")
        .arg(WAIT.as_secs().to_string())
        .arg("bash")
        .arg(bad.join("submit.sh"))
        .arg("--wait")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&submit.stderr);
    assert_eq!(submit.status.code(), Some(1), "{err}");
    assert!(err.contains("the study was not merged"), "{err}");
    assert!(!bad.join("study.json").exists());
}
