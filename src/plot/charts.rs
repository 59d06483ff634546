//! The drawing: one function per chart.

use super::data::{BodyMotion, GumbelData, Profile, Series};
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

/// Draws `chart` on a white canvas of [`SIZE`] and writes it to `path` as an 8-bit RGB
/// PNG. plotters draws into a buffer here and `png` encodes it: plotters' own file
/// backend would need the `image` crate and its other codecs.
fn draw_png(
    path: &Path,
    chart: impl FnOnce(&Canvas) -> Result<(), Box<dyn std::error::Error>>,
) -> Result<(), Error> {
    let (w, h) = SIZE;
    let mut rgb = vec![0u8; 3 * w as usize * h as usize];
    let draw = |rgb: &mut [u8]| -> Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::with_buffer(rgb, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        chart(&root)?;
        root.present()?;
        Ok(())
    };
    draw(&mut rgb).map_err(plot_err(path))?;
    let write = || -> Result<(), Box<dyn std::error::Error>> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let mut png = png::Encoder::new(file, w, h);
        png.set_color(png::ColorType::Rgb);
        png.set_depth(png::BitDepth::Eight);
        // As the `image` crate's encoder did: fast deflate, a filter chosen per row (the
        // same bytes as the files plotters wrote through `image`).
        png.set_compression(png::Compression::Fast);
        png.set_filter(png::FilterType::Sub);
        png.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut png = png.write_header()?;
        png.write_image_data(&rgb)?;
        png.finish()?;
        Ok(())
    };
    write().map_err(plot_err(path))
}

/// What every chart draws on: the whole picture, in pixels.
type Canvas<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

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

/// An axis label in at most about five significant digits: `2.014e6` rather than
/// `2014000.0`.
fn tick(v: &f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        format!("{v:.3e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".into()
        } else {
            s.to_string()
        }
    }
}

fn colour(k: usize) -> RGBAColor {
    Palette99::pick(k).to_rgba()
}

/// How a chart's axes are ranged.
#[derive(Clone, Copy, PartialEq)]
enum Axes {
    /// The y axis starts at 0 (magnitudes), with room above the data for the legend.
    FromZero,
    /// Same metres per pixel on both axes, so that shapes are not distorted.
    Equal,
    /// Each axis around its data.
    Data,
}

/// The legend corner holding the fewest points of `series` (a corner is the outer 35%
/// of both axes' ranges), so that the legend hides as little as it can.
fn legend_corner(
    series: &[Series],
    x: &std::ops::Range<f64>,
    y: &std::ops::Range<f64>,
) -> SeriesLabelPosition {
    let (wx, wy) = (0.35 * (x.end - x.start), 0.35 * (y.end - y.start));
    let count = |right: bool, top: bool| {
        series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|(px, py)| {
                (if right {
                    *px > x.end - wx
                } else {
                    *px < x.start + wx
                }) && (if top {
                    *py > y.end - wy
                } else {
                    *py < y.start + wy
                })
            })
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, count(true, true)),
        (SeriesLabelPosition::UpperLeft, count(false, true)),
        (SeriesLabelPosition::LowerRight, count(true, false)),
        (SeriesLabelPosition::LowerLeft, count(false, false)),
    ]
    .into_iter()
    .min_by_key(|c| c.1)
    .map(|c| c.0)
    .expect("four corners")
}

/// The plotting area of a panel of `dim` pixels (less the caption and label areas).
fn plot_pixels(dim: (u32, u32)) -> (f64, f64) {
    (
        dim.0.saturating_sub(120) as f64,
        dim.1.saturating_sub(110) as f64,
    )
}

/// Ranges of `x` and `y` padded, and widened to equal scales for `Axes::Equal` in a
/// panel of `dim` pixels.
fn ranges(
    series: &[Series],
    axes: Axes,
    dim: (u32, u32),
) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
    let ((x0, x1), (y0, y1)) = bounds(series.iter().flat_map(|s| s.points.iter().copied()));
    let (mut xr, mut yr) = (padded(x0, x1), padded(y0, y1));
    match axes {
        Axes::FromZero => {
            let top = if y1.is_finite() && y1 > 0.0 { y1 } else { 1.0 };
            let extra = if series.len() > 1 {
                0.04 * series.len() as f64
            } else {
                0.0
            };
            yr = 0.0..top * (1.1 + extra);
        }
        Axes::Data => {}
        Axes::Equal => {
            let (pw, ph) = plot_pixels(dim);
            let (sx, sy) = ((xr.end - xr.start) / pw, (yr.end - yr.start) / ph);
            if sx > sy {
                let c = 0.5 * (yr.start + yr.end);
                yr = (c - 0.5 * sx * ph)..(c + 0.5 * sx * ph);
            } else {
                let c = 0.5 * (xr.start + xr.end);
                xr = (c - 0.5 * sy * pw)..(c + 0.5 * sy * pw);
            }
        }
    }
    (xr, yr)
}

