//! `singdist draw`: an SVG drawing of a 3-RPR at one pose with the closest singular
//! configuration K′ of each chosen metric overlaid (computed as `singdist distance`
//! computes it).

use super::curve::{load_inputs, parse_metrics};
use super::distance::{parse_pose, solve_pose};
use super::failures::warn_failures;
use super::outcome::Outcome;
use super::output::{check_output_file, write_file};
use anyhow::{Result, bail};
use clap::Args;
use singdist::io::draw::{Scene, scene_extent, scene_svg};
use std::path::PathBuf;

/// Arguments of `singdist draw`.
#[derive(Args, Debug)]
pub struct DrawArgs {
    /// Design file; default: the built-in example. Lengths are drawn in its unit.
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
    /// The pose `x,y,phi`: platform position (design length unit) and orientation φ
    /// (radians).
    #[arg(long, value_name = "X,Y,PHI", allow_hyphen_values = true)]
    pose: String,
    /// Metrics whose closest singular configuration K′ is drawn: `all`, or names
    /// `PLATFORM/BASE` with each part `plate`, `bars` or `rigid` (or comma separated).
    #[arg(long, value_name = "NAME", num_args = 1.., default_value = "all")]
    metric: Vec<String>,
    /// Output drawing (`.svg`).
    #[arg(long, value_name = "FILE.svg")]
    out: PathBuf,
    /// Worker threads (default: all cores; more than the cores is clamped to them).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Seed of every random choice.
    #[arg(long, value_name = "S", default_value_t = 1)]
    seed: u64,
}

/// Runs `singdist draw`.
pub fn run(args: DrawArgs) -> Result<Outcome> {
    check_output_file("--out", &args.out, &["svg"])?;
    let pose = parse_pose(&args.pose)?;
    let (design, _) = load_inputs(args.design.as_deref(), None)?;
    let metrics = parse_metrics(&args.metric)?;
    let result = solve_pose(&design, pose, &metrics, args.seed, args.threads)?;
    let Some(at) = result.poses.first() else {
        bail!("no result for the pose");
    };
    let names: Vec<String> = metrics.iter().map(|m| m.name()).collect();
    for name in names.iter().filter(|n| !at.metrics.contains_key(*n)) {
        eprintln!("singdist: warning: {name}: no real critical point found, not drawn");
    }
    let scene = Scene::of_pose(&design, at, &names, "design length unit");
    write_file("--out", &args.out, scene_svg(&scene, &scene_extent(&scene)))?;
    Ok(Outcome::paths_lost_if(warn_failures(&result.failures)))
}
