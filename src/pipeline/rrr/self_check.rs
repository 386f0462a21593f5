//! The 3-RRR run's own check, as for the 3-RPR ([`crate::pipeline::curve::SelfCheck`]): a few
//! poses of every window solved again by an independent route.
//!
//! A path that jumps onto another one's track, or a seed count two seed points agree
//! on wrongly, would silently hide a minimum. So every window re-solves its first and
//! last pose and, per sub-problem, the pose of its smallest distance, from a second
//! seed stage with another seed (another `τ*`, perturbation and detours) along the
//! seed route (no chains). Where the check finds a closer real critical point than the
//! run, the run missed one: the pose reports the check's (smaller, feasible) result
//! and a [`RrrPathFailure`] `…:self-check` (exit code 3), since the poses that were not
//! checked may have missed it too.

use super::chain::{ChainPose, solve_chain};
use super::curve::{RrrCurveOptions, RrrPathFailure, RrrPoseResult};
use super::seed::RrrSeedStage;
use crate::mechanism::rrr::RrrTrajectory;
use crate::pipeline::curve::{SELF_CHECK_TOLERANCE, SelfCheck, check_seed, checked_poses};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The check's options: its own seed (the 3-RPR check's, [`check_seed`]), every pose
/// from the seed.
pub(crate) fn check_options(options: &RrrCurveOptions) -> RrrCurveOptions {
    RrrCurveOptions {
        seed: check_seed(options.seed),
        chain_length: 1,
        self_check: false,
        ..options.clone()
    }
}

/// The poses to check among `results` (one window): first, last, and per sub-problem
/// the pose of its smallest distance.
fn poses_to_check(results: &[RrrPoseResult]) -> Vec<usize> {
    let names: Vec<String> = results
        .first()
        .map(|r| r.subproblems.keys().cloned().collect())
        .unwrap_or_default();
    let indices: Vec<usize> = results.iter().map(|r| r.index).collect();
    checked_poses(&indices, &names, |i, name| {
        results[i].subproblems.get(name)?.distance
    })
}

/// Re-solves [`poses_to_check`] of `results` (`poses[i]` the configuration of
/// `results[i]`) from the check's stage and folds the comparison in: a sub-problem the
/// check finds closer gets the check's result and a failure. Returns what was compared
/// and the indices (into `results`) of the poses whose sub-problems changed, which the
/// caller assembles again. `length_scale` sets the absolute floor `10⁻¹² · length_scale`
/// under which distances differ by rounding only.
pub(crate) fn check_window(
    (trajectory, stage, options): (&RrrTrajectory, &RrrSeedStage, &RrrCurveOptions),
    poses: &[ChainPose],
    results: &mut [RrrPoseResult],
    length_scale: f64,
) -> (SelfCheck, Vec<usize>) {
    let checked_poses = poses_to_check(results);
    let jobs: Vec<(usize, usize)> = checked_poses
        .iter()
        .filter_map(|&index| results.iter().position(|r| r.index == index))
        .flat_map(|at| (0..stage.problems.len()).map(move |p| (at, p)))
        .collect();
    let checked: Vec<_> = jobs
        .par_iter()
        .map(|&(at, p)| {
            let pose = [poses[at]];
            let seeded = &stage.problems[p];
            let frame = &stage.frame;
            let entry = solve_chain(trajectory, seeded, frame, &pose, 0, p, options).remove(0);
            (at, seeded.problem.kind(), entry.result)
        })
        .collect();
    let floor = 1e-12 * length_scale;
    let mut worst: f64 = 0.0;
    let mut disagreements = 0;
    let mut changed = Vec::new();
    for (at, kind, check) in checked {
        let run = &mut results[at];
        let Some(run_result) = run.subproblems.get_mut(&kind.short_name()) else {
            continue;
        };
        let Some(check_distance) = check.distance else {
            continue;
        };
        let closer = match run_result.distance {
            Some(run_distance) => {
                let difference = run_distance - check_distance;
                worst = worst.max(difference.abs() / run_distance.max(floor));
                difference > SELF_CHECK_TOLERANCE * run_distance + floor
            }
            None => true,
        };
        if closer {
            *run_result = check;
            run.failures.push(RrrPathFailure {
                pose_index: Some(run.index),
                tau: Some(run.tau),
                problem: format!("{}:self-check", kind.name()),
                expected: 1,
                accounted: 0,
                reasons: BTreeMap::from([("SelfCheckFoundCloser".to_string(), 1)]),
            });
            disagreements += 1;
            changed.push(at);
        }
    }
    changed.sort_unstable();
    changed.dedup();
    let check = SelfCheck {
        seed: options.seed,
        poses: checked_poses,
        worst_relative_difference: worst,
        disagreements,
        completed: 0,
    };
    (check, changed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::rrr::example_trajectory;
    use crate::pipeline::rrr::curve::default_rrr_start_solutions;
    use crate::pipeline::rrr::curve::{compute_rrr_curve_at, configuration_at};
    use crate::pipeline::rrr::seed::rrr_seed_stage;

    /// A run that missed the closest critical point of one sub-problem at its last
    /// pose: the check finds it, reports it and puts the true distance back.
    #[test]
    fn a_missed_minimum_is_found_and_reported() {
        let trajectory = example_trajectory();
        let taus = [0.3, 1.1, 2.0, 2.9, 3.7, 4.6];
        let options = RrrCurveOptions {
            self_check: false,
            ..RrrCurveOptions::default()
        };
        let provider = &default_rrr_start_solutions;
        let mut result = compute_rrr_curve_at(&trajectory, &taus, &options, provider).unwrap();
        let truth = result.poses[5].subproblems["leg2"].distance.unwrap();
        // As if the run had missed it.
        let tampered = result.poses[5].subproblems.get_mut("leg2").unwrap();
        tampered.distance = Some(2.0 * truth);
        let poses: Vec<ChainPose> = taus
            .iter()
            .enumerate()
            .map(|(index, &tau)| {
                let (_, k) = configuration_at(&trajectory, index, tau).unwrap();
                ChainPose {
                    index,
                    tau,
                    k: k.to_array(),
                }
            })
            .collect();
        let check_options = check_options(&options);
        let stage = rrr_seed_stage(&trajectory, &check_options, provider).unwrap();
        let checked = (&trajectory, &stage, &check_options);
        let (check, changed) = check_window(checked, &poses, &mut result.poses, 1.0);
        assert_eq!(check.disagreements, 1, "{check:?}");
        assert_eq!(changed, vec![5]);
        assert!(check.poses.contains(&5) && check.poses.contains(&0));
        let repaired = result.poses[5].subproblems["leg2"].distance.unwrap();
        assert!(
            (repaired - truth).abs() <= 1e-10 * truth,
            "{repaired} vs {truth}"
        );
        let failures = &result.poses[5].failures;
        assert!(
            failures.iter().any(|f| f.problem == "rrr:leg2:self-check"),
            "{failures:?}"
        );
        // The tampered distance was twice the check's: a relative difference of 1/2.
        assert!((check.worst_relative_difference - 0.5).abs() < 1e-9);
        assert_eq!(result.poses[0].failures, vec![]);
    }
}
