//! Dynamics of the f64 reference stepper against closed-form physics.

use super::common::*;
use cablesim::cpu::CpuSolver;
use cablesim::model::{Layout, PointMass, Route};
use cablesim::options::{Scheme, SolverOptions};

/// Axial waves travel at sqrt(EA / mbar): a step in end velocity sent down a taut
/// line reaches two elements at times whose difference gives the speed.
#[test]
fn axial_wave_travels_at_sqrt_ea_over_mbar() {
    let mut lt = wire();
    lt.damping = 0.0;
    let (length, n) = (1000.0, 1000);
    let eps0 = 1e-3;
    let a = [0.0, 0.0, 0.0];
    let b = [length * (1.0 + eps0), 0.0, 0.0];
    let def = straight_cable(
        vacuum(),
        lt.clone(),
        a,
        b,
        length,
        n,
        Some(Route::Fixed { position: a }),
        Some(Route::Line {
            start: b,
            velocity: [0.5, 0.0, 0.0],
        }),
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, pos) = Layout::build(&def).unwrap();
    let c = lt.wave_speed();
    let dt = 0.5 * (length / n as f64) / c;
    let mut s = CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            dt,
            ..Default::default()
        },
    );
    let t0 = lt.ea * eps0;
    // The front raises tension from EA eps0 by the impedance jump mbar c v.
    let jump = lt.mass_per_length * c * 0.5;
    let probes = [750usize, 250]; // elements, counted from the fixed end
    let mut arrival = [f64::NAN; 2];
    while s.t() < 1.2 * length / c {
        s.advance(1).unwrap();
        let ev = s.evaluate().unwrap();
        for (k, &e) in probes.iter().enumerate() {
            if arrival[k].is_nan() && ev.tension[e] > t0 + 0.5 * jump {
                arrival[k] = s.t();
            }
        }
    }
    let distance = (probes[0] - probes[1]) as f64 * length / n as f64;
    let speed = distance / (arrival[1] - arrival[0]);
    assert!(
        (speed / c - 1.0).abs() < 0.01,
        "measured {speed} m/s, expected {c} m/s (arrivals {arrival:?})"
    );
}

/// With drag and damping off, the symplectic scheme keeps the energy of a vibrating
/// taut line bounded (no drift) over a long run.
#[test]
fn symplectic_energy_stays_bounded() {
    let mut lt = wire();
    lt.damping = 0.0;
    let (length, n) = (100.0, 50);
    let eps0 = 2e-3;
    let a = [0.0, 0.0, 0.0];
    let b = [length * (1.0 + eps0), 0.0, 0.0];
    let def = straight_cable(
        vacuum(),
        lt.clone(),
        a,
        b,
        length,
        n,
        Some(Route::Fixed { position: a }),
        Some(Route::Fixed { position: b }),
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, mut pos) = Layout::build(&def).unwrap();
    // Pluck: a half-sine transverse displacement of 1 m.
    for (k, p) in pos.iter_mut().enumerate() {
        p[2] = (std::f64::consts::PI * k as f64 / n as f64).sin();
    }
    let dt = 0.5 * (length / n as f64) / lt.wave_speed();
    let mut s = CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            dt,
            scheme: Scheme::Symplectic,
            ..Default::default()
        },
    );
    let e0 = s.kinetic_energy() + s.strain_energy();
    assert!(e0 > 1e3, "the pluck stores energy: {e0}");
    let (mut lo, mut hi) = (e0, e0);
    let mut early = 0.0;
    let steps = 200_000;
    for k in 0..steps / 100 {
        s.advance(100).unwrap();
        let e = s.kinetic_energy() + s.strain_energy();
        lo = lo.min(e);
        hi = hi.max(e);
        if k == steps / 1000 {
            early = e;
        }
    }
    let spread = (hi - lo) / e0;
    assert!(
        spread < 0.02,
        "energy wandered by {:.3}% (from {lo} to {hi})",
        100.0 * spread
    );
    // And it does not drift: the last sample is as close as the early one.
    let last = s.kinetic_energy() + s.strain_energy();
    assert!(
        (last - e0).abs() / e0 < 0.02 && (early - e0).abs() / e0 < 0.02,
        "e0 {e0} early {early} last {last}"
    );
}

/// A vertical cable with an end mass, released from its unstretched length, settles
/// (with internal damping and water drag) to a top reaction equal to its wet weight
/// plus the mass's.
#[test]
fn hanging_cable_with_end_mass_settles_to_wet_weight() {
    let mut lt = wire();
    // Enough internal damping to settle the mass's vertical bounce (about 53 rad/s)
    // within the run: c = 1e-3 s gives a damping ratio c omega / 2 of about 3%.
    lt.damping = 1e-3;
    let env = cablesim::model::Environment {
        depth: f64::INFINITY,
        ..Default::default()
    };
    let (length, n) = (50.0, 10);
    let mass = PointMass {
        mass: 200.0,
        volume: 0.01,
        drag_area: 0.5,
        added_mass_coef: 0.5,
    };
    let top = [0.0, 0.0, -1.0];
    let def = straight_cable(
        env,
        lt.clone(),
        top,
        [0.0, 0.0, -1.0 - length],
        length,
        n,
        Some(Route::Fixed { position: top }),
        None,
        mass,
        [0.0; 3],
    );
    let (lay, pos) = Layout::build(&def).unwrap();
    let mut s = CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            dt: 2e-4,
            ..Default::default()
        },
    );
    s.advance((60.0 / 2e-4) as u64).unwrap();
    let ev = s.evaluate().unwrap();
    let w =
        lt.wet_weight_per_length(9.81, 1025.0) * length + (mass.mass - 1025.0 * mass.volume) * 9.81;
    let fz = ev.reaction[0][2];
    assert!(
        (-fz / w - 1.0).abs() < 1e-3,
        "top reaction {fz} N, wet weight {w} N"
    );
    assert!(ev.reaction[0][0].abs() < 1e-6 * w && ev.reaction[0][1].abs() < 1e-6 * w);
}

