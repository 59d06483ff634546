//! Waves in the CPU stepper: the kinematics cache against exact evaluation, the chain
//! fast path against the general path, and a point mass moving with the water.

use super::common::*;
use cablesim::cpu::CpuSolver;
use cablesim::model::{Environment, Layout, LineType, ModelDef, PointMass, Route, Seabed};
use cablesim::options::{Scheme, SolverOptions};
use cablesim::sea::cache::refresh_interval;
use cablesim::sea::irregular::{discretise, Discretisation};
use cablesim::sea::kinematics::WaveField;
use cablesim::sea::schedule::{SUBMERGED_FACTOR, SURFACE_MARGIN};
use cablesim::sea::spectrum::Spectrum;
use cablesim::sea::{SeaSet, SeaState, Stretching, WaveComponent};
use cablesim::sim::reach::sea_reach;
use cablesim::stability::stable_step;
use cablesim::statics::{relax, RelaxOptions};

const DEPTH: f64 = 50.0;

/// A 200-component JONSWAP sea (Hs 4 m, Tp 9 s) in 50 m of water, ramped in over 4 s.
pub(crate) fn jonswap() -> SeaState {
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
        stretching: Stretching::Wheeler,
        ramp_duration: 4.0,
        cache_tolerance: 1e-3,
    }
}

/// A rope moored on the seabed at 50 m, its fairlead held 1 m under the mean level
/// (its top elements go through the surface in the troughs), in static equilibrium.
pub(crate) fn moored_rope() -> (Layout, Vec<[f64; 3]>) {
    moored_rope_at(-1.0)
}

/// The rope of [`moored_rope`] with its fairlead at height `zf`, m.
fn moored_rope_at(zf: f64) -> (Layout, Vec<[f64; 3]>) {
    moored_rope_with(zf, 0.0)
}

/// The rope of [`moored_rope_at`] with the tangential added-mass coefficient `cat`.
fn moored_rope_with(zf: f64, cat: f64) -> (Layout, Vec<[f64; 3]>) {
    let env = Environment {
        depth: DEPTH,
        seabed: Seabed::default(),
        ..water()
    };
    let lt = LineType {
        diameter: 0.05,
        cat,
        ..rope()
    };
    let def: ModelDef = straight_cable(
        env,
        lt,
        [-60.0, 0.0, -DEPTH],
        [0.0, 0.0, zf],
        80.0,
        20,
        Some(Route::Fixed {
            position: [-60.0, 0.0, -DEPTH],
        }),
        Some(Route::Fixed {
            position: [0.0, 0.0, zf],
        }),
        PointMass::default(),
        [0.2, 0.0, 0.0],
    );
    let (lay, mut pos) = Layout::build(&def).unwrap();
    relax(&lay, &mut pos, &RelaxOptions::default()).unwrap();
    (lay, pos)
}

/// The fairlead force every `every` steps over `steps` steps.
fn fairlead_history(s: &mut CpuSolver, steps: u64, every: u64) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    let mut done = 0;
    while done < steps {
        s.advance(every).unwrap();
        done += every;
        out.push(s.evaluate().unwrap().reaction[1]);
    }
    out
}

fn norm(f: [f64; 3]) -> f64 {
    (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt()
}

/// The cached, interpolated kinematics against exact evaluation of the 200-component
/// sum at every node and stage: the fairlead force over 20 s agrees within 1e-3 of its
/// largest value, while the waves change it by far more than that. Each run reports
/// its force as it steps (the cached run through the cache, `waves_output`), so this
/// holds the path's error and the output's together.
#[test]
fn cached_kinematics_give_the_exact_end_force() {
    let (lay, pos) = moored_rope();
    let sea = jonswap();
    let opts = SolverOptions {
        dt: 2e-4,
        ..SolverOptions::default()
    };
    let (steps, every) = (100_000u64, 500u64);
    let run = |exact: Option<bool>| {
        let mut s = CpuSolver::new(lay.clone(), &pos, opts);
        if let Some(exact) = exact {
            s.set_sea(&sea, exact);
        }
        fairlead_history(&mut s, steps, every)
    };
    let cached = run(Some(false));
    let exact = run(Some(true));
    let still = run(None);
    let fmax = exact.iter().map(|f| norm(*f)).fold(0.0f64, f64::max);
    let diff = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| norm([x[0] - y[0], x[1] - y[1], x[2] - y[2]]))
            .fold(0.0f64, f64::max)
    };
    let (d_cache, d_still) = (diff(&cached, &exact), diff(&still, &exact));
    println!(
        "fairlead force: largest {fmax:.1} N; cache against exact {d_cache:.3e} N ({:.2e} \
         relative); still water against waves {d_still:.1} N",
        d_cache / fmax
    );
    assert!(
        d_cache < 1e-3 * fmax,
        "cache off by {d_cache} N of {fmax} N"
    );
    assert!(
        d_still > 0.05 * fmax,
        "the waves change the force by only {d_still} N"
    );
}

