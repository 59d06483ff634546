//! Bending stiffness `EI` of the lumped-mass cable (docs/src/model/bending.md):
//! Euler-Bernoulli beams under their own weight (simply supported, cantilever), the
//! stable step's bending waves, the dynamic path against the static forces, and a
//! vibrating beam against the ANCF reference and the closed-form frequency.

use super::common::*;
use cablesim::ancf::{AncfCable, AncfConfig, AncfEnd, StaticOptions};
use cablesim::cpu::CpuSolver;
use cablesim::math::V3;
use cablesim::model::{Clamp, Environment, Layout, LineType, ModelDef, PointMass, Route, Seabed};
use cablesim::options::{Baumgarte, Scheme, SolverOptions};
use cablesim::stability::stable_step;
use cablesim::statics::{relax, static_forces, RelaxOptions};

const G: f64 = 9.80665;
const L: f64 = 10.0;
const EI: f64 = 1e7;
const MASS: f64 = 100.0;
const Z0: f64 = 10.0;

/// Gravity, no water (the beams of MoorDyn's bending test hang in air), no seabed.
fn air() -> Environment {
    Environment {
        gravity: G,
        water_density: 0.0,
        depth: f64::INFINITY,
        seabed: Seabed::default(),
    }
}

/// MoorDyn's test beam: d 0.05 m, 100 kg/m, EI 1e7 N m^2, axial stiffness `ea`.
fn beam(ea: f64) -> LineType {
    LineType {
        name: "beam".into(),
        diameter: 0.05,
        mass_per_length: MASS,
        ea,
        damping: 0.0,
        cn: 0.0,
        ct: 0.0,
        cm: 0.0,
        cat: 0.0,
        ei: EI,
        allow_compression: false,
        ea_curve: None,
        viscoelastic: None,
    }
}

/// A straight beam along x at height Z0 from x = 0 to x = L in `n` segments; end a
/// fixed, end b fixed (`pinned_b`) or free.
fn beam_model(ea: f64, n: usize, pinned_b: bool) -> ModelDef {
    let a = [0.0, 0.0, Z0];
    let b = [L, 0.0, Z0];
    straight_cable(
        air(),
        beam(ea),
        a,
        b,
        L,
        n,
        Some(Route::Fixed { position: a }),
        pinned_b.then_some(Route::Fixed { position: b }),
        PointMass::default(),
        [0.0; 3],
    )
}

fn relaxed(def: &ModelDef) -> (Layout, Vec<[f64; 3]>) {
    let (lay, mut pos) = Layout::build(def).unwrap();
    let rep = relax(&lay, &mut pos, &RelaxOptions::default()).unwrap();
    assert!(rep.converged, "{rep:?}");
    (lay, pos)
}

/// Deflection of the node nearest `x`, m (positive down).
fn deflection_at(pos: &[[f64; 3]], x: f64) -> f64 {
    let p = pos
        .iter()
        .min_by(|p, q| (p[0] - x).abs().total_cmp(&(q[0] - x).abs()))
        .unwrap();
    Z0 - p[2]
}

/// Mid-span deflection of a simply supported beam under `q` N/m carrying the axial
/// tension `t` (a beam-tie: `w'''' EI - T w'' = q`), m; plain Euler-Bernoulli at t = 0.
fn beam_tie_mid(q: f64, t: f64) -> f64 {
    if t <= 0.0 {
        return 5.0 * q * L.powi(4) / (384.0 * EI);
    }
    let k = (t / EI).sqrt();
    q / (t * k * k) * (1.0 / (k * L / 2.0).cosh() - 1.0) + q * L * L / (8.0 * t)
}

/// The shape of the same beam-tie, m.
fn beam_tie(q: f64, t: f64, x: f64) -> f64 {
    let k = (t / EI).sqrt();
    q / (t * k * k) * ((k * (x - L / 2.0)).cosh() / (k * L / 2.0).cosh() - 1.0)
        + q * x * (L - x) / (2.0 * t)
}

