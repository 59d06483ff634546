//! `src/ancf/mod.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.
//!
//! Unit tests of the ANCF cable that reach into its model (energy gradient, ALE
//! remeshing, momentum balance).

use cablesim::ancf::element::{ale_kinematics, kinematics, PointKinematics};
use cablesim::ancf::{AncfCable, AncfConfig, AncfEnd};
use cablesim::math::V3;
use cablesim::model::{Current, Environment, LineType, PointMass, Route, Seabed};

type V = V3<f64>;

fn line(ei: f64, compression: bool) -> LineType {
    LineType {
        name: "l".into(),
        diameter: 0.04,
        mass_per_length: 5.0,
        ea: 6e7,
        damping: 0.0,
        cn: 1.0,
        ct: 0.01,
        cm: 0.0,
        cat: 0.0,
        ei,
        allow_compression: compression,
        ea_curve: None,
        viscoelastic: None,
    }
}

/// The static forces in still water are the negative gradient of the potential
/// energy (strain, weights, seabed) that the static solver descends.
#[test]
fn static_forces_are_the_energy_gradient() {
    let env = Environment {
        depth: 95.0,
        seabed: Seabed::default(),
        ..Default::default()
    };
    let cfg = AncfConfig::new(
        line(50.0, false),
        120.0,
        3,
        AncfEnd::fixed([0.0, 0.0, -90.0]),
        AncfEnd::free([100.0, 5.0, 0.0]).with_point(PointMass {
            mass: 100.0,
            ..Default::default()
        }),
        env,
    );
    let mut c = AncfCable::new(cfg).unwrap();
    c.set_shape(|s| {
        let u = s / 120.0;
        [
            100.0 * u,
            5.0 * u * u,
            -90.0 + 90.0 * u - 10.0 * (3.0 * u).sin(),
        ]
    });
    let q = c.q.clone();
    let zero = vec![0.0; q.len()];
    c.m.forces(&q, &zero, 0.0, &mut c.ws, false);
    let f = c.ws.f.clone();
    let n = q.len();
    for trial in 0..4 {
        let d: Vec<f64> = (0..n)
            .map(|i| {
                if c.m.is_prescribed[i] {
                    0.0
                } else {
                    ((i * 7 + trial * 13) as f64 * 0.618).sin() * if i % 6 < 3 { 1.0 } else { 0.01 }
                }
            })
            .collect();
        let h = 1e-5;
        let plus: Vec<f64> = q.iter().zip(&d).map(|(a, b)| a + h * b).collect();
        let minus: Vec<f64> = q.iter().zip(&d).map(|(a, b)| a - h * b).collect();
        let de = (c.m.potential_energy(&plus) - c.m.potential_energy(&minus)) / (2.0 * h);
        let fd: f64 = f.iter().zip(&d).map(|(a, b)| a * b).sum();
        assert!(
            (de + fd).abs() <= 1e-6 * fd.abs().max(1.0),
            "trial {trial}: dE {de} vs -F.d {}",
            -fd
        );
    }
}

/// A winch cable hanging from a moving top with a clump at its far end, curved and
/// moving (so every ALE term is non-zero), element length 10 m.
fn winch_cable(at_start: bool, schedule: cablesim::ale::PayoutSchedule) -> AncfCable {
    use cablesim::ale::{Winch, WinchEnd};
    let mut lt = line(200.0, false);
    lt.cm = 0.2;
    lt.damping = 1e-4;
    let top = Route::Circle {
        center: [0.0, 0.0, 0.0],
        radius: 5.0,
        period: 20.0,
        axis: [0.0, 0.0, 1.0],
        phase: 0.0,
        advance: 0.0,
    };
    let clump = PointMass {
        mass: 200.0,
        ..Default::default()
    };
    let (held, free) = (
        AncfEnd::driven(top),
        AncfEnd::free([5.0, 0.0, -40.0]).with_point(clump),
    );
    let (start, end) = if at_start { (held, free) } else { (free, held) };
    let mut cfg = AncfConfig::new(
        lt,
        40.0,
        4,
        start,
        end,
        Environment {
            depth: f64::INFINITY,
            ..Default::default()
        },
    );
    cfg.current = Current::uniform([0.5, 0.2, 0.0]);
    cfg.winch = Some(Winch {
        cable: 0,
        end: if at_start {
            WinchEnd::Start
        } else {
            WinchEnd::End
        },
        schedule: std::sync::Arc::new(schedule),
        drum_length: 200.0,
        element_length: 10.0,
    });
    AncfCable::new(cfg).unwrap()
}

