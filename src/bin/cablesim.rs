//! The `cablesim` command line: a thin layer over the library.

use anyhow::{Context, Result};
use cablesim::options::{
    Backend, CableModel, FormulationChoice, OutputFormat, Overrides, Precision, Scheme,
    SolverOptions,
};
use cablesim::output::{FailedStart, FanOut, FileSink, VtkSink};
use cablesim::scenario::{LimitOverrides, Scenario};
use cablesim::sim::{self, Progress, Simulation};
use cablesim::stability::AUTO_SAFETY;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

#[path = "cablesim/study.rs"]
mod study;

#[derive(Parser)]
#[command(
    name = "cablesim",
    version,
    about = "Many underwater cables at once (GLMF lumped mass)"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
    /// Warnings and errors only: no information lines, no progress bar, no closing
    /// summary line (the files and the exit status say how it went).
    #[arg(long, short, global = true)]
    quiet: bool,
    /// More detail: -v adds cablesim's debug lines (a study: its information lines),
    /// -vv its trace lines and other crates' information, -vvv their debug lines.
    /// Without -q or -v, RUST_LOG (env_logger's syntax) sets the levels when it is set.
    #[arg(long, short, action = clap::ArgAction::Count, global = true, conflicts_with = "quiet")]
    verbose: u8,
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
        /// Backend (default: the scenario's, else auto). The GPU adapter can be picked
        /// with WGPU_BACKEND (vulkan, gl, ...) and WGPU_ADAPTER_NAME.
        #[arg(long, value_enum)]
        backend: Option<Backend>,
        /// GPU shader precision (default: the scenario's, else f32; f64 needs an
        /// adapter with SHADER_F64). The CPU path is always f64.
        #[arg(long, value_enum)]
        precision: Option<Precision>,
        /// Time scheme (default: the scenario's, else symplectic).
        #[arg(long, value_enum)]
        scheme: Option<Scheme>,
        /// Cable model and load formulation: glmf, rvef, euler, frenet (lumped mass), or
        /// ancf (the ANCF reference model; see the scenario's `[ancf]`).
        #[arg(long, value_enum)]
        formulation: Option<FormulationChoice>,
        /// Time step in seconds (overrides the scenario's `dt`).
        #[arg(long, value_parser = positive)]
        dt: Option<f64>,
        /// Simulated duration in seconds (overrides the scenario's).
        #[arg(long, value_parser = positive)]
        duration: Option<f64>,
        /// Also write ParaView files into OUT/vtk (as `[output] vtk = true` does).
        #[arg(long)]
        vtk: bool,
        /// Format of the tables (end forces, tensions, positions, ...; default: the
        /// scenario's `[output] format`, else csv): csv, or parquet for large runs.
        #[arg(long, value_enum)]
        format: Option<OutputFormat>,
        /// Raise (or lower) a limit of the work budget over the scenario's `[limits]`:
        /// node_steps (default 1e12), memory_gib (16), output_gib (20); repeatable,
        /// e.g. `--limit node_steps=1e13`.
        #[arg(long, value_name = "KEY=VALUE")]
        limit: Vec<String>,
    },
    /// Draw PNG charts of a run's output directory (end forces, cable profiles) or a
    /// study's (Gumbel plots of the seed maxima, utilisation).
    Plot {
        /// The output directory of `cablesim run` or `cablesim study`.
        dir: PathBuf,
        /// Where to write the images (default: DIR/plots).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Output times for the profiles, s, comma separated (default: the first and
        /// the last).
        #[arg(long, value_delimiter = ',')]
        times: Vec<f64>,
    },
    /// Validate a scenario file without running it.
    Check {
        /// Scenario file (TOML), or a MoorDyn input file.
        scenario: PathBuf,
        /// A limit of the work budget over the scenario's `[limits]` (as for `run`).
        #[arg(long, value_name = "KEY=VALUE")]
        limit: Vec<String>,
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
    /// Monte Carlo sea-state studies: run members (or one shard of them), merge shards,
    /// write a Slurm submission script.
    Study {
        #[command(subcommand)]
        cmd: study::StudyCmd,
    },
}

/// A positive, finite number of seconds.
fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x > 0.0 && x.is_finite() => Ok(x),
        _ => Err("must be a positive number".into()),
    }
}

/// The log's filter: `-q` warnings and errors; by default cablesim's information lines
/// (a study's members would each log their mesh and step plan: a study shows warnings
/// and its own progress); each `-v` one level more. Other crates (wgpu, naga) say only
/// warnings until `-vv`. Without `-q` or `-v`, RUST_LOG wins when set.
fn log_filter(quiet: bool, verbose: u8, study: bool) -> Option<String> {
    const LEVELS: [&str; 5] = ["warn", "info", "debug", "trace", "trace"];
    if !quiet && verbose == 0 && std::env::var("RUST_LOG").is_ok_and(|v| !v.trim().is_empty()) {
        return None;
    }
    if quiet {
        return Some("warn".into());
    }
    let own = usize::from(!study) + verbose as usize;
    let others = own.saturating_sub(2).min(2);
    Some(format!(
        "{},cablesim={}",
        LEVELS[others],
        LEVELS[own.min(4)]
    ))
}