/// In waves the chain fast path and the general path agree, for every scheme, with no
/// tangential added mass and with one below and above the normal one (`cm` 1; the
/// top elements pierce the surface, so their added masses take their wetted
/// fractions).
#[test]
fn chain_kernel_matches_the_general_path_in_waves() {
    let sea = jonswap();
    for (scheme, cat) in [
        (Scheme::Symplectic, 0.0),
        (Scheme::Rk2, 0.0),
        (Scheme::Rk4, 0.0),
        (Scheme::Symplectic, 0.6),
        (Scheme::Rk4, 1.8),
    ] {
        let (lay, pos) = moored_rope_with(-1.0, cat);
        let opts = SolverOptions {
            dt: 2e-4,
            scheme,
            ..SolverOptions::default()
        };
        let mut fast = CpuSolver::new(lay.clone(), &pos, opts);
        let mut general = CpuSolver::new(lay.clone(), &pos, opts);
        fast.set_sea(&sea, false);
        general.set_sea(&sea, false);
        general.use_chain_kernel = false;
        fast.advance(30_000).unwrap();
        general.advance(30_000).unwrap();
        let dr = fast
            .r
            .iter()
            .zip(&general.r)
            .map(|(a, b)| (*a - *b).norm())
            .fold(0.0f64, f64::max);
        let moved = fast
            .r
            .iter()
            .zip(&pos)
            .map(|(a, b)| (a.to_f64()[2] - b[2]).abs())
            .fold(0.0f64, f64::max);
        println!("{scheme:?}, cat {cat}: |dr| {dr:.2e} m, largest heave from rest {moved:.3} m");
        assert!(
            moved > 0.05,
            "{scheme:?}: the waves moved the line {moved} m"
        );
        assert!(
            dr < 1e-8,
            "{scheme:?}, cat {cat}: fast and general paths differ by {dr} m"
        );
    }
}

