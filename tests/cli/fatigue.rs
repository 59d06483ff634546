//! The fatigue limit state from the command line: `cablesim run` of a scenario with a
//! `[fatigue]` table writes `fatigue.csv`, whose every row recomputes from
//! `end_forces.csv` or `tensions.csv`; bad `[fatigue]` input is refused by key; a study
//! with a scatter diagram writes its `fatigue.csv`, the same from shards as from one
//! machine.

use cablesim::fatigue::{chain_area, cycles, TnCurve};
use cablesim::scenario::Scenario;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");
const EXAMPLE: &str = "examples/fatigue_spread_mooring.toml";

fn run_ok(args: &[&str]) {
    let out = Command::new(BIN)
        .env("RAYON_NUM_THREADS", "2")
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn read_csv(path: &Path) -> Vec<BTreeMap<String, String>> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let h = r.headers().unwrap().clone();
    r.records()
        .map(|rec| {
            let rec = rec.unwrap();
            h.iter()
                .zip(rec.iter())
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

fn num(row: &BTreeMap<String, String>, k: &str) -> f64 {
    row[k]
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {:?}", row[k]))
}

/// The fatigue example, cut to 100 s: every row of its `fatigue.csv` recomputed from
/// the run's own `end_forces.csv` (an end's force magnitude) or `tensions.csv` (an
/// element), the samples from the row's `transient` on, with the row's curve and area.
#[test]
fn a_run_writes_fatigue_csv_that_its_end_forces_recompute() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    run_ok(&[
        "run",
        EXAMPLE,
        "--duration",
        "100",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ]);
    let rows = read_csv(&out.join("fatigue.csv"));
    // Eight lines at both ends, and three elements of line 1.
    assert_eq!(rows.len(), 8 * 2 + 3);
    let mut series: BTreeMap<(String, String), Vec<(f64, f64)>> = BTreeMap::new();
    for r in read_csv(&out.join("end_forces.csv")) {
        let (fx, fy, fz) = (num(&r, "fx"), num(&r, "fy"), num(&r, "fz"));
        series
            .entry((r["cable"].clone(), r["end"].clone()))
            .or_default()
            .push((num(&r, "time"), (fx * fx + fy * fy + fz * fz).sqrt()));
    }
    for r in read_csv(&out.join("tensions.csv")) {
        series
            .entry((r["cable"].clone(), r["element"].clone()))
            .or_default()
            .push((num(&r, "time"), num(&r, "tension")));
    }
    let chain = TnCurve::named("studless_chain").unwrap();
    for row in &rows {
        let key = (row["cable"].clone(), row["location"].clone());
        let (a_d, m, area) = (num(row, "a_d"), num(row, "m"), num(row, "area_m2"));
        assert_eq!(
            (row["curve"].as_str(), a_d, m),
            ("studless_chain", chain.a_d, chain.m)
        );
        assert_eq!(area, chain_area(0.076), "{key:?}");
        let t0 = num(row, "transient");
        assert_eq!(t0, 60.0);
        let s: Vec<(f64, f64)> = series[&key].iter().copied().filter(|x| x.0 >= t0).collect();
        let values: Vec<f64> = s.iter().map(|x| x.1).collect();
        let c = cycles(&values);
        let n: f64 = c.iter().map(|c| c.count).sum();
        let d: f64 = c
            .iter()
            .map(|c| c.count * (c.range / area / 1.0e6).powf(m) / a_d)
            .sum();
        assert_eq!(num(row, "cycles"), n, "{key:?}");
        let got = num(row, "damage");
        assert!(
            got > 0.0 && (got - d).abs() <= 1e-12 * d,
            "{key:?}: {got} vs {d}"
        );
        assert_eq!(num(row, "duration"), s.last().unwrap().0 - s[0].0);
    }
    // The fairlead (end) of a line sees more damage than its anchor (start).
    let damage = |c: &str, l: &str| {
        num(
            rows.iter()
                .find(|r| r["cable"] == c && r["location"] == l)
                .unwrap(),
            "damage",
        )
    };
    assert!(damage("line1", "end") > damage("line1", "start"));
}

/// Bad `[fatigue]` input is refused with the key named.
#[test]
fn bad_fatigue_input_is_refused_by_key() {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    let path = Path::new(EXAMPLE);
    let cases: [(&str, &str, &str); 7] = [
        (
            "curve = \"studless_chain\"\nbar_diameter = 0.076",
            "a_d = -6.0e10\nm = 3.0\narea_m2 = 0.009",
            "fatigue.line_types.chain76.a_d: must be positive",
        ),
        (
            "curve = \"studless_chain\"\nbar_diameter = 0.076",
            "a_d = 6.0e10\nm = 0.0\narea_m2 = 0.009",
            "fatigue.line_types.chain76.m: must be positive",
        ),
        (
            "curve = \"studless_chain\"\nbar_diameter = 0.076",
            "curve = \"studless_chain\"\narea_m2 = -1.0",
            "fatigue.line_types.chain76.area_m2: must be positive",
        ),
        (
            "curve = \"studless_chain\"\nbar_diameter = 0.076",
            "curve = \"studless\"\nbar_diameter = 0.076",
            "fatigue.line_types.chain76.curve: unknown curve \"studless\"",
        ),
        (
            "curve = \"studless_chain\"\nbar_diameter = 0.076",
            "curve = \"spiral_rope\"\nbar_diameter = 0.076",
            "fatigue.line_types.chain76.bar_diameter: a bar diameter gives the nominal area of a chain",
        ),
        (
            "locations = [\"start\", \"end\", 10, 20, 30]",
            "locations = [\"start\", \"end\", 10, 40, 30]",
            "fatigue.cables.line1.locations[3]: element 40 is off cable \"line1\", whose elements are 0 to 39",
        ),
        (
            "[fatigue.cables.line1]",
            "[fatigue.cables.line9]",
            "fatigue.cables.line9: no cable is named \"line9\"",
        ),
    ];
    for (from, to, says) in cases {
        assert!(text.contains(from), "{from}");
        let e = Scenario::parse(&text.replace(from, to), path)
            .unwrap_err()
            .to_string();
        assert!(e.contains(says), "{to}: {e}");
    }
    // A fatigue location given as something else.
    let e = Scenario::parse(
        &text.replace(
            "locations = [\"start\", \"end\", 10, 20, 30]",
            "locations = [\"middle\"]",
        ),
        path,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("fatigue.cables.line1.locations[0]: a location is"),
        "{e}"
    );
}

/// The example study of three wire lines, with a `[fatigue]` table (spiral rope), a
/// scatter diagram of three sea states by probability and a fourth (extreme) sea state
/// outside it, two seeds each; written into `dir`.
fn fatigue_study(dir: &Path) -> std::path::PathBuf {
    let text = std::fs::read_to_string("examples/study_spread_mooring.toml").unwrap();
    let start = text.find("sea_states = [").unwrap();
    let end = start + text[start..].find("]\n").unwrap() + 2;
    let rows = r#"sea_states = [
  { name = "calm", hs = 1.0, tp = 7.0, probability = 0.6 },
  { name = "operating", hs = 2.0, tp = 8.0, heading = 0.0, current_speed = 0.3, probability = 0.3 },
  { name = "rough", hs = 3.5, tp = 9.5, heading = 20.0, probability = 0.1 },
  { name = "storm", hs = 5.0, tp = 11.0, gamma = 3.3, heading = 30.0, current_speed = 0.8, current_heading = 15.0 },
]
"#;
    let mut t = format!("{}{}{}", &text[..start], rows, &text[end..]);
    t = t.replace("seeds = 3\n", "seeds = 2\n");
    assert!(t.contains("seeds = 2\n"));
    t.push_str(
        r#"
[study.fatigue]
design_fatigue_factor = 5.0

[fatigue]
[fatigue.line_types.wire]
curve = "spiral_rope"
area_m2 = 0.00098
"#,
    );
    let p = dir.join("fatigue_study.toml");
    std::fs::write(&p, t).unwrap();
    p
}

/// A study with a scatter diagram: its `fatigue.csv` holds per location and sea state
/// the seeds' mean damage, scaled to the sea state's hours, their sum and the life; the
/// members' records give it back; two shards merged, and members packed into runs,
/// give the one machine's files byte for byte.
#[test]
fn a_study_scatter_diagram_gives_annual_damage_and_life_the_same_from_shards() {
    let tmp = tempfile::tempdir().unwrap();
    let study = fatigue_study(tmp.path());
    let s = study.to_str().unwrap();
    let one = tmp.path().join("one");
    run_ok(&["study", "run", s, "-q", "--out", one.to_str().unwrap()]);
    let (s1, s2, merged) = (
        tmp.path().join("s1"),
        tmp.path().join("s2"),
        tmp.path().join("m"),
    );
    run_ok(&[
        "study",
        "run",
        s,
        "-q",
        "--shard",
        "1/2",
        "--out",
        s1.to_str().unwrap(),
    ]);
    run_ok(&[
        "study",
        "run",
        s,
        "-q",
        "--shard",
        "2/2",
        "--out",
        s2.to_str().unwrap(),
    ]);
    run_ok(&[
        "study",
        "merge",
        s2.to_str().unwrap(),
        s1.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    // Packed (`--backend auto`: on the CPU here, members packed three to a run), each
    // member steps as alone: the same files.
    let packed = tmp.path().join("packed");
    run_ok(&[
        "study",
        "run",
        s,
        "-q",
        "--backend",
        "auto",
        "--batch",
        "3",
        "--out",
        packed.to_str().unwrap(),
    ]);
    for f in ["fatigue.csv", "study.csv", "members.csv", "study.json"] {
        let a = std::fs::read(one.join(f)).unwrap();
        for (other, what) in [(&merged, "the merged shards"), (&packed, "a packed run")] {
            let b = std::fs::read(other.join(f)).unwrap();
            assert!(a == b, "{f} differs between one machine and {what}");
        }
    }
    let rows = read_csv(&one.join("fatigue.csv"));
    assert_eq!(rows.len(), 3 * 2 * 4, "3 lines x 2 ends x 4 sea states");
    // The members' own records (members/NNNNNN.json), by member.
    let mut records: BTreeMap<usize, serde_json::Value> = BTreeMap::new();
    for e in std::fs::read_dir(one.join("members")).unwrap() {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(e.unwrap().path()).unwrap()).unwrap();
        let index = v["result"]["member"]["index"].as_u64().unwrap() as usize;
        records.insert(index, v["result"].clone());
    }
    assert_eq!(records.len(), 8);
    let probability = [Some(0.6), Some(0.3), Some(0.1), None];
    let mut by_location: BTreeMap<(String, String), f64> = BTreeMap::new();
    for (i, row) in rows.iter().enumerate() {
        let loc_index = i / 4; // the study's location order: cables, then start, end
        let ss: usize = row["sea_state"].parse().unwrap();
        assert_eq!(ss, i % 4);
        assert_eq!((num(row, "a_d"), num(row, "m")), (1.7e17, 4.8));
        // The mean of the two seeds' records.
        let recs: Vec<&serde_json::Value> = records
            .values()
            .filter(|v| v["member"]["sea_state"].as_u64() == Some(ss as u64))
            .map(|v| &v["fatigue"][loc_index])
            .collect();
        assert_eq!(recs.len(), 2);
        let mean = |k: &str| recs.iter().map(|r| r[k].as_f64().unwrap()).sum::<f64>() / 2.0;
        assert_eq!(num(row, "damage"), mean("damage"));
        assert_eq!(num(row, "duration"), mean("duration"));
        assert!(num(row, "damage") > 0.0);
        match probability[ss] {
            Some(p) => {
                let hours = p * 8766.0;
                assert_eq!(num(row, "hours"), hours);
                let a = num(row, "sea_state_annual_damage");
                assert!(
                    (a - mean("damage") * hours * 3600.0 / mean("duration")).abs() <= 1e-12 * a
                );
                *by_location
                    .entry((row["cable"].clone(), row["location"].clone()))
                    .or_default() += a;
            }
            None => assert!(row["hours"].is_empty() && row["sea_state_annual_damage"].is_empty()),
        }
    }
    for row in &rows {
        let total = by_location[&(row["cable"].clone(), row["location"].clone())];
        let annual = num(row, "annual_damage");
        assert!((annual - total).abs() <= 1e-12 * total);
        assert_eq!(num(row, "design_fatigue_factor"), 5.0);
        assert_eq!(num(row, "life"), 1.0 / (5.0 * annual));
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(one.join("study.json")).unwrap()).unwrap();
    assert_eq!(json["fatigue"].as_array().unwrap().len(), 6);
}

/// Scatter diagrams that do not add up, and a study asking for fatigue of a base
/// scenario without curves, are refused by key.
#[test]
fn bad_scatter_diagrams_are_refused_by_key() {
    use cablesim::study::definition::parse_study;
    let tmp = tempfile::tempdir().unwrap();
    let study = fatigue_study(tmp.path());
    let text = std::fs::read_to_string(&study).unwrap();
    for (from, to, says) in [
        (
            "probability = 0.1 }",
            "probability = 0.05 }",
            "study.sea_states: probability: the probabilities of the 3 fatigue sea states sum to 0.95",
        ),
        (
            "probability = 0.1 }",
            "hours = 876.6 }",
            "study.sea_states: hours: the scatter diagram mixes probabilities and hours",
        ),
        (
            "probability = 0.6 }",
            "probability = 1.6 }",
            "study.sea_states[0].probability: a probability is at most 1",
        ),
        (
            "design_fatigue_factor = 5.0",
            "design_fatigue_factor = 0.0",
            "study.fatigue.design_fatigue_factor: must be positive",
        ),
        ("[study.fatigue]\ndesign_fatigue_factor = 5.0\n", "", "study.fatigue: missing"),
    ] {
        assert!(text.contains(from), "{from}");
        let e = parse_study(&text.replace(from, to), &study).unwrap_err().to_string();
        assert!(e.contains(says), "{to}: {e}");
    }
    // Hours that do not sum to the year.
    let hours = text
        .replace("probability = 0.6", "hours = 5000.0")
        .replace("probability = 0.3", "hours = 2000.0")
        .replace("probability = 0.1", "hours = 1000.0");
    let e = parse_study(&hours, &study).unwrap_err().to_string();
    assert!(
        e.contains("study.sea_states: hours: the hours of the 3 fatigue sea states sum to 8000, not study.fatigue.hours_per_year = 8766"),
        "{e}"
    );
    let fine = hours.replace(
        "design_fatigue_factor = 5.0",
        "design_fatigue_factor = 5.0\nhours_per_year = 8000.0",
    );
    parse_study(&fine, &study).unwrap();
    // No [fatigue] in the base scenario.
    let cut = text.find("[fatigue]").unwrap();
    std::fs::write(&study, &text[..cut]).unwrap();
    let f = cablesim::study::StudyFile::load(&study).unwrap();
    let e = cablesim::study::StudyRunner::new(&f)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("study.fatigue: the base scenario has no [fatigue] table"),
        "{e}"
    );
}
