//! MoorDyn input files (v1 and v2) converted to scenarios: the converted fields against
//! values worked by hand from the file, errors that name the file's line, and a
//! converted static line's fairlead force against the analytic elastic catenary.

use cablesim::cpu::CpuSolver;
use cablesim::moordyn::{convert_text, ConvertOptions, Version};
use cablesim::options::SolverOptions;
use cablesim::output::end_forces;
use cablesim::physics::catenary::catenary;
use cablesim::scenario::Scenario;
use cablesim::sim::prepare;
use std::path::Path;

/// A v2 file: a chain from an anchor to a buoy, a rope from the buoy to a vessel
/// fairlead, and a second chain from another anchor to the same buoy.
const V2: &str = "\
--------------------- MoorDyn Input File ------------------------------------
Buoy held by chains, written for cablesim's tests
---------------------- LINE TYPES -------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI    Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2) (-)  (-)    (-)     (-)
chain      0.1     150.0      1.0e9      -0.8        0     2.4    1.0    1.15    0.0
rope       0.08    6.0        2.0e7      4.0e5       0     1.2    0.8    0.008   0.0
---------------------- POINTS -----------------------------------------------
ID  Attachment  X       Y      Z       Mass   Volume  CdA    Ca
(#) (-)         (m)     (m)    (m)     (kg)   (m^3)   (m^2)  (-)
1   Fixed       -300    0      -80     0      0       0      0
2   Free        -40     0      -30     200    2.5     1.2    0.7   # the buoy
3   Coupled     0       0      -5      0      0       0      0
4   Anchor      150     260    -80     0      0       0      0
---------------------- LINES ------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#) (name)    (ID)     (ID)     (m)       (-)      (-)
1   chain     1        2        280       28       p
2   rope      2        3        50        10       -
3   chain     4        2        300       20       t
---------------------- OPTIONS ----------------------------------------------
0.001   dtM       time step (s)
9.80    g         gravity
1020    rho       water density
80      WtrDpth   water depth (m)
2.0e6   kBot      bottom stiffness (Pa/m)
2.0e5   cBot      bottom damping (Pa-s/m)
0.4     FrictionCoefficient
0.5     dtOut
1.0     dtIC
60      TmaxIC
---------------------- OUTPUTS ----------------------------------------------
FairTen2
AnchTen1
------------------------- need this line ------------------------------------
";

/// A v1 file: MoorDyn v1's column orders (`Can Cat Cdn Cdt`; `UnstrLen NumSegs
/// NodeAnch NodeFair`; point rows with `FX FY FZ`), no WtrDpth (the anchor sets it).
const V1: &str = "\
MoorDyn v1 input file, written for cablesim's tests
----------------------- LINE TYPES ------------------------------------------
LineType  Diam    MassDen   EA        BA/-zeta  Can   Cat   Cdn   Cdt
(-)       (m)     (kg/m)    (N)       (Pa-s/-)  (-)   (-)   (-)   (-)
nylon     0.124   13.76     2515288.0 1.0e4     0.9   0.0   1.6   0.05
----------------------- CONNECTION PROPERTIES -------------------------------
Node  Type     X       Y    Z       M    V    FX   FY   FZ   CdA  CA
(-)   (-)      (m)     (m)  (m)     (kg) (m^3) (kN) (kN) (kN) (m^2) (-)
1     Vessel   0.0     0    -10.0   0    0    0    0    0    0    0
2     Fixed    267.0   0    -70.0   0    0    0    0    0    0    0
----------------------- LINE PROPERTIES -------------------------------------
Line  LineType  UnstrLen  NumSegs  NodeAnch  NodeFair  Flags/Outputs
(-)   (-)       (m)       (-)      (-)       (-)       (-)
1     nylon     300.0     50       2         1         -
----------------------- SOLVER OPTIONS --------------------------------------
0.001    dtM          - time step to use in mooring integration
3.0e6    kb           - bottom stiffness
3.0e5    cb           - bottom damping
5.0      ICDfac       - factor by which to scale drag coefficients
-------------------------- OUTPUTS ------------------------------------------
FairTen1
END
------------------------- need this line ------------------------------------
";

fn convert(text: &str) -> (String, Scenario) {
    let path = Path::new("model.dat");
    let c = convert_text(text, path, &ConvertOptions::default()).expect("converts");
    let sc = Scenario::parse(&c.toml, path)
        .unwrap_or_else(|e| panic!("converted scenario does not load: {e}\n{}", c.toml));
    (c.toml, sc)
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-12 * b.abs().max(1e-300),
        "{what}: {a} vs {b}"
    );
}

