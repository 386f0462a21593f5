//! `singdist rrr`: 3-RRR singularity distances (Kapilavai and Nawratil, §6.3;
//! docs/theory.md §10).
//!
//! - `rrr curve`: the four signed distance curves (parallel, legs 1–3), the overall
//!   singularity distance and the scaled parallel determinant (Kapilavai and Nawratil,
//!   Fig. 17) along a motion, as JSON / CSV / a table on stdout, optionally an SVG plot.
//!   Exit code 3 when paths were lost.
//! - `rrr ab-initio`: computes, certifies and writes the start-solution files
//!   `rrr-parallel.json`, `rrr-leg1.json` … (or verifies the embedded ones).

use super::args::{HtmlReportArg, ModesArg, MotionRunArgs};
use super::curve::{check_samples, pose_count};
use super::failures::{lost_paths, warn_failures};
use super::outcome::Outcome;
use super::output::{PartialFile, check_output_file, check_output_folder, is_csv, write_file};
use super::resources::{MAX_POSES, MAX_RRR_POSES, check_pose_count, with_threads};
use super::start_check::{all_passed, trace_text, verify_stored_file, write_start_file};
use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, Subcommand};
use singdist::io::chart::{Chart, Marker, Panel};
use singdist::io::load_motion;
use singdist::io::report::{report_html, rrr_report};
use singdist::io::rrr::load_rrr_design;
use singdist::mechanism::rrr::{
    EXAMPLE_MODES, ElbowMode, RrrMotion, RrrTrajectory, WorkingModes, example_design,
    example_motion,
};
use singdist::pipeline::ab_initio_stage::AbInitioProblem;
use singdist::pipeline::curve::window_ranges;
use singdist::pipeline::rrr::ab_initio::{
    RrrAbInitioOptions, compute_rrr_start_solutions, trace_certificate,
};
use singdist::pipeline::rrr::curve::{
    RrrCurveOptions, RrrCurveResult, RrrCurveRun, RrrPathFailure, RrrPoseResult, compute_rrr_curve,
    configurations_at, default_rrr_start_solutions, parallel_singular_parameters,
};
use singdist::problem::rrr::{RrrProblem, RrrSubProblem};
use std::io::Write;
use std::path::{Path, PathBuf};

/// `singdist rrr` subcommands.
#[derive(Subcommand, Debug)]
pub enum RrrCommand {
    /// Signed distance curves to the parallel and leg singularities along a motion.
    ///
    /// Outputs: `--out FILE.json` (full detail) or `FILE.csv` (the curves); without
    /// `--out` a table on stdout. `--plot`: the four signed curves and the scaled
    /// parallel determinant.
    Curve(RrrCurveArgs),
    /// Compute (or verify) the generic start solutions of the four 3-RRR sub-problems.
    AbInitio(RrrAbInitioArgs),
    /// SVG drawing of the 3-RRR at a pose with its closest parallel-singular and
    /// leg-singular configurations.
    ///
    /// The design's working modes (or `--modes`) choose the elbows at the pose.
    Draw(super::rrr_draw::RrrDrawArgs),
}

/// Arguments of `singdist rrr curve`.
#[derive(Args, Debug)]
pub struct RrrCurveArgs {
    #[command(flatten)]
    motion_run: MotionRunArgs,
    #[command(flatten)]
    report: HtmlReportArg,
    #[command(flatten)]
    modes: ModesArg,
    /// Hold the working modes along the whole motion instead of continuing the
    /// configuration through leg singularities.
    #[arg(long)]
    hold_modes: bool,
    /// Poses per chain: the poses are cut into blocks of N, each block into chains
    /// (pose lists in nearest-neighbour order, a new chain where the next pose is far);
    /// one pose of every chain is solved from the seed (the one nearest Re τ*; the
    /// first for pose lists), the others forwards and backwards from it, each from its
    /// neighbour's complete set of critical points (the seed route where that set or
    /// the pose-to-pose paths lose one); 1 = every pose from the seed.
    #[arg(long, value_name = "N", default_value_t = RrrCurveOptions::default().chain_length)]
    chain: usize,
    /// Skip the self-check: by default the first and last pose and each sub-problem's
    /// closest pose of every window are solved again from an independent seed stage,
    /// and a closer singular configuration found there is reported (exit code 3).
    #[arg(long)]
    no_self_check: bool,
}

