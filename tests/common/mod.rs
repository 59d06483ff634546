//! Model builders and helpers shared by the integration-test binaries (`tests/cpu`,
//! `tests/gpu`, `tests/cli`), each of which includes this file as `mod common`.
#![allow(dead_code)]

pub mod free_bodies;

use cablesim::model::{
    CableDef, Current, Environment, LineType, ModelDef, NodeDef, PointMass, Route, Seabed,
};

/// Euclidean distance of two points.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The catenary example's line type.
pub fn wire() -> LineType {
    LineType {
        name: "wire".into(),
        diameter: 0.04,
        mass_per_length: 5.0265,
        ea: 6.2832e7,
        damping: 1e-5,
        cn: 1.0,
        ct: 0.01,
        cm: 0.2,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    }
}

/// A light rope (stable steps of a fraction of a millisecond on 1-2 m elements).
pub fn rope() -> LineType {
    LineType {
        name: "rope".into(),
        diameter: 0.02,
        mass_per_length: 1.0,
        ea: 2.0e6,
        damping: 1e-4,
        cn: 1.2,
        ct: 0.01,
        cm: 1.0,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    }
}

/// Open water: gravity, sea water, no seabed.
pub fn water() -> Environment {
    Environment {
        gravity: 9.81,
        water_density: 1025.0,
        depth: f64::INFINITY,
        seabed: Seabed::default(),
    }
}

/// An environment without water or gravity (pure elastic dynamics).
pub fn vacuum() -> Environment {
    Environment {
        gravity: 0.0,
        water_density: 0.0,
        depth: f64::INFINITY,
        seabed: Seabed::default(),
    }
}

/// A single straight cable from `a` to `b` with `n` segments of unstretched length
/// `length / n`; `ra`, `rb` are the end routes (None = free), `mass_b` a point mass at b.
#[allow(clippy::too_many_arguments)]
pub fn straight_cable(
    env: Environment,
    lt: LineType,
    a: [f64; 3],
    b: [f64; 3],
    length: f64,
    n: usize,
    ra: Option<Route>,
    rb: Option<Route>,
    mass_b: PointMass,
    current: [f64; 3],
) -> ModelDef {
    let mut nodes = Vec::new();
    for k in 0..=n {
        let s = k as f64 / n as f64;
        nodes.push(NodeDef {
            position: [0, 1, 2].map(|d| a[d] + s * (b[d] - a[d])),
            point: if k == n { mass_b } else { PointMass::default() },
            route: if k == 0 {
                ra.clone()
            } else if k == n {
                rb.clone()
            } else {
                None
            },
            label: None,
        });
    }
    ModelDef {
        env,
        line_types: vec![lt],
        currents: vec![Current::uniform(current)],
        cables: vec![CableDef {
            name: "c0".into(),
            line_type: 0,
            nodes: (0..=n).collect(),
            l0: vec![length / n as f64; n],
            current: 0,
            output_positions: true,
            elem_lines: Vec::new(),
        }],
        nodes,
        clamps: Vec::new(),
        joints: Vec::new(),
        screens: Default::default(),
    }
}

/// A GPU context for a test, or `None` (after saying so loudly on stderr) when the
/// machine has no suitable adapter. With `CABLESIM_REQUIRE_GPU=1` a missing adapter
/// (or a missing `SHADER_F64` when `need_f64`) fails the test instead.
pub fn gpu_context(test: &str, need_f64: bool) -> Option<cablesim::gpu::GpuContext> {
    match cablesim::gpu::GpuContext::new(need_f64) {
        Ok(c) => {
            eprintln!("{test}: running on {}", c.describe());
            Some(c)
        }
        Err(e) => {
            let required = std::env::var("CABLESIM_REQUIRE_GPU").is_ok_and(|v| v == "1");
            if required {
                panic!("{test}: CABLESIM_REQUIRE_GPU=1 but {e}");
            }
            // Straight to the process's stderr: the test harness captures eprintln! of
            // passing tests, and a skip must be seen.
            use std::io::Write;
            let _ = writeln!(
                std::io::stderr(),
                "\n*** SKIPPED {test}: {e}\n*** (set CABLESIM_REQUIRE_GPU=1 to make this a failure; \
                 on Linux `apt-get install mesa-vulkan-drivers libvulkan1` gives lavapipe, \
                 then WGPU_BACKEND=vulkan)\n"
            );
            None
        }
    }
}

