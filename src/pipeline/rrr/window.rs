//! A 3-RRR curve solved window by window: the seed stage and a first pass over every
//! pose (its configuration exists; the largest |parallel determinant|, which scales
//! [`RrrPoseResult::parallel_determinant_abs_scaled`] over the whole motion) once, then
//! any range of poses on demand. Every (pose, sub-problem) is a pure function of its
//! index, so a window's results are those of the whole curve at its poses, and a caller
//! can write a window and drop it: memory is bounded by one window, not by the number
//! of poses.

use super::ab_initio::RrrAbInitioError;
use super::chain::{ChainPose, block_anchor, chain_blocks, solve_chain};
use super::curve::{
    Entry, RrrCurveError, RrrCurveOptions, RrrCurveResult, RrrPathFailure, RrrPoseResult,
    configuration_at, parallel_singular_parameters, signed,
};
use super::seed::{RrrSeedStage, reconcile_seed_counts, rrr_seed_stage};
use super::self_check::{check_options, check_window};
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrTrajectory, parallel_polynomial};
use crate::pipeline::curve::SelfCheck;
use crate::pipeline::start_file::StartSolutions;
use crate::pipeline::sweep::chains_over;
use crate::problem::rrr::RrrProblem;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The start-solution provider of a 3-RRR run.
pub type RrrStartProvider<'p> =
    &'p (dyn Fn(&RrrProblem) -> Result<StartSolutions, RrrAbInitioError> + Sync);

/// A 3-RRR curve being computed window by window (see the module documentation).
pub struct RrrCurveRun<'a> {
    trajectory: &'a RrrTrajectory,
    taus: &'a [f64],
    options: &'a RrrCurveOptions,
    stage: RrrSeedStage,
    /// The self-check's independent seed stage and options.
    check: Option<(RrrSeedStage, RrrCurveOptions)>,
    max_parallel: f64,
}

/// One window's final results.
#[derive(Clone, Debug, PartialEq)]
pub struct RrrWindow {
    /// Its poses, in order.
    pub poses: Vec<RrrPoseResult>,
    /// Its self-check (first, last and each sub-problem's closest pose of the window).
    pub self_check: Option<SelfCheck>,
}

impl<'a> RrrCurveRun<'a> {
    /// Checks every pose (in order; the first without a configuration is the error),
    /// takes the largest |parallel determinant| over them, and runs the seed stage (and
    /// the self-check's).
    pub fn new(
        trajectory: &'a RrrTrajectory,
        taus: &'a [f64],
        options: &'a RrrCurveOptions,
        provider: RrrStartProvider<'_>,
    ) -> Result<Self, RrrCurveError> {
        if taus.is_empty() {
            return Err(RrrCurveError::NoPoses(0));
        }
        let mut max_parallel = 0.0f64;
        for (index, &tau) in taus.iter().enumerate() {
            let (_, k) = configuration_at(trajectory, index, tau)?;
            max_parallel = max_parallel.max(parallel_polynomial(&k.to_array()).abs());
        }
        let mut stage = rrr_seed_stage(trajectory, options, provider)?;
        // Without the self-check, its seed stage still runs where a count is below the
        // generic one, to reconcile the counts ([`reconcile_seed_counts`]).
        let short = stage
            .problems
            .iter()
            .any(|p| p.at_seed.start_count < p.at_seed.generic_count);
        let check = if options.self_check || short {
            let check_options = check_options(options);
            let mut check_stage = rrr_seed_stage(trajectory, &check_options, provider)?;
            reconcile_seed_counts(&mut stage, &mut check_stage);
            options.self_check.then_some((check_stage, check_options))
        } else {
            None
        };
        Ok(RrrCurveRun {
            trajectory,
            taus,
            options,
            stage,
            check,
            max_parallel,
        })
    }

    /// Paths lost at the seed stage (they affect every pose).
    pub fn seed_failures(&self) -> &[RrrPathFailure] {
        &self.stage.failures
    }

