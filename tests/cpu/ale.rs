//! ALE-GLMF (cables of varying length, paper Sec. 3.1): mass accounting through
//! remeshing, the 1.5x / 0.5x node rules, exact reduction to the GLMF with zero payout,
//! the top tension of a slow vertical deployment, the mass-flow force against the
//! material acceleration it stands for, and the errors of impossible schedules.

use super::common::*;
use cablesim::ale::{mass_flow_forces, PayoutSchedule, Winch, WinchEnd};
use cablesim::cpu::CpuSolver;
use cablesim::error::Error;
use cablesim::math::V3;
use cablesim::model::{Layout, LineType, ModelDef, PointMass, Route};
use cablesim::options::{Scheme, SolverOptions};
use cablesim::scenario::Scenario;
use std::path::Path;
use std::sync::Arc;

mod scenario;

type V = V3<f64>;

const TOP: [f64; 3] = [0.0, 0.0, -2.0];

/// A vertical cable of `n` elements of `l_s` hanging from a winch held at `TOP`, with
/// `clump` at the far end. The winch is at the cable's start or end node.
pub(crate) fn hanging(
    lt: LineType,
    n: usize,
    l_s: f64,
    clump: PointMass,
    end: WinchEnd,
    current: [f64; 3],
) -> ModelDef {
    let bottom = [TOP[0], TOP[1], TOP[2] - n as f64 * l_s];
    let held = Some(Route::Fixed { position: TOP });
    match end {
        WinchEnd::Start => straight_cable(
            water(),
            lt,
            TOP,
            bottom,
            n as f64 * l_s,
            n,
            held,
            None,
            clump,
            current,
        ),
        WinchEnd::End => {
            let mut d = straight_cable(
                water(),
                lt,
                bottom,
                TOP,
                n as f64 * l_s,
                n,
                None,
                held,
                PointMass::default(),
                current,
            );
            d.nodes[0].point = clump;
            d
        }
    }
}

pub(crate) fn winch(end: WinchEnd, schedule: PayoutSchedule, drum: f64, l_s: f64) -> Winch {
    Winch {
        cable: 0,
        end,
        schedule: Arc::new(schedule),
        drum_length: drum,
        element_length: l_s,
    }
}

pub(crate) fn clump(mass: f64) -> PointMass {
    PointMass {
        mass,
        volume: mass / 7800.0,
        drag_area: 0.05,
        added_mass_coef: 1.0,
    }
}

pub(crate) fn solver(def: ModelDef, w: Winch, dt: f64, scheme: Scheme) -> CpuSolver {
    let (_, pos) = Layout::build(&def).unwrap();
    CpuSolver::with_winches(
        def,
        vec![w],
        &pos,
        SolverOptions {
            dt,
            scheme,
            ..Default::default()
        },
    )
    .unwrap()
}

/// Pays out 12 m (ramp to 2 m/s, hold, ramp down) and hauls the same 12 m back in.
pub(crate) fn out_and_back() -> PayoutSchedule {
    PayoutSchedule::rates(&[
        (0.0, 0.0),
        (1.0, 2.0),
        (6.0, 2.0),
        (7.0, 0.0),
        (8.0, -2.0),
        (13.0, -2.0),
        (14.0, 0.0),
    ])
    .unwrap()
}

