//! Absurd and wrong inputs get a clear error or warning before any work: the work
//! budget (`[limits]`, `--limit`), the cap on input files, the checks of geometry and
//! derived quantities, array keys read as written.

use cablesim::error::Error;
use cablesim::scenario::Scenario;
use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");

fn catenary() -> String {
    std::fs::read_to_string("examples/catenary.toml").unwrap()
}

/// `text` with `from` replaced by `to` (which must be there) and `extra` appended.
fn edit(text: &str, from: &str, to: &str, extra: &str) -> String {
    assert!(text.contains(from), "the example changed: no `{from}`");
    format!("{}{extra}", text.replacen(from, to, 1))
}

/// Writes `text` to `dir/case.toml` and runs `cablesim ARGS case.toml`.
fn cli(dir: &Path, text: &str, args: &[&str]) -> (bool, String) {
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    let r = Command::new(BIN).args(args).arg(&path).output().unwrap();
    (
        r.status.success(),
        String::from_utf8_lossy(&r.stderr).into_owned(),
    )
}

fn check(dir: &Path, text: &str) -> (bool, String) {
    cli(dir, text, &["check"])
}

/// `check` fails with an error naming `field` and saying `what`.
fn refused(dir: &Path, text: &str, field: &str, what: &str) {
    let (ok, err) = check(dir, text);
    assert!(!ok, "accepted: expected {field}: {what}");
    assert!(err.contains(field) && err.contains(what), "{err}");
}

fn parse(text: &str) -> Result<Scenario, Error> {
    Scenario::parse(text, Path::new("/tmp/case.toml"))
}

fn parse_error(text: &str) -> (String, String) {
    match parse(text) {
        Err(Error::Scenario { field, message, .. }) => (field, message),
        Err(e) => panic!("wrong error kind: {e}"),
        Ok(_) => panic!("accepted"),
    }
}

const ARRAY: &str = r#"
[[cable_arrays]]
name = "a"
count = COUNT
line_type = "wire"
length = 250.0
segments = 50
start = { fixed = [-220.0, 0.0, -100.0] }
end = { fixed = [0.0, 0.0, -10.0] }
"#;

const NET: &str = r#"
[[nets]]
name = "n"
line_type = "wire"
shape = "panel"
knots = [100000, 100000]
size = [10.0, 10.0]
top = [0.0, 0.0, -1.0]
"#;

#[test]
fn absurd_work_is_refused_with_the_estimate_before_anything_is_built() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let c = catenary();
    let ancf = edit(
        &c,
        "backend = \"auto\" ",
        "formulation = \"ancf\"\nbackend = \"auto\" ",
        "\n[ancf]\nelement_length = 1e-9\n",
    );
    refused(
        d,
        &ancf,
        "ancf.element_length",
        "GiB of memory, over the budget",
    );
    let array = edit(
        &c,
        "segments = 50",
        "segments = 50",
        &ARRAY.replace("COUNT", "10000000"),
    );
    refused(
        d,
        &array,
        "cable_arrays[0] (\"a\").count",
        "over the budget of 16 GiB",
    );
    refused(
        d,
        &edit(&c, "segments = 50", "segments = 50", NET),
        "nets[0] (\"n\").knots",
        "over the budget",
    );
    let short = edit(&c, "length = 250.0", "length = 1e-6", "");
    refused(
        d,
        &short,
        "simulation.duration",
        "over the budget of 1e12 node-steps",
    );
    // 6e7 frames (3e9 node-steps, within that budget) of 51 rows: about 230 GiB.
    let dense = edit(&c, "output_interval = 1.0", "output_interval = 1e-6", "");
    refused(
        d,
        &dense,
        "simulation.output_interval",
        "GiB, over the budget",
    );
    let long = edit(&c, "duration = 60.0", "duration = 1e20", "");
    refused(
        d,
        &long,
        "simulation.duration",
        "over the budget of 1e12 node-steps",
    );
    // A tiny given step, on the command line: refused before stepping.
    let (ok, err) = cli(
        d,
        &c,
        &[
            "run",
            "-q",
            "--dt",
            "1e-300",
            "--out",
            d.join("out").to_str().unwrap(),
        ],
    );
    assert!(
        !ok && err.contains("over the budget of 1e12 node-steps"),
        "{err}"
    );
    assert!(!d.join("out/summary.json").exists() || err.contains("simulation.duration"));
}

