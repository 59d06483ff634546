//! The water surface on the CPU path (docs/src/water_surface.md): what is above `z = 0`
//! is in air (dry weight, no buoyancy, added mass or water drag), an element crossing
//! the surface takes the water terms times its wetted fraction, a point mass times the
//! submerged share of its sphere.

use crate::common::*;
use cablesim::cpu::CpuSolver;
use cablesim::model::{Environment, Layout, LineType, ModelDef, PointMass, Route, Seabed};
use cablesim::options::{Scheme, SolverOptions};
use cablesim::statics::{relax, RelaxOptions};

const G: f64 = 9.81;
const RHO: f64 = 1025.0;

/// A stiff rope (strain ~1e-7 under its own weight), so unstretched and stretched
/// lengths agree to well below the tolerances here.
fn stiff_rope() -> LineType {
    LineType {
        ea: 1.0e9,
        ..rope()
    }
}

/// A vertical line of length `length` in `n` elements hung from a fixed point at
/// height `top`, its lower end free, in equilibrium.
fn hung_line(top: f64, length: f64, n: usize) -> (Layout, Vec<[f64; 3]>) {
    let def: ModelDef = straight_cable(
        water(),
        stiff_rope(),
        [0.0, 0.0, top],
        [0.0, 0.0, top - length],
        length,
        n,
        Some(Route::Fixed {
            position: [0.0, 0.0, top],
        }),
        None,
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, mut pos) = Layout::build(&def).unwrap();
    relax(&lay, &mut pos, &RelaxOptions::default()).unwrap();
    (lay, pos)
}

/// The force the line exerts on its support, N.
fn support_force(lay: &Layout, pos: &[[f64; 3]]) -> [f64; 3] {
    let mut s = CpuSolver::new(lay.clone(), pos, SolverOptions::default());
    s.evaluate().unwrap().reaction[0]
}

/// A line hung from 12 m above the water, 30 m long, carries its dry weight for the
/// 12 m above the surface and its wet weight for the 18 m below (less half a diameter
/// above, more below: the section's band): the surface falls inside an element
/// (12 / 2.5 = 4.8 elements) and, in a second line, on a node.
/// Tolerance 1e-6 relative: the strain (~1e-7) and the static solve's round-off floor
/// (`8 eps r k` per node, ~3e-5 N with `k = EA / l0 = 4e8 N/m`) are below it; a line
/// with its buoyancy kept in air (the old model) is 15% off, one that lost it under
/// water too 20%.
#[test]
fn hung_line_carries_dry_weight_above_and_wet_weight_below() {
    let lt = stiff_rope();
    let area = lt.area();
    for (n, label) in [(12, "surface inside an element"), (15, "surface on a node")] {
        let (lay, pos) = hung_line(12.0, 30.0, n);
        let f = support_force(&lay, &pos);
        let dry = lt.mass_per_length * G;
        let wet = (lt.mass_per_length - RHO * area) * G;
        // The support pulls up; the line pulls the support down. The section's band
        // (docs/src/water_surface.md) counts half a diameter more wet length.
        let d = lt.diameter;
        let expected = -((12.0 - 0.5 * d) * dry + (18.0 + 0.5 * d) * wet);
        let rel = (f[2] - expected).abs() / expected.abs();
        println!(
            "{label}: support force {:.6} N, hand {expected:.6} N, rel {rel:.2e}",
            f[2]
        );
        assert!(rel < 1e-6, "{label}: {} N against {expected} N", f[2]);
        assert!(f[0].abs() < 1e-9 && f[1].abs() < 1e-9);
    }
    // Wholly in air: the dry weight; wholly under water: the wet weight.
    let (lay, pos) = hung_line(40.0, 30.0, 12);
    let f = support_force(&lay, &pos)[2];
    let dry = -30.0 * lt.mass_per_length * G;
    assert!(
        (f - dry).abs() < 1e-6 * dry.abs(),
        "in air: {f} against {dry}"
    );
    let (lay, pos) = hung_line(-5.0, 30.0, 12);
    let f = support_force(&lay, &pos)[2];
    let wet = -30.0 * (lt.mass_per_length - RHO * area) * G;
    assert!(
        (f - wet).abs() < 1e-6 * wet.abs(),
        "under water: {f} against {wet}"
    );
}

