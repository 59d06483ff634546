//! MoorDyn line types whose `EA` names a strain-tension curve file: read relative to
//! the input file, written into the converted scenario as `ea_curve`, with the damping
//! ratio taken on MoorDyn's stiffness for it; a bad curve file is refused naming the
//! file and its line.

use cablesim::moordyn::{convert_text, ConvertOptions};
use cablesim::scenario::Scenario;

const MODEL: &str = "\
--------------------- MoorDyn Input File ------------------------------------
A polyester line with a tabulated EA, written for cablesim's tests
---------------------- LINE TYPES -------------------------------------------
TypeName   Diam    Mass/m     EA              BA/-zeta    EI    Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)             (N-s/-)     (N-m^2) (-)  (-)    (-)     (-)
poly       0.15    40.0       poly_ea.txt     -0.5        0     1.2    1.0    0.01    0.0
---------------------- POINTS -----------------------------------------------
ID  Attachment  X       Y      Z       Mass   Volume  CdA    Ca
(#) (-)         (m)     (m)    (m)     (kg)   (m^3)   (m^2)  (-)
1   Fixed       0       0      -600    0      0       0      0
2   Coupled     400     0      -300    0      0       0      0
---------------------- LINES ------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#) (name)    (ID)     (ID)     (m)       (-)      (-)
1   poly      1        2        490       49       -
---------------------- OPTIONS ----------------------------------------------
0.001   dtM       time step (s)
9.81    g         gravity
1025    rho       water density
1000    WtrDpth   water depth (m)
---------------------- OUTPUTS ----------------------------------------------
FairTen1
------------------------- need this line ------------------------------------
";

const CURVE: &str = "\
Strain   Tension
(-)      (N)
-------------------
0.005    1.0e5
0.01     3.0e5
0.02     9.0e5
0.05     4.0e6
";

#[test]
fn moordyn_ea_curve_file_converts_and_runs() {
    let dir = std::env::temp_dir().join(format!("cablesim_md_curve_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("model.dat");
    std::fs::write(&model, MODEL).unwrap();
    std::fs::write(dir.join("poly_ea.txt"), CURVE).unwrap();
    let c = convert_text(MODEL, &model, &ConvertOptions::default()).expect("converts");
    assert!(
        c.toml.contains(
            "ea_curve = [[0.005, 100000.0], [0.01, 300000.0], [0.02, 900000.0], [0.05, 4000000.0]]"
        ),
        "{}",
        c.toml
    );
    let sc = Scenario::parse(&c.toml, &dir.join("model.toml")).unwrap();
    let lt = &sc.model.line_types[0];
    // EA is the largest slope, (4e6 - 9e5) / 0.03; the damping ratio takes MoorDyn's
    // stiffness, the last secant 4e6 / 0.05: c = zeta (L/N) sqrt(EA_n m) / EA_max.
    let ea_max = (4.0e6 - 9.0e5) / 0.03;
    assert!((lt.ea - ea_max).abs() < 1e-6 * ea_max, "{}", lt.ea);
    let c_expected = 0.5 * 10.0 * (8.0e7f64 * 40.0).sqrt() / ea_max;
    assert!(
        (lt.damping - c_expected).abs() < 1e-12 * c_expected,
        "{}",
        lt.damping
    );
    // It runs: the static start holds its strain inside the curve.
    let (lay, pos, residual) = cablesim::initial::prepare(&sc).unwrap();
    assert!(residual < 1e-2, "{residual}");
    assert_eq!(lay.n_elements(), 49);
    let _ = pos;

    // A curve whose strains do not increase: the curve file and the row.
    std::fs::write(dir.join("poly_ea.txt"), CURVE.replace("0.02 ", "0.004")).unwrap();
    let e = convert_text(MODEL, &model, &ConvertOptions::default())
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("poly_ea.txt") && e.contains("row 3") && e.contains("0.004"),
        "{e}"
    );
    // A row that is not two numbers: the curve file's line.
    std::fs::write(
        dir.join("poly_ea.txt"),
        CURVE.replace("0.02     9.0e5", "0.02 x"),
    )
    .unwrap();
    let e = convert_text(MODEL, &model, &ConvertOptions::default())
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("poly_ea.txt") && e.contains("line 6") && e.contains("0.02 x"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