#[test]
fn the_budget_is_raised_by_the_scenario_or_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // 60 s every 1 ms: 6e4 frames of 51 positions, some 0.25 GiB.
    let dense = edit(
        &catenary(),
        "output_interval = 1.0 ",
        "output_interval = 0.001 ",
        "",
    );
    assert!(check(d, &dense).0, "within the default budget");
    let low = format!("{dense}\n[limits]\noutput_gib = 0.01\n");
    refused(d, &low, "simulation.output_interval", "[limits] output_gib");
    let (ok, err) = cli(d, &low, &["check", "--limit", "output_gib=1"]);
    assert!(ok, "--limit raises it: {err}");
    let (ok, err) = cli(d, &dense, &["check", "--limit", "node_steps=1e3"]);
    assert!(!ok && err.contains("budget of 1e3 node-steps"), "{err}");
    let (ok, err) = cli(d, &dense, &["check", "--limit", "colour=1"]);
    assert!(!ok && err.contains("unknown limit"), "{err}");
    refused(
        d,
        &format!("{dense}\n[limits]\nnode_steps = -1.0\n"),
        "limits.node_steps",
        "positive",
    );
}

#[test]
fn an_endless_scenario_or_route_file_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let r = Command::new(BIN)
        .args(["check", "/dev/zero"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(!r.status.success() && err.contains("64 MiB"), "{err}");
    let route = edit(
        &catenary(),
        "end = { fixed = [0.0, 0.0, -10.0] }",
        "end = { route = \"table\", file = \"/dev/zero\" }",
        "",
    );
    refused(
        dir.path(),
        &route,
        "cables[0] (\"line1\").end.file",
        "64 MiB",
    );
}

/// `check` of a cable of 10^6 segments: the stable-step search is linear (it put each
/// node's terms in words and searched the cable's elements per node before, 10^12
/// steps here); this finishes in about a second (benchmarks/history/BENCHMARKS-2026-12.md, "check").
#[test]
fn check_takes_a_million_node_cable() {
    let dir = tempfile::tempdir().unwrap();
    let big = edit(&catenary(), "segments = 50", "segments = 1000000", "")
        .replace("initial = \"catenary\"", "initial = \"straight\"")
        .replace("duration = 60.0 ", "duration = 0.001 ")
        .replace("output_interval = 1.0 ", "output_interval = 0.001 ");
    // 5e12 node-steps: over the default budget (1e12) and refused, with its size.
    let (ok, err) = check(dir.path(), &big);
    assert!(!ok && err.contains("is 5.000e12 node-steps"), "{err}");
    let (ok, err) = cli(dir.path(), &big, &["check", "--limit", "node_steps=1e13"]);
    assert!(ok, "{err}");
}

#[test]
fn ends_against_the_seabed_and_the_surface() {
    let dir = tempfile::tempdir().unwrap();
    let c = catenary();
    let buried = edit(&c, "[-220.0, 0.0, -100.0]", "[-220.0, 0.0, -150.0]", "");
    refused(
        dir.path(),
        &buried,
        "cables[0] (\"line1\").start",
        "below the seabed",
    );
    let high = edit(&c, "[0.0, 0.0, -10.0]", "[0.0, 0.0, 500.0]", "");
    let (ok, err) = check(dir.path(), &high);
    assert!(
        err.contains("cables[0] (\"line1\").end") && err.contains("above the water surface"),
        "ok = {ok}: {err}"
    );
}

#[test]
fn unused_points_and_line_types_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let c = catenary();
    let fixed = format!("{c}\n[[points]]\nname = \"spare\"\nfixed = [5.0, 0.0, -20.0]\n\n[[line_types]]\nname = \"rope\"\ndiameter = 0.1\nmass_per_length = 8.0\nea = 1e8\n");
    let (ok, err) = check(dir.path(), &fixed);
    assert!(ok, "{err}");
    assert!(
        err.contains("points[0] (\"spare\"): no cable uses"),
        "{err}"
    );
    assert!(
        err.contains("line_types[1] (\"rope\"): no cable or net uses"),
        "{err}"
    );
    // A free point nothing holds: an error on that point, not on another cable.
    let free = format!("{c}\n[[points]]\nname = \"lost\"\nfree = [5.0, 0.0, -20.0]\nmass = 10.0\n");
    refused(dir.path(), &free, "points[0] (\"lost\")", "no cable uses");
}

