//! `singdist indices`: kinematic performance indices of a 3-RPR (docs/theory.md §9) along a
//! motion (CSV / JSON Lines / JSON table, SVG plot) or at one pose (`--pose x,y,phi
//! --json`).
//!
//! With `--with-metrics [all|NAME…]` (or the `compare` command) the table also holds the
//! singularity distances of the selected extrinsic metrics (docs/theory.md §8, computed
//! window by window by [`CurveRun`] at the very same τ samples, [`sample_motion`]), so
//! metric and index can be compared pose by pose (Kapilavai and Nawratil, Figs. 14–16).
//! The table is streamed: each window's rows are written as soon as they are final and
//! dropped. Lost homotopy paths of the metric computation are reported on stderr, in the
//! output, and by exit code 3 (as `curve`).

use super::args::MotionRunArgs;
use super::curve::{check_samples, pose_count};
use super::failures::warn_failures;
use super::indices_plot::{plot, scaled_curves, write_plot_data};
use super::indices_stream::{RowSink, TableFormat};
use super::outcome::Outcome;
use super::output::{check_output_file, write_file};
use super::resources::{MAX_POSES, check_metric_pose_count, check_pose_count, with_threads};
use super::values::{parse_metrics, parse_pose};
use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use singdist::index::rpr::{
    CnVariant, DEFAULT_CYLINDER_HALF_WIDTH, DsAggregate, INDEX_COLUMN_NAMES, IndexOptions,
    RprIndices, compute_indices, index_columns,
};
use singdist::io::{load_design, load_motion};
use singdist::mechanism::rpr::{
    Design, Motion, PoseList, SampledPose, example_design, example_motion,
};
use singdist::metric::Metric;
use singdist::pipeline::curve::{
    CurveOptions, CurveResult, CurveRun, PathFailure, PoseResult,
    compute_curve_from_embedded_starts, default_start_solutions, sample_motion,
    singular_parameters, window_ranges,
};
use singdist::pipeline::postprocess::MetricDistance;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Arguments of `singdist indices`.
#[derive(Args, Debug)]
pub struct IndicesArgs {
    #[command(flatten)]
    motion_run: MotionRunArgs,
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
    /// CSV of the plotted data: τ and every curve divided by its maximum along the
    /// motion (the divisor is in the column header).
    #[arg(long, value_name = "FILE.csv")]
    plot_data: Option<PathBuf>,
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
    let design = match args.motion_run.design() {
        Some(path) => load_design(path)?,
        None => example_design(),
    };
    if let Some(text) = &args.pose {
        if args.motion_run.output.plot.is_some()
            || args.plot_data.is_some()
            || args.motion_run.output.out.is_some()
        {
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
        return Ok(Outcome::paths_lost_if(
            curve.is_some_and(|curve| warn_failures(&curve.failures)),
        ));
    }
    if args.json {
        bail!("--json applies to a single pose (--pose x,y,phi); use --out FILE.json for a motion");
    }
    let motion = match args.motion_run.motion() {
        Some(path) => load_motion(path)?,
        None => example_motion(),
    };
    if args.motion_run.poses == 0 {
        bail!("--poses: expected at least 1");
    }
    let count = pose_count(&motion, args.motion_run.poses);
    let format = TableFormat::of(args.motion_run.output.out.as_deref());
    // Only a `.json` document or a plot holds every row until the end.
    let keep = format == TableFormat::Json
        || args.motion_run.output.plot.is_some()
        || args.plot_data.is_some();
    if keep {
        let why = "a .json document, --plot and --plot-data hold every row: stream long runs with --out FILE.csv or FILE.jsonl";
        check_pose_count(count, MAX_POSES, why)?;
        check_metric_pose_count(count, metrics.len()).map_err(|e| anyhow!("{e}; {why}"))?;
    } else {
        check_pose_count(count, MAX_POSES, "its pose list is sampled in memory")?;
    }
    let samples = sample_motion(&motion, args.motion_run.poses).context("--poses")?;
    check_samples(args.motion_run.motion(), &samples)?;
    if let Some(path) = &args.motion_run.output.out {
        check_output_file("--out", path, &["csv", "jsonl", "json"])?;
    }
    if let Some(path) = &args.motion_run.output.plot {
        check_output_file("--plot", path, &["svg"])?;
        if samples.len() < 2 {
            bail!("--plot: need at least 2 poses, got {}", samples.len());
        }
    }
    if let Some(path) = &args.plot_data {
        check_output_file("--plot-data", path, &["csv"])?;
    }
    let metric_names: Vec<String> = metrics.iter().map(Metric::name).collect();
    let sink = RowSink::new(
        (format, args.motion_run.output.out.as_deref()),
        (&options, &metric_names),
        keep,
    );
    let (summary, kept) = stream_table(
        (&design, &motion, &metrics),
        &samples,
        &options,
        &args,
        sink,
    )?;
    if let Some(rows) = kept {
        let table = Table {
            rows,
            metric_names,
            curve: summary.as_ref().map(|s| CurveSummary {
                seed: s.seed,
                not_applicable: s.not_applicable.clone(),
                failures: s.failures.clone(),
            }),
        };
        if let (Some(path), TableFormat::Json) = (&args.motion_run.output.out, format) {
            write_json_document(path, &table, &options)?;
        }
        if args.motion_run.output.plot.is_some() || args.plot_data.is_some() {
            let curves = scaled_curves(&table);
            if let Some(path) = &args.motion_run.output.plot {
                let singular = singular_parameters(&design, &motion, &samples);
                plot(path, &table, &curves, &singular)?;
            }
            if let Some(path) = &args.plot_data {
                write_plot_data(path, &table, &curves)?;
            }
        }
    }
    Ok(Outcome::paths_lost_if(
        summary.is_some_and(|s| warn_failures(&s.failures)),
    ))
}

/// The metric distances at every pose ([`compute_curve_from_embedded_starts`] with the
/// `curve` command's default options), or `None` when no metric was asked for.
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
        seed: args.motion_run.run.seed,
        ..CurveOptions::default()
    };
    let result = with_threads(args.motion_run.run.threads, || {
        compute_curve_from_embedded_starts(design, motion, poses, metrics, &options)
    })?
    .context("--with-metrics")?;
    Ok(Some(result))
}