/// A neutrally buoyant sphere (mass `rho V`) deep under a regular wave, on a short
/// slack thread, moves with the water: its equation is
/// `(1 + Ca) rho V a = (1 + Ca) rho V a_w` plus drag on the relative velocity. So its
/// acceleration is the water's (to the thread's share of the mass, 5e-5), and started
/// with the water's velocity it follows the water particle's path (integrated here
/// from the same field) at first. Not for long: the linear loads leave out the
/// convective part of the particle's acceleration, `k |u|^2` (here 1e-3 m/s^2, 0.8%
/// of `a_w`), whose effect grows as `t^2` with nothing to restore it; over a second it
/// is 4e-4 m, 0.3% of the orbit radius.
#[test]
fn neutrally_buoyant_sphere_follows_the_water() {
    let rho = 1025.0;
    let (period, amp) = (8.0, 1.0);
    let omega = 2.0 * std::f64::consts::PI / period;
    let k = omega * omega / 9.81;
    let sea = SeaState {
        components: vec![WaveComponent {
            amplitude: amp,
            omega,
            k,
            direction: 0.0,
            phase: 0.0,
        }],
        depth: f64::INFINITY,
        stretching: Stretching::Wheeler,
        ramp_duration: 0.0,
        cache_tolerance: 1e-3,
    };
    let volume = 0.5;
    // A neutrally buoyant thread, soft, without drag or added mass: the sphere
    // dominates.
    let thread = LineType {
        name: "thread".into(),
        diameter: 0.01,
        mass_per_length: rho * std::f64::consts::PI * 0.01 * 0.01 / 4.0,
        ea: 1.0,
        damping: 0.0,
        cn: 0.0,
        ct: 0.0,
        cm: 0.0,
        cat: 0.0,
        ei: 0.0,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    };
    let z0 = -30.0;
    let mut def = straight_cable(
        water(),
        thread,
        [0.0, 0.0, z0],
        [0.0, 0.0, z0 - 1.0],
        1.0,
        1,
        None,
        None,
        PointMass::default(),
        [0.0; 3],
    );
    def.nodes[0].point = PointMass {
        mass: rho * volume,
        volume,
        drag_area: 0.5,
        added_mass_coef: 0.5,
    };
    let (lay, pos) = Layout::build(&def).unwrap();
    let sphere = lay.cables[0].nodes[0] as usize;
    let opts = SolverOptions {
        dt: 1e-3,
        scheme: Scheme::Rk4,
        ..SolverOptions::default()
    };
    let mut s = CpuSolver::new(lay.clone(), &pos, opts);
    s.set_sea(&sea, true);
    // Start every node with the water's velocity at its place.
    let field = cablesim::sea::kinematics::WaveField::new(&sea);
    for (i, p) in pos.iter().enumerate() {
        s.v[i] = cablesim::math::V3::from_f64(field.kinematics(*p, 0.0).u);
    }
    // The water particle from the sphere's start, by RK4 on dx/dt = u(x, t).
    let u = |p: [f64; 3], t: f64| field.kinematics(p, t).u;
    let add =
        |p: [f64; 3], d: [f64; 3], h: f64| [p[0] + h * d[0], p[1] + h * d[1], p[2] + h * d[2]];
    let mut particle = pos[sphere];
    // The acceleration at the start, from the general path's evaluation.
    let a0 = s.evaluate().unwrap().acc[sphere];
    let aw0 = field.kinematics(pos[sphere], 0.0).a;
    let da = norm([a0[0] - aw0[0], a0[1] - aw0[1], a0[2] - aw0[2]]);
    println!("sphere: acceleration {a0:?}, water's {aw0:?}");
    assert!(
        da < 1e-4 * norm(aw0),
        "acceleration {a0:?} against the water's {aw0:?}"
    );
    let steps = (1.0 / opts.dt) as u64;
    let radius = amp * (k * z0).exp();
    let (mut worst, mut xmax) = (0.0f64, f64::NEG_INFINITY);
    for n in 0..steps {
        let (t, h) = (n as f64 * opts.dt, opts.dt);
        let k1 = u(particle, t);
        let k2 = u(add(particle, k1, 0.5 * h), t + 0.5 * h);
        let k3 = u(add(particle, k2, 0.5 * h), t + 0.5 * h);
        let k4 = u(add(particle, k3, h), t + h);
        for q in 0..3 {
            particle[q] += h / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);
        }
        s.advance(1).unwrap();
        let r = s.r[sphere].to_f64();
        xmax = xmax.max(r[0]);
        worst = worst.max(norm([
            r[0] - particle[0],
            r[1] - particle[1],
            r[2] - particle[2],
        ]));
    }
    println!(
        "sphere: orbit radius {radius:.4} m, largest distance from the particle {worst:.2e} m"
    );
    assert!(
        xmax > 0.5 * radius,
        "the sphere moved only {xmax} m along the wave"
    );
    assert!(worst < 0.01 * radius, "{worst} m off the particle's path");
}