#[test]
fn v2_file_maps_every_field() {
    let file = cablesim::moordyn::parse(V2, Path::new("model.dat")).unwrap();
    assert_eq!(file.version, Version::V2);
    let (toml, sc) = convert(V2);
    let m = &sc.model;
    close(m.env.gravity, 9.80, "g");
    close(m.env.water_density, 1020.0, "rho");
    close(m.env.depth, 80.0, "depth");
    // kBot and cBot times the chain's diameter (the most line length is chain).
    close(m.env.seabed.stiffness, 2.0e6 * 0.1, "seabed stiffness");
    close(m.env.seabed.damping, 2.0e5 * 0.1, "seabed damping");
    close(m.env.seabed.friction, 0.4, "friction");
    close(sc.sim.output_interval, 0.5, "dtOut");
    // Chain lines 1 (280 m / 28) and 3 (300 m / 20) have different segment lengths,
    // so the damping ratio gives two time constants: c = zeta (L/N) sqrt(m/EA).
    let lt = |name: &str| m.line_types.iter().find(|t| t.name == name).unwrap();
    let c1 = 0.8 * 10.0 * (150.0f64 / 1.0e9).sqrt();
    let c3 = 0.8 * 15.0 * (150.0f64 / 1.0e9).sqrt();
    close(lt("chain").damping, c1, "chain c (line 1)");
    close(lt("chain_line3").damping, c3, "chain c (line 3)");
    close(lt("rope").damping, 4.0e5 / 2.0e7, "rope c = BA/EA");
    let ch = lt("chain");
    close(ch.diameter, 0.1, "Diam");
    close(ch.mass_per_length, 150.0, "Mass/m");
    close(ch.ea, 1.0e9, "EA");
    close(ch.cn, 2.4, "Cd");
    close(ch.ct, 1.15, "CdAx");
    close(ch.cm, 1.0, "Ca");
    close(ch.cat, 0.0, "CaAx");
    assert_eq!(m.line_types.len(), 3);
    // Cables: names, lengths, segments, line types.
    assert_eq!(m.cables.len(), 3);
    let seg: Vec<usize> = m.cables.iter().map(|c| c.l0.len()).collect();
    assert_eq!(seg, vec![28, 10, 20]);
    let len: f64 = m.cables[1].l0.iter().sum();
    close(len, 50.0, "line 2 length");
    assert_eq!(m.line_types[m.cables[2].line_type].name, "chain_line3");
    assert!(m.cables[0].output_positions, "LineOutputs p");
    // The buoy: one shared node, free, with the point's properties.
    let buoy: Vec<_> = m
        .nodes
        .iter()
        .filter(|n| n.label.as_deref() == Some("point2"))
        .collect();
    assert_eq!(buoy.len(), 1);
    let b = buoy[0];
    assert!(b.route.is_none(), "a free point is not held");
    close(b.point.mass, 200.0, "buoy mass");
    close(b.point.volume, 2.5, "buoy volume");
    close(b.point.drag_area, 1.2, "buoy CdA");
    close(b.point.added_mass_coef, 0.7, "buoy Ca");
    let bi = m.nodes.iter().position(|n| std::ptr::eq(n, b)).unwrap();
    assert_eq!(*m.cables[0].nodes.last().unwrap(), bi);
    assert_eq!(m.cables[1].nodes[0], bi);
    assert_eq!(*m.cables[2].nodes.last().unwrap(), bi);
    // Anchors and the vessel fairlead are held where the file puts them.
    let held = |i: usize| m.nodes[i].route.is_some();
    let first = m.cables[0].nodes[0];
    assert!(held(first));
    assert_eq!(m.nodes[first].position, [-300.0, 0.0, -80.0]);
    let fair = *m.cables[1].nodes.last().unwrap();
    assert!(held(fair));
    assert_eq!(m.nodes[fair].position, [0.0, 0.0, -5.0]);
    // Every mapping choice is commented; the vessel point says it is held for now.
    assert!(toml.contains("held still"), "{toml}");
    assert!(toml.contains("zeta (L/N) sqrt(m/EA)"), "{toml}");
}