/// `n` members of a packed run (`sim::pack`): the RAO-driven spread mooring of
/// `examples/spread_mooring_waves.toml` with `segments` segments per line, each member
/// in its own sea (its own wave seed, Hs and current), as `(prefix, scenario)`.
pub fn wave_members(n: usize, segments: usize) -> Vec<(String, cablesim::scenario::Scenario)> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join("spread_mooring_waves.toml");
    let text = std::fs::read_to_string(&path).expect("the example");
    (0..n)
        .map(|j| {
            let t = text
                .replace("seed = 1\n", &format!("seed = {}\n", 11 + 7 * j))
                .replace("hs = 6.0 ", &format!("hs = {} ", 4.0 + 1.5 * j as f64))
                .replace(
                    "current = [0.6, 0.35, 0.0]",
                    &format!("current = [{}, 0.35, 0.0]", 0.2 + 0.3 * j as f64),
                )
                .replace("segments = 40", &format!("segments = {segments}"));
            assert_ne!(t, text);
            let sc = cablesim::scenario::Scenario::parse(&t, &path).expect("a member");
            (format!("m{j}"), sc)
        })
        .collect()
}

/// A copy of `examples/study_spread_mooring.toml` in `dir` with a short duration
/// (`duration` s, the first second discarded) and `seeds` seeds; returns its path.
pub fn short_study(dir: &std::path::Path, duration: f64, seeds: usize) -> std::path::PathBuf {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join("study_spread_mooring.toml");
    let text = std::fs::read_to_string(path).expect("the example");
    let t = text
        .replace(
            "duration = 40.0          # s (a study",
            &format!("duration = {duration}          # s (a study"),
        )
        .replace(
            "duration = 40.0          # s per member",
            &format!("duration = {duration}          # s per member"),
        )
        .replace("transient = 10.0", "transient = 1.0")
        .replace("seeds = 3\n", &format!("seeds = {seeds}\n"));
    assert_eq!(t.matches(&format!("duration = {duration} ")).count(), 2);
    let out = dir.join("study.toml");
    std::fs::write(&out, t).expect("writing the study");
    out
}