/// The tension of a beam pinned at both ends `L` apart with unstretched length `L`:
/// `T = EA (1 / 2L) int w'^2 dx`, solved by bisection with the beam-tie's shape.
fn beam_tie_tension(q: f64, ea: f64) -> f64 {
    let strain = |t: f64| {
        let n = 2000;
        let h = L / n as f64;
        let mut s = 0.0;
        for i in 0..n {
            let x = (i as f64 + 0.5) * h;
            let d = (beam_tie(q, t, x + 1e-4) - beam_tie(q, t, x - 1e-4)) / 2e-4;
            s += d * d * h;
        }
        s / (2.0 * L)
    };
    let (mut lo, mut hi) = (1e-3, ea * 1e-3);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid - ea * strain(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// MoorDyn's bending test (tests/Mooring/BeamSimplySupported.txt of MoorDyn-C): the
/// beam pinned at both ends, 10 m apart, at 20 segments. Euler-Bernoulli gives a
/// mid-span deflection of `5 q L^4 / 384 EI` = 12.77 mm; a chain of bars sagged 54 mm.
/// The ends 10 m apart make the beam a tie too (EA 1.5e9 N): against the beam-tie
/// solution with its tension, and against plain Euler-Bernoulli with a beam whose
/// axial stiffness carries nothing (EA 1e7 N).
#[test]
fn simply_supported_beam_matches_euler_bernoulli() {
    let q = MASS * G;
    for (ea, tie) in [(1.5e9, true), (1e7, false)] {
        let t = if tie { beam_tie_tension(q, ea) } else { 0.0 };
        let exact = beam_tie_mid(q, t);
        let eb = beam_tie_mid(q, 0.0);
        let mut errs = Vec::new();
        for n in [10, 20, 40] {
            let (_, pos) = relaxed(&beam_model(ea, n, true));
            let w = deflection_at(&pos, L / 2.0);
            let err = (w - exact) / exact;
            eprintln!(
                "simply supported, EA {ea:e} N, {n} segments: mid-span {:.4} mm, exact {:.4} mm (tension {t:.1} N; plain E-B {:.4} mm): error {:+.3} %",
                w * 1e3,
                exact * 1e3,
                eb * 1e3,
                err * 100.0
            );
            errs.push(err.abs());
            if n == 20 {
                assert!(err.abs() < 0.01, "EA {ea:e}: error {err:e} at 20 segments");
                // The figure: within 1 % of plain Euler-Bernoulli too.
                assert!(((w - eb) / eb).abs() < 0.01, "EA {ea:e}: {w} against {eb}");
            }
        }
        // Second order: halving the segments quarters the error (within a margin).
        assert!(
            errs[2] < 0.4 * errs[1] && errs[1] < 0.4 * errs[0],
            "{errs:?}"
        );
    }
}

/// MoorDyn's cantilever test (BeamCantilevered.txt): the beam clamped at x = 0 along
/// x, free at x = L; tip deflection `q L^4 / 8 EI` = 122.6 mm and the whole line
/// `q x^2 (6 L^2 - 4 L x + x^2) / 24 EI`, within 1 % of the tip deflection at 20
/// segments.
#[test]
fn cantilever_matches_euler_bernoulli() {
    let q = MASS * G;
    let tip = q * L.powi(4) / (8.0 * EI);
    let mut errs = Vec::new();
    for n in [10, 20, 40] {
        let mut def = beam_model(1.5e9, n, false);
        def.clamps.push(Clamp {
            cable: 0,
            end_b: false,
            tangent: [1.0, 0.0, 0.0],
        });
        let (_, pos) = relaxed(&def);
        let w = Z0 - pos[n][2];
        let err = (w - tip) / tip;
        let mut curve = 0.0f64;
        for p in &pos {
            let x = p[0];
            let exact = q * x * x * (6.0 * L * L - 4.0 * L * x + x * x) / (24.0 * EI);
            curve = curve.max(((Z0 - p[2]) - exact).abs() / tip);
        }
        eprintln!(
            "cantilever, {n} segments: tip {:.4} mm, exact {:.4} mm: error {:+.3} %, curve {:.3} % of the tip",
            w * 1e3,
            tip * 1e3,
            err * 100.0,
            curve * 100.0
        );
        errs.push(err.abs());
        if n == 20 {
            assert!(err.abs() < 0.01, "tip error {err:e} at 20 segments");
            assert!(curve < 0.01, "curve error {curve:e} at 20 segments");
        }
    }
    assert!(errs[2] < errs[1] && errs[1] < errs[0], "{errs:?}");
    // Without the clamp the same beam has no moment at x = 0 and falls: the statics
    // cannot hold it (a mechanism), so the clamp is what carries it.
}

/// The dynamic path's forces (`CpuSolver::evaluate`, the element shears of the
/// bending pass) equal the static solver's (`static_forces`, each hinge's forces
/// on its three nodes) on a bent, clamped, stretched line at rest.
#[test]
fn dynamic_forces_equal_static_forces() {
    let n = 12;
    let mut def = beam_model(1e6, n, true);
    def.clamps.push(Clamp {
        cable: 0,
        end_b: true,
        tangent: [0.6, 0.0, 0.8],
    });
    let (lay, mut pos) = Layout::build(&def).unwrap();
    for (k, p) in pos.iter_mut().enumerate().skip(1).take(n - 1) {
        let s = k as f64 / n as f64;
        p[1] = 0.3 * (3.0 * s).sin();
        p[2] += 0.5 * (2.0 * s).sin() + 0.01 * k as f64;
    }
    let fs = static_forces(&lay, &pos);
    let mut s = CpuSolver::new(lay.clone(), &pos, SolverOptions::default());
    let ev = s.evaluate().unwrap();
    let scale = fs
        .iter()
        .map(|f| V3::<f64>::from_f64(*f).norm())
        .fold(0.0, f64::max);
    assert!(scale > 1e3, "{scale}");
    for k in 1..n {
        let d = (V3::<f64>::from_f64(ev.force[k]) - V3::from_f64(fs[k])).norm();
        assert!(
            d < 1e-9 * scale,
            "node {k}: {:?} against {:?}",
            ev.force[k],
            fs[k]
        );
    }
    // And without bending stiffness the bent line's forces differ: EI matters.
    let mut flat = def.clone();
    flat.line_types[0].ei = 0.0;
    let (lay0, _) = Layout::build(&flat).unwrap();
    let f0 = static_forces(&lay0, &pos);
    let diff = (1..n)
        .map(|k| (V3::<f64>::from_f64(f0[k]) - V3::from_f64(fs[k])).norm())
        .fold(0.0, f64::max);
    assert!(diff > 1e-3 * scale, "{diff}");
}

/// The stable step holds the bending waves (`omega^2 = 16 EI / (m l^4)` at the
/// shortest wavelength): a beam whose bending is faster than its axial waves is stable
/// at 0.9 of the bound and blows up at 1.3 of it, from the zig-zag that is that mode.
#[test]
fn stable_step_includes_bending_waves() {
    let n = 40;
    let def = beam_model(1e5, n, true);
    let (lay, pos) = Layout::build(&def).unwrap();
    let bound = stable_step(&lay, Scheme::Symplectic, Baumgarte::default());
    eprintln!(
        "bending beam: stable step {:e} s ({})",
        bound.dt, bound.term
    );
    assert!(bound.term.contains("bending"), "{}", bound.term);
    let l = L / n as f64;
    let theory = 2.0 / (16.0 * EI / (MASS * l.powi(4))).sqrt();
    assert!(
        (bound.dt / theory - 1.0).abs() < 0.05,
        "{} against {theory}",
        bound.dt
    );
    let run = |factor: f64| {
        let mut s = CpuSolver::new(
            lay.clone(),
            &pos,
            SolverOptions {
                dt: factor * bound.dt,
                ..Default::default()
            },
        );
        for k in 1..n {
            s.r[k].z += if k % 2 == 0 { 1e-6 } else { -1e-6 };
        }
        let ok = s.advance(4000).is_ok();
        ok && s.r.iter().all(|p| (p.z - Z0).abs() < 0.1)
    };
    assert!(run(0.9), "unstable at 0.9 of the bound");
    assert!(
        !run(1.3),
        "still stable at 1.3 of the bound: the bound is not the bending mode's"
    );
}

/// A simply supported beam released straight in gravity swings about its sagged
/// shape at its first bending frequency `pi^2 sqrt(EI / m L^4)` (4.97 Hz): the
/// lumped-mass line (20 segments) against that frequency, and its amplitude against
/// the ANCF reference's (cubic elements with the same EI) over two periods.
#[test]
fn vibrating_beam_matches_ancf_and_first_frequency() {
    let ea = 1e7;
    let n = 20;
    let def = beam_model(ea, n, true);
    let (lay, pos) = Layout::build(&def).unwrap();
    let bound = stable_step(&lay, Scheme::Symplectic, Baumgarte::default());
    let sample = 1e-3;
    let per = (sample / (0.8 * bound.dt)).ceil() as u64;
    let mut s = CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            dt: sample / per as f64,
            ..Default::default()
        },
    );
    let mut ancf = AncfCable::new(AncfConfig::new(
        beam(ea),
        L,
        8,
        AncfEnd::fixed([0.0, 0.0, Z0]),
        AncfEnd::fixed([L, 0.0, Z0]),
        air(),
    ))
    .unwrap();
    let _ = StaticOptions::default();
    let period = 2.0 * std::f64::consts::PI
        / (std::f64::consts::PI.powi(2) * (EI / (MASS * L.powi(4))).sqrt());
    let steps = (2.0 * period / sample).round() as usize;
    let (mut lm, mut an) = (vec![0.0], vec![0.0]);
    for _ in 0..steps {
        s.advance(per).unwrap();
        ancf.advance_time(sample).unwrap();
        lm.push(Z0 - s.r[n / 2].z);
        an.push(Z0 - ancf.position_at(L / 2.0)[2]);
    }
    let peak = an.iter().cloned().fold(0.0, f64::max);
    let diff = lm
        .iter()
        .zip(&an)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    // The first return to the straight line (a minimum of the deflection) after the
    // first maximum: one period.
    let first_min = |w: &[f64]| {
        let imax = (1..w.len() - 1)
            .find(|&i| w[i] >= w[i - 1] && w[i] > w[i + 1])
            .unwrap();
        let imin = (imax + 1..w.len() - 1)
            .find(|&i| w[i] <= w[i - 1] && w[i] < w[i + 1])
            .unwrap();
        // Parabolic refinement of the sampled minimum.
        let (a, b, c) = (w[imin - 1], w[imin], w[imin + 1]);
        (imin as f64 + 0.5 * (a - c) / (a - 2.0 * b + c)) * sample
    };
    let (t_lm, t_an) = (first_min(&lm), first_min(&an));
    eprintln!(
        "vibrating beam: peak deflection {:.3} mm (ANCF) {:.3} mm (lumped mass); largest difference {:.3} mm; period {t_lm:.5} s (lumped mass), {t_an:.5} s (ANCF), {period:.5} s (Euler-Bernoulli)",
        peak * 1e3,
        lm.iter().cloned().fold(0.0, f64::max) * 1e3,
        diff * 1e3
    );
    assert!(
        (t_lm / period - 1.0).abs() < 0.01,
        "{t_lm} against {period}"
    );
    // The swing's amplitude (twice the static deflection) agrees with the ANCF's.
    let peak_lm = lm.iter().cloned().fold(0.0, f64::max);
    assert!(
        (peak_lm / peak - 1.0).abs() < 0.01,
        "{peak_lm} against {peak}"
    );
    // The ANCF's period is not asserted: with 8 elements it swings about 7 % slower
    // than Euler-Bernoulli here (0.2157 s against 0.2013 s), which the lumped-mass
    // line does not (open: docs/src/validation.md, "Bending stiffness").
    let _ = (t_an, diff);
}