    /// Paths tracked by the seed stage.
    pub fn seed_paths_tracked(&self) -> usize {
        self.stage.paths_tracked
    }

    /// The poses `range` (indices into the run's τ values): the chains of their blocks
    /// ([`super::chain`]) for every sub-problem in parallel, then the window's
    /// self-check ([`super::self_check`]).
    pub fn solve_window(&self, range: std::ops::Range<usize>) -> Result<RrrWindow, RrrCurveError> {
        let (stage, options) = (&self.stage, self.options);
        let blocks = chain_blocks(&range, options.chain_length, self.taus.len());
        let mut chains = Vec::with_capacity(blocks.len());
        for block in &blocks {
            let poses = block
                .clone()
                .map(|index| {
                    let tau = self.taus[index];
                    configuration_at(self.trajectory, index, tau).map(|(pose, k)| {
                        let at = ChainPose {
                            index,
                            tau,
                            k: k.to_array(),
                        };
                        (pose, at)
                    })
                })
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
                solve_chain(&stage.problems[p], &stage.frame, poses, *anchor, p, options)
            })
            .collect();
        let mut solved = solved.into_iter();
        let mut results = Vec::with_capacity(range.len());
        let mut window_poses = Vec::with_capacity(range.len());
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
                results.push(self.assemble(
                    at.index,
                    (at.tau, *pose, &at.k),
                    subproblems,
                    failures,
                    paths_tracked,
                ));
                window_poses.push((*pose, *at));
            }
        }
        // Chains of a pose list run in nearest-neighbour order: back to pose order.
        let mut by_pose: Vec<_> = results.into_iter().zip(window_poses).collect();
        by_pose.sort_by_key(|(_, (_, at))| at.index);
        let (mut results, window_poses): (Vec<RrrPoseResult>, Vec<([f64; 3], ChainPose)>) =
            by_pose.into_iter().unzip();
        let self_check = self.check.as_ref().map(|(check_stage, check_options)| {
            let poses: Vec<ChainPose> = window_poses.iter().map(|(_, at)| *at).collect();
            let checked = (check_stage, check_options);
            let scale = self.stage.frame.scale();
            let (summary, changed) = check_window(checked, &poses, &mut results, scale);
            for i in changed {
                let (pose, at) = &window_poses[i];
                let result = &results[i];
                let (subproblems, failures) = (result.subproblems.clone(), result.failures.clone());
                let tracked = result.paths_tracked;
                let at_pose = (at.tau, *pose, &at.k);
                results[i] = self.assemble(at.index, at_pose, subproblems, failures, tracked);
            }
            summary
        });
        Ok(RrrWindow {
            poses: results,
            self_check,
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

    /// The whole curve from its windows in order (every pose of the run).
    pub fn collect(&self, windows: Vec<RrrWindow>) -> RrrCurveResult {
        let stage = &self.stage;
        let mut self_check: Option<SelfCheck> = None;
        let mut poses = Vec::new();
        for window in windows {
            match (&mut self_check, &window.self_check) {
                (Some(merged), Some(check)) => merged.merge(check),
                (None, check) => self_check = check.clone(),
                _ => {}
            }
            poses.extend(window.poses);
        }
        let mut failures = stage.failures.clone();
        failures.extend(poses.iter().flat_map(|r| r.failures.iter().cloned()));
        let paths_tracked =
            stage.paths_tracked + poses.iter().map(|r| r.paths_tracked).sum::<usize>();
        RrrCurveResult {
            seed: self.options.seed,
            tau_star: stage.tau_star.map(|t| [t.re, t.im]),
            start_counts: stage
                .problems
                .iter()
                .map(|p| (p.problem.kind().short_name(), p.at_seed.start_count))
                .collect(),
            parallel_singular_parameters: parallel_singular_parameters(self.trajectory, self.taus),
            leg_singular_parameters: self.trajectory.leg_crossings().clone(),
            self_check,
            poses,
            failures,
            paths_tracked,
        }
    }
}
