//! Scenario files: the example parses, and bad input gives a clear error naming the
//! file, the field and the problem (never a panic, never a partial run).

use cablesim::error::Error;
use cablesim::scenario::Scenario;
use std::path::Path;
use std::process::Command;

const EXAMPLE: &str = include_str!("../../examples/catenary.toml");

fn parse(text: &str) -> Result<Scenario, Error> {
    Scenario::parse(text, Path::new("/tmp/case.toml"))
}

/// Asserts `text` fails with an error whose field contains `field` and whose message
/// contains `msg`.
fn fails(text: &str, field: &str, msg: &str) {
    match parse(text) {
        Ok(_) => panic!("expected an error for field {field}"),
        Err(Error::Scenario {
            path,
            field: f,
            message,
        }) => {
            assert_eq!(path, Path::new("/tmp/case.toml"));
            assert!(
                f.contains(field),
                "field `{f}` should name `{field}` (message: {message})"
            );
            assert!(
                message.contains(msg),
                "message `{message}` should say `{msg}`"
            );
        }
        Err(e) => panic!("wrong error kind: {e}"),
    }
}

#[test]
fn example_parses() {
    let sc = parse(EXAMPLE).unwrap();
    assert_eq!(sc.model.cables.len(), 1);
    assert_eq!(sc.model.cables[0].l0.len(), 50);
    assert!((sc.model.cables[0].l0.iter().sum::<f64>() - 250.0).abs() < 1e-9);
    assert_eq!(sc.model.env.depth, 100.0);
}

#[test]
fn missing_field_is_named() {
    fails(
        &EXAMPLE.replace("length = 250.0", ""),
        "cables[0]",
        "missing field `length`",
    );
    fails(
        &EXAMPLE.replace("ea = 6.2832e7", ""),
        "line_types[0]",
        "missing field `ea`",
    );
    fails(
        &EXAMPLE.replace("output_interval = 1.0", ""),
        "simulation",
        "missing field `output_interval`",
    );
}

#[test]
fn negative_length_is_refused() {
    fails(
        &EXAMPLE.replace("length = 250.0", "length = -250.0"),
        "cables[0] (\"line1\").length",
        "must be positive",
    );
    fails(
        &EXAMPLE.replace("segments = 50", "segments = 0"),
        "segments",
        "from 1 to",
    );
    fails(
        &EXAMPLE.replace("diameter = 0.04", "diameter = -0.04"),
        "line_types[0] (\"wire\").diameter",
        "positive",
    );
}

#[test]
fn tangential_added_mass_is_read_and_checked() {
    // Default 0 (as MoorDyn's CaAx), given as `cat`.
    assert_eq!(parse(EXAMPLE).unwrap().model.line_types[0].cat, 0.0);
    let sc = parse(&EXAMPLE.replace("cm = 0.2", "cm = 0.2\ncat = 0.5")).unwrap();
    assert_eq!(sc.model.line_types[0].cat, 0.5);
    fails(
        &EXAMPLE.replace("cm = 0.2", "cm = 0.2\ncat = -0.5"),
        "line_types[0] (\"wire\").cat",
        "must not be negative",
    );
    fails(
        &EXAMPLE.replace("cm = 0.2", "cm = 0.2\ncat = nan"),
        "line_types[0] (\"wire\").cat",
        "finite",
    );
    fails(
        &EXAMPLE.replace("cm = 0.2", "cm = 0.2\ncat = inf"),
        "line_types[0] (\"wire\").cat",
        "finite",
    );
}

#[test]
fn unknown_line_type_lists_known_ones() {
    fails(
        &EXAMPLE.replace("line_type = \"wire\"", "line_type = \"chain\""),
        "line_type",
        "unknown line type \"chain\" (defined: wire)",
    );
}

#[test]
fn nan_and_inf_are_refused() {
    fails(
        &EXAMPLE.replace("ea = 6.2832e7", "ea = nan"),
        "ea",
        "finite",
    );
    fails(
        &EXAMPLE.replace(
            "end = { fixed = [0.0, 0.0, -10.0] }",
            "end = { fixed = [0.0, nan, -10.0] }",
        ),
        "end.fixed[1]",
        "finite",
    );
    fails(
        &EXAMPLE.replace("duration = 60.0", "duration = inf"),
        "simulation.duration",
        "finite",
    );
    fails(
        &EXAMPLE.replace("current = [0.0, 0.0, 0.0]", "current = [0.0, 0.0, nan]"),
        "current[2]",
        "finite",
    );
}

