//! Studies without the simulation: the Gumbel fits against known laws, the `[study]`
//! table and its errors, and shards merged into results equal to a one-machine study
//! byte for byte.

use cablesim::scenario::Scenario;
use cablesim::study::channels::CableChannels;
use cablesim::study::definition::parse_study;
use cablesim::study::{
    merge, summarise, tables, ChannelStats, Gumbel, MemberResult, MemberStatus, ModelChannels,
    ShardResult, ShardSpec, StudyFile, StudyPlan,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------
// Gumbel fits against samples of known laws
// ---------------------------------------------------------------------------------

/// `n` draws of the Gumbel law `(mu, beta)` by inversion, `x = mu - beta ln(-ln U)`.
fn gumbel_sample(rng: &mut ChaCha8Rng, n: usize, mu: f64, beta: f64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            // U in (0, 1): never exactly 0, where ln(-ln U) is infinite.
            let u =
                (rng.gen::<u64>() >> 11) as f64 / (1u64 << 53) as f64 + 0.5 / (1u64 << 53) as f64;
            mu - beta * (-u.ln()).ln()
        })
        .collect()
}

/// `n` draws of a normal law by Box-Muller.
fn normal_sample(rng: &mut ChaCha8Rng, n: usize, mean: f64, std: f64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            let u1: f64 = 1.0 - rng.gen::<f64>();
            let u2: f64 = rng.gen();
            mean + std * (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
        })
        .collect()
}

/// Asymptotic standard deviations of the fitted `(mu, beta)` over `beta`, times
/// `sqrt(n)`:
/// - maximum likelihood, from the inverse Fisher information of the Gumbel law:
///   `Var mu = (1 + 6 (1 - gamma_E)^2 / pi^2) beta^2 / n = 1.10866 beta^2 / n`,
///   `Var beta = 6 / pi^2 beta^2 / n = 0.60793 beta^2 / n`;
/// - moments, by the delta method from the law's skewness 1.13955 and excess kurtosis
///   2.4: `Var s = (mu4 - sigma^4) / (4 sigma^2 n) = 1.1 sigma^2 / n`, so
///   `Var beta = 1.1 beta^2 / n`; `mu = mean - c s` with `c = gamma_E sqrt 6 / pi`,
///   `Cov(mean, s) = mu3 / (2 sigma n)`, so
///   `Var mu = (1 + 1.1 c^2 - 1.13955 c) sigma^2 / n = 1.16781 beta^2 / n`.
const SD_MLE: (f64, f64) = (1.052_932, 0.779_697);
const SD_MOMENTS: (f64, f64) = (1.080_654, 1.048_809);

/// Whether a fit is within `k` asymptotic standard deviations of the truth.
fn within(fit: Gumbel, mu: f64, beta: f64, n: usize, sd: (f64, f64), k: f64) -> bool {
    let s = beta / (n as f64).sqrt();
    (fit.mu - mu).abs() < k * sd.0 * s && (fit.beta - beta).abs() < k * sd.1 * s
}

#[test]
fn asymptotic_standard_deviations_are_the_stated_numbers() {
    let g = cablesim::study::gumbel::EULER_GAMMA;
    let pi2 = std::f64::consts::PI.powi(2);
    let c = g * 6f64.sqrt() / std::f64::consts::PI;
    assert!((SD_MLE.0 - (1.0 + 6.0 * (1.0 - g).powi(2) / pi2).sqrt()).abs() < 1e-6);
    assert!((SD_MLE.1 - (6.0 / pi2).sqrt()).abs() < 1e-6);
    let sigma2 = pi2 / 6.0;
    let skew = 1.139_547;
    assert!((SD_MOMENTS.0 - ((1.0 + 1.1 * c * c - skew * c) * sigma2).sqrt()).abs() < 1e-5);
    assert!((SD_MOMENTS.1 - 1.1f64.sqrt()).abs() < 1e-6);
}