/// The GPU path runs bending (its hinge rows hold every hinge of a cable, clamped
/// ends included: tests/gpu/bending.rs compares its runs with these), so
/// `--backend auto` need not fall back for it.
#[test]
fn gpu_path_takes_bending() {
    let mut def = beam_model(1e7, 4, false);
    def.clamps.push(Clamp {
        cable: 0,
        end_b: false,
        tangent: [1.0, 0.0, 0.0],
    });
    let (lay, _) = Layout::build(&def).unwrap();
    assert_eq!(
        cablesim::gpu::solver::unsupported(&lay, &SolverOptions::default()),
        None
    );
    assert_eq!(cablesim::gpu::solver::unsupported_bending(&lay), None);
    let rows = cablesim::gpu::solver::HingeRows::new(&lay, 7).unwrap();
    // Four elements: the clamp at node 0 and three interior hinges; the clamp's
    // direction in the first clamp row.
    assert_eq!(rows.clamps, vec![[1.0, 0.0, 0.0]]);
    let none = cablesim::gpu::solver::NO_HINGE;
    let e = &lay.cables[0].elements;
    let r0 = rows.rows[e[0] as usize];
    assert_eq!((r0.2, r0.3), (7, none));
    assert_eq!(r0.1, lay.elem_b[e[1] as usize]);
    let r3 = rows.rows[e[3] as usize];
    assert_eq!((r3.0, r3.1), (lay.elem_a[e[2] as usize], none));
    // The interior hinges' stiffness EI / l0; the clamp's over half an element.
    let l0 = L / 4.0;
    assert!((r3.4 - EI / l0).abs() < 1e-9 * EI);
    assert!((r0.4 - EI / (0.5 * l0)).abs() < 1e-9 * EI);
}

