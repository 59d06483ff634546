//! Backend choice in the run driver: `--backend gpu` runs on the adapter and says so
//! in summary.json; `--backend gpu` without an adapter is a clear error; `--backend
//! auto` without one falls back to the CPU path with a logged reason.

use super::common::*;
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
    // The run failed before its first step: its summary says so, and why.
    let s = summary.expect("a failed start writes summary.json");
    assert_eq!(s["status"], "failed");
    assert_eq!(s["steps"], 0);
    assert!(
        s["error"].as_str().unwrap().contains("no GPU adapter"),
        "{s}"
    );
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

/// A scenario whose fairlead follows a table route (a CSV file beside it) runs on the
/// GPU end to end (the route used to be refused there), and its end forces after the
/// motion match the CPU path's within 1%.
#[test]
fn table_route_scenario_runs_on_the_gpu() {
    let Some(ctx) = gpu_context("table_route_scenario_runs_on_the_gpu", false) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // Out 1 m along x over 2 s and held there (the run lasts 3 s).
    std::fs::write(
        dir.path().join("fairlead.csv"),
        "t,x,y,z\n0,0,0,-10\n0.5,0.15,0,-10\n1,0.5,0,-10\n1.5,0.85,0,-10\n2,1,0,-10\n",
    )
    .unwrap();
    let text = std::fs::read_to_string("examples/catenary.toml")
        .unwrap()
        .replace(
            "end = { fixed = [0.0, 0.0, -10.0] }",
            "end = { route = \"table\", file = \"fairlead.csv\" }",
        );
    assert!(text.contains("route = \"table\""));
    let scen = dir.path().join("table.toml");
    std::fs::write(&scen, text).unwrap();
    let env = format!("{:?}", ctx.info.backend).to_lowercase();
    let run = |backend: &str| {
        let out = dir.path().join(format!("out-{backend}"));
        let o = Command::new(env!("CARGO_BIN_EXE_cablesim"))
            .arg("run")
            .arg(&scen)
            .args(["--out", out.to_str().unwrap(), "--duration", "3"])
            .args(["--backend", backend])
            // `auto` says at the information level why it chose the CPU, which `-q`
            // hides (warnings and errors only).
            .args(if backend == "auto" {
                &[][..]
            } else {
                &["-q"][..]
            })
            .env("WGPU_BACKEND", &env)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "{backend}: {err}");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        (s, err)
    };
    let (gpu, _) = run("gpu");
    let (cpu, _) = run("cpu");
    assert_eq!(gpu["backend"], "gpu");
    assert_eq!(gpu["status"], "completed");
    let (_, err) = run("auto");
    if ctx.info.device_type == wgpu::DeviceType::Cpu {
        assert!(err.contains("software"), "{err}");
    }
    let end = |s: &serde_json::Value| -> Vec<f64> {
        s["cables"][0]["end_forces"]["end"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (g, c) = (end(&gpu), end(&cpu));
    let d = g
        .iter()
        .zip(&c)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt();
    let n = c.iter().map(|a| a * a).sum::<f64>().sqrt();
    eprintln!("table route: fairlead force GPU {g:?} N, CPU {c:?} N");
    assert!(d < 0.01 * n, "fairlead force {g:?} vs CPU {c:?}");
    let x = super::common::final_state(&dir.path().join("out-gpu"))[0].1[50].0[0];
    assert!(
        (x - 1.0).abs() < 1e-3,
        "the fairlead should be held at x = 1 m: {x}"
    );
}
