//! `singdist distance`: the singularity distances of a 3-RPR at one pose for the
//! selected metrics, in full detail (docs/theory.md §5, §8): per metric the distance,
//! signed distance, attaining sub-problem, closest configuration K′, cut-locus flag and
//! every sub-problem's own minimum.

use super::args::{DesignArg, MetricsArg, PoseArg, RunArgs};
use super::curve::load_inputs;
use super::failures::warn_failures;
use super::outcome::Outcome;
use super::resources::with_threads;
use anyhow::{Context, Result};
use clap::Args;
use singdist::mechanism::rpr::{Design, Motion, Pose, PoseList};
use singdist::metric::Metric;
use singdist::pipeline::curve::{
    CurveOptions, CurveResult, PoseResult, compute_curve_from_embedded_starts,
};

/// The pose problem `distance` solves and `draw` draws: design, pose and metrics.
#[derive(Args, Debug)]
pub struct PoseMetricArgs {
    #[command(flatten)]
    design: DesignArg,
    #[command(flatten)]
    pose: PoseArg,
    #[command(flatten)]
    metrics: MetricsArg,
}

/// Arguments of `singdist distance`.
#[derive(Args, Debug)]
pub struct DistanceArgs {
    #[command(flatten)]
    problem: PoseMetricArgs,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    run: RunArgs,
}

/// A solved pose problem: the design, the metrics and the curve pipeline's result on
/// the one pose (its only entry of `poses`).
pub struct SolvedPose {
    /// The design (the built-in example without `--design`).
    pub design: Design,
    /// The metrics asked for, in order.
    pub metrics: Vec<Metric>,
    /// The result; `poses[0]` is the pose.
    pub result: CurveResult,
}

impl SolvedPose {
    /// The pose's result (an error if the pipeline returned none).
    pub fn at(&self) -> Result<&PoseResult> {
        self.result.poses.first().context("no result for the pose")
    }
}

impl PoseMetricArgs {
    /// Parses the pose, loads the design and metrics, and solves the pose.
    pub fn solve(&self, run: &RunArgs) -> Result<SolvedPose> {
        let pose = self.pose.parse()?;
        let (design, _) = load_inputs(self.design.path(), None)?;
        let metrics = self.metrics.parse()?;
        let result = solve_pose(&design, pose, &metrics, run)?;
        Ok(SolvedPose {
            design,
            metrics,
            result,
        })
    }
}

/// The curve pipeline on the single pose `pose` (what `distance` prints and `draw`
/// draws): one [`PoseResult`](singdist::pipeline::curve::PoseResult) in `poses`.
pub fn solve_pose(
    design: &Design,
    pose: Pose,
    metrics: &[Metric],
    run: &RunArgs,
) -> Result<CurveResult> {
    let motion = Motion::Poses(PoseList { poses: vec![pose] });
    let options = CurveOptions {
        seed: run.seed,
        ..CurveOptions::default()
    };
    with_threads(run.threads, || {
        compute_curve_from_embedded_starts(design, &motion, 1, metrics, &options)
    })?
    .map_err(Into::into)
}

/// The twelve coordinates of a configuration as `a1 (x, y)  a2 (x, y) … b3 (x, y)`.
pub fn labelled_points(k: &[f64; 12]) -> String {
    (0..6)
        .map(|j| {
            let name = if j < 3 {
                format!("a{}", j + 1)
            } else {
                format!("b{}", j - 2)
            };
            format!("{name} ({:.6}, {:.6})", k[2 * j], k[2 * j + 1])
        })
        .collect::<Vec<_>>()
        .join("  ")
}

/// Runs `singdist distance`.
pub fn run(args: DistanceArgs) -> Result<Outcome> {
    let solved = args.problem.solve(&args.run)?;
    let (at, metrics, result) = (solved.at()?, &solved.metrics, &solved.result);
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&serde_json::json!({
                "pose": at.pose,
                "S": at.singularity,
                "metrics": at.metrics,
                "failures": result.failures,
                "not_applicable": result.not_applicable,
            }))?
        );
    } else {
        println!(
            "pose x = {}, y = {}, phi = {}: S = {:.6e}",
            at.pose[0], at.pose[1], at.pose[2], at.singularity
        );
        for metric in metrics {
            let name = metric.name();
            let Some(m) = at.metrics.get(&name) else {
                println!("{name:>12}: no real critical point found");
                continue;
            };
            println!(
                "{name:>12}: distance {:.9} (signed {:.9}) via {}{}",
                m.distance,
                m.signed_distance,
                m.subproblem,
                if m.cut_locus { " [cut locus]" } else { "" }
            );
            println!("{:>14}closest K' = {}", "", labelled_points(&m.closest));
            for (sub, d) in &m.subproblems {
                println!(
                    "{:>14}{sub}: {} ({} real of {} finite / {} expected)",
                    "",
                    d.distance
                        .map(|v| format!("{v:.9}"))
                        .unwrap_or_else(|| "none".into()),
                    d.real_critical_points,
                    d.accounted_paths,
                    d.expected_paths
                );
            }
        }
    }
    Ok(Outcome::paths_lost_if(warn_failures(&result.failures)))
}