#[test]
fn v1_file_reads_v1_column_orders() {
    let file = cablesim::moordyn::parse(V1, Path::new("model.dat")).unwrap();
    assert_eq!(file.version, Version::V1);
    let (_, sc) = convert(V1);
    let m = &sc.model;
    let lt = &m.line_types[0];
    // v1 order: Can Cat Cdn Cdt.
    close(lt.cm, 0.9, "Can");
    close(lt.cn, 1.6, "Cdn");
    close(lt.ct, 0.05, "Cdt");
    close(lt.cat, 0.0, "Cat");
    close(lt.damping, 1.0e4 / 2515288.0, "c = BA/EA");
    // MoorDyn's default gravity; no WtrDpth: the fixed point at z = -70 sets the seabed.
    close(m.env.gravity, 9.80665, "g");
    close(m.env.depth, 70.0, "depth");
    close(m.env.seabed.stiffness, 3.0e6 * 0.124, "kb d");
    close(m.env.seabed.damping, 3.0e5 * 0.124, "cb d");
    // Line 1 runs from node 2 (anchor, NodeAnch) to node 1 (fairlead): 300 m in 50.
    let c = &m.cables[0];
    assert_eq!(c.l0.len(), 50);
    close(c.l0.iter().sum::<f64>(), 300.0, "UnstrLen");
    assert_eq!(m.nodes[c.nodes[0]].position, [267.0, 0.0, -70.0]);
    assert_eq!(
        m.nodes[*c.nodes.last().unwrap()].position,
        [0.0, 0.0, -10.0]
    );
}

/// The file with one line of `V2` replaced.
fn v2_with(old: &str, new: &str) -> String {
    assert!(V2.contains(old), "{old}");
    V2.replacen(old, new, 1)
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).unwrap() + 1
}

fn error_of(text: &str) -> String {
    convert_text(text, Path::new("model.dat"), &ConvertOptions::default())
        .expect_err("should be refused")
        .to_string()
}

#[test]
fn unsupported_features_are_errors_naming_the_line() {
    let cases: Vec<(String, &str, &str)> = vec![
        (
            v2_with(
                "chain      0.1     150.0      1.0e9 ",
                "chain      0.1     150.0      SYROPE:owc.txt|2.0e9|0.4 ",
            ),
            "chain      0.1",
            "Syrope",
        ),
        (
            v2_with("3   Coupled ", "3   Body1   "),
            "3   Body1",
            "bodies",
        ),
        (
            v2_with("2   rope      2        3 ", "2   rope      2        R1B "),
            "2   rope      2",
            "rod",
        ),
        (
            v2_with("1   chain     1 ", "1   cable     1 "),
            "1   cable     1",
            "unknown line type \"cable\"",
        ),
        (
            v2_with("80      WtrDpth", "bathy.txt WtrDpth"),
            "bathy.txt WtrDpth",
            "bathymetry",
        ),
        (
            v2_with("0.5     dtOut", "2       WaveKin"),
            "2       WaveKin",
            "WaveKin",
        ),
        (
            v2_with(
                "---------------------- POINTS ---",
                "---------------------- RODS -----\nID Type\n(#) (-)\n1 Can Fixed 0 0 0 0 0 1 4 -\n---------------------- POINTS ---",
            ),
            "1 Can Fixed",
            "rods are not supported",
        ),
        (
            v2_with("150.0      1.0e9", "150.0      1.0e9x"),
            "150.0      1.0e9x",
            "neither a number nor a readable curve file",
        ),
        (
            v2_with("2   Free        -40     0      -30     200    2.5 ", "2   Free        -40     0      -30     200    abc "),
            "-30     200    abc",
            "Volume",
        ),
    ];
    for (text, needle, what) in cases {
        let e = error_of(&text);
        let n = line_of(&text, needle);
        assert!(
            e.contains(&format!("line {n}:")) && e.contains(what) && e.contains("model.dat"),
            "expected line {n} and \"{what}\" in: {e}"
        );
    }
}