/// Whether progress bars are drawn: not with `-q`, and not when standard error is not a
/// terminal (a pipe, a file, a Slurm log), where a bar's redraws would be noise.
fn show_progress(quiet: bool) -> bool {
    use std::io::IsTerminal;
    !quiet && std::io::stderr().is_terminal()
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let study = matches!(cli.cmd, Cmd::Study { .. });
    let filter = log_filter(cli.quiet, cli.verbose, study);
    // RUST_LOG is read only when it sets the levels (else its module directives would
    // outlive -q); RUST_LOG_STYLE always.
    let mut logger = match &filter {
        Some(f) => {
            let mut b = env_logger::Builder::new();
            b.parse_filters(f);
            if let Ok(style) = std::env::var("RUST_LOG_STYLE") {
                b.parse_write_style(&style);
            }
            b
        }
        None => env_logger::Builder::from_env(env_logger::Env::default()),
    };
    logger.format_timestamp(None).init();
    match real_main(cli) {
        Ok(RunOutcome::Done) => ExitCode::SUCCESS,
        Ok(RunOutcome::Interrupted) => ExitCode::from(130),
        Err(e) => {
            // The chain of causes, each once: the library's errors already name their
            // cause in their own message.
            let mut text = String::new();
            for cause in e.chain() {
                let c = cause.to_string();
                if !text.contains(&c) {
                    if !text.is_empty() {
                        text.push_str(": ");
                    }
                    text.push_str(&c);
                }
            }
            eprintln!("error: {text}");
            ExitCode::FAILURE
        }
    }
}

fn real_main(cli: Cli) -> Result<RunOutcome> {
    let quiet = cli.quiet;
    match cli.cmd {
        Cmd::Study { cmd } => study::main(cmd, quiet),
        Cmd::Convert {
            input,
            output,
            duration,
            motion,
        } => convert(&input, output.as_deref(), duration, &motion).map(|_| RunOutcome::Done),
        Cmd::Check { scenario, limit } => {
            check(&scenario, &limits(&limit)?).map(|_| RunOutcome::Done)
        }
        Cmd::Plot { dir, out, times } => {
            let out = out.unwrap_or_else(|| dir.join("plots"));
            for p in cablesim::plot::plot_dir(&dir, &out, &times)? {
                println!("{}", p.display());
            }
            Ok(RunOutcome::Done)
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
            vtk,
            format,
            limit,
        } => {
            let limits = limits(&limit)?;
            let mut overrides = Overrides {
                backend,
                precision,
                scheme,
                dt,
                duration,
                ..Overrides::default()
            };
            if let Some(f) = formulation {
                overrides = overrides.with_formulation(f);
            }
            let out_dir = out.unwrap_or_else(|| {
                PathBuf::from("out").join(
                    scenario
                        .file_stem()
                        .map(|s| s.to_os_string())
                        .unwrap_or_else(|| "run".into()),
                )
            });
            let context = || {
                // Name the output only when the run got as far as writing some.
                if ["end_forces.csv", "end_forces.parquet"]
                    .iter()
                    .any(|f| out_dir.join(f).exists())
                {
                    format!(
                        "run of {} (output so far kept in {})",
                        scenario.display(),
                        out_dir.display()
                    )
                } else {
                    format!("run of {}", scenario.display())
                }
            };
            // A scenario that does not validate writes nothing. Then the output
            // directory: an earlier run's files go before the build can fail, and a
            // directory in use or not ours is refused before any work.
            let sc = Scenario::load_any_with(&scenario, &limits).with_context(context)?;
            let format = format.unwrap_or(sc.output_format);
            format
                .check_available()
                .map_err(anyhow::Error::msg)
                .context("--format")?;
            let mut sink = FileSink::claim(&out_dir)?.format(format)?;
            let scenario_path = sc.path.clone();
            let mut simulation = match Simulation::new(sc, &overrides) {
                Ok(s) => s,
                Err(e) => {
                    // The docs promise a summary for a failed run: this one failed
                    // before its first step (the initial equilibrium, the GPU set-up).
                    let summary = FailedStart::new(&scenario_path, &e.to_string());
                    if let Err(w) = summary.write(&out_dir) {
                        log::warn!("could not write the summary of the failed run: {w}");
                    }
                    return Err(e).with_context(context);
                }
            };
            let bar = if !show_progress(quiet) {
                indicatif::ProgressBar::hidden()
            } else {
                let b = indicatif::ProgressBar::new(0);
                b.set_style(
                    indicatif::ProgressStyle::with_template(
                        "{elapsed_precise} [{bar:40}] {percent}% t = {msg} (eta {eta})",
                    )
                    .expect("valid template")
                    .progress_chars("=> "),
                );
                b
            };
            let mut vtk_sink = VtkSink::new(out_dir.join("vtk"));
            let mut fatigue = (simulation.scenario().fatigue.clone())
                .map(|f| cablesim::output::FatigueSink::new(&out_dir, f));
            // The file sink last: it takes each frame to its writer thread without a
            // copy (`FanOut` hands the last sink the frame itself).
            let mut sinks = FanOut::new();
            if let Some(f) = fatigue.as_mut() {
                sinks = sinks.with(f);
            }
            if vtk || simulation.scenario().vtk {
                sinks = sinks.with(&mut vtk_sink);
            }
            let mut sinks = sinks.with(&mut sink);
            // Ctrl-C and SIGTERM ask the run to stop at the next step boundary; it then
            // writes its last frame and an `interrupted` summary.
            let stop = Arc::new(AtomicBool::new(false));
            {
                let stop = stop.clone();
                ctrlc::set_handler(move || stop.store(true, Ordering::Relaxed))
                    .context("cannot install the Ctrl-C/SIGTERM handler")?;
            }
            let s = simulation
                .run_until(
                    &mut sinks,
                    |p: Progress| {
                        bar.set_length(p.total);
                        bar.set_position(p.done);
                        bar.set_message(format!("{:.2} s", p.time));
                    },
                    || stop.load(Ordering::Relaxed),
                )
                .with_context(context);
            bar.finish_and_clear();
            let s = s?;
            if s.status == "interrupted" {
                eprintln!(
                    "interrupted at t = {} s after {} steps; output so far in {}",
                    s.simulated_time,
                    s.steps,
                    out_dir.display()
                );
                return Ok(RunOutcome::Interrupted);
            }
            if quiet {
                return Ok(RunOutcome::Done);
            }
            eprintln!(
                "done: {} steps of {:.4e} s to t = {} s in {:.3} s of stepping ({:.3e} node-steps/s); output in {}",
                s.steps,
                s.dt,
                s.simulated_time,
                s.wall_seconds,
                s.node_steps_per_second,
                out_dir.display()
            );
            Ok(RunOutcome::Done)
        }
    }
}