/// Arguments of `singdist rrr ab-initio`.
#[derive(Args, Debug)]
pub struct RrrAbInitioArgs {
    /// Directory to write `rrr-*.json` into (default: only print the summary).
    #[arg(long, value_name = "DIR")]
    out_dir: Option<PathBuf>,
    /// Seed of the source point and the monodromy loops.
    #[arg(long, value_name = "S", default_value_t = singdist::pipeline::rrr::ab_initio::RRR_DEFAULT_SEED)]
    seed: u64,
    /// Only these problems (`parallel`, `leg1`, `leg2`, `leg3`); default all four.
    #[arg(long, value_name = "NAME", num_args = 1..)]
    problem: Vec<String>,
    /// Verify the embedded files instead of computing.
    #[arg(long)]
    verify: bool,
    /// With `--verify`: re-run the trace test on the embedded solutions (witness loops:
    /// `--stagnant-loops`, slices from `--seed`); with `--out-dir`, write the files with
    /// the new certificate.
    #[arg(long, requires = "verify")]
    retrace: bool,
    /// Skip the trace test (measure the monodromy count only; certificate `none`).
    #[arg(long)]
    no_trace_test: bool,
    /// Consecutive loops without a new solution before monodromy stops.
    #[arg(long, value_name = "N", default_value_t = 15)]
    stagnant_loops: usize,
}

/// Runs `singdist rrr …`.
pub fn run(command: RrrCommand) -> Result<Outcome> {
    match command {
        RrrCommand::Curve(args) => run_curve(args),
        RrrCommand::AbInitio(args) => run_ab_initio(args),
        RrrCommand::Draw(args) => super::rrr_draw::run(args),
    }
}

fn load_trajectory(args: &RrrCurveArgs) -> Result<RrrTrajectory> {
    let motion = match args.motion_run.motion() {
        Some(path) => load_motion(path)?,
        None => example_motion(),
    };
    let trajectory = trajectory_of(
        args.motion_run.design(),
        args.modes.text(),
        motion,
        "--motion",
    )?;
    Ok(if args.hold_modes {
        trajectory.holding_modes()
    } else {
        trajectory
    })
}

/// `--modes`: three signs `+`/`-` (or `1`/`-1`, `+1`) separated by commas.
pub(super) fn parse_modes(text: &str) -> Result<WorkingModes> {
    let items: Vec<&str> = text.split(',').map(str::trim).collect();
    if items.len() != 3 {
        bail!(
            "--modes: expected three signs like +,-,+, got {} item(s) in `{text}`",
            items.len()
        );
    }
    let mut modes = EXAMPLE_MODES;
    for (leg, item) in items.iter().enumerate() {
        modes[leg] = match *item {
            "+" | "1" | "+1" => ElbowMode::Positive,
            "-" | "-1" => ElbowMode::Negative,
            other => bail!("--modes[{leg}]: expected + or -, got `{other}`"),
        };
    }
    Ok(modes)
}

/// The design file's (or the built-in example's) 3-RRR with its working modes (or
/// `modes`, the `--modes` text, when given), moved along `motion`; errors of the motion
/// (e.g. a pose out of reach) name `option`.
pub(super) fn trajectory_of(
    design: Option<&Path>,
    modes: Option<&str>,
    motion: RrrMotion,
    option: &str,
) -> Result<RrrTrajectory> {
    let (design, mut initial) = match design {
        Some(path) => load_rrr_design(path)?,
        None => (example_design(), EXAMPLE_MODES),
    };
    if let Some(text) = modes {
        initial = parse_modes(text)?;
    }
    RrrTrajectory::new(design, initial, motion).with_context(|| option.to_string())
}

