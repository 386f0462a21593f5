//! The 3-RRR curve as an instance of the sweep engine ([`RrrCurveFamily`], a
//! [`SweptFamily`]; the run is a [`Sweep`] of it): a first pass over every pose (its
//! configuration exists; the largest |parallel determinant|, which scales
//! [`RrrPoseResult::parallel_determinant_abs_scaled`] over the whole motion), the seed
//! stage once, then any range of poses on demand. Every (pose, sub-problem) is a pure
//! function of its index, so a window's results are those of the whole curve at its
//! poses, and a caller can write a window and drop it: memory is bounded by one
//! window, not by the number of poses.

use super::ab_initio::RrrAbInitioError;
use super::chain::{ChainPose, block_anchor, chain_blocks, solve_chain};
use super::curve::{
    Entry, RrrCurveError, RrrCurveOptions, RrrCurveResult, RrrPathFailure, RrrPoseResult,
    configuration_at, parallel_singular_parameters, signed,
};
use super::seed::{RrrSeedStage, reconcile_seed_counts, rrr_seed_stage};
use super::self_check::{check_options, check_window};
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrTrajectory, parallel_polynomial};
use crate::pipeline::start_file::StartSolutions;
use crate::pipeline::sweep::chains_over;
use crate::pipeline::sweep::{
    PoseRange, SelfCheck, Sweep, SweepWindow, SweptFamily, merge_windows,
};
use crate::problem::rrr::RrrProblem;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The start-solution provider of a 3-RRR run.
pub type RrrStartProvider<'p> =
    &'p (dyn Fn(&RrrProblem) -> Result<StartSolutions, RrrAbInitioError> + Sync);

/// One window's final results.
pub type RrrWindow = SweepWindow<RrrPoseResult>;

/// A 3-RRR curve as the sweep engine sees it ([`SweptFamily`]): the trajectory, its τ
/// samples, the options, the start-solution provider and the largest |parallel
/// determinant| over the poses.
pub struct RrrCurveFamily<'a> {
    trajectory: &'a RrrTrajectory,
    taus: &'a [f64],
    options: &'a RrrCurveOptions,
    provider: RrrStartProvider<'a>,
    max_parallel: f64,
}

/// A 3-RRR curve being computed window by window (see the module documentation).
pub type RrrCurveRun<'a> = Sweep<RrrCurveFamily<'a>>;

impl<'a> Sweep<RrrCurveFamily<'a>> {
    /// Checks every pose (in order; the first without a configuration is the error),
    /// takes the largest |parallel determinant| over them, and runs the seed stage (and
    /// the self-check's; without the self-check, its seed stage still runs where a
    /// count is below the generic one, to reconcile the counts).
    pub fn new(
        trajectory: &'a RrrTrajectory,
        taus: &'a [f64],
        options: &'a RrrCurveOptions,
        provider: RrrStartProvider<'a>,
    ) -> Result<Self, RrrCurveError> {
        if taus.is_empty() {
            return Err(RrrCurveError::NoPoses(0));
        }
        let mut max_parallel = 0.0f64;
        for (index, &tau) in taus.iter().enumerate() {
            let (_, k) = configuration_at(trajectory, index, tau)?;
            max_parallel = max_parallel.max(parallel_polynomial(&k.to_array()).abs());
        }
        let family = RrrCurveFamily {
            trajectory,
            taus,
            options,
            provider,
            max_parallel,
        };
        Sweep::start(family, taus.len(), options.self_check)
    }

    /// Paths lost at the seed stage (they affect every pose).
    pub fn seed_failures(&self) -> &[RrrPathFailure] {
        &self.stage().failures
    }

    /// Paths tracked by the seed stage.
    pub fn seed_paths_tracked(&self) -> usize {
        self.stage().paths_tracked
    }

