//! PNG line charts, drawn in memory (so that a scene writes its outputs all or none): the one
//! module that knows `plotters` and `png`.
//!
//! ```
//! use mortar_scenes::plot::{line_chart_png, Chart, Curve};
//!
//! let png = line_chart_png(&Chart {
//!     title: "a line",
//!     x_label: "t (s)",
//!     y_label: "T (K)",
//!     curves: vec![Curve { name: "T", points: vec![(0.0, 300.0), (1.0, 310.0)] }],
//! })?;
//! assert_eq!(&png[1..4], b"PNG");
//! # Ok::<(), mortar::io::IoError>(())
//! ```

use std::sync::OnceLock;

use plotters::prelude::*;

use mortar::io::IoError;

/// DejaVu Sans (Bitstream Vera licence, see `crates/mortar-scenes/assets/DejaVuSans-LICENSE.txt`).
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
/// Curve colours, in order.
const COLOURS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
];
/// The image size (pixels).
const SIZE: (u32, u32) = (1000, 650);

/// One curve of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve<'a> {
    /// The legend.
    pub name: &'a str,
    /// The points `(x, y)`, in order; non-finite points are left out.
    pub points: Vec<(f64, f64)>,
}

/// A chart of curves on linear axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart<'a> {
    /// The title.
    pub title: &'a str,
    /// The x axis's label.
    pub x_label: &'a str,
    /// The y axis's label.
    pub y_label: &'a str,
    /// The curves.
    pub curves: Vec<Curve<'a>>,
}

fn plot_error(e: impl std::fmt::Display) -> IoError {
    IoError::Write {
        path: "<chart>".into(),
        source: std::io::Error::other(e.to_string()),
    }
}

/// The PNG file of `chart`.
///
/// # Errors
/// [`IoError::Write`] (path `<chart>`) when there is no finite point to draw or drawing or
/// encoding fails.
pub fn line_chart_png(chart: &Chart<'_>) -> Result<Vec<u8>, IoError> {
    static FONT_LOADED: OnceLock<bool> = OnceLock::new();
    if !FONT_LOADED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok()
    }) {
        return Err(plot_error("cannot load the embedded font"));
    }
    let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let all: Vec<(f64, f64)> = chart
        .curves
        .iter()
        .flat_map(|c| c.points.iter().filter(finite).copied())
        .collect();
    if all.is_empty() {
        return Err(plot_error(format!("{}: nothing to plot", chart.title)));
    }
    let range = |f: fn(&(f64, f64)) -> f64| {
        let (lo, hi) = all
            .iter()
            .map(f)
            .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
        let pad = if hi > lo {
            0.05 * (hi - lo)
        } else {
            0.5 * lo.abs().max(1.0)
        };
        (lo - pad, hi + pad)
    };
    let (x0, x1) = range(|p| p.0);
    let (y0, y1) = range(|p| p.1);
    let mut buffer = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let mut c = ChartBuilder::on(&root)
            .caption(chart.title, ("sans-serif", 24))
            .margin(20)
            .x_label_area_size(55)
            .y_label_area_size(90)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(plot_error)?;
        c.configure_mesh()
            .x_desc(chart.x_label)
            .y_desc(chart.y_label)
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 18))
            .draw()
            .map_err(plot_error)?;
        for (i, curve) in chart.curves.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let points: Vec<(f64, f64)> = curve.points.iter().filter(finite).copied().collect();
            c.draw_series(LineSeries::new(points, colour.stroke_width(2)))
                .map_err(plot_error)?
                .label(curve.name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        c.configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()
            .map_err(plot_error)?;
        root.present().map_err(plot_error)?;
    }
    let mut png = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut png, SIZE.0, SIZE.1);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(plot_error)?;
        writer.write_image_data(&buffer).map_err(plot_error)?;
    }
    Ok(png)
}
