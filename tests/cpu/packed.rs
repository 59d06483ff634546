//! Packed runs (`sim::pack`) on the CPU: each member of a packed run, in its own sea,
//! steps exactly as it does alone; packing refuses members that cannot share a run;
//! and a study run packed gives the same members as one run per member, for any batch
//! size.

use crate::common::{short_study, wave_members};
use cablesim::options::{Backend, Overrides};
use cablesim::sim::pack::{pack, packed_name};
use cablesim::sim::Simulation;
use cablesim::study::{PackedRun, StudyFile, StudyRunner};
use std::sync::atomic::AtomicBool;

fn cpu(duration: f64) -> Overrides {
    Overrides {
        backend: Some(Backend::Cpu),
        duration: Some(duration),
        ..Overrides::default()
    }
}

#[test]
fn a_member_of_a_packed_run_steps_as_it_does_alone() {
    let members = wave_members(3, 20);
    let packed = pack(&members).unwrap();
    assert_eq!(packed.scenario.sea_set().seas.len(), 3);
    let t = 3.0;
    let mut all = Simulation::new(packed.scenario.clone(), &cpu(t)).unwrap();
    all.advance_to(t).unwrap();
    let snap = all.snapshot().unwrap();
    let mut alone_tensions = Vec::new();
    for (pm, (_, sc)) in packed.members.iter().zip(&members) {
        let mut one = Simulation::new(sc.clone(), &cpu(t)).unwrap();
        assert_eq!(one.dt(), all.dt());
        one.advance_to(t).unwrap();
        let s1 = one.snapshot().unwrap();
        assert_eq!(snap.steps, s1.steps);
        assert_eq!(pm.cables.len(), s1.cables.len());
        for (c, c1) in snap.cables[pm.cables.clone()].iter().zip(&s1.cables) {
            assert_eq!(c.name, packed_name(&pm.prefix, &c1.name));
            // Blocks step independently: the same arithmetic, bit for bit.
            assert_eq!(c.positions, c1.positions, "{}", c.name);
            assert_eq!(c.tensions, c1.tensions, "{}", c.name);
            assert_eq!(c.end_forces, c1.end_forces, "{}", c.name);
        }
        // The RAO-driven vessel follows its member's waves, and carries its loads.
        let vessel = snap
            .bodies
            .iter()
            .find(|b| b.name == packed_name(&pm.prefix, "vessel"))
            .expect("the member's vessel");
        assert_eq!(s1.bodies.len(), 1);
        assert_eq!(vessel.position, s1.bodies[0].position);
        assert_eq!(vessel.force, s1.bodies[0].force);
        assert_eq!(vessel.moment, s1.bodies[0].moment);
        alone_tensions.push(s1.cables[0].tensions.clone());
    }
    // The members are in different seas: equal results would not show that each
    // member got its own.
    for j in 1..alone_tensions.len() {
        let d = alone_tensions[0]
            .iter()
            .zip(&alone_tensions[j])
            .map(|(a, b)| (a - b).abs() / a.abs())
            .fold(0.0f64, f64::max);
        assert!(d > 1e-3, "members 0 and {j} differ by only {d} in tension");
    }
}

#[test]
fn packing_refuses_members_that_cannot_share_a_run() {
    let mut members = wave_members(2, 4);
    members[1].1.model.env.depth = 140.0;
    let m = pack(&members).unwrap_err().to_string();
    assert!(m.contains("\"m1\"") && m.contains("environment"), "{m}");
    let mut members = wave_members(2, 4);
    members[1].1.sim.output_interval = 0.25;
    let m = pack(&members).unwrap_err().to_string();
    assert!(m.contains("[simulation]"), "{m}");
    let m = pack(&[]).unwrap_err().to_string();
    assert!(m.contains("at least one member"), "{m}");
}

#[test]
fn a_study_run_packed_equals_one_run_per_member_for_any_batch_size() {
    let dir = tempfile::tempdir().unwrap();
    let file = StudyFile::load(short_study(dir.path(), 3.0, 2)).unwrap();
    let runner = StudyRunner::new(&file).unwrap();
    let members = runner.plan().members.clone();
    assert_eq!(members.len(), 4);
    let stop = AtomicBool::new(false);
    let none = |_: f64| {};
    let keep = |_: &cablesim::study::MemberResult| Ok(());
    let alone = runner.run(&members, &stop, &none, &keep).unwrap();
    assert_eq!(alone.len(), 4);
    for batch in [None, Some(1), Some(3)] {
        let how = PackedRun {
            backend: Backend::Cpu,
            precision: None,
            batch,
        };
        let packed = runner
            .run_packed(&members, &how, &stop, &none, &keep)
            .unwrap();
        // Compared as JSON: a statistic may be NaN (no up-crossing period).
        let json = |r: &[cablesim::study::MemberResult]| serde_json::to_string(r).unwrap();
        assert_eq!(json(&packed), json(&alone), "batch {batch:?}");
    }
    // Not every member alike: the statistics depend on the member's sea.
    assert_ne!(
        serde_json::to_string(&alone[0].stats).unwrap(),
        serde_json::to_string(&alone[2].stats).unwrap()
    );
}
