//! `src/fatigue/`: rainflow counting (ASTM E1049-85), T-N curves, Miner's damage and
//! the narrow-band closed form.

use cablesim::fatigue::{
    chain_area, curves::gamma, cycles, narrow_band_damage, Cycle, DamageCounter, FatigueLocation,
    Location, TnCurve,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;

/// Cycle counts by range (ranges of the example are integers).
fn histogram(c: &[Cycle]) -> BTreeMap<i64, f64> {
    let mut h = BTreeMap::new();
    for x in c {
        *h.entry(x.range.round() as i64).or_insert(0.0) += x.count;
    }
    h
}

/// ASTM E1049-85 (reapproved 2017), 5.4.4 and its Fig. 6 / Table 4: the load history
/// -2, 1, -3, 5, -1, 3, -4, 4, -2 counts 0.5 cycle of range 3, 1.5 of range 4, 0.5 of
/// range 6, 1.0 of range 8 and 0.5 of range 9 (none of 5, 7 or 10).
#[test]
fn astm_e1049_worked_example() {
    let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
    let c = cycles(&history);
    let expected: BTreeMap<i64, f64> = [(3, 0.5), (4, 1.5), (6, 0.5), (8, 1.0), (9, 0.5)]
        .into_iter()
        .collect();
    assert_eq!(histogram(&c), expected);
    // The standard's order of counting: B-C (half, 3), C-D... as it steps through.
    let seq: Vec<(f64, f64)> = c.iter().map(|x| (x.range, x.count)).collect();
    assert_eq!(
        seq,
        vec![
            (3.0, 0.5),
            (4.0, 0.5),
            (4.0, 1.0),
            (8.0, 0.5),
            (9.0, 0.5),
            (8.0, 0.5),
            (6.0, 0.5)
        ]
    );
    // The same history sampled finely (points between the reversals, plateaus) counts
    // the same: only reversals matter.
    let mut fine = Vec::new();
    for w in history.windows(2) {
        for k in 0..5 {
            fine.push(w[0] + (w[1] - w[0]) * k as f64 / 5.0);
        }
        fine.push(w[1]);
    }
    fine.push(-2.0);
    assert_eq!(histogram(&cycles(&fine)), expected);
}

/// Every range between successive reversals is counted exactly once: twice the summed
/// counts is the number of reversals less one, and no range exceeds the record's span.
#[test]
fn counts_cover_every_range_once() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for n in [3usize, 10, 100, 5000] {
        let x: Vec<f64> = (0..n).map(|_| rng.gen_range(-1.0..1.0)).collect();
        // Reversals of a random sequence without ties: the ends and every turn.
        let turns = x
            .windows(3)
            .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
            .count();
        let reversals = turns + 2;
        let c = cycles(&x);
        let total: f64 = c.iter().map(|c| 2.0 * c.count).sum();
        assert_eq!(total, (reversals - 1) as f64, "n = {n}");
        let span =
            x.iter().cloned().fold(f64::MIN, f64::max) - x.iter().cloned().fold(f64::MAX, f64::min);
        assert!(c.iter().all(|c| c.range <= span && c.range >= 0.0));
        // The largest range of the record is always counted (as a half cycle at least).
        let largest = c.iter().map(|c| c.range).fold(0.0, f64::max);
        assert_eq!(largest, span, "n = {n}");
    }
}

#[test]
fn curves_and_areas() {
    let c = TnCurve::named("studless_chain").unwrap();
    assert_eq!((c.a_d, c.m), (6.0e10, 3.0));
    assert_eq!(TnCurve::named("stud_chain").unwrap().a_d, 1.2e11);
    assert_eq!(TnCurve::named("multi_strand_rope").unwrap().m, 4.0);
    assert_eq!(TnCurve::named("spiral_rope").unwrap().a_d, 1.7e17);
    assert!(TnCurve::named("polyester").is_none());
    // 76 mm chain: two bars of 76 mm, 9073 mm^2.
    let a = chain_area(0.076);
    assert!((a - 2.0 * std::f64::consts::PI * 0.038 * 0.038).abs() < 1e-15);
    // One cycle of 1 MN on it: s = 110.2 MPa, n = 6e10 / s^3 cycles.
    let s = 1.0e6 / a / 1.0e6;
    let d = c.damage(1.0e6, a, 1.0);
    assert!((d - 1.0 / c.cycles_to_failure(s)).abs() < 1e-15 * d.max(1e-300) + 1e-20);
    assert!((d * 6.0e10 - s.powi(3)).abs() < 1e-9 * s.powi(3));
}

