//! `src/physics/frames.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::math::V3;
use cablesim::physics::element::glmf_element;
use cablesim::physics::element::{Coefs, ElementInput};
use cablesim::physics::frames::*;

fn curve(s: f64) -> V3<f64> {
    V3::new(
        1.0 + 2.0 * s - 0.5 * s * s + 0.25 * s * s * s,
        -3.0 + 0.3 * s + 0.7 * s * s - 0.1 * s * s * s,
        -10.0 - 4.0 * s + 0.2 * s * s + 0.05 * s * s * s,
    )
}

#[test]
fn virtual_node_reproduces_cubics_and_quadratics() {
    let p = |s: f64| curve(s);
    let v = frenet_virtual_node(Some(p(-1.0)), p(0.0), p(1.0), Some(p(2.0)));
    assert!((v - p(0.5)).norm() < 1e-14, "{v:?} vs {:?}", p(0.5));
    // Quadratics at the ends.
    let q = |s: f64| V3::new(1.0 + s - 0.3 * s * s, 2.0 * s * s, -s + 0.5 * s * s);
    let v = frenet_virtual_node(Some(q(-1.0)), q(0.0), q(1.0), None);
    assert!((v - q(0.5)).norm() < 1e-14);
    let v = frenet_virtual_node(None, q(0.0), q(1.0), Some(q(2.0)));
    assert!((v - q(0.5)).norm() < 1e-14);
    let v = frenet_virtual_node(None, q(0.0), q(1.0), None);
    assert_eq!(v, (q(0.0) + q(1.0)) * 0.5);
    // A cubic is not reproduced by the quadratic: the end formula is really used.
    let v = frenet_virtual_node(Some(p(-1.0)), p(0.0), p(1.0), None);
    assert!((v - p(0.5)).norm() > 1e-3);
}

fn input() -> ElementInput<f64> {
    ElementInput {
        ra: V3::new(1.0, 2.0, -30.0),
        rb: V3::new(3.0, 1.0, -34.5),
        va: V3::new(0.1, -0.2, 0.05),
        vb: V3::new(0.3, 0.1, -0.1),
        l0: 5.0,
        current: V3::new(1.0, 0.2, 0.0),
        water_accel: V3::new(0.1, 0.0, -0.2),
    }
}

#[test]
fn frames_are_orthonormal_with_a_column_along_the_element() {
    let e = input();
    let d = e.rb - e.ra;
    let axis = d / d.norm();
    let mid = (e.ra + e.rb) * 0.5 + V3::new(0.2, -0.1, 0.05);
    for frame in [Frame::Euler, Frame::Frenet, Frame::Rvef] {
        let ax = element_frame(frame, &e, mid).unwrap();
        for p in 0..3 {
            for q in 0..3 {
                let want = if p == q { 1.0 } else { 0.0 };
                let got = ax.cols[p].dot(ax.cols[q]);
                assert!((got - want).abs() < 1e-15, "{frame:?} {p}{q}: {got}");
            }
        }
        // Right-handed.
        assert!((ax.cols[0].cross(ax.cols[1]) - ax.cols[2]).norm() < 1e-15);
        let c = ax.cols[ax.tangent];
        let sign = if frame == Frame::Euler {
            d.z.signum()
        } else {
            1.0
        };
        assert!((c - axis * sign).norm() < 1e-15, "{frame:?}: {c:?}");
    }
}

#[test]
fn euler_axis_sign_follows_dz() {
    let mut e = input();
    e.rb = e.ra + V3::new(2.0, 1.0, 4.5); // dz > 0
    let ax = element_frame(Frame::Euler, &e, V3::zero()).unwrap();
    let d = e.rb - e.ra;
    assert!((ax.cols[2] - d / d.norm()).norm() < 1e-15);
    // Second branch of Eq. 9 (theta > pi/4).
    e.rb = e.ra + V3::new(4.0, -1.0, 1.0);
    let ax = element_frame(Frame::Euler, &e, V3::zero()).unwrap();
    let d = e.rb - e.ra;
    assert!((ax.cols[2] - d / d.norm()).norm() < 1e-15);
}

#[test]
fn rvef_matches_glmf_in_f32() {
    let e = input();
    let c = Coefs::<f64> {
        ea: 6e7,
        ea_c: 600.0,
        drag_n: 20.5,
        drag_t: 0.64,
        froude_krylov: 2.6,
        froude_krylov_t: 1.5,
        mass: 5.0,
        added_mass: 1.3,
        added_mass_t: 0.2,
        wet_weight_z: -36.0,
        compression: 0.0,
    };
    let c32 = Coefs::<f32> {
        ea: 6e7,
        ea_c: 600.0,
        drag_n: 20.5,
        drag_t: 0.64,
        froude_krylov: 2.6,
        froude_krylov_t: 1.5,
        mass: 5.0,
        added_mass: 1.3,
        added_mass_t: 0.2,
        wet_weight_z: -36.0,
        compression: 0.0,
    };
    let cv = |v: V3<f64>| V3::<f32>::from_f64(v.to_f64());
    let e32 = ElementInput {
        ra: cv(e.ra),
        rb: cv(e.rb),
        va: cv(e.va),
        vb: cv(e.vb),
        l0: 5.0f32,
        current: cv(e.current),
        water_accel: cv(e.water_accel),
    };
    let g = glmf_element(&c32, &e32);
    let r = frame_element(Frame::Rvef, &c32, &e32, V3::zero()).unwrap();
    let scale = glmf_element(&c, &e).f_half.norm() as f32;
    assert!((g.f_half - r.f_half).norm() <= 64.0 * f32::EPSILON * scale);
    assert_eq!(g.tension, r.tension);
}