#[test]
fn dropped_features_are_warnings_naming_the_line() {
    let text = v2_with(
        "rope       0.08    6.0        2.0e7      4.0e5       0     1.2    0.8    0.008   0.0",
        "rope       0.08    6.0        2.0e7      4.0e5       250   1.2    0.8    0.008   0.5",
    );
    let c = convert_text(&text, Path::new("model.dat"), &ConvertOptions::default()).unwrap();
    let n = line_of(&text, "rope       0.08");
    let at: Vec<_> = c.warnings.iter().filter(|w| w.line == n).collect();
    // The bending stiffness is modelled now: no warning about it.
    assert!(!at.iter().any(|w| w.message.contains("EI")), "{at:?}");
    // The tangential added mass is no longer dropped (below): no warning about it.
    assert!(!at.iter().any(|w| w.message.contains("CaAx")), "{at:?}");
    // The chain and rope differ in diameter: the seabed's per-metre values can only
    // follow one of them, and the warning says so.
    assert!(c
        .warnings
        .iter()
        .any(|w| w.message.contains("\"rope\" (d = 0.08 m)")));
    // The EI is converted, and the lumped-mass model bends with it.
    let sc = Scenario::parse(&c.toml, Path::new("model.dat")).unwrap();
    let rope = sc
        .model
        .line_types
        .iter()
        .find(|t| t.name == "rope")
        .unwrap();
    close(rope.ei, 250.0, "EI");
    close(rope.cat, 0.5, "CaAx");
    assert!(
        c.toml.contains("cat = 0.5  # CaAx, tangential added mass"),
        "{}",
        c.toml
    );
}

#[test]
fn tangential_added_mass_is_read_and_checked_in_both_versions() {
    // v1's `Cat` (the seventh column) becomes `cat`.
    let v1 = V1.replacen("0.9   0.0   1.6", "0.9   0.3   1.6", 1);
    assert_ne!(v1, V1);
    let (toml, sc) = convert(&v1);
    close(sc.model.line_types[0].cat, 0.3, "Cat");
    assert!(
        toml.contains("cat = 0.3  # Cat, tangential added mass"),
        "{toml}"
    );
    // A negative one is refused, naming the file, the line and the column as the
    // file's version names it.
    let bad1 = V1.replacen("0.9   0.0   1.6", "0.9   -0.3  1.6", 1);
    let e = error_of(&bad1);
    let n = line_of(&bad1, "-0.3");
    assert!(
        e.contains(&format!("line {n}:")) && e.contains("Cat") && e.contains("model.dat"),
        "{e}"
    );
    let bad2 = v2_with(
        "rope       0.08    6.0        2.0e7      4.0e5       0     1.2    0.8    0.008   0.0",
        "rope       0.08    6.0        2.0e7      4.0e5       0     1.2    0.8    0.008   -1",
    );
    let e = error_of(&bad2);
    let n = line_of(&bad2, "0.008   -1");
    assert!(
        e.contains(&format!("line {n}:")) && e.contains("CaAx") && e.contains("negative"),
        "{e}"
    );
    // Not finite: refused by the table's reader.
    let bad3 = v2_with(
        "rope       0.08    6.0        2.0e7      4.0e5       0     1.2    0.8    0.008   0.0",
        "rope       0.08    6.0        2.0e7      4.0e5       0     1.2    0.8    0.008   nan",
    );
    let e = error_of(&bad3);
    assert!(e.contains("CaAx") && e.contains("finite"), "{e}");
}