/// A moored rope whose fairlead circles through the surface (6 m of heave, period
/// 30 s): the force on the fairlead changes smoothly, the largest step-to-step change
/// while the top element crosses the surface is no larger than where the line is
/// wholly submerged, and far below what a jump would be (the buoyancy of an element,
/// switched on or off in one step).
#[test]
fn fairlead_through_the_surface_gives_a_smooth_end_force() {
    let lt = rope();
    let period = 30.0;
    let def = straight_cable(
        water(),
        lt.clone(),
        [-30.0, 0.0, -30.0],
        [0.0, 0.0, -3.0],
        45.0,
        15,
        Some(Route::Fixed {
            position: [-30.0, 0.0, -30.0],
        }),
        Some(Route::Circle {
            center: [0.0, 0.0, 0.0],
            radius: 3.0,
            period,
            axis: [0.0, 1.0, 0.0],
            phase: -std::f64::consts::FRAC_PI_2,
            advance: 0.0,
        }),
        PointMass::default(),
        [0.0; 3],
    );
    let (lay, mut pos) = Layout::build(&def).unwrap();
    let fairlead = lay.cables[0].nodes[15] as usize;
    let start = Route::Circle {
        center: [0.0, 0.0, 0.0],
        radius: 3.0,
        period,
        axis: [0.0, 1.0, 0.0],
        phase: -std::f64::consts::FRAC_PI_2,
        advance: 0.0,
    }
    .eval(0.0);
    pos[fairlead] = start.r;
    relax(&lay, &mut pos, &RelaxOptions::default()).unwrap();
    let dt = 2e-4;
    let mut s = CpuSolver::new(
        lay.clone(),
        &pos,
        SolverOptions {
            dt,
            ..SolverOptions::default()
        },
    );
    s.v[fairlead] = cablesim::math::V3::from_f64(start.v);
    let steps = (period / dt) as usize;
    let mut f = Vec::with_capacity(steps);
    let mut z = Vec::with_capacity(steps);
    for _ in 0..steps {
        s.advance(1).unwrap();
        f.push(s.evaluate().unwrap().reaction[1]);
        z.push(s.r[fairlead].z);
    }
    let jump = RHO * lt.area() * G * 3.0 / 2.0; // half an element's buoyancy
    let l0 = 3.0;
    // Steps where the fairlead's element crosses the surface (its lower node is about
    // one element below), and as many steps wholly under water before the crossing,
    // after the start-up transient has died down.
    let crossing: Vec<usize> = (1..steps)
        .filter(|&k| z[k] > -0.5 * l0 && z[k] < 0.5 && z[k] > z[k - 1])
        .collect();
    assert!(crossing.len() > 100, "the fairlead crosses the surface");
    let k0 = crossing[0];
    let under: Vec<usize> = (k0.saturating_sub(crossing.len())..k0).collect();
    let dmax = |ks: &[usize]| {
        ks.iter()
            .map(|&k| {
                let d = [0, 1, 2].map(|q| f[k][q] - f[k - 1][q]);
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
            })
            .fold(0.0f64, f64::max)
    };
    let (d_cross, d_under) = (dmax(&crossing), dmax(&under));
    println!(
        "largest step change of the fairlead force: {d_cross:.3e} N crossing, {d_under:.3e} N \
         under water; a jump would be {jump:.3} N"
    );
    assert!(d_cross < 1e-2 * jump, "{d_cross} N in one step");
    assert!(
        d_cross < 2.0 * d_under.max(1e-6),
        "{d_cross} against {d_under}"
    );
    // Going up, the line out of the water weighs more: the vertical pull on the
    // fairlead grows by about the buoyancy lost.
    let up_top = z
        .iter()
        .enumerate()
        .fold(0, |b, (k, &v)| if v > z[b] { k } else { b });
    assert!(z[up_top] > 2.5);
    assert!(
        f[up_top][2] < f[k0][2],
        "pull at the crest {:?} against at the crossing {:?}",
        f[up_top],
        f[k0]
    );
}

