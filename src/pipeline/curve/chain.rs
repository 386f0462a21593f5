//! Stage 2 along chains of poses: one pose from the seed, the others from their
//! predecessors, and the rescue of poses that lost paths from complete neighbours.

use super::*;
use crate::pipeline::sweep::{
    ChainHistory, ChainRoutes, Rescued, chains_over, lost_runs, rescue_run, solve_in_chain,
};

/// Stages 2–4 at one pose along the reference route: parameter homotopy from the seed
/// along the complexified motion (`MotionPath`) for every sub-problem (in parallel),
/// re-runs of failed paths (detours through a random complex point near the pose),
/// post-processing. ([`compute_curve`] solves most poses from their neighbours instead,
/// see [`CurveOptions::chain_length`].)
pub fn solve_pose(
    stage: &SeedStage,
    design: &Design,
    motion: &Motion,
    metrics: &[Metric],
    index: usize,
    sample: SampledPose,
    options: &CurveOptions,
) -> PoseResult {
    let (entries, k) = track_pose(stage, design, motion, (index, sample), options);
    assemble_pose(stage, metrics, index, sample, &k, entries, options)
}

/// Stages 2–3 of [`solve_pose`]: every sub-problem's entry at the pose, and the
/// pose's configuration.
pub(super) fn track_pose(
    stage: &SeedStage,
    design: &Design,
    motion: &Motion,
    (index, sample): (usize, SampledPose),
    options: &CurveOptions,
) -> (Vec<PoseEntry>, [f64; 12]) {
    track_pose_of(stage, design, motion, (index, sample), options, &|_| true)
}

/// [`track_pose`] for the sub-problems of the metrics `wanted` accepts; the others'
/// entries are empty (no candidate, no path, no failure), so a pose assembled from
/// them with only the wanted metrics is theirs alone.
pub(super) fn track_pose_of(
    stage: &SeedStage,
    design: &Design,
    motion: &Motion,
    (index, sample): (usize, SampledPose),
    options: &CurveOptions,
    wanted: &(dyn Fn(Metric) -> bool + Sync),
) -> (Vec<PoseEntry>, [f64; 12]) {
    let context = SolveContext {
        stage,
        motion,
        options,
    };
    let entries = (0..stage.problems.len())
        .into_par_iter()
        .map(|problem_index| {
            if !wanted(stage.problems[problem_index].id.metric) {
                return PoseEntry::default();
            }
            let at = (index, sample);
            track_problem(context, at, problem_index, Route::Seed).entry
        })
        .collect();
    (entries, design.configuration(sample.pose).to_array())
}

/// The chains of stage 2 over the poses `first..last` (a window), each as its pose
/// indices in chain order: at most `chain_length` poses each
/// ([`CurveOptions::chain_length`]), split where consecutive poses of the order are
/// farther apart than [`FAR_POSE_STEP`] (the sweep engine's scheduler,
/// [`chains_over`]). Analytic motions keep the order of τ; an explicit pose list is
/// ordered by nearest neighbours, so that scattered poses form chains too (200 random
/// poses of a generic design, nine metrics, 2 threads: 9.0 s in the given order, 3.9 s
/// ordered). Depends on the poses only, not on the thread count.
pub(super) fn chain_blocks(
    design: &Design,
    (motion, samples): (&Motion, &[SampledPose]),
    (first, last): (usize, usize),
    chain_length: usize,
    normalization: Normalization,
) -> Vec<Vec<usize>> {
    let normalised: Vec<[C64; 12]> = (first..last)
        .map(|j| normalization.apply(&to_real(&design.configuration(samples[j].pose).to_array())))
        .collect();
    let step = |a: usize, b: usize| {
        normalised[a - first]
            .iter()
            .zip(&normalised[b - first])
            .fold(0.0f64, |m, (u, v)| m.max((u - v).norm()))
    };
    let ordered_motion = matches!(motion, Motion::Analytic(_));
    chains_over(first..last, &step, ordered_motion, chain_length)
}

/// Poses a block of [`solve_chain`] runs through per sub-problem before they are
/// assembled (and reported as partial results).
pub(super) const POSES_PER_BLOCK: usize = 10;

/// One sub-problem along a chain of the 3-RPR curve, as the sweep engine's chain walk
/// ([`solve_in_chain`]) sees it: Newton jumps ([`jump_problem`]) where
/// [`CurveOptions::jump`] allows, pose-to-pose paths along the motion from the latest
/// complete set, the seed route.
pub(super) struct ProblemChain<'a> {
    pub context: SolveContext<'a>,
    /// Poses from pose index `offset` on.
    pub samples: &'a [SampledPose],
    pub offset: usize,
    pub problem_index: usize,
}

impl ProblemChain<'_> {
    /// Pose `pose` with its sample.
    fn at(&self, pose: usize) -> (usize, SampledPose) {
        (pose, self.samples[pose - self.offset])
    }

    /// Pose `pose`'s point of the motion.
    fn point(&self, pose: usize) -> MotionPoint {
        MotionPoint::target(self.context.motion, &self.samples[pose - self.offset])
    }
}

