//! Output for viewers: `points.csv` (shared points), the ParaView files (`--vtk`) and
//! `cablesim plot`, on a buoy held by three chains.

use cablesim::plot::data::{GumbelData, Series};
use cablesim::sim::Simulation;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

const BIN: &str = env!("CARGO_BIN_EXE_cablesim");
const BUOY: &str = "tests/data/buoy_three_chains.toml";
/// The buoy's weight less buoyancy, N (negative: it floats): (2000 - 1025 * 10) * 9.81.
const BUOY_WET_WEIGHT: f64 = (2000.0 - 1025.0 * 10.0) * 9.81;

/// One run of the buoy scenario with `--vtk`, shared by the tests (kept for the run).
fn buoy_run() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let out = Command::new(BIN)
            .args(["run", BUOY, "--vtk", "-q", "--out"])
            .arg(dir.path())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        dir
    })
    .path()
}

fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

fn f(s: &str) -> f64 {
    s.parse().unwrap()
}

#[test]
fn buoy_point_force_balances_its_net_buoyancy_at_rest() {
    // In memory, at t = 0 (the relaxed static equilibrium): the chains pull the buoy
    // down by exactly its buoyancy less its weight, and the three horizontal pulls cancel.
    let mut sim = Simulation::from_file(BUOY, &Default::default()).unwrap();
    let s = sim.snapshot().unwrap();
    assert_eq!(s.points.len(), 1);
    let p = &s.points[0];
    assert_eq!(p.name, "buoy");
    let net = -BUOY_WET_WEIGHT;
    assert!(
        (p.force[2] + net).abs() < 1e-3 * net,
        "{:?} vs {net}",
        p.force
    );
    assert!(p.force[0].hypot(p.force[1]) < 1e-3 * net, "{:?}", p.force);
    // The buoy has risen until the chains are taut: above its starting depth.
    assert!(p.position[2] > -20.5, "{:?}", p.position);
    // It is the sum of the three chains' end forces at the buoy.
    let sum: f64 = s.cables.iter().map(|c| c.end_forces.end[2]).sum();
    assert!((sum - p.force[2]).abs() < 1e-9 * net);

    // points.csv: a row per output time, still in balance at the end (the buoy stays put).
    let rows = csv_rows(&buoy_run().join("points.csv"));
    let head = std::fs::read_to_string(buoy_run().join("points.csv")).unwrap();
    assert!(head.starts_with("time,point,x,y,z,fx,fy,fz\n"));
    let times: Vec<f64> = rows.iter().map(|r| f(&r[0])).collect();
    assert_eq!(times, [0.0, 0.5, 1.0, 1.5, 2.0]);
    for r in &rows {
        assert_eq!(r[1], "buoy");
        assert!((f(&r[7]) + net).abs() < 1e-2 * net, "{r:?}");
    }
    // A scenario without [[points]] has none in its snapshots.
    let mut sim = Simulation::from_file("examples/catenary.toml", &Default::default()).unwrap();
    assert!(sim.snapshot().unwrap().points.is_empty());
}

