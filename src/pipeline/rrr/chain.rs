//! Stage 2 of the 3-RRR curve along chains of poses, as for the 3-RPR
//! ([`crate::pipeline::curve::CurveOptions::chain_length`]): the poses are cut into blocks of
//! [`RrrCurveOptions::chain_length`] consecutive poses (at fixed pose indices, so
//! that neither the thread count nor the window a caller asks for changes a result).
//! Each block is split into chains by the sweep engine's scheduler
//! (`chains_over`, shared with the 3-RPR): in the order of τ for an
//! analytic motion, in nearest-neighbour order for a pose list (60 scattered poses of
//! the example's circle: 0.99 s in the given order, 0.46 s ordered, the same distances
//! to 10⁻¹⁴), cut where the next pose is more than [`crate::pipeline::sweep::FAR_POSE_STEP`]
//! away in the run's normalised frame. In each chain one pose, the *anchor*, is solved
//! from the seed (the pose nearest `Re τ*`, the shortest seed route; the chain's first
//! pose for pose lists), and the others forwards and backwards from it, each
//! sub-problem from its predecessors' solutions by the sweep engine's chain walk
//! (`walk_chain`, the rule the 3-RPR's chains follow too):
//!
//! - with [`RrrCurveOptions::jump`], first by the sweep engine's Newton jump
//!   (`jump_set`): each critical point of the latest three complete sets extrapolated
//!   to the pose and corrected there by Newton's method, one per complex conjugate
//!   pair, Newton sub-steps along the straight segment and paths for what that
//!   leaves; kept only when the set is complete;
//! - otherwise the predecessor's distinct finite critical points are tracked along two
//!   segments through a random complex midpoint `(p + q)/2 + ε·ξ` of the two
//!   configurations (`ε` half their largest coordinate difference, `ξ` standard complex
//!   normal): between two real configurations the straight segment may meet a real
//!   branch point, where two real critical points merge into a complex pair;
//! - such a pose-to-pose homotopy starts from a *complete* set only (as many distinct
//!   finite critical points as the seed has, every path accounted for) and its result
//!   is kept only when it is complete again, so a chain can never pass on a loss;
//!   otherwise the pose is solved from the seed (with its re-runs and detours), and
//!   of the two the result accounting for more paths is kept.
//!
//! Parameter homotopy from any complete solution set at a parameter point reaches
//! every isolated solution at a generic target (Morgan and Sommese,
//! *Coefficient-parameter polynomial continuation*, Appl. Math. Comput. 29, 1989); the
//! seed route remains the reference where that fails.

use super::curve::{
    Entry, RrrCurveOptions, path_stream, subproblem_entry, target_parameters, track_from_seed,
};
use super::motion_route::MotionRoute;
use super::seed::{RrrFrame, RrrSeededProblem};
use crate::C64;
use crate::homotopy::{PathParameterHomotopy, PolylinePath};
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrTrajectory};
use crate::pipeline::sweep::{
    ChainRoutes, JUMP_HISTORY, JumpRoutes, Retried, TrackingPlan, chain_anchor, jump_set,
    rescue_lost_runs, track_with_retries, walk_chain,
};
use crate::problem::rrr::RrrProblem;
use crate::random;

/// One pose of a block: its index along the motion, τ and its configuration.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ChainPose {
    /// Index of the pose along the motion.
    pub index: usize,
    /// Motion parameter.
    pub tau: f64,
    /// The configuration `K` (18 coordinates).
    pub k: [f64; CONFIGURATION_LEN],
}

/// The blocks of consecutive pose indices (`chain_length` each, at multiples of it)
/// that meet `range`, each whole (a caller keeps the poses in `range`).
pub(crate) fn chain_blocks(
    range: &std::ops::Range<usize>,
    chain_length: usize,
    poses: usize,
) -> Vec<std::ops::Range<usize>> {
    let length = chain_length.max(1);
    if range.is_empty() {
        return Vec::new();
    }
    let first = range.start / length;
    let last = (range.end - 1) / length;
    (first..=last)
        .map(|b| b * length..((b + 1) * length).min(poses))
        .collect()
}

