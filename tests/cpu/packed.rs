//! Packed runs (`sim::pack`) on the CPU: each member of a packed run, in its own sea,
//! steps exactly as it does alone; packing refuses members that cannot share a run;
//! and a study run packed gives the same members as one run per member, for any batch
//! size; a member that blows up in a packed run (run again alone, the others again
//! without it) counts once in the progress.

use super::common::{short_study, study_with_a_failing_member, wave_members};
use cablesim::options::{Backend, Overrides};
use cablesim::sim::pack::{pack, packed_name};
use cablesim::sim::Simulation;
use cablesim::study::{MemberResult, MemberStatus, PackedRun, StudyFile, StudyRunner};
use std::sync::atomic::AtomicBool;
use std::sync::Mutex;

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

/// Members 3 (which blows up at about 17 s of its 20) and 4 packed in one batch: the
/// batch stops at the blow-up, member 3 runs again alone and member 4 again alone.
/// The progress told, in member-seconds, never passes the study's total (2 x 20 s) and
/// ends on it, as when each member runs once; the records are those of one run per
/// member.
#[test]
fn a_member_run_again_after_a_packed_blow_up_counts_once_in_the_progress() {
    let dir = tempfile::tempdir().unwrap();
    let file = StudyFile::load(study_with_a_failing_member(dir.path())).unwrap();
    let runner = StudyRunner::new(&file).unwrap();
    let members = runner.plan().members[3..5].to_vec();
    let total = 2.0 * runner.plan().def.duration;
    let stop = AtomicBool::new(false);
    let keep = |_: &MemberResult| Ok(());
    // (sum told so far, the most it reached)
    let told = Mutex::new((0.0f64, 0.0f64));
    let progress = |dt: f64| {
        let mut t = told.lock().unwrap();
        t.0 += dt;
        t.1 = t.1.max(t.0);
    };
    let how = PackedRun {
        backend: Backend::Cpu,
        precision: None,
        batch: None,
    };
    let packed = runner
        .run_packed(&members, &how, &stop, &progress, &keep)
        .unwrap();
    let (sum, most) = *told.lock().unwrap();
    println!("packed: progress told {sum} member-s (at most {most}) of {total}");
    assert!(
        matches!(packed[0].status, MemberStatus::Failed { .. }),
        "member 3 did not fail: the case no longer tests a rerun"
    );
    assert_eq!(packed[1].status, MemberStatus::Completed);
    assert!((sum - total).abs() <= 1e-9 * total, "told {sum} of {total}");
    assert!(
        most <= total * (1.0 + 1e-12),
        "passed the total: {most} of {total}"
    );
    // One run per member tells the same total, and records the same members.
    *told.lock().unwrap() = (0.0, 0.0);
    let alone = runner.run(&members, &stop, &progress, &keep).unwrap();
    let (sum, _) = *told.lock().unwrap();
    assert!(
        (sum - total).abs() <= 1e-9 * total,
        "alone: told {sum} of {total}"
    );
    let json = |r: &[MemberResult]| serde_json::to_string(r).unwrap();
    assert_eq!(json(&packed), json(&alone));
}
