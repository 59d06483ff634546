//! The model the benches step, shared by `benches/lib.rs` and `benches/gpu_vs_cpu.rs`.
#![allow(dead_code)]

use cablesim::model::{
    CableDef, Current, Environment, Layout, LineType, ModelDef, NodeDef, PointMass, Route,
};

/// `n_cables` copies of the catenary example's line (250 m, `segments` elements) on a
/// 50 m grid, anchor on the seabed and fairlead fixed, in a 0.5 m/s current, starting
/// straight (so drag, tension and seabed contact are all active).
pub fn fleet(n_cables: usize, segments: usize) -> (Layout, Vec<[f64; 3]>) {
    let lt = LineType {
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
    };
    let mut def = ModelDef {
        env: Environment::default(),
        line_types: vec![lt],
        currents: vec![Current::uniform([0.5, 0.0, 0.0])],
        ..Default::default()
    };
    for c in 0..n_cables {
        let y = 50.0 * c as f64;
        let a = [-220.0, y, -100.0];
        let b = [0.0, y, -10.0];
        let first = def.nodes.len();
        for k in 0..=segments {
            let s = k as f64 / segments as f64;
            let route = if k == 0 {
                Some(Route::Fixed { position: a })
            } else if k == segments {
                Some(Route::Fixed { position: b })
            } else {
                None
            };
            def.nodes.push(NodeDef {
                position: [0, 1, 2].map(|d| a[d] + s * (b[d] - a[d])),
                point: PointMass::default(),
                route,
                label: None,
            });
        }
        def.cables.push(CableDef {
            name: format!("c{c}"),
            line_type: 0,
            nodes: (first..=first + segments).collect(),
            l0: vec![250.0 / segments as f64; segments],
            current: 0,
            output_positions: false,
            elem_lines: Vec::new(),
        });
    }
    Layout::build(&def).unwrap()
}
