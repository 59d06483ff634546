//! `src/model/bathymetry.rs` (the seabed grid file) and the sloped contact of
//! `src/physics/seabed.rs`.

use cablesim::math::V3;
use cablesim::model::Bathymetry;
use cablesim::physics::seabed::*;
use std::path::Path;

const GOOD: &str =
    "# a grid\n3 2\n0 10 30\n-5 5\n0 -5 -50\n0 5 -52\n10 -5 -51\n10 5 -53\n30 -5 -55\n30 5 -57\n";

fn parse(text: &str) -> Result<Bathymetry, String> {
    Bathymetry::parse(Path::new("bed.txt"), text).map_err(|e| e.to_string())
}

#[test]
fn grid_reads_and_interpolates_bilinearly() {
    let g = parse(GOOD).unwrap();
    assert_eq!(g.xs, vec![0.0, 10.0, 30.0]);
    assert_eq!(g.ys, vec![-5.0, 5.0]);
    // At the grid points, the values.
    assert_eq!(g.height(10.0, 5.0), -53.0);
    assert_eq!(g.height(30.0, -5.0), -55.0);
    // Bilinear in the cell [10, 30] x [-5, 5]: at (20, 0) the mean of the four.
    let mid = (-51.0 - 53.0 - 55.0 - 57.0) / 4.0;
    assert!((g.height(20.0, 0.0) - mid).abs() < 1e-12);
    // The slopes, and that they are the derivatives of the height.
    let h = seabed_height(&g.packed[..], 17.0, 1.5);
    let d = 1e-6;
    let dx = (g.height(17.0 + d, 1.5) - g.height(17.0 - d, 1.5)) / (2.0 * d);
    let dy = (g.height(17.0, 1.5 + d) - g.height(17.0, 1.5 - d)) / (2.0 * d);
    assert!(
        (h.y - dx).abs() < 1e-8 && (h.z - dy).abs() < 1e-8,
        "{h:?} {dx} {dy}"
    );
    // Outside: the edge values, flat.
    let out = seabed_height(&g.packed[..], 45.0, -20.0);
    assert_eq!((out.x, out.y, out.z), (-55.0, 0.0, 0.0));
    assert!(g.covers(30.0, 5.0, 0.0) && !g.covers(30.1, 0.0, 0.0));
    // In f32 the same arithmetic.
    let p32: Vec<f32> = g.packed.iter().map(|&x| x as f32).collect();
    let h32 = seabed_height(&p32[..], 17.0f32, 1.5f32);
    assert!((h32.x as f64 - h.x).abs() < 1e-4);
}

#[test]
fn bad_grids_name_the_line_and_value() {
    let cases = [
        (
            "2 2\n0 10\n0 1\n0 0 -5\n0 1 -5\n10 0 -5\n",
            "line 6",
            "not complete",
        ),
        (
            "2 2\n0 10\n0 1\n0 0 -5\n0 1 -5\n10 0 -5\n10 1 -5\n10 1 -6\n",
            "line 8",
            "given twice",
        ),
        ("2 2\n10 0\n0 1\n", "line 2", "increase strictly"),
        ("2 2\n0 10 20\n0 1\n", "line 2", "has 3 values"),
        (
            "2 2\n0 10\n0 1\n0 0 -5\n0 1 nan\n",
            "line 5",
            "must be finite",
        ),
        (
            "2 2\n0 10\n0 1\n0 0 -5\n0 1 3\n",
            "line 5",
            "above the water surface",
        ),
        (
            "2 2\n0 10\n0 1\n0 0 -5\n5 1 -5\n",
            "line 5",
            "x = 5 is not one of",
        ),
        (
            "2 2\n0 10\n0 1\n0 0 -5\n0 1\n",
            "line 5",
            "expected `x y z`",
        ),
        ("2 x\n", "line 1", "ny = \"x\""),
    ];
    for (text, line, what) in cases {
        let e = parse(text).unwrap_err();
        assert!(
            e.contains("bed.txt") && e.contains(&format!("{line}:")) && e.contains(what),
            "{text:?}: {e}"
        );
    }
}

fn coefs(mu: f64) -> SeabedCoefs<f64> {
    SeabedCoefs {
        z: -50.0,
        k: 3e6,
        c: 3e4,
        mu,
        mu_axial: mu,
        v_eps: 0.01,
    }
}

#[test]
fn sloped_contact_is_the_flat_one_on_a_flat_bed() {
    let s = coefs(0.4);
    let r = V3::new(1.0, 2.0, -50.02);
    for v in [
        V3::new(0.3, -0.2, 0.1),
        V3::new(0.001, 0.0, -0.5),
        V3::zero(),
    ] {
        let g = V3::new(-50.0, 0.0, 0.0);
        let a = seabed_slope_force(&s, 1.5, r, v, g);
        let b = seabed_force(&s, 1.5, r, v);
        assert!((a - b).norm() <= 1e-9 * b.norm(), "{a:?} {b:?}");
        let (cn, ct) = seabed_slope_damping(&s, 1.5, r, v, g);
        let c = seabed_damping(&s, 1.5, r, v);
        assert!((cn - c.z).abs() < 1e-9 * c.z && (ct - c.x).abs() <= 1e-9 * c.x);
    }
}

#[test]
fn sloped_contact_acts_along_the_normal() {
    let s = coefs(0.5);
    // A plane rising along x at 1 in 10: z_b = -50 + 0.1 x.
    let g = V3::<f64>::new(-49.0, 0.1, 0.0); // at x = 10
    let n = seabed_slope_normal(g);
    assert!((n.norm() - 1.0).abs() < 1e-14 && n.x < 0.0 && n.z > 0.0);
    let r = V3::new(10.0, 0.0, -49.01);
    let f = seabed_slope_force(&s, 2.0, r, V3::zero(), g);
    // Along n, with the penetration below the tangent plane: 0.01 n_z.
    let p = 0.01 * n.z;
    assert!((f - n * (3e6 * 2.0 * p)).norm() < 1e-6, "{f:?}");
    // Sliding along the slope: friction opposes it and stays in the tangent plane;
    // a normal velocity only damps along n.
    let t = V3::new(n.z, 0.0, -n.x);
    let fs = seabed_slope_force(&s, 2.0, r, t * 2.0, g) - f;
    assert!((fs + t * (0.5 * 3e6 * 2.0 * p)).norm() < 1e-6, "{fs:?}");
    let fnv = seabed_slope_force(&s, 2.0, r, n * 0.1, g) - f;
    assert!((fnv + n * (3e4 * 2.0 * 0.1)).norm() < 1e-6, "{fnv:?}");
    // The damping slopes reproduce the damping part: -(c_t v_t + c_n v_n).
    let v = V3::new(0.2, -0.1, 0.05);
    let (cn, ct) = seabed_slope_damping(&s, 2.0, r, v, g);
    let vn = n * v.dot(n);
    let fd = seabed_slope_force(&s, 2.0, r, v, g) - f;
    assert!((fd + (v - vn) * ct + vn * cn).norm() < 1e-6, "{fd:?}");
    // Above the seabed nothing.
    let above = V3::new(10.0, 0.0, -48.9);
    assert_eq!(seabed_slope_force(&s, 2.0, above, v, g), V3::zero());
    assert_eq!(seabed_slope_damping(&s, 2.0, above, v, g), (0.0, 0.0));
}