/// Translational mass in the assembled mass matrix: the position blocks' diagonal
/// directions summed. The position shape functions sum to one, so it is
/// `int (3 mbar + 3 Cm rho A - Cm rho A t.t) dx` = `(3 mbar + 2 Cm rho A) L` plus
/// three times the point masses.
fn assembled_mass(c: &mut AncfCable) -> f64 {
    let (q, qd, t) = (c.q.clone(), c.qd.clone(), c.t);
    c.m.forces(&q, &qd, t, &mut c.ws, true);
    let n = c.n_nodes();
    let mut s = 0.0;
    for i in 0..n {
        for j in 0..n {
            for a in 0..3 {
                s += c.ws.m.get(6 * i + a, 6 * j + a);
            }
        }
    }
    s
}

/// An inserted node carries the cubic's position and slope and the material
/// velocity and slope rate: shape and motion of the cable are unchanged by the
/// insertion (positions everywhere, velocities on the new fixed element).
#[test]
fn ale_insertion_keeps_shape_and_material_motion() {
    for at_start in [true, false] {
        let mut c = winch_cable(
            at_start,
            cablesim::ale::PayoutSchedule::constant(0.8).unwrap(),
        );
        c.set_shape(|s| [5.0 + 3.0 * (s / 13.0).sin(), 0.5 * s / 40.0, -s]);
        if !at_start {
            c.set_shape(|s| [5.0 + 3.0 * (s / 13.0).sin(), 0.5 * s / 40.0, s - 40.0]);
        }
        for (k, v) in c.qd.iter_mut().enumerate() {
            *v = 0.3 * ((k * 7) as f64).sin();
        }
        let t = c.t;
        c.m.apply_prescribed(&mut c.q, &mut c.qd, t);
        // Just past the 1.5 l_s threshold: 40 m + 5.5 m, variable element 15.5 m.
        c.t = 5.5 / 0.8;
        let len = c.length();
        let far = |s_from_far: f64| {
            if at_start {
                len - s_from_far
            } else {
                s_from_far
            }
        };
        let before: Vec<PointKinematics> =
            (0..=90).map(|k| c.point_at(far(k as f64 * 0.5))).collect();
        let n0 = c.n_nodes();
        c.remesh().unwrap();
        assert_eq!(c.n_nodes(), n0 + 1, "one node inserted");
        assert!((c.length() - len).abs() < 1e-12);
        for (k, b) in before.iter().enumerate() {
            let s = k as f64 * 0.5;
            let a = c.point_at(far(s));
            assert!(
                (a.r - b.r).norm() < 1e-10,
                "at {s} m from the far end: {:?} vs {:?}",
                a.r,
                b.r
            );
            // The new fixed element spans 30..40 m from the far end.
            if (30.0..=40.0).contains(&s) {
                assert!(
                    (a.rd - b.rd).norm() < 1e-10,
                    "velocity at {s} m: {:?} vs {:?}",
                    a.rd,
                    b.rd
                );
            }
        }
    }
}

