//! Line charts against the motion parameter τ as SVG text, in small multiples: one
//! panel per group of curves, each with its own value axis (so dimensionless
//! quantities and lengths never share one), the legend of a panel to its right,
//! outside the data, and vertical markers (e.g. singular poses) drawn in every panel
//! and labelled in the legend. Every curve has its own colour and dash pattern.

use super::svg::{SeriesStyle, escape, number, px, stroke_attributes, tick_label, ticks};
use std::fmt::Write;

/// One curve: connected pieces of `(τ, value)` points.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Colour and dash pattern.
    pub style: SeriesStyle,
    /// Pieces of the curve, with gaps between them (where the value is undefined).
    pub segments: Vec<Vec<(f64, f64)>>,
}

/// One panel: curves sharing a value axis.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Title above the panel.
    pub title: String,
    /// Title of the value axis, with its unit.
    pub y_title: String,
    /// The curves.
    pub series: Vec<Series>,
    /// Value range; `None`: the data's range (with 0) and 5 % padding.
    pub y_range: Option<(f64, f64)>,
}

/// A vertical marker at one τ, in every panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Marker {
    /// Parameter value.
    pub tau: f64,
    /// Legend text (markers with the same text share one legend entry).
    pub label: String,
    /// Dash pattern of the marker line.
    pub dash: &'static str,
}

/// A whole chart.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    /// Title at the top.
    pub title: String,
    /// Title of the τ axis (under every panel).
    pub x_title: String,
    /// τ range shown.
    pub tau_range: (f64, f64),
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
    /// Vertical markers.
    pub markers: Vec<Marker>,
}

const WIDTH: f64 = 1180.0;
const LEFT: f64 = 84.0;
const PLOT_WIDTH: f64 = 700.0;
const PANEL_HEIGHT: f64 = 250.0;
const PANEL_GAP: f64 = 92.0;
const TOP: f64 = 44.0;
const LEGEND_ROW: f64 = 19.0;

/// The pixel rectangle of a plot area.
pub(crate) struct PlotFrame {
    pub(crate) left: f64,
    pub(crate) top: f64,
    pub(crate) width: f64,
    pub(crate) height: f64,
}

/// How a τ chart's ticks look.
pub(crate) struct TickStyle {
    /// Font size of the tick labels (px).
    pub(crate) font_size: f64,
    /// About how many ticks on the τ axis and on the value axis.
    pub(crate) counts: (usize, usize),
    /// Baseline of the τ labels below the plot area (px).
    pub(crate) tau_label_drop: f64,
    /// Colour of the grid line at value 0.
    pub(crate) zero_line: &'static str,
}

const PANEL_TICKS: TickStyle = TickStyle {
    font_size: 13.0,
    counts: (10, 6),
    tau_label_drop: 17.0,
    zero_line: "#aaa",
};

/// Vertical grid lines and labels at "nice" τ ticks (1, 2 or 5 × 10^k) and horizontal
/// ones at value ticks in `frame`, which shows `τ ∈ [t0, t1]` across and
/// `value ∈ [lo, hi]` up: `x = left + (τ − t0)/(t1 − t0)·width`,
/// `y = top + height − (value − lo)/(hi − lo)·height`.
pub(crate) fn grid_and_ticks(
    out: &mut String,
    frame: &PlotFrame,
    ((t0, t1), (lo, hi)): ((f64, f64), (f64, f64)),
    style: &TickStyle,
) {
    let PlotFrame {
        left,
        top,
        width: w,
        height: h,
    } = *frame;
    let x = |t: f64| left + (t - t0) / (t1 - t0) * w;
    let y = |v: f64| top + h - (v - lo) / (hi - lo) * h;
    let size = px(style.font_size);
    let (xs, dx) = ticks(t0, t1, style.counts.0);
    for t in xs {
        let _ = writeln!(
            out,
            r##"<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#eee"/><text x="{0}" y="{3}" font-size="{size}" text-anchor="middle">{4}</text>"##,
            px(x(t)),
            px(top),
            px(top + h),
            px(top + h + style.tau_label_drop),
            tick_label(t, dx)
        );
    }
    let (ys, dy) = ticks(lo, hi, style.counts.1);
    for v in ys {
        let _ = writeln!(
            out,
            r##"<line x1="{1}" y1="{0}" x2="{2}" y2="{0}" stroke="{3}"/><text x="{4}" y="{0}" font-size="{size}" text-anchor="end" dominant-baseline="central">{5}</text>"##,
            px(y(v)),
            px(left),
            px(left + w),
            if v == 0.0 { style.zero_line } else { "#eee" },
            px(left - 6.0),
            tick_label(v, dy)
        );
    }
}