/// Wet mass and weight in the water equal `mbar L(t)` and `w L(t)` at every step,
/// through every insertion and deletion; the node count follows the 1.5x / 0.5x rules
/// at every step and comes back to where it started when the payout is hauled back in.
#[test]
fn wet_mass_and_node_counts_follow_the_deployed_length() {
    let (l_s, n0, dt) = (2.0, 5usize, 2e-4);
    let lt = rope();
    let wet = lt.wet_weight_per_length(9.81, 1025.0);
    for end in [WinchEnd::Start, WinchEnd::End] {
        let def = hanging(lt.clone(), n0, l_s, clump(20.0), end, [0.0; 3]);
        let l_init = n0 as f64 * l_s;
        let mut s = solver(
            def,
            winch(end, out_and_back(), 100.0, l_s),
            dt,
            Scheme::Symplectic,
        );
        let (mut worst_mass, mut worst_weight, mut max_elems) = (0.0f64, 0.0f64, 0);
        let (mut inserts, mut deletes) = (0usize, 0usize);
        let mut prev_elems = n0;
        let mut prev_var = l_s;
        let steps = (15.0 / dt) as u64;
        for _ in 0..steps {
            s.advance(1).unwrap();
            let st = &s.winch_status()[0];
            let l = l_init + out_and_back().eval(s.t()).dl;
            assert!((st.deployed_length - l).abs() < 1e-12 * l);
            // Mass and wet weight of the elements the step used, from the evaluation.
            let ev = s.evaluate().unwrap();
            let mass: f64 = ev.elements.iter().map(|e| 2.0 * e.half_mass).sum();
            worst_mass =
                worst_mass.max((mass - lt.mass_per_length * l).abs() / (lt.mass_per_length * l));
            // Wet weight: the stepper's element lengths times the wet weight per length.
            let l0s = s.element_l0();
            let w_sum: f64 = l0s.iter().map(|l0| wet * l0).sum();
            worst_weight = worst_weight.max((w_sum - wet * l).abs() / (wet * l));
            // In the water.
            assert!(s.r.iter().all(|p| p.z < 0.0));
            // The rules: every element but the variable one is l_s exactly, the
            // variable one is within [0.5, 1.5] l_s, and the count is the only one
            // that allows that.
            let c = &s.layout().cables[0];
            let ne = c.elements.len();
            assert_eq!(ne, st.elements);
            assert_eq!(c.nodes.len(), ne + 1);
            let var = match end {
                WinchEnd::Start => c.elements[0],
                WinchEnd::End => c.elements[ne - 1],
            } as usize;
            for &e in &c.elements {
                if e as usize != var {
                    assert_eq!(l0s[e as usize], l_s);
                }
            }
            assert!((0.5 * l_s..=1.5 * l_s).contains(&l0s[var]), "{}", l0s[var]);
            let x = l / l_s - 1.5;
            if (x - x.round()).abs() > 1e-9 {
                assert_eq!(ne, 1 + x.ceil() as usize, "L = {l}");
            }
            if ne > prev_elems {
                inserts += ne - prev_elems;
                // The variable element had just passed 1.5 l_s.
                let grown = prev_var + 2.0 * dt * 1.0001;
                assert!(prev_var <= 1.5 * l_s && grown > 1.5 * l_s, "{prev_var}");
            } else if ne < prev_elems {
                deletes += prev_elems - ne;
                let shrunk = prev_var - 2.0 * dt * 1.0001;
                assert!(prev_var >= 0.5 * l_s && shrunk < 0.5 * l_s, "{prev_var}");
            }
            prev_elems = ne;
            prev_var = st.variable_l0;
            max_elems = max_elems.max(ne);
        }
        println!(
            "{end:?}: {inserts} insertions, {deletes} deletions, {n0} -> {max_elems} -> {prev_elems} elements; worst relative mass error {worst_mass:.2e}, weight {worst_weight:.2e}"
        );
        assert!(worst_mass < 1e-13 && worst_weight < 1e-13);
        assert_eq!(inserts, 6);
        assert_eq!(deletes, 6);
        assert_eq!(max_elems, n0 + 6);
        assert_eq!(
            prev_elems, n0,
            "payout and equal retrieval return to the start"
        );
        let st = &s.winch_status()[0];
        assert_eq!((st.inserted, st.deleted), (6, 6));
        // Material nodes kept their physical coordinates: p runs from the far end.
        let p = &st.physical_coordinates;
        let far_to_winch: Vec<f64> = match end {
            WinchEnd::Start => p.iter().rev().cloned().collect(),
            WinchEnd::End => p.clone(),
        };
        for (k, &x) in far_to_winch.iter().enumerate().take(n0) {
            assert_eq!(x, k as f64 * l_s);
        }
        assert!((far_to_winch[n0] - l_init).abs() < 1e-12 * l_init);
    }
}

