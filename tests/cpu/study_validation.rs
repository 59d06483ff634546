//! A study's streamed statistics against a long single run: for a nearly linear system
//! (a taut line in small irregular waves) the tension's mean and standard deviation
//! pooled over the seeds of one sea state are the same process's as those of one long
//! record of it, within their sampling errors.

use cablesim::options::Overrides;
use cablesim::sim::Simulation;
use cablesim::study::{merge, summarise, ChannelStats, ShardSpec, StudyFile, StudyRunner};
use std::sync::atomic::AtomicBool;

/// A taut synthetic rope (55.76 m between its ends, 55.5 m long: about 0.5 % stretch)
/// from an anchor in 50 m of water to a fixed point 3 m below the surface. Small waves
/// move the water around its upper part; the tension varies a little about its
/// pretension.
const BASE: &str = r#"
[simulation]
duration = 100.0
dt = "auto"
output_interval = 0.5

[environment]
gravity = 9.81
water_density = 1025.0
depth = 50.0

[environment.waves]
ramp = 10.0

[[line_types]]
name = "rope"
diameter = 0.1
mass_per_length = 10.0
ea = 5.0e5
damping = 0.05
cn = 1.2
ct = 0.01
cm = 1.0

[[cables]]
name = "taut"
line_type = "rope"
length = 55.5
segments = 8
start = { fixed = [0.0, 0.0, -50.0] }
end = { fixed = [30.0, 0.0, -3.0] }
"#;

/// Seeds of the study, and its member duration and transient (s).
const SEEDS: usize = 8;
const DURATION: f64 = 130.0;
const TRANSIENT: f64 = 30.0;
const HS: f64 = 1.5;
const TP: f64 = 7.0;

fn mean_sd(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let v = x.iter().map(|a| (a - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, v.sqrt())
}

/// One long record of the sea state (its own wave seed, not one of the study's), the
/// fairlead force sampled at every output time after the transient, cut into `SEEDS`
/// blocks as long as a member's record. Plain two-pass statistics, not the study's code.
fn long_run_blocks() -> Vec<Vec<f64>> {
    let text = BASE.replace(
        "[environment.waves]\nramp = 10.0\n",
        &format!(
            "[environment.waves]\nramp = 10.0\nseed = 987654321\ntrains = [{{ type = \"jonswap\", \
             hs = {HS}, tp = {TP}, direction = 0.0 }}]\n"
        ),
    );
    let record = DURATION - TRANSIENT;
    let total = TRANSIENT + SEEDS as f64 * record;
    let overrides = Overrides {
        duration: Some(total),
        ..Overrides::default()
    };
    let mut sim =
        Simulation::from_toml(&text, std::path::Path::new("long.toml"), &overrides).unwrap();
    let dt_out = sim.scenario().sim.output_interval;
    let per_block = (record / dt_out).round() as usize;
    let mut samples = Vec::new();
    let mut k = 0u64;
    loop {
        k += 1;
        let t = k as f64 * dt_out;
        if t > total + 1e-9 {
            break;
        }
        sim.advance_to(t).unwrap();
        if t > TRANSIENT + 1e-9 {
            let f = sim.snapshot().unwrap().cables[0].end_forces.end;
            samples.push((f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt());
        }
    }
    assert_eq!(samples.len(), SEEDS * per_block);
    samples.chunks(per_block).map(<[f64]>::to_vec).collect()
}

#[test]
fn seed_pooled_tension_statistics_match_a_long_run_within_sampling_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("taut_study.toml");
    let study = format!(
        "{BASE}\n[study]\nseed = 11\nseeds = {SEEDS}\nduration = {DURATION:.1}\n\
         transient = {TRANSIENT:.1}\nsea_states = [{{ hs = {HS}, tp = {TP} }}]\n\
         channels = [\"taut.end_force\"]\n"
    );
    std::fs::write(&path, study).unwrap();
    let file = StudyFile::load(&path).unwrap();
    let runner = StudyRunner::new(&file).unwrap();
    let plan = runner.plan();
    let stop = AtomicBool::new(false);
    let members = runner
        .run(&plan.members, &stop, &|_| {}, &|_| Ok(()))
        .unwrap();
    assert_eq!(members.len(), SEEDS);
    let per_seed: Vec<&ChannelStats> = members.iter().map(|m| &m.stats[0]).collect();
    let merged = merge(vec![(
        path.clone(),
        plan.shard_result(ShardSpec::WHOLE, members.clone()),
    )])
    .unwrap();
    let summary = summarise(&merged);
    let c = &summary.sea_states[0].channels[0];
    assert_eq!(
        (c.channel.as_str(), c.seeds, c.failed),
        ("taut.end_force", SEEDS, 0)
    );
    let (mean, std) = (c.mean.unwrap(), c.std.unwrap());

    // Sampling errors from the spread of the seeds' own estimates (independent records)
    // and of the long record's blocks (batch means: nearly independent for blocks of
    // 100 s against wave periods of 7 s).
    let seed_means: Vec<f64> = per_seed.iter().map(|s| s.mean().unwrap()).collect();
    let seed_stds: Vec<f64> = per_seed.iter().map(|s| s.std().unwrap()).collect();
    let blocks = long_run_blocks();
    let block_means: Vec<f64> = blocks.iter().map(|b| mean_sd(b).0).collect();
    let block_stds: Vec<f64> = blocks.iter().map(|b| mean_sd(b).1).collect();
    let all: Vec<f64> = blocks.concat();
    let (long_mean, long_std) = mean_sd(&all);
    let n = (SEEDS as f64).sqrt();
    let se_mean = (mean_sd(&seed_means).1.powi(2) + mean_sd(&block_means).1.powi(2)).sqrt() / n;
    let se_std = (mean_sd(&seed_stds).1.powi(2) + mean_sd(&block_stds).1.powi(2)).sqrt() / n;
    eprintln!(
        "fairlead force: study mean {mean:.3} N, std {std:.4} N over {SEEDS} seeds; \
         long run mean {long_mean:.3} N, std {long_std:.4} N; \
         standard errors of the differences {se_mean:.4} N, {se_std:.4} N"
    );
    // The waves matter (the tension varies) and the comparison can tell: its tolerance
    // is well under the effect of the waves.
    assert!(
        std > 1e-2 * mean,
        "the waves hardly move the tension: {std} of {mean}"
    );
    assert!(
        4.0 * se_mean < std,
        "mean's tolerance {se_mean} against std {std}"
    );
    assert!(
        4.0 * se_std < 0.4 * std,
        "std's tolerance {se_std} against std {std}"
    );
    assert!(
        (mean - long_mean).abs() < 4.0 * se_mean,
        "mean: study {mean}, long run {long_mean}, standard error {se_mean}"
    );
    assert!(
        (std - long_std).abs() < 4.0 * se_std,
        "std: study {std}, long run {long_std}, standard error {se_std}"
    );
}
