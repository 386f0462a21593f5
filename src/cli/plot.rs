//! SVG line plots against the motion parameter τ, shared by `curve`, `indices` and
//! `rrr curve`: thin wrappers around [`singdist::io::chart`] (panels with their own
//! axes, a colour and dash pattern per curve, legends outside the data, singular poses
//! marked).

use anyhow::Result;
use singdist::io::chart::{Chart, Marker, Panel, Series, chart_svg};
use singdist::io::svg::{metric_style, series_style};
use singdist::metric::Metric;
use std::path::Path;

/// One labelled curve: segments of `(τ, value)` points, with gaps between segments.
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// Connected pieces of the curve.
    pub segments: Vec<Vec<(f64, f64)>>,
}

/// Caption, axis text and ranges of a one-panel plot.
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

/// Title of the τ axis.
pub const TAU_AXIS: &str = "motion parameter τ (as in the motion file)";

/// The series of `curves`: a 3-RPR metric keeps its own style (the same in every
/// picture), any other curve takes the next free one.
pub fn series_of(curves: Vec<Curve>) -> Vec<Series> {
    let metric_names: Vec<String> = Metric::all().iter().map(Metric::name).collect();
    let mut next = 0;
    curves
        .into_iter()
        .map(|curve| {
            let name = curve.label.split(' ').next().unwrap_or_default();
            let style = if metric_names.iter().any(|m| m == name) {
                metric_style(name)
            } else {
                next += 1;
                series_style(next - 1)
            };
            Series {
                label: curve.label,
                style,
                segments: curve.segments,
            }
        })
        .collect()
}

/// Markers at the singular poses (S = 0).
pub fn singular_markers(singular: &[f64]) -> Vec<Marker> {
    singular
        .iter()
        .map(|&tau| Marker {
            tau,
            label: "singular pose, S = 0".into(),
            dash: "5 3",
        })
        .collect()
}

/// Writes the chart as an SVG file at `path` (drawn in memory first, so a failed
/// write leaves no half-written file).
pub fn write_chart(path: &Path, chart: &Chart) -> Result<()> {
    super::output::write_file("--plot", path, chart_svg(chart))
}

/// Writes the curves as a one-panel SVG plot at `path`, marking the singular τ values.
pub fn plot_against_tau(
    path: &Path,
    layout: &Layout,
    curves: &[Curve],
    singular: &[f64],
) -> Result<()> {
    let curves = curves
        .iter()
        .map(|c| Curve {
            label: c.label.clone(),
            segments: c.segments.clone(),
        })
        .collect();
    // A length axis says its unit; "signed" is explained by the caption and legend.
    let y_title = if layout.y_description.starts_with("signed distance D") {
        "signed distance D (design length unit)".to_string()
    } else {
        layout.y_description.to_string()
    };
    let chart = Chart {
        title: layout.caption.to_string(),
        x_title: TAU_AXIS.into(),
        tau_range: layout.tau_range,
        panels: vec![Panel {
            title: String::new(),
            y_title,
            series: series_of(curves),
            y_range: Some(layout.y_range),
        }],
        markers: singular_markers(singular),
    };
    write_chart(path, &chart)
}