#[test]
fn overflowing_inputs_name_their_field() {
    let c = catenary();
    for (from, to, field) in [
        (
            "ea = 6.2832e7 ",
            "ea = 1e308 ",
            "line_types[0] (\"wire\").ea",
        ),
        (
            "damping = 1.0e-5 ",
            "damping = 1e305 ",
            "line_types[0] (\"wire\").damping",
        ),
        (
            "mass_per_length = 5.0265",
            "mass_per_length = 1e307",
            "line_types[0] (\"wire\").mass_per_length",
        ),
        (
            "stiffness = 3.0e6 ",
            "stiffness = 1e308 ",
            "environment.seabed.stiffness",
        ),
        (
            "backend = \"auto\" ",
            "baumgarte_alpha = 1e308\nbackend = \"auto\" ",
            "simulation.baumgarte_alpha",
        ),
    ] {
        let (f, m) = parse_error(&edit(&c, from, to, ""));
        assert!(
            f.contains(field) && m.contains("overflows"),
            "{to}: {f}: {m}"
        );
    }
}

/// Finite inputs whose squares overflow f64 (the solvers square lengths and forces):
/// each is refused by name before the statics, which without these checks stopped on
/// "non-finite static force ... (a zero-length element?)" (found by mutating the
/// examples' numbers to 1e200 and -1e160), with the value or the product's factors.
#[test]
fn inputs_whose_squares_overflow_name_their_field() {
    let c = catenary();
    let point = "\n[[points]]\nname = \"buoy\"\nfixed = [0.0, 0.0, -5.0]\n";
    for (from, to, extra, field, what) in [
        (
            "gravity = 9.81",
            "gravity = 1e200",
            "",
            "environment.gravity",
            "1e200 m/s^2 is beyond 1e150",
        ),
        (
            "water_density = 1025.0",
            "water_density = 1e200",
            "",
            "environment.water_density",
            "1e200 kg/m^3",
        ),
        (
            "current = [0.0, 0.0, 0.0]",
            "current = [0.0, -1e160, 0.0]",
            "",
            "environment.current",
            "beyond 1e75 m/s",
        ),
        (
            "length = 250.0 ",
            "length = 1e200 ",
            "",
            "cables[0] (\"line1\").length",
            "1e200 m is beyond 1e150 m",
        ),
        (
            "[-220.0, 0.0, -100.0]",
            "[1e200, 0.0, -100.0]",
            "",
            "cables[0] (\"line1\").start",
            "a coordinate beyond 1e150 m",
        ),
        (
            "end = { fixed = [0.0, 0.0, -10.0] }",
            "end = { fixed = [0.0, 0.0, -1e160] }",
            "",
            "cables[0] (\"line1\").end",
            "a coordinate beyond 1e150 m",
        ),
        // A product: each factor in range, the weight beyond (and its factors named).
        (
            "mass_per_length = 5.0265",
            "mass_per_length = 1e149",
            "",
            "line_types[0] (\"wire\").mass_per_length",
            "mass_per_length 1e149 kg/m x length 2.5e2 m x gravity 9.81e0",
        ),
        (
            "cm = 0.2",
            "cm = 1e200",
            "",
            "line_types[0] (\"wire\").cm",
            "the added mass of a cable (cm 1e200",
        ),
        (
            "cm = 0.2",
            "cm = 0.2\ncat = 1e200",
            "",
            "line_types[0] (\"wire\").cat",
            "the tangential added mass of a cable (cat 1e200",
        ),
        (
            "end = { fixed = [0.0, 0.0, -10.0] }",
            "end = { point = \"buoy\" }",
            &format!("{point}mass = 1e200\n"),
            "points[0] (\"buoy\").mass",
            "weight (mass x gravity) is 9.81e200 N",
        ),
        (
            "end = { fixed = [0.0, 0.0, -10.0] }",
            "end = { fixed = [0.0, 0.0, -10.0], drag_area = 1e200 }",
            "",
            "cables[0] (\"line1\").end.drag_area",
            "drag (drag_area x water_density x speed^2)",
        ),
    ] {
        let (f, m) = parse_error(&edit(&c, from, to, extra));
        assert!(f.contains(field) && m.contains(what), "{to}: {f}: {m}");
    }
}

