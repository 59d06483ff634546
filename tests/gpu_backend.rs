//! Backend choice in the run driver: `--backend gpu` runs on the adapter and says so
//! in summary.json; `--backend gpu` without an adapter is a clear error; `--backend
//! auto` without one falls back to the CPU path with a logged reason.

mod common;

use common::*;
use std::process::Command;

fn run_cli(args: &[&str], backend_env: Option<&str>) -> (bool, String, Option<serde_json::Value>) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let bin = env!("CARGO_BIN_EXE_cablesim");
    let mut cmd = Command::new(bin);
    cmd.arg("run")
        .arg("examples/catenary.toml")
        .arg("--out")
        .arg(&out)
        .arg("-q")
        .arg("--duration")
        .arg("2")
        .args(args);
    if let Some(b) = backend_env {
        cmd.env("WGPU_BACKEND", b);
    }
    let o = cmd.output().unwrap();
    let summary = std::fs::read_to_string(out.join("summary.json"))
        .ok()
        .map(|s| serde_json::from_str(&s).unwrap());
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        summary,
    )
}

/// No adapter at all: `WGPU_BACKEND=metal` on a machine without Metal.
#[cfg(not(target_vendor = "apple"))]
#[test]
fn without_an_adapter_gpu_fails_and_auto_falls_back() {
    let (ok, err, summary) = run_cli(&["--backend", "gpu"], Some("metal"));
    assert!(!ok, "--backend gpu without an adapter must fail");
    assert!(err.contains("no GPU adapter"), "{err}");
    assert!(summary.is_none(), "no run without an adapter");
    let (ok, err, summary) = run_cli(&["--backend", "auto"], Some("metal"));
    assert!(ok, "{err}");
    assert!(
        err.contains("backend auto") && err.contains("running the f64 CPU reference path"),
        "{err}"
    );
    let s = summary.unwrap();
    assert_eq!(s["backend"], "cpu");
    assert_eq!(s["precision"], "f64");
}

#[test]
fn gpu_backend_reports_device_and_precision() {
    let Some(ctx) = gpu_context("gpu_backend_reports_device_and_precision", false) else {
        return;
    };
    let env = format!("{:?}", ctx.info.backend).to_lowercase();
    let (ok, err, cpu) = run_cli(&["--backend", "cpu"], None);
    assert!(ok, "{err}");
    let cpu = cpu.unwrap();
    let mut precisions = vec!["f32"];
    if ctx.supports(cablesim::gpu::Precision::F64) {
        precisions.push("f64");
    }
    for p in precisions {
        let (ok, err, s) = run_cli(&["--backend", "gpu", "--precision", p], Some(&env));
        assert!(ok, "{err}");
        let s = s.unwrap();
        assert_eq!(s["backend"], "gpu");
        assert_eq!(s["precision"], p);
        assert_eq!(s["device"], ctx.describe().as_str());
        assert_eq!(s["status"], "completed");
        for end in ["start", "end"] {
            let f = |v: &serde_json::Value| -> Vec<f64> {
                v["cables"][0]["end_forces"][end]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect()
            };
            let (g, c) = (f(&s), f(&cpu));
            let d = g
                .iter()
                .zip(&c)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            let n = c.iter().map(|a| a * a).sum::<f64>().sqrt();
            assert!(d < 0.01 * n, "{p}: {end} force {g:?} vs CPU {c:?}");
        }
    }
}