impl ChainRoutes for ProblemChain<'_> {
    type Set = Vec<Vec<C64>>;
    type Outcome = ProblemAtPose;

    fn seed_route(&self, pose: usize) -> ProblemAtPose {
        track_problem(self.context, self.at(pose), self.problem_index, Route::Seed)
    }

    fn neighbour_route(&self, pose: usize, previous: usize, set: &Self::Set) -> ProblemAtPose {
        let route = Route::Neighbour {
            from: self.point(previous),
            solutions: set,
        };
        track_problem(self.context, self.at(pose), self.problem_index, route)
    }

    fn jump(&self, pose: usize, previous: usize, history: &[Self::Set]) -> Option<ProblemAtPose> {
        if !self.context.options.jump {
            return None;
        }
        let sets: Vec<&[Vec<C64>]> = history.iter().map(|s| s.as_slice()).collect();
        let from = self.point(previous);
        jump_problem(self.context, self.at(pose), self.problem_index, from, &sets)
    }

    fn complete_set(&self, outcome: &ProblemAtPose) -> Option<Self::Set> {
        outcome.complete.clone()
    }

    fn is_complete(&self, outcome: &ProblemAtPose) -> bool {
        outcome.complete.is_some()
    }

    fn accounted(&self, outcome: &ProblemAtPose) -> usize {
        outcome.entry.accounted
    }

    fn tracked<'o>(&self, outcome: &'o mut ProblemAtPose) -> &'o mut usize {
        &mut outcome.entry.tracked
    }

    fn lost(&self, outcome: &ProblemAtPose) -> bool {
        outcome.entry.failure.is_some()
    }
}

/// The pose of `poses` where a chain starts from the seed: the one nearest `Re τ*`
/// (the shortest seed route: on the built-in example the `rigid/rigid` seed route to
/// the motion's first pose took 13 × as long as to the pose nearest `Re τ*`), or the
/// first pose for explicit pose lists (whose seed is the first pose perturbed).
pub(super) fn chain_anchor(stage: &SeedStage, samples: &[SampledPose], chain: &[usize]) -> usize {
    let seed_tau = match stage.seed.point {
        MotionPoint::Tau(tau) => Some(tau.re),
        MotionPoint::Pose(_) => None,
    };
    let taus = chain.iter().map(|&j| samples[j].tau);
    crate::pipeline::sweep::chain_anchor(taus, seed_tau)
}

/// Stage 2 along one block of consecutive poses (see [`CurveOptions::chain_length`]):
/// the anchor ([`chain_anchor`]) from the seed, then the poses after it (forwards) and
/// before it (backwards), each per sub-problem from the preceding pose's (in chain
/// order) complete finite solution set, or from the seed when that set is incomplete
/// or the pose-to-pose paths do not reach a complete set. Calls `on_pose` per pose;
/// returns the poses in index order.
pub(super) fn solve_chain(
    context: SolveContext<'_>,
    (design, metrics): (&Design, &[Metric]),
    samples: &[SampledPose],
    (window, chain): (std::ops::Range<usize>, &[usize]),
    on_pose: &(dyn Fn(&PoseResult) + Sync),
) -> Vec<(PoseResult, Vec<ProblemAtPose>)> {
    let SolveContext { stage, options, .. } = context;
    let problems = stage.problems.len();
    let at = chain_anchor(stage, samples, chain);
    let anchor = chain[at];
    // The two directions, in chain order after the anchor.
    let directions: [Vec<usize>; 2] = [
        chain[at + 1..].to_vec(),
        chain[..at].iter().rev().copied().collect(),
    ];
    // Per (direction, sub-problem), the complete solution sets of the last poses
    // (latest first) and the latest pose: cleared where a pose went the seed route.
    type History = ChainHistory<Vec<Vec<C64>>>;
    let assemble = |j: usize, mut at_pose: Vec<ProblemAtPose>| {
        let sample = samples[j];
        let k = design.configuration(sample.pose).to_array();
        let entries = at_pose.iter().map(|p| p.entry.clone()).collect();
        let result = assemble_pose(stage, metrics, j, sample, &k, entries, options);
        on_pose(&result);
        // Only poses that lost paths are assembled again (by the rescue pass): the
        // others' candidates are done with.
        if at_pose.iter().all(|p| p.entry.failure.is_none()) {
            for problem in &mut at_pose {
                problem.entry.candidates = Vec::new();
            }
        }
        (result, at_pose)
    };
    // Runs one sub-problem's chain through `block` (poses in chain order).
    let run =
        |history: &mut History, problem_index: usize, block: &[usize]| -> Vec<ProblemAtPose> {
            let routes = ProblemChain {
                context,
                samples,
                offset: 0,
                problem_index,
            };
            block
                .iter()
                .map(|&j| solve_in_chain(&routes, j, history))
                .collect()
        };
    let mut anchor_history: Vec<History> = vec![ChainHistory::new(anchor, JUMP_HISTORY); problems];
    let at_anchor: Vec<ProblemAtPose> = anchor_history
        .par_iter_mut()
        .enumerate()
        .map(|(problem_index, history)| run(history, problem_index, &[anchor]).remove(0))
        .collect();
    let mut out = vec![assemble(anchor, at_anchor)];
    // Where each pose of the window is in `out` (by pose index; poses of other chains
    // stay `None`).
    let mut position: Vec<Option<usize>> = vec![None; window.len()];
    position[anchor - window.start] = Some(0);
    // Both directions continue from the anchor's sets.
    let mut histories: Vec<History> = [anchor_history.clone(), anchor_history].concat();
    // The sub-problems' chains are independent: each runs through a block of poses
    // on its own (no barrier per pose), both directions at once, then the blocks'
    // poses are assembled.
    let blocks: [Vec<&[usize]>; 2] = directions
        .each_ref()
        .map(|d| d.chunks(POSES_PER_BLOCK).collect());
    for step in 0..blocks[0].len().max(blocks[1].len()) {
        let per_task: Vec<Vec<ProblemAtPose>> = histories
            .par_iter_mut()
            .enumerate()
            .map(|(task, history)| {
                let (direction, problem_index) = (task / problems, task % problems);
                match blocks[direction].get(step) {
                    Some(block) => run(history, problem_index, block),
                    None => Vec::new(),
                }
            })
            .collect();
        let mut per_task: Vec<std::vec::IntoIter<ProblemAtPose>> =
            per_task.into_iter().map(|v| v.into_iter()).collect();
        for (direction, tasks) in per_task.chunks_mut(problems).enumerate() {
            let Some(block) = blocks[direction].get(step) else {
                continue;
            };
            for &j in *block {
                let at_pose: Vec<ProblemAtPose> = tasks
                    .iter_mut()
                    .map(|results| results.next().expect("one result per pose"))
                    .collect();
                position[j - window.start] = Some(out.len());
                out.push(assemble(j, at_pose));
            }
        }
        release_unneeded_sets(&mut out, &position);
    }
    out.sort_by_key(|(result, _)| result.index);
    out
}

