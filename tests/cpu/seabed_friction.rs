//! Seabed friction split along and across the line (`friction_axial`,
//! `friction_transverse`): the scenario keys and their errors.

use cablesim::scenario::Scenario;

#[test]
fn friction_keys_are_checked() {
    let base = |fr: &str| {
        format!(
            r#"
[simulation]
duration = 1.0
dt = "auto"
output_interval = 1.0

[environment]
depth = 50.0

[environment.seabed]
{fr}

[[line_types]]
name = "chain"
diameter = 0.1
mass_per_length = 100.0
ea = 1.0e9

[[cables]]
name = "a"
line_type = "chain"
length = 10.0
segments = 5
start = {{ fixed = [0.0, 0.0, -50.0] }}
end = {{ fixed = [10.0, 0.0, -50.0] }}
"#
        )
    };
    let p = std::path::Path::new("fric.toml");
    let e = Scenario::parse(&base("friction = 0.5\nfriction_transverse = 0.4"), p)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("friction_transverse") && e.contains("not both"),
        "{e}"
    );
    let e = Scenario::parse(&base("friction_axial = -0.1"), p)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("friction_axial") && e.contains("negative"),
        "{e}"
    );
    let sc = Scenario::parse(&base("friction = 0.5\nfriction_axial = 0.2"), p).unwrap();
    let sb = sc.model.env.seabed;
    assert_eq!((sb.friction, sb.mu_axial()), (0.5, 0.2));
    let sc = Scenario::parse(&base("friction_transverse = 0.7"), p).unwrap();
    let sb = sc.model.env.seabed;
    assert_eq!((sb.friction, sb.mu_axial()), (0.7, 0.0));
}