#[test]
fn gamma_function() {
    for (x, g) in [
        (1.0, 1.0),
        (2.0, 1.0),
        (5.0, 24.0),
        (0.5, std::f64::consts::PI.sqrt()),
        (2.5, 1.329_340_388_179_137),
        (3.4, 2.981_206_426_810_332),
        (0.3, 2.991_568_987_687_591),
    ] {
        assert!(
            (gamma(x) - g).abs() < 1e-12 * g,
            "gamma({x}) = {} not {g}",
            gamma(x)
        );
    }
}

/// A counter's damage is the sum of its cycles' damages, and samples before the
/// transient are not counted.
#[test]
fn damage_counter_sums_its_cycles() {
    let loc = FatigueLocation {
        cable: "a".into(),
        cable_index: 0,
        location: Location::End,
        line_type: "chain".into(),
        curve: TnCurve::named("studless_chain").unwrap(),
        area_m2: chain_area(0.1),
    };
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let x: Vec<f64> = (0..2000)
        .map(|_| 1.0e6 + rng.gen_range(-3.0e5..3.0e5))
        .collect();
    let mut c = DamageCounter::new(&loc, 10.0);
    for (i, v) in x.iter().enumerate() {
        c.push(i as f64 * 0.1, *v);
    }
    let r = c.finish();
    let counted = &x[100..];
    let expect: f64 = cycles(counted)
        .iter()
        .map(|c| loc.curve.damage(c.range, loc.area_m2, c.count))
        .sum();
    let n: f64 = cycles(counted).iter().map(|c| c.count).sum();
    assert_eq!(r.cycles, n);
    assert!((r.damage - expect).abs() <= 1e-12 * expect);
    assert!((r.duration - 1999.0 * 0.1 + 10.0).abs() < 1e-9);
}