#[test]
fn a_straight_start_far_beyond_its_length_warns() {
    let dir = tempfile::tempdir().unwrap();
    // 250 m between ends 750 m apart: 200 % strain.
    let text = edit(
        &catenary(),
        "[-220.0, 0.0, -100.0]",
        "[-750.0, 0.0, -10.0]",
        "",
    )
    .replace("initial = \"catenary\"", "initial = \"straight\"");
    let (_, err) = check(dir.path(), &text);
    assert!(err.contains("200 % longer than its length"), "{err}");
}

#[test]
fn impossible_random_specs_are_errors() {
    let fleet = std::fs::read_to_string("examples/fleet.toml").unwrap();
    let (f, m) = parse_error(&edit(
        &fleet,
        "segments = 50",
        "segments = { random = [40, 60] }",
        "",
    ));
    assert!(
        f.ends_with("segments") && m.contains("cannot be random"),
        "{f}: {m}"
    );
    let (f, m) = parse_error(&edit(
        &fleet,
        "random = [245.0, 255.0]",
        "random = [255.0, 245.0]",
        "",
    ));
    assert!(
        f.ends_with("length.random") && m.contains("reversed"),
        "{f}: {m}"
    );
    // A range whose width overflows cannot be sampled (it panicked the random
    // generator before; found by the fuzz test).
    let (f, m) = parse_error(&edit(
        &fleet,
        "random = [245.0, 255.0]",
        "random = [-1e308, 1e308]",
        "",
    ));
    assert!(
        f.ends_with("length.random") && m.contains("too wide"),
        "{f}: {m}"
    );
}

fn array_text(start: &str, end: &str, extra: &str) -> String {
    let c = catenary();
    let head = &c[..c.find("[[cables]]").unwrap()];
    format!(
        "{head}{extra}\n[[cable_arrays]]\nname = \"a\"\ncount = 3\nline_type = \"wire\"\nlength = 250.0\nsegments = 10\nstart = {start}\nend = {end}\n"
    )
}

#[test]
fn end_keys_of_an_array_vary_as_written() {
    // An offset that varies inside an end: each cable gets its own.
    let text = array_text(
        "{ fixed = [0.0, 0.0, -100.0], offset = [[100.0, 0.0, 0.0], [-50.0, 86.6, 0.0], [-50.0, -86.6, 0.0]] }",
        "{ fixed = [0.0, 0.0, -10.0], offset = { from = [0.0, 0.0, 0.0], to = [0.0, 0.0, 4.0] } }",
        "",
    );
    let sc = parse(&text).unwrap();
    let ends: Vec<([f64; 3], [f64; 3])> = sc
        .model
        .cables
        .iter()
        .map(|c| {
            let (a, b) = (c.nodes[0], *c.nodes.last().unwrap());
            (sc.model.nodes[a].position, sc.model.nodes[b].position)
        })
        .collect();
    assert_eq!(ends[0].0, [100.0, 0.0, -100.0]);
    assert_eq!(ends[1].0, [-50.0, 86.6, -100.0]);
    assert_eq!(ends[2].0, [-50.0, -86.6, -100.0]);
    assert_eq!(
        [ends[0].1[2], ends[1].1[2], ends[2].1[2]],
        [-10.0, -8.0, -6.0]
    );
    // A position list and a mass ramp too.
    let text = array_text(
        "{ fixed = [[10.0, 0.0, -100.0], [20.0, 0.0, -100.0]] }",
        "{ free = [0.0, 0.0, -10.0], mass = [1.0, 2.0, 3.0] }",
        "",
    );
    let sc = parse(&text).unwrap();
    let c2 = &sc.model.cables[2];
    assert_eq!(sc.model.nodes[c2.nodes[0]].position, [10.0, 0.0, -100.0]);
    assert_eq!(sc.model.nodes[*c2.nodes.last().unwrap()].point.mass, 3.0);
}

