//! The plot of `singdist indices` / `compare` (`--plot`, `--plot-data`): every index
//! (and metric distance) along the motion divided by its maximum, in one panel per
//! group of indices. It needs every row of the table in memory.

use super::indices::{Table, cell};
use super::output::write_file;
use anyhow::{Result, bail};
use singdist::index::rpr::{INDEX_COLUMN_NAMES, index_columns};
use singdist::io::chart::{Chart, Panel};
use std::path::Path;

/// Curves of the plot, unscaled: name and values (absolute value for S; distances for
/// the metrics).
fn plot_curves(table: &Table) -> Vec<(String, Vec<Option<f64>>)> {
    // Every index column except the signed duplicates of the two distances.
    let names = INDEX_COLUMN_NAMES
        .iter()
        .copied()
        .filter(|name| !name.ends_with("_signed"));
    let mut curves: Vec<(String, Vec<Option<f64>>)> = names
        .map(|name| {
            let values = table
                .rows
                .iter()
                .map(|r| {
                    index_columns(&r.indices)
                        .iter()
                        .find(|(n, _)| *n == name)
                        .and_then(|(_, v)| *v)
                        .map(f64::abs)
                })
                .collect();
            let label = if name == "S" {
                "|S|".to_string()
            } else {
                name.to_string()
            };
            (label, values)
        })
        .collect();
    for name in &table.metric_names {
        let values = table
            .rows
            .iter()
            .map(|r| r.metrics.get(name).map(|m| m.distance))
            .collect();
        curves.push((format!("D {name}"), values));
    }
    curves
}

/// A plotted curve: label, the divisor (its maximum along the motion) and the values
/// divided by it (`None` where undefined).
pub struct ScaledCurve {
    label: String,
    max: f64,
    values: Vec<Option<f64>>,
}

/// Every plotted curve divided by its maximum along the motion, so each lies in
/// [0, 1] (a curve that is identically 0 is left as is).
pub fn scaled_curves(table: &Table) -> Vec<ScaledCurve> {
    plot_curves(table)
        .into_iter()
        .map(|(label, values)| {
            let values: Vec<Option<f64>> = values
                .into_iter()
                .map(|v| v.filter(|v| v.is_finite()))
                .collect();
            let max = values.iter().flatten().fold(0.0_f64, |m, v| m.max(*v));
            let scale = if max > 0.0 { max } else { 1.0 };
            ScaledCurve {
                label,
                max,
                values: values.into_iter().map(|v| v.map(|v| v / scale)).collect(),
            }
        })
        .collect()
}

pub fn write_plot_data(path: &Path, table: &Table, curves: &[ScaledCurve]) -> Result<()> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["tau".to_string()];
    header.extend(curves.iter().map(|c| format!("{} / {:e}", c.label, c.max)));
    writer.write_record(&header)?;
    for (j, row) in table.rows.iter().enumerate() {
        let mut record = vec![format!("{}", row.tau)];
        record.extend(curves.iter().map(|c| cell(c.values[j])));
        writer.write_record(&record)?;
    }
    let text = String::from_utf8(writer.into_inner()?)?;
    write_file("--plot-data", path, text)
}

/// The panel of an index (small multiples, each curve divided by its maximum):
/// transmission and pressure-angle indices, manipulability / conditioning, the
/// index-based singularity distances, and the metric distances D.
fn panel_of(label: &str) -> usize {
    match label {
        "TI" | "MTI" | "DS" | "MDS" | "IR" => 0,
        "M" | "|S|" | "CN" | "MCN" => 1,
        "orientation_distance" | "position_distance" | "cylinder_radius" => 2,
        _ => 3,
    }
}

const PANEL_TITLES: [&str; 4] = [
    "transmission: TI = min |cos α_i| (pressure angles α_i), DS, their minima MTI, MDS; IR = incircle radius",
    "manipulability M = |det J|, singularity polynomial |S|, control number CN, MCN = 1/√λ_max",
    "index-based singularity distances: orientation (rad), position, singularity-free cylinder radius",
    "metric distances D(K, K′) to the closest singular configuration (platform/base metric)",
];

pub fn plot(path: &Path, table: &Table, curves: &[ScaledCurve], singular: &[f64]) -> Result<()> {
    let rows = &table.rows;
    if rows.len() < 2 {
        bail!("--plot: need at least 2 poses");
    }
    let mut groups: Vec<Vec<super::plot::Curve>> =
        (0..PANEL_TITLES.len()).map(|_| Vec::new()).collect();
    for curve in curves {
        // Split at undefined values so gaps stay gaps.
        let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for (row, value) in rows.iter().zip(&curve.values) {
            match value {
                Some(v) => {
                    if let Some(segment) = segments.last_mut() {
                        segment.push((row.tau, *v));
                    }
                }
                None => segments.push(Vec::new()),
            }
        }
        let label = curve.label.strip_prefix("D ").unwrap_or(&curve.label);
        groups[panel_of(&curve.label)].push(super::plot::Curve {
            label: format!("{label} (max {})", singdist::io::svg::short(curve.max)),
            segments,
        });
    }
    let panels = groups
        .into_iter()
        .zip(PANEL_TITLES)
        .filter(|(group, _)| !group.is_empty())
        .map(|(group, title)| Panel {
            title: title.to_string(),
            y_title: "value / its maximum (1)".into(),
            series: super::plot::series_of(group),
            y_range: Some((0.0, 1.05)),
        })
        .collect();
    let title = if table.metric_names.is_empty() {
        "3-RPR kinematic indices along the motion (each curve divided by its maximum)"
    } else {
        "3-RPR indices and metric distances D along the motion (each curve divided by its maximum)"
    };
    let chart = Chart {
        title: title.into(),
        x_title: super::plot::TAU_AXIS.into(),
        tau_range: (rows[0].tau, rows[rows.len() - 1].tau),
        panels,
        markers: super::plot::singular_markers(singular),
    };
    super::plot::write_chart(path, &chart)
}