/// A narrow-band Gaussian stress record against the closed form
/// `D = (nu0 T / a_D) (2 sqrt(2) sigma)^m Gamma(1 + m/2)` (ranges twice Rayleigh
/// amplitudes): within 5 %. The record: 300 sinusoids of equal amplitude, random
/// frequencies uniform in 0.09 to 0.11 Hz (a band of 20 % about 0.1 Hz) and random
/// phases, sigma = 10 MPa about a mean of 100 MPa, 600,000 s (about 60,000 cycles)
/// sampled 32 times a period.
#[test]
fn narrow_band_damage_matches_the_closed_form() {
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    let n = 300;
    let sigma = 10.0;
    let amp = (2.0 * sigma * sigma / n as f64).sqrt();
    let comps: Vec<(f64, f64)> = (0..n)
        .map(|_| {
            (
                rng.gen_range(0.09..0.11),
                rng.gen_range(0.0..std::f64::consts::TAU),
            )
        })
        .collect();
    // Spectral moments of the line spectrum: nu0 = sqrt(m2 / m0), and the bandwidth
    // parameter epsilon = sqrt(1 - m2^2 / (m0 m4)).
    let m0 = n as f64 * amp * amp / 2.0;
    let m2: f64 = comps.iter().map(|(f, _)| amp * amp / 2.0 * f * f).sum();
    let m4: f64 = comps.iter().map(|(f, _)| amp * amp / 2.0 * f.powi(4)).sum();
    let nu0 = (m2 / m0).sqrt();
    let eps = (1.0 - m2 * m2 / (m0 * m4)).sqrt();
    assert!(eps < 0.12, "bandwidth parameter {eps}");
    let dt = 1.0 / (32.0 * 0.1);
    let t_end = 600_000.0;
    let steps = (t_end / dt) as usize;
    // Each component as a phasor rotated by its step (no sine per sample).
    let mut z: Vec<(f64, f64)> = comps.iter().map(|(_, p)| (p.cos(), p.sin())).collect();
    let rot: Vec<(f64, f64)> = comps
        .iter()
        .map(|(f, _)| {
            let w = std::f64::consts::TAU * f * dt;
            (w.cos(), w.sin())
        })
        .collect();
    let area = 1.0e-6; // s = range (MPa) with a tension "range" in N
    let curves = [
        TnCurve {
            name: None,
            a_d: 6.0e10,
            m: 3.0,
        },
        TnCurve {
            name: None,
            a_d: 3.4e14,
            m: 4.0,
        },
    ];
    let mut counters: Vec<DamageCounter> = curves
        .iter()
        .map(|curve| {
            let loc = FatigueLocation {
                cable: "x".into(),
                cable_index: 0,
                location: Location::Start,
                line_type: "x".into(),
                curve: curve.clone(),
                area_m2: area,
            };
            DamageCounter::new(&loc, 0.0)
        })
        .collect();
    for k in 0..=steps {
        let x: f64 = 100.0 + amp * z.iter().map(|c| c.0).sum::<f64>();
        for c in &mut counters {
            c.push(k as f64 * dt, x);
        }
        for (c, r) in z.iter_mut().zip(&rot) {
            *c = (c.0 * r.0 - c.1 * r.1, c.0 * r.1 + c.1 * r.0);
        }
    }
    for (curve, counter) in curves.iter().zip(counters) {
        let r = counter.finish();
        let closed = narrow_band_damage(curve, nu0, r.duration, sigma);
        let ratio = r.damage / closed;
        eprintln!(
            "m = {}: rainflow damage {:.6e}, closed form {closed:.6e}, ratio {ratio:.4}; \
             nu0 {nu0:.5} Hz, epsilon {eps:.4}, {} cycles",
            curve.m, r.damage, r.cycles
        );
        assert!(
            (ratio - 1.0).abs() < 0.05,
            "m = {}: rainflow {} against closed form {closed} (ratio {ratio})",
            curve.m,
            r.damage
        );
        // Cycles: about nu0 T.
        assert!(
            (r.cycles / (nu0 * r.duration) - 1.0).abs() < 0.03,
            "{}",
            r.cycles
        );
    }
}

/// Against an independent implementation: the `rainflow` Python package (3.2.0, ASTM
/// E1049-85) counted the tension records of a run of `examples/fatigue_spread_mooring.toml`
/// (`--duration 1200`: line 1's two ends and its element 20, from t = 60 s; `scripts/rainflow_reference.py`
/// wrote both files). cablesim's counting gives the same cycles in the same order: the
/// same ranges, means and counts, to the bit.
#[test]
fn counts_as_the_rainflow_python_package_on_a_runs_tension_records() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/fatigue");
    let mut records: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let mut r = csv::Reader::from_path(dir.join("record.csv")).unwrap();
    for rec in r.records() {
        let rec = rec.unwrap();
        records
            .entry(rec[0].to_string())
            .or_default()
            .push(rec[2].parse().unwrap());
    }
    let text = std::fs::read_to_string(dir.join("cycles.csv")).unwrap();
    assert!(text.starts_with("# rainflow 3.2.0"));
    let body: String = text.lines().skip(1).map(|l| format!("{l}\n")).collect();
    let mut theirs: BTreeMap<String, Vec<Cycle>> = BTreeMap::new();
    for rec in csv::Reader::from_reader(body.as_bytes()).records() {
        let rec = rec.unwrap();
        theirs.entry(rec[0].to_string()).or_default().push(Cycle {
            range: rec[1].parse().unwrap(),
            mean: rec[2].parse().unwrap(),
            count: rec[3].parse().unwrap(),
        });
    }
    assert_eq!(records.len(), 3);
    for (loc, values) in &records {
        assert!(values.len() > 2000, "{loc}: {} samples", values.len());
        let mine = cycles(values);
        let theirs = &theirs[loc];
        assert!(theirs.len() > 100, "{loc}: {} cycles", theirs.len());
        assert_eq!(mine.len(), theirs.len(), "{loc}");
        for (i, (a, b)) in mine.iter().zip(theirs).enumerate() {
            assert_eq!(a, b, "{loc}: cycle {i}");
        }
    }
}
