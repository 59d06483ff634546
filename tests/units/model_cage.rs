//! `src/model/cage.rs`: the enclosed volume against its closed forms, the collar's ring
//! and its joints, the flotation's hand calculation.

use cablesim::model::cage::*;
use cablesim::model::{LineType, ModelDef, NetShape, NetSpec, PointMass};
use std::f64::consts::PI;

fn cylinder(around: usize, rows: usize, radius: f64, depth: f64) -> NetSpec {
    NetSpec {
        name: "cage".into(),
        line_type: 0,
        current: 0,
        shape: NetShape::Cylinder {
            around,
            rows,
            radius,
            depth,
            top: [3.0, -2.0, 0.1],
        },
        segments: 1,
        sinker: PointMass {
            mass: 5.0,
            volume: 0.001,
            ..Default::default()
        },
        output_positions: false,
        screen: None,
    }
}

fn line(name: &str, d: f64, m: f64, ei: f64) -> LineType {
    LineType {
        name: name.into(),
        diameter: d,
        mass_per_length: m,
        ea: 1e6,
        damping: 0.0,
        cn: 1.0,
        ct: 0.01,
        cm: 1.0,
        cat: 0.0,
        ei,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    }
}

/// The knots of a net as generated enclose the polygon prism `n r^2 sin(2 pi / n) h / 2`
/// (to round-off), and so `pi r^2 h` within the polygon's discretisation error
/// `1 - sin(2 pi / n) / (2 pi / n)`: 0.64% at 32 knots around, 0.16% at 64.
#[test]
fn volume_of_the_undeformed_cage() {
    let (r, h) = (10.0, 8.0);
    for (n, bound) in [(32, 0.0065), (64, 0.0017)] {
        let spec = cylinder(n, 6, r, h);
        let knots: Vec<[f64; 3]> = (0..6)
            .flat_map(|row| (0..n).map(move |col| (row, col)))
            .map(|(row, col)| match spec.shape {
                NetShape::Cylinder { top, .. } => {
                    let a = 2.0 * PI * col as f64 / n as f64;
                    [
                        top[0] + r * a.cos(),
                        top[1] + r * a.sin(),
                        top[2] - h * row as f64 / 5.0,
                    ]
                }
                _ => unreachable!(),
            })
            .collect();
        let v = enclosed_volume(&knots, n);
        let prism = 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin() * h;
        assert!((v - prism).abs() < 1e-9 * prism, "{n}: {v} against {prism}");
        let cyl = PI * r * r * h;
        let err = (cyl - v) / cyl;
        assert!(err > 0.0 && err < bound, "{n}: {err}");
        // What add_cage records is the same volume.
        let mut def = ModelDef {
            line_types: vec![line("twine", 0.01, 0.1, 0.0)],
            ..Default::default()
        };
        let info = add_cage(&mut def, &spec, &CageSpec::default()).unwrap();
        assert!((info.reference_volume - prism).abs() < 1e-9 * prism);
    }
}

/// A cage squeezed to half its radius at the bottom row only: a frustum of pyramids
/// stacked (each band between rows a prismatoid), against the prismatoid formula.
#[test]
fn volume_of_a_tapered_cage() {
    let n = 24;
    let area = |r: f64| 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin();
    let radii = [10.0, 7.0];
    let h = 5.0;
    let knots: Vec<[f64; 3]> = (0..2)
        .flat_map(|row| (0..n).map(move |col| (row, col)))
        .map(|(row, col)| {
            let a = 2.0 * PI * col as f64 / n as f64;
            let r = radii[row];
            [r * a.cos(), r * a.sin(), -h * row as f64]
        })
        .collect();
    // A frustum of a regular pyramid: h / 3 (A1 + A2 + sqrt(A1 A2)).
    let (a1, a2) = (area(radii[0]), area(radii[1]));
    let expect = h / 3.0 * (a1 + a2 + (a1 * a2).sqrt());
    let v = enclosed_volume(&knots, n);
    assert!((v - expect).abs() < 1e-9 * expect, "{v} against {expect}");
}

