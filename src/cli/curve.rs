//! `singdist curve`: distance-to-singularity curves of a 3-RPR along a motion for the
//! nine extrinsic metrics (docs/theory.md §8): JSON / CSV table, SVG plot, compact table on
//! stdout. Exit code 3 when paths were lost (listed in the output and on stderr).

use super::args::{HtmlReportArg, MetricsArg, MotionRunArgs};
use super::curve_log::{PoseLines, RunLog};
use super::failures::warn_failures;
use super::outcome::Outcome;
use super::output::{PartialFile, check_output_file, extension, write_file};
use super::resources::{MAX_POSES, check_metric_pose_count, check_pose_count, with_threads};
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
    CurveOptions, CurveResult, CurveRun, PathFailure, PoseResult, collect_curve,
    default_start_solutions, sample_motion, singular_parameters,
};
use std::path::Path;

/// Arguments of `singdist curve`.
#[derive(Args, Debug)]
pub struct CurveArgs {
    #[command(flatten)]
    motion_run: MotionRunArgs,
    #[command(flatten)]
    metrics: MetricsArg,
    #[command(flatten)]
    report: HtmlReportArg,
    /// Poses per chain: one pose of every block of N is solved from the seed (the
    /// one nearest Re τ*; the first for pose lists, which are chained in
    /// nearest-neighbour order), the others forwards and
    /// backwards from it, each from its predecessors (Newton's method from extrapolated critical
    /// points, short pose-to-pose paths where that set is incomplete, the seed route
    /// where those lose a critical point); 1 = every pose from the seed.
    #[arg(long, value_name = "N", default_value_t = CurveOptions::default().chain_length)]
    chain: usize,
    /// Skip the self-check: by default the first and last pose and each metric's
    /// closest pose are solved again from an independent seed stage, and a closer
    /// singular configuration found there is reported (exit code 3). It costs about
    /// twice the rest of a 90-pose run of the example; skipping it is not recommended.
    /// Without it, the metrics whose seed count is below the generic one still get the
    /// independent seed stage, which confirms or raises that count.
    #[arg(long)]
    no_self_check: bool,
    /// Certify every pose's critical points in interval arithmetic (Krawczyk's test)
    /// and report per metric whether the distance is a proved global minimum (table
    /// mark `G`), a proved critical value whose completeness is not proved (`m`), or
    /// unproved (`?`); in JSON / JSON Lines a `certificate` per metric and sub-problem.
    #[arg(long)]
    certify: bool,
    /// Continue the interrupted run of `--out FILE` from `FILE.partial`: its complete
    /// windows are kept, the rest is computed again; the output is byte for byte that of
    /// an uninterrupted run (without `FILE.partial`, the run starts afresh). Refused (naming the difference) if the arguments that
    /// determine the results (design, motion, metrics, poses, seed, chain, window,
    /// self-check) differ from the interrupted run's.
    #[arg(long)]
    resume: bool,
    /// Poses per window: the motion is solved window by window, each window completely
    /// (chains, rescue, self-check of its first, last and closest poses) before it is
    /// written and dropped. Chains stay within a window. Results depend on it, not on
    /// the thread count.
    #[arg(long, value_name = "N", default_value_t = CurveOptions::default().window_poses)]
    window: usize,
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

/// Where the poses of a run go as windows complete.
#[derive(Clone, Copy, Debug, PartialEq)]
enum OutputKind {
    /// The compact table on stdout.
    Table,
    /// `.json`: one document, written at the end (every pose kept in memory).
    Json,
    /// `.jsonl`: the run log with its summary line.
    JsonLines,
    /// `.csv`: one row per pose.
    Csv,
}

impl OutputKind {
    fn of(out: Option<&Path>) -> Self {
        match out.map(|p| extension(p).unwrap_or_default()) {
            None => OutputKind::Table,
            Some(e) if e == "csv" => OutputKind::Csv,
            Some(e) if e == "jsonl" => OutputKind::JsonLines,
            Some(_) => OutputKind::Json,
        }
    }
}

/// `(name, value)` of every argument the results depend on, as the run log's header
/// records them (a resume must match them all).
fn run_arguments(
    (design, motion, metrics): (&Design, &Motion, &[Metric]),
    poses: usize,
    options: &CurveOptions,
) -> Result<Vec<(String, serde_json::Value)>> {
    let json = |name: &str, v: serde_json::Value| (name.to_string(), v);
    Ok(vec![
        json("program", serde_json::json!(env!("CARGO_PKG_VERSION"))),
        json("design", serde_json::to_value(design)?),
        json("motion", serde_json::to_value(motion)?),
        json(
            "metric",
            serde_json::json!(metrics.iter().map(Metric::name).collect::<Vec<_>>()),
        ),
        json("poses", serde_json::json!(poses)),
        json("seed", serde_json::json!(options.seed)),
        json("chain", serde_json::json!(options.chain_length)),
        json("window", serde_json::json!(options.window_poses)),
        json("self-check", serde_json::json!(options.self_check)),
        json("certify", serde_json::json!(options.certify)),
    ])
}

/// Runs `singdist curve`.
pub fn run(args: CurveArgs) -> Result<Outcome> {
    let (design, motion) = load_inputs(args.motion_run.design(), args.motion_run.motion())?;
    let metrics = args.metrics.parse()?;
    let kind = OutputKind::of(args.motion_run.output.out.as_deref());
    let count = pose_count(&motion, args.motion_run.poses);
    // Only a `.json` document, a plot or a report holds every pose until the end.
    let in_memory = kind == OutputKind::Json
        || args.motion_run.output.plot.is_some()
        || args.report.html.is_some();
    if in_memory {
        check_metric_pose_count(count, metrics.len()).map_err(|e| {
            anyhow!(
                "{e}; a .json document, --plot and --html hold every pose: stream long runs with --out FILE.csv or FILE.jsonl"
            )
        })?;
    } else {
        check_pose_count(count, MAX_POSES, "its pose list is sampled in memory")?;
    }
    let samples = sample_motion(&motion, args.motion_run.poses).context("--poses")?;
    check_samples(args.motion_run.motion(), &samples)?;
    if args.chain == 0 {
        bail!("--chain: must be at least 1");
    }
    if args.window == 0 {
        bail!("--window: must be at least 1");
    }
    if let Some(out) = &args.motion_run.output.out {
        check_output_file("--out", out, &["json", "jsonl", "csv"])?;
    }
    if args.resume && !matches!(kind, OutputKind::Csv | OutputKind::JsonLines) {
        bail!(
            "--resume: continues a streamed run: needs --out FILE.csv or FILE.jsonl (the run to continue is FILE.partial)"
        );
    }
    if args.resume && (args.motion_run.output.plot.is_some() || args.report.html.is_some()) {
        bail!("--resume: --plot and --html need every pose in memory; resume without them");
    }
    if let Some(plot) = &args.motion_run.output.plot {
        check_output_file("--plot", plot, &["svg"])?;
        if samples.len() < 2 {
            bail!("--plot: need at least 2 poses, got {}", samples.len());
        }
    }
    if let Some(html) = &args.report.html {
        check_output_file("--html", html, &["html"])?;
    }
    let options = CurveOptions {
        seed: args.motion_run.run.seed,
        chain_length: args.chain,
        self_check: !args.no_self_check,
        window_poses: args.window,
        certify: args.certify,
        ..CurveOptions::default()
    };
    let arguments = run_arguments((&design, &motion, &metrics), samples.len(), &options)?;
    let progress = if args.motion_run.quiet {
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
    let on_pose = |_: &PoseResult| {
        progress.set_message("poses");
        progress.inc(1);
    };
    let started = std::time::Instant::now();
    let context = (&design, &motion, &metrics[..]);
    let streamed = with_threads(args.motion_run.run.threads, || -> Result<Streamed> {
        let run = CurveRun::new(context, args.motion_run.poses, &options, &default_start_solutions)?;
        let header = run.header();
        let lines = match kind {
            OutputKind::Csv => PoseLines::Csv,
            _ => PoseLines::Json,
        };
        let log_header = (arguments, header.clone());
        let samples = run.samples();
        let tau_of = |j: usize| samples.get(j).map(|s| s.tau);
        let mut log = match &args.motion_run.output.out {
            None => None,
            Some(out) if args.resume && PartialFile::path_for(out).exists() => {
                let log = RunLog::resume(out, log_header, (lines, &metrics[..]), &tau_of)?;
                progress.set_position(log.totals.poses as u64);
                Some(log)
            }
            Some(out) => {
                if args.resume {
                    eprintln!(
                        "singdist: note: --resume: {} does not exist; starting from the first window",
                        PartialFile::path_for(out).display()
                    );
                }
                Some(RunLog::create(out, log_header, lines, &metrics)?)
            }
        };
        let mut kept = Vec::new();
        if kind == OutputKind::Table {
            print_table_header(&metrics);
        }
        let first = log.as_ref().map_or(0, |l| l.totals.windows);
        let mut table_totals = (header.seed_paths_tracked, header.seed_failures.clone());
        for w in first..header.windows {
            let window = run.solve_window(w, &on_pose)?;
            if let Some(file) = &mut log
                && let Err(error) = file.write_window(&window)
            {
                let log = log.take().expect("the log is open");
                return Err(log.abandon(error));
            }
            if kind == OutputKind::Table {
                print_table_rows(&window.poses, &metrics);
                table_totals.0 += window.paths_tracked;
                table_totals
                    .1
                    .extend(window.poses.iter().flat_map(|p| p.failures.iter().cloned()));
            }
            if in_memory {
                kept.push(window);
            }
        }
        let (paths_tracked, failures) = match &log {
            Some(file) => (file.paths_tracked(), file.failures()),
            None => table_totals,
        };
        let curve = in_memory.then(|| collect_curve(header, kept));
        Ok(Streamed {
            log,
            curve,
            paths_tracked,
            failures,
        })
    })
    .and_then(|r| r);
    progress.finish_and_clear();
    let streamed = streamed?;
    let elapsed = started.elapsed().as_secs_f64();
    let singular = singular_parameters(&design, &motion, &samples);
    if let (Some(path), Some(log)) = (&args.motion_run.output.out, streamed.log) {
        match kind {
            OutputKind::JsonLines => log.finish_jsonl(path)?,
            OutputKind::Csv => log.finish_csv(path)?,
            _ => {
                let result = streamed
                    .curve
                    .as_ref()
                    .expect("a .json run keeps its poses");
                let text = serde_json::to_string_pretty(result).context("serialising the curve")?;
                if let Err(error) = write_file("--out", path, text) {
                    return Err(log.abandon(error));
                }
                // The final file supersedes the partial one.
                log.remove();
            }
        }
    }
    if kind == OutputKind::Table {
        print_table_footer(&singular);
        if options.certify {
            println!(
                "certified (interval arithmetic): G = global minimum proved, m = critical value proved but not that it is the smallest, ? = not proved"
            );
        }
    }
    if let (Some(path), Some(result)) = (&args.motion_run.output.plot, &streamed.curve) {
        plot(path, result, &metrics, &singular)?;
    }
    if let (Some(path), Some(result)) = (&args.report.html, &streamed.curve) {
        let names: Vec<String> = metrics.iter().map(Metric::name).collect();
        let report = rpr_report(&design, result, &names, &singular);
        write_file("--html", path, report_html(&report))?;
    }
    if !args.motion_run.quiet {
        eprintln!(
            "singdist: {} poses, {} metrics, {} paths in {:.3} s ({:.0} paths/s)",
            samples.len(),
            metrics.len(),
            streamed.paths_tracked,
            elapsed,
            streamed.paths_tracked as f64 / elapsed.max(1e-9)
        );
    }
    Ok(Outcome::paths_lost_if(warn_failures(&streamed.failures)))
}

/// What a run leaves for its outputs once every window is done.
struct Streamed {
    log: Option<RunLog>,
    curve: Option<CurveResult>,
    paths_tracked: usize,
    failures: Vec<PathFailure>,
}

fn print_table_header(metrics: &[Metric]) {
    print!("{:>9} {:>11}", "tau", "S");
    for metric in metrics {
        print!(" {:>12}", metric.name());
    }
    println!();
}

fn print_table_rows(poses: &[PoseResult], metrics: &[Metric]) {
    for pose in poses {
        print!("{:>9.4} {:>11.4e}", pose.tau, pose.singularity);
        for metric in metrics {
            match pose.metrics.get(&metric.name()) {
                Some(m) => print!(
                    " {:>11.6}{}{}",
                    m.signed_distance,
                    if m.cut_locus { "*" } else { " " },
                    certified_mark(m)
                ),
                None => print!(" {:>12}", "-"),
            }
        }
        println!();
    }
}

/// `G` (certified global minimum), `m` (minimiser only), `?` (not proved), or nothing
/// when the run does not certify.
fn certified_mark(m: &singdist::pipeline::postprocess::MetricDistance) -> &'static str {
    use singdist::certify::distance::CertifiedStatus;
    match m.certificate.as_ref().map(|c| c.status) {
        None => "",
        Some(CertifiedStatus::GlobalMinimum) => "G",
        Some(CertifiedStatus::MinimiserOnly) => "m",
        Some(CertifiedStatus::None) => "?",
    }
}

fn print_table_footer(singular: &[f64]) {
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
