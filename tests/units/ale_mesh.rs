//! `src/ale/mesh.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::ale::{Winch, WinchEnd};
use cablesim::math::V3;
use cablesim::model::{CableDef, Layout, ModelDef, NodeDef, PointMass};
use cablesim::testing::ale_mesh::*;
use std::sync::Arc;

type V = V3<f64>;
use cablesim::ale::PayoutSchedule;
use cablesim::model::{Current, Environment, LineType, Route};

fn cable(def: &mut ModelDef, name: &str, x: f64, n: usize, top_route: bool) -> usize {
    let first = def.nodes.len();
    for k in 0..=n {
        let p = [x, 0.0, -5.0 - 5.0 * k as f64];
        def.nodes.push(NodeDef {
            position: p,
            point: PointMass::default(),
            route: (k == 0 && top_route).then_some(Route::Fixed { position: p }),
            label: None,
        });
    }
    def.cables.push(CableDef {
        name: name.into(),
        line_type: 0,
        nodes: (first..=first + n).collect(),
        l0: vec![5.0; n],
        current: def.cables.len() % 2,
        output_positions: false,
        elem_lines: Vec::new(),
    });
    def.cables.len() - 1
}

/// Splicing the remeshed cables into the layout gives exactly the layout a full
/// build of the edited description gives, state included, through insertions and
/// deletions at either end, with plain cables and a network in between.
#[test]
fn splice_equals_a_full_rebuild() {
    let lt = LineType {
        name: "w".into(),
        diameter: 0.04,
        mass_per_length: 5.0,
        ea: 6e7,
        damping: 0.0,
        cn: 1.0,
        ct: 0.0,
        cm: 0.0,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    let mut def = ModelDef {
        env: Environment::default(),
        line_types: vec![lt],
        currents: vec![
            Current::uniform([0.1, 0.0, 0.0]),
            Current::uniform([0.0, 0.2, 0.0]),
        ],
        ..Default::default()
    };
    let a = cable(&mut def, "a", 0.0, 4, true);
    let _plain = cable(&mut def, "plain", 10.0, 3, true);
    let b = cable(&mut def, "b", 20.0, 5, false);
    // b is held at its far (end) node: the winch there.
    let last = *def.cables[b].nodes.last().unwrap();
    def.nodes[last].route = Some(Route::Fixed {
        position: def.nodes[last].position,
    });
    // A small network: two cables sharing a knot.
    let n1 = cable(&mut def, "n1", 30.0, 2, true);
    let knot = *def.cables[n1].nodes.last().unwrap();
    let n2 = cable(&mut def, "n2", 40.0, 2, true);
    let k2 = def.cables[n2].nodes.len() - 1;
    def.cables[n2].nodes[k2] = knot;
    let c = cable(&mut def, "c", 50.0, 3, true);
    let winch = |cable, end, rates: &[(f64, f64)]| Winch {
        cable,
        end,
        schedule: Arc::new(PayoutSchedule::rates(rates).unwrap()),
        drum_length: 1e3,
        element_length: 5.0,
    };
    let winches = vec![
        winch(
            a,
            WinchEnd::Start,
            &[(0.0, 1.0), (20.0, 1.0), (20.0, -1.3), (40.0, -1.3)],
        ),
        winch(
            b,
            WinchEnd::End,
            &[(0.0, -0.7), (10.0, -0.7), (10.0, 1.1), (40.0, 1.1)],
        ),
        winch(c, WinchEnd::Start, &[(0.0, 0.37)]),
    ];
    let (lay0, pos, packed) = Layout::build_indexed(&def).unwrap();
    let mut ale = AleState::new(def, winches, packed).unwrap();
    ale.index(&lay0);
    let mut lay = lay0;
    let mut r: Vec<V> = pos.iter().map(|p| V::from_f64(*p)).collect();
    let mut v: Vec<V> = (0..r.len())
        .map(|i| V::new(i as f64, -(i as f64), 0.5))
        .collect();
    let mut events = 0;
    for k in 1..=4000 {
        let t = k as f64 * 0.01;
        // Move the state so positions and velocities carry through.
        for (i, x) in r.iter_mut().enumerate() {
            x.x += 1e-3 * (i as f64).sin();
        }
        if !ale.needs_action(t) {
            continue;
        }
        assert!(ale.remesh_in_place(t, &mut lay, &mut r, &mut v).unwrap());
        events += 1;
        let (full, fpos, fpacked) = Layout::build_indexed(&ale.def).unwrap();
        assert!(
            lay == full,
            "t = {t}: the spliced layout differs from a full build"
        );
        assert_eq!(ale.packed_of_def, fpacked, "t = {t}");
        for (i, p) in fpos.iter().enumerate() {
            assert_eq!(r[i].to_f64(), *p, "t = {t}: node {i}");
        }
        assert_eq!(r.len(), v.len());
    }
    let (ins, del): (u64, u64) = ale
        .winches
        .iter()
        .fold((0, 0), |s, (_, tr)| (s.0 + tr.inserted, s.1 + tr.deleted));
    assert!(
        events > 10 && ins > 5 && del > 5,
        "{events} events, {ins} insertions, {del} deletions"
    );
}
