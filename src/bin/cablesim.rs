//! The `cablesim` command line: a thin layer over the library.

use anyhow::{Context, Result};
use cablesim::gpu::Precision;
use cablesim::options::{parse_formulation, CableModel, Scheme, SolverOptions};
use cablesim::scenario::{Backend, Scenario};
use cablesim::sim::{self, Overrides, RunOptions};
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "cablesim",
    version,
    about = "Many underwater cables at once (GLMF lumped mass)"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Run a simulation.
    Run {
        /// Scenario file (TOML), or a MoorDyn input file (v1 or v2, told by its content).
        scenario: PathBuf,
        /// Output directory (default: out/<scenario name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// auto | cpu | gpu (default: the scenario's, else auto). The GPU adapter can
        /// be picked with WGPU_BACKEND (vulkan, gl, ...) and WGPU_ADAPTER_NAME.
        #[arg(long)]
        backend: Option<String>,
        /// f32 | f64: GPU shader precision (default: the scenario's, else f32; f64
        /// needs an adapter with SHADER_F64). The CPU path is always f64.
        #[arg(long)]
        precision: Option<String>,
        /// symplectic | rk2 | rk4.
        #[arg(long)]
        scheme: Option<String>,
        /// glmf | rvef | euler | frenet (lumped mass), or ancf (the ANCF reference
        /// model, ALE-ANCF for winch cables; CPU only; see the scenario's `[ancf]`).
        #[arg(long)]
        formulation: Option<String>,
        /// Time step in seconds (overrides the scenario's `dt`).
        #[arg(long)]
        dt: Option<f64>,
        /// Simulated duration in seconds (overrides the scenario's).
        #[arg(long)]
        duration: Option<f64>,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Validate a scenario file without running it.
    Check {
        /// Scenario file (TOML), or a MoorDyn input file.
        scenario: PathBuf,
    },
    /// Convert a MoorDyn input file (v1 or v2) to a scenario file, with a comment on
    /// every mapping choice.
    Convert {
        /// MoorDyn input file.
        input: PathBuf,
        /// Scenario file to write (default: standard output).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Simulated duration in seconds (a MoorDyn file has none).
        #[arg(long, default_value_t = 60.0)]
        duration: f64,
        /// Drive a vessel/coupled point by a CSV motion file `t,x,y,z`: `ID=FILE`
        /// (repeatable; a relative FILE is read from the scenario's folder).
        #[arg(long, value_name = "ID=FILE")]
        motion: Vec<String>,
    },
}

