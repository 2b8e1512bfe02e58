//! Plots and images for the benchmark suites: line charts, grouped bar charts and raw RGB
//! images, each written under a temporary name and renamed, so no half-written PNG remains.
//! Charts are drawn into memory and encoded by the `image` crate the workspace already uses
//! (plotters' own encoder would build a second version of it).

use anyhow::Context;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The font every plot uses: Debian's DejaVu Sans (package fonts-dejavu-core).
pub const FONT_PATH: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// Loads the plots' font once. Suites that draw charts call it before they measure anything,
/// so a machine without the font fails at once instead of after minutes of measurements
/// whose results it could then not write.
///
/// # Errors
/// The font file is missing (the message names the package) or unusable.
pub fn ensure_font() -> anyhow::Result<()> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            let bytes = std::fs::read(FONT_PATH).map_err(|e| {
                format!("{FONT_PATH}: {e} (install the Debian package fonts-dejavu-core)")
            })?;
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
                .map_err(|_| format!("{FONT_PATH}: not a usable TrueType font"))
        })
        .clone()
        .map_err(anyhow::Error::msg)
}

fn partial(path: &Path) -> PathBuf {
    path.with_extension("partial.png")
}

fn finish(path: &Path) -> anyhow::Result<()> {
    std::fs::rename(partial(path), path).with_context(|| format!("writing {}", path.display()))
}

/// One line of a chart.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(127, 127, 127),
    RGBColor(23, 190, 207),
];

/// A line chart with a logarithmic y axis (rates span orders of magnitude).
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> anyhow::Result<()> {
    xy_chart(path, title, x_label, y_label, series, true)
}

/// A line chart (a series of one point is a marker), the y axis logarithmic when `log_y`.
pub fn xy_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    log_y: bool,
) -> anyhow::Result<()> {
    ensure_font()?;
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| p.1 > 0.0 && p.1.is_finite())
        .collect();
    anyhow::ensure!(!all.is_empty(), "{}: nothing to plot", path.display());
    let (x0, x1) = all
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (y0, y1) = all
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let pad = ((x1 - x0) * 0.03).max(0.01);
    let (image_width, image_height) = (1100, 700);
    let mut pixels = vec![0u8; image_width as usize * image_height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (image_width, image_height))
            .into_drawing_area();
        root.fill(&WHITE)?;
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(title, ("sans-serif", 24))
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(80);
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(x_label)
                    .y_desc(y_label)
                    .label_style(("sans-serif", 16))
                    .draw()?;
                for (i, s) in series.iter().enumerate() {
                    let color = COLORS[i % COLORS.len()];
                    let pts: Vec<(f64, f64)> = s
                        .points
                        .iter()
                        .copied()
                        .filter(|p| p.1 > 0.0 && p.1.is_finite())
                        .collect();
                    let size = if pts.len() == 1 { 7 } else { 4 };
                    chart
                        .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
                        .label(s.name.clone())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                        });
                    chart.draw_series(
                        pts.into_iter()
                            .map(|p| Circle::new(p, size, color.filled())),
                    )?;
                }
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .label_font(("sans-serif", 15))
                    .position(if log_y {
                        SeriesLabelPosition::LowerLeft
                    } else {
                        SeriesLabelPosition::LowerRight
                    })
                    .draw()?;
            }};
        }
        if log_y {
            draw!(builder.build_cartesian_2d(
                (x0 - pad)..(x1 + pad),
                ((y0 * 0.8)..(y1 * 1.25)).log_scale()
            )?);
        } else {
            let ypad = ((y1 - y0) * 0.05).max(0.5);
            draw!(builder.build_cartesian_2d((x0 - pad)..(x1 + pad), (y0 - ypad)..(y1 + ypad))?);
        }
        root.present()?;
    }
    rgb_image(path, image_width, image_height, pixels)
}

/// Grouped bars: one group per category, one bar per series; log y axis when `log_y`.
pub fn bar_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    categories: &[String],
    series: &[(String, Vec<f64>)],
    log_y: bool,
) -> anyhow::Result<()> {
    ensure_font()?;
    let max = series
        .iter()
        .flat_map(|s| s.1.iter().copied())
        .fold(1.0f64, f64::max);
    let n = categories.len() as f64;
    let width = 0.8 / series.len().max(1) as f64;
    let (image_width, image_height) = (1100, 650);
    let mut pixels = vec![0u8; image_width as usize * image_height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (image_width, image_height))
            .into_drawing_area();
        root.fill(&WHITE)?;
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(title, ("sans-serif", 24))
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(80);
        let cats = categories.to_vec();
        let fmt = move |x: &f64| {
            let i = x.round();
            if (x - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < cats.len() {
                cats[i as usize].clone()
            } else {
                String::new()
            }
        };
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(x_label)
                    .y_desc(y_label)
                    .x_labels(categories.len() + 1)
                    .x_label_formatter(&fmt)
                    .disable_x_mesh()
                    .label_style(("sans-serif", 15))
                    .draw()?;
                for (si, (name, values)) in series.iter().enumerate() {
                    let color = COLORS[si % COLORS.len()];
                    let x_off = -0.4 + width * si as f64;
                    chart
                        .draw_series(values.iter().enumerate().filter(|(_, v)| **v > 0.0).map(
                            move |(ci, v)| {
                                let x = ci as f64 + x_off;
                                Rectangle::new(
                                    [(x, if log_y { 0.5 } else { 0.0 }), (x + width * 0.95, *v)],
                                    color.filled(),
                                )
                            },
                        ))?
                        .label(name.clone())
                        .legend(move |(x, y)| {
                            Rectangle::new([(x, y - 6), (x + 14, y + 6)], color.filled())
                        });
                }
                chart
                    .configure_series_labels()
                    .position(SeriesLabelPosition::UpperRight)
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .label_font(("sans-serif", 15))
                    .draw()?;
            }};
        }
        if log_y {
            draw!(builder.build_cartesian_2d(-0.6..(n - 0.4), (0.5..max * 2.0).log_scale())?);
        } else {
            // Headroom above the tallest bar keeps the legend clear of the bars.
            draw!(builder.build_cartesian_2d(-0.6..(n - 0.4), 0.0..max * 1.35)?);
        }
        root.present()?;
    }
    rgb_image(path, image_width, image_height, pixels)
}

/// Writes an RGB8 image.
pub fn rgb_image(path: &Path, width: u32, height: u32, pixels: Vec<u8>) -> anyhow::Result<()> {
    let img = image::RgbImage::from_raw(width, height, pixels)
        .context("image size does not match its pixels")?;
    img.save_with_format(partial(path), image::ImageFormat::Png)
        .with_context(|| format!("writing {}", path.display()))?;
    finish(path)
}

/// A colour for `t` in [0, 1] (dark blue → yellow), for maps of small integers such as ages.
pub fn heat(t: f64) -> [u8; 3] {
    let c = ViridisRGB::get_color(t.clamp(0.0, 1.0));
    [c.0, c.1, c.2]
}