    /// The whole curve from its windows in order (every pose of the run).
    pub fn collect(&self, windows: Vec<RrrWindow>) -> RrrCurveResult {
        let (stage, family) = (self.stage(), self.family());
        let mut failures = stage.failures.clone();
        for window in &windows {
            failures.extend(window.poses.iter().flat_map(|r| r.failures.iter().cloned()));
        }
        let (poses, self_check, paths_tracked) = merge_windows(windows);
        RrrCurveResult {
            seed: family.options.seed,
            tau_star: stage.tau_star.map(|t| [t.re, t.im]),
            start_counts: stage
                .problems
                .iter()
                .map(|p| (p.problem.kind().short_name(), p.at_seed.start_count))
                .collect(),
            parallel_singular_parameters: parallel_singular_parameters(
                family.trajectory,
                family.taus,
            ),
            leg_singular_parameters: family.trajectory.leg_crossings().clone(),
            self_check,
            poses,
            failures,
            paths_tracked: stage.paths_tracked + paths_tracked,
        }
    }
}

impl SweptFamily for RrrCurveFamily<'_> {
    type Stage = RrrSeedStage;
    type Check = (RrrSeedStage, RrrCurveOptions);
    type Pose = RrrPoseResult;
    type Error = RrrCurveError;

    fn seed_stage(&self) -> Result<RrrSeedStage, RrrCurveError> {
        rrr_seed_stage(self.trajectory, self.options, self.provider)
    }

    /// The check's stage over every sub-problem, also when only some are short.
    fn check_stage(
        &self,
        stage: &RrrSeedStage,
        all: bool,
    ) -> Result<Option<(RrrSeedStage, RrrCurveOptions)>, RrrCurveError> {
        let short = stage
            .problems
            .iter()
            .any(|p| p.at_seed.start_count < p.at_seed.generic_count);
        if !(all || short) {
            return Ok(None);
        }
        let check_options = check_options(self.options);
        let check_stage = rrr_seed_stage(self.trajectory, &check_options, self.provider)?;
        Ok(Some((check_stage, check_options)))
    }

    fn reconcile(&self, stage: &mut RrrSeedStage, (check, _): &mut Self::Check) {
        reconcile_seed_counts(stage, check);
    }

    /// The chains of the range's blocks ([`super::chain`]) for every sub-problem in
    /// parallel, assembled pose by pose.
    fn solve_poses(
        &self,
        stage: &RrrSeedStage,
        PoseRange { range, on_pose }: PoseRange<'_, RrrPoseResult>,
    ) -> Result<Vec<RrrPoseResult>, RrrCurveError> {
        let options = self.options;
        let blocks = chain_blocks(&range, options.chain_length, self.taus.len());
        let mut chains = Vec::with_capacity(blocks.len());
        for block in &blocks {
            let poses = block
                .clone()
                .map(|index| self.chain_pose(index))
                .collect::<Result<Vec<_>, _>>()?;
            // The block's chains ([`chains_over`]): an analytic motion in the order of
            // τ, a pose list in nearest-neighbour order, cut where the next pose is far
            // in the run's normalised frame.
            let normalised: Vec<[f64; CONFIGURATION_LEN]> = poses
                .iter()
                .map(|(_, at)| stage.frame.apply(&at.k))
                .collect();
            let step = |a: usize, b: usize| {
                normalised[a]
                    .iter()
                    .zip(&normalised[b])
                    .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()))
            };
            let ordered_motion = stage.tau_star.is_some();
            for chain in chains_over(0..poses.len(), &step, ordered_motion, poses.len()) {
                let (pose_values, chain_poses): (Vec<[f64; 3]>, Vec<ChainPose>) =
                    chain.iter().map(|&i| poses[i]).unzip();
                let anchor = block_anchor(&chain_poses, stage.tau_star);
                chains.push((pose_values, chain_poses, anchor));
            }
        }
        let jobs: Vec<(usize, usize)> = (0..chains.len())
            .flat_map(|c| (0..stage.problems.len()).map(move |p| (c, p)))
            .collect();
        let solved: Vec<Vec<Entry>> = jobs
            .par_iter()
            .map(|&(c, p)| {
                let (_, poses, anchor) = &chains[c];
                let seeded = &stage.problems[p];
                solve_chain(
                    self.trajectory,
                    seeded,
                    &stage.frame,
                    poses,
                    *anchor,
                    p,
                    options,
                )
            })
            .collect();
        let mut solved = solved.into_iter();
        let mut results = Vec::with_capacity(range.len());
        for (pose_values, poses, _) in &chains {
            let per_problem: Vec<Vec<Entry>> = solved.by_ref().take(stage.problems.len()).collect();
            for (j, (pose, at)) in pose_values.iter().zip(poses).enumerate() {
                if !range.contains(&at.index) {
                    continue;
                }
                let mut subproblems = BTreeMap::new();
                let mut failures = Vec::new();
                let mut paths_tracked = 0;
                for (seeded, entries) in stage.problems.iter().zip(&per_problem) {
                    let Some(entry) = entries.get(j).cloned() else {
                        continue;
                    };
                    failures.extend(entry.failure);
                    paths_tracked += entry.tracked;
                    subproblems.insert(seeded.problem.kind().short_name(), entry.result);
                }
                let result = self.assemble(
                    at.index,
                    (at.tau, *pose, &at.k),
                    subproblems,
                    failures,
                    paths_tracked,
                );
                on_pose(&result);
                results.push(result);
            }
        }
        // Chains of a pose list run in nearest-neighbour order: back to pose order.
        results.sort_by_key(|r| r.index);
        Ok(results)
    }

    /// The 3-RRR window check, then the poses whose sub-problems changed assembled
    /// again.
    fn check_poses(
        &self,
        stage: &RrrSeedStage,
        check: &Self::Check,
        results: &mut [RrrPoseResult],
    ) -> Result<SelfCheck, RrrCurveError> {
        let window_poses = results
            .iter()
            .map(|r| self.chain_pose(r.index))
            .collect::<Result<Vec<_>, _>>()?;
        let poses: Vec<ChainPose> = window_poses.iter().map(|(_, at)| *at).collect();
        let checked = (self.trajectory, &check.0, &check.1);
        let (summary, changed) = check_window(checked, &poses, results, stage.frame.scale());
        for i in changed {
            let (pose, at) = &window_poses[i];
            let result = &results[i];
            let (subproblems, failures) = (result.subproblems.clone(), result.failures.clone());
            let tracked = result.paths_tracked;
            let at_pose = (at.tau, *pose, &at.k);
            results[i] = self.assemble(at.index, at_pose, subproblems, failures, tracked);
        }
        Ok(summary)
    }

    fn paths_tracked(pose: &RrrPoseResult) -> usize {
        pose.paths_tracked
    }

    fn pose_count(&self) -> usize {
        self.taus.len()
    }
}