/// The numbers of `doc`'s `DataArray` named `name` (`None`: the points' coordinates).
fn data_array(doc: &roxmltree::Document, name: Option<&str>) -> Vec<f64> {
    let node = doc
        .descendants()
        .find(|n| {
            n.has_tag_name("DataArray")
                && match name {
                    Some(name) => n.attribute("Name") == Some(name),
                    // The points' coordinates: the DataArray inside <Points>.
                    None => n.parent().is_some_and(|p| p.has_tag_name("Points")),
                }
        })
        .unwrap_or_else(|| panic!("no DataArray {name:?}"));
    node.text()
        .unwrap_or("")
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

#[test]
fn vtk_files_hold_the_cables_bodies_and_times() {
    let dir = buoy_run().join("vtk");
    let pvd = std::fs::read_to_string(dir.join("cablesim.pvd")).unwrap();
    let doc = roxmltree::Document::parse(&pvd).unwrap();
    let sets: Vec<(f64, String, String)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("DataSet"))
        .map(|n| {
            (
                f(n.attribute("timestep").unwrap()),
                n.attribute("part").unwrap().to_string(),
                n.attribute("file").unwrap().to_string(),
            )
        })
        .collect();
    // Five output times, each with the cables (part 0) and the buoy (part 1).
    assert_eq!(sets.len(), 10);
    let cable_times: Vec<f64> = sets.iter().filter(|s| s.1 == "0").map(|s| s.0).collect();
    assert_eq!(cable_times, [0.0, 0.5, 1.0, 1.5, 2.0]);

    let positions = csv_rows(&buoy_run().join("positions.csv"));
    let tensions = csv_rows(&buoy_run().join("tensions.csv"));
    let points = csv_rows(&buoy_run().join("points.csv"));
    for (t, part, file) in &sets {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let piece = doc.descendants().find(|n| n.has_tag_name("Piece")).unwrap();
        let n_points: usize = piece.attribute("NumberOfPoints").unwrap().parse().unwrap();
        let xyz = data_array(&doc, None);
        assert_eq!(xyz.len(), 3 * n_points);
        if part == "0" {
            // 3 chains of 21 nodes, node by node in cable order; each of their 60
            // elements a two-point line.
            assert_eq!(n_points, 63);
            assert_eq!(piece.attribute("NumberOfLines"), Some("60"));
            let conn = data_array(&doc, Some("connectivity"));
            let want_conn: Vec<f64> = (0..3)
                .flat_map(|c| (0..20).flat_map(move |k| [21 * c + k, 21 * c + k + 1]))
                .map(f64::from)
                .collect();
            assert_eq!(conn, want_conn);
            let want_off: Vec<f64> = (1..=60).map(|e| f64::from(2 * e)).collect();
            assert_eq!(data_array(&doc, Some("offsets")), want_off);
            assert_eq!(data_array(&doc, Some("velocity")).len(), 3 * 63);
            // Node 5 of chain2 (point 26): its position and the mean of its elements'
            // tensions, as the CSV files give them at this time.
            let row = |rows: &[Vec<String>], cable: &str, k: &str| -> Vec<f64> {
                rows.iter()
                    .find(|r| f(&r[0]) == *t && r[1] == cable && r[2] == k)
                    .unwrap()[3..]
                    .iter()
                    .map(|v| f(v))
                    .collect()
            };
            let p = row(&positions, "chain2", "5");
            assert_eq!(&xyz[3 * 26..3 * 27], &p[..]);
            let tn = data_array(&doc, Some("tension"))[26];
            let want = 0.5 * (row(&tensions, "chain2", "4")[0] + row(&tensions, "chain2", "5")[0]);
            assert!((tn - want).abs() <= 1e-12 * want.abs(), "{tn} vs {want}");
            // Element 4 of chain2 (cell 24): its own tension, exactly as tensions.csv.
            let te = data_array(&doc, Some("element_tension"))[24];
            assert_eq!(te, row(&tensions, "chain2", "4")[0]);
        } else {
            assert_eq!(n_points, 1);
            assert_eq!(piece.attribute("NumberOfVerts"), Some("1"));
            let r = points.iter().find(|r| f(&r[0]) == *t).unwrap();
            let want: Vec<f64> = r[2..].iter().map(|v| f(v)).collect();
            assert_eq!(&xyz[..], &want[..3]);
            assert_eq!(data_array(&doc, Some("force")), &want[3..]);
        }
    }
}

/// A decoded 8-bit RGB picture, row by row.
struct Rgb {
    width: u32,
    height: u32,
    pixels: Vec<[u8; 3]>,
}

impl Rgb {
    fn dimensions(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn pixels(&self) -> impl Iterator<Item = &[u8; 3]> {
        self.pixels.iter()
    }

    /// `(x, y, pixel)`, x across and y down from the top left corner.
    fn enumerate_pixels(&self) -> impl Iterator<Item = (u32, u32, [u8; 3])> + '_ {
        let w = self.width as usize;
        (self.pixels.iter().enumerate()).map(move |(k, p)| ((k % w) as u32, (k / w) as u32, *p))
    }
}

/// Reads a PNG that `cablesim plot` wrote: it must be 8-bit RGB, one frame.
fn decode(path: &Path) -> Rgb {
    fn fail(path: &Path, e: impl std::fmt::Display) -> ! {
        panic!("{}: {e}", path.display())
    }
    let file = std::fs::File::open(path).unwrap_or_else(|e| fail(path, e));
    let mut reader = png::Decoder::new(file)
        .read_info()
        .unwrap_or_else(|e| fail(path, e));
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader
        .next_frame(&mut buf)
        .unwrap_or_else(|e| fail(path, e));
    assert_eq!(
        (info.color_type, info.bit_depth),
        (png::ColorType::Rgb, png::BitDepth::Eight),
        "{}",
        path.display()
    );
    let bytes = &buf[..info.buffer_size()];
    Rgb {
        width: info.width,
        height: info.height,
        pixels: bytes.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
    }
}