/// The example study with a violent sea state in which one member's line moves faster
/// than the base scenario's `max_speed` allows (the blow-up guard): that member, seed 1
/// of the violent sea state, fails at about 17 s with a node speed of 0.85 m/s; the
/// others stay under 0.5 m/s, well below the limit of 0.75 m/s.
pub fn study_with_a_failing_member(dir: &std::path::Path) -> std::path::PathBuf {
    let study = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join("study_spread_mooring.toml");
    let text = std::fs::read_to_string(study).unwrap();
    let text = text.replace(
        "output_interval = 0.5    # s: the study samples every channel at each output time",
        "output_interval = 0.5\nmax_speed = 0.75",
    );
    let cut = text.find("\n[study]\n").unwrap();
    let text = text[..cut].to_string()
        + r#"
[study]
seed = 2026
seeds = 3
duration = 20.0
transient = 10.0
sea_states = [
  { name = "calm", hs = 1.0, tp = 8.0 },
  { name = "violent", hs = 8.0, tp = 10.0 },
]
"#;
    assert!(text.contains("max_speed = 0.75"));
    let path = dir.join("failing.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `final_state.csv` of output directory `dir`: per cable (in file order) its name
/// and its nodes' `(position, velocity)`, m and m/s.
pub fn final_state(dir: &std::path::Path) -> Vec<(String, Vec<([f64; 3], [f64; 3])>)> {
    let path = dir.join("final_state.csv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("cable,node,x,y,z,vx,vy,vz"));
    let mut out: Vec<(String, Vec<([f64; 3], [f64; 3])>)> = Vec::new();
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let v: Vec<f64> = f[2..8].iter().map(|x| x.parse().unwrap()).collect();
        let node: usize = f[1].parse().unwrap();
        if out.last().is_none_or(|(n, _)| n != f[0]) {
            out.push((f[0].to_string(), Vec::new()));
        }
        let nodes = &mut out.last_mut().unwrap().1;
        assert_eq!(nodes.len(), node, "{}: nodes in order", path.display());
        nodes.push(([v[0], v[1], v[2]], [v[3], v[4], v[5]]));
    }
    out
}

/// The analytic water-acceleration case (docs/src/model/glmf.md, "External loads"):
/// one free horizontal element 2 m long along x, 5 m under the mean level of 200 m of
/// water, without drag, of a line heavier than the water it displaces (`mbar` 30 kg/m,
/// `rho A` 8.05 kg/m, `cm` and `cat` given), at rest and exactly unstretched, in a
/// regular wave (amplitude 1 m, period 6 s, travelling 0.5 rad off +x, its phase at the
/// element 1 rad at t = 0, when the water's acceleration there has all three
/// components). Returns the layout, the positions and the sea.
pub fn froude_krylov_case(
    cm: f64,
    cat: f64,
) -> (
    cablesim::model::Layout,
    Vec<[f64; 3]>,
    cablesim::sea::SeaState,
) {
    use cablesim::sea::dispersion::wave_number;
    let depth = 200.0;
    let env = Environment { depth, ..water() };
    let lt = LineType {
        name: "heavy".into(),
        diameter: 0.1,
        mass_per_length: 30.0,
        ea: 1e7,
        damping: 1e-4,
        cn: 0.0,
        ct: 0.0,
        cm,
        cat,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    let def = straight_cable(
        env,
        lt,
        [0.0, 0.0, -5.0],
        [2.0, 0.0, -5.0],
        2.0,
        1,
        None,
        None,
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, pos) = cablesim::model::Layout::build(&def).unwrap();
    let omega = 2.0 * std::f64::consts::PI / 6.0;
    let sea = cablesim::sea::SeaState {
        components: vec![cablesim::sea::WaveComponent {
            amplitude: 1.0,
            omega,
            k: wave_number(omega, depth, 9.81),
            direction: 0.5,
            phase: 1.0,
        }],
        ..cablesim::sea::SeaState::still(depth)
    };
    (lay, pos, sea)
}

/// What [`froude_krylov_case`] gives at t = 0 by the model's equations: the element's
/// total load (the water-acceleration load `rho A l0 [(1 + cm) P a + (1 + cat) t t^T a]`
/// plus its weight less buoyancy; no drag, no tension) and each node's acceleration
/// (its half load over its half mass block `(mbar l0 I + cm rho A l0 P + cat rho A l0
/// t t^T) / 2`, diagonal along x, y, z here), with `a` the mean of the water's
/// acceleration at the two nodes (Airy theory, `sea::kinematics`), and the largest of
/// `|a|` and `g` (the scale of the acceleration).
pub fn froude_krylov_expected(
    lay: &cablesim::model::Layout,
    pos: &[[f64; 3]],
    sea: &cablesim::sea::SeaState,
) -> ([f64; 3], [f64; 3], f64) {
    let lt = &lay.line_types[0];
    let (rho, g) = (lay.env.water_density, lay.env.gravity);
    let rho_a = rho * lt.area();
    let l0 = lay.elem_l0[0];
    let field = cablesim::sea::kinematics::WaveField::new(sea);
    let (ka, kb) = (field.kinematics(pos[0], 0.0), field.kinematics(pos[1], 0.0));
    let a: [f64; 3] = std::array::from_fn(|q| 0.5 * (ka.a[q] + kb.a[q]));
    // The tangent is +x: along is x, across are y and z.
    let wz = -(lt.mass_per_length - rho_a) * l0 * g;
    let force = [
        (1.0 + lt.cat) * rho_a * l0 * a[0],
        (1.0 + lt.cm) * rho_a * l0 * a[1],
        (1.0 + lt.cm) * rho_a * l0 * a[2] + wz,
    ];
    let (m_along, m_across) = (
        (lt.mass_per_length + lt.cat * rho_a) * l0,
        (lt.mass_per_length + lt.cm * rho_a) * l0,
    );
    let acc = [force[0] / m_along, force[1] / m_across, force[2] / m_across];
    let scale = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().max(g);
    (force, acc, scale)
}