/// Zero payout: the ALE path (constant rate 0, a rate table of zeros, a flat length
/// table) reproduces the plain GLMF general path bit for bit, every scheme, winch at
/// either end, a cable swinging in a current; and matches the default chain fast path
/// to the fast path's own tolerance.
#[test]
fn zero_payout_is_bitwise_the_plain_glmf() {
    let (l_s, n, dt) = (2.0, 8usize, 2e-4);
    let steps = 3000;
    for end in [WinchEnd::Start, WinchEnd::End] {
        for scheme in [Scheme::Symplectic, Scheme::Rk2, Scheme::Rk4] {
            let def = hanging(rope(), n, l_s, clump(20.0), end, [0.6, 0.2, 0.0]);
            let (lay, pos) = Layout::build(&def).unwrap();
            let opts = SolverOptions {
                dt,
                scheme,
                ..Default::default()
            };
            let mut plain = CpuSolver::new(lay.clone(), &pos, opts);
            plain.use_chain_kernel = false;
            plain.advance(steps).unwrap();
            let mut fast = CpuSolver::new(lay, &pos, opts);
            fast.advance(steps).unwrap();
            let l = n as f64 * l_s;
            for sched in [
                PayoutSchedule::constant(0.0).unwrap(),
                PayoutSchedule::rates(&[(0.0, 0.0), (1.0, 0.0)]).unwrap(),
                PayoutSchedule::table(&[(0.0, l), (100.0, l)]).unwrap(),
            ] {
                // The winch cable on each path against the plain cable on the same path:
                // the general path, and the chain fast path.
                let mut ale = solver(def.clone(), winch(end, sched.clone(), 1e3, l_s), dt, scheme);
                ale.use_chain_kernel = false;
                ale.advance(steps).unwrap();
                let mut ale_fast = solver(def.clone(), winch(end, sched, 1e3, l_s), dt, scheme);
                ale_fast.advance(steps).unwrap();
                let moved = (ale.r[n / 2] - V::from_f64(pos[n / 2])).norm();
                assert!(moved > 0.05, "the current moves the cable ({moved} m)");
                for (x, y, path) in [(&ale, &plain, "general"), (&ale_fast, &fast, "chain")] {
                    for i in 0..x.r.len() {
                        for (a, b) in [(x.r[i], y.r[i]), (x.v[i], y.v[i])] {
                            assert_eq!(
                                a.to_f64().map(f64::to_bits),
                                b.to_f64().map(f64::to_bits),
                                "{end:?} {scheme:?} {path} path node {i}"
                            );
                        }
                    }
                }
                let (ea, ep) = (ale.evaluate().unwrap(), plain.evaluate().unwrap());
                assert_eq!(ea.tension, ep.tension);
                assert_eq!(ea.reaction, ep.reaction);
                let far = ale
                    .r
                    .iter()
                    .zip(&fast.r)
                    .map(|(a, b)| (*a - *b).norm())
                    .fold(0.0, f64::max);
                assert!(far < 1e-9, "ALE vs chain fast path: {far} m");
            }
        }
    }
}