#[test]
fn an_array_on_a_named_point_blames_the_field_at_fault() {
    let hub = "\n[[points]]\nname = \"hub\"\nfixed = [0.0, 0.0, -10.0]\n";
    // The other end's own offset list is fine with a point end.
    let ok = array_text(
        "{ fixed = [0.0, 0.0, -100.0], offset = [[100.0, 0.0, 0.0], [-50.0, 86.6, 0.0], [-50.0, -86.6, 0.0]] }",
        "{ point = \"hub\" }",
        hub,
    );
    let sc = parse(&ok).unwrap();
    assert_eq!(sc.model.cables.len(), 3);
    // The array's own offset would move the point end: blamed on the offset.
    let moved = format!("{ok}offset = [1.0, 0.0, 0.0]\n");
    let (f, m) = parse_error(&moved);
    assert!(
        f.ends_with("(\"a\").offset") && m.contains("named point"),
        "{f}: {m}"
    );
    // Mass on a point end was dropped without a word.
    let (f, m) = parse_error(&array_text(
        "{ fixed = [0.0, 0.0, -100.0] }",
        "{ point = \"hub\", mass = 5.0 }",
        hub,
    ));
    assert!(
        f.ends_with("end.mass") && m.contains("on the point"),
        "{f}: {m}"
    );
}

/// Each point-mass key on a `{ point = ... }` end of a `[[cables]]` entry: an error that
/// names the cable and the key (the point carries the mass; the key was dropped).
#[test]
fn mass_keys_on_a_point_end_name_the_cable_and_key() {
    let c = catenary();
    let point = "\n[[points]]\nname = \"buoy\"\nfixed = [0.0, 0.0, -5.0]\n";
    let (from, end) = c
        .lines()
        .find_map(|l| l.strip_prefix("end = ").map(|e| (l, e)))
        .expect("an end line");
    assert!(!end.contains("point"));
    for key in ["mass", "volume", "drag_area", "added_mass"] {
        let to = format!("end = {{ point = \"buoy\", {key} = 2.0 }}");
        let (f, m) = parse_error(&edit(&c, from, &to, point));
        assert!(
            f.starts_with("cables[0] (\"line1\")") && f.ends_with(&format!(".end.{key}")),
            "{key}: {f}: {m}"
        );
        assert!(m.contains("takes no point mass"), "{key}: {f}: {m}");
    }
    // Without the key the same end is accepted.
    let to = "end = { point = \"buoy\" }";
    parse(&edit(&c, from, to, point)).unwrap();
}