/// A line that stays well under the troughs: the rope of
/// `cached_kinematics_give_the_exact_end_force` with its fairlead 25 m down. Its
/// reach as a run bounds it (`sim::reach::sea_reach`: the fairlead plus the margin)
/// is [`SURFACE_MARGIN`] under the lowest trough the plan assumes, so the plan takes
/// [`SUBMERGED_FACTOR`] of the rule with the amplitudes decayed to the nodes' highest
/// evaluation depth (the step chosen so that the grid leaves it whole): over four
/// times the interval of the rule at the mean level times 0.3, and the fairlead force
/// stays within 1e-3 of its largest value against exact evaluation (what justifies
/// the factor). The nodes do stay under the reach (checked as the forces are
/// sampled).
#[test]
fn submerged_line_keeps_the_end_force_at_the_planned_interval() {
    let (lay, pos) = moored_rope_at(-25.0);
    let (steps, every) = (100_000u64, 500u64);
    let sea = jonswap();
    let mut set = SeaSet::single(&sea);
    set.reach = sea_reach(&lay, &pos, &set, 20.0);
    // A step that puts the grid at the factor's own interval (3072 steps of it, just
    // under the unrounded interval), so that the test holds the factor itself, not
    // what rounding down leaves of it.
    let unrounded = set.plan(0, 2e-4).unrounded;
    let opts = SolverOptions {
        dt: unrounded / 3072.0 * (1.0 - 1e-9),
        ..SolverOptions::default()
    };
    let plan = set.plan(0, opts.dt);
    assert_eq!(plan.steps, 3072);
    assert!(plan.interval > (1.0 - 1e-6) * plan.unrounded);
    let surface = refresh_interval(&sea.components, sea.cache_tolerance);
    println!(
        "submerged rope: reach {:.2} m, trough {:.2} m, evaluation depth {:.2} m, factor \
         {}, interval {:.4} s ({} steps; unrounded {:.4} s); at the surface {surface:.4} s",
        plan.reach,
        plan.trough,
        plan.eval_depth,
        plan.factor,
        plan.interval,
        plan.steps,
        plan.unrounded
    );
    assert!(
        plan.submerged && plan.factor == SUBMERGED_FACTOR,
        "{plan:?}"
    );
    assert!(plan.reach <= plan.trough - SURFACE_MARGIN);
    assert!(plan.interval > 4.0 * surface, "{plan:?}");
    let field = WaveField::new(&sea);
    let run = |exact: bool| {
        let mut s = CpuSolver::new(lay.clone(), &pos, opts);
        s.set_seas(&set, exact);
        let mut out = Vec::new();
        let mut top = f64::NEG_INFINITY;
        let mut gap = f64::NEG_INFINITY;
        for k in 1..=steps / every {
            s.advance(every).unwrap();
            out.push(s.evaluate().unwrap().reaction[1]);
            let t = (k * every) as f64 * opts.dt;
            for r in &s.r {
                let r = r.to_f64();
                top = top.max(r[2]);
                gap = gap.max(r[2] - field.elevation(r[0], r[1], t));
            }
        }
        (out, top, gap)
    };
    let (exact, top, gap) = run(true);
    let (cached, _, _) = run(false);
    println!(
        "highest node {top:.2} m, {:.2} m under the surface at most",
        -gap
    );
    assert!(top <= plan.reach, "a node rose to {top} m, above the reach");
    let fmax = exact.iter().map(|f| norm(*f)).fold(0.0f64, f64::max);
    let d = cached
        .iter()
        .zip(&exact)
        .map(|(x, y)| norm([x[0] - y[0], x[1] - y[1], x[2] - y[2]]))
        .fold(0.0f64, f64::max);
    println!(
        "fairlead force {fmax:.1} N, cache against exact {:.3e} relative",
        d / fmax
    );
    assert!(d < 1e-3 * fmax, "cache off by {d} N of {fmax} N");
}

/// The JONSWAP sea of [`jonswap`] in `depth` m of water.
fn jonswap_in(depth: f64) -> SeaState {
    let mut sea = jonswap();
    let d = Discretisation {
        components: 200,
        direction: 0.3,
        spreading: None,
        seed: 7,
        stream: 0,
    };
    let spectrum = Spectrum::Jonswap {
        hs: 4.0,
        tp: 9.0,
        gamma: 3.3,
    };
    sea.components = discretise(&spectrum, &d, depth, 9.81);
    sea.depth = depth;
    sea
}