#[test]
fn gumbel_fits_recover_a_known_law_within_sampling_error() {
    // A fairlead tension's seed maxima: mu = 6 MN, beta = 0.25 MN.
    let (mu, beta, n) = (6.0e6, 2.5e5, 20_000);
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let x = gumbel_sample(&mut rng, n, mu, beta);
    let mle = Gumbel::fit_mle(&x).unwrap();
    let mom = Gumbel::fit_moments(&x).unwrap();
    // Four standard deviations: a correct fit fails with probability about 1e-4 (and
    // the sample is fixed, so it either always passes or always fails).
    assert!(within(mle, mu, beta, n, SD_MLE, 4.0), "{mle:?}");
    assert!(within(mom, mu, beta, n, SD_MOMENTS, 4.0), "{mom:?}");
    // The quantile and the most probable maximum follow: the 0.9 quantile's error is
    // that of mu + 2.25 beta, within the sum of the two bounds.
    let q = mu - beta * (-0.9f64.ln()).ln();
    let s = beta / (n as f64).sqrt();
    assert!((mle.quantile(0.9) - q).abs() < 4.0 * (SD_MLE.0 + 2.25 * SD_MLE.1) * s);

    // Negative control (wrong parameters): the same check rejects the truth moved by
    // 10% of beta in scale or by half a beta in location, so the tolerance is not so
    // loose that anything passes.
    assert!(!within(mle, mu, 1.1 * beta, n, SD_MLE, 4.0));
    assert!(!within(mle, mu + 0.5 * beta, beta, n, SD_MLE, 4.0));
    assert!(!within(mom, mu, 1.1 * beta, n, SD_MOMENTS, 4.0));
}