/// The bending forces are conservative: a bent beam in a vacuum, pinned at both ends,
/// undamped, keeps its kinetic plus strain (axial and bending) energy over many
/// swings (the symplectic step holds it to a small bounded error), and the bending
/// energy is most of it.
#[test]
fn bending_conserves_energy() {
    let n = 16;
    let mut def = beam_model(1e7, n, true);
    def.env = vacuum();
    let (lay, mut pos) = Layout::build(&def).unwrap();
    for (k, p) in pos.iter_mut().enumerate() {
        let s = k as f64 / n as f64;
        p[2] += 0.05 * (std::f64::consts::PI * s).sin()
            + 0.002 * (3.0 * std::f64::consts::PI * s).sin();
        p[1] += 0.01 * (2.0 * std::f64::consts::PI * s).sin();
    }
    let bound = stable_step(&lay, Scheme::Symplectic, Baumgarte::default());
    let mut s = CpuSolver::new(
        lay,
        &pos,
        SolverOptions {
            // Small enough that the symplectic step's own energy error (about
            // omega dt / 2 of each mode's energy) stays well below the bound.
            dt: 0.1 * bound.dt,
            ..Default::default()
        },
    );
    let e0 = s.kinetic_energy() + s.strain_energy();
    assert!(e0 > 0.0);
    let mut worst = 0.0f64;
    let mut ke_max = 0.0f64;
    for _ in 0..200 {
        s.advance(250).unwrap();
        let ke = s.kinetic_energy();
        ke_max = ke_max.max(ke);
        worst = worst.max(((ke + s.strain_energy()) - e0).abs() / e0);
    }
    eprintln!("bent beam in a vacuum: energy {e0:.4e} J, largest drift {worst:.2e}, largest kinetic {ke_max:.3e} J");
    // The beam swings: most of the energy goes through kinetic and back.
    assert!(ke_max > 0.4 * e0, "{ke_max} of {e0}");
    assert!(worst < 1e-2, "energy drift {worst}");
}

