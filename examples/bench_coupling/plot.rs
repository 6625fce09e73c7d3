//! The log-log plot of error against time of the tradeoff table.

use std::path::Path;

use plotters::prelude::*;

use crate::tradeoff::{Case, Row};
use crate::Res;

/// DejaVu Sans (Bitstream Vera licence, see `crates/mortar-scenes/assets/DejaVuSans-LICENSE.txt`).
const FONT: &[u8] = include_bytes!("../../crates/mortar-scenes/assets/DejaVuSans.ttf");
/// Errors below this are drawn at this value.
const FLOOR: f64 = 1e-16;
const COLOURS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
];

/// Draws, for each case, each metric but `patch` (round-off for every option) in its own panel.
pub(crate) fn draw(path: &Path, cases: &[&Case]) -> Res<()> {
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| "cannot load the embedded font")?;
    let panels: Vec<(&Case, usize)> = cases
        .iter()
        .flat_map(|c| {
            (0..c.metrics.len())
                .filter(|&k| c.metrics[k] != "patch")
                .map(move |k| (*c, k))
        })
        .collect();
    let cols = 2;
    let rows = panels.len().div_ceil(cols);
    let root = BitMapBackend::new(path, (1400, 100 + 520 * rows as u32)).into_drawing_area();
    root.fill(&WHITE)?;
    let (top, body) = root.split_vertically(100);
    top.draw_text(
        "Mortar integration: error against time (log-log), quadrature degrees 1 to 8 labelled; \
         errors below 1e-16 drawn at 1e-16",
        &("sans-serif", 22).into_font().color(&BLACK),
        (20, 15),
    )?;
    let font = ("sans-serif", 17).into_font();
    for (s, name) in cases
        .first()
        .map(|c| series_names(c))
        .unwrap_or_default()
        .iter()
        .enumerate()
    {
        let at = EmptyElement::at((40 + 330 * s as i32, 68));
        let text = Text::new(name.clone(), (14, -9), font.clone());
        let (colour, style) = (
            COLOURS[s % COLOURS.len()],
            COLOURS[s % COLOURS.len()].filled(),
        );
        match s {
            0 => top.draw(&(at + Circle::new((0, 0), 5, style) + text))?,
            1 => top.draw(&(at + TriangleMarker::new((0, 0), 7, style) + text))?,
            2 => top.draw(&(at + Rectangle::new([(-4, -4), (4, 4)], style) + text))?,
            _ => top.draw(&(at + Cross::new((0, 0), 5, colour.stroke_width(2)) + text))?,
        }
    }
    for (area, (case, k)) in body.split_evenly((rows, cols)).iter().zip(&panels) {
        panel(area, case, *k)?;
    }
    root.present()?;
    Ok(())
}

fn series_names(case: &Case) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for r in &case.rows {
        if !names.contains(&r.series()) {
            names.push(r.series());
        }
    }
    names
}

fn panel(
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    case: &Case,
    k: usize,
) -> Res<()> {
    let pts = |r: &Row| (r.seconds, r.errors[k].max(FLOOR));
    let ok: Vec<(f64, f64)> = case
        .rows
        .iter()
        .map(pts)
        .filter(|(t, e)| t.is_finite() && e.is_finite())
        .collect();
    let (t0, t1) = ok
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (e0, e1) = ok
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let name = case.title.split(':').next().unwrap_or("");
    let mut chart = ChartBuilder::on(area)
        .caption(format!("{name}: {}", case.metrics[k]), ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(
            (t0 / 1.5..t1 * 1.5).log_scale(),
            (e0 / 10.0..e1 * 10.0).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc("time per assembly, 1 thread [s]")
        .y_desc(format!("{} error", case.metrics[k]))
        .x_label_formatter(&|v| one_two_five(*v))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .light_line_style(WHITE)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()?;
    for (s, name) in series_names(case).iter().enumerate() {
        let colour = COLOURS[s % COLOURS.len()];
        let line: Vec<(f64, f64)> = case
            .rows
            .iter()
            .filter(|r| &r.series() == name && r.degree.is_some())
            .map(pts)
            .filter(|(t, e)| t.is_finite() && e.is_finite())
            .collect();
        let degrees: Vec<u32> = case
            .rows
            .iter()
            .filter(|r| &r.series() == name && pts(r).0.is_finite() && pts(r).1.is_finite())
            .filter_map(|r| r.degree)
            .collect();
        // The default (automatic degree) as a ring labelled "default".
        let defaults: Vec<(f64, f64)> = case
            .rows
            .iter()
            .filter(|r| &r.series() == name && r.degree.is_none())
            .map(pts)
            .filter(|(t, e)| t.is_finite() && e.is_finite())
            .collect();
        chart.draw_series(defaults.iter().map(|&p| {
            EmptyElement::at(p)
                + Circle::new((0, 0), 9, colour.stroke_width(2))
                + Text::new("default", (10, 4), ("sans-serif", 12))
        }))?;
        chart.draw_series(LineSeries::new(
            line.clone(),
            colour.mix(0.5).stroke_width(1),
        ))?;
        let style = colour.filled();
        match s {
            0 => chart.draw_series(line.iter().map(|&p| Circle::new(p, 5, style)))?,
            1 => chart.draw_series(line.iter().map(|&p| TriangleMarker::new(p, 7, style)))?,
            2 => {
                chart
                    .draw_series(line.iter().map(|&p| {
                        EmptyElement::at(p) + Rectangle::new([(-4, -4), (4, 4)], style)
                    }))?
            }
            _ => chart.draw_series(
                line.iter()
                    .map(|&p| Cross::new(p, 5, colour.stroke_width(2))),
            )?,
        };
        chart.draw_series(line.iter().zip(&degrees).map(|(&p, d)| {
            EmptyElement::at(p) + Text::new(d.to_string(), (6, -16), ("sans-serif", 12))
        }))?;
    }
    Ok(())
}

/// `v` in the form `2e-3` when its mantissa is 1, 2 or 5, else nothing (uncluttered log axes).
fn one_two_five(v: f64) -> String {
    let mantissa = v / 10f64.powf(v.log10().floor());
    if [1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-6) {
        format!("{v:.0e}")
    } else {
        String::new()
    }
}