#[test]
fn bad_keys_and_values_are_named() {
    fails(
        &EXAMPLE.replace("cm = 0.2", "cm = 0.2\ncolour = 3"),
        "line_types[0]",
        "unknown field `colour`",
    );
    fails(
        &EXAMPLE.replace("dt = \"auto\"", "dt = \"fast\""),
        "simulation.dt",
        "\"auto\" or a step",
    );
    fails(
        &EXAMPLE.replace("backend = \"auto\"", "backend = \"tpu\""),
        "simulation.backend",
        "auto, cpu or gpu",
    );
    fails(
        &EXAMPLE.replace("initial = \"catenary\"", "initial = \"wavy\""),
        "initial",
        "catenary",
    );
    fails(
        &EXAMPLE.replace("start = { fixed", "start = { fixd"),
        "start",
        "needs one of",
    );
    fails(
        &EXAMPLE.replace(
            "end = { fixed = [0.0, 0.0, -10.0] }",
            "end = { fixed = [0.0, 0.0, -10.0], colour = 1 }",
        ),
        "end.colour",
        "unknown key",
    );
    fails(
        &EXAMPLE.replace("length = 250.0", "length = \"long\""),
        "cables[0].length",
        "invalid type",
    );
}

fn with_route_file(rows: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("fairlead.csv"), rows).unwrap();
    let text = EXAMPLE.replace(
        "end = { fixed = [0.0, 0.0, -10.0] }",
        "end = { route = \"table\", file = \"fairlead.csv\" }",
    );
    (dir, text)
}

#[test]
fn route_file_is_read_relative_to_the_scenario() {
    let (dir, text) = with_route_file("t,x,y,z\n0,0,0,-10\n10,5,0,-10\n");
    let sc = Scenario::parse(&text, &dir.path().join("s.toml")).unwrap();
    let route = sc.model.nodes.iter().find_map(|n| match &n.route {
        Some(r @ cablesim::model::Route::Table { .. }) => Some(r.clone()),
        _ => None,
    });
    let st = route.expect("a table route").eval(5.0);
    assert_eq!(st.r, [2.5, 0.0, -10.0]);
}

