//! `src/math.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::math::*;

#[test]
fn sym3_solve_inverts_mul() {
    let t = V3::new(0.3f64, -0.5, 0.8);
    let t = t / t.norm();
    let mut m = Sym3::scalar(2.0);
    m.add_normal_projection(0.7, t);
    let b = V3::new(1.0, 2.0, -3.0);
    let x = m.solve(b);
    let back = m.mul_vec(x);
    assert!((back - b).norm() < 1e-13, "{back:?}");
    // Along t the added mass does not act; across it it does.
    assert!((m.mul_vec(t) - t * 2.0).norm() < 1e-14);
}