/// Slow vertical deployment of a clump: once the payout is steady, the top force
/// equals the wet weight of the deployed length plus the clump, less the drag of the
/// descent, bounded from the payout speed `v` and the drag law:
/// `D_min = 1/2 rho (Ct pi d (L - 1.5 l_s) + Cd A) v^2` (the variable element may be
/// still) `<= W - T <= D_max = 1/2 rho (Ct pi d L + Cd A) (v (1 + eps))^2`. The paid-out
/// element is not damped by its own growth: its axial force is its elastic force.
#[test]
fn slow_vertical_deployment_top_force_is_wet_weight_less_drag() {
    let text = r#"
[simulation]
duration = 40.0
output_interval = 0.5
[environment]
depth = 500.0
[[line_types]]
name = "wire"
diameter = 0.04
mass_per_length = 5.0265
ea = 6.2832e7
damping = 1.0e-4
cn = 1.0
ct = 0.01
cm = 0.2
[[cables]]
name = "tether"
line_type = "wire"
length = 20.0
segments = 4
start = { fixed = [0.0, 0.0, -5.0] }
end = { free = [0.0, 0.0, -25.0], mass = 500.0, volume = 0.064, drag_area = 0.3, added_mass = 1.0 }
initial = "catenary"
winch = { end = "start", schedule = "rates", rates = [[0.0, 0.0], [5.0, 0.5]], drum_length = 300.0 }
"#;
    let sc = Scenario::parse(text, Path::new("/tmp/deploy.toml")).unwrap();
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let mut opts = SolverOptions::default();
    let plan = cablesim::sim::plan_steps(&sc, &lay, &opts, 40.0, sc.sim.dt).unwrap();
    opts.dt = plan.dt;
    let mut s = CpuSolver::with_winches(sc.model.clone(), sc.winches.clone(), &pos, opts).unwrap();
    let lt = &sc.model.line_types[0];
    let (rho, g) = (1025.0, 9.81);
    let w = lt.wet_weight_per_length(g, rho);
    let clump_wet = (500.0 - rho * 0.064) * g;
    let drag_t = 0.5 * rho * lt.ct * std::f64::consts::PI * lt.diameter;
    let (speed, l_s) = (0.5, 5.0);
    let mut worst = (0.0f64, f64::INFINITY, 0.0f64);
    let mut checked = 0;
    while s.t() < 40.0 - 1e-9 {
        s.advance(plan.steps_per_output).unwrap();
        let ev = s.evaluate().unwrap();
        let st = &s.winch_status()[0];
        let l = st.deployed_length;
        let top = -ev.reaction[0][2];
        let weight = w * l + clump_wet;
        let eps = top / lt.ea;
        let d_max = (0.5 * rho * 0.3 + drag_t * l) * (speed * (1.0 + eps)).powi(2);
        let d_min = (0.5 * rho * 0.3 + drag_t * (l - 1.5 * l_s)) * speed * speed;
        // The variable element's axial force is elastic (no spurious damping).
        let c = &s.layout().cables[0];
        let e = c.elements[0] as usize;
        let (a, b) = (s.r[c.nodes[0] as usize], s.r[c.nodes[1] as usize]);
        let elastic = lt.ea * ((b - a).norm() / st.variable_l0 - 1.0);
        if s.t() >= 15.0 {
            let deficit = weight - top;
            let tol = 0.02 * d_max;
            assert!(
                deficit >= d_min - tol && deficit <= d_max + tol,
                "t = {}: W - T = {deficit} N outside [{d_min}, {d_max}] N",
                s.t()
            );
            assert!(
                (ev.tension[e] - elastic).abs() < 0.5,
                "t = {}: variable element {} N vs elastic {elastic} N",
                s.t(),
                ev.tension[e]
            );
            worst.0 = worst.0.max(deficit);
            worst.1 = worst.1.min(deficit);
            worst.2 = worst.2.max(d_max);
            checked += 1;
        }
    }
    let st = &s.winch_status()[0];
    println!(
        "L = {} m, {} elements; W - T in [{:.3}, {:.3}] N, D_max up to {:.3} N",
        st.deployed_length, st.elements, worst.1, worst.0, worst.2
    );
    assert!(checked >= 50 && st.elements > 6 && st.deployed_length > 35.0);
}