/// Drops the complete solution sets of a chain's poses (`out`, with `position[i]` the
/// place of the window's `i`-th pose in it, if this chain solved it) that the rescue
/// pass cannot need: it starts only from a pose next to one (in pose order) that lost
/// paths for that sub-problem, so a set whose two neighbours are solved by this chain
/// and lost nothing goes. A pose whose neighbour is in another chain keeps its set.
/// This bounds a chain's memory by its results, not by its critical points.
fn release_unneeded_sets(out: &mut [(PoseResult, Vec<ProblemAtPose>)], position: &[Option<usize>]) {
    let lost = |out: &[(PoseResult, Vec<ProblemAtPose>)], at: usize, p: usize| {
        out[at].1[p].entry.failure.is_some()
    };
    for i in 1..position.len().saturating_sub(1) {
        let (Some(at), Some(before), Some(after)) = (position[i], position[i - 1], position[i + 1])
        else {
            continue;
        };
        for p in 0..out[at].1.len() {
            if out[at].1[p].complete.is_some() && !lost(out, before, p) && !lost(out, after, p) {
                out[at].1[p].complete = None;
            }
        }
    }
}

/// The rescue pass (stage 3b): every run of consecutive poses at which a sub-problem
/// lost paths is re-solved pose by pose from a neighbouring pose whose finite solution
/// set is complete — first forward from the pose before the run, then backward from the
/// pose after it for what is still incomplete. Near a pose the critical points move
/// little, so short pose-to-pose paths (through a complex midpoint) follow critical
/// points that the long seed → pose paths lose, e.g. huge ill-conditioned ones.
/// `samples` and `work` are one window's poses, the first of index `offset`; the
/// runs and neighbours stay within the window. Returns the window-local indices of
/// the poses whose entries changed.
pub(super) fn rescue_from_neighbours(
    context: SolveContext<'_>,
    (offset, samples): (usize, &[SampledPose]),
    work: &mut [Vec<ProblemAtPose>],
) -> Vec<usize> {
    let n = samples.len();
    let chain = |problem_index| ProblemChain {
        context,
        samples,
        offset,
        problem_index,
    };
    // (sub-problem, first pose, last pose) of every run of failing poses.
    let runs: Vec<(usize, (usize, usize))> = (0..context.stage.problems.len())
        .flat_map(|p| {
            let routes = chain(p);
            lost_runs(n, |j| routes.lost(&work[j][p]))
                .into_iter()
                .map(move |run| (p, run))
        })
        .collect();
    let view: &[Vec<ProblemAtPose>] = work;
    let outcomes: Vec<(usize, Rescued<ProblemAtPose>)> = runs
        .par_iter()
        .map(|&(p, run)| (p, rescue_run(&chain(p), &|j| &view[j][p], (offset, n), run)))
        .collect();
    let mut changed = Vec::new();
    for (p, Rescued { improved, tracked }) in outcomes {
        for (j, count) in tracked {
            work[j][p].entry.tracked += count;
            changed.push(j);
        }
        for (j, mut result) in improved {
            // Every path tracked counts: the seed route's and the rescue's.
            result.entry.tracked = work[j][p].entry.tracked;
            work[j][p] = result;
        }
    }
    changed.sort_unstable();
    changed.dedup();
    changed
}