#[test]
fn plot_command_draws_end_forces_and_profiles() {
    let out = tempfile::tempdir().unwrap();
    let run = Command::new(BIN)
        .arg("plot")
        .arg(buoy_run())
        .args(["--times", "0,2", "--out"])
        .arg(out.path())
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for name in ["end_forces.png", "profiles.png"] {
        let img = decode(&out.path().join(name));
        assert_eq!(img.dimensions(), cablesim::plot::SIZE, "{name}");
        // Not blank: more than a few per cent of the pixels are drawn on.
        let inked = img.pixels().filter(|p| **p != [255, 255, 255]).count();
        assert!(inked > 5_000, "{name}: {inked} pixels drawn");
    }
    // The profiles read from positions.csv at the two chosen times.
    let prof =
        cablesim::plot::data::profiles(&buoy_run().join("positions.csv"), &[0.1, 1.9]).unwrap();
    let seen: Vec<(String, f64)> = prof.iter().map(|p| (p.cable.clone(), p.time)).collect();
    assert_eq!(seen.len(), 6);
    assert!(seen.contains(&("chain3".into(), 0.0)) && seen.contains(&("chain1".into(), 2.0)));
    assert!(prof.iter().all(|p| p.nodes.len() == 21));
    // A directory with nothing to plot is an error that names it.
    let empty = tempfile::tempdir().unwrap();
    let run = Command::new(BIN)
        .arg("plot")
        .arg(empty.path())
        .output()
        .unwrap();
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("nothing to plot"));
}

#[test]
fn end_force_plot_puts_the_peak_at_its_time() {
    // A triangle from t = 0 to 10 s peaking at t = 3 s: the highest drawn pixel of the
    // line sits 30% of the way across the line's horizontal extent.
    let out = tempfile::tempdir().unwrap();
    let csv = out.path().join("end_forces.csv");
    let mut text = String::from("time,cable,end,fx,fy,fz\n");
    for k in 0..=100 {
        let t = k as f64 * 0.1;
        let f = if t <= 3.0 {
            t
        } else {
            3.0 - (t - 3.0) * 3.0 / 7.0
        } * 1e3
            + 500.0;
        text += &format!("{t},a,end,0,0,{f}\n");
    }
    std::fs::write(&csv, text).unwrap();
    let series: Vec<Series> = cablesim::plot::data::end_force_series(&csv).unwrap();
    assert_eq!(series.len(), 1);
    assert_eq!(series[0].points.len(), 101);
    let png = out.path().join("plots");
    cablesim::plot::plot_dir(out.path(), &png, &[]).unwrap();
    let img = decode(&png.join("end_forces.png"));
    // The line's colour (the first of the palette): strongly red, little green.
    let line: Vec<(u32, u32)> = img
        .enumerate_pixels()
        .filter(|(_, _, p)| p[0] > 180 && p[1] < 80 && p[2] < 120)
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(line.len() > 500, "{} line pixels", line.len());
    let x0 = line.iter().map(|p| p.0).min().unwrap() as f64;
    let x1 = line.iter().map(|p| p.0).max().unwrap() as f64;
    let top = line.iter().min_by_key(|p| p.1).unwrap();
    let want = x0 + 0.3 * (x1 - x0);
    assert!(
        (top.0 as f64 - want).abs() <= 4.0,
        "peak at column {} not {want}",
        top.0
    );
}