/// The chain fast path (`cpu::chain::bending`: the hinges' forces as extra forces of
/// its node pass, the arctangent a rational function) agrees with the general path
/// (`bending_pass`) to round-off: the beam pinned, and cantilevered from either end, each released straight to swing, the time of 3000 symplectic steps, every
/// scheme. And a block with bending takes the fast path (its constants have the
/// hinges): the two runs are not the same bits.
#[test]
fn chain_fast_path_bends_as_the_general_path() {
    use cablesim::options::Scheme;
    let cases: Vec<(&str, ModelDef)> = {
        let pinned = beam_model(1e8, 20, true);
        let mut cantilever = beam_model(1e8, 20, false);
        cantilever.clamps.push(Clamp {
            cable: 0,
            end_b: false,
            tangent: [1.0, 0.0, 0.0],
        });
        // The mirror image: clamped at end b along x, end a free.
        let mut mirrored = beam_model(1e8, 20, true);
        mirrored.nodes[0].route = None;
        mirrored.clamps.push(Clamp {
            cable: 0,
            end_b: true,
            tangent: [1.0, 0.0, 0.0],
        });
        vec![
            ("pinned", pinned),
            ("cantilever", cantilever),
            ("cantilever clamped at end b", mirrored),
        ]
    };
    for (name, def) in cases {
        let (lay, pos) = Layout::build(&def).unwrap();
        assert!(lay.blocks[0].is_chain);
        // The same time for every scheme: 3000 symplectic steps at half its bound.
        let duration = 1500.0 * stable_step(&lay, Scheme::Symplectic, Baumgarte::default()).dt;
        for scheme in [Scheme::Symplectic, Scheme::Rk2, Scheme::Rk4] {
            let bound = stable_step(&lay, scheme, Baumgarte::default());
            let opts = SolverOptions {
                dt: 0.5 * bound.dt,
                scheme,
                ..Default::default()
            };
            let steps = (duration / opts.dt).ceil() as u64;
            let mut fast = CpuSolver::new(lay.clone(), &pos, opts);
            let mut slow = CpuSolver::new(lay.clone(), &pos, opts);
            slow.use_chain_kernel = false;
            fast.advance(steps).unwrap();
            slow.advance(steps).unwrap();
            let moved = fast
                .r
                .iter()
                .zip(&pos)
                .map(|(r, p)| (r.z - p[2]).abs())
                .fold(0.0, f64::max);
            let worst = fast
                .r
                .iter()
                .zip(&slow.r)
                .map(|(a, b)| (*a - *b).norm())
                .fold(0.0, f64::max);
            let worst_v = fast
                .v
                .iter()
                .zip(&slow.v)
                .map(|(a, b)| (*a - *b).norm())
                .fold(0.0, f64::max);
            eprintln!(
                "{name}, {scheme:?}: moved {moved:.3e} m; fast and general paths differ by {worst:.2e} m, {worst_v:.2e} m/s"
            );
            assert!(
                moved > 1e-3,
                "{name}: the beam should swing, moved {moved} m"
            );
            assert!(
                worst > 0.0,
                "{name}: the same bits: the fast path did not run"
            );
            assert!(
                worst < 1e-9 && worst_v < 1e-7,
                "{name}, {scheme:?}: fast and general paths differ by {worst:e} m, {worst_v:e} m/s"
            );
        }
    }
}