/// The rest of the sweep of the examples' numbers (1e200, -1e160, 1e-200): waves whose
/// kinematics overflow or underflow (a regular `height = 1e200` panicked in the
/// kinematics cache; the others went NaN at the first step), point and sinker masses,
/// positions beyond the blow-up distance, routes faster than `max_speed`. Each is
/// refused by `cablesim check` with the field and the reason, and never a panic.
#[test]
fn derived_kinematics_out_of_range_name_their_field() {
    let dir = tempfile::tempdir().unwrap();
    let read = |f: &str| std::fs::read_to_string(format!("examples/{f}")).unwrap();
    let train = "environment.waves.trains[0]";
    let cases: &[(&str, &str, &str, &str, &str)] = &[
        (
            "buoy_spread.toml",
            "height = 3.0 ",
            "height = 1e200 ",
            &format!("{train}.height"),
            "above 1e4 m/s, far beyond any sea",
        ),
        (
            "buoy_spread.toml",
            "height = 3.0 ",
            "height = 1e-200 ",
            &format!("{train}.height"),
            "overflow or underflow f64",
        ),
        (
            "buoy_spread.toml",
            "period = 12.0 ",
            "period = 1e-200 ",
            &format!("{train}.period"),
            "wave number inf rad/m",
        ),
        (
            "buoy_spread.toml",
            "period = 12.0 ",
            "period = 1e200 ",
            &format!("{train}.period"),
            "wave number 0e0 rad/m",
        ),
        (
            "net_cage_waves.toml",
            "height = 2.0 ",
            "height = 1e200 ",
            &format!("{train}.height"),
            "above 1e4 m/s, far beyond any sea",
        ),
        (
            "spread_mooring_waves.toml",
            "hs = 6.0 ",
            "hs = 1e200 ",
            &format!("{train}.hs"),
            "overflow or underflow f64",
        ),
        (
            "spread_mooring_waves.toml",
            "tp = 11.0 ",
            "tp = 1e200 ",
            &format!("{train}.tp"),
            "wave number",
        ),
        (
            "spread_mooring_waves.toml",
            "tp = 11.0 ",
            "tp = 1e-200 ",
            &format!("{train}.tp"),
            "",
        ),
        (
            "spread_mooring_waves.toml",
            "hs = 6.0 ",
            "hs = 1e-200 ",
            &format!("{train}.hs"),
            "overflow or underflow f64",
        ),
        (
            "spread_mooring_waves.toml",
            "ramp = 20.0 ",
            "ramp = 1e-200 ",
            "environment.waves.ramp",
            "use 0 for no ramp",
        ),
        (
            "buoy_spread.toml",
            "added_mass = 1.0 ",
            "added_mass = 1e200 ",
            "points[0] (\"buoy\").added_mass",
            "added mass's weight",
        ),
        (
            "net_cage.toml",
            "mass = 20.0,",
            "mass = 1e200,",
            "nets[0] (\"cage\").sinker.mass",
            "weight (mass x gravity)",
        ),
        (
            "net_cage.toml",
            "top = [0.0, 0.0, -0.5]",
            "top = [0.0, 2e7, -0.5]",
            "nets[0] (\"cage\").top",
            "1e7 m or more from the origin",
        ),
        (
            "catenary.toml",
            "[-220.0, 0.0, -100.0]",
            "[-1e7, 0.0, -100.0]",
            "cables[0] (\"line1\").start",
            "1e7 m or more from the origin",
        ),
        (
            "case2_straight.toml",
            "velocity = [2.0, 0.0, 0.0]",
            "velocity = [2.0, -1e160, 0.0]",
            "cables[0] (\"payout\").start.velocity",
            "more than sqrt(3) x simulation.max_speed",
        ),
        (
            "case2_circle.toml",
            "period = 62.8 }",
            "period = 1e-200 }",
            "cables[0] (\"payout\").start.period",
            "more than sqrt(3) x simulation.max_speed",
        ),
        (
            "case1_screw.toml",
            "advance = 62.8,",
            "advance = 1e200,",
            "cables[0] (\"towed\").start.advance",
            "more than sqrt(3) x simulation.max_speed",
        ),
    ];
    for (file, from, to, field, what) in cases {
        let text = edit(&read(file), from, to, "");
        let (ok, err) = check(dir.path(), &text);
        assert!(!ok, "{file}: {to}: accepted");
        assert!(!err.contains("panicked"), "{file}: {to}: {err}");
        assert!(
            err.contains(&format!("{field}:")) && err.contains(what),
            "{file}: {to}: expected {field}: {what}, got {err}"
        );
    }
}