/// With a collar the net's top row hangs from a ring of cables through its top knots
/// (none held), joined end to end; the ring's hinges run all round it, across the
/// knots too; the sinker tube hangs on its chains below the bottom row.
#[test]
fn the_net_hangs_from_the_collar_ring() {
    let (n, seg) = (12, 3);
    let mut def = ModelDef {
        line_types: vec![
            line("twine", 0.01, 0.1, 0.0),
            line("collar", 0.4, 30.0, 1e6),
            line("tube", 0.25, 60.0, 1e5),
            line("chain", 0.02, 8.0, 0.0),
        ],
        currents: vec![cablesim::model::Current::uniform([0.0; 3])],
        ..Default::default()
    };
    let spec = cylinder(n, 4, 10.0, 6.0);
    let cage = CageSpec {
        collar: Some(RingSpec {
            line_type: 1,
            segments: seg,
        }),
        shared_top: Vec::new(),
        sinker_tube: Some(SinkerTube {
            ring: RingSpec {
                line_type: 2,
                segments: 1,
            },
            radius: 10.5,
            chain_line_type: 3,
            chain_length: 2.0,
            every: 3,
            chain_segments: 2,
        }),
    };
    let info = add_cage(&mut def, &spec, &cage).unwrap();
    assert_eq!(info.collar.len(), n);
    assert_eq!(info.tube.len(), n);
    assert_eq!(info.chains.len(), n / 3);
    assert!(
        def.nodes.iter().all(|d| d.route.is_none()),
        "nothing is held"
    );
    // Each collar cable runs from top knot col to the next, through nodes on the circle.
    for col in 0..n {
        let c = &def.cables[info.collar.start + col];
        assert_eq!(c.nodes[0], def.cables[info.knot_cable(0, col)].nodes[0]);
        assert_eq!(
            *c.nodes.last().unwrap(),
            def.cables[info.knot_cable(0, (col + 1) % n)].nodes[0]
        );
        assert_eq!(c.l0.len(), seg);
        for &k in &c.nodes {
            let p = def.nodes[k].position;
            let r = ((p[0] - 3.0).powi(2) + (p[1] + 2.0).powi(2)).sqrt();
            assert!((r - 10.0).abs() < 1e-12 && (p[2] - 0.1).abs() < 1e-12);
        }
    }
    // Chains from bottom knots 0, 3, 6, 9 to the tube 2 m below at radius 10.5.
    for (k, ci) in info.chains.clone().enumerate() {
        let c = &def.cables[ci];
        assert_eq!(c.nodes[0], def.cables[info.knot_cable(3, 3 * k)].nodes[0]);
        let b = def.nodes[*c.nodes.last().unwrap()].position;
        assert!((b[2] - (0.1 - 6.0 - 2.0)).abs() < 1e-12);
        assert!(((b[0] - 3.0).hypot(b[1] + 2.0) - 10.5).abs() < 1e-12);
    }
    assert_eq!(def.joints.len(), 2 * n);
    // The packed layout's hinges: every node of both rings is one (EI > 0 on both
    // sides), the joints' included, and every hinge's elements meet at its node.
    let (lay, _) = cablesim::model::Layout::build(&def).unwrap();
    let hinges = lay.hinges();
    assert_eq!(hinges.len(), n * seg + n);
    for h in &hinges {
        let (p, q) = (h.prev as usize, h.next as usize);
        assert_eq!(lay.elem_b[p], lay.elem_a[q]);
    }
    // The flotation: the hand sum of the weights in water.
    let f = flotation(&def, &info).unwrap();
    let (g, rho) = (def.env.gravity, def.env.water_density);
    let area = |d: f64| PI * d * d / 4.0;
    let len = |r: std::ops::Range<usize>| -> f64 {
        def.cables[r].iter().map(|c| c.l0.iter().sum::<f64>()).sum()
    };
    let lc = len(info.collar.clone());
    let expect_load = 30.0 * g * lc
        + (0.1 - rho * area(0.01)) * g * len(info.twines.clone())
        + (60.0 - rho * area(0.25)) * g * len(info.tube.clone())
        + (8.0 - rho * area(0.02)) * g * len(info.chains.clone())
        + n as f64 * (5.0 - rho * 0.001) * g;
    assert!((f.load - expect_load).abs() < 1e-9 * expect_load);
    assert!((f.capacity - rho * g * area(0.4) * lc).abs() < 1e-9 * f.capacity);
    assert!((f.freeboard - 0.4 * (1.0 - expect_load / f.capacity)).abs() < 1e-12);
}

/// A pipe's line type: the wall's mass, EA and EI of a hollow section.
#[test]
fn pipe_line_type() {
    let p = Pipe {
        diameter: 0.4,
        wall: 0.024,
        density: 950.0,
        youngs_modulus: 1e9,
        flooded: false,
        ballast: 0.0,
        cn: 1.2,
        cm: 1.0,
    };
    let lt = p.line_type("c".into(), 1025.0);
    let d = 0.4 - 0.048;
    let a = PI / 4.0 * (0.16 - d * d);
    assert!((lt.mass_per_length - 950.0 * a).abs() < 1e-9);
    assert!((lt.ea - 1e9 * a).abs() < 1e-3);
    assert!((lt.ei - 1e9 * PI / 64.0 * (0.4f64.powi(4) - d.powi(4))).abs() < 1e-3);
    let flooded = Pipe {
        flooded: true,
        ballast: 15.0,
        ..p
    }
    .line_type("t".into(), 1025.0);
    assert!(
        (flooded.mass_per_length - (950.0 * a + 15.0 + 1025.0 * PI / 4.0 * d * d)).abs() < 1e-9
    );
}