/// The progress bar of the metric computation (hidden with `--quiet`).
fn progress_bar(quiet: bool, poses: usize) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(poses as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} poses ({elapsed}, eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message("metric distances: start solutions + seed");
    bar
}

/// Computes the motion table window by window and hands each window's rows to `sink`
/// as soon as they are final: the indices of the window's poses and, with metrics,
/// the window of the metric curve ([`CurveRun`] with the `curve` command's default
/// start provider and options, at the very same τ samples). Memory is bounded by one
/// window. Returns the run-level facts of the metric computation and the rows the
/// sink kept.
fn stream_table(
    (design, motion, metrics): (&Design, &Motion, &[Metric]),
    samples: &[SampledPose],
    options: &IndexOptions,
    args: &IndicesArgs,
    mut sink: RowSink,
) -> Result<(Option<CurveSummary>, Option<Vec<Row>>)> {
    let index_rows = |range: std::ops::Range<usize>| -> Vec<Row> {
        samples[range]
            .par_iter()
            .map(|s| Row {
                tau: s.tau,
                indices: compute_indices(design, s.pose, options),
                metrics: BTreeMap::new(),
                metric_failures: Vec::new(),
            })
            .collect()
    };
    let curve_options = CurveOptions {
        seed: args.motion_run.run.seed,
        ..CurveOptions::default()
    };
    if metrics.is_empty() {
        let result = with_threads(args.motion_run.run.threads, || -> Result<()> {
            sink.start(None)?;
            for range in window_ranges(samples.len(), curve_options.window_poses) {
                sink.write(index_rows(range))?;
            }
            Ok(())
        })
        .and_then(|r| r);
        return match result {
            Ok(()) => Ok((None, sink.finish(None)?)),
            Err(error) => Err(sink.fail(error)),
        };
    }
    let progress = progress_bar(args.motion_run.quiet, samples.len());
    let on_pose = |_: &PoseResult| {
        progress.set_message("metric distances");
        progress.inc(1);
    };
    let mut summary: Option<CurveSummary> = None;
    let result = with_threads(args.motion_run.run.threads, || -> Result<()> {
        let run = CurveRun::new(
            (design, motion, metrics),
            args.motion_run.poses,
            &curve_options,
            &default_start_solutions,
        )
        .context("--with-metrics")?;
        let header = run.header();
        if run.samples().len() != samples.len() {
            bail!(
                "--with-metrics: {} metric poses for {} index poses",
                run.samples().len(),
                samples.len()
            );
        }
        // Losses of the seed stage affect every pose: listed with each.
        let seed_failures: Vec<PathFailure> = header
            .seed_failures
            .iter()
            .filter(|f| f.pose_index.is_none())
            .cloned()
            .collect();
        let facts = summary.insert(CurveSummary {
            seed: header.seed,
            not_applicable: header.not_applicable.clone(),
            failures: header.seed_failures.clone(),
        });
        sink.start(Some(facts))?;
        for w in 0..header.windows {
            let window = run.solve_window(w, &on_pose)?;
            let mut rows = index_rows(run.window_range(w));
            for (row, pose) in rows.iter_mut().zip(window.poses) {
                // Both come from `sample_motion`: the same τ and pose, bit for bit.
                if pose.tau != row.tau {
                    bail!(
                        "--with-metrics: pose {} has tau {} for the metrics but {} for the indices",
                        pose.index,
                        pose.tau,
                        row.tau
                    );
                }
                facts.failures.extend(pose.failures.iter().cloned());
                row.metric_failures = seed_failures.iter().cloned().chain(pose.failures).collect();
                row.metrics = pose.metrics;
            }
            sink.write(rows)?;
        }
        Ok(())
    })
    .and_then(|r| r);
    progress.finish_and_clear();
    match result {
        Ok(()) => {
            let kept = sink.finish(summary.as_ref())?;
            Ok((summary, kept))
        }
        Err(error) => Err(sink.fail(error)),
    }
}

