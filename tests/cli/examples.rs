//! Every example scenario loads, packs and plans (what `cablesim check` does), so the
//! files the README points to keep working as the format evolves.

use cablesim::model::Layout;
use cablesim::options::SolverOptions;
use cablesim::scenario::Scenario;
use cablesim::sim::plan_steps;

#[test]
fn every_example_checks() {
    let mut n = 0;
    for entry in std::fs::read_dir("examples").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        let sc = Scenario::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let (lay, _) =
            Layout::build(&sc.model).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let opts = SolverOptions {
            scheme: sc.sim.scheme,
            baumgarte: sc.sim.baumgarte,
            ..Default::default()
        };
        let plan = plan_steps(&sc, &lay, &opts, sc.sim.duration, sc.sim.dt)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(plan.dt > 0.0 && plan.total_steps > 0, "{}", path.display());
        assert!(
            plan.warning.is_none(),
            "{}: {:?}",
            path.display(),
            plan.warning
        );
        n += 1;
    }
    assert!(n >= 9, "found only {n} examples");
}