/// Lines of `series` on labelled axes in `area`.
fn lines(
    area: &Canvas,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    axes: Axes,
) -> Result<(), Box<dyn std::error::Error>> {
    let (xr, yr) = ranges(series, axes, area.dim_in_pixel());
    let corner = if axes == Axes::FromZero {
        SeriesLabelPosition::UpperRight
    } else {
        legend_corner(series, &xr, &yr)
    };
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
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
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
            .position(corner)
            .draw()?;
    }
    Ok(())
}

/// `end_forces.png`: force magnitude at each cable end against time.
pub fn end_forces(path: &Path, series: &[Series]) -> Result<(), Error> {
    draw_png(path, |root| {
        // kN reads better than N for mooring loads.
        let kn: Vec<Series> = series
            .iter()
            .map(|s| Series {
                label: s.label.clone(),
                points: s.points.iter().map(|&(t, f)| (t, f / 1e3)).collect(),
            })
            .collect();
        lines(
            root,
            "End forces",
            "time (s)",
            "force magnitude (kN)",
            &kn,
            Axes::FromZero,
        )?;
        Ok(())
    })
}

/// `profiles.png`: side view (x-z) and plan view (x-y) of every cable at each time.
pub fn profiles(path: &Path, profiles: &[Profile]) -> Result<(), Error> {
    draw_png(path, |root| {
        let view = |a: usize, b: usize| -> Vec<Series> {
            profiles
                .iter()
                .map(|p| Series {
                    label: format!("{} t = {} s", p.cable, p.time),
                    points: p.nodes.iter().map(|x| (x[a], x[b])).collect(),
                })
                .collect()
        };
        let (xz, xy) = (view(0, 2), view(0, 1));
        // Side by side or one above the other: whichever draws the metres larger.
        let scale = |s: &[Series], dim: (u32, u32)| {
            let (x, _) = ranges(s, Axes::Equal, dim);
            plot_pixels(dim).0 / (x.end - x.start)
        };
        let (w, h) = SIZE;
        let beside = scale(&xz, (w / 2, h)).min(scale(&xy, (w / 2, h)));
        let stacked = scale(&xz, (w, h / 2)).min(scale(&xy, (w, h / 2)));
        let (side, plan) = if stacked > beside {
            root.split_vertically(h / 2)
        } else {
            root.split_horizontally(w / 2)
        };
        lines(&side, "Side view", "x (m)", "z (m)", &xz, Axes::Equal)?;
        lines(&plan, "Plan view", "x (m)", "y (m)", &xy, Axes::Equal)?;
        Ok(())
    })
}

/// `bodies.png`: each body's reference point and angles against time, and (runs with
/// free or pinned bodies) its velocity and angular velocity: two or four panels.
pub fn bodies(path: &Path, m: &BodyMotion) -> Result<(), Error> {
    draw_png(path, |root| {
        let moving = !m.velocity.is_empty();
        let panels = if moving {
            root.split_evenly((2, 2))
        } else {
            root.split_evenly((1, 2))
        };
        lines(
            &panels[0],
            "Reference point",
            "time (s)",
            "position (m)",
            &m.position,
            Axes::Data,
        )?;
        lines(
            &panels[1],
            "Attitude",
            "time (s)",
            "angle (deg)",
            &m.angles,
            Axes::Data,
        )?;
        if moving {
            lines(
                &panels[2],
                "Velocity",
                "time (s)",
                "velocity (m/s)",
                &m.velocity,
                Axes::Data,
            )?;
            lines(
                &panels[3],
                "Angular velocity",
                "time (s)",
                "rate (deg/s)",
                &m.rates,
                Axes::Data,
            )?;
        }
        Ok(())
    })
}

/// `gumbel_*.png`: the seed maxima against their reduced variate, and the fitted line.
pub fn gumbel(path: &Path, g: &GumbelData) -> Result<(), Error> {
    draw_png(path, |root| {
        let pts = g.points();
        let ((x0, x1), (y0, y1)) = bounds(pts.iter().copied());
        let mut chart = ChartBuilder::on(root)
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
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
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
        Ok(())
    })
}

/// `utilisation.png`: one bar per sea state and channel, with the limit 1 drawn.
pub fn utilisation(path: &Path, rows: &[(String, String, f64)]) -> Result<(), Error> {
    utilisation_bars(
        path,
        rows,
        "Utilisation (design value / capacity)",
        "sea state, channel",
        false,
    )
}

/// `conditions.png`: the governing utilisation of each mooring condition (one bar
/// each, labelled by the condition; the channel and sea state written on the bar),
/// with the limit 1 drawn.
pub fn governing(path: &Path, rows: &[(String, String, f64)]) -> Result<(), Error> {
    utilisation_bars(
        path,
        rows,
        "Governing utilisation per mooring condition",
        "condition (limit state)",
        true,
    )
}