/// One row of the motion table.
pub struct Row {
    /// Motion parameter of the pose.
    pub tau: f64,
    /// The indices at the pose.
    pub indices: RprIndices,
    /// Per metric name: its distance at this pose (absent: no real critical point).
    pub metrics: BTreeMap<String, MetricDistance>,
    /// Lost paths of the metric computation at this pose.
    pub metric_failures: Vec<PathFailure>,
}

/// The motion table: indices (and metric distances) per pose.
pub struct Table {
    /// Its rows, in pose order.
    pub rows: Vec<Row>,
    /// Names of the metrics in the table (empty without `--with-metrics`).
    pub metric_names: Vec<String>,
    /// The metric computation, if any (seed, failures, not-applicable sub-problems).
    pub curve: Option<CurveSummary>,
}

/// Run-level facts of the metric computation written into the JSON table.
pub struct CurveSummary {
    /// Seed of the metric computation.
    pub seed: u64,
    /// Sub-problems not applicable to the design.
    pub not_applicable: Vec<String>,
    /// Every lost path: the seed stage's, then the poses' in order.
    pub failures: Vec<PathFailure>,
}

/// Column headers with the variant named where a Choice was made; then per metric
/// `NAME` (distance) and `NAME_signed` (signed distance), and `metric_failures`.
pub fn headers(options: &IndexOptions, metric_names: &[String]) -> Vec<String> {
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

pub fn cell(value: Option<f64>) -> String {
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

/// The CSV records of `rows` (no header), in the columns of [`headers`].
pub fn csv_rows(rows: &[Row], metric_names: &[String]) -> Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    for row in rows {
        let p = row.indices.pose;
        let mut record = vec![
            format!("{}", row.tau),
            format!("{}", p.x),
            format!("{}", p.y),
            format!("{}", p.phi),
        ];
        record.extend(index_columns(&row.indices).iter().map(|(_, v)| cell(*v)));
        for name in metric_names {
            let m = row.metrics.get(name);
            record.push(cell(m.map(|m| m.distance)));
            record.push(cell(m.map(|m| m.signed_distance)));
        }
        if !metric_names.is_empty() {
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

/// The JSON object of one row: its indices, `tau` and (with metrics) `metrics` and
/// `metric_failures`.
pub fn row_json(row: &Row, metric_names: &[String]) -> Result<serde_json::Value> {
    let mut v = serde_json::to_value(&row.indices)?;
    v["tau"] = serde_json::json!(row.tau);
    if !metric_names.is_empty() {
        v["metrics"] = metrics_json(metric_names, &row.metrics).into();
        v["metric_failures"] = serde_json::to_value(&row.metric_failures)?;
    }
    Ok(v)
}

/// What `null` means in the JSON outputs.
const UNDEFINED_NOTE: &str =
    "null marks an index (or metric distance) that is undefined at that pose";

/// The JSON Lines header record: `variants`, `undefined` and, with metrics,
/// `metric_names`, `metric_seed`, `not_applicable` and the seed stage's lost paths.
pub fn jsonl_header(
    options: &IndexOptions,
    metric_names: &[String],
    curve: Option<&CurveSummary>,
) -> Result<serde_json::Value> {
    let mut header = serde_json::json!({
        "record": "header",
        "variants": options.variants(),
        "undefined": UNDEFINED_NOTE,
    });
    if let Some(curve) = curve {
        header["metric_names"] = serde_json::to_value(metric_names)?;
        header["metric_seed"] = serde_json::json!(curve.seed);
        header["not_applicable"] = serde_json::to_value(&curve.not_applicable)?;
        header["seed_failures"] = serde_json::to_value(&curve.failures)?;
    }
    Ok(header)
}

/// Writes the table as one JSON document (every row in memory).
fn write_json_document(path: &Path, table: &Table, options: &IndexOptions) -> Result<()> {
    let rows: Vec<serde_json::Value> = table
        .rows
        .iter()
        .map(|r| row_json(r, &table.metric_names))
        .collect::<Result<_>>()?;
    let mut document = serde_json::json!({
        "variants": options.variants(),
        "undefined": UNDEFINED_NOTE,
        "poses": rows,
    });
    if let Some(curve) = &table.curve {
        document["metric_names"] = serde_json::to_value(&table.metric_names)?;
        document["metric_seed"] = serde_json::json!(curve.seed);
        document["not_applicable"] = serde_json::to_value(&curve.not_applicable)?;
        document["metric_failures"] = serde_json::to_value(&curve.failures)?;
    }
    write_file("--out", path, serde_json::to_string_pretty(&document)?)
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
