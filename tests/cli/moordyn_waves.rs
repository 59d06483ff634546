//! MoorDyn files with waves: `WaveKin` 7 (`wave_frequencies.txt`) and 3
//! (`wave_elevation.txt`) converted to a `"components"` train whose elevation is
//! MoorDyn's, run as they are, and bad wave files refused naming the file's line.

use cablesim::moordyn::{convert_text, ConvertOptions};
use cablesim::scenario::Scenario;
use cablesim::sea::kinematics::WaveField;
use std::f64::consts::TAU;
use std::path::Path;

/// A chain from an anchor 60 m down to a vessel fairlead 5 m under the surface.
const LINE: &str = "\
--------------------- MoorDyn Input File ------------------------------------
A chain in waves, written for cablesim's tests
---------------------- LINE TYPES -------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI    Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2) (-)  (-)    (-)     (-)
chain      0.1     100.0      1.0e9      -0.8        0     2.4    1.0    1.15    0.0
---------------------- POINTS -----------------------------------------------
ID  Attachment  X       Y      Z       Mass   Volume  CdA    Ca
(#) (-)         (m)     (m)    (m)     (kg)   (m^3)   (m^2)  (-)
1   Fixed       -250    0      -60     0      0       0      0
2   Vessel      0       0      -5      0      0       0      0
---------------------- LINES ------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#) (name)    (ID)     (ID)     (m)       (-)      (-)
1   chain     1        2        270       20       pt
---------------------- OPTIONS ----------------------------------------------
0.001   dtM       time step (s)
60      WtrDpth   water depth (m)
0.5     dtOut
7       WaveKin
------------------------- need this line ------------------------------------
";

/// MoorDyn's component file: `omega re im [beta]` (rad/s, m, m, rad), the first row
/// at 0 rad/s.
const FREQUENCIES: &str = "\
0.0 0.0 0.0
0.5 0.8 0.3
0.62 -0.2 0.5 0.3
0.9 0.1 -0.05 -0.4   # a comment, as MoorDyn allows
";

/// MoorDyn's elevation at `(x, y)` and `t` from its component file
/// (`SpectrumKin::getWaveKin`): `sum |a| sin(w t - k (x cos b + y sin b) + arg a)`.
fn moordyn_elevation(rows: &[[f64; 4]], depth: f64, x: f64, y: f64, t: f64) -> f64 {
    rows.iter()
        .map(|&[w, re, im, b]| {
            let k = cablesim::sea::dispersion::wave_number(w, depth, 9.80665);
            re.hypot(im) * (w * t - k * (x * b.cos() + y * b.sin()) + im.atan2(re)).sin()
        })
        .sum()
}

/// `text` with `from` replaced by `to`.
fn with(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

/// A folder holding `model.dat` (`text`) and the `files`.
fn folder(text: &str, files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("model.dat"), text).unwrap();
    for (name, body) in files {
        std::fs::write(dir.path().join(name), body).unwrap();
    }
    dir
}

/// Converts `model.dat` of `dir`: the TOML, the scenario it makes, the warnings.
fn convert(dir: &Path) -> (String, Scenario, Vec<cablesim::moordyn::Warning>) {
    let dat = dir.join("model.dat");
    let text = std::fs::read_to_string(&dat).unwrap();
    let c = convert_text(&text, &dat, &ConvertOptions::default()).unwrap();
    let sc = Scenario::parse(&c.toml, &dat).unwrap();
    (c.toml, sc, c.warnings)
}

fn error(dir: &Path) -> String {
    let dat = dir.join("model.dat");
    let text = std::fs::read_to_string(&dat).unwrap();
    convert_text(&text, &dat, &ConvertOptions::default())
        .expect_err("should be refused")
        .to_string()
}

#[test]
fn wavekin_7_components_give_moordyns_elevation() {
    let dir = folder(LINE, &[("wave_frequencies.txt", FREQUENCIES)]);
    let (toml, sc, _) = convert(dir.path());
    assert!(toml.contains("type = \"components\""), "{toml}");
    assert!(toml.contains("WaveKin = 7 (line"), "{toml}");
    // The row at 0 rad/s is left out.
    assert_eq!(sc.sea.components.len(), 3);
    let rows: Vec<[f64; 4]> = vec![
        [0.5, 0.8, 0.3, 0.0],
        [0.62, -0.2, 0.5, 0.3],
        [0.9, 0.1, -0.05, -0.4],
    ];
    let field = WaveField::new(&sc.sea);
    for (x, y) in [(0.0, 0.0), (-120.0, 35.0), (40.0, -80.0)] {
        for t in [0.0, 1.7, 13.0, 59.5] {
            let md = moordyn_elevation(&rows, 60.0, x, y, t);
            let ours = field.elevation(x, y, t);
            assert!(
                (md - ours).abs() < 1e-12,
                "({x}, {y}) at {t} s: {ours} against MoorDyn's {md}"
            );
        }
    }
}

#[test]
fn a_wavekin_7_file_runs_and_its_waves_move_the_line() {
    let exe = env!("CARGO_BIN_EXE_cablesim");
    let fairlead_tension = |text: &str| -> Vec<f64> {
        let dir = folder(text, &[("wave_frequencies.txt", FREQUENCIES)]);
        let out = dir.path().join("out");
        let r = std::process::Command::new(exe)
            .args(["run", "-q"])
            .arg(dir.path().join("model.dat"))
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        assert!(out.join("summary.json").exists());
        // The last element's tension at each output time.
        let csv = std::fs::read_to_string(out.join("tensions.csv")).unwrap();
        csv.lines()
            .skip(1)
            .filter(|l| l.split(',').nth(2) == Some("19"))
            .map(|l| l.split(',').nth(3).unwrap().parse().unwrap())
            .collect()
    };
    let waves = fairlead_tension(LINE);
    let still = fairlead_tension(&with(LINE, "7       WaveKin", "0       WaveKin"));
    assert_eq!(waves.len(), still.len());
    assert!(waves.len() > 100);
    let range = |v: &[f64]| {
        v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
    };
    println!(
        "fairlead tension range: {:.1} N in waves, {:.1} N in still water",
        range(&waves),
        range(&still)
    );
    assert!(range(&waves) > 10.0 * range(&still).max(1.0));
}

#[test]
fn wavekin_3_record_becomes_moordyns_components() {
    // Samples every 0.125 s up to 32 s; MoorDyn resamples every dtWave = 0.25 s from 0
    // (129 samples, the last dropped: 128, a period of 32 s) and keeps the FFT's bins
    // up to pi rad/s (16 of 64). The record: two waves on bins 3 and 7, one on bin 20
    // (0.625 Hz, cut) and a mean of 0.1 m (left out, with a warning).
    let wave =
        |t: f64| 0.8 * (TAU * 3.0 * t / 32.0 + 0.2).cos() + 0.3 * (TAU * 7.0 * t / 32.0).sin();
    let mut record = String::new();
    for i in 0..=256 {
        let t = 0.125 * i as f64;
        record += &format!(
            "{t} {}\n",
            0.1 + wave(t) + 0.05 * (TAU * 20.0 * t / 32.0).cos()
        );
    }
    let text = with(LINE, "7       WaveKin", "3       WaveKin\n0.25    dtWave");
    let dir = folder(&text, &[("wave_elevation.txt", &record)]);
    let (toml, sc, warnings) = convert(dir.path());
    assert!(toml.contains("WaveKin = 3 (line"), "{toml}");
    assert!(toml.contains("128 samples every 0.25 s"), "{toml}");
    assert_eq!(sc.sea.components.len(), 16);
    assert!(sc
        .sea
        .components
        .iter()
        .all(|c| c.omega <= std::f64::consts::PI));
    assert!(
        warnings
            .iter()
            .any(|w| w.message.contains("mean") && w.message.contains("z = 0")),
        "{warnings:?}"
    );
    let field = WaveField::new(&sc.sea);
    for i in 0..200 {
        let t = 0.37 * i as f64;
        let got = field.elevation(0.0, 0.0, t);
        assert!(
            (got - wave(t)).abs() < 1e-12,
            "t = {t}: {got} against {}",
            wave(t)
        );
    }
    // Along +x, as MoorDyn's record waves travel.
    assert!(sc.sea.components.iter().all(|c| c.direction == 0.0));
    // Without dtWave, MoorDyn's default 0.25 s.
    let dir = folder(
        &with(LINE, "7       WaveKin", "3       WaveKin"),
        &[("wave_elevation.txt", &record)],
    );
    let (toml, _, _) = convert(dir.path());
    assert!(toml.contains("dtWave, MoorDyn's default"), "{toml}");
}

#[test]
fn bad_moordyn_wave_files_are_refused_naming_the_line() {
    let line_of =
        |needle: &str, text: &str| text.lines().position(|l| l.contains(needle)).unwrap() + 1;
    // Each case: the file's text, the line and what the error says.
    for (body, line, says) in [
        ("0.1 0.0 0.0\n0.5 1.0 0.0\n", 1, "first row at 0 rad/s"),
        ("0.0 0.0 0.0\n0.5 abc 0.0\n", 2, "real part"),
        ("0.0 0.0 0.0\n0.5 1.0\n", 2, "needs 3 values"),
        ("0.0 0.0 0.0\n0.5 nan 0.0\n", 2, "finite"),
        ("0.0 0.0 0.0\n-0.5 1.0 0.0\n", 2, "must not be negative"),
        ("0.0 0.0 0.0\n0.5 1.0 0.0 7.0\n", 2, "radians"),
    ] {
        let dir = folder(LINE, &[("wave_frequencies.txt", body)]);
        let e = error(dir.path());
        assert!(
            e.contains("wave_frequencies.txt")
                && e.contains(&format!("line {line}:"))
                && e.contains(says),
            "expected line {line} and \"{says}\" in: {e}"
        );
    }
    let dir = folder(LINE, &[("wave_frequencies.txt", "0.0 0.0 0.0\n")]);
    assert!(error(dir.path()).contains("at least 2"));
    // No file: the option's line and the file's name.
    let dir = folder(LINE, &[]);
    let e = error(dir.path());
    let n = line_of("7       WaveKin", LINE);
    assert!(
        e.contains(&format!("line {n}:")) && e.contains("wave_frequencies.txt"),
        "{e}"
    );
    // Records: too short once resampled, times that do not increase, not a number.
    let kin3 = with(LINE, "7       WaveKin", "3       WaveKin");
    for (body, says) in [
        (
            "0 0\n0.5 1\n1.0 0\n1.5 -1\n",
            "gives 6 samples, fewer than 8",
        ),
        (
            "0 0\n0.5 1\n0.5 0\n1.5 -1\n",
            "line 3: t: time 0.5 does not increase",
        ),
        ("0 0\n0.5 x\n", "line 2: eta"),
        ("0 0\n0.5 inf\n", "line 2: eta"),
    ] {
        let dir = folder(&kin3, &[("wave_elevation.txt", body)]);
        let e = error(dir.path());
        assert!(
            e.contains("wave_elevation.txt") && e.contains(says),
            "expected \"{says}\" in: {e}"
        );
    }
    let bad_dt = with(LINE, "7       WaveKin", "3       WaveKin\n-1      dtWave");
    let dir = folder(&bad_dt, &[("wave_elevation.txt", "0 0\n10 1\n")]);
    let e = error(dir.path());
    assert!(
        e.contains("dtWave") && e.contains("must be positive"),
        "{e}"
    );
    // Other WaveKin values are refused.
    let dir = folder(&with(LINE, "7       WaveKin", "2       WaveKin"), &[]);
    assert!(error(dir.path()).contains("WaveKin = 2"));
}