/// Bars of utilisation `rows` (`(label, second label, value)`); `annotate` writes the
/// second label on its bar instead of beside the first under the axis.
fn utilisation_bars(
    path: &Path,
    rows: &[(String, String, f64)],
    caption: &str,
    x_desc: &str,
    annotate: bool,
) -> Result<(), Error> {
    draw_png(path, |root| {
        // Room above the tallest bar for the legend.
        let top = rows.iter().map(|r| r.2).fold(1.0f64, f64::max) * 1.3;
        let n = rows.len();
        let mut chart = ChartBuilder::on(root)
            .caption(caption, ("sans-serif", 26))
            .margin(15)
            .x_label_area_size(60)
            .y_label_area_size(90)
            .build_cartesian_2d(-0.5f64..(n as f64 - 0.5), 0.0..top)?;
        let labels: Vec<String> = rows
            .iter()
            .map(|r| {
                if annotate {
                    r.0.clone()
                } else {
                    format!("{} {}", r.0, r.1)
                }
            })
            .collect();
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
            .x_desc(x_desc)
            .y_desc("utilisation (-)")
            .y_label_formatter(&tick)
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 18))
            .draw()?;
        chart.draw_series(rows.iter().enumerate().map(|(k, r)| {
            let c = if r.2 > 1.0 {
                RED.to_rgba()
            } else {
                RGBColor(0, 110, 190).to_rgba()
            };
            Rectangle::new([(k as f64 - 0.35, 0.0), (k as f64 + 0.35, r.2)], c.filled())
        }))?;
        if annotate {
            chart.draw_series(rows.iter().enumerate().map(|(k, r)| {
                Text::new(
                    format!("{:.3}: {}", r.2, r.1),
                    (k as f64 - 0.35, r.2 + 0.02 * top),
                    ("sans-serif", 12),
                )
            }))?;
        }
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
            .position(SeriesLabelPosition::UpperLeft)
            .draw()?;
        Ok(())
    })
}

/// Bars of the fatigue damage per location on a logarithmic axis (labels `cable
/// location`; the axis is `log10` of the damage, labelled in powers of ten), with the
/// limit 1 drawn where it is in range.
pub fn fatigue(path: &Path, rows: &[(String, f64)], what: &str) -> Result<(), Error> {
    draw_png(path, |root| {
        let logs: Vec<f64> = rows
            .iter()
            .map(|r| r.1)
            .filter(|v| *v > 0.0)
            .map(f64::log10)
            .collect();
        let lo = logs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = logs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (lo, hi) = if logs.is_empty() {
            (-12.0, 0.0)
        } else {
            (lo.floor() - 1.0, hi.ceil().max(lo.floor() + 1.0) + 0.5)
        };
        let n = rows.len();
        let mut chart = ChartBuilder::on(root)
            .caption(format!("Fatigue: {what}"), ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(60)
            .y_label_area_size(100)
            .build_cartesian_2d(-0.5f64..(n as f64 - 0.5), lo..hi)?;
        let labels: Vec<String> = rows.iter().map(|r| r.0.clone()).collect();
        let decades = (hi - lo).ceil() as usize;
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
            .y_labels(decades + 1)
            .y_label_formatter(&|v| {
                if (v - v.round()).abs() < 1e-6 {
                    format!("1e{}", v.round() as i64)
                } else {
                    String::new()
                }
            })
            .x_desc("line, location")
            .y_desc("damage (-), logarithmic")
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 18))
            .draw()?;
        chart.draw_series(
            rows.iter()
                .enumerate()
                .filter(|(_, r)| r.1 > 0.0)
                .map(|(k, r)| {
                    let c = if r.1 > 1.0 {
                        RED.to_rgba()
                    } else {
                        RGBColor(0, 110, 190).to_rgba()
                    };
                    Rectangle::new(
                        [(k as f64 - 0.35, lo), (k as f64 + 0.35, r.1.log10())],
                        c.filled(),
                    )
                }),
        )?;
        if hi > 0.0 {
            chart.draw_series(LineSeries::new(
                [(-0.5, 0.0), (n as f64 - 0.5, 0.0)],
                BLACK.stroke_width(2),
            ))?;
        }
        Ok(())
    })
}

/// `nets.png` (against time) or `cage_sweep.png` (against the current speed): each net's
/// volume ratio and the drag on it, in two panels.
pub fn nets(path: &Path, volume: &[Series], drag: &[Series], sweep: bool) -> Result<(), Error> {
    draw_png(path, |root| {
        let panels = root.split_evenly((1, 2));
        let x = if sweep {
            "current speed (m/s)"
        } else {
            "time (s)"
        };
        lines(
            &panels[0],
            "Cage volume",
            x,
            "volume / volume as generated (-)",
            volume,
            Axes::FromZero,
        )?;
        lines(
            &panels[1],
            "Drag on the net",
            x,
            "drag (kN)",
            drag,
            Axes::FromZero,
        )?;
        Ok(())
    })
}
