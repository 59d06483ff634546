//! `src/body/kinematics.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::body::kinematics::*;

fn motion(t: f64) -> Dofs {
    // Smooth, large, unrelated motions in every degree of freedom.
    let f = |a: f64, w: f64, p: f64| {
        (
            a * (w * t + p).cos(),
            -a * w * (w * t + p).sin(),
            -a * w * w * (w * t + p).cos(),
        )
    };
    let mut d = Dofs::default();
    for (i, (a, w, p)) in [
        (2.0, 0.7, 0.1),
        (-1.5, 0.9, 1.0),
        (3.0, 0.5, 2.0),
        (0.4, 1.1, 0.3),
        (0.3, 0.8, -0.5),
        (0.9, 0.6, 1.7),
    ]
    .into_iter()
    .enumerate()
    {
        (d.q[i], d.qd[i], d.qdd[i]) = f(a, w, p);
    }
    d
}

#[test]
fn rotation_is_yaw_after_pitch_after_roll() {
    // Roll alone turns +y towards +z; pitch alone turns +z towards +x; yaw alone
    // turns +x towards +y.
    let r = rotation(0.5, 0.0, 0.0);
    assert!((r[2][1] - 0.5f64.sin()).abs() < 1e-15);
    let p = rotation(0.0, 0.5, 0.0);
    assert!((p[0][2] - 0.5f64.sin()).abs() < 1e-15);
    let y = rotation(0.0, 0.0, 0.5);
    assert!((y[1][0] - 0.5f64.sin()).abs() < 1e-15);
    // The product, composed by hand in that order.
    let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        c
    };
    let full = rotation(0.3, -0.4, 1.2);
    let composed = mul(
        rotation(0.0, 0.0, 1.2),
        mul(rotation(0.0, -0.4, 0.0), rotation(0.3, 0.0, 0.0)),
    );
    for i in 0..3 {
        for j in 0..3 {
            assert!((full[i][j] - composed[i][j]).abs() < 1e-15);
        }
    }
}

#[test]
fn attachment_velocity_and_acceleration_are_derivatives_of_its_position() {
    let pose = MeanPose {
        reference: [10.0, -5.0, 2.0],
        offset: [1.0, 2.0, -0.5],
        heading: 0.7,
    };
    let at = [40.0, -12.0, 8.0];
    let pos = |t: f64| attachment(&body_state(&pose, &motion(t)), at).r;
    let h = 1e-4;
    for &t in &[0.0, 1.3, 7.9] {
        let s = attachment(&body_state(&pose, &motion(t)), at);
        let (m, p) = (pos(t - h), pos(t + h));
        for k in 0..3 {
            let v = (p[k] - m[k]) / (2.0 * h);
            let a = (p[k] - 2.0 * s.r[k] + m[k]) / (h * h);
            // Central differences: error h^2 |r'''| / 6 (v) and rounding
            // 4 eps |r| / h^2 (a), with |r| ~ 50 m and rates ~ 1 s^-1.
            assert!((v - s.v[k]).abs() < 1e-6, "t {t} v{k}: {v} vs {}", s.v[k]);
            assert!((a - s.a[k]).abs() < 5e-4, "t {t} a{k}: {a} vs {}", s.a[k]);
        }
    }
}

#[test]
#[allow(clippy::needless_range_loop)] // matrix products written out
fn angular_velocity_is_the_rotation_rate() {
    // dR/dt R^T = [w]x, and its derivative gives alpha.
    let h = 1e-5;
    let pose = MeanPose::default();
    for &t in &[0.4, 3.0] {
        let s = body_state(&pose, &motion(t));
        let (m, p) = (
            body_state(&pose, &motion(t - h)),
            body_state(&pose, &motion(t + h)),
        );
        let mut w = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                w[i][j] = (0..3)
                    .map(|k| (p.rot[i][k] - m.rot[i][k]) / (2.0 * h) * s.rot[j][k])
                    .sum();
            }
        }
        let fd = [w[2][1], w[0][2], w[1][0]];
        let om = s.omega.to_f64();
        let al = s.alpha.to_f64();
        let fd_alpha = [0, 1, 2].map(|k| (p.omega.to_f64()[k] - m.omega.to_f64()[k]) / (2.0 * h));
        for k in 0..3 {
            assert!((fd[k] - om[k]).abs() < 1e-8, "w{k}: {} vs {}", fd[k], om[k]);
            assert!(
                (fd_alpha[k] - al[k]).abs() < 1e-7,
                "alpha{k}: {} vs {}",
                fd_alpha[k],
                al[k]
            );
        }
    }
}