/// The anchor of `block` ([`crate::pipeline::sweep::chain_anchor`]): the pose nearest `Re τ*`
/// (analytic motions), else the first.
pub(crate) fn block_anchor(block: &[ChainPose], tau_star: Option<C64>) -> usize {
    chain_anchor(block.iter().map(|p| p.tau), tau_star.map(|t| t.re))
}

/// A complete solution set at a parameter point, from which the next pose of a chain
/// starts.
#[derive(Clone)]
struct CompleteSet {
    parameters: Vec<C64>,
    solutions: Vec<Vec<C64>>,
}

/// One sub-problem along a block of the 3-RRR curve, as the sweep engine's chain walk
/// ([`walk_chain`]) sees it: Newton jumps from the latest complete sets (with
/// [`RrrCurveOptions::jump`]), pose-to-pose paths from the latest one, the seed route.
struct ProblemChain<'a> {
    trajectory: &'a RrrTrajectory,
    seeded: &'a RrrSeededProblem,
    frame: &'a RrrFrame,
    block: &'a [ChainPose],
    problem_index: usize,
    options: &'a RrrCurveOptions,
}

impl ProblemChain<'_> {
    /// The parameters of pose `j` of the block and its random stream.
    fn target(&self, j: usize) -> (Vec<C64>, u64) {
        let pose = &self.block[j];
        (
            target_parameters(self.frame, &pose.k),
            path_stream(pose.index, self.problem_index),
        )
    }
}

impl<'a> ProblemChain<'a> {
    /// The seed → pose route along the motion to pose `j` (parameters `target`), where
    /// the options ask for it and it exists ([`MotionRoute::new`]).
    fn motion_route(&self, j: usize, target: &[C64]) -> Option<MotionRoute<'a>> {
        if !self.options.motion_route {
            return None;
        }
        let source = (self.seeded.tau_star?, &self.seeded.at_seed.parameters[..]);
        MotionRoute::new(
            self.trajectory,
            *self.frame,
            source,
            (self.block[j].tau, target),
        )
    }
}

impl ChainRoutes for ProblemChain<'_> {
    type Set = CompleteSet;
    type Outcome = (Retried, Vec<C64>);

    fn seed_route(&self, j: usize) -> Self::Outcome {
        let (target, stream) = self.target(j);
        let along = self.motion_route(j, &target);
        let retried = track_from_seed(self.seeded, &target, stream, self.options, along.as_ref());
        (retried, target)
    }

    fn neighbour_route(&self, j: usize, _previous: usize, set: &CompleteSet) -> Self::Outcome {
        let (target, stream) = self.target(j);
        let retried = track_from_neighbour(self.seeded, set, &target, stream, self.options);
        (retried, target)
    }

    fn jump(&self, j: usize, _previous: usize, history: &[CompleteSet]) -> Option<Self::Outcome> {
        if !self.options.jump {
            return None;
        }
        let (target, stream) = self.target(j);
        let retried = jump_to(self.seeded, history, &target, stream, self.options)?;
        Some((retried, target))
    }

    fn complete_set(&self, outcome: &Self::Outcome) -> Option<CompleteSet> {
        let (retried, target) = outcome;
        self.is_complete(outcome).then(|| CompleteSet {
            parameters: target.clone(),
            solutions: retried.endpoints.clone(),
        })
    }

    fn is_complete(&self, (retried, _): &Self::Outcome) -> bool {
        let count = self.seeded.at_seed.start_count;
        retried.accounted == count && retried.endpoints.len() == count
    }

    fn accounted(&self, (retried, _): &Self::Outcome) -> usize {
        retried.accounted
    }

    fn tracked<'o>(&self, (retried, _): &'o mut Self::Outcome) -> &'o mut usize {
        &mut retried.tracked
    }

    fn lost(&self, (retried, _): &Self::Outcome) -> bool {
        retried.accounted < self.seeded.at_seed.start_count
    }
}