/// `dt = "auto"` is stable for every scheme: the relaxed catenary example holds still
/// for 60 s with each (an RK2 step that ignored how little damping the axial mode has
/// let it ring up by 18% in this test's first version).
#[test]
fn auto_step_keeps_the_relaxed_catenary_still_for_every_scheme() {
    use cablesim::scenario::Scenario;
    use cablesim::sim::{plan_steps, prepare};
    for scheme in [Scheme::Symplectic, Scheme::Rk2, Scheme::Rk4] {
        let sc = Scenario::load("examples/catenary.toml").unwrap();
        let (lay, pos, _) = prepare(&sc).unwrap();
        let mut opts = SolverOptions {
            scheme,
            ..Default::default()
        };
        let plan = plan_steps(&sc, &lay, &opts, 60.0, sc.sim.dt).unwrap();
        opts.dt = plan.dt;
        let mut s = CpuSolver::new(lay, &pos, opts);
        let f0 = s.evaluate().unwrap().reaction;
        s.advance(plan.total_steps).unwrap();
        let f1 = s.evaluate().unwrap().reaction;
        for (a, b) in f0.iter().zip(&f1) {
            for k in 0..3 {
                assert!(
                    (a[k] - b[k]).abs() < 1e-6 * 7000.0,
                    "{scheme:?} (dt {}): {a:?} became {b:?}",
                    plan.dt
                );
            }
        }
    }
}

/// A point mass bouncing on a vertical cable: the period includes the mass's added mass
/// `Ca rho V` (and a third of the cable's mass, Rayleigh), so the point-mass terms of
/// the mass block are exercised.
#[test]
fn point_mass_added_mass_sets_the_bounce_period() {
    let mut lt = wire();
    lt.ea = 2.0e5; // soft, so the bounce is slow and well resolved
    lt.damping = 0.0;
    lt.cn = 0.0;
    lt.ct = 0.0;
    let env = cablesim::model::Environment {
        depth: f64::INFINITY,
        ..Default::default()
    };
    let (length, n) = (20.0, 20);
    let mass = PointMass {
        mass: 2000.0,
        volume: 1.0,
        drag_area: 0.0,
        added_mass_coef: 0.5,
    };
    let top = [0.0, 0.0, -1.0];
    // Start unstretched: the mass falls, bounces about the stretched equilibrium.
    let def = straight_cable(
        env,
        lt.clone(),
        top,
        [0.0, 0.0, -1.0 - length],
        length,
        n,
        Some(Route::Fixed { position: top }),
        None,
        mass,
        [0.0; 3],
    );
    let (lay, pos) = Layout::build(&def).unwrap();
    let bottom = lay.cables[0].nodes[n] as usize;
    let dt = 1e-4;
    let mut s = CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            dt,
            ..Default::default()
        },
    );
    // Record the bottom's z and find the times of its successive minima.
    let mut z = Vec::new();
    for _ in 0..(20.0 / dt) as usize {
        s.advance(1).unwrap();
        z.push(s.r[bottom].z);
    }
    let mut minima = Vec::new();
    for k in 1..z.len() - 1 {
        if z[k] < z[k - 1] && z[k] <= z[k + 1] {
            minima.push(k as f64 * dt);
        }
    }
    assert!(minima.len() >= 3, "minima at {minima:?}");
    let period = (minima[minima.len() - 1] - minima[0]) / (minima.len() - 1) as f64;
    let k = lt.ea / length;
    let m_eff =
        mass.mass + mass.added_mass_coef * 1025.0 * mass.volume + lt.mass_per_length * length / 3.0;
    let expected = 2.0 * std::f64::consts::PI * (m_eff / k).sqrt();
    assert!(
        (period / expected - 1.0).abs() < 0.01,
        "period {period} s, expected {expected} s"
    );
    // Without the added mass the period would be 11% shorter: the test sees it.
    let without = 2.0 * std::f64::consts::PI * ((m_eff - 512.5) / k).sqrt();
    assert!((period / without - 1.0).abs() > 0.05);
}

/// The blow-up check finds a NaN in any one component of a position or a velocity,
/// the others sane (`f64::max` alone would drop it).
#[test]
fn a_nan_in_any_one_component_is_a_blow_up() {
    use cablesim::math::V3;
    use cablesim::step::blow_up;
    let opts = SolverOptions::default();
    let sane = V3::new(1.0, -2.0, 3.0);
    assert!(blow_up(&opts, sane, sane).is_none());
    for k in 0..3 {
        let mut c = [1.0, -2.0, 3.0];
        c[k] = f64::NAN;
        let bad = V3::new(c[0], c[1], c[2]);
        assert!(bad.max_abs().is_nan(), "component {k}");
        for (r, v) in [(bad, sane), (sane, bad)] {
            let what = blow_up(&opts, r, v).expect("a NaN is a blow-up");
            assert!(what.contains("non-finite"), "component {k}: {what}");
        }
    }
}
