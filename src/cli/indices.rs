//! `singdist indices`: kinematic performance indices of a 3-RPR (SPEC Part B) along a
//! motion (CSV / JSON table, SVG plot) or at one pose (`--pose x,y,phi --json`).
//!
//! With `--with-metrics [all|NAME…]` (or the `compare` command) the table also holds the
//! singularity distances of the selected extrinsic metrics (SPEC A.9, computed by
//! [`compute_curve`] at the very same τ samples, [`sample_motion`]), so metric and index
//! can be compared pose by pose (paper Figs. 14–16). Lost homotopy paths of the metric
//! computation are reported on stderr, in the output, and by exit code 3 (as `curve`).

use super::curve::{check_samples, parse_metrics, pose_count};
use super::distance::parse_pose;
use super::failures::warn_failures;
use super::outcome::Outcome;
use super::output::{check_output_file, extension, write_file};
use super::resources::{MAX_POSES, check_metric_pose_count, check_pose_count, with_threads};
use anyhow::{Context, Result, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use singdist::index::rpr::{
    CnVariant, DEFAULT_CYLINDER_HALF_WIDTH, DsAggregate, INDEX_COLUMN_NAMES, IndexOptions,
    RprIndices, compute_indices, index_columns,
};
use singdist::io::chart::{Chart, Panel};
use singdist::io::{load_design, load_motion};
use singdist::mechanism::rpr::{
    Design, Motion, PoseList, SampledPose, example_design, example_motion,
};
use singdist::metric::Metric;
use singdist::pipeline::curve::{
    CurveOptions, CurveResult, PathFailure, PoseResult, compute_curve, default_start_solutions,
    sample_motion, singular_parameters,
};
use singdist::pipeline::postprocess::MetricDistance;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Arguments of `singdist indices`.
#[derive(Args, Debug)]
pub struct IndicesArgs {
    /// Design file (JSON `{"base": [[x,y],…], "platform": [[x,y],…]}`); default: the
    /// built-in example (systems/rpr_example_design.json).
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
    /// Motion file (poses or analytic motion); default: the built-in example.
    #[arg(long, value_name = "FILE")]
    motion: Option<PathBuf>,
    /// Number of poses evenly spaced in τ (analytic motions; pose lists are used as given);
    /// at most 1,000,000, and poses × metrics at most 100,000 with metric distances.
    #[arg(long, value_name = "N", default_value_t = 90)]
    poses: usize,
    /// Table of every index along the motion: `.csv` or `.json` (default: CSV on stdout).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// SVG plot of the indices along the motion, each scaled to [0, 1] by its maximum.
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// One pose `x,y,phi` instead of a motion.
    #[arg(long, value_name = "X,Y,PHI", allow_hyphen_values = true)]
    pose: Option<String>,
    /// With `--pose`: print one JSON object (keys M, S, IR, TI, DS, MTI, MDS, CN, MCN,
    /// orientation_distance, position_distance, …).
    #[arg(long)]
    json: bool,
    /// DS aggregate of the pressure-angle cosines (DS is reconstructed): product,
    /// geometric-mean or arithmetic-mean.
    #[arg(long, value_name = "AGGREGATE", default_value = "product")]
    ds: String,
    /// Control number variant: lambda-ratio (λ_min/λ_max) or sqrt-lambda-ratio.
    #[arg(long, value_name = "VARIANT", default_value = "lambda-ratio")]
    cn: String,
    /// Half width w (radians) of the orientation range [φ − w, φ + w] of the
    /// singularity-free cylinder.
    #[arg(long, value_name = "RAD", default_value_t = DEFAULT_CYLINDER_HALF_WIDTH)]
    cylinder_half_width: f64,
    /// Add the singularity distances of these metrics at the same poses:
    /// `all` (the default when the option has no value) or names like `plate/plate
    /// bars/rigid`. CSV: columns `NAME` (distance) and `NAME_signed`; JSON: a `metrics`
    /// object per pose; the plot shows them next to the indices.
    #[arg(long, value_name = "NAME", num_args = 0.., default_missing_value = "all")]
    with_metrics: Option<Vec<String>>,
    /// Seed of every random choice of the metric computation (as `curve --seed`).
    #[arg(long, value_name = "S", default_value_t = 1)]
    seed: u64,
    /// Worker threads of the metric computation (default: all cores; more than the
    /// cores is clamped to them).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// CSV of the plotted data: τ and every curve divided by its maximum along the
    /// motion (the divisor is in the column header).
    #[arg(long, value_name = "FILE.csv")]
    plot_data: Option<PathBuf>,
    /// No progress bar for the metric computation.
    #[arg(long)]
    quiet: bool,
}

/// Runs `singdist compare`: `indices` with the metric distances (all nine unless
/// `--with-metrics` names some).
pub fn run_compare(mut args: IndicesArgs) -> Result<Outcome> {
    if args.with_metrics.is_none() {
        args.with_metrics = Some(vec!["all".to_string()]);
    }
    run(args)
}

/// Runs `singdist indices`.
pub fn run(args: IndicesArgs) -> Result<Outcome> {
    let ds: DsAggregate = args.ds.parse().context("--ds")?;
    let cn: CnVariant = args.cn.parse().context("--cn")?;
    if !args.cylinder_half_width.is_finite() || args.cylinder_half_width < 0.0 {
        bail!(
            "--cylinder-half-width: expected a finite number >= 0, got {}",
            args.cylinder_half_width
        );
    }
    let options = IndexOptions {
        ds,
        cn,
        cylinder_half_width: args.cylinder_half_width,
    };
    let metrics = match &args.with_metrics {
        Some(values) => parse_metrics(values).context("--with-metrics")?,
        None => Vec::new(),
    };
    let design = match &args.design {
        Some(path) => load_design(path)?,
        None => example_design(),
    };
    if let Some(text) = &args.pose {
        if args.plot.is_some() || args.plot_data.is_some() || args.out.is_some() {
            bail!("--pose: --out, --plot and --plot-data apply to a motion, not to one pose");
        }
        let pose = parse_pose(text)?;
        let indices = compute_indices(&design, pose, &options);
        let motion = Motion::Poses(PoseList { poses: vec![pose] });
        let curve = metric_curve(&design, &motion, 1, &metrics, &args)?;
        let at = curve.as_ref().and_then(|c| c.poses.first());
        if args.json {
            println!(
                "{}",
                single_pose_json(&indices, &options, curve.as_ref(), at)?
            );
        } else {
            print_single_pose(&indices, &options, &metrics, at);
        }
        return finish(curve.as_ref());
    }
    if args.json {
        bail!("--json applies to a single pose (--pose x,y,phi); use --out FILE.json for a motion");
    }
    let motion = match &args.motion {
        Some(path) => load_motion(path)?,
        None => example_motion(),
    };
    if args.poses == 0 {
        bail!("--poses: expected at least 1");
    }
    let count = pose_count(&motion, args.poses);
    check_pose_count(count, MAX_POSES, "every row stays in memory until the end")?;
    check_metric_pose_count(count, metrics.len())?;
    let samples = sample_motion(&motion, args.poses).context("--poses")?;
    check_samples(args.motion.as_deref(), &samples)?;
    if let Some(path) = &args.out {
        check_output_file("--out", path, &["csv", "json"])?;
    }
    if let Some(path) = &args.plot {
        check_output_file("--plot", path, &["svg"])?;
        if samples.len() < 2 {
            bail!("--plot: need at least 2 poses, got {}", samples.len());
        }
    }
    if let Some(path) = &args.plot_data {
        check_output_file("--plot-data", path, &["csv"])?;
    }
    let curve = metric_curve(&design, &motion, args.poses, &metrics, &args)?;
    let table = motion_table(&design, &samples, &options, curve.as_ref(), &metrics)?;
    match &args.out {
        Some(path) => write_table(path, &table, &options)?,
        None => print!("{}", csv_text(&table, &options)?),
    }
    if args.plot.is_some() || args.plot_data.is_some() {
        let curves = scaled_curves(&table);
        if let Some(path) = &args.plot {
            let singular = singular_parameters(&design, &motion, &samples);
            plot(path, &table, &curves, &singular)?;
        }
        if let Some(path) = &args.plot_data {
            write_plot_data(path, &table, &curves)?;
        }
    }
    finish(curve.as_ref())
}

/// Warns about lost paths of the metric computation (after every output was written);
/// [`Outcome::PathsLost`] if there were any.
fn finish(curve: Option<&CurveResult>) -> Result<Outcome> {
    Ok(Outcome::paths_lost_if(
        curve.is_some_and(|curve| warn_failures(&curve.failures)),
    ))
}

/// The metric distances along the motion ([`compute_curve`] with the `curve` command's
/// default start provider and options), or `None` when no metric was asked for.
fn metric_curve(
    design: &Design,
    motion: &Motion,
    poses: usize,
    metrics: &[Metric],
    args: &IndicesArgs,
) -> Result<Option<CurveResult>> {
    if metrics.is_empty() {
        return Ok(None);
    }
    let options = CurveOptions {
        seed: args.seed,
        ..CurveOptions::default()
    };
    let count = match motion {
        Motion::Poses(list) => list.poses.len(),
        Motion::Analytic(_) => poses,
    };
    let progress = if args.quiet {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::new(count as u64);
        bar.set_style(
            ProgressStyle::with_template(
                "{msg} [{bar:40}] {pos}/{len} poses ({elapsed}, eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar.set_message("metric distances: start solutions + seed");
        bar
    };
    let on_pose = |_: &PoseResult| {
        progress.set_message("metric distances");
        progress.inc(1);
    };
    let result = with_threads(args.threads, || {
        compute_curve(
            design,
            motion,
            poses,
            metrics,
            &options,
            &default_start_solutions,
            &on_pose,
        )
    })?
    .context("--with-metrics")?;
    progress.finish_and_clear();
    Ok(Some(result))
}

/// One row of the motion table.
struct Row {
    tau: f64,
    indices: RprIndices,
    /// Per metric name: its distance at this pose (absent: no real critical point).
    metrics: BTreeMap<String, MetricDistance>,
    /// Lost paths of the metric computation at this pose.
    metric_failures: Vec<PathFailure>,
}

/// The motion table: indices (and metric distances) per pose.
struct Table {
    rows: Vec<Row>,
    /// Names of the metrics in the table (empty without `--with-metrics`).
    metric_names: Vec<String>,
    /// The metric computation, if any (seed, failures, not-applicable sub-problems).
    curve: Option<CurveSummary>,
}

/// Run-level facts of the metric computation written into the JSON table.
struct CurveSummary {
    seed: u64,
    not_applicable: Vec<String>,
    failures: Vec<PathFailure>,
}

fn motion_table(
    design: &Design,
    samples: &[SampledPose],
    options: &IndexOptions,
    curve: Option<&CurveResult>,
    metrics: &[Metric],
) -> Result<Table> {
    let mut rows: Vec<Row> = samples
        .par_iter()
        .map(|s| Row {
            tau: s.tau,
            indices: compute_indices(design, s.pose, options),
            metrics: BTreeMap::new(),
            metric_failures: Vec::new(),
        })
        .collect();
    if let Some(curve) = curve {
        if curve.poses.len() != rows.len() {
            bail!(
                "--with-metrics: {} metric poses for {} index poses",
                curve.poses.len(),
                rows.len()
            );
        }
        for (row, pose) in rows.iter_mut().zip(&curve.poses) {
            // Both come from `sample_motion`: the same τ and pose, bit for bit.
            if pose.tau != row.tau {
                bail!(
                    "--with-metrics: pose {} has tau {} for the metrics but {} for the indices",
                    pose.index,
                    pose.tau,
                    row.tau
                );
            }
            row.metrics = pose.metrics.clone();
            // Losses of the seed stage affect every pose: listed with each.
            row.metric_failures = curve
                .failures
                .iter()
                .filter(|f| f.pose_index.is_none())
                .chain(&pose.failures)
                .cloned()
                .collect();
        }
    }
    Ok(Table {
        rows,
        metric_names: metrics.iter().map(Metric::name).collect(),
        curve: curve.map(|c| CurveSummary {
            seed: c.seed,
            not_applicable: c.not_applicable.clone(),
            failures: c.failures.clone(),
        }),
    })
}

/// Column headers with the variant named where a Choice was made; then per metric
/// `NAME` (distance) and `NAME_signed` (signed distance), and `metric_failures`.
fn headers(options: &IndexOptions, metric_names: &[String]) -> Vec<String> {
    let mut out: Vec<String> = ["tau", "x", "y", "phi"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let w = options.cylinder_half_width;
    for name in INDEX_COLUMN_NAMES {
        out.push(match name {
            "DS" => format!("DS({},reconstructed)", options.ds.name()),
            "MDS" => format!("MDS({},reconstructed)", options.ds.name()),
            "CN" => format!("CN({})", options.cn.name()),
            "cylinder_radius" => format!("cylinder_radius(phi+-{w})"),
            other => other.to_string(),
        });
    }
    for name in metric_names {
        out.push(name.clone());
        out.push(format!("{name}_signed"));
    }
    if !metric_names.is_empty() {
        out.push("metric_failures".into());
    }
    out
}

fn cell(value: Option<f64>) -> String {
    match value {
        Some(v) if v.is_finite() => format!("{v:.12e}"),
        _ => "undefined".into(),
    }
}

/// `PROBLEM failed/expected` of every group with failed paths (`seed PROBLEM …` for
/// the seed stage), `;`-separated.
fn failure_cell(failures: &[PathFailure]) -> String {
    failures
        .iter()
        .map(|f| {
            let stage = if f.pose_index.is_none() { "seed " } else { "" };
            format!(
                "{stage}{} {}/{} failed",
                f.problem,
                f.expected - f.accounted,
                f.expected
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn csv_text(table: &Table, options: &IndexOptions) -> Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(headers(options, &table.metric_names))?;
    for row in &table.rows {
        let p = row.indices.pose;
        let mut record = vec![
            format!("{}", row.tau),
            format!("{}", p.x),
            format!("{}", p.y),
            format!("{}", p.phi),
        ];
        record.extend(index_columns(&row.indices).iter().map(|(_, v)| cell(*v)));
        for name in &table.metric_names {
            let m = row.metrics.get(name);
            record.push(cell(m.map(|m| m.distance)));
            record.push(cell(m.map(|m| m.signed_distance)));
        }
        if !table.metric_names.is_empty() {
            record.push(failure_cell(&row.metric_failures));
        }
        writer.write_record(record)?;
    }
    Ok(String::from_utf8(writer.into_inner()?)?)
}

/// JSON of one metric's distance at one pose (`null` when no real critical point).
fn metric_json(metric: Option<&MetricDistance>) -> serde_json::Value {
    match metric {
        Some(m) => serde_json::json!({
            "distance": m.distance,
            "signed_distance": m.signed_distance,
            "subproblem": m.subproblem,
            "cut_locus": m.cut_locus,
            "closest": m.closest,
        }),
        None => serde_json::Value::Null,
    }
}

fn metrics_json(
    names: &[String],
    values: &BTreeMap<String, MetricDistance>,
) -> serde_json::Map<String, serde_json::Value> {
    names
        .iter()
        .map(|name| (name.clone(), metric_json(values.get(name))))
        .collect()
}

fn write_table(path: &Path, table: &Table, options: &IndexOptions) -> Result<()> {
    let text = match extension(path).as_deref() {
        Some("csv") => csv_text(table, options)?,
        Some("json") => {
            let rows: Vec<serde_json::Value> = table
                .rows
                .iter()
                .map(|r| {
                    let mut v = serde_json::to_value(&r.indices)?;
                    v["tau"] = serde_json::json!(r.tau);
                    if table.curve.is_some() {
                        v["metrics"] = metrics_json(&table.metric_names, &r.metrics).into();
                        v["metric_failures"] = serde_json::to_value(&r.metric_failures)?;
                    }
                    Ok(v)
                })
                .collect::<Result<_, serde_json::Error>>()?;
            let mut document = serde_json::json!({
                "variants": options.variants(),
                "undefined": "null marks an index (or metric distance) that is undefined at that pose",
                "poses": rows,
            });
            if let Some(curve) = &table.curve {
                document["metric_names"] = serde_json::to_value(&table.metric_names)?;
                document["metric_seed"] = serde_json::json!(curve.seed);
                document["not_applicable"] = serde_json::to_value(&curve.not_applicable)?;
                document["metric_failures"] = serde_json::to_value(&curve.failures)?;
            }
            serde_json::to_string_pretty(&document)?
        }
        _ => bail!(
            "--out {}: expected a .csv or .json file name",
            path.display()
        ),
    };
    write_file("--out", path, text)
}

fn single_pose_json(
    indices: &RprIndices,
    options: &IndexOptions,
    curve: Option<&CurveResult>,
    at: Option<&PoseResult>,
) -> Result<String> {
    let mut value = serde_json::to_value(indices)?;
    value["variants"] = serde_json::to_value(options.variants())?;
    if let Some(curve) = curve {
        let empty = BTreeMap::new();
        let values = at.map_or(&empty, |p| &p.metrics);
        value["metrics"] = metrics_json(&curve.metric_names, values).into();
        value["metric_seed"] = serde_json::json!(curve.seed);
        value["not_applicable"] = serde_json::to_value(&curve.not_applicable)?;
        value["metric_failures"] = serde_json::to_value(&curve.failures)?;
    }
    Ok(serde_json::to_string_pretty(&value)?)
}

fn print_single_pose(
    indices: &RprIndices,
    options: &IndexOptions,
    metrics: &[Metric],
    at: Option<&PoseResult>,
) {
    let p = indices.pose;
    println!("pose x = {}, y = {}, phi = {}", p.x, p.y, p.phi);
    for (name, value) in index_columns(indices) {
        println!("{name:>28}  {}", cell(value));
    }
    for metric in metrics {
        let name = metric.name();
        let m = at.and_then(|p| p.metrics.get(&name));
        println!(
            "{name:>28}  {}  (signed {})",
            cell(m.map(|m| m.distance)),
            cell(m.map(|m| m.signed_distance))
        );
    }
    let v = options.variants();
    println!("variants: DS = {}; CN = {}; IR = {}", v.ds, v.cn, v.ir);
}

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
struct ScaledCurve {
    label: String,
    max: f64,
    values: Vec<Option<f64>>,
}

/// Every plotted curve divided by its maximum along the motion, so each lies in
/// [0, 1] (a curve that is identically 0 is left as is).
fn scaled_curves(table: &Table) -> Vec<ScaledCurve> {
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

fn write_plot_data(path: &Path, table: &Table, curves: &[ScaledCurve]) -> Result<()> {
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

fn plot(path: &Path, table: &Table, curves: &[ScaledCurve], singular: &[f64]) -> Result<()> {
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