#[test]
fn route_file_errors_name_the_line() {
    for (rows, msg) in [
        (
            "t,x,y,z\n0,0,0,-10\n1,abc,0,-10\n",
            "line 3, column x: `abc` is not a finite number",
        ),
        ("t,x,y,z\n0,0,0,-10\n1,0,0\n", "line 3: expected 4 values"),
        (
            "t,x,y,z\n0,0,0,-10\n0,1,0,-10\n",
            "line 3: time 0 does not increase",
        ),
        ("time,x,y,z\n0,0,0,-10\n", "header must be `t,x,y,z`"),
        ("t,x,y,z\n", "no rows"),
        ("t,x,y,z\n0,0,NaN,-10\n", "not a finite number"),
    ] {
        let (dir, text) = with_route_file(rows);
        match Scenario::parse(&text, &dir.path().join("s.toml")) {
            Err(Error::Scenario { field, message, .. }) => {
                assert!(field.contains("end.file"), "{field}");
                assert!(
                    message.contains(msg) && message.contains("fairlead.csv"),
                    "`{message}` should say `{msg}`"
                );
            }
            other => panic!("expected an error for {rows:?}, got {other:?}"),
        }
    }
    let text = EXAMPLE.replace(
        "end = { fixed = [0.0, 0.0, -10.0] }",
        "end = { route = \"table\", file = \"missing.csv\" }",
    );
    match parse(&text) {
        Err(Error::Scenario { message, .. }) => {
            assert!(message.contains("cannot read route file"), "{message}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn cli_check_fails_with_the_field_and_runs_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(&file, EXAMPLE.replace("length = 250.0", "length = -1.0")).unwrap();
    let bin = env!("CARGO_BIN_EXE_cablesim");
    let out = Command::new(bin).arg("check").arg(&file).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml")
            && err.contains("cables[0] (\"line1\").length")
            && err.contains("must be positive"),
        "{err}"
    );
    // `run` refuses too, before writing anything.
    let out_dir = dir.path().join("out");
    let out = Command::new(bin)
        .arg("run")
        .arg(&file)
        .arg("--out")
        .arg(&out_dir)
        .arg("-q")
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(!out_dir.exists(), "no partial run");
    // And the good example checks out.
    let out = Command::new(bin)
        .arg("check")
        .arg("examples/catenary.toml")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn net_panel_shares_knots_between_cables_and_holds_still() {
    use cablesim::cpu::CpuSolver;
    use cablesim::options::SolverOptions;
    let sc = Scenario::load("examples/net_panel.toml").unwrap();
    let (lay, pos, residual) = cablesim::sim::prepare(&sc).unwrap();
    // 16 knots shared by 24 two-segment cables: 16 + 24 interior nodes, one block.
    assert_eq!(lay.n_nodes(), 40);
    assert_eq!(lay.blocks.len(), 1);
    assert!(!lay.blocks[0].is_chain);
    let knot = lay.cables[0].nodes[2]; // h00 ends at k10 ...
    assert_eq!(knot, lay.cables[2].nodes[0]); // ... where h10 starts
    assert!(residual < 1e-4, "relaxation residual {residual} N");
    // The current pushes the hanging panel downstream (+y).
    let sinker = lay.cables.iter().find(|c| c.name == "v02").unwrap().nodes[2] as usize;
    assert!(pos[sinker][1] > 0.5, "sinker at {:?}", pos[sinker]);
    let mut s = CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            dt: 5e-4,
            ..Default::default()
        },
    );
    s.advance(4000).unwrap();
    let moved =
        s.r.iter()
            .zip(&pos)
            .map(|(r, p)| {
                (r.x - p[0])
                    .abs()
                    .max((r.y - p[1]).abs())
                    .max((r.z - p[2]).abs())
            })
            .fold(0.0, f64::max);
    assert!(moved < 1e-6, "the relaxed net moved {moved} m in 2 s");
}

#[test]
fn point_references_are_checked() {
    let net = include_str!("../../examples/net_panel.toml");
    fails(
        &net.replace("end = { point = \"k10\" }", "end = { point = \"k99\" }"),
        "end.point",
        "unknown point \"k99\"",
    );
    fails(
        &net.replacen("name = \"k10\"", "name = \"k00\"", 1),
        "points[1]",
        "duplicate point name",
    );
    fails(
        &net.replacen(
            "fixed = [0.0, 0.0, -2.0]",
            "fixed = [0.0, 0.0, -2.0]\nfree = [0.0, 0.0, -2.0]",
            1,
        ),
        "points[0]",
        "only one of",
    );
}

#[test]
fn cable_arrays_expand_with_variations_and_placement() {
    let text = include_str!("../../examples/fleet.toml");
    let a = parse(text).unwrap();
    let b = parse(text).unwrap();
    assert_eq!(a.model.cables.len(), 1000);
    assert_eq!(a.model.cables[41].name, "mooring_41");
    // Random lengths: in range, reproducible from the seed, not all equal.
    let lengths: Vec<f64> = a.model.cables.iter().map(|c| c.l0.iter().sum()).collect();
    let again: Vec<f64> = b.model.cables.iter().map(|c| c.l0.iter().sum()).collect();
    assert_eq!(lengths, again);
    assert!(lengths.iter().all(|l| (245.0..255.0).contains(l)));
    assert!(lengths.iter().any(|l| (l - lengths[0]).abs() > 1.0));
    // Each cable has its own current, drawn per component in range.
    let cur = |i: usize| a.model.currents[a.model.cables[i].current].table[0].1;
    assert!((0..1000).all(|i| (0.0..0.8).contains(&cur(i)[0]) && (-0.3..0.3).contains(&cur(i)[1])));
    assert_ne!(cur(0), cur(1));
    // Grid: 40 columns 300 m apart in x, rows 100 m apart in y; cable 41 is row 1, column 1.
    let anchor = a.model.nodes[a.model.cables[41].nodes[0]]
        .route
        .clone()
        .unwrap()
        .eval(0.0)
        .r;
    assert_eq!(anchor, [-220.0 + 300.0, 100.0, -100.0]);
    let fairlead = a.model.nodes[*a.model.cables[41].nodes.last().unwrap()].position;
    assert_eq!(fairlead, [300.0, 100.0, -10.0]);
    // Positions are not written for so many cables unless asked.
    assert!(a.model.cables.iter().all(|c| !c.output_positions));
}

#[test]
fn cable_array_errors_are_named() {
    let text = include_str!("../../examples/fleet.toml");
    fails(
        &text.replace("count = 1000", "count = 0"),
        "cable_arrays[0] (\"mooring\").count",
        "integer from 1",
    );
    fails(
        &text.replace("seed = 7", "seed = 7\ncolour = 1"),
        "cable_arrays[0] (\"mooring\").colour",
        "unknown key",
    );
    fails(
        &text.replace(
            "length = { random = [245.0, 255.0] }",
            "length = { random = 3 }",
        ),
        "length",
        "{ random = [low, high] }",
    );
    fails(
        &text.replace(
            "length = { random = [245.0, 255.0] }",
            "length = { from = -1.0, to = 10.0 }",
        ),
        "cable_arrays[0] (\"mooring\") cable 0 (\"mooring_0\").length",
        "must be positive",
    );
    fails(
        &text.replace(
            "line_type = \"wire\"\nlength",
            "line_type = \"rope\"\nlength",
        ),
        "mooring_0",
        "unknown line type \"rope\"",
    );
}

#[test]
fn a_line_type_from_a_material_and_a_nominal_size() {
    let text = EXAMPLE.replace(
        "diameter = 0.04",
        "material = \"chain_studless\"\nnominal_diameter = 0.076\ndiameter = 0.04",
    );
    // Given values win over the material's; the rest come from the table.
    let sc = parse(&text.replace("ea = 6.2832e7", "")).unwrap();
    let lt = &sc.model.line_types[0];
    assert_eq!(lt.diameter, 0.04);
    let d2 = 0.076f64 * 0.076;
    assert!(
        (lt.ea - (85.6e9 * d2 - 3.93e7 * d2 * 0.076)).abs() < 1e-3,
        "{}",
        lt.ea
    );
    fails(
        &EXAMPLE.replace("diameter = 0.04", "material = \"chain\""),
        "line_types[0] (\"wire\").nominal_diameter",
        "is required with `material`",
    );
    fails(
        &EXAMPLE.replace(
            "diameter = 0.04",
            "material = \"kevlar\"\nnominal_diameter = 0.05",
        ),
        "line_types[0]",
        "unknown variant `kevlar`",
    );
}