/// One sub-problem at every pose of `block` (module documentation), in block order.
pub(crate) fn solve_chain(
    trajectory: &RrrTrajectory,
    seeded: &RrrSeededProblem,
    frame: &RrrFrame,
    block: &[ChainPose],
    anchor: usize,
    problem_index: usize,
    options: &RrrCurveOptions,
) -> Vec<Entry> {
    let routes = ProblemChain {
        trajectory,
        seeded,
        frame,
        block,
        problem_index,
        options,
    };
    let forwards: Vec<usize> = (anchor + 1..block.len()).collect();
    let backwards: Vec<usize> = (0..anchor).rev().collect();
    let mut outcomes: Vec<Option<(Retried, Vec<C64>)>> = (0..block.len()).map(|_| None).collect();
    let keep = if options.jump { JUMP_HISTORY } else { 1 };
    for (j, outcome) in walk_chain(&routes, anchor, [&forwards, &backwards], keep) {
        outcomes[j] = Some(outcome);
    }
    let mut outcomes: Vec<(Retried, Vec<C64>)> = outcomes.into_iter().flatten().collect();
    rescue_lost_runs(&routes, &mut outcomes);
    let mut entries: Vec<Option<Entry>> = vec![None; block.len()];
    for (j, (retried, _)) in outcomes.into_iter().enumerate() {
        let pose = &block[j];
        entries[j] = Some(subproblem_entry(
            seeded,
            frame,
            &pose.k,
            (pose.index, pose.tau),
            &retried,
            options,
        ));
    }
    entries.into_iter().flatten().collect()
}

/// Random stream offset of the pose-to-pose routes (the seed routes use the offsets
/// `0 ..= retry_attempts`).
const NEIGHBOUR_SALT: u64 = 8;

/// The pose-to-pose route from the parameters `from` to `target`: two segments through
/// the random complex midpoint `(p + q)/2 + ε·ξ` (module documentation) of stream
/// `stream`.
fn neighbour_path(from: &[C64], target: &[C64], stream: u64, seed: u64) -> PolylinePath {
    let mut rng = random::stream(seed, stream.wrapping_mul(16).wrapping_add(NEIGHBOUR_SALT));
    let spread = from
        .iter()
        .zip(target)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
    // Coincident poses still get a (tiny) loop, so that the route is a proper path.
    let epsilon = (0.5 * spread).max(1e-6);
    let midpoint: Vec<C64> = from
        .iter()
        .zip(target)
        .map(|(a, b)| (a + b) * 0.5 + random::complex_normal(&mut rng) * epsilon)
        .collect();
    PolylinePath::new(vec![from.to_vec(), midpoint, target.to_vec()])
}

/// The sweep engine's Newton jump ([`jump_set`]) to `target` from the complete sets
/// `history` (latest first, consecutive poses of the chain): Newton's method at the
/// pose from extrapolated critical points, Newton sub-steps along the straight segment
/// from the latest pose and the pose-to-pose route for what it leaves. `None` when the
/// set it finds is not complete.
fn jump_to(
    seeded: &RrrSeededProblem,
    history: &[CompleteSet],
    target: &[C64],
    stream: u64,
    options: &RrrCurveOptions,
) -> Option<Retried> {
    let from = &history.first()?.parameters;
    let evaluator = seeded.problem.evaluator();
    let neighbour = PathParameterHomotopy::new(
        evaluator,
        neighbour_path(from, target, stream, options.seed),
    );
    let straight = PolylinePath::new(vec![from.clone(), target.to_vec()]);
    let straight = PathParameterHomotopy::new(evaluator, straight);
    let routes = JumpRoutes {
        neighbour: &neighbour,
        straight: &straight,
        tracker: &options.neighbour_tracker,
        conjugate: &RrrProblem::conjugate,
    };
    let sets: Vec<&[Vec<C64>]> = history.iter().map(|set| set.solutions.as_slice()).collect();
    let count = seeded.at_seed.start_count;
    let (endpoints, tracked) = jump_set(routes, &sets, count)?;
    Some(Retried {
        endpoints,
        accounted: count,
        tracked,
        reasons: Default::default(),
        confirmed_by_twin: false,
        at_infinity_in_twin: 0,
        handed_over: false,
    })
}