fn run_curve(args: RrrCurveArgs) -> Result<Outcome> {
    let trajectory = load_trajectory(&args)?;
    let count = pose_count(trajectory.motion(), args.motion_run.poses);
    // Only a `.json` document, a plot or a report holds every pose until the end.
    let in_memory = args.motion_run.output.plot.is_some()
        || args.report.html.is_some()
        || args
            .motion_run
            .output
            .out
            .as_deref()
            .is_some_and(|p| !is_csv(p));
    if in_memory {
        check_pose_count(
            count,
            MAX_RRR_POSES,
            "a .json document, --plot and --html keep every pose's critical points: stream long runs with --out FILE.csv or the table on stdout",
        )?;
    } else {
        check_pose_count(count, MAX_POSES, "its pose list is sampled in memory")?;
    }
    let samples = trajectory.motion().sample(args.motion_run.poses);
    check_samples(args.motion_run.motion(), &samples)?;
    if let Some(out) = &args.motion_run.output.out {
        check_output_file("--out", out, &["json", "csv"])?;
    }
    if let Some(plot) = &args.motion_run.output.plot {
        check_output_file("--plot", plot, &["svg"])?;
        if count < 2 {
            bail!("--plot: need at least 2 poses, got {}", count);
        }
    }
    if let Some(html) = &args.report.html {
        check_output_file("--html", html, &["html"])?;
    }
    if args.chain == 0 {
        bail!("--chain: must be at least 1");
    }
    let options = RrrCurveOptions {
        seed: args.motion_run.run.seed,
        chain_length: args.chain,
        self_check: !args.no_self_check,
        ..RrrCurveOptions::default()
    };
    let taus: Vec<f64> = samples.iter().map(|s| s.tau).collect();
    drop(samples);
    let started = std::time::Instant::now();
    if !in_memory {
        let (poses, paths_tracked, failures) = stream_curve(&trajectory, &taus, &options, &args)?;
        if args.motion_run.output.out.is_none() {
            let parallel = parallel_singular_parameters(&trajectory, &taus);
            print_table_footer(&parallel, trajectory.leg_crossings());
        }
        report_speed(&args, poses, paths_tracked, started);
        return Ok(Outcome::paths_lost_if(warn_failures(&failures)));
    }
    let result = with_threads(args.motion_run.run.threads, || {
        compute_rrr_curve(
            &trajectory,
            args.motion_run.poses,
            &options,
            &default_rrr_start_solutions,
        )
    })??;
    match &args.motion_run.output.out {
        Some(path) => {
            let text = serde_json::to_string_pretty(&result).context("serialising the curve")?;
            write_file("--out", path, text)?;
        }
        None => {
            print!("{}", table_header());
            print!("{}", table_rows(&result.poses));
            print_table_footer(
                &result.parallel_singular_parameters,
                &result.leg_singular_parameters,
            );
        }
    }
    report_speed(&args, result.poses.len(), result.paths_tracked, started);
    if let Some(path) = &args.motion_run.output.plot {
        plot(path, &result)?;
    }
    if let Some(path) = &args.report.html {
        let taus: Vec<f64> = result.poses.iter().map(|p| p.tau).collect();
        let configurations: Vec<_> = configurations_at(&trajectory, &taus)?
            .into_iter()
            .map(|(_, _, k)| k)
            .collect();
        write_file(
            "--html",
            path,
            report_html(&rrr_report(&configurations, &result)),
        )?;
    }
    Ok(Outcome::paths_lost_if(warn_failures(&result.failures)))
}

/// The closing line on stderr: poses, paths, time.
fn report_speed(args: &RrrCurveArgs, poses: usize, paths: usize, started: std::time::Instant) {
    if !args.motion_run.quiet {
        let elapsed = started.elapsed().as_secs_f64();
        eprintln!(
            "singdist: {poses} poses, 4 sub-problems, {paths} paths in {elapsed:.3} s ({:.0} paths/s)",
            paths as f64 / elapsed.max(1e-9)
        );
    }
}

/// Solves the curve window by window ([`RrrCurveRun`], windows of 1000 poses) and
/// writes each window as soon as it is solved: CSV rows to `FILE.partial` (renamed to
/// `FILE` at the end, removed on an error) or table rows to stdout. Returns the poses,
/// paths tracked and every failure (seed stage first).
fn stream_curve(
    trajectory: &RrrTrajectory,
    taus: &[f64],
    options: &RrrCurveOptions,
    args: &RrrCurveArgs,
) -> Result<(usize, usize, Vec<RrrPathFailure>)> {
    let mut partial: Option<PartialFile> = None;
    let result = with_threads(
        args.motion_run.run.threads,
        || -> Result<(usize, usize, Vec<RrrPathFailure>)> {
            let run = RrrCurveRun::new(trajectory, taus, options, &default_rrr_start_solutions)?;
            let write = |partial: &Option<PartialFile>, text: &str| -> Result<()> {
                match partial {
                    Some(file) => file.append(text),
                    None => {
                        let mut out = std::io::stdout().lock();
                        out.write_all(text.as_bytes())
                            .and_then(|()| out.flush())
                            .map_err(|e| anyhow!("stdout: cannot write: {e}"))
                    }
                }
            };
            match &args.motion_run.output.out {
                Some(out) => {
                    let file = partial.insert(PartialFile::create("--out", out)?);
                    file.append(&csv_header()?)?;
                }
                None => write(&partial, &table_header())?,
            }
            let mut failures = run.seed_failures().to_vec();
            let mut paths_tracked = run.seed_paths_tracked();
            for range in window_ranges(taus.len(), WINDOW_POSES) {
                let poses = run.solve_range(range, &|_| {})?.poses;
                let text = match &args.motion_run.output.out {
                    Some(_) => csv_rows(&poses, run.seed_failures())?,
                    None => table_rows(&poses),
                };
                write(&partial, &text)?;
                paths_tracked += poses.iter().map(|p| p.paths_tracked).sum::<usize>();
                failures.extend(poses.iter().flat_map(|p| p.failures.iter().cloned()));
            }
            Ok((taus.len(), paths_tracked, failures))
        },
    )
    .and_then(|r| r);
    match (result, partial, &args.motion_run.output.out) {
        (Ok(done), Some(file), Some(out)) => match std::fs::rename(file.path(), out) {
            Ok(()) => Ok(done),
            Err(e) => {
                file.finish();
                bail!("--out: {}: cannot write: {e}", out.display())
            }
        },
        (Ok(done), _, _) => Ok(done),
        (Err(error), file, _) => {
            if let Some(file) = file {
                file.finish();
            }
            Err(error)
        }
    }
}

