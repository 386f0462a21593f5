//! A 3-RRR curve solved window by window: the seed stage and a first pass over every
//! pose (its configuration exists; the largest |parallel determinant|, which scales
//! [`RrrPoseResult::parallel_determinant_abs_scaled`] over the whole motion) once, then
//! any range of poses on demand. Every (pose, sub-problem) is a pure function of its
//! index, so a window's results are those of the whole curve at its poses, and a caller
//! can write a window and drop it: memory is bounded by one window, not by the number
//! of poses.

use super::rrr_ab_initio::RrrAbInitioError;
use super::rrr_chain::{ChainPose, chain_anchor, chain_blocks, solve_chain};
use super::rrr_curve::{
    Entry, RrrCurveError, RrrCurveOptions, RrrCurveResult, RrrPathFailure, RrrPoseResult,
    configuration_at, parallel_singular_parameters, signed,
};
use super::rrr_seed::{RrrSeedStage, rrr_seed_stage};
use super::start_file::StartSolutions;
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrTrajectory, parallel_polynomial};
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
    max_parallel: f64,
}

impl<'a> RrrCurveRun<'a> {
    /// Checks every pose (in order; the first without a configuration is the error),
    /// takes the largest |parallel determinant| over them, and runs the seed stage.
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
        let stage = rrr_seed_stage(trajectory, options, provider)?;
        Ok(RrrCurveRun {
            trajectory,
            taus,
            options,
            stage,
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
    /// ([`super::rrr_chain`]) for every sub-problem in parallel.
    pub fn solve_poses(
        &self,
        range: std::ops::Range<usize>,
    ) -> Result<Vec<RrrPoseResult>, RrrCurveError> {
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
            let (pose_values, poses): (Vec<[f64; 3]>, Vec<ChainPose>) = poses.into_iter().unzip();
            let anchor = chain_anchor(&poses, stage.tau_star);
            chains.push((pose_values, poses, anchor));
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
                    let Some((result, failure, tracked)) = entries.get(j).cloned() else {
                        continue;
                    };
                    failures.extend(failure);
                    paths_tracked += tracked;
                    subproblems.insert(seeded.problem.kind().short_name(), result);
                }
                results.push(self.assemble(
                    at.index,
                    (at.tau, *pose, &at.k),
                    subproblems,
                    failures,
                    paths_tracked,
                ));
            }
        }
        Ok(results)
    }

    fn assemble(
        &self,
        index: usize,
        (tau, pose, k): (f64, [f64; 3], &[f64; CONFIGURATION_LEN]),
        subproblems: BTreeMap<String, super::rrr_curve::RrrSubproblemResult>,
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

    /// The whole curve from its poses in order (every pose of the run).
    pub fn collect(&self, poses: Vec<RrrPoseResult>) -> RrrCurveResult {
        let stage = &self.stage;
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
                .map(|p| (p.problem.kind().short_name(), p.start_count))
                .collect(),
            parallel_singular_parameters: parallel_singular_parameters(self.trajectory, self.taus),
            leg_singular_parameters: self.trajectory.leg_crossings().clone(),
            poses,
            failures,
            paths_tracked,
        }
    }
}
