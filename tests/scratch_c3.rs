use cablesim::ancf::run::cable_config;
use cablesim::ancf::{AncfCable, AncfEnd};
use cablesim::scenario::Scenario;
#[test]
fn scratch() {
    let sc = Scenario::load(std::path::Path::new("/tmp/c3.toml")).unwrap();
    let (lay, pos, _) = cablesim::sim::prepare(&sc).unwrap();
    let mut cfg = cable_config(&sc, &Default::default(), 0).unwrap();
    cfg.winch = None;
    cfg.line_type.ei = 0.0;
    cfg.start = AncfEnd::fixed(cfg.start.route.as_ref().unwrap().eval(0.0).r);
    let mut c = AncfCable::new(cfg).unwrap();
    let info = &lay.cables[0];
    let pts: Vec<[f64; 3]> = info.nodes.iter().map(|&n| pos[n as usize]).collect();
    c.set_shape(|s| {
        let k = ((s / 5.0).floor() as usize).min(pts.len() - 2);
        let u = s / 5.0 - k as f64;
        [0, 1, 2].map(|i| pts[k][i] + u * (pts[k + 1][i] - pts[k][i]))
    });
    let sl = c.node_slopes();
    eprintln!(
        "slopes |r'|: {:?}",
        sl.iter()
            .map(|s| format!("{:.6}", (s[0] * s[0] + s[2] * s[2]).sqrt()))
            .collect::<Vec<_>>()
    );
    for k in 0..30 {
        let t = c.t();
        let p = c.node_positions();
        let tn: Vec<String> = (0..24)
            .map(|j| format!("{:.0}", c.tension_at(2.5 * j as f64 + 1.25)))
            .collect();
        eprintln!(
            "t {t:.3} x7 {:.5} x9 {:.5} x5 {:.4} z5 {:.4} T {:?}",
            p[7][0] - pts[7][0],
            p[9][0] - pts[9][0],
            p[5][0] - pts[5][0],
            p[5][2] - pts[5][2],
            tn
        );
        c.advance_time(if k < 10 { 0.02 } else { 0.5 }).unwrap();
    }
}
