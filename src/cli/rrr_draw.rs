//! `singdist rrr draw`: an SVG drawing of a 3-RRR at one pose with its closest
//! parallel-singular and leg-singular configurations overlaid (computed as
//! `singdist rrr curve` computes them, on the one-pose motion).

use super::args::{DesignArg, ModesArg, PoseArg};
use super::draw::{DrawingOutputArgs, write_drawing};
use super::outcome::Outcome;
use super::output::check_output_file;
use super::resources::with_threads;
use super::rrr::trajectory_of;
use anyhow::{Context, Result, bail};
use clap::Args;
use singdist::io::rrr_draw::{RRR_SUBPROBLEMS, RrrScene};
use singdist::io::scene::{MechanismScene, scene_extent};
use singdist::mechanism::rpr::{Motion, PoseList};
use singdist::pipeline::rrr::curve::{
    RrrCurveOptions, compute_rrr_curve_at, default_rrr_start_solutions,
};

/// Arguments of `singdist rrr draw`.
#[derive(Args, Debug)]
pub struct RrrDrawArgs {
    #[command(flatten)]
    design: DesignArg,
    #[command(flatten)]
    pose: PoseArg,
    #[command(flatten)]
    modes: ModesArg,
    #[command(flatten)]
    output: DrawingOutputArgs,
}

/// Runs `singdist rrr draw`.
pub fn run(args: RrrDrawArgs) -> Result<Outcome> {
    let output = &args.output;
    check_output_file("--out", &output.out, &["svg"])?;
    let pose = args.pose.parse()?;
    let motion = Motion::Poses(PoseList { poses: vec![pose] });
    let trajectory = trajectory_of(args.design.path(), args.modes.text(), motion, "--pose")?;
    let configuration = trajectory.configuration(0.0).context("--pose")?;
    let options = RrrCurveOptions {
        seed: output.run.seed,
        ..RrrCurveOptions::default()
    };
    let result = with_threads(output.run.threads, || {
        compute_rrr_curve_at(&trajectory, &[0.0], &options, &default_rrr_start_solutions)
    })??;
    let Some(at) = result.poses.first() else {
        bail!("no result for the pose");
    };
    for (name, title) in RRR_SUBPROBLEMS {
        if at.subproblems.get(name).and_then(|s| s.closest).is_none() {
            eprintln!("singdist: warning: {title}: no real critical point found, not drawn");
        }
    }
    let scene = RrrScene::of_pose(&configuration, at, "design length unit");
    let svg = scene.svg(&scene_extent(&scene));
    write_drawing(&output.out, svg, &result.failures)
}