/// A deep catenary: anchored 300 m down (on the seabed of 300 m of water), 640 m of
/// rope in 32 segments to a fairlead 6 m under the mean level on a vertical circle of
/// 2 m (period 7 s), in static equilibrium.
fn deep_catenary() -> (Layout, Vec<[f64; 3]>) {
    let depth = 300.0;
    let env = Environment {
        depth,
        seabed: Seabed::default(),
        ..water()
    };
    let lt = LineType {
        diameter: 0.05,
        ..rope()
    };
    let (a, b) = ([-560.0, 0.0, -depth], [0.0, 0.0, -6.0]);
    let def: ModelDef = straight_cable(
        env,
        lt,
        a,
        b,
        640.0,
        32,
        Some(Route::Fixed { position: a }),
        Some(Route::Circle {
            center: [0.0, 0.0, -8.0],
            radius: 2.0,
            period: 7.0,
            axis: [0.0, 1.0, 0.0],
            phase: 0.0,
            advance: 0.0,
        }),
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, mut pos) = Layout::build(&def).unwrap();
    relax(&lay, &mut pos, &RelaxOptions::default()).unwrap();
    (lay, pos)
}

/// Refresh per depth band (`sea::bands`) on a line that crosses the bands' tops: a
/// 300 m-deep catenary whose fairlead moves near the surface. Its nodes spread over
/// at least three bands, none is ever found above its band's top, and the fairlead
/// force over 40 s stays within 1.5e-3 of its largest value against exact evaluation;
/// the result is the same (bit for bit) on one thread as on several, and the same
/// when the line is packed with another cable in another sea.
#[test]
fn depth_bands_keep_the_end_force_of_a_deep_line() {
    let (lay, pos) = deep_catenary();
    let sea = jonswap_in(300.0);
    let mut set = SeaSet::single(&sea);
    set.reach = sea_reach(&lay, &pos, &set, 40.0);
    set.banded = true;
    let dt = 0.5 * stable_step(&lay, Scheme::Symplectic, Default::default()).dt;
    let opts = SolverOptions {
        dt,
        ..SolverOptions::default()
    };
    let bands = set.band_plan(0, dt);
    println!(
        "deep line: dt {dt:.3e} s, reach {:.2} m, bands every {:?} steps under {:?} m, \
         the coarsest every {:.3} s",
        bands.base.reach,
        bands.steps,
        bands.tops,
        bands.horizon()
    );
    assert!(bands.len() >= 3, "{bands:?}");
    let every = 40;
    let steps = (40.0 / dt) as u64 / every * every;
    let run = |exact: bool, banded: bool| {
        let mut s = CpuSolver::new(lay.clone(), &pos, opts);
        let mut set = set.clone();
        set.banded = banded;
        s.set_seas(&set, exact);
        let mut census = vec![0usize; 0];
        let mut out = Vec::new();
        let mut done = 0;
        while done < steps {
            s.advance(every).unwrap();
            done += every;
            out.push(s.evaluate().unwrap().reaction[1]);
            let census_now = s.wave_band_census();
            assert_eq!(
                census_now.breaches, 0,
                "a node above its band's top at step {done}"
            );
            let c = census_now.nodes;
            if c.iter().filter(|&&n| n > 0).count() > census.iter().filter(|&&n| n > 0).count() {
                census = c;
            }
        }
        (out, census)
    };
    let (exact, _) = run(true, false);
    let (banded, census) = run(false, true);
    let (one, _) = run(false, false);
    println!("nodes per band (the most bands in use): {census:?}");
    assert!(census.iter().filter(|&&n| n > 0).count() >= 3, "{census:?}");
    let fmax = exact.iter().map(|f| norm(*f)).fold(0.0f64, f64::max);
    let diff = |a: &[[f64; 3]]| {
        a.iter()
            .zip(&exact)
            .map(|(x, y)| norm([x[0] - y[0], x[1] - y[1], x[2] - y[2]]))
            .fold(0.0f64, f64::max)
    };
    let (d_banded, d_one) = (diff(&banded), diff(&one));
    println!(
        "fairlead force {fmax:.1} N; against exact: banded {:.3e}, one band {:.3e} relative",
        d_banded / fmax,
        d_one / fmax
    );
    // 1.5e-3: the axial part of the water-acceleration load (the Froude-Krylov load along
    // the line, docs/src/model/glmf.md) carries the deep bands' acceleration error
    // straight into the tension, summed along the line: 1.02e-3 with it, 4.0e-4 before
    // (one band: 6.0e-5 and 7.3e-5). The band rule was set against the loads across the
    // line only (docs/src/sea_states.md).
    assert!(
        d_banded < 1.5e-3 * fmax,
        "banded cache off by {d_banded} N of {fmax} N"
    );
    // One thread against several, and packed with another cable in another sea.
    let on_threads = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut s = CpuSolver::new(lay.clone(), &pos, opts);
            s.set_seas(&set, false);
            s.advance(steps / 4).unwrap();
            s.r.iter().map(|r| r.to_f64()).collect::<Vec<_>>()
        })
    };
    assert_eq!(on_threads(1), on_threads(3));
}