#[test]
fn study_tables_give_gumbel_points_and_utilisation_chart() {
    // Plotting positions: the i-th smallest of n maxima at -ln(-ln(i / (n + 1))).
    let g = GumbelData {
        sea_state: (0, "s".into()),
        channel: ("c".into(), "N".into()),
        maxima: vec![1.0, 2.0, 3.0],
        fit: None,
    };
    let pts = g.points();
    assert_eq!(pts[1], (2.0, -(-(0.5f64).ln()).ln()));
    assert!(pts[0].1 < pts[1].1 && pts[1].1 < pts[2].1);
    assert!((pts[1].1 - 0.366_512_920_581_664_3).abs() < 1e-15);

    // Small study tables with the columns `cablesim study` writes.
    let dir = tempfile::tempdir().unwrap();
    let members = "member,sea_state,sea_state_name,seed,wave_seed,status,channel,unit,samples,max,time_of_max,min,time_of_min,mean,std,up_crossings,up_crossing_period,error\n\
        0,0,calm,1,1,completed,line1.end.tension,N,10,1000,1,0,0,1,1,1,1,\n\
        1,0,calm,2,2,completed,line1.end.tension,N,10,1200,1,0,0,1,1,1,1,\n\
        2,0,calm,3,3,completed,line1.end.tension,N,10,1100,1,0,0,1,1,1,1,\n\
        3,0,calm,4,4,failed,line1.end.tension,N,0,,,,,,,0,,diverged\n";
    let study = "sea_state,sea_state_name,hs,tp,gamma,heading,current_speed,current_heading,channel,unit,seeds,failed,mean,std,up_crossing_period,max_mean,max_std,max_largest,min_smallest,mle_mu,mle_beta,moments_mu,moments_beta,fit,mpm,quantile_p,quantile,capacity,design_tension,utilisation\n\
        0,calm,2,8,,0,0,0,line1.end.tension,N,3,1,1,1,1,1100,100,1200,0,1050,80,1050,80,mle,1050,0.9,1230,2000,1230,0.615\n";
    std::fs::write(dir.path().join("members.csv"), members).unwrap();
    std::fs::write(dir.path().join("study.csv"), study).unwrap();
    let data = cablesim::plot::data::gumbel_data(
        &dir.path().join("members.csv"),
        &dir.path().join("study.csv"),
    )
    .unwrap();
    assert_eq!(data.len(), 1);
    assert_eq!(data[0].maxima, [1000.0, 1100.0, 1200.0]);
    assert_eq!(data[0].fit, Some((1050.0, 80.0)));
    let written = cablesim::plot::plot_dir(dir.path(), &dir.path().join("plots"), &[]).unwrap();
    let names: Vec<PathBuf> = written
        .iter()
        .map(|p| p.file_name().unwrap().into())
        .collect();
    assert_eq!(
        names,
        [
            PathBuf::from("gumbel_0_line1_end_tension.png"),
            PathBuf::from("utilisation.png")
        ]
    );
    for p in &written {
        assert_eq!(decode(p).dimensions(), cablesim::plot::SIZE);
    }
}

#[test]
fn body_plot_draws_the_pose_and_the_velocities() {
    // A bodies.csv with a free body's columns: x = sin t, roll = 10 sin t (deg),
    // vx = cos t, wx = 10 deg/s cos t in rad/s.
    let out = tempfile::tempdir().unwrap();
    let csv = out.path().join("bodies.csv");
    let mut text =
        String::from("time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz,vx,vy,vz,wx,wy,wz\n");
    for k in 0..=60 {
        let t = k as f64 * 0.1;
        let w = 10f64.to_radians() * t.cos();
        text += &format!(
            "{t},buoy,{},0,-20,{},0,0,0,0,0,0,0,0,{},0,0,{w},0,0\n",
            t.sin(),
            10.0 * t.sin(),
            t.cos()
        );
    }
    std::fs::write(&csv, text).unwrap();
    let m = cablesim::plot::data::body_motion(&csv).unwrap();
    let labels: Vec<&str> = m.position.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(labels, ["buoy x", "buoy y", "buoy z"]);
    assert_eq!(m.angles[0].label, "buoy roll");
    assert_eq!(m.velocity.len(), 3);
    assert_eq!(m.rates[0].points.len(), 61);
    // Rates in degrees per second.
    assert!((m.rates[0].points[0].1 - 10.0).abs() < 1e-12);
    assert!((m.position[0].points[10].1 - 1f64.sin()).abs() < 1e-12);
    let png = out.path().join("plots");
    let written = cablesim::plot::plot_dir(out.path(), &png, &[]).unwrap();
    assert!(written.iter().any(|p| p.ends_with("bodies.png")));
    let img = decode(&png.join("bodies.png"));
    let inked = img.pixels().filter(|p| **p != [255, 255, 255]).count();
    assert!(inked > 5_000, "{inked} pixels drawn");
    // Without velocity columns (prescribed bodies) it still draws, two panels.
    let csv2 = out.path().join("p");
    std::fs::create_dir_all(&csv2).unwrap();
    std::fs::write(
        csv2.join("bodies.csv"),
        "time,body,x,y,z,roll,pitch,yaw,fx,fy,fz,mx,my,mz\n0,ship,0,0,0,0,0,0,0,0,0,0,0,0\n1,ship,1,0,0,2,0,0,0,0,0,0,0,0\n",
    )
    .unwrap();
    let m2 = cablesim::plot::data::body_motion(&csv2.join("bodies.csv")).unwrap();
    assert!(m2.velocity.is_empty() && m2.rates.is_empty());
    cablesim::plot::plot_dir(&csv2, &csv2.join("plots"), &[]).unwrap();
}
