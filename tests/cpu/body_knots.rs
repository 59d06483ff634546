//! RAO body motion interpolated between knots (`body::rao`, `RaoMotion::eval`) against
//! the exact sum over the wave components (`RaoMotion::eval_exact`), on the design-check
//! platform: the synthetic RAO table of `examples/spread_mooring_rao.csv` in the
//! 200-component JONSWAP sea (Hs 9 m, Tp 13 s) of `examples/study_design_check.toml`,
//! through its 60 s ramp and past it.

use cablesim::body::rao::RAO_KNOT_TOLERANCE;
use cablesim::body::{Body, Dofs, Motion, RaoMotion};
use cablesim::model::Route;
use cablesim::scenario::Scenario;
use std::sync::Arc;

fn design_platform() -> Arc<Body> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join("study_design_check.toml");
    let sc = Scenario::load(path).unwrap();
    sc.model
        .nodes
        .iter()
        .find_map(|n| match &n.route {
            Some(Route::Body { body, .. }) => Some(body.clone()),
            _ => None,
        })
        .expect("a cable end on the platform")
}

fn rao(body: &Body) -> &RaoMotion {
    match &body.motion {
        Motion::Rao(m) => m,
        _ => panic!("the platform moves by RAOs"),
    }
}

/// Picks the displacements, rates or accelerations.
type Pick = fn(&Dofs) -> [f64; 6];

/// Per degree of freedom: (rms of the exact values, rms of the error, largest error),
/// for the values picked by `f`.
fn errors(exact: &[Dofs], got: &[Dofs], f: Pick) -> [(f64, f64, f64); 6] {
    std::array::from_fn(|k| {
        let n = exact.len() as f64;
        let (mut s, mut e, mut m) = (0.0, 0.0, 0.0f64);
        for (a, b) in exact.iter().zip(got) {
            let (x, y) = (f(a)[k], f(b)[k]);
            s += x * x;
            e += (x - y) * (x - y);
            m = m.max((x - y).abs());
        }
        ((s / n).sqrt(), (e / n).sqrt(), m)
    })
}

#[test]
fn interpolated_rao_motion_is_within_its_tolerance_of_the_exact_sum() {
    let body = design_platform();
    let m = rao(&body);
    let dt_b = m.knot_interval();
    eprintln!("knot interval {dt_b:.4} s, tolerance {RAO_KNOT_TOLERANCE:e}");
    assert!(dt_b.is_finite() && dt_b > 0.0);
    // Times off the knots, through the ramp and 40 minutes past it.
    let ts: Vec<f64> = (0..6000).map(|i| 0.4137 * i as f64 + 0.01).collect();
    let exact: Vec<Dofs> = ts.iter().map(|&t| m.eval_exact(t)).collect();
    let got: Vec<Dofs> = ts.iter().map(|&t| m.eval(t)).collect();
    let names = ["surge", "sway", "heave", "roll", "pitch", "yaw"];
    let kinds: [(&str, Pick); 3] = [
        ("value", |d| d.q),
        ("rate", |d| d.qd),
        ("acceleration", |d| d.qdd),
    ];
    for (kind, f) in kinds {
        for (k, (rms, rms_err, max_err)) in errors(&exact, &got, f).into_iter().enumerate() {
            eprintln!(
                "{} {kind}: rms {rms:.4e}, error rms {:.3e} max {:.3e} of it",
                names[k],
                rms_err / rms,
                max_err / rms
            );
            assert!(rms > 0.0, "{} {kind} does not move", names[k]);
            // The rule bounds the root-mean-square error; the largest stays within a
            // few times it (the components' errors do not all peak together).
            assert!(
                rms_err <= RAO_KNOT_TOLERANCE * rms,
                "{} {kind}: rms error {rms_err} of rms {rms}",
                names[k]
            );
            assert!(
                max_err <= 5.0 * RAO_KNOT_TOLERANCE * rms,
                "{} {kind}: largest error {max_err} of rms {rms}",
                names[k]
            );
        }
    }
}

#[test]
fn rao_motion_is_the_same_whatever_order_or_thread_asks() {
    // Studies are bit-reproducible for any thread or shard count: the interpolated
    // motion must not depend on which times were asked for before, nor by whom.
    let body = design_platform();
    let m = rao(&body);
    let ts: Vec<f64> = (0..3000).map(|i| 0.00731 * i as f64 * 7.0 + 55.0).collect();
    let ahead: Vec<Dofs> = ts.iter().map(|&t| m.eval(t)).collect();
    let fresh = m.clone();
    let back: Vec<Dofs> = ts.iter().rev().map(|&t| fresh.eval(t)).collect();
    assert!(ahead.iter().eq(back.iter().rev()));
    let fresh = m.clone();
    let threads: Vec<Dofs> = std::thread::scope(|s| {
        let hs: Vec<_> = ts
            .chunks(97)
            .map(|c| s.spawn(|| c.iter().map(|&t| fresh.eval(t)).collect::<Vec<_>>()))
            .collect();
        hs.into_iter().flat_map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(threads, ahead);
}
