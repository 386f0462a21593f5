//! `singdist draw`: an SVG drawing of a 3-RPR at one pose with the closest singular
//! configuration K′ of each chosen metric overlaid (computed as `singdist distance`
//! computes it).

use super::args::RunArgs;
use super::distance::PoseMetricArgs;
use super::failures::warn_failures;
use super::outcome::Outcome;
use super::output::{check_output_file, write_file};
use anyhow::Result;
use clap::Args;
use singdist::io::draw::Scene;
use singdist::io::scene::{MechanismScene, scene_extent};
use singdist::pipeline::curve::PathFailure;
use std::path::{Path, PathBuf};

/// Arguments of `singdist draw`.
#[derive(Args, Debug)]
pub struct DrawArgs {
    #[command(flatten)]
    problem: PoseMetricArgs,
    #[command(flatten)]
    output: DrawingOutputArgs,
}

/// The output file, threads and seed of a drawing command.
#[derive(Args, Debug)]
pub struct DrawingOutputArgs {
    /// Output drawing (`.svg`).
    #[arg(long, value_name = "FILE.svg")]
    pub out: PathBuf,
    #[command(flatten)]
    pub run: RunArgs,
}

/// Runs `singdist draw`.
pub fn run(args: DrawArgs) -> Result<Outcome> {
    let output = &args.output;
    check_output_file("--out", &output.out, &["svg"])?;
    let solved = args.problem.solve(&output.run)?;
    let at = solved.at()?;
    let (design, metrics, result) = (&solved.design, &solved.metrics, &solved.result);
    let names: Vec<String> = metrics.iter().map(|m| m.name()).collect();
    for name in names.iter().filter(|n| !at.metrics.contains_key(*n)) {
        eprintln!("singdist: warning: {name}: no real critical point found, not drawn");
    }
    let scene = Scene::of_pose(design, at, &names, "design length unit");
    let svg = scene.svg(&scene_extent(&scene));
    write_drawing(&output.out, svg, &result.failures)
}

/// Writes the drawing `svg` to `--out`; exit code 3 (after a warning listing them) if
/// paths were lost.
pub(super) fn write_drawing(out: &Path, svg: String, failures: &[PathFailure]) -> Result<Outcome> {
    write_file("--out", out, svg)?;
    Ok(Outcome::paths_lost_if(warn_failures(failures)))
}