fn data_range(panel: &Panel) -> (f64, f64) {
    if let Some(range) = panel.y_range {
        return range;
    }
    let values = panel
        .series
        .iter()
        .flat_map(|s| s.segments.iter().flatten().map(|p| p.1))
        .filter(|v| v.is_finite());
    let (lo, hi) = values.fold((0.0f64, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let pad = 0.05 * (hi - lo).max(1e-12);
    (lo - pad, hi + pad)
}

/// Height of one panel block: the plot or its legend, whichever is taller.
fn block_height(panel: &Panel, legend_rows: usize) -> f64 {
    PANEL_HEIGHT.max((panel.series.len() + legend_rows) as f64 * LEGEND_ROW + 10.0)
}

/// The chart as a standalone SVG document.
pub fn chart_svg(chart: &Chart) -> String {
    let mut marker_labels: Vec<(&str, &'static str)> = Vec::new();
    for m in &chart.markers {
        if !marker_labels.iter().any(|(l, _)| *l == m.label) {
            marker_labels.push((&m.label, m.dash));
        }
    }
    let heights: Vec<f64> = chart
        .panels
        .iter()
        .map(|p| block_height(p, marker_labels.len()))
        .collect();
    let height = TOP + heights.iter().map(|h| h + PANEL_GAP).sum::<f64>();
    let mut out = String::new();
    let _ = writeln!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif"><rect width="100%" height="100%" fill="#fff"/><text class="title" x="{2}" y="26" font-size="18">{3}</text>"##,
        px(WIDTH),
        px(height),
        px(LEFT),
        escape(&chart.title)
    );
    let (t0, t1) = if chart.tau_range.1 > chart.tau_range.0 {
        chart.tau_range
    } else {
        (chart.tau_range.0 - 0.5, chart.tau_range.0 + 0.5)
    };
    let mut top = TOP + 24.0;
    for (k, (panel, block)) in chart.panels.iter().zip(&heights).enumerate() {
        panel_svg(&mut out, chart, panel, k, top, (t0, t1), &marker_labels);
        top += block + PANEL_GAP;
    }
    out.push_str("</svg>\n");
    out
}

fn panel_svg(
    out: &mut String,
    chart: &Chart,
    panel: &Panel,
    index: usize,
    top: f64,
    (t0, t1): (f64, f64),
    marker_labels: &[(&str, &'static str)],
) {
    let (lo, hi) = data_range(panel);
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        (lo - 1.0, lo + 1.0)
    };
    let h = PANEL_HEIGHT;
    let x = |t: f64| LEFT + (t - t0) / (t1 - t0) * PLOT_WIDTH;
    let y = |v: f64| top + h - (v - lo) / (hi - lo) * h;
    let _ = writeln!(
        out,
        r##"<g class="panel" data-panel="{index}"><text x="{}" y="{}" font-size="15" font-weight="bold">{}</text><rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#888"/>"##,
        px(LEFT),
        px(top - 8.0),
        escape(&panel.title),
        px(LEFT),
        px(top),
        px(PLOT_WIDTH),
        px(h)
    );
    let frame = PlotFrame {
        left: LEFT,
        top,
        width: PLOT_WIDTH,
        height: h,
    };
    grid_and_ticks(out, &frame, ((t0, t1), (lo, hi)), &PANEL_TICKS);
    let _ = writeln!(
        out,
        r#"<text x="{}" y="{}" font-size="14" text-anchor="middle">{}</text><text x="{4}" y="{5}" font-size="14" text-anchor="middle" transform="rotate(-90 {4} {5})">{3}</text>"#,
        px(LEFT + 0.5 * PLOT_WIDTH),
        px(top + h + 38.0),
        escape(&chart.x_title),
        escape(&panel.y_title),
        px(22.0),
        px(top + 0.5 * h)
    );
    let _ = writeln!(
        out,
        r#"<clipPath id="panel-{index}"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath><g clip-path="url(#panel-{index})">"#,
        px(LEFT),
        px(top),
        px(PLOT_WIDTH),
        px(h)
    );
    for m in &chart.markers {
        let _ = writeln!(
            out,
            r##"<line class="marker" x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#333" stroke-width="1.2" stroke-dasharray="{3}"/>"##,
            px(x(m.tau)),
            px(top),
            px(top + h),
            m.dash
        );
    }
    for series in &panel.series {
        for segment in series.segments.iter().filter(|s| s.len() > 1) {
            let points: Vec<String> = segment
                .iter()
                .filter(|p| p.1.is_finite())
                .map(|p| format!("{},{}", px(x(p.0)), px(y(p.1))))
                .collect();
            let _ = writeln!(
                out,
                r#"<polyline class="curve" data-label="{}" points="{}"{}/>"#,
                escape(&series.label),
                points.join(" "),
                stroke_attributes(series.style, 2.0)
            );
        }
        if let [single] = series
            .segments
            .iter()
            .filter(|s| !s.is_empty())
            .collect::<Vec<_>>()[..]
            && single.len() == 1
        {
            let _ = writeln!(
                out,
                r#"<circle cx="{}" cy="{}" r="3" fill="{}"/>"#,
                px(x(single[0].0)),
                px(y(single[0].1)),
                series.style.colour
            );
        }
    }
    out.push_str("</g>\n");
    // Legend, right of the plot area.
    let lx = LEFT + PLOT_WIDTH + 20.0;
    let mut ly = top + 8.0;
    out.push_str("<g class=\"legend\" font-size=\"13\">\n");
    for series in &panel.series {
        let _ = writeln!(
            out,
            r#"<line x1="{0}" y1="{1}" x2="{2}" y2="{1}"{3}/><text x="{4}" y="{1}" dominant-baseline="central">{5}</text>"#,
            px(lx),
            px(ly),
            px(lx + 36.0),
            stroke_attributes(series.style, 2.5),
            px(lx + 44.0),
            escape(&series.label)
        );
        ly += LEGEND_ROW;
    }
    for (label, dash) in marker_labels {
        let taus: Vec<String> = chart
            .markers
            .iter()
            .filter(|m| m.label == *label)
            .map(|m| number(m.tau, 4))
            .collect();
        let _ = writeln!(
            out,
            r##"<line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="#333" stroke-width="1.2" stroke-dasharray="{3}"/><text x="{4}" y="{1}" dominant-baseline="central">{5} (τ = {6})</text>"##,
            px(lx),
            px(ly),
            px(lx + 36.0),
            dash,
            px(lx + 44.0),
            escape(label),
            taus.join(", ")
        );
        ly += LEGEND_ROW;
    }
    out.push_str("</g></g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::svg::series_style;

    #[test]
    fn panels_have_their_own_axes_and_legends_outside_the_data() {
        let series = |label: &str, k: usize, scale: f64| Series {
            label: label.into(),
            style: series_style(k),
            segments: vec![vec![(0.0, -scale), (1.0, scale)]],
        };
        let chart = Chart {
            title: "t".into(),
            x_title: "motion parameter τ".into(),
            tau_range: (0.0, 1.0),
            panels: vec![
                Panel {
                    title: "lengths".into(),
                    y_title: "D (m)".into(),
                    series: vec![series("a", 0, 0.1), series("b", 1, 0.05)],
                    y_range: None,
                },
                Panel {
                    title: "ratios".into(),
                    y_title: "ratio (1)".into(),
                    series: vec![series("c", 0, 1.0)],
                    y_range: Some((0.0, 1.0)),
                },
            ],
            markers: vec![Marker {
                tau: 0.5,
                label: "singular pose".into(),
                dash: "4 3",
            }],
        };
        let svg = chart_svg(&chart);
        assert_eq!(svg.matches(r#"<g class="panel""#).count(), 2);
        assert_eq!(svg.matches(r#"<polyline class="curve""#).count(), 3);
        assert_eq!(svg.matches(r#"class="marker""#).count(), 2);
        assert!(svg.contains("singular pose (τ = 0.5000)"));
        assert!(svg.contains(">D (m)</text>") && svg.contains(">ratio (1)</text>"));
        assert!(!svg.contains(">-0.0<") && !svg.contains(">-0<"));
    }
}
