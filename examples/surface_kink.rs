//! Why the kinematics cache needs 0.3 of its rule near the surface (issue 8): the rope of
//! `tests/cpu/waves_steppers.rs` (`cached_kinematics_give_the_exact_end_force`: 80 m
//! of rope in 20 elements from the seabed at 50 m to a fairlead held at `zf`, a
//! 200-component JONSWAP sea, Hs 4 m, Tp 9 s) run with the cache and with exact
//! evaluation side by side, reporting
//!
//! - the fairlead force of the cached run against the exact run's (largest difference
//!   over the largest force, as the test measures it);
//! - the cache's own interpolation error, node by node and refresh interval by interval:
//!   a cache of the solver's band 0 clock fed the exact run's node positions and
//!   velocities (every 4 steps, so its refreshes fall on the grid as the solver's do),
//!   its interpolated water acceleration against exact evaluation at the same points
//!   and times, over the rms acceleration of the sea at the mean level `sqrt(m4)`; each
//!   (interval, node) classed as *crossing* (the node's submergence `eta - z` changed
//!   sign within the interval: the surface went over it or uncovered it), *dry* (above
//!   the surface throughout) or *wet* (under it throughout).
//! - an *oracle*: the same intervals interpolated from the values and rates at the
//!   nodes' actual states at both ends (the interpolation's error alone along the path
//!   they took), and the prediction's largest miss of the actual position at `t1`;
//! - *replicas* of the cache on the exact run's trajectory with other path predictions
//!   (the node's acceleration at the refresh; and its jerk): remedy (c) of issue 8.
//!
//! Arguments: `wheeler|constant` (the stretching), `zf` (m, the fairlead's height),
//! `steps` (of 2e-4 s), optionally a CSV path for the time series (time, force
//! difference, nodes above the surface, largest acceleration error of any node; `-`:
//! none) and the start-up ramp's duration, s (4 as the test; 0: no ramp).
//! The factor on the rule near the surface is the library's
//! (`sea::schedule::surface_factor`): 0.3 unless `CABLESIM_EXPERIMENT_SURFACE_FACTOR`
//! says otherwise, e.g.
//!
//! `CABLESIM_EXPERIMENT_SURFACE_FACTOR=1.0 target/release/examples/surface_kink wheeler -1 100000`
//!
//! Built with `cargo build --release --features bench --example surface_kink`.

use cablesim::cpu::CpuSolver;
use cablesim::model::{
    CableDef, Current, Environment, Layout, LineType, ModelDef, NodeDef, PointMass, Route, Seabed,
};
use cablesim::options::SolverOptions;
use cablesim::sea::cache::WaveCache;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::kinematics::WaveField;
use cablesim::sea::schedule::{surface_factor, RefreshClock};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaSet, SeaState, Stretching};
use cablesim::statics::{relax, RelaxOptions};
use std::io::Write;

const DEPTH: f64 = 50.0;
const DT: f64 = 2e-4;
/// Steps between samples of the cache's error (a divisor of the grid's steps).
const SAMPLE: u64 = 4;
/// Steps between samples of the fairlead force (as the test).
const EVERY: u64 = 500;

fn sea(stretching: Stretching, ramp: f64) -> SeaState {
    let spectrum = Spectrum::Jonswap {
        hs: 4.0,
        tp: 9.0,
        gamma: 3.3,
    };
    let d = Discretisation {
        components: 200,
        direction: 0.3,
        spreading: None,
        seed: 7,
        stream: 0,
    };
    SeaState {
        components: discretise(&spectrum, &d, DEPTH, 9.81),
        depth: DEPTH,
        stretching,
        ramp_duration: ramp,
        cache_tolerance: 1e-3,
    }
}