/// A buoy on a short rope, pushed 3 m under and let go, rises and floats at its
/// equilibrium draft (the submerged share of its sphere carries its weight and the
/// rope's) instead of rising into the air: first the static solver finds the draft to
/// round-off, then the dynamics settle there.
#[test]
fn buoy_pushed_under_floats_at_its_equilibrium_draft() {
    let lt = rope();
    let (mass, volume) = (300.0, 1.0);
    let buoy = PointMass {
        mass,
        volume,
        drag_area: 3.0,
        added_mass_coef: 0.5,
    };
    let env = Environment {
        depth: f64::INFINITY,
        seabed: Seabed::default(),
        ..water()
    };
    // The rope hangs below the buoy, its lower end free; its top node carries the buoy.
    let def = straight_cable(
        env,
        lt.clone(),
        [0.0, 0.0, -13.0],
        [0.0, 0.0, -3.0],
        10.0,
        5,
        None,
        None,
        buoy,
        [0.0; 3],
    );
    let (lay, pos0) = Layout::build(&def).unwrap();
    let top = lay.cables[0].nodes[5] as usize;
    let radius = (3.0 * volume / (4.0 * std::f64::consts::PI)).cbrt();
    // Hand computation: submerged volume share f with rho V f g = m g + the rope's
    // weight less the buoyancy of its part under water (the rope's top, up to the
    // buoy's centre, is in air when the centre is, less half a diameter: the
    // section's band); the sphere's cap share is
    // x^2 (3 - 2x), x = (s + R) / (2R), s the centre's depth. A fixed point in the
    // centre's height.
    let rope_wet = 10.0 * (lt.mass_per_length - RHO * lt.area()) * G;
    let mut z_eq = 0.0f64;
    for _ in 0..20 {
        let in_air = (z_eq - 0.5 * lt.diameter).max(0.0);
        let need = (mass * G + rope_wet + RHO * lt.area() * G * in_air) / (RHO * volume * G);
        assert!(need > 0.0 && need < 1.0);
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..200 {
            let x = 0.5 * (lo + hi);
            if x * x * (3.0 - 2.0 * x) < need {
                lo = x;
            } else {
                hi = x;
            }
        }
        z_eq = radius - 0.5 * (lo + hi) * 2.0 * radius;
    }
    println!("buoy equilibrium: centre at z = {z_eq:.6} m (radius {radius:.4} m)");
    assert!(z_eq.abs() < radius, "the buoy floats across the surface");

    let mut pos = pos0.clone();
    relax(&lay, &mut pos, &RelaxOptions::default()).unwrap();
    assert!(
        (pos[top][2] - z_eq).abs() < 1e-6,
        "static: {} against {z_eq}",
        pos[top][2]
    );

    let dt = 5e-4;
    let mut s = CpuSolver::new(
        lay.clone(),
        &pos0,
        SolverOptions {
            dt,
            scheme: Scheme::Symplectic,
            ..SolverOptions::default()
        },
    );
    let (t_end, t_avg) = (120.0, 20.0);
    let n = (t_end / dt) as u64;
    let n_avg = (t_avg / dt) as u64;
    let (mut zmax, mut zsum) = (f64::NEG_INFINITY, 0.0);
    for k in 0..n {
        s.advance(1).unwrap();
        let z = s.r[top].z;
        zmax = zmax.max(z);
        if k >= n - n_avg {
            zsum += z;
        }
    }
    let zmean = zsum / n_avg as f64;
    println!("buoy: highest centre {zmax:.4} m, mean over the last {t_avg} s {zmean:.5} m");
    assert!(zmax < radius, "the buoy left the water: centre at {zmax} m");
    assert!(
        (zmean - z_eq).abs() < 2e-3,
        "mean height {zmean} against the draft's {z_eq}"
    );
}

/// The chain fast path and the general path agree on a line crossing the surface,
/// with a buoy crossing it too.
#[test]
fn chain_kernel_matches_the_general_path_across_the_surface() {
    let lt = rope();
    let def = straight_cable(
        water(),
        lt,
        [-30.0, 0.0, -20.0],
        [0.0, 0.0, 1.0],
        40.0,
        20,
        Some(Route::Fixed {
            position: [-30.0, 0.0, -20.0],
        }),
        None,
        PointMass {
            mass: 50.0,
            volume: 0.2,
            drag_area: 0.5,
            added_mass_coef: 1.0,
        },
        [0.3, 0.0, 0.0],
    );
    let (lay, pos) = Layout::build(&def).unwrap();
    for scheme in [Scheme::Symplectic, Scheme::Rk2, Scheme::Rk4] {
        let opts = SolverOptions {
            dt: 2e-4,
            scheme,
            ..SolverOptions::default()
        };
        let mut fast = CpuSolver::new(lay.clone(), &pos, opts);
        let mut general = CpuSolver::new(lay.clone(), &pos, opts);
        general.use_chain_kernel = false;
        fast.advance(20000).unwrap();
        general.advance(20000).unwrap();
        let top = lay.cables[0].nodes[20] as usize;
        let crossed = fast.r.iter().filter(|r| r.z > 0.0).count();
        let dr = fast
            .r
            .iter()
            .zip(&general.r)
            .map(|(a, b)| (*a - *b).norm())
            .fold(0.0f64, f64::max);
        println!(
            "{scheme:?}: buoy at z = {:.4} m, {crossed} nodes above the surface, |dr| {dr:.2e} m",
            fast.r[top].z
        );
        assert!(
            dr < 1e-8,
            "{scheme:?}: fast and general paths differ by {dr} m"
        );
    }
}