/// With refresh per depth band the chain fast path (the nodes' cubics in the power
/// basis, formed again only where a refresh touched them) and the general path (each
/// node with its band's Hermite weights) agree on the deep catenary of
/// [`depth_bands_keep_the_end_force_of_a_deep_line`], for every scheme, over 20 s
/// (several refreshes of the coarsest band).
#[test]
fn depth_bands_chain_kernel_matches_the_general_path() {
    let (lay, pos) = deep_catenary();
    let sea = jonswap_in(300.0);
    let mut set = SeaSet::single(&sea);
    set.reach = sea_reach(&lay, &pos, &set, 20.0);
    set.banded = true;
    let dt = 0.5 * stable_step(&lay, Scheme::Symplectic, Default::default()).dt;
    for scheme in [Scheme::Symplectic, Scheme::Rk2, Scheme::Rk4] {
        let opts = SolverOptions {
            dt: if scheme == Scheme::Symplectic {
                dt
            } else {
                0.5 * dt
            },
            scheme,
            ..SolverOptions::default()
        };
        let steps = (20.0 / opts.dt) as u64;
        let mut fast = CpuSolver::new(lay.clone(), &pos, opts);
        let mut general = CpuSolver::new(lay.clone(), &pos, opts);
        fast.set_seas(&set, false);
        general.set_seas(&set, false);
        general.use_chain_kernel = false;
        fast.advance(steps).unwrap();
        general.advance(steps).unwrap();
        let dr = fast
            .r
            .iter()
            .zip(&general.r)
            .map(|(a, b)| (*a - *b).norm())
            .fold(0.0f64, f64::max);
        let c = fast.wave_band_census();
        let census = &c.nodes;
        println!("{scheme:?}: |dr| {dr:.2e} m; nodes per band {census:?}");
        assert!(census.iter().filter(|&&n| n > 0).count() >= 2, "{census:?}");
        assert_eq!(c.breaches, 0);
        assert!(
            dr < 1e-8,
            "{scheme:?}: fast and general paths differ by {dr} m"
        );
    }
}

/// A checkpoint in waves (the state and the blocks' kinematics caches; their chain
/// columns are formed again after a restore, whole, where the run formed them a
/// refresh at a time) replays the run to the same bits: the deep catenary in bands,
/// checkpointed between two refreshes of the coarsest band, stepped on over the next, put
/// back and stepped again.
#[test]
fn a_checkpoint_in_waves_replays_to_the_same_bits() {
    let (lay, pos) = deep_catenary();
    let sea = jonswap_in(300.0);
    let mut set = SeaSet::single(&sea);
    set.reach = sea_reach(&lay, &pos, &set, 20.0);
    set.banded = true;
    let dt = 0.5 * stable_step(&lay, Scheme::Symplectic, Default::default()).dt;
    let opts = SolverOptions {
        dt,
        ..SolverOptions::default()
    };
    let mut s = CpuSolver::new(lay.clone(), &pos, opts);
    s.set_seas(&set, false);
    // 3.3 s in: refreshes of the finer bands alone (and their decisions) have
    // happened since the coarsest band's last.
    s.advance((3.3 / dt) as u64).unwrap();
    let cp = s.checkpoint().expect("the CPU path checkpoints");
    let on = (2.5 / dt) as u64;
    s.advance(on).unwrap();
    let (r1, v1) = (s.r.clone(), s.v.clone());
    s.restore(&cp);
    s.advance(on).unwrap();
    let moved = r1
        .iter()
        .zip(&pos)
        .map(|(a, b)| (a.to_f64()[2] - b[2]).abs())
        .fold(0.0f64, f64::max);
    assert!(moved > 0.05, "the waves moved the line {moved} m");
    assert!(s.r == r1 && s.v == v1, "the replay differs");
}