/// The mass in the water is `mbar` times the deployed length at every step, through
/// insertions and deletions; a payout and an equal retrieval return to the starting
/// mesh.
#[test]
fn ale_mass_follows_the_deployed_length_through_remeshing() {
    for at_start in [true, false] {
        let sched = cablesim::ale::PayoutSchedule::rates(&[
            (0.0, 2.0),
            (30.0, 2.0),
            (30.0, -2.0),
            (60.0, -2.0),
            (60.0, 0.0),
        ])
        .unwrap();
        let mut c = winch_cable(at_start, sched);
        let per_length = 3.0 * c.m.coefs.line.mass + 2.0 * c.m.added_iso;
        let n0 = c.n_elements();
        let mut max_err = 0.0f64;
        let (mut most, mut fewest) = (n0, n0);
        while c.t() < 60.0 {
            c.advance(200).unwrap();
            let expect = per_length * c.length() + 3.0 * 200.0;
            max_err = max_err.max((assembled_mass(&mut c) - expect).abs() / expect);
            let lens = c.element_lengths();
            let sum: f64 = lens.iter().sum();
            let deployed = 40.0 + 2.0 * c.t().min(60.0 - c.t()).max(0.0);
            assert!(
                (sum - deployed).abs() < 1e-9,
                "t {}: {sum} vs {deployed}",
                c.t()
            );
            most = most.max(c.n_elements());
            fewest = fewest.min(c.n_elements());
        }
        assert!(max_err < 1e-13, "mass error {max_err:e}");
        assert_eq!(most, 4 + 6, "60 m paid out in 10 m elements");
        assert_eq!(c.n_elements(), n0, "back to the starting mesh");
        let (ins, del) = c.remeshes();
        assert_eq!((ins, del), (6, 6));
        assert!(fewest >= 4);
    }
}

/// With a still schedule the ALE-ANCF cable moves as the plain one, to round-off
/// (the mass matrix is summed in another order, so not bitwise).
#[test]
fn ale_with_zero_payout_is_the_plain_cable() {
    let mut a = winch_cable(true, cablesim::ale::PayoutSchedule::constant(0.0).unwrap());
    let mut cfg = a.cfg.clone();
    cfg.winch = None;
    cfg.dt = Some(a.dt());
    let mut b = AncfCable::new(cfg).unwrap();
    a.advance(3000).unwrap();
    b.advance(3000).unwrap();
    let d = a
        .node_positions()
        .iter()
        .zip(b.node_positions())
        .map(|(x, y)| (V::from_f64(*x) - V::from_f64(y)).norm())
        .fold(0.0, f64::max);
    assert_eq!(a.n_nodes(), b.n_nodes());
    assert!(d < 1e-9, "zero payout moved the cable by {d} m");
}

/// Momentum of the deployed cable (material velocities, the variable element's
/// convective part included) and point masses, N s.
fn momentum(c: &AncfCable) -> V {
    let now = c.m.ale_now(c.t);
    let mut p = V::zero();
    for e in 0..c.n_elements() {
        let (gps, ale) = c.m.element_rule(e, &now);
        let (q, qd) = (&c.q[6 * e..6 * e + 12], &c.qd[6 * e..6 * e + 12]);
        for (g, gp) in gps.iter().enumerate() {
            let mut k = kinematics(&gp.shape, q, qd);
            if let Some(a) = &ale {
                ale_kinematics(&a.shapes[g], a.ldot, a.lddot, q, qd, &mut k);
            }
            p += k.rd * (c.m.coefs.line.mass * gp.dx);
        }
    }
    for el in &c.m.ends {
        let i = 6 * el.node;
        p += V::new(c.qd[i], c.qd[i + 1], c.qd[i + 2]) * el.mass;
    }
    p
}