#[test]
fn spread_of_repeated_fits_matches_the_asymptotic_standard_deviations() {
    // The tolerances above come from asymptotic formulas; check them on repeated
    // trials. 400 trials estimate a standard deviation to about 1 / sqrt(800) = 3.5%:
    // the measured spread must be within 15% of the formula.
    let (mu, beta, n, trials) = (100.0, 10.0, 2000, 400);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut fits = (Vec::new(), Vec::new());
    for _ in 0..trials {
        let x = gumbel_sample(&mut rng, n, mu, beta);
        fits.0.push(Gumbel::fit_mle(&x).unwrap());
        fits.1.push(Gumbel::fit_moments(&x).unwrap());
    }
    let rms = |v: &[f64], truth: f64| {
        (v.iter().map(|x| (x - truth).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
    };
    let s = beta / (n as f64).sqrt();
    for (fits, sd, name) in [(&fits.0, SD_MLE, "mle"), (&fits.1, SD_MOMENTS, "moments")] {
        let mus: Vec<f64> = fits.iter().map(|g| g.mu).collect();
        let betas: Vec<f64> = fits.iter().map(|g| g.beta).collect();
        let r_mu = rms(&mus, mu) / (sd.0 * s);
        let r_beta = rms(&betas, beta) / (sd.1 * s);
        assert!((r_mu - 1.0).abs() < 0.15, "{name}: mu spread ratio {r_mu}");
        assert!(
            (r_beta - 1.0).abs() < 0.15,
            "{name}: beta spread ratio {r_beta}"
        );
    }
    // And maximum likelihood is the tighter of the two for beta, as the formulas say.
    let rb = |f: &Vec<Gumbel>| rms(&f.iter().map(|g| g.beta).collect::<Vec<_>>(), beta);
    assert!(rb(&fits.0) < rb(&fits.1));
}

/// The Kolmogorov-Smirnov distance between a sample and a law's distribution function.
fn ks_distance(x: &[f64], cdf: impl Fn(f64) -> f64) -> f64 {
    let mut v = x.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len() as f64;
    v.iter()
        .enumerate()
        .map(|(i, &xi)| {
            let f = cdf(xi);
            (f - i as f64 / n).abs().max(((i + 1) as f64 / n - f).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_wrong_law_is_rejected() {
    // Negative control (wrong law): a Gumbel fit of normal samples, with the same mean
    // and standard deviation as a Gumbel law, does not describe them. The threshold is
    // the largest Kolmogorov-Smirnov distance of the fitted law over 200 samples that
    // *are* Gumbel (parameters estimated, so the textbook critical values do not apply).
    let (n, trials) = (2000, 200);
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let null_max = (0..trials)
        .map(|_| {
            let x = gumbel_sample(&mut rng, n, 50.0, 4.0);
            let g = Gumbel::fit_mle(&x).unwrap();
            ks_distance(&x, |v| g.cdf(v))
        })
        .fold(0.0, f64::max);
    let gumbel_std = 4.0 * std::f64::consts::PI / 6f64.sqrt();
    for seed in 0..5 {
        let mut rng = ChaCha8Rng::seed_from_u64(100 + seed);
        let y = normal_sample(&mut rng, n, 50.0 + 0.5772 * 4.0, gumbel_std);
        for fit in [Gumbel::fit_mle, Gumbel::fit_moments] {
            let g = fit(&y).unwrap();
            let d = ks_distance(&y, |v| g.cdf(v));
            assert!(
                d > null_max,
                "normal sample {seed}: KS {d} vs Gumbel null max {null_max}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------
// The [study] table
// ---------------------------------------------------------------------------------

const STUDY: &str = r#"
[study]
seed = 42
seeds = 4
duration = 600.0
transient = 100.0
sea_states = [
  { name = "operating", hs = 3.0, tp = 9.0, heading = 180.0, current_speed = 0.5, current_heading = 180.0 },
  { name = "survival, 100 yr", hs = 12.5, tp = 15.0, gamma = 3.3, heading = 180.0 },
  { hs = 8.0, tp = 12.0, heading = 135.0 },
]
channels = ["default", "ship.fx", "a.tension[2]"]
quantile = 0.9

[study.design]
mean_factor = 1.1
dynamic_factor = 1.5
capacities = { chain = 9.0e6 }
"#;

fn model() -> ModelChannels {
    ModelChannels {
        cables: vec![
            CableChannels {
                name: "a".into(),
                line_type: "chain".into(),
                elements: 4,
            },
            CableChannels {
                name: "b".into(),
                line_type: "rope".into(),
                elements: 4,
            },
        ],
        bodies: vec!["ship".into()],
        ..Default::default()
    }
}

fn error_of(text: &str) -> String {
    let p = Path::new("study.toml");
    match parse_study(text, p) {
        Err(e) => e.to_string(),
        Ok((def, _)) => StudyPlan::from_parts(def, "", p, &model())
            .map(|_| "no error".to_string())
            .unwrap_or_else(|e| e.to_string()),
    }
}

#[test]
fn a_study_table_is_read_with_its_defaults() {
    let (def, scenario) = parse_study(STUDY, Path::new("study.toml")).unwrap();
    assert_eq!(scenario, None);
    assert_eq!(def.seeds, [1, 2, 3, 4]);
    assert_eq!(def.sea_states.len(), 3);
    assert_eq!(def.sea_states[0].gamma, None);
    assert_eq!(def.sea_states[1].gamma, Some(3.3));
    assert_eq!(def.sea_states[2].current_speed, 0.0);
    let plan =
        StudyPlan::from_parts(def.clone(), "base", Path::new("study.toml"), &model()).unwrap();
    let names: Vec<String> = plan.channels.iter().map(|c| c.name()).collect();
    assert_eq!(
        names,
        [
            "a.tension_max",
            "b.tension_max",
            "a.start_force",
            "b.start_force",
            "a.end_force",
            "b.end_force",
            "ship.fx",
            "a.tension[2]"
        ]
    );
    assert_eq!(plan.members.len(), 12);
    for (i, m) in plan.members.iter().enumerate() {
        assert_eq!(m.index, i);
        assert_eq!((m.sea_state, m.seed), (i / 4, (i % 4) as u64 + 1));
    }
    // Wave seeds are all different, and a study with a seed added at the end keeps the
    // existing members' waves.
    let mut seeds: Vec<u64> = plan.members.iter().map(|m| m.wave_seed).collect();
    seeds.sort();
    seeds.dedup();
    assert_eq!(seeds.len(), 12);
    let more = STUDY.replace("seeds = 4", "seeds = 5");
    let (def5, _) = parse_study(&more, Path::new("study.toml")).unwrap();
    let plan5 = StudyPlan::from_parts(def5, "base", Path::new("study.toml"), &model()).unwrap();
    for m in &plan.members {
        let same = plan5
            .members
            .iter()
            .find(|n| (n.sea_state, n.seed) == (m.sea_state, m.seed))
            .unwrap();
        assert_eq!(same.wave_seed, m.wave_seed);
    }
    // The hash covers the definition and the base scenario, and nothing else.
    let again =
        StudyPlan::from_parts(def.clone(), "base", Path::new("elsewhere.toml"), &model()).unwrap();
    assert_eq!(again.hash, plan.hash);
    assert_ne!(plan5.hash, plan.hash);
    let other_base =
        StudyPlan::from_parts(def, "base ", Path::new("study.toml"), &model()).unwrap();
    assert_ne!(other_base.hash, plan.hash);
    let reformatted = STUDY
        .replace("quantile = 0.9\n", "")
        .replace("seed = 42", "seed = 42 # the study seed");
    let (def_r, _) = parse_study(&reformatted, Path::new("study.toml")).unwrap();
    let plan_r = StudyPlan::from_parts(def_r, "base", Path::new("study.toml"), &model()).unwrap();
    assert_eq!(plan_r.hash, plan.hash);
}

#[test]
fn bad_study_tables_are_errors_naming_the_file_and_field() {
    for (change, field, says) in [
        (
            ("seeds = 4", "seeds = 0"),
            "study.seeds",
            "at least one seed",
        ),
        (
            ("seeds = 4", "seeds = []"),
            "study.seeds",
            "at least one seed",
        ),
        (
            ("seeds = 4", "seeds = [3, 5, 3]"),
            "study.seeds[2]",
            "listed twice",
        ),
        (
            ("seeds = 4", "seeds = 2.5"),
            "study.seeds",
            "count of seeds",
        ),
        (
            ("transient = 100.0", "transient = 600.0"),
            "study.transient",
            "shorter than the duration",
        ),
        (
            ("transient = 100.0", "transient = -1.0"),
            "study.transient",
            "must not be negative",
        ),
        (("duration = 600.0\n", ""), "study.duration", "missing"),
        (
            ("\"ship.fx\"", "\"ship.fq\""),
            "study.channels[1]",
            "unknown quantity \"fq\"",
        ),
        (
            ("\"ship.fx\"", "\"boat.fx\""),
            "study.channels[1]",
            "no body named \"boat\"",
        ),
        (
            ("\"a.tension[2]\"", "\"c.tension[2]\""),
            "study.channels[2]",
            "no cable named \"c\"",
        ),
        (
            ("\"a.tension[2]\"", "\"a.tension[4]\""),
            "study.channels[2]",
            "has 4 elements",
        ),
        (
            ("hs = 8.0", "hs = 0.0"),
            "study.sea_states[2].hs",
            "must be positive",
        ),
        (
            ("hs = 8.0, tp = 12.0", "hs = 8.0"),
            "study.sea_states[2].tp",
            "missing",
        ),
        (
            ("gamma = 3.3", "gamma = 0.5"),
            "study.sea_states[1].gamma",
            "at least 1",
        ),
        (
            ("hs = 8.0,", "hs = 8.0, period = 3.0,"),
            "study.sea_states[2]",
            "unknown field `period`",
        ),
        (
            ("quantile = 0.9", "quantile = 1.0"),
            "study.quantile",
            "strictly between 0 and 1",
        ),
        (
            ("quantile = 0.9", "fit = \"lsq\""),
            "study.fit",
            "mle or moments",
        ),
        (
            ("chain = 9.0e6", "chains = 9.0e6"),
            "study.design.capacities.chains",
            "no cable of the base scenario has line type",
        ),
        (
            ("chain = 9.0e6", "chain = -1.0"),
            "study.design.capacities.chain",
            "must be positive",
        ),
        (
            ("dynamic_factor = 1.5\n", ""),
            "study.design.dynamic_factor",
            "missing",
        ),
        (
            ("seed = 42", "seed = 42\nseeds_per_state = 3"),
            "study",
            "unknown field `seeds_per_state`",
        ),
    ] {
        let text = STUDY.replace(change.0, change.1);
        assert_ne!(text, STUDY, "{change:?} changed nothing");
        let m = error_of(&text);
        assert!(
            m.starts_with(&format!("study.toml: {field}")),
            "{change:?}: expected field {field}, got: {m}"
        );
        assert!(
            m.contains(says),
            "{change:?}: expected \"{says}\", got: {m}"
        );
    }
    assert!(error_of("[simulation]\nduration = 1.0\n").contains("no [study] table"));
}

fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

#[test]
fn a_study_file_names_its_base_scenario_and_reads_sea_states_from_csv() {
    let dir = tempdir();
    let catenary = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/catenary.toml");
    std::fs::write(
        dir.path().join("states.csv"),
        "name,hs,tp,gamma,heading\n\"operating, light\",2.5,8.0,,90\nstorm,9.0,13.0,2.0,0\n",
    )
    .unwrap();
    let study = dir.path().join("study.toml");
    std::fs::write(
        &study,
        format!(
            "[study]\nscenario = {:?}\nseeds = [10, 20]\nduration = 100.0\ntransient = 20.0\n\
             sea_states_file = \"states.csv\"\nchannels = [\"line1.tension[*]\"]\n",
            catenary.display().to_string()
        ),
    )
    .unwrap();
    let file = StudyFile::load(&study).unwrap();
    assert_eq!(file.scenario_path, catenary);
    assert_eq!(file.def.seeds, [10, 20]);
    assert_eq!(
        file.def.sea_states[0].name.as_deref(),
        Some("operating, light")
    );
    assert_eq!(file.def.sea_states[0].gamma, None);
    assert_eq!(file.def.sea_states[0].heading, 90.0);
    assert_eq!(file.def.sea_states[1].gamma, Some(2.0));
    let scenario = Scenario::load(&file.scenario_path).unwrap();
    let plan = StudyPlan::new(&file, &ModelChannels::from_model(&scenario.model)).unwrap();
    // The catenary example's one line has 50 segments.
    assert_eq!(plan.channels.len(), 50);
    assert_eq!(plan.channels[49].name(), "line1.tension[49]");
    assert_eq!(plan.channels[0].line_type.as_deref(), Some("wire"));
    assert_eq!(plan.members.len(), 4);

    // A CSV error names the CSV file, the line and the column.
    std::fs::write(dir.path().join("states.csv"), "hs,tp\n2.5,8.0\n3.0,-1\n").unwrap();
    let m = StudyFile::load(&study).unwrap_err().to_string();
    assert!(
        m.contains("states.csv: line 3: tp: must be positive"),
        "{m}"
    );
    std::fs::write(dir.path().join("states.csv"), "hs,tp,dir\n2.5,8.0,0\n").unwrap();
    let m = StudyFile::load(&study).unwrap_err().to_string();
    assert!(
        m.contains("states.csv: column 3 (\"dir\"): unknown column"),
        "{m}"
    );
    // A study file that names a base scenario holds nothing else.
    let text = std::fs::read_to_string(&study).unwrap();
    std::fs::write(&study, format!("{text}\n[simulation]\nduration = 5.0\n")).unwrap();
    let m = StudyFile::load(&study).unwrap_err().to_string();
    assert!(
        m.contains("simulation: a study file that names its base scenario"),
        "{m}"
    );
}

// ---------------------------------------------------------------------------------
// Shards, merge and the output files
// ---------------------------------------------------------------------------------

/// A plan of 12 members and their synthetic results: each channel a random record
/// seeded by the member's wave seed (as a run would be), one member failed.
fn synthetic_study() -> (StudyPlan, Vec<MemberResult>) {
    let (def, _) = parse_study(STUDY, Path::new("study.toml")).unwrap();
    let plan = StudyPlan::from_parts(def, "base", Path::new("study.toml"), &model()).unwrap();
    let results = plan
        .members
        .iter()
        .map(|m| {
            let mut rng = ChaCha8Rng::seed_from_u64(m.wave_seed);
            let mut stats = plan.new_stats();
            for (c, s) in stats.iter_mut().enumerate() {
                let level = 1.0e6 * (1 + c + m.sea_state) as f64;
                for i in 0..3000 {
                    let t = i as f64 * 0.2;
                    let x = level * (1.0 + 0.1 * (0.7 * t).sin() + 0.05 * rng.gen::<f64>());
                    s.push(t, x);
                }
            }
            let status = if m.index == 5 {
                MemberStatus::Failed {
                    message: "simulation diverged at t = 312.5 s: cable 'a', node 3".into(),
                }
            } else {
                MemberStatus::Completed
            };
            MemberResult {
                member: *m,
                status,
                stats,
                fatigue: Vec::new(),
            }
        })
        .collect();
    (plan, results)
}

/// Runs the shards of `count` (members handed over in reverse, as threads might
/// finish), writes each shard file, reads them back in `order`, merges, and writes the
/// tables into `out`.
fn sharded_run(
    plan: &StudyPlan,
    results: &[MemberResult],
    count: usize,
    order: &[usize],
    out: &Path,
) {
    let shard_dir = out.join("shards");
    std::fs::create_dir_all(&shard_dir).unwrap();
    let mut files = Vec::new();
    for k in 1..=count {
        let spec = ShardSpec { index: k, count };
        let mine = plan.shard_members(spec, Path::new("--shard")).unwrap();
        let mut done: Vec<MemberResult> = mine.iter().map(|m| results[m.index].clone()).collect();
        done.reverse();
        let path = shard_dir.join(format!("shard_{k}.json"));
        plan.shard_result(spec, done).write(&path).unwrap();
        files.push(path);
    }
    let shards: Vec<(PathBuf, ShardResult)> = order
        .iter()
        .map(|&i| (files[i].clone(), ShardResult::read(&files[i]).unwrap()))
        .collect();
    let merged = merge(shards).unwrap();
    let summary = summarise(&merged);
    tables::write_all(out, &merged, &summary).unwrap();
}

#[test]
fn merged_shards_equal_the_one_machine_study_byte_for_byte() {
    let (plan, results) = synthetic_study();
    let base = tempdir();
    sharded_run(&plan, &results, 1, &[0], base.path());
    for (count, order) in [
        (2, vec![1, 0]),
        (3, vec![2, 0, 1]),
        (5, vec![3, 1, 4, 0, 2]),
        (12, (0..12).rev().collect()),
    ] {
        let dir = tempdir();
        sharded_run(&plan, &results, count, &order, dir.path());
        for f in ["members.csv", "study.csv", "study.json"] {
            let a = std::fs::read(base.path().join(f)).unwrap();
            let b = std::fs::read(dir.path().join(f)).unwrap();
            assert!(
                a == b,
                "{f} differs with {count} shards merged in order {order:?}"
            );
        }
    }
    // And the files hold what they should: 12 members x 8 channels, 3 x 8 summary
    // rows, the sea-state name with a comma quoted.
    let members = std::fs::read_to_string(base.path().join("members.csv")).unwrap();
    assert_eq!(members.lines().count(), 1 + 12 * 8);
    assert!(members.lines().next().unwrap().starts_with(
        "member,condition,sea_state,sea_state_name,seed,wave_seed,status,channel,unit,samples,max,time_of_max"
    ));
    let study = std::fs::read_to_string(base.path().join("study.csv")).unwrap();
    assert_eq!(study.lines().count(), 1 + 3 * 8);
    assert!(study.contains(",\"survival, 100 yr\","), "{study}");
    assert!(members.contains(",failed,"));
}

#[test]
fn the_summary_reduces_completed_members_in_member_order() {
    let (plan, results) = synthetic_study();
    let merged = merge(vec![(
        PathBuf::from("one.json"),
        plan.shard_result(ShardSpec::WHOLE, results.clone()),
    )])
    .unwrap();
    let s = summarise(&merged);
    assert_eq!((s.members, s.failed), (12, 1));
    // Sea state 1 holds member 5, which failed: three seeds remain.
    let ss = &s.sea_states[1];
    let c = &ss.channels[0]; // a.tension_max, line type chain: has a capacity
    assert_eq!((c.seeds, c.failed), (3, 1));
    let done: Vec<&MemberResult> = results[4..8]
        .iter()
        .filter(|m| m.status == MemberStatus::Completed)
        .collect();
    let maxima: Vec<f64> = done
        .iter()
        .map(|m| m.stats[0].max().unwrap().value)
        .collect();
    let fit = Gumbel::fit_mle(&maxima).unwrap();
    assert_eq!(c.gumbel_mle, Some(fit));
    assert_eq!(c.mpm, Some(fit.mu));
    assert_eq!(c.quantile, Some(fit.quantile(0.9)));
    assert_eq!(c.max_mean, Some(maxima.iter().sum::<f64>() / 3.0));
    // T_mean is the mean of the three records pooled (equal lengths: the mean of means).
    let mean = done.iter().map(|m| m.stats[0].mean().unwrap()).sum::<f64>() / 3.0;
    let d = c.design.unwrap();
    assert!((d.mean_tension - mean).abs() < 1e-9 * mean);
    let td = 1.1 * d.mean_tension + 1.5 * (fit.mu - d.mean_tension);
    assert!((d.design_tension - td).abs() < 1e-9 * td);
    assert_eq!(d.utilisation, d.design_tension / 9.0e6);
    // b's line type (rope) has no capacity, a body force never has one.
    assert!(ss.channels[1].design.is_none());
    assert!(ss.channels[6].design.is_none());
    // Every sea state has both fits and a quantile above the MPM.
    for ss in &s.sea_states {
        for c in &ss.channels {
            assert!(c.quantile.unwrap() > c.mpm.unwrap(), "{}", c.channel);
            assert!(c.gumbel_moments.is_some());
        }
    }
}

#[test]
fn merge_refuses_foreign_missing_repeated_and_incomplete_shards() {
    let (plan, results) = synthetic_study();
    let shard = |k: usize, n: usize| {
        let spec = ShardSpec { index: k, count: n };
        let mine = plan.shard_members(spec, Path::new("--shard")).unwrap();
        plan.shard_result(
            spec,
            mine.iter().map(|m| results[m.index].clone()).collect(),
        )
    };
    let p = |s: &str| PathBuf::from(s);
    let msg = |v: Vec<(PathBuf, ShardResult)>| merge(v).unwrap_err().to_string();

    // Another study: a different hash.
    let mut foreign = shard(2, 2);
    let other = STUDY.replace("seed = 42", "seed = 43");
    let (def, _) = parse_study(&other, Path::new("study.toml")).unwrap();
    foreign.study_hash = StudyPlan::from_parts(def, "base", Path::new("s"), &model())
        .unwrap()
        .hash;
    let m = msg(vec![(p("a/1.json"), shard(1, 2)), (p("b/2.json"), foreign)]);
    assert!(
        m.starts_with("b/2.json: study_hash: belongs to another study"),
        "{m}"
    );

    let m = msg(vec![(p("1.json"), shard(1, 3)), (p("3.json"), shard(3, 3))]);
    assert!(
        m.contains("shard: the merge needs all 3 shards") && m.contains("missing: 2/3"),
        "{m}"
    );

    let m = msg(vec![(p("1.json"), shard(1, 2)), (p("x.json"), shard(2, 3))]);
    assert!(
        m.starts_with("x.json: shard: is shard 2/3 of a 3-shard run"),
        "{m}"
    );

    let m = msg(vec![
        (p("1.json"), shard(1, 2)),
        (p("2.json"), shard(2, 2)),
        (p("2b.json"), shard(2, 2)),
    ]);
    assert!(
        m.starts_with("2b.json: shard: shard 2/2 is also given by 2.json"),
        "{m}"
    );

    let mut cut = shard(2, 2);
    cut.members.truncate(3);
    let m = msg(vec![(p("1.json"), shard(1, 2)), (p("2.json"), cut)]);
    assert!(
        m.starts_with("2.json: members: shard 2/2 is incomplete"),
        "{m}"
    );
    assert!(m.contains("members 9, 10, 11 are missing"), "{m}");

    assert!(msg(vec![]).contains("no shard file given"));

    // A shard file that is not one says so, with the file.
    let dir = tempdir();
    let bad = dir.path().join("shard.json");
    std::fs::write(&bad, "{\"format\": 1}").unwrap();
    let m = ShardResult::read(&bad).unwrap_err().to_string();
    assert!(m.contains("not a cablesim shard file"), "{m}");
}

#[test]
fn channel_stats_of_a_member_start_empty_with_the_study_transient() {
    let (plan, _) = synthetic_study();
    let stats = plan.new_stats();
    assert_eq!(stats.len(), plan.channels.len());
    assert!(stats.iter().all(|s| *s == ChannelStats::new(100.0)));
}
