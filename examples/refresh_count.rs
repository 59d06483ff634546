//! The per-node refresh sum alone, for load-independent instruction counts: a
//! 200-component JONSWAP sea (Hs 6 m, Tp 10 s, 320 m depth) evaluated at nodes along a
//! line from 18 m to 320 m depth (the design-check chains' span), values alone or
//! values with their rates:
//!
//! `valgrind --tool=callgrind target/release/examples/refresh_count rates 2000`
//! (arguments: `values` or `rates`, node evaluations; the instructions of
//! `wave_kinematics_*columns` over the evaluations are the cost per node).
//!
//! Built with `cargo build --release --features bench --example refresh_count`: the
//! examples/*.rs are behind the `bench` feature, so `cargo test` does not build them.

use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::kinematics::{KinematicsScratch, WaveField};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::SeaState;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let rates = args.get(1).map(String::as_str) == Some("rates");
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let depth = 320.0;
    let comps = discretise(
        &Spectrum::Jonswap {
            hs: 6.0,
            tp: 10.0,
            gamma: 3.3,
        },
        &Discretisation {
            components: 200,
            direction: 0.0,
            spreading: None,
            seed: 1,
            stream: 0,
        },
        depth,
        9.81,
    );
    let sea = SeaState {
        components: comps,
        ..SeaState::still(depth)
    };
    let field = WaveField::new(&sea);
    let mut scratch = KinematicsScratch::default();
    let mut check = 0.0;
    for i in 0..n {
        let f = i as f64 / n as f64;
        let p = [900.0 * f, 3.0, -18.0 - (depth - 18.0) * f];
        let t = 12.3 + 1e-3 * i as f64;
        if rates {
            let (k, d) = field.kinematics_rates_with(p, [0.3, -0.2, 0.1], t, &mut scratch);
            check += k.a[0] + d.a[0];
        } else {
            check += field.kinematics_with(p, t, &mut scratch).a[0];
        }
    }
    println!("{check}");
}