/// The test's rope (`moored_rope_at` of tests/cpu/waves_steppers.rs).
fn rope(zf: f64) -> (Layout, Vec<[f64; 3]>) {
    let env = Environment {
        gravity: 9.81,
        water_density: 1025.0,
        depth: DEPTH,
        seabed: Seabed::default(),
    };
    let lt = LineType {
        name: "rope".into(),
        diameter: 0.05,
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
    };
    let (a, b, n, length) = ([-60.0, 0.0, -DEPTH], [0.0, 0.0, zf], 20usize, 80.0);
    let nodes = (0..=n)
        .map(|k| {
            let s = k as f64 / n as f64;
            NodeDef {
                position: [0, 1, 2].map(|d| a[d] + s * (b[d] - a[d])),
                point: PointMass::default(),
                route: match k {
                    0 => Some(Route::Fixed { position: a }),
                    k if k == n => Some(Route::Fixed { position: b }),
                    _ => None,
                },
                label: None,
            }
        })
        .collect();
    let def = ModelDef {
        env,
        line_types: vec![lt],
        currents: vec![Current::uniform([0.2, 0.0, 0.0])],
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
    };
    let (lay, mut pos) = Layout::build(&def).unwrap();
    relax(&lay, &mut pos, &RelaxOptions::default()).unwrap();
    (lay, pos)
}

