//! The drawing: one function per chart.

use super::data::{GumbelData, Profile, Series};
use super::SIZE;
use crate::error::Error;
use plotters::prelude::*;
use std::path::Path;

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Makes DejaVu Sans the sans-serif font (ab_glyph reads no system fonts).
pub fn register_font() {
    // Registering twice replaces the same font: harmless.
    let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
}

fn plot_err(path: &Path) -> impl Fn(Box<dyn std::error::Error>) -> Error + '_ {
    move |e| Error::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// A range around `lo..hi` with 5% margins (a unit range around a single value).
fn padded(lo: f64, hi: f64) -> std::ops::Range<f64> {
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0..1.0;
    }
    let span = hi - lo;
    let m = if span > 0.0 {
        0.05 * span
    } else {
        lo.abs().max(1.0) * 0.05
    };
    (lo - m)..(hi + m)
}

fn bounds(points: impl Iterator<Item = (f64, f64)>) -> ((f64, f64), (f64, f64)) {
    points.fold(
        (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        ),
        |((x0, x1), (y0, y1)), (x, y)| ((x0.min(x), x1.max(x)), (y0.min(y), y1.max(y))),
    )
}

fn colour(k: usize) -> RGBAColor {
    Palette99::pick(k).to_rgba()
}

/// Lines of `series` on labelled axes in `area`.
fn lines(
    area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    equal: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    let ((x0, x1), (y0, y1)) = bounds(series.iter().flat_map(|s| s.points.iter().copied()));
    let (mut xr, mut yr) = (padded(x0, x1), padded(y0, y1));
    if equal {
        // Same metres per pixel on both axes, so that shapes are not distorted.
        let (w, h) = area.dim_in_pixel();
        let (pw, ph) = (w.saturating_sub(110) as f64, h.saturating_sub(110) as f64);
        let (sx, sy) = ((xr.end - xr.start) / pw, (yr.end - yr.start) / ph);
        if sx > sy {
            let c = 0.5 * (yr.start + yr.end);
            yr = (c - 0.5 * sx * ph)..(c + 0.5 * sx * ph);
        } else {
            let c = 0.5 * (xr.start + xr.end);
            xr = (c - 0.5 * sy * pw)..(c + 0.5 * sy * pw);
        }
    }
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 26))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(90)
        .build_cartesian_2d(xr, yr)?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    for (k, s) in series.iter().enumerate() {
        let c = colour(k);
        chart
            .draw_series(LineSeries::new(s.points.iter().copied(), c.stroke_width(2)))?
            .label(s.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3)));
    }
    if series.len() > 1 {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
    }
    Ok(())
}

/// `end_forces.png`: force magnitude at each cable end against time.
pub fn end_forces(path: &Path, series: &[Series]) -> Result<(), Error> {
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::new(path, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        // kN reads better than N for mooring loads.
        let kn: Vec<Series> = series
            .iter()
            .map(|s| Series {
                label: s.label.clone(),
                points: s.points.iter().map(|&(t, f)| (t, f / 1e3)).collect(),
            })
            .collect();
        lines(
            &root,
            "End forces",
            "time (s)",
            "force magnitude (kN)",
            &kn,
            false,
        )?;
        root.present()?;
        Ok(())
    };
    draw().map_err(plot_err(path))
}

/// `profiles.png`: side view (x-z) and plan view (x-y) of every cable at each time.
pub fn profiles(path: &Path, profiles: &[Profile]) -> Result<(), Error> {
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::new(path, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let (side, plan) = root.split_horizontally(SIZE.0 / 2);
        let view = |a: usize, b: usize| -> Vec<Series> {
            profiles
                .iter()
                .map(|p| Series {
                    label: format!("{} t = {} s", p.cable, p.time),
                    points: p.nodes.iter().map(|x| (x[a], x[b])).collect(),
                })
                .collect()
        };
        lines(&side, "Side view", "x (m)", "z (m)", &view(0, 2), true)?;
        lines(&plan, "Plan view", "x (m)", "y (m)", &view(0, 1), true)?;
        root.present()?;
        Ok(())
    };
    draw().map_err(plot_err(path))
}

/// `gumbel_*.png`: the seed maxima against their reduced variate, and the fitted line.
pub fn gumbel(path: &Path, g: &GumbelData) -> Result<(), Error> {
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::new(path, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let pts = g.points();
        let ((x0, x1), (y0, y1)) = bounds(pts.iter().copied());
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "Gumbel plot: {}, sea state {} ({})",
                    g.channel.0, g.sea_state.0, g.sea_state.1
                ),
                ("sans-serif", 26),
            )
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d(padded(x0, x1), padded(y0, y1))?;
        chart
            .configure_mesh()
            .x_desc(format!("seed maximum ({})", g.channel.1))
            .y_desc("reduced variate -ln(-ln p)")
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 18))
            .draw()?;
        let c = colour(0);
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 6, c.filled())))?
            .label("seed maxima")
            .legend(move |(x, y)| Circle::new((x + 10, y), 6, c.filled()));
        if let Some((mu, beta)) = g.fit {
            let line = [y0, y1].map(|y| (mu + beta * y, y));
            let c = colour(1);
            chart
                .draw_series(LineSeries::new(line, c.stroke_width(2)))?
                .label(format!("fit: mu = {mu:.4e}, beta = {beta:.3e}"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()?;
        root.present()?;
        Ok(())
    };
    draw().map_err(plot_err(path))
}

/// `utilisation.png`: one bar per sea state and channel, with the limit 1 drawn.
pub fn utilisation(path: &Path, rows: &[(String, String, f64)]) -> Result<(), Error> {
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::new(path, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let top = rows.iter().map(|r| r.2).fold(1.0f64, f64::max) * 1.1;
        let n = rows.len();
        let mut chart = ChartBuilder::on(&root)
            .caption("Utilisation (design value / capacity)", ("sans-serif", 26))
            .margin(15)
            .x_label_area_size(60)
            .y_label_area_size(90)
            .build_cartesian_2d(-0.5f64..(n as f64 - 0.5), 0.0..top)?;
        let labels: Vec<String> = rows.iter().map(|r| format!("{} {}", r.0, r.1)).collect();
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(n.max(1))
            .x_label_formatter(&|x| {
                let k = x.round();
                if (x - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < labels.len() {
                    labels[k as usize].clone()
                } else {
                    String::new()
                }
            })
            .x_desc("sea state, channel")
            .y_desc("utilisation (-)")
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 18))
            .draw()?;
        chart.draw_series(rows.iter().enumerate().map(|(k, r)| {
            let c = if r.2 > 1.0 { RED.to_rgba() } else { colour(0) };
            Rectangle::new([(k as f64 - 0.35, 0.0), (k as f64 + 0.35, r.2)], c.filled())
        }))?;
        chart
            .draw_series(LineSeries::new(
                [(-0.5, 1.0), (n as f64 - 0.5, 1.0)],
                BLACK.stroke_width(2),
            ))?
            .label("limit")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()?;
        root.present()?;
        Ok(())
    };
    draw().map_err(plot_err(path))
}
