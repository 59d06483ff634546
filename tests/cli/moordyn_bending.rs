//! A MoorDyn file with bending stiffness (the `EI` column of LINE TYPES): it converts,
//! runs, and its beam sags as Euler-Bernoulli says; bad `ei` and `clamp` values in a
//! scenario are errors naming the key.

use cablesim::moordyn::{convert_text, ConvertOptions};
use cablesim::scenario::Scenario;
use cablesim::sim::prepare;
use std::path::Path;

/// The numbers of MoorDyn-C's simply supported beam test: a 10 m beam of 100 kg/m,
/// EA 1.5e9 N, EI 1e7 N m^2, pinned at both ends 10 m apart, 10 m above the water.
const BEAM: &str = "\
--------------------- MoorDyn Input File ------------------------------------
a simply supported beam
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)
beam      0.25     100.0      1.5e9      -1.0        1e7        0.0    0.0    0.1     0.0
---------------------- POINT PROPERTIES --------------------------------
ID    Type      X       Y       Z       Mass   Volume  CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)
1     Fixed     0       0.0     10.0    0      0       0      0
2     Fixed     10      0.0     10.0    0      0       0      0
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
1     beam       1        2         10        19      -
---------------------- OPTIONS -----------------------------------------
10            WtrDpth              water depth (m)
------------------------- need this line --------------------------------------
";

#[test]
fn moordyn_beam_converts_and_sags_as_euler_bernoulli() {
    let path = Path::new("beam.dat");
    let c = convert_text(BEAM, path, &ConvertOptions::default()).expect("converts");
    assert!(c.toml.contains("ei = 10000000"), "{}", c.toml);
    assert!(
        !c.warnings.iter().any(|w| w.message.contains("EI")),
        "{:?}",
        c.warnings
    );
    let sc = Scenario::parse(&c.toml, path).unwrap();
    assert_eq!(sc.model.line_types[0].ei, 1e7);
    // The initial state is the static equilibrium, bending included.
    let (_, pos, _) = prepare(&sc).unwrap();
    let (l, ei, q) = (10.0, 1e7, 100.0 * sc.model.env.gravity);
    let mid = 5.0 * q * l * l * l * l / (384.0 * ei);
    let mut worst = 0.0f64;
    for p in &pos {
        let x = p[0];
        let w = q * x * (l * l * l - 2.0 * l * x * x + x * x * x) / (24.0 * ei);
        worst = worst.max(((10.0 - p[2]) - w).abs());
    }
    eprintln!(
        "MoorDyn beam (19 segments): largest deflection error {:.3} mm of a mid-span deflection of {:.3} mm",
        worst * 1e3,
        mid * 1e3
    );
    // 1 % of the mid-span deflection (a chain of bars without EI sags 54 mm).
    assert!(worst < 0.01 * mid, "{worst} against {mid}");
}

fn scenario_error(extra_type: &str, start: &str) -> String {
    let text = format!(
        r#"
[simulation]
duration = 1.0
output_interval = 0.5
dt = "auto"

[environment]
depth = 100.0

[[line_types]]
name = "cable"
diameter = 0.1
mass_per_length = 20.0
ea = 1e8
{extra_type}

[[cables]]
name = "c"
line_type = "cable"
length = 50.0
segments = 10
start = {start}
end = {{ fixed = [50.0, 0.0, -50.0] }}
"#
    );
    match Scenario::parse(&text, Path::new("bend.toml")) {
        Ok(_) => String::new(),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_bending_input_is_an_error_naming_the_key() {
    let e = scenario_error("ei = -1.0", "{ fixed = [0.0, 0.0, -50.0] }");
    assert!(e.contains("ei") && e.contains("negative"), "{e}");
    let e = scenario_error("ei = nan", "{ fixed = [0.0, 0.0, -50.0] }");
    assert!(e.contains("ei"), "{e}");
    // A clamp needs bending stiffness, a fixed end and a direction.
    let e = scenario_error("", "{ fixed = [0.0, 0.0, -50.0], clamp = [1.0, 0.0, 0.0] }");
    assert!(e.contains("clamp") && e.contains("ei = 0"), "{e}");
    let e = scenario_error(
        "ei = 1e4",
        "{ free = [0.0, 0.0, -50.0], clamp = [1.0, 0.0, 0.0] }",
    );
    assert!(e.contains("clamp") && e.contains("fixed"), "{e}");
    let e = scenario_error(
        "ei = 1e4",
        "{ fixed = [0.0, 0.0, -50.0], clamp = [0.0, 0.0, 0.0] }",
    );
    assert!(e.contains("clamp") && e.contains("zero"), "{e}");
    assert_eq!(
        scenario_error(
            "ei = 1e4",
            "{ fixed = [0.0, 0.0, -50.0], clamp = [1.0, 0.0, 0.0] }"
        ),
        ""
    );
}

#[test]
fn a_net_of_a_bending_line_type_is_an_error() {
    let text = r#"
[simulation]
duration = 1.0
output_interval = 0.5
dt = "auto"

[environment]
depth = 100.0

[[line_types]]
name = "twine"
diameter = 0.003
mass_per_length = 0.01
ea = 1e4
ei = 1e-3

[[nets]]
name = "panel"
line_type = "twine"
shape = "panel"
knots = [4, 3]
size = [3.0, 2.0]
top = [0.0, 0.0, -1.0]
"#;
    let e = Scenario::parse(text, Path::new("net.toml"))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(e.contains("line_type") && e.contains("bending"), "{e}");
}
