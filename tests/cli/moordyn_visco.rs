//! MoorDyn line types with the viscoelastic cells `EA_s|EA_d`, `EA_s|EA_Dc|EA_D_Lm` and
//! `BA_s|BA_d`: converted to `ea`, `ea_dynamic`, `ea_dynamic_slope`, `ba_static`,
//! `ba_dynamic` (a damping ratio for `BA_s` on MoorDyn's rule), run as they are, and
//! bad cells refused naming the line and the column.

use cablesim::moordyn::{convert_text, ConvertOptions};
use cablesim::options::{Backend, Overrides};
use cablesim::scenario::Scenario;
use cablesim::{MemorySink, Simulation};

const MODEL: &str = "\
--------------------- MoorDyn Input File ------------------------------------
Two polyester lines, viscoelastic, written for cablesim's tests
---------------------- LINE TYPES -------------------------------------------
TypeName   Diam    Mass/m   EA                        BA/-zeta     EI    Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)   (N)                       (N-s/-)      (N-m^2) (-)  (-)    (-)     (-)
poly       0.1438  22.42    1.424e+08|1.586e+08       4E9|11E6     0     1.2    1.0    0.01    0.0
polym      0.1438  22.42    1.424e+08|1.586e+08|0.4   -0.8         0     1.2    1.0    0.01    0.0
---------------------- POINTS -----------------------------------------------
ID  Attachment  X       Y      Z       Mass   Volume  CdA    Ca
(#) (-)         (m)     (m)    (m)     (kg)   (m^3)   (m^2)  (-)
1   Fixed       0       0      -200    0      0       0      0
2   Coupled     240     0      -20     0      0       0      0
3   Fixed       0       100    -200    0      0       0      0
4   Coupled     240     100    -20     0      0       0      0
---------------------- LINES ------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#) (name)    (ID)     (ID)     (m)       (-)      (-)
1   poly      1        2        295       20       -
2   polym     3        4        295       20       -
---------------------- OPTIONS ----------------------------------------------
0.001   dtM       time step (s)
9.81    g         gravity
1025    rho       water density
200     WtrDpth   water depth (m)
---------------------- OUTPUTS ----------------------------------------------
FairTen1
------------------------- need this line ------------------------------------
";

#[test]
fn moordyn_viscoelastic_cells_convert_and_run() {
    let dir = std::env::temp_dir().join(format!("cablesim_md_visco_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("model.dat");
    std::fs::write(&model, MODEL).unwrap();
    let c = convert_text(MODEL, &model, &ConvertOptions::default()).expect("converts");
    for key in [
        "ea = 142400000.0",
        "ea_dynamic = 158600000.0",
        "ba_static = 4000000000.0",
        "ba_dynamic = 11000000.0",
        "ea_dynamic_slope = 0.4",
    ] {
        assert!(c.toml.contains(key), "{key} missing from\n{}", c.toml);
    }
    // No damping time constant for a viscoelastic line (the seabed's `damping` is N s/m).
    assert!(!c.toml.contains("  # s\n"), "{}", c.toml);
    let sc = Scenario::parse(&c.toml, &dir.join("model.toml")).unwrap();
    let v0 = sc.model.line_types[0]
        .viscoelastic
        .expect("poly is viscoelastic");
    assert_eq!(v0.ea_dynamic, 1.586e8);
    assert_eq!(v0.ea_dynamic_slope, 0.0);
    assert_eq!((v0.ba_static, v0.ba_dynamic), (4e9, 11e6));
    let v1 = sc.model.line_types[1]
        .viscoelastic
        .expect("polym is viscoelastic");
    assert_eq!(v1.ea_dynamic_slope, 0.4);
    // BA_s = -0.8: MoorDyn's damping ratio, zeta (L/N) sqrt(EA_s m); BA_d = 0.
    let want = 0.8 * (295.0 / 20.0) * (1.424e8f64 * 22.42).sqrt();
    assert!(
        (v1.ba_static - want).abs() < 1e-9 * want,
        "{}",
        v1.ba_static
    );
    assert_eq!(v1.ba_dynamic, 0.0);

    // It runs as it is (the file, not the TOML), on the CPU, for 2 s.
    let mut mem = MemorySink::new();
    let summary = Simulation::from_file(
        &model,
        &Overrides {
            backend: Some(Backend::Cpu),
            duration: Some(2.0),
            ..Overrides::default()
        },
    )
    .unwrap()
    .run(&mut mem, |_| {})
    .unwrap();
    assert!(summary.steps > 0);
    let last = mem.frames.last().expect("frames");
    assert!(last.time > 1.99, "{}", last.time);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn moordyn_bad_viscoelastic_cells_are_refused() {
    let dir = std::env::temp_dir().join(format!("cablesim_md_visco_bad_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("model.dat");
    let row = "1.424e+08|1.586e+08       4E9|11E6";
    for (cells, what) in [
        ("1.424e+08|1.2e+08       4E9|11E6", "must exceed the static"),
        (
            "1.424e+08|1.586e+08|-0.4   4E9|11E6",
            "EA_D_Lm must not be negative",
        ),
        (
            "1.424e+08|1.586e+08       4E9|-11E6",
            "BA_d must not be negative",
        ),
        ("1.424e+08|1.586e+08       0|11E6", "static damping BA_s"),
        ("1.424e+08|1.586e+08|0.4|3   4E9|11E6", "at most 3"),
        ("1.424e+08       4E9|11E6", "more (|-separated) values"),
        ("1.424e+08|x       4E9|11E6", "EA_d of \"x\""),
        ("SYROPE:a.txt|1|2       4E9|11E6", "Syrope"),
    ] {
        let text = MODEL.replacen(row, cells, 1);
        assert_ne!(text, MODEL);
        std::fs::write(&model, &text).unwrap();
        let e = convert_text(&text, &model, &ConvertOptions::default())
            .expect_err(cells)
            .to_string();
        assert!(
            e.contains("line 6") && e.contains("line type \"poly\"") && e.contains(what),
            "{cells}: {e}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