#[test]
fn vessel_point_follows_a_motion_file_when_given() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("motion.csv"),
        "t,x,y,z\n0,0,0,-5\n10,2,0,-5\n",
    )
    .unwrap();
    let mut opts = ConvertOptions::default();
    opts.motions.insert(3, "motion.csv".into());
    let path = dir.path().join("model.toml");
    let c = convert_text(V2, &path, &opts).unwrap();
    let sc = Scenario::parse(&c.toml, &path).unwrap();
    let fair = *sc.model.cables[1].nodes.last().unwrap();
    let r = sc.model.nodes[fair].route.as_ref().unwrap();
    assert_eq!(r.eval(5.0).r, [1.0, 0.0, -5.0]);
    // Only coupled points take a motion.
    let mut bad = ConvertOptions::default();
    bad.motions.insert(1, "motion.csv".into());
    assert!(convert_text(V2, &path, &bad).is_err());
}

/// One chain from an anchor on the seabed to a vessel fairlead, MoorDyn v2.
const STATIC: &str = "\
--------------------- MoorDyn Input File ------------------------------------
one static chain
---------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI    Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (-)   (-)    (-)    (-)     (-)
chain      0.252   390        1.674e9    -1.0        0     1.37   1.0    0.64    0.0
---------------------- POINT PROPERTIES --------------------------------
ID    Type      X       Y       Z       Mass   Volume  CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)
1     Fixed     400     0.0     -200.0  0      0       0      0
2     Vessel    0.0     0.0     0.0     0      0       0      0
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
1     chain      1        2         480       48      -
---------------------- OPTIONS -----------------------------------------
3.0e6        kBot
3.0e5        cBot
1025.0       WtrDnsty
200          WtrDpth
------------------------- need this line -------------------------------------- 
";

#[test]
fn converted_static_line_matches_the_analytic_catenary() {
    let (_, sc) = convert(STATIC);
    let (lay, pos, _) = prepare(&sc).unwrap();
    let mut s = CpuSolver::new(lay.clone(), &pos, SolverOptions::default());
    let ev = s.evaluate().unwrap();
    let f = end_forces(&lay, &ev, &lay.cables[0]).end;
    let lt = &sc.model.line_types[0];
    let w = lt.wet_weight_per_length(sc.model.env.gravity, sc.model.env.water_density);
    // Hand value of the wet weight, with MoorDyn-C's default g:
    // (390 - 1025 pi 0.252^2 / 4) 9.80665.
    close(
        w,
        (390.0 - 1025.0 * std::f64::consts::PI * 0.252 * 0.252 / 4.0) * 9.80665,
        "w",
    );
    let c = catenary(400.0, 200.0, 480.0, 1.674e9, w, true).unwrap();
    // The fairlead is pulled towards the anchor (+x) and down; part of the chain lies
    // on the seabed (the case the contact constants matter for).
    assert!(c.grounded_length > 10.0, "{c:?}");
    let (eh, ev_) = ((f[0] - c.hf).abs() / c.hf, (-f[2] - c.vf).abs() / c.vf);
    println!("fairlead HF error {eh:.2e}, VF error {ev_:.2e}");
    assert!(
        eh < 2e-3 && ev_ < 2e-3,
        "fairlead force {f:?} vs analytic HF {} VF {}: errors {eh:.2e} {ev_:.2e}",
        c.hf,
        c.vf
    );
}

#[test]
fn detection_tells_scenarios_from_moordyn_files() {
    let dir = tempfile::tempdir().unwrap();
    let dat = dir.path().join("model.dat");
    std::fs::write(&dat, STATIC).unwrap();
    let sc = Scenario::load_any(&dat).unwrap();
    assert_eq!(sc.model.cables.len(), 1);
    assert!(cablesim::moordyn::is_moordyn(Path::new("a.txt"), V1));
    assert!(!cablesim::moordyn::is_moordyn(Path::new("a.toml"), V1));
    let toml = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/catenary.toml"),
    )
    .unwrap();
    assert!(!cablesim::moordyn::is_moordyn(Path::new("a.dat"), &toml));
}