/// The closed-form mass-flow force equals Eq. 39 evaluated numerically: the convective
/// acceleration of material points (finite differences of their trajectories at fixed
/// `p`, less the interpolated node accelerations), projected on the shape functions by
/// Gauss quadrature, for arbitrary smooth node motions and payout.
#[test]
fn mass_flow_force_is_eq39_of_the_material_acceleration() {
    let rm = |t: f64| V::new(t.sin(), 0.3 * t * t, -2.0 + (2.0 * t).cos());
    let rw = |t: f64| V::new(0.5 * t, 1.0 + 0.1 * (3.0 * t).sin(), 0.2 * t * t * t);
    let (pm, mbar) = (3.0, 7.0);
    let len = |t: f64| 5.0 + 0.7 * t + 0.4 * t * t - 0.3 * t * t * t;
    let t0 = 0.8;
    let h = 1e-3;
    let d1 = |f: &dyn Fn(f64) -> V| (f(t0 + h) - f(t0 - h)) / (2.0 * h);
    let d2 = |f: &dyn Fn(f64) -> V| (f(t0 + h) - f(t0) * 2.0 + f(t0 - h)) / (h * h);
    let (am, aw) = (d2(&rm), d2(&rw));
    let l0 = len(t0) - pm;
    // 4-point Gauss-Legendre on [0, 1].
    let gp = [
        (0.5 - 0.430568155797026, 0.173927422568727),
        (0.5 - 0.169990521792428, 0.326072577431273),
        (0.5 + 0.169990521792428, 0.326072577431273),
        (0.5 + 0.430568155797026, 0.173927422568727),
    ];
    let (mut fm, mut fw) = (V::zero(), V::zero());
    for (xi, wgt) in gp {
        let p = pm + xi * l0;
        let mat = |t: f64| {
            let x = (p - pm) / (len(t) - pm);
            rm(t) * (1.0 - x) + rw(t) * x
        };
        let conv = d2(&mat) - am * (1.0 - xi) - aw * xi;
        fm -= conv * (mbar * l0 * wgt * (1.0 - xi));
        fw -= conv * (mbar * l0 * wgt * xi);
    }
    let rate = (len(t0 + h) - len(t0 - h)) / (2.0 * h);
    let accel = (len(t0 + h) - 2.0 * len(t0) + len(t0 - h)) / (h * h);
    let (cm, cw) = mass_flow_forces(mbar, l0, rate, accel, rm(t0), rw(t0), d1(&rm), d1(&rw));
    let err = ((cm - fm).norm() + (cw - fw).norm()) / (fm.norm() + fw.norm());
    println!(
        "Eq. 39: numeric {fm:?} {fw:?}, closed form {cm:?} {cw:?}; relative difference {err:.2e}"
    );
    assert!(fm.norm() > 1.0, "a test with a real force");
    assert!(err < 1e-5, "{err}");
}

/// Impossible schedules stop the run between steps, naming the cable and the time.
#[test]
fn retrieval_past_the_last_node_and_payout_past_the_drum_are_errors() {
    let (l_s, dt) = (2.0, 2e-4);
    for end in [WinchEnd::Start, WinchEnd::End] {
        // 10 m hauled in at 1 m/s: at one element the last may not go below 1 m, at 9 s.
        let def = hanging(rope(), 5, l_s, clump(20.0), end, [0.0; 3]);
        let mut s = solver(
            def.clone(),
            winch(end, PayoutSchedule::constant(-1.0).unwrap(), 100.0, l_s),
            dt,
            Scheme::Symplectic,
        );
        match s.advance((12.0 / dt) as u64) {
            Err(Error::Winch {
                cable,
                time,
                message,
            }) => {
                assert_eq!(cable, "c0");
                assert!((9.0..9.0 + 2.0 * dt).contains(&time), "{time}");
                assert!(message.contains("past the cable's last node"), "{message}");
                let text = Error::Winch {
                    cable,
                    time,
                    message,
                }
                .to_string();
                assert!(text.contains("cable 'c0' at t = 9.000"), "{text}");
            }
            other => panic!("expected a winch error, got {other:?}"),
        }
        assert_eq!(s.winch_status()[0].elements, 1);
        // 10 m on a 12 m drum paid out at 1 m/s: the drum is empty at 2 s.
        let mut s = solver(
            def,
            winch(end, PayoutSchedule::constant(1.0).unwrap(), 12.0, l_s),
            dt,
            Scheme::Symplectic,
        );
        match s.advance((5.0 / dt) as u64) {
            Err(Error::Winch { time, message, .. }) => {
                assert!((2.0..2.0 + 2.0 * dt).contains(&time), "{time}");
                assert!(message.contains("drum_length = 12"), "{message}");
            }
            other => panic!("expected a winch error, got {other:?}"),
        }
    }
}

