//! SVG line plots against the motion parameter τ, shared by `curve` and `indices`:
//! labelled curves (split into segments where a value is undefined), a vertical marker
//! at each singular pose (S = 0), and a legend.

use anyhow::{Result, anyhow};
use plotters::prelude::*;
use std::path::Path;

/// One labelled curve: segments of `(τ, value)` points, with gaps between segments.
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// Connected pieces of the curve.
    pub segments: Vec<Vec<(f64, f64)>>,
}

/// Caption, axis text and ranges of a plot.
pub struct Layout<'a> {
    /// Title above the plot.
    pub caption: &'a str,
    /// Text of the value axis.
    pub y_description: &'a str,
    /// First and last τ.
    pub tau_range: (f64, f64),
    /// Lower and upper end of the value axis.
    pub y_range: (f64, f64),
}

/// Writes the curves as an SVG file at `path`, marking the singular τ values. The plot
/// is drawn in memory first, so a failed write leaves no half-written file.
pub fn plot_against_tau(
    path: &Path,
    layout: &Layout,
    curves: &[Curve],
    singular: &[f64],
) -> Result<()> {
    let mut svg = String::new();
    draw_against_tau(&mut svg, layout, curves, singular)
        .map_err(|e| anyhow!("--plot: {}: plotting failed: {e}", path.display()))?;
    super::output::write_file("--plot", path, svg)
}

/// Draws the plot of [`plot_against_tau`] into `svg`.
fn draw_against_tau(
    svg: &mut String,
    layout: &Layout,
    curves: &[Curve],
    singular: &[f64],
) -> Result<()> {
    let root = SVGBackend::with_string(svg, (1100, 700)).into_drawing_area();
    let draw = |e: DrawingAreaErrorKind<_>| anyhow!("{e}");
    root.fill(&WHITE).map_err(draw)?;
    let (t0, t1) = layout.tau_range;
    let (lo, hi) = layout.y_range;
    let mut chart = ChartBuilder::on(&root)
        .caption(layout.caption, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(t0.min(t1)..t0.max(t1), lo..hi)
        .map_err(draw)?;
    chart
        .configure_mesh()
        .x_desc("motion parameter tau")
        .y_desc(layout.y_description)
        .draw()
        .map_err(draw)?;
    let colors = [
        BLUE,
        RED,
        GREEN,
        MAGENTA,
        CYAN,
        BLACK,
        full_palette::ORANGE,
        full_palette::BROWN,
        full_palette::PURPLE,
        full_palette::TEAL,
        full_palette::PINK,
        full_palette::GREY,
    ];
    for (curve, &color) in curves.iter().zip(colors.iter().cycle()) {
        let mut first = true;
        for segment in curve.segments.iter().filter(|s| !s.is_empty()) {
            let series = chart
                .draw_series(LineSeries::new(segment.clone(), color.stroke_width(2)))
                .map_err(draw)?;
            if first {
                series.label(curve.label.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
                first = false;
            }
        }
    }
    for &tau in singular {
        chart
            .draw_series(LineSeries::new(
                vec![(tau, lo), (tau, hi)],
                BLACK.stroke_width(1),
            ))
            .map_err(draw)?
            .label(format!("singular pose (S = 0) at tau = {tau:.4}"))
            .legend(|(x, y)| PathElement::new(vec![(x, y - 6), (x, y + 6)], BLACK.stroke_width(1)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(draw)?;
    root.present().map_err(draw)?;
    Ok(())
}