/// How a command ended, when it did not fail.
enum RunOutcome {
    Done,
    /// A run or a study stopped by Ctrl-C or SIGTERM (exit status 130, as a shell
    /// reports SIGINT).
    Interrupted,
}

/// The `--limit KEY=VALUE` flags.
fn limits(flags: &[String]) -> Result<LimitOverrides> {
    let mut l = LimitOverrides::default();
    for f in flags {
        l.set(f).map_err(anyhow::Error::msg)?;
    }
    Ok(l)
}

/// `cablesim check`: validates the scenario and prints the mesh and the step plan.
fn check(scenario: &std::path::Path, limits: &LimitOverrides) -> Result<()> {
    let sc = Scenario::load_any_with(scenario, limits)?;
    let (lay, _) = cablesim::model::Layout::build(&sc.model)?;
    let opts = SolverOptions {
        scheme: sc.sim.scheme,
        formulation: sc.sim.formulation,
        baumgarte: sc.sim.baumgarte,
        ..Default::default()
    };
    if sc.sim.model == CableModel::Ancf {
        sim::budget::check_output(&sc, sc.sim.duration)?;
        for (name, n, dt, term) in sim::ancf::check(&sc, &sc.ancf, sc.sim.scheme)? {
            let work = (n + 1) as f64 * (sc.sim.duration / (AUTO_SAFETY * dt)).ceil();
            println!(
                "{}: ok: cable '{name}': ANCF, {n} elements, stable step {dt:.4e} s ({term}); \
                 work: {work:.3e} element-node steps (no measured rate of the ANCF model: no time estimate)",
                scenario.display()
            );
        }
        return Ok(());
    }
    let plan = sim::plan_steps(&sc, &lay, &opts, sc.sim.duration, sc.sim.dt)?;
    if let Some(w) = &plan.warning {
        log::warn!("{w}");
    }
    let above = if plan.dt > plan.bound.dt {
        " (dt is above the stable step: expect a blow-up or wrong results)"
    } else {
        ""
    };
    println!(
        "{}: ok: {} cables, {} nodes, {} elements; dt = {:.4e} s (stable {:.4e} s, set by {}); {} steps{above}",
        scenario.display(),
        lay.cables.len(),
        lay.n_nodes(),
        lay.n_elements(),
        plan.dt,
        plan.bound.dt,
        plan.bound.term,
        plan.total_steps
    );
    let est = sim::budget::cpu_estimate(&sc, &lay, &opts, plan.total_steps);
    let gpu = match sc.sim.backend {
        Backend::Cpu => String::new(),
        // The GPU's rate depends on the adapter, which `check` does not open.
        _ => format!(
            "; on a datacenter GPU at least {} (sim::estimate)",
            sim::estimate::duration_words(
                sim::estimate::lumped(
                    &lay,
                    &opts,
                    plan.total_steps,
                    sim::budget::in_waves(&sc),
                    sim::estimate::Path::Gpu(sc.sim.precision.unwrap_or_default()),
                )
                .seconds
            )
        ),
    };
    println!(
        "{}: work: {}{gpu}; budget {:e} node-steps",
        scenario.display(),
        est.describe(),
        sc.limits.node_steps
    );
    Ok(())
}

/// `cablesim convert`: a MoorDyn input file as a scenario file.
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
    let text = cablesim::input::read_text(input)
        .map_err(|e| anyhow::anyhow!("{}: {e}", input.display()))?;
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
