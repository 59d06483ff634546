//! `src/model/net.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::model::net::*;
use cablesim::model::{ModelDef, PointMass};

#[test]
fn cylinder_is_closed_and_held_at_the_top() {
    let mut def = ModelDef::default();
    let spec = NetSpec {
        name: "cage".into(),
        line_type: 0,
        current: 0,
        shape: NetShape::Cylinder {
            around: 12,
            rows: 5,
            radius: 10.0,
            depth: 8.0,
            top: [1.0, 2.0, -1.0],
        },
        segments: 3,
        sinker: PointMass {
            mass: 4.0,
            ..Default::default()
        },
        output_positions: false,
        screen: None,
    };
    let n = add_net(&mut def, &spec).unwrap();
    assert_eq!(n, 12 * 5 + 12 * 4);
    assert_eq!(def.nodes.len(), 12 * 5 + n * 2);
    let held = def.nodes.iter().filter(|d| d.route.is_some()).count();
    let sinkers = def.nodes.iter().filter(|d| d.point.mass == 4.0).count();
    assert_eq!((held, sinkers), (12, 12));
    // Every knot is on the cylinder; twines join neighbours at their length.
    for d in &def.nodes[..60] {
        let r = ((d.position[0] - 1.0).powi(2) + (d.position[1] - 2.0).powi(2)).sqrt();
        assert!((r - 10.0).abs() < 1e-12);
    }
    let chord = 2.0 * 10.0 * (std::f64::consts::PI / 12.0).sin();
    for c in &def.cables {
        let total: f64 = c.l0.iter().sum();
        let expect = if c.name.contains(".h") { chord } else { 2.0 };
        assert!((total - expect).abs() < 1e-12, "{}: {total}", c.name);
    }
    // The ring closes: the last twine of a row ends at the row's first knot.
    let last = def.cables.iter().find(|c| c.name == "cage.h0.11").unwrap();
    assert_eq!(*last.nodes.last().unwrap(), 0);
    assert!(add_net(
        &mut def,
        &NetSpec {
            shape: NetShape::Panel {
                columns: 1,
                rows: 3,
                width: 1.0,
                depth: 1.0,
                top: [0.0; 3]
            },
            ..spec
        }
    )
    .unwrap_err()
    .to_string()
    .contains("net 'cage': needs at least 2 knots across"));
}