#[test]
fn cli_converts_checks_and_refuses_by_line() {
    let exe = env!("CARGO_BIN_EXE_cablesim");
    let dir = tempfile::tempdir().unwrap();
    let dat = dir.path().join("model.dat");
    std::fs::write(&dat, V2).unwrap();
    let toml = dir.path().join("model.toml");
    let out = std::process::Command::new(exe)
        .args([
            "convert",
            dat.to_str().unwrap(),
            "-o",
            toml.to_str().unwrap(),
        ])
        .args(["--duration", "12.5"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let sc = Scenario::load(&toml).unwrap();
    assert_eq!(sc.sim.duration, 12.5);
    assert_eq!(sc.model.cables.len(), 3);
    let out = std::process::Command::new(exe)
        .args(["check", dat.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("3 cables"));
    let bad = v2_with("3   Coupled ", "3   Body1   ");
    std::fs::write(&dat, &bad).unwrap();
    let out = std::process::Command::new(exe)
        .args(["convert", dat.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let n = line_of(&bad, "3   Body1");
    assert!(err.contains(&format!("line {n}:")), "{err}");
}

#[test]
fn steady_current_profile_is_read_from_current_profile_txt() {
    let dir = tempfile::tempdir().unwrap();
    let text = v2_with("0.5     dtOut", "1       Currents");
    let dat = dir.path().join("model.dat");
    std::fs::write(&dat, &text).unwrap();
    // MoorDyn's layout: three header lines, then `z ux [uy [uz]]`, any order.
    std::fs::write(
        dir.path().join("current_profile.txt"),
        "--- MoorDyn steady currents File ---\nnotes\nz ux uy uz\n\
         0.0 1.0 0.2\n-80 0.1 0 0\n-20.0 0.8 0.1 0.05\n",
    )
    .unwrap();
    let sc = Scenario::load_any(&dat).unwrap();
    assert_eq!(
        sc.model.currents[0].table,
        vec![
            (-80.0, [0.1, 0.0, 0.0]),
            (-20.0, [0.8, 0.1, 0.05]),
            (0.0, [1.0, 0.2, 0.0]),
        ]
    );
    // A missing profile names the option's line; dynamic grids are refused.
    std::fs::remove_file(dir.path().join("current_profile.txt")).unwrap();
    let e = Scenario::load_any(&dat).unwrap_err().to_string();
    let n = line_of(&text, "1       Currents");
    assert!(
        e.contains(&format!("line {n}:")) && e.contains("current_profile.txt"),
        "{e}"
    );
    let e = error_of(&v2_with("0.5     dtOut", "2       Currents"));
    assert!(e.contains("dynamic"), "{e}");
}

#[test]
fn seafloor_file_becomes_the_seabed_grid() {
    let dir = tempfile::tempdir().unwrap();
    // MoorDyn opens the name from its working directory: here the folder above the
    // input file's, as in MoorDyn's own tests.
    let sub = dir.path().join("Mooring");
    std::fs::create_dir_all(&sub).unwrap();
    let text = v2_with("80      WtrDpth", "Mooring/bed.txt SeafloorFile");
    let dat = sub.join("model.dat");
    std::fs::write(&dat, &text).unwrap();
    std::fs::write(
        sub.join("bed.txt"),
        "3 2\n-400 0 200\n-50 300\n-400 -50 -80\n-400 300 -80\n0 -50 -80\n0 300 -80\n\
         200 -50 -81\n200 300 -81\n",
    )
    .unwrap();
    let c = convert_text(&text, &dat, &ConvertOptions::default()).unwrap();
    assert!(
        c.toml.contains("seabed_file = ") && c.toml.contains("bed.txt"),
        "{}",
        c.toml
    );
    assert!(!c.toml.contains("\ndepth = "), "{}", c.toml);
    let sc = Scenario::load_any(&dat).unwrap();
    let g = sc.model.env.seabed.grid.expect("a seabed grid");
    assert_eq!((g.xs.len(), g.ys.len()), (3, 2));
    // The waves' depth: the grid's mean depth, as MoorDyn takes it.
    close(sc.model.env.depth, (4.0 * 80.0 + 2.0 * 81.0) / 6.0, "depth");
    // The second anchor (x = 150) lies 0.75 m above the grid there; moved below it, it
    // is an error naming the point and the file.
    let under = text.replace(
        "4   Anchor      150     260    -80 ",
        "4   Anchor      150     260    -82 ",
    );
    std::fs::write(&dat, &under).unwrap();
    let e = Scenario::load_any(&dat).unwrap_err().to_string();
    assert!(
        e.contains("below the seabed") && e.contains("bed.txt"),
        "{e}"
    );
    // A missing grid file names the option's line.
    let e = error_of(&v2_with("80      WtrDpth", "nothing.txt SeafloorFile"));
    let n = line_of(
        &v2_with("80      WtrDpth", "nothing.txt SeafloorFile"),
        "nothing.txt SeafloorFile",
    );
    assert!(
        e.contains(&format!("line {n}:")) && e.contains("not found"),
        "{e}"
    );
}

#[test]
fn default_option_values_fall_back_with_a_warning() {
    // MoorDyn-F's `DEFAULT` (OpenFAST's value): the depth falls back to the lowest
    // point, as MoorDyn-C does without the option.
    let text = v2_with("80      WtrDpth", "DEFAULT WtrDpth");
    let c = convert_text(&text, Path::new("model.dat"), &ConvertOptions::default()).unwrap();
    let n = line_of(&text, "DEFAULT WtrDpth");
    assert!(c
        .warnings
        .iter()
        .any(|w| w.line == n && w.message.contains("DEFAULT")));
    let sc = Scenario::parse(&c.toml, Path::new("model.dat")).unwrap();
    close(sc.model.env.depth, 80.0, "depth from the lowest point");
}

/// MoorDyn-F's `MU_KT` and `MU_KA` become `friction_transverse` and `friction_axial`
/// (each 0 unless given, as in MoorDyn-F), in the converted file and in the scenario it
/// loads as; a `FrictionCoefficient` beside them is left out with a warning naming its
/// line; `FrictionCoefficient` alone stays the one coefficient.
#[test]
fn mu_kt_and_mu_ka_convert_to_split_friction() {
    let with = |opts: &str| V2.replace("0.4     FrictionCoefficient\n", opts);
    let (toml, sc) = convert(&with("0.9     MU_KT\n0.3     MU_KA\n"));
    let sb = sc.model.env.seabed;
    close(sb.friction, 0.9, "mu_t");
    close(sb.mu_axial(), 0.3, "mu_a");
    assert!(sb.split_friction());
    assert!(
        toml.contains("friction_transverse = 0.9") && toml.contains("friction_axial = 0.3"),
        "{toml}"
    );
    // MU_KT alone: MoorDyn-F's MU_KA is 0.
    let (_, sc) = convert(&with("0.7     mu_kT\n"));
    let sb = sc.model.env.seabed;
    close(sb.friction, 0.7, "mu_t");
    assert_eq!(sb.mu_axial(), 0.0);
    // FrictionCoefficient beside them: left out, with a warning at its line.
    let text = with("0.4     FrictionCoefficient\n0.9     MU_KT\n0.3     MU_KA\n");
    let line = text
        .lines()
        .position(|l| l.contains("FrictionCoefficient"))
        .unwrap()
        + 1;
    let c = convert_text(&text, Path::new("model.dat"), &ConvertOptions::default()).unwrap();
    assert!(
        c.warnings
            .iter()
            .any(|w| w.line == line && w.message.contains("FrictionCoefficient")),
        "{:?}",
        c.warnings
    );
    let sc = Scenario::parse(&c.toml, Path::new("model.dat")).unwrap();
    close(sc.model.env.seabed.friction, 0.9, "mu_t");
    // FrictionCoefficient alone: the same both ways.
    let (_, sc) = convert(V2);
    assert!(!sc.model.env.seabed.split_friction());
    close(sc.model.env.seabed.mu_axial(), 0.4, "mu");
}
