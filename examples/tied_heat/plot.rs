//! The log-log plot of the errors against the mesh size h.

use std::path::Path;

use plotters::prelude::*;

use super::Res;

/// DejaVu Sans (Bitstream Vera licence, see `crates/mortar-scenes/assets/DejaVuSans-LICENSE.txt`).
const FONT: &[u8] = include_bytes!("../../crates/mortar-scenes/assets/DejaVuSans.ttf");
const COLOURS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
];

/// One curve: a name and its points (h, error).
pub(crate) struct Series {
    pub(crate) name: String,
    pub(crate) points: Vec<(f64, f64)>,
}

/// Draws the series on log-log axes with reference slopes h^1 and h^2.
pub(crate) fn draw(path: &Path, title: &str, series: &[Series]) -> Res<()> {
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| "cannot load the embedded font")?;
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|(h, e)| *h > 0.0 && *e > 0.0 && e.is_finite())
        .collect();
    if all.is_empty() {
        return Err("nothing to plot".into());
    }
    let (h0, h1) = all
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (e0, e1) = all
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let root = BitMapBackend::new(path, (1000, 750)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 24))
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(90)
        .build_cartesian_2d(
            (h0 / 1.3..h1 * 1.3).log_scale(),
            (e0 / 5.0..e1 * 5.0).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc("h = 1 / n (coarse body)")
        .y_desc("error")
        .x_label_formatter(&|v| format!("{v:.3}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    // Reference slopes through the largest h of the first two series.
    for (order, anchor) in [(1.0, 1usize), (2.0, 0usize)] {
        if let Some(s) = series.get(anchor) {
            if let Some(&(h, e)) = s.points.first() {
                let line = vec![(h, e * 2.0), (h0, e * 2.0 * (h0 / h).powf(order))];
                chart
                    .draw_series(LineSeries::new(line, BLACK.mix(0.4).stroke_width(1)))?
                    .label(format!("slope {order}"))
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.4)));
            }
        }
    }
    for (i, s) in series.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        chart
            .draw_series(LineSeries::new(s.points.clone(), colour.stroke_width(2)))?
            .label(s.name.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
        chart.draw_series(s.points.iter().map(|&p| Circle::new(p, 5, colour.filled())))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .label_font(("sans-serif", 16))
        .draw()?;
    root.present()?;
    Ok(())
}