/// Poses per window of a streamed run.
const WINDOW_POSES: usize = 1000;

fn cell(v: Option<f64>) -> String {
    v.map(|v| v.to_string()).unwrap_or_default()
}

/// The CSV header: `tau, x, y, phi, parallel, leg1, leg2, leg3, distance, nearest,
/// parallel_determinant_abs_scaled, working_modes, lost_paths`.
fn csv_header() -> Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record([
        "tau",
        "x",
        "y",
        "phi",
        "parallel",
        "leg1",
        "leg2",
        "leg3",
        "distance",
        "nearest",
        "parallel_determinant_abs_scaled",
        "working_modes",
        "lost_paths",
    ])?;
    let bytes = writer.into_inner().context("writing CSV")?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// CSV rows of `poses` under [`csv_header`] (`working_modes`: the three legs' modes at
/// that pose, e.g. `+,-,+`; `lost_paths`: paths lost at that pose plus those lost at
/// the seed, `seed_failures`, which affect every pose).
fn csv_rows(poses: &[RrrPoseResult], seed_failures: &[RrrPathFailure]) -> Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    for p in poses {
        writer.write_record([
            p.tau.to_string(),
            p.pose[0].to_string(),
            p.pose[1].to_string(),
            p.pose[2].to_string(),
            cell(p.parallel),
            cell(p.leg1),
            cell(p.leg2),
            cell(p.leg3),
            cell(p.distance),
            p.nearest.clone().unwrap_or_default(),
            p.parallel_determinant_abs_scaled.to_string(),
            p.working_modes
                .map(|m| if m < 0 { "-" } else { "+" })
                .join(","),
            lost_paths(&p.failures, seed_failures).to_string(),
        ])?;
    }
    let bytes = writer.into_inner().context("writing CSV")?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

fn table_header() -> String {
    format!(
        "{:>9} {:>11} {:>11} {:>11} {:>11} {:>11} {:>9} {:>8} {:>6}\n",
        "tau", "parallel", "leg1", "leg2", "leg3", "distance", "nearest", "|detJ|~", "modes"
    )
}

fn table_rows(poses: &[RrrPoseResult]) -> String {
    let show = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
    let mut text = String::new();
    for p in poses {
        text.push_str(&format!(
            "{:>9.4} {:>11} {:>11} {:>11} {:>11} {:>11} {:>9} {:>8.4} {:>6}\n",
            p.tau,
            show(p.parallel),
            show(p.leg1),
            show(p.leg2),
            show(p.leg3),
            show(p.distance),
            p.nearest.as_deref().unwrap_or("-"),
            p.parallel_determinant_abs_scaled,
            p.working_modes
                .map(|m| if m < 0 { "-" } else { "+" })
                .join(",")
        ));
    }
    text
}

