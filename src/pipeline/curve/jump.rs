//! Newton continuation between consecutive poses of a 3-RPR chain: the sweep
//! engine's Newton jump ([`jump_set`]) along the routes of the 3-RPR's motion.

use super::*;
use crate::pipeline::sweep::{JumpRoutes, jump_set};

/// Solves one sub-problem at pose `index` from the complete solution sets of the
/// preceding poses (`history`, latest first, each in the same order) by the sweep
/// engine's Newton jump ([`jump_set`]): Newton's method at the pose from extrapolated
/// critical points, the pose-to-pose route (through a random complex midpoint along
/// the motion) and Newton sub-steps along the straight real route for what it leaves;
/// `None` when the set is still incomplete.
pub(super) fn jump_problem(
    context: SolveContext<'_>,
    (index, sample): (usize, SampledPose),
    problem_index: usize,
    from: MotionPoint,
    history: &[&[Vec<C64>]],
) -> Option<ProblemAtPose> {
    let (seeded, k, target, parameters) = context.problem_at(problem_index, &sample);
    let SolveContext {
        stage,
        motion,
        options,
    } = context;
    let design = &seeded.design;
    let stream = ((index as u64 + 1) << 32) | problem_index as u64;
    let rng = random::stream(options.seed, stream.wrapping_mul(16) + 8);
    let path = route_path(
        (stage, seeded),
        (design, motion),
        (from, target),
        RouteLeg::BetweenNeighbours,
        rng,
        parameters[12..].to_vec(),
    );
    let homotopy = PathParameterHomotopy::new(seeded.problem.evaluator(), path);
    let straight = PathParameterHomotopy::new(
        seeded.problem.evaluator(),
        MotionPath::new(
            design,
            motion,
            vec![from, target],
            [C64::new(0.0, 0.0); 12],
            stage.normalization,
            parameters[12..].to_vec(),
        ),
    );
    let conjugate = |x: &[C64]| seeded.problem.conjugate(x);
    let routes = JumpRoutes {
        neighbour: &homotopy,
        straight: &straight,
        tracker: &options.neighbour_tracker,
        conjugate: &conjugate,
    };
    let (endpoints, tracked) = jump_set(routes, history, seeded.at_seed.start_count)?;
    let at = (&parameters[..], &k);
    let count = (seeded.at_seed.start_count, None, tracked);
    Some(problem_at_pose(
        stage, seeded, endpoints, at, count, options,
    ))
}
