//! `singdist curve`: distance-to-singularity curves of a 3-RPR along a motion for the
//! nine extrinsic metrics (SPEC A.9): JSON / CSV table, SVG plot, compact table on
//! stdout. Exit code 3 when paths were lost (listed in the output and on stderr).

use super::failures::{lost_paths, warn_failures};
use super::outcome::Outcome;
use super::output::{PartialFile, check_output_file, is_csv, write_file};
use super::resources::{check_metric_pose_count, with_threads};
use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use singdist::io::report::{report_html, rpr_report};
use singdist::io::{load_design, load_motion};
use singdist::mechanism::rpr::{
    Design, Motion, SampledPose, check_sampled_poses, example_design, example_motion,
};
use singdist::metric::Metric;
use singdist::pipeline::curve::{
    CurveOptions, CurveResult, PoseResult, compute_curve, default_start_solutions, sample_motion,
    singular_parameters,
};
use std::path::{Path, PathBuf};

/// Arguments of `singdist curve`.
#[derive(Args, Debug)]
pub struct CurveArgs {
    /// Design file (JSON `{"base": [[x,y],…], "platform": [[x,y],…]}`); default: the
    /// built-in example.
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
    /// Motion file (analytic motion or explicit pose list); default: the built-in example.
    #[arg(long, value_name = "FILE")]
    motion: Option<PathBuf>,
    /// Number of poses evenly spaced in τ (pose lists are used as given); poses ×
    /// metrics at most 100,000 (every pose's results stay in memory until the end).
    #[arg(long, value_name = "N", default_value_t = 90)]
    poses: usize,
    /// Metrics: `all`, or names like `plate/plate bars/rigid` (or comma separated).
    #[arg(long, value_name = "NAME", num_args = 1.., default_value = "all")]
    metric: Vec<String>,
    /// Output table: `.json` (full detail) or `.csv` (signed distance per metric, and
    /// `lost_paths` per pose: paths lost there plus those lost at the seed, which
    /// affect every pose). Checked, like `--plot`, before the computation.
    /// Partial results are appended to `FILE.partial` (JSON lines, each with its pose
    /// `index`) while running, in the order poses complete: the chain's start pose
    /// (nearest Re τ*) first, then forwards and backwards from it, block by block. A
    /// pose re-solved by the rescue pass (from a neighbouring pose) appears again, the
    /// later line wins.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// SVG plot of the signed distance curves against τ, singular poses marked.
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// Self-contained HTML report: the curves against τ with a slider on τ, and the
    /// drawing of the manipulator K and each metric's closest singular configuration K′
    /// at the chosen τ (no network access needed to view it).
    #[arg(long, value_name = "FILE.html")]
    html: Option<PathBuf>,
    /// Worker threads (default: all cores; more than the cores is clamped to them).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Seed of every random choice (results are identical for any thread count).
    #[arg(long, value_name = "S", default_value_t = 1)]
    seed: u64,
    /// Poses per chain: one pose of every block of N is solved from the seed (the
    /// one nearest Re τ*; the first for pose lists), the others forwards and
    /// backwards from it, each from its predecessors (Newton's method from extrapolated critical
    /// points, short pose-to-pose paths where that set is incomplete, the seed route
    /// where those lose a critical point); 1 = every pose from the seed.
    #[arg(long, value_name = "N", default_value_t = CurveOptions::default().chain_length)]
    chain: usize,
    /// Skip the self-check: by default the first and last pose and each metric's
    /// closest pose are solved again from an independent seed stage, and a closer
    /// singular configuration found there is reported (exit code 3). It costs about
    /// twice the rest of a 90-pose run of the example; skipping it is not recommended.
    #[arg(long)]
    no_self_check: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// Loads the design and motion (built-in example by default).
pub fn load_inputs(design: Option<&Path>, motion: Option<&Path>) -> Result<(Design, Motion)> {
    let design = match design {
        Some(path) => load_design(path)?,
        None => example_design(),
    };
    let motion = match motion {
        Some(path) => load_motion(path)?,
        None => example_motion(),
    };
    Ok((design, motion))
}

/// Parses `--metric` values (each `all` or a comma-separated list).
pub fn parse_metrics(values: &[String]) -> Result<Vec<Metric>> {
    let mut metrics: Vec<Metric> = Vec::new();
    for value in values {
        for metric in Metric::parse_list(value).context("--metric")? {
            if !metrics.contains(&metric) {
                metrics.push(metric);
            }
        }
    }
    if metrics.is_empty() {
        bail!("--metric: no metric given");
    }
    Ok(metrics)
}

/// Number of poses a run of `motion` with `--poses poses` has (pose lists: their length).
pub fn pose_count(motion: &Motion, poses: usize) -> usize {
    match motion {
        Motion::Poses(list) => list.poses.len(),
        Motion::Analytic(_) => poses,
    }
}

/// Checks every sampled pose of the motion (finite, within the input range); errors
/// name the motion file (or `motion` for the built-in one).
pub fn check_samples(motion: Option<&Path>, samples: &[SampledPose]) -> Result<()> {
    check_sampled_poses(samples).map_err(|e| match motion {
        Some(path) => anyhow!("{}: {e}", path.display()),
        None => anyhow!("motion: {e}"),
    })
}

/// Runs `singdist curve`.
pub fn run(args: CurveArgs) -> Result<Outcome> {
    let (design, motion) = load_inputs(args.design.as_deref(), args.motion.as_deref())?;
    let metrics = parse_metrics(&args.metric)?;
    check_metric_pose_count(pose_count(&motion, args.poses), metrics.len())?;
    let samples = sample_motion(&motion, args.poses).context("--poses")?;
    check_samples(args.motion.as_deref(), &samples)?;
    if args.chain == 0 {
        bail!("--chain: must be at least 1");
    }
    if let Some(out) = &args.out {
        check_output_file("--out", out, &["json", "csv"])?;
    }
    if let Some(plot) = &args.plot {
        check_output_file("--plot", plot, &["svg"])?;
        if samples.len() < 2 {
            bail!("--plot: need at least 2 poses, got {}", samples.len());
        }
    }
    if let Some(html) = &args.html {
        check_output_file("--html", html, &["html"])?;
    }
    let options = CurveOptions {
        seed: args.seed,
        chain_length: args.chain,
        self_check: !args.no_self_check,
        ..CurveOptions::default()
    };
    let partial = match &args.out {
        Some(out) => Some(PartialFile::create("--out", out)?),
        None => None,
    };
    let progress = if args.quiet {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::new(samples.len() as u64);
        bar.set_style(
            ProgressStyle::with_template(
                "{msg} [{bar:40}] {pos}/{len} poses ({elapsed}, eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar.set_message("start solutions + seed");
        bar
    };
    let on_pose = |pose: &PoseResult| {
        progress.set_message("poses");
        progress.inc(1);
        if let Some(file) = &partial
            && let Ok(line) = serde_json::to_string(pose)
        {
            file.append_line(&line);
        }
    };
    let started = std::time::Instant::now();
    let computed = with_threads(args.threads, || {
        compute_curve(
            &design,
            &motion,
            args.poses,
            &metrics,
            &options,
            &default_start_solutions,
            &on_pose,
        )
    })
    .and_then(|r| Ok(r?));
    progress.finish_and_clear();
    let result = match computed {
        Ok(result) => result,
        Err(error) => return Err(abandon(partial, error)),
    };
    let elapsed = started.elapsed().as_secs_f64();
    let singular = singular_parameters(&design, &motion, &samples);
    match &args.out {
        Some(path) => {
            if let Err(error) = write_output(path, &result, &metrics) {
                return Err(abandon(partial, error));
            }
            if let Some(partial) = partial {
                // The final file supersedes the partial one.
                partial.finish();
            }
        }
        None => print_table(&result, &metrics, &singular),
    }
    if let Some(path) = &args.plot {
        plot(path, &result, &metrics, &singular)?;
    }
    if let Some(path) = &args.html {
        let names: Vec<String> = metrics.iter().map(Metric::name).collect();
        let report = rpr_report(&design, &result, &names, &singular);
        write_file("--html", path, report_html(&report))?;
    }
    if !args.quiet {
        eprintln!(
            "singdist: {} poses, {} metrics, {} paths in {:.3} s ({:.0} paths/s)",
            result.poses.len(),
            metrics.len(),
            result.paths_tracked,
            elapsed,
            result.paths_tracked as f64 / elapsed.max(1e-9)
        );
    }
    Ok(Outcome::paths_lost_if(warn_failures(&result.failures)))
}

/// The error of a failed run, naming (or removing, if empty) its partial file.
fn abandon(partial: Option<PartialFile>, error: anyhow::Error) -> anyhow::Error {
    match partial {
        Some(partial) => partial.abandon(error),
        None => error,
    }
}

fn write_output(path: &Path, result: &CurveResult, metrics: &[Metric]) -> Result<()> {
    let text = if is_csv(path) {
        csv_text(result, metrics)?
    } else {
        serde_json::to_string_pretty(result).context("serialising the curve")?
    };
    write_file("--out", path, text)
}

/// CSV: `tau, x, y, phi, S`, then one column per metric (signed distance), then
/// `lost_paths`: the paths lost at that pose (its own failures plus the seed stage's,
/// which affect every pose; 0 when every critical point was found).
pub fn csv_text(result: &CurveResult, metrics: &[Metric]) -> Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    let mut header: Vec<String> = ["tau", "x", "y", "phi", "S"].map(String::from).to_vec();
    header.extend(metrics.iter().map(Metric::name));
    header.push("lost_paths".into());
    writer.write_record(&header)?;
    for pose in &result.poses {
        let mut row: Vec<String> = vec![
            pose.tau.to_string(),
            pose.pose[0].to_string(),
            pose.pose[1].to_string(),
            pose.pose[2].to_string(),
            pose.singularity.to_string(),
        ];
        for metric in metrics {
            row.push(
                pose.metrics
                    .get(&metric.name())
                    .map(|m| m.signed_distance.to_string())
                    .unwrap_or_default(),
            );
        }
        row.push(lost_paths(&pose.failures, &result.failures).to_string());
        writer.write_record(&row)?;
    }
    let bytes = writer.into_inner().context("writing CSV")?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

fn print_table(result: &CurveResult, metrics: &[Metric], singular: &[f64]) {
    print!("{:>9} {:>11}", "tau", "S");
    for metric in metrics {
        print!(" {:>12}", metric.name());
    }
    println!();
    for pose in &result.poses {
        print!("{:>9.4} {:>11.4e}", pose.tau, pose.singularity);
        for metric in metrics {
            match pose.metrics.get(&metric.name()) {
                Some(m) => print!(
                    " {:>11.6}{}",
                    m.signed_distance,
                    if m.cut_locus { "*" } else { " " }
                ),
                None => print!(" {:>12}", "-"),
            }
        }
        println!();
    }
    println!(
        "signed distance to the nearest singularity (sign of S); * = cut locus; singular poses at tau = {}",
        singular
            .iter()
            .map(|t| format!("{t:.6}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
}

fn plot(path: &Path, result: &CurveResult, metrics: &[Metric], singular: &[f64]) -> Result<()> {
    if result.poses.len() < 2 {
        bail!("--plot: need at least 2 poses");
    }
    let t0 = result.poses[0].tau;
    let t1 = result.poses[result.poses.len() - 1].tau;
    let values = result
        .poses
        .iter()
        .flat_map(|p| p.metrics.values().map(|m| m.signed_distance));
    let (lo, hi) = values.fold((0.0f64, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let pad = 0.05 * (hi - lo).max(1e-9);
    let curves: Vec<super::plot::Curve> = metrics
        .iter()
        .map(|metric| {
            let name = metric.name();
            let points = result
                .poses
                .iter()
                .filter_map(|p| p.metrics.get(&name).map(|m| (p.tau, m.signed_distance)))
                .collect();
            super::plot::Curve {
                label: name,
                segments: vec![points],
            }
        })
        .collect();
    let layout = super::plot::Layout {
        caption: "3-RPR signed distance to singularity along the motion",
        y_description: "signed distance D (sign of S)",
        tau_range: (t0, t1),
        y_range: (lo - pad, hi + pad),
    };
    super::plot::plot_against_tau(path, &layout, &curves, singular)
}