fn print_table_footer(parallel: &[f64], legs: &[Vec<f64>; 3]) {
    let list = |v: &[f64]| {
        if v.is_empty() {
            return "none".to_string();
        }
        v.iter()
            .map(|t| format!("{t:.6}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    println!(
        "signed distances (sign of the respective determinant); |detJ|~ = |parallel determinant| / its max over the poses; parallel singular at tau = {}; leg singular at tau = {}",
        list(parallel),
        legs.iter()
            .enumerate()
            .filter(|(_, v)| !v.is_empty())
            .map(|(i, v)| format!("leg{}: {}", i + 1, list(v)))
            .reduce(|a, b| format!("{a}; {b}"))
            .unwrap_or_else(|| "none".to_string())
    );
}

fn plot(path: &Path, result: &RrrCurveResult) -> Result<()> {
    if result.poses.len() < 2 {
        bail!("--plot: need at least 2 poses");
    }
    let t0 = result.poses[0].tau;
    let t1 = result.poses[result.poses.len() - 1].tau;
    type Getter = fn(&singdist::pipeline::rrr::curve::RrrPoseResult) -> Option<f64>;
    let curve = |label: &str, get: Getter| {
        let mut segments = vec![Vec::new()];
        for p in &result.poses {
            match get(p) {
                Some(v) => {
                    if let Some(segment) = segments.last_mut() {
                        segment.push((p.tau, v));
                    }
                }
                None => segments.push(Vec::new()),
            }
        }
        super::plot::Curve {
            label: label.to_string(),
            segments,
        }
    };
    let distances = vec![
        curve("parallel singularity (signed)", |p| p.parallel),
        curve("leg 1 singularity (signed)", |p| p.leg1),
        curve("leg 2 singularity (signed)", |p| p.leg2),
        curve("leg 3 singularity (signed)", |p| p.leg3),
        curve("nearest singularity (min |D|)", |p| p.distance),
    ];
    let determinant = vec![curve("|det J_parallel| / its maximum", |p| {
        Some(p.parallel_determinant_abs_scaled)
    })];
    let mut markers: Vec<Marker> = result
        .parallel_singular_parameters
        .iter()
        .map(|&tau| Marker {
            tau,
            label: "parallel singularity".into(),
            dash: "5 3",
        })
        .collect();
    for (leg, taus) in result.leg_singular_parameters.iter().enumerate() {
        markers.extend(taus.iter().map(|&tau| Marker {
            tau,
            label: format!("leg {} singularity", leg + 1),
            dash: ["1 3", "8 3 2 3", "12 3"][leg % 3],
        }));
    }
    let chart = Chart {
        title: "3-RRR signed distances to parallel and leg singularities along the motion".into(),
        x_title: super::plot::TAU_AXIS.into(),
        tau_range: (t0, t1),
        panels: vec![
            Panel {
                title: "signed distance D, all-deformable metric".into(),
                y_title: "D (design length unit)".into(),
                series: super::plot::series_of(distances),
                y_range: None,
            },
            Panel {
                title: "parallel-singularity determinant (dimensionless)".into(),
                y_title: "|det J| / max (1)".into(),
                series: super::plot::series_of(determinant),
                y_range: Some((0.0, 1.05)),
            },
        ],
        markers,
    };
    super::plot::write_chart(path, &chart)
}

fn run_ab_initio(args: RrrAbInitioArgs) -> Result<Outcome> {
    let kinds: Vec<RrrSubProblem> = if args.problem.is_empty() {
        RrrSubProblem::ALL.to_vec()
    } else {
        args.problem
            .iter()
            .map(|s| s.parse().context("--problem"))
            .collect::<Result<_>>()?
    };
    let mut options = RrrAbInitioOptions {
        seed: args.seed,
        ..RrrAbInitioOptions::default()
    };
    options.monodromy.trace_test = !args.no_trace_test;
    options.monodromy.max_stagnant_loops = args.stagnant_loops;
    if let Some(dir) = &args.out_dir {
        check_output_folder("--out-dir", dir, false)?;
    }
    let mut failures = 0;
    for kind in kinds {
        let problem = RrrProblem::new(kind)?;
        if args.verify {
            let Some(file) = problem.embedded() else {
                bail!("{}: no embedded start-solution file", kind.name());
            };
            let mut file = file?;
            if args.retrace {
                let started = std::time::Instant::now();
                file.certificate = trace_certificate(&problem, &file, &options)?;
                print_summary(&file, started);
                if let Some(dir) = &args.out_dir {
                    write_start_file("--out-dir", dir, &problem, &file, false)?;
                }
            }
            failures += usize::from(!verify_stored_file(&problem, &file)?);
            continue;
        }
        let started = std::time::Instant::now();
        let file = compute_rrr_start_solutions(&problem, &options)?;
        print_summary(&file, started);
        if let Some(dir) = &args.out_dir {
            write_start_file("--out-dir", dir, &problem, &file, false)?;
        }
    }
    all_passed(failures)
}

/// One line: count, residual, certificate, time.
fn print_summary(
    file: &singdist::pipeline::start_file::StartSolutions,
    started: std::time::Instant,
) {
    println!(
        "{}: {} solutions, max residual {:.2e}, certificate {} (trace residual {}, {} loops, {} failed paths, passed {}) in {:.1} s",
        file.problem,
        file.solutions.len(),
        file.max_residual,
        file.certificate.kind,
        trace_text(file.certificate.trace_residual),
        file.certificate.loops,
        file.certificate.failed_paths,
        file.certificate.passed,
        started.elapsed().as_secs_f64()
    );
}