/// Laying on the seabed (examples/case3_laying.toml): a ship moving at the payout
/// speed lays the cable. Mass stays `mbar L`; the laid cable rests on the seabed
/// (penetration of the order of its weight over the seabed stiffness, no vertical
/// motion) and friction holds it still; the grounded length grows at the ship's speed;
/// once the start-up transient is over, the top force is steady.
#[test]
fn laying_on_the_seabed_from_a_moving_ship() {
    let sc = Scenario::load("examples/case3_laying.toml").unwrap();
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let mut opts = SolverOptions::default();
    let plan = cablesim::sim::plan_steps(&sc, &lay, &opts, 60.0, sc.sim.dt).unwrap();
    opts.dt = plan.dt;
    let mut s = CpuSolver::with_winches(sc.model.clone(), sc.winches.clone(), &pos, opts).unwrap();
    let lt = &sc.model.line_types[0];
    let seabed = -30.0;
    let mut grounded = Vec::new();
    let mut top = Vec::new();
    while s.t() < 60.0 - 1e-9 {
        s.advance(plan.steps_per_output).unwrap();
        let st = &s.winch_status()[0];
        let l0: f64 = s.element_l0().iter().sum();
        assert!((l0 - st.deployed_length).abs() < 1e-12 * l0);
        assert!((st.deployed_length - (60.0 + s.t())).abs() < 1e-9);
        let c = &s.layout().cables[0];
        let on_bed: Vec<usize> = c
            .nodes
            .iter()
            .map(|&n| n as usize)
            .filter(|&n| s.r[n].z < seabed + 1e-3)
            .collect();
        for &n in &on_bed {
            // Penetration about w lt / K (1.2e-5 m), no vertical motion but a node's
            // lift-off: node 5 rises at 1.2-3.0 mm/s at t = 11 s with the contact's
            // damping implicit (dt 8.5e-5 to 6.8e-4 s; the explicit contact at its
            // 0.2 ms step had it below 1 mm/s).
            assert!(s.r[n].z > seabed - 1e-4, "node sinks: {:?}", s.r[n]);
            assert!(s.v[n].z.abs() < 5e-3, "{:?}", s.v[n]);
        }
        grounded.push(on_bed.len());
        top.push(s.evaluate().unwrap().reaction[0]);
    }
    // Laid cable lies still on the seabed once the span travels steadily.
    let c = &s.layout().cables[0];
    let still = c
        .nodes
        .iter()
        .map(|&n| n as usize)
        .filter(|&n| s.r[n].z < seabed + 1e-3 && s.r[n].x < 40.0)
        .map(|n| s.v[n].norm())
        .fold(0.0, f64::max);
    let (f40, f60) = (V::from_f64(top[39]), V::from_f64(top[59]));
    let drift = (f60 - f40).norm() / f60.norm();
    println!(
        "grounded nodes at 10, 30, 60 s: {}, {}, {}; top force at 60 s {:?} N (drift since 40 s {:.2e}); laid cable speed up to {still:.2e} m/s",
        grounded[9], grounded[29], grounded[59], f60.to_f64(), drift
    );
    assert!(still < 1e-3, "{still}");
    assert!(drift < 0.01, "{drift}");
    // 40 m of seabed covered in 40 s: about eight more 5 m elements on the bed.
    assert!(grounded[59] >= grounded[19] + 7, "{grounded:?}");
    let wet = lt.wet_weight_per_length(9.81, 1025.0);
    assert!(f60.norm() > wet * 25.0, "the span's weight at least");
}