fn norm(f: [f64; 3]) -> f64 {
    (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt()
}

/// Per (interval, node) class: count, sum of squared largest errors, largest error.
#[derive(Default, Clone, Copy)]
struct Class {
    n: u64,
    sq: f64,
    max: f64,
}

impl Class {
    fn add(&mut self, e: f64) {
        self.n += 1;
        self.sq += e * e;
        self.max = self.max.max(e);
    }
    fn rms(&self) -> f64 {
        if self.n == 0 {
            0.0
        } else {
            (self.sq / self.n as f64).sqrt()
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let stretching = match args.get(1).map(String::as_str) {
        Some("constant") => Stretching::Constant,
        _ => Stretching::Wheeler,
    };
    let zf: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(-1.0);
    let steps: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let csv_path = args.get(4).filter(|s| s.as_str() != "-").cloned();
    let ramp: f64 = args.get(5).and_then(|s| s.parse().ok()).unwrap_or(4.0);
    let sea = sea(stretching, ramp);
    let (lay, pos) = rope(zf);
    let n = pos.len();
    let opts = SolverOptions {
        dt: DT,
        ..SolverOptions::default()
    };
    let set = SeaSet::single(&sea);
    let bands = set.band_plan(0, DT);
    let base = bands.base;
    println!(
        "{stretching:?}, fairlead at {zf} m, {steps} steps of {DT} s; factor near the surface \
         {}; band 0 every {} steps ({:.4} s; unrounded {:.4} s), {} bands",
        surface_factor(),
        base.steps,
        base.interval,
        base.unrounded,
        bands.len()
    );
    assert_eq!(
        base.steps % SAMPLE,
        0,
        "the grid's steps must be a multiple of {SAMPLE}"
    );
    let field = WaveField::new(&sea);
    let sigma_a = sea
        .components
        .iter()
        .map(|c| 0.5 * (c.amplitude * c.omega * c.omega).powi(2))
        .sum::<f64>()
        .sqrt();

    let mut exact = CpuSolver::new(lay.clone(), &pos, opts);
    exact.set_seas(&set, true);
    let mut cached = CpuSolver::new(lay.clone(), &pos, opts);
    cached.set_seas(&set, false);
    let mut probe = WaveCache::with_clock(&sea, n, RefreshClock::on_grid(&base));

    let mut csv = csv_path.map(|p| std::io::BufWriter::new(std::fs::File::create(p).unwrap()));
    if let Some(w) = csv.as_mut() {
        writeln!(w, "t,force_diff,nodes_above,acc_err").unwrap();
    }
    let (mut wet, mut dry, mut crossing) = (Class::default(), Class::default(), Class::default());
    // Per node over the current interval: largest error, submergence signs seen.
    let mut worst = vec![0.0f64; n];
    let mut seen_wet = vec![false; n];
    let mut seen_dry = vec![false; n];
    let mut generation = u64::MAX;
    let (mut fmax, mut dmax, mut dmax_t) = (0.0f64, 0.0f64, 0.0);
    let (mut pos_now, mut vel_now) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
    let mut crossings_per_node = vec![0u64; n];
    let mut wet_per_node = vec![Class::default(); n];
    let mut intervals = 0u64;
    let mut done = 0u64;
    // The exact run's states at every sample, for the oracle below.
    let mut states: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    let mut close = |worst: &mut [f64], seen_wet: &mut [bool], seen_dry: &mut [bool]| {
        for i in 0..n {
            match (seen_wet[i], seen_dry[i]) {
                (true, true) => {
                    crossing.add(worst[i]);
                    crossings_per_node[i] += 1;
                }
                (false, true) => dry.add(worst[i]),
                (true, false) => {
                    wet.add(worst[i]);
                    wet_per_node[i].add(worst[i]);
                }
                _ => {}
            }
            worst[i] = 0.0;
            seen_wet[i] = false;
            seen_dry[i] = false;
        }
    };
    while done < steps {
        let t = done as f64 * DT;
        for (i, (r, v)) in exact.r.iter().zip(&exact.v).enumerate() {
            pos_now[3 * i..3 * i + 3].copy_from_slice(&r.to_f64());
            vel_now[3 * i..3 * i + 3].copy_from_slice(&v.to_f64());
        }
        probe.refresh_if_due(t, &pos_now, &vel_now);
        states.push((pos_now.clone(), vel_now.clone()));
        if probe.generation != generation {
            // A new interval starts at this sample (its values at t0 are this one's).
            if generation != u64::MAX {
                close(&mut worst, &mut seen_wet, &mut seen_dry);
                intervals += 1;
            }
            generation = probe.generation;
        }
        let (mut above, mut err_now) = (0u64, 0.0f64);
        for i in 0..n {
            let p = [pos_now[3 * i], pos_now[3 * i + 1], pos_now[3 * i + 2]];
            let k = field.kinematics(p, t);
            let c = probe.node(i, t);
            let e = norm([0, 1, 2].map(|d| c.a[d] - k.a[d])) / sigma_a;
            worst[i] = worst[i].max(e);
            err_now = err_now.max(e);
            if p[2] > k.eta {
                seen_dry[i] = true;
                above += 1;
            } else {
                seen_wet[i] = true;
            }
        }
        let mut diff = f64::NAN;
        if done % EVERY == 0 && done > 0 {
            let fe = exact.evaluate().unwrap().reaction[1];
            let fc = cached.evaluate().unwrap().reaction[1];
            let d = norm([0, 1, 2].map(|q| fc[q] - fe[q]));
            fmax = fmax.max(norm(fe));
            if d > dmax {
                dmax = d;
                dmax_t = t;
            }
            diff = d;
        }
        if let Some(w) = csv.as_mut() {
            writeln!(w, "{t:.4},{diff:.6e},{above},{err_now:.6e}").unwrap();
        }
        exact.advance(SAMPLE).unwrap();
        cached.advance(SAMPLE).unwrap();
        done += SAMPLE;
    }
    let fe = exact.evaluate().unwrap().reaction[1];
    let fc = cached.evaluate().unwrap().reaction[1];
    let d = norm([0, 1, 2].map(|q| fc[q] - fe[q]));
    fmax = fmax.max(norm(fe));
    if d > dmax {
        dmax = d;
        dmax_t = steps as f64 * DT;
    }
    println!(
        "fairlead force: largest {fmax:.1} N, cache against exact {dmax:.3e} N at {dmax_t:.2} s \
         ({:.3e} relative)",
        dmax / fmax
    );
    let total = wet.sq + dry.sq + crossing.sq;
    println!(
        "cache's acceleration error over sqrt(m4) = {sigma_a:.4} m/s^2, per (interval, node), \
         {intervals} intervals x {n} nodes:"
    );
    println!("  class     count   rms        max        share of squares");
    for (name, c) in [("wet", wet), ("dry", dry), ("crossing", crossing)] {
        println!(
            "  {name:<9} {:>6}  {:.3e}  {:.3e}  {:.3}",
            c.n,
            c.rms(),
            c.max,
            if total > 0.0 { c.sq / total } else { 0.0 }
        );
    }
    let with: Vec<String> = crossings_per_node
        .iter()
        .enumerate()
        .filter(|(_, &c)| c > 0)
        .map(|(i, c)| format!("node {i}: {c}"))
        .collect();
    println!("  crossing intervals per node: {}", with.join(", "));
    let top: Vec<String> = (n.saturating_sub(5)..n)
        .map(|i| {
            format!(
                "node {i}: {:.2e} / {:.2e}",
                wet_per_node[i].rms(),
                wet_per_node[i].max
            )
        })
        .collect();
    println!("  wet rms / max, top five nodes: {}", top.join(", "));
    oracle(&field, &states, (base.steps / SAMPLE) as usize, sigma_a);
    let per = (base.steps / SAMPLE) as usize;
    for predictor in [Predictor::Cache, Predictor::Acceleration, Predictor::Jerk] {
        replica(&field, &states, per, sigma_a, predictor);
    }
}

/// How a replica of the cache predicts a node's state at `t1` from its states so far.
#[derive(Clone, Copy, Debug)]
enum Predictor {
    /// As the cache: the velocity change over the previous interval as acceleration.
    Cache,
    /// The node's acceleration at the refresh (a central difference of the exact run's
    /// velocities one sample either side: what the solver's last stage knows).
    Acceleration,
    /// That and the jerk, the acceleration's change over the previous interval.
    Jerk,
}

/// A replica of the cache (values at `t1` at the predicted state, those at `t0` the
/// previous interval's `t1` ones) on the exact run's trajectory, with `predictor`: its
/// acceleration error over `sqrt(m4)`, rms and largest of each (interval, node)'s
/// largest, for the top five nodes. Prototype of remedy (c): a better path prediction.
fn replica(
    field: &WaveField,
    states: &[(Vec<f64>, Vec<f64>)],
    per: usize,
    sigma_a: f64,
    predictor: Predictor,
) {
    let n = states[0].0.len() / 3;
    let step = SAMPLE as f64 * DT;
    let h = per as f64 * step;
    let mut scratch = Default::default();
    let mut err = vec![Class::default(); n];
    let node = |q: usize, i: usize| {
        let (p, v) = &states[q];
        (
            [p[3 * i], p[3 * i + 1], p[3 * i + 2]],
            [v[3 * i], v[3 * i + 1], v[3 * i + 2]],
        )
    };
    // The acceleration at sample q (central difference; one-sided at the start).
    let acc = |q: usize, i: usize| {
        let (lo, hi) = (q.saturating_sub(1), (q + 1).min(states.len() - 1));
        let (va, vb) = (node(lo, i).1, node(hi, i).1);
        [0, 1, 2].map(|d| (vb[d] - va[d]) / ((hi - lo) as f64 * step))
    };
    for i in 0..n {
        let (p, v) = node(0, i);
        let (mut k0, mut d0) = field.kinematics_rates_with(p, v, 0.0, &mut scratch);
        let mut j = 0;
        while j + per < states.len() {
            let t0 = j as f64 * step;
            let (p, v) = node(j, i);
            let (a, jerk) = match predictor {
                Predictor::Cache if j >= per => {
                    let vb = node(j - per, i).1;
                    ([0, 1, 2].map(|d| (v[d] - vb[d]) / h), [0.0; 3])
                }
                Predictor::Cache => ([0.0; 3], [0.0; 3]),
                Predictor::Acceleration => (acc(j, i), [0.0; 3]),
                Predictor::Jerk => {
                    let a = acc(j, i);
                    let jerk = if j >= per {
                        let ab = acc(j - per, i);
                        [0, 1, 2].map(|d| (a[d] - ab[d]) / h)
                    } else {
                        [0.0; 3]
                    };
                    (a, jerk)
                }
            };
            let p1 = [0, 1, 2].map(|d| p[d] + h * (v[d] + h * (a[d] / 2.0 + h * jerk[d] / 6.0)));
            let v1 = [0, 1, 2].map(|d| v[d] + h * (a[d] + h * jerk[d] / 2.0));
            let (k1, d1) = field.kinematics_rates_with(p1, v1, t0 + h, &mut scratch);
            let mut worst = 0.0f64;
            for q in j + 1..j + per {
                let t = q as f64 * step;
                let w = cablesim::sea::cache::hermite_weights((t - t0) / h, h);
                let k = field.kinematics(node(q, i).0, t);
                let e = norm([0, 1, 2].map(|d| {
                    w[0] * k0.a[d] + w[1] * d0.a[d] + w[2] * k1.a[d] + w[3] * d1.a[d] - k.a[d]
                }));
                worst = worst.max(e / sigma_a);
            }
            err[i].add(worst);
            (k0, d0) = (k1, d1);
            j += per;
        }
    }
    let all = err.iter().fold(Class::default(), |mut c, e| {
        c.n += e.n;
        c.sq += e.sq;
        c.max = c.max.max(e.max);
        c
    });
    let top: Vec<String> = (n.saturating_sub(5)..n)
        .map(|i| format!("node {i}: {:.2e} / {:.2e}", err[i].rms(), err[i].max))
        .collect();
    println!(
        "replica, {predictor:?} prediction: all {:.2e} / {:.2e}; {}",
        all.rms(),
        all.max,
        top.join(", ")
    );
}

/// The same intervals interpolated with the values and rates at the nodes' *actual*
/// states at both ends (an oracle that knows where each node will be): its error is
/// the interpolation's alone along the path the node took; what the cache errs beyond
/// it is the path prediction's. Also the prediction's miss, m: the position the cache
/// predicts for `t1` from the state at `t0` (and the velocity change over the
/// interval before) against the actual one.
fn oracle(field: &WaveField, states: &[(Vec<f64>, Vec<f64>)], per: usize, sigma_a: f64) {
    use cablesim::sea::cache::hermite_weights;
    let n = states[0].0.len() / 3;
    let mut scratch = Default::default();
    let mut err = vec![Class::default(); n];
    let mut miss = vec![0.0f64; n];
    let dtr = per as f64 * SAMPLE as f64 * DT;
    let mut j = 0;
    while j + per < states.len() {
        let (t0, t1) = (
            j as f64 * SAMPLE as f64 * DT,
            (j + per) as f64 * SAMPLE as f64 * DT,
        );
        for i in 0..n {
            let at = |q: usize| {
                let (p, v) = &states[q];
                (
                    [p[3 * i], p[3 * i + 1], p[3 * i + 2]],
                    [v[3 * i], v[3 * i + 1], v[3 * i + 2]],
                )
            };
            let ((p0, v0), (p1, v1)) = (at(j), at(j + per));
            let (k0, d0) = field.kinematics_rates_with(p0, v0, t0, &mut scratch);
            let (k1, d1) = field.kinematics_rates_with(p1, v1, t1, &mut scratch);
            let mut worst = 0.0f64;
            for q in j + 1..j + per {
                let t = q as f64 * SAMPLE as f64 * DT;
                let w = hermite_weights((t - t0) / (t1 - t0), t1 - t0);
                let (p, _) = at(q);
                let k = field.kinematics(p, t);
                let e = norm([0, 1, 2].map(|d| {
                    w[0] * k0.a[d] + w[1] * d0.a[d] + w[2] * k1.a[d] + w[3] * d1.a[d] - k.a[d]
                }));
                worst = worst.max(e / sigma_a);
            }
            err[i].add(worst);
            if j >= per {
                let (_, vb) = at(j - per);
                let pred = [0, 1, 2]
                    .map(|d| p0[d] + v0[d] * dtr + 0.5 * (v0[d] - vb[d]) / dtr * dtr * dtr);
                miss[i] = miss[i].max(norm([0, 1, 2].map(|d| pred[d] - p1[d])));
            }
        }
        j += per;
    }
    let top: Vec<String> = (n.saturating_sub(5)..n)
        .map(|i| {
            format!(
                "node {i}: {:.2e} / {:.2e} / {:.1e} m",
                err[i].rms(),
                err[i].max,
                miss[i]
            )
        })
        .collect();
    println!(
        "oracle (actual states at both ends), acceleration error rms / max over sqrt(m4), \
         and the prediction's largest miss: {}",
        top.join(", ")
    );
}