/// Momentum balance of a paid-out cable in vacuum (no water: no drag, buoyancy or
/// added mass), its winch on a circle, the payout rate changing: the momentum of the
/// deployed cable changes at `W - R + mbar Ldot v_w` (weight, the reaction the cable
/// puts on the winch, and the momentum the paid-out material brings in with its
/// velocity at the winch, `v_w + Ldot r'_w`). This holds for the continuum; it
/// checks the ALE kinematics, the mass-flow force, the varying mass matrix and the
/// reported reaction together.
#[test]
fn ale_momentum_balance_holds() {
    use cablesim::ale::{PayoutSchedule, Winch, WinchEnd};
    for at_start in [true, false] {
        let mut lt = line(500.0, false);
        lt.damping = 1e-3;
        let top = Route::Circle {
            center: [0.0, 0.0, 0.0],
            radius: 5.0,
            period: 15.0,
            axis: [0.0, 0.0, 1.0],
            phase: 0.0,
            advance: 0.0,
        };
        let clump = PointMass {
            mass: 300.0,
            ..Default::default()
        };
        let held = AncfEnd::driven(top);
        let free = AncfEnd::free([5.0, 0.0, -30.0]).with_point(clump);
        let (start, end) = if at_start { (held, free) } else { (free, held) };
        let env = Environment {
            water_density: 0.0,
            depth: f64::INFINITY,
            ..Default::default()
        };
        let mut cfg = AncfConfig::new(lt, 30.0, 3, start, end, env);
        cfg.winch = Some(Winch {
            cable: 0,
            end: if at_start {
                WinchEnd::Start
            } else {
                WinchEnd::End
            },
            schedule: std::sync::Arc::new(
                PayoutSchedule::rates(&[(0.0, 0.0), (10.0, 3.0), (20.0, -1.0)]).unwrap(),
            ),
            drum_length: 200.0,
            element_length: 10.0,
        });
        let mut c = AncfCable::new(cfg).unwrap();
        let g = V::new(0.0, 0.0, -9.81);
        let we = if at_start { 0 } else { 1 };
        // Rate of change of momentum vs the balance, over windows of 0.2 s.
        let (mut worst, mut scale) = (0.0f64, 0.0f64);
        c.advance_time(1.0).unwrap();
        for _ in 0..60 {
            let p0 = momentum(&c);
            let mut impulse = V::zero();
            let n = (0.2 / c.dt()).round() as usize;
            for k in 0..n {
                // Trapezoid in time of the balance's right-hand side.
                let w = if k == 0 { 0.5 } else { 1.0 };
                impulse += balance(&mut c, g, we, at_start) * (w * c.dt());
                c.step().unwrap();
            }
            impulse += balance(&mut c, g, we, at_start) * (0.5 * c.dt());
            let dp = momentum(&c) - p0;
            worst = worst.max((dp - impulse).norm());
            scale = scale.max(impulse.norm());
        }
        assert!(c.remeshes().0 > 0, "the run must remesh");
        assert!(
            worst < 2e-4 * scale,
            "winch at start {at_start}: momentum change off the balance by {worst:.3e} N s (impulses up to {scale:.3e})"
        );
    }
}

/// `W - R + mbar Ldot v_mat` at the current state.
fn balance(c: &mut AncfCable, g: V, we: usize, at_start: bool) -> V {
    let r = V::from_f64(c.end_forces().unwrap()[we].unwrap());
    let pay = c.m.ale.as_ref().unwrap().winch.schedule.eval(c.t);
    let mass: f64 = c.m.ends.iter().map(|e| e.mass).sum::<f64>() + c.m.coefs.line.mass * c.length();
    let node = if at_start { 0 } else { c.n_nodes() - 1 };
    let i = 6 * node;
    let vw = V::new(c.qd[i], c.qd[i + 1], c.qd[i + 2]);
    let slope = V::new(c.q[i + 3], c.q[i + 4], c.q[i + 5]);
    // The paid-out material leaves the winch into the cable: along +r' at the start,
    // along -r' at the end.
    let dir = if at_start { 1.0 } else { -1.0 };
    let v_mat = vw + slope * (dir * pay.rate);
    g * mass - r + v_mat * (c.m.coefs.line.mass * pay.rate)
}