/// `set`'s solutions tracked to `target` along two segments through a random complex
/// midpoint (module documentation), without detours: where this route does not
/// complete the pose, the seed route does.
fn track_from_neighbour(
    seeded: &RrrSeededProblem,
    set: &CompleteSet,
    target: &[C64],
    stream: u64,
    options: &RrrCurveOptions,
) -> Retried {
    let path = neighbour_path(&set.parameters, target, stream, options.seed);
    let plan = TrackingPlan {
        // Between two generic real poses every critical point is finite and
        // nonsingular: no endgame; paths that fail, cross or diverge are re-run with it.
        endgame: false,
        ..TrackingPlan::with_endgame(&options.neighbour_tracker, &options.retry_tracker)
            .with_conjugate(Some(&RrrProblem::conjugate))
    };
    track_with_retries(
        seeded.problem.evaluator(),
        &set.solutions,
        |_| path.clone(),
        0,
        plan,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stage whose seed has fewer solutions than the reconciled count (another
    /// stage's seed reached more) completes its poses by the generic route; its seed
    /// route alone cannot.
    #[test]
    fn a_short_seed_set_completes_its_poses_by_the_generic_route() {
        use crate::mechanism::rrr::example_trajectory;
        use crate::pipeline::rrr::curve::{configuration_at, default_rrr_start_solutions};
        use crate::pipeline::rrr::seed::rrr_seed_stage;
        let trajectory = example_trajectory();
        let options = RrrCurveOptions::default();
        let provider = &default_rrr_start_solutions;
        let mut stage = rrr_seed_stage(&trajectory, &options, provider).unwrap();
        let (_, k) = configuration_at(&trajectory, 3, 1.1).unwrap();
        let target = target_parameters(&stage.frame, &k.to_array());
        let seeded = &mut stage.problems[0];
        let full = seeded.at_seed.start_count;
        assert_eq!(seeded.at_seed.solutions.len(), full);
        // As if this stage's seed had missed one critical point the other stage found.
        seeded.at_seed.solutions.remove(full / 2);
        let seeded = &stage.problems[0];
        let retried = track_from_seed(seeded, &target, path_stream(3, 0), &options, None);
        assert_eq!(retried.accounted, full);
        assert_eq!(retried.endpoints.len(), full);
        // The seed route alone (the count not raised) reaches one fewer.
        stage.problems[0].at_seed.start_count = full - 1;
        let seeded = &stage.problems[0];
        let retried = track_from_seed(seeded, &target, path_stream(3, 0), &options, None);
        assert_eq!(retried.endpoints.len(), full - 1);
    }

    #[test]
    fn blocks_sit_at_multiples_of_the_chain_length() {
        assert_eq!(chain_blocks(&(0..10), 4, 10), vec![0..4, 4..8, 8..10]);
        // A window starting inside a block gets the whole block.
        assert_eq!(chain_blocks(&(5..7), 4, 10), vec![4..8]);
        assert_eq!(chain_blocks(&(3..9), 4, 10), vec![0..4, 4..8, 8..10]);
        assert_eq!(chain_blocks(&(0..3), 1, 3), vec![0..1, 1..2, 2..3]);
        assert!(chain_blocks(&(2..2), 4, 10).is_empty());
    }

    #[test]
    fn the_anchor_is_the_pose_nearest_the_seed() {
        let pose = |tau| ChainPose {
            index: 0,
            tau,
            k: [0.0; CONFIGURATION_LEN],
        };
        let block = [pose(0.0), pose(0.1), pose(0.2), pose(0.3)];
        assert_eq!(block_anchor(&block, Some(C64::new(0.21, 0.5))), 2);
        assert_eq!(block_anchor(&block, Some(C64::new(-4.0, 0.5))), 0);
        assert_eq!(block_anchor(&block, None), 0);
    }
}