impl RrrCurveFamily<'_> {
    /// The pose and the chain's view of pose `index` (its τ and configuration).
    fn chain_pose(&self, index: usize) -> Result<([f64; 3], ChainPose), RrrCurveError> {
        let tau = self.taus[index];
        configuration_at(self.trajectory, index, tau).map(|(pose, k)| {
            let at = ChainPose {
                index,
                tau,
                k: k.to_array(),
            };
            (pose, at)
        })
    }

    fn assemble(
        &self,
        index: usize,
        (tau, pose, k): (f64, [f64; 3], &[f64; CONFIGURATION_LEN]),
        subproblems: BTreeMap<String, super::curve::RrrSubproblemResult>,
        failures: Vec<RrrPathFailure>,
        paths_tracked: usize,
    ) -> RrrPoseResult {
        let get = |name: &str| subproblems.get(name).and_then(signed);
        let (parallel, leg1, leg2, leg3) = (get("parallel"), get("leg1"), get("leg2"), get("leg3"));
        let nearest = [
            ("parallel", parallel),
            ("leg1", leg1),
            ("leg2", leg2),
            ("leg3", leg3),
        ]
        .into_iter()
        .filter_map(|(name, v)| v.map(|v| (name, v.abs())))
        .min_by(|a, b| a.1.total_cmp(&b.1));
        let modes = self.trajectory.modes_at(tau);
        RrrPoseResult {
            index,
            tau,
            pose,
            working_modes: modes.map(|m| m.sign() as i8),
            parallel,
            leg1,
            leg2,
            leg3,
            distance: nearest.map(|(_, d)| d),
            nearest: nearest.map(|(name, _)| name.to_string()),
            parallel_determinant_abs_scaled: if self.max_parallel > 0.0 {
                parallel_polynomial(k).abs() / self.max_parallel
            } else {
                0.0
            },
            subproblems,
            failures,
            paths_tracked,
        }
    }
}