fn parse_opt<T>(
    v: &Option<String>,
    what: &str,
    f: impl Fn(&str) -> Option<T>,
) -> Result<Option<T>> {
    match v {
        None => Ok(None),
        Some(s) => f(s)
            .map(Some)
            .ok_or_else(|| anyhow::anyhow!("--{what}: unknown value \"{s}\"")),
    }
}

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("info"))
        .format_timestamp(None)
        .init();
    match real_main() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn real_main() -> Result<()> {
    let cli = Cli::parse();
    match cli.cmd {
        Cmd::Convert {
            input,
            output,
            duration,
            motion,
        } => convert(&input, output.as_deref(), duration, &motion),
        Cmd::Check { scenario } => {
            let sc = Scenario::load_any(&scenario)?;
            let (lay, _) = cablesim::model::Layout::build(&sc.model)?;
            let opts = SolverOptions {
                scheme: sc.sim.scheme,
                baumgarte: sc.sim.baumgarte,
                ..Default::default()
            };
            if sc.sim.model == CableModel::Ancf {
                for (name, n, dt, term) in cablesim::ancf::run::check(&sc, &sc.ancf)? {
                    println!(
                        "{}: ok: cable '{name}': ANCF, {n} elements, stable step {dt:.4e} s ({term})",
                        scenario.display()
                    );
                }
                return Ok(());
            }
            let plan = sim::plan_steps(&sc, &lay, &opts, sc.sim.duration, sc.sim.dt)?;
            if let Some(w) = &plan.warning {
                log::warn!("{w}");
            }
            println!(
                "{}: ok: {} cables, {} nodes, {} elements; dt = {:.4e} s (stable {:.4e} s, set by {}); {} steps",
                scenario.display(),
                lay.cables.len(),
                lay.n_nodes(),
                lay.n_elements(),
                plan.dt,
                plan.bound.dt,
                plan.bound.term,
                plan.total_steps
            );
            Ok(())
        }
        Cmd::Run {
            scenario,
            out,
            backend,
            precision,
            scheme,
            formulation,
            dt,
            duration,
            quiet,
        } => {
            let fm = parse_opt(&formulation, "formulation", parse_formulation)?;
            let overrides = Overrides {
                backend: parse_opt(&backend, "backend", Backend::parse)?,
                precision: parse_opt(&precision, "precision", Precision::parse)?,
                scheme: parse_opt(&scheme, "scheme", Scheme::parse)?,
                formulation: fm.map(|x| x.1),
                model: fm.map(|x| x.0),
                dt: dt
                    .map(|d| {
                        if d > 0.0 && d.is_finite() {
                            Ok(d)
                        } else {
                            Err(anyhow::anyhow!("--dt must be a positive number"))
                        }
                    })
                    .transpose()?,
                duration: duration
                    .map(|d| {
                        if d > 0.0 && d.is_finite() {
                            Ok(d)
                        } else {
                            Err(anyhow::anyhow!("--duration must be a positive number"))
                        }
                    })
                    .transpose()?,
            };
            let sc = Scenario::load_any(&scenario)?;
            let out_dir = out.unwrap_or_else(|| {
                PathBuf::from("out").join(
                    scenario
                        .file_stem()
                        .map(|s| s.to_os_string())
                        .unwrap_or_else(|| "run".into()),
                )
            });
            let ro = RunOptions {
                out_dir: out_dir.clone(),
                overrides,
                progress: !quiet,
            };
            let s = sim::run(&sc, &ro).with_context(|| {
                // Name the output only when the run got as far as writing some.
                if out_dir.join("end_forces.csv").exists() {
                    format!(
                        "run of {} (output so far kept in {})",
                        scenario.display(),
                        out_dir.display()
                    )
                } else {
                    format!("run of {}", scenario.display())
                }
            })?;
            eprintln!(
                "done: {} steps of {:.4e} s to t = {} s in {:.3} s of stepping ({:.3e} node-steps/s); output in {}",
                s.steps,
                s.dt,
                s.simulated_time,
                s.wall_seconds,
                s.node_steps_per_second,
                out_dir.display()
            );
            Ok(())
        }
    }
}

fn convert(
    input: &std::path::Path,
    output: Option<&std::path::Path>,
    duration: f64,
    motion: &[String],
) -> Result<()> {
    if !(duration > 0.0 && duration.is_finite()) {
        anyhow::bail!("--duration must be a positive number");
    }
    let mut opts = cablesim::moordyn::ConvertOptions {
        duration,
        ..Default::default()
    };
    for m in motion {
        let (id, file) = m
            .split_once('=')
            .ok_or_else(|| anyhow::anyhow!("--motion {m}: expected ID=FILE"))?;
        let id: usize = id
            .trim()
            .parse()
            .map_err(|_| anyhow::anyhow!("--motion {m}: \"{id}\" is not a point ID"))?;
        opts.motions.insert(id, file.to_string());
    }
    let text = std::fs::read_to_string(input)
        .with_context(|| format!("cannot read {}", input.display()))?;
    let conv = cablesim::moordyn::convert_text(&text, input, &opts)?;
    for w in &conv.warnings {
        log::warn!("{}: line {}: {}", input.display(), w.line, w.message);
    }
    // The result must load as a scenario; checked from where it will live, so that
    // motion files resolve as they will.
    let at = output
        .map(|o| o.to_path_buf())
        .unwrap_or_else(|| input.with_extension("toml"));
    Scenario::parse(&conv.toml, &at).context("the converted scenario does not validate")?;
    match output {
        Some(o) => std::fs::write(o, &conv.toml)
            .with_context(|| format!("cannot write {}", o.display()))?,
        None => print!("{}", conv.toml),
    }
    Ok(())
}
