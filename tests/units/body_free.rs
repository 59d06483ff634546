//! `src/body/free.rs`: free and pinned rigid bodies against analytic solutions (springs
//! in all six degrees of freedom, an eccentric spin, free fall with quadratic drag,
//! heave on the waterplane, a pinned pendulum), and the checks of bad properties.

use cablesim::body::free::*;
use cablesim::body::kinematics::{rotation, MeanPose};
use std::f64::consts::{PI, TAU};

const RHO: f64 = 1025.0;

fn diag6(d: [f64; 6]) -> [[f64; 6]; 6] {
    let mut m = [[0.0; 6]; 6];
    for k in 0..6 {
        m[k][k] = d[k];
    }
    m
}

fn diag3(d: [f64; 3]) -> [[f64; 3]; 3] {
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// The mean period of the up-crossings of `s` (sampled every `dt`) through its mean.
fn period(s: &[f64], dt: f64) -> f64 {
    let mean = s.iter().sum::<f64>() / s.len() as f64;
    let mut ups = Vec::new();
    for i in 1..s.len() {
        let (a, b) = (s[i - 1] - mean, s[i] - mean);
        if a < 0.0 && b >= 0.0 {
            ups.push((i - 1) as f64 * dt + dt * a / (a - b));
        }
    }
    assert!(ups.len() >= 3, "{} up-crossings", ups.len());
    (ups[ups.len() - 1] - ups[0]) / (ups.len() - 1) as f64
}

#[test]
fn springs_give_their_natural_period_in_each_dof() {
    let (m, inertia) = (2.0e3, [4.0e3, 6.0e3, 9.0e3]);
    let k = [1.0e4, 2.0e4, 3.0e4, 5.0e4, 7.0e4, 4.0e4];
    let masses = [m, m, m, inertia[0], inertia[1], inertia[2]];
    let fluid = Fluid { rho: RHO, g: 0.0 };
    for dof in 0..6 {
        let spec = FreeSpec {
            mass: m,
            inertia: diag3(inertia),
            stiffness: diag6(k),
            angles: std::array::from_fn(|j| if dof == 3 + j { 1e-3 } else { 0.0 }),
            ..FreeSpec::default()
        };
        let mut offset = [0.0; 3];
        if dof < 3 {
            offset[dof] = 0.1;
        }
        let pose = MeanPose {
            reference: [1.0, 2.0, -3.0],
            offset,
            heading: 0.0,
        };
        let mut b = FreeBody::new(spec, FreeKind::Free, &pose);
        let want = TAU * (masses[dof] / k[dof]).sqrt();
        let dt = want / 2000.0;
        let mut s = Vec::new();
        for n in 0..(8 * 2000) {
            let x = b.reference();
            s.push(if dof < 3 {
                x[dof]
            } else {
                // The rotation vector from the heading.
                let r0 = quaternion(0.0, 0.0, 0.0);
                (b.q * r0.inverse()).scaled_axis()[dof - 3]
            });
            b.step(n as f64 * dt, dt, fluid, [0.0; 3], &[], None, None)
                .unwrap();
        }
        let got = period(&s, dt);
        assert!(
            (got / want - 1.0).abs() < 1e-3,
            "dof {dof}: period {got} s, analytic {want} s"
        );
    }
}

/// One classic RK4 step of a body alone through [`FreeBody::rates`] and
/// [`FreeBody::advanced`] (the stages the CPU solver runs with the lines).
fn rk4_step(b: &mut FreeBody, t: f64, dt: f64, fluid: Fluid) {
    let b0 = b.clone();
    let mut sum = Rates::default();
    let mut stage = b0.clone();
    for (tau, w, next) in [
        (0.0, 1.0, 0.5),
        (0.5, 2.0, 0.5),
        (0.5, 2.0, 1.0),
        (1.0, 1.0, 0.0),
    ] {
        let k = stage
            .rates(t + tau * dt, fluid, [0.0; 3], &[], None)
            .unwrap();
        sum.add_scaled(&k, w);
        stage = b0.advanced(&k, next * dt, None).unwrap();
    }
    *b = b0.advanced(&sum, dt / 6.0, None).unwrap();
}

/// The springs of the test above under RK4 at 40 steps a period (symplectic Euler
/// takes 2000 there): each degree of freedom's period within 0.1 %, and the amplitude
/// kept within 1 % over 8 periods (no damping).
#[test]
fn springs_give_their_natural_period_under_rk4() {
    let (m, inertia) = (2.0e3, [4.0e3, 6.0e3, 9.0e3]);
    let k = [1.0e4, 2.0e4, 3.0e4, 5.0e4, 7.0e4, 4.0e4];
    let masses = [m, m, m, inertia[0], inertia[1], inertia[2]];
    let fluid = Fluid { rho: RHO, g: 0.0 };
    for dof in 0..6 {
        let spec = FreeSpec {
            mass: m,
            inertia: diag3(inertia),
            stiffness: diag6(k),
            angles: std::array::from_fn(|j| if dof == 3 + j { 1e-3 } else { 0.0 }),
            ..FreeSpec::default()
        };
        let mut offset = [0.0; 3];
        if dof < 3 {
            offset[dof] = 0.1;
        }
        let pose = MeanPose {
            reference: [1.0, 2.0, -3.0],
            offset,
            heading: 0.0,
        };
        let mut b = FreeBody::new(spec, FreeKind::Free, &pose);
        let want = TAU * (masses[dof] / k[dof]).sqrt();
        let per = 40;
        let dt = want / per as f64;
        let mut s = Vec::new();
        for n in 0..(8 * per) {
            let x = b.reference();
            s.push(if dof < 3 {
                x[dof] - pose.reference[dof]
            } else {
                (b.q * quaternion(0.0, 0.0, 0.0).inverse()).scaled_axis()[dof - 3]
            });
            rk4_step(&mut b, n as f64 * dt, dt, fluid);
        }
        let got = period(&s, dt);
        assert!(
            (got / want - 1.0).abs() < 1e-3,
            "dof {dof}: period {got} s, analytic {want} s"
        );
        let a0 = s[..per].iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let a1 = s[7 * per..].iter().fold(0.0f64, |a, x| a.max(x.abs()));
        assert!(
            (a1 / a0 - 1.0).abs() < 1e-2,
            "dof {dof}: amplitude {a0} -> {a1}"
        );
    }
}

#[test]
fn eccentric_spin_in_zero_gravity_keeps_its_orbit_and_rate() {
    // The reference point 10 m from the centre of gravity, the body spinning about z at
    // 0.2 rad/s: the reference point orbits the (resting) centre of gravity.
    let (r, w) = (10.0, 0.2);
    let spec = FreeSpec {
        mass: 100.0,
        cg: [0.0, -r, 0.0],
        inertia: diag3([50.0, 70.0, 30.0]),
        ..FreeSpec::default()
    };
    let mut b = FreeBody::new(spec, FreeKind::Free, &MeanPose::default());
    b.w = nalgebra::Vector3::new(0.0, 0.0, w);
    let xg = b.x_g;
    let dt = 0.25;
    let fluid = Fluid { rho: RHO, g: 0.0 };
    for n in 0..40 {
        b.step(n as f64 * dt, dt, fluid, [0.0; 3], &[], None, None)
            .unwrap();
        let t = (n + 1) as f64 * dt;
        let d = b.reference() - xg;
        assert!(
            ((d.norm() - r) / r).abs() < 1e-6,
            "radius {} at {t}",
            d.norm()
        );
        // At t = 0 the reference point is at +y of the centre of gravity.
        let ang = d.x.atan2(d.y).rem_euclid(TAU);
        let want = (-w * t).rem_euclid(TAU);
        let diff = (ang - want + PI).rem_euclid(TAU) - PI;
        assert!(
            diff.abs() < 1e-6 * w * t,
            "angle {ang} against {want} at {t}"
        );
        assert!(((b.w.z - w) / w).abs() < 1e-6);
    }
}

#[test]
fn free_fall_with_quadratic_drag_reaches_its_terminal_velocity() {
    let (m, vol, cda, ca, g) = (1000.0, 0.5, 2.0, 1.0, 9.81);
    let mut am = [[0.0; 6]; 6];
    am[2][2] = ca * RHO * vol;
    let spec = FreeSpec {
        mass: m,
        inertia: diag3([100.0; 3]),
        volume: vol,
        drag_area: [cda, cda, cda],
        added_mass: am,
        ..FreeSpec::default()
    };
    let mut b = FreeBody::new(spec, FreeKind::Free, &MeanPose::default());
    let fluid = Fluid { rho: RHO, g };
    let vt = (2.0 * (m - RHO * vol) * g / (RHO * cda)).sqrt();
    let g_eff = (m - RHO * vol) * g / (m + ca * RHO * vol);
    let tau = vt / g_eff;
    let dt = 1e-4;
    let n_tau = (tau / dt).round() as usize;
    for n in 0..(20 * n_tau) {
        b.step(n as f64 * dt, dt, fluid, [0.0; 3], &[], None, None)
            .unwrap();
        if n + 1 == n_tau {
            // The transient: v = -vt tanh(t / tau).
            let t = n_tau as f64 * dt;
            let want = -vt * (t / tau).tanh();
            assert!(
                ((b.v_g.z - want) / want).abs() < 1e-3,
                "{} against {want}",
                b.v_g.z
            );
        }
    }
    assert!(
        ((b.v_g.z + vt) / vt).abs() < 1e-3,
        "terminal {} against {vt}",
        b.v_g.z
    );
    assert!(b.v_g.x.abs() < 1e-12 && b.v_g.y.abs() < 1e-12);
}

#[test]
fn heave_on_the_waterplane_stiffness() {
    let (aw, vol, g) = (10.0, 50.0, 9.81);
    let m = RHO * vol;
    let a33 = 0.4 * RHO * vol;
    let mut am = [[0.0; 6]; 6];
    am[2][2] = a33;
    let spec = FreeSpec {
        mass: m,
        cg: [0.0, 0.0, -2.0],
        cb: [0.0, 0.0, -1.0],
        inertia: diag3([2.0e5, 2.0e5, 1.0e5]),
        volume: vol,
        waterplane_area: aw,
        added_mass: am,
        ..FreeSpec::default()
    };
    let pose = MeanPose {
        offset: [0.0, 0.0, 0.2],
        ..MeanPose::default()
    };
    let mut b = FreeBody::new(spec, FreeKind::Free, &pose);
    let fluid = Fluid { rho: RHO, g };
    let want = TAU * ((m + a33) / (RHO * g * aw)).sqrt();
    let dt = want / 2000.0;
    let mut s = Vec::new();
    for n in 0..(6 * 2000) {
        s.push(b.reference().z);
        b.step(n as f64 * dt, dt, fluid, [0.0; 3], &[], None, None)
            .unwrap();
    }
    let got = period(&s, dt);
    assert!((got / want - 1.0).abs() < 1e-3, "{got} against {want}");
    // It oscillates about the reference pose, where buoyancy carries the weight.
    let mean = s.iter().sum::<f64>() / s.len() as f64;
    assert!(mean.abs() < 0.01, "mean heave {mean}");
}

#[test]
fn pinned_pendulum_swings_at_its_compound_period() {
    // A body pinned at its reference point, its centre of gravity 3 m below, in air.
    let (m, d, ig, g) = (500.0, 3.0, 200.0, 9.81);
    let spec = FreeSpec {
        mass: m,
        cg: [0.0, 0.0, -d],
        inertia: diag3([ig, ig, ig]),
        angles: [0.01, 0.0, 0.0],
        ..FreeSpec::default()
    };
    let mut b = FreeBody::new(spec, FreeKind::Pinned, &MeanPose::default());
    let fluid = Fluid { rho: 0.0, g };
    let want = TAU * ((ig + m * d * d) / (m * g * d)).sqrt();
    let dt = want / 4000.0;
    let pin = Some(Pin {
        x: [0.0; 3],
        v: [0.0; 3],
        a: [0.0; 3],
    });
    let mut s = Vec::new();
    for n in 0..(5 * 4000) {
        s.push(b.angles()[0]);
        b.step(n as f64 * dt, dt, fluid, [0.0; 3], &[], pin, pin)
            .unwrap();
        assert!(b.reference().norm() < 1e-12);
    }
    let got = period(&s, dt);
    assert!((got / want - 1.0).abs() < 1e-3, "{got} against {want}");
}

#[test]
fn angles_follow_the_prescribed_bodies_rotation_order() {
    let (r, p, y) = (0.3, -0.7, 2.5);
    let q = quaternion(r, p, y);
    let m = q.to_rotation_matrix();
    let want = rotation(r, p, y);
    for i in 0..3 {
        for j in 0..3 {
            assert!((m[(i, j)] - want[i][j]).abs() < 1e-12);
        }
    }
    let a = euler_angles(&q);
    assert!((a[0] - r).abs() < 1e-12 && (a[1] - p).abs() < 1e-12 && (a[2] - y).abs() < 1e-12);
}

#[test]
fn bad_properties_name_the_key() {
    let ok = FreeSpec {
        mass: 10.0,
        inertia: diag3([1.0, 2.0, 3.0]),
        ..FreeSpec::default()
    };
    assert!(check(&ok, FreeKind::Free).is_ok());
    let key = |s: FreeSpec| check(&s, FreeKind::Free).unwrap_err().0;
    assert_eq!(
        key(FreeSpec {
            mass: 0.0,
            ..ok.clone()
        }),
        "mass"
    );
    assert_eq!(
        key(FreeSpec {
            mass: f64::NAN,
            ..ok.clone()
        }),
        "mass"
    );
    let mut nonsym = ok.clone();
    nonsym.inertia[0][1] = 0.5;
    assert_eq!(key(nonsym), "inertia");
    assert_eq!(
        key(FreeSpec {
            inertia: diag3([1.0, -2.0, 3.0]),
            ..ok.clone()
        }),
        "inertia"
    );
    // No inertia about one axis and no added inertia there: no mass in that DOF.
    let (k, msg) = check(
        &FreeSpec {
            inertia: diag3([1.0, 2.0, 0.0]),
            ..ok.clone()
        },
        FreeKind::Free,
    )
    .unwrap_err();
    assert_eq!(k, "inertia");
    assert!(msg.contains("yaw"), "{msg}");
    // An added inertia there makes it whole.
    let mut am = [[0.0; 6]; 6];
    am[5][5] = 1.0;
    assert!(check(
        &FreeSpec {
            inertia: diag3([1.0, 2.0, 0.0]),
            added_mass: am,
            ..ok.clone()
        },
        FreeKind::Free
    )
    .is_ok());
}
