//! The run's own check: a few of its poses solved again by an independent route.
//!
//! Homotopy continuation finds every critical point with probability one when no path
//! fails, but a path that jumps onto another one's track, or a seed whose finite count
//! two seed points agree on wrongly, would silently hide a minimum. So every curve
//! re-solves its first and last pose and, per metric, the pose of its smallest
//! distance from a second seed stage with another seed (another τ*, perturbation and
//! detours: every path of the check differs from the run's) along the seed route
//! (no chains, no Newton jumps). Where the check finds a closer real critical point
//! than the run, the run missed one: the pose reports the check's (smaller, feasible)
//! result and a [`PathFailure`] `self-check` (exit code 3), since the poses that were
//! not checked may have missed it too. A run in windows ([`CurveOptions::window_poses`])
//! checks every window this way (its first, last and closest poses) before the window
//! is written. Where the run lost paths of a metric at a checked pose and the check
//! lost none there, the check's result replaces the run's (`completed`).

use super::local_seed::{completes, lost_paths_of};
use super::*;
use crate::pipeline::sweep::{SELF_CHECK_TOLERANCE, SelfCheck, check_seed, checked_poses};

/// The poses to check: first, last, and per metric the pose of its smallest distance.
fn poses_to_check(results: &[PoseResult], metrics: &[Metric]) -> Vec<usize> {
    let names: Vec<String> = metrics.iter().map(Metric::name).collect();
    let indices: Vec<usize> = results.iter().map(|r| r.index).collect();
    checked_poses(&indices, &names, |i, name| {
        results[i].metrics.get(name).map(|m| m.distance)
    })
}

/// The metrics checked at pose `index` of `results`: every metric at the first and the
/// last pose, elsewhere those whose smallest distance is there (the first of equal
/// ones), in the order of `metrics`.
fn metrics_to_check(results: &[PoseResult], metrics: &[Metric], index: usize) -> Vec<Metric> {
    let at_end = results.first().map(|r| r.index) == Some(index)
        || results.last().map(|r| r.index) == Some(index);
    metrics
        .iter()
        .copied()
        .filter(|metric| {
            let name = metric.name();
            let smallest = results
                .iter()
                .filter_map(|r| r.metrics.get(&name).map(|m| (r.index, m.distance)))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            at_end || smallest.is_some_and(|(j, _)| j == index)
        })
        .collect()
}

/// The check's independent seed stage (seed + 24,095), built once per run and shared by
/// every window.
pub(super) fn check_stage(
    (design, motion, metrics): (&Design, &Motion, &[Metric]),
    options: &CurveOptions,
    provider: StartProvider<'_>,
    known_probes: &BTreeMap<String, (usize, usize)>,
) -> Result<(SeedStage, CurveOptions), PipelineError> {
    let check_options = CurveOptions {
        seed: check_seed(options.seed),
        generic_route_bend: true,
        ..options.clone()
    };
    let stage = seed_stage_with_probes(
        design,
        motion,
        metrics,
        &check_options,
        provider,
        known_probes,
    )?;
    Ok((stage, check_options))
}

/// Re-solves [`poses_to_check`] from an independent seed stage and folds the
/// comparison into `results` (see the module documentation; a disagreement is added
/// to the pose's failures). Returns what was compared.
#[cfg(test)]
pub(super) fn self_check(
    context: (&Design, &Motion, &[Metric]),
    samples: &[SampledPose],
    results: &mut [PoseResult],
    options: &CurveOptions,
    provider: StartProvider<'_>,
) -> Result<SelfCheck, PipelineError> {
    let (stage, check_options) = check_stage(context, options, provider, &BTreeMap::new())?;
    let (design, motion, metrics) = context;
    let checked = (&stage, &check_options);
    Ok(check_poses(
        checked,
        (design, motion, metrics),
        samples,
        results,
    ))
}

/// [`self_check`] with the check's stage and options given ([`check_stage`]):
/// `results` are consecutive poses (one window of the run), `samples` every pose of
/// the run (indexed by pose index).
pub(super) fn check_poses(
    (stage, check_options): (&SeedStage, &CurveOptions),
    (design, motion, metrics): (&Design, &Motion, &[Metric]),
    samples: &[SampledPose],
    results: &mut [PoseResult],
) -> SelfCheck {
    let poses = poses_to_check(results, metrics);
    // The checked poses are assembled uncertified; a pose whose result replaces the
    // run's is assembled again, certified (as the run's own results are).
    let uncertified = CurveOptions {
        certify: false,
        ..check_options.clone()
    };
    // Each pose only for the metrics it is checked for (at the first and the last pose
    // all of them): on the built-in example's 90 poses 18 + 9 (pose, metric) pairs
    // instead of 9 × 11.
    type Checked = (PoseResult, Vec<PoseEntry>, [f64; 12], Vec<Metric>);
    let checked: Vec<Checked> = poses
        .par_iter()
        .map(|&j| {
            let wanted = metrics_to_check(results, metrics, j);
            let at = (j, samples[j]);
            let is_wanted = |metric: Metric| wanted.contains(&metric);
            let (entries, k) = track_pose_of(stage, design, motion, at, check_options, &is_wanted);
            let result = assemble_pose(
                stage,
                &wanted,
                j,
                samples[j],
                &k,
                entries.clone(),
                &uncertified,
            );
            (result, entries, k, wanted)
        })
        .collect();
    let floor = 1e-12 * design.length_scale();
    let mut worst: f64 = 0.0;
    let mut disagreements = 0;
    let mut completed_by_check = 0;
    for (check, entries, k, wanted) in checked {
        let Some(run) = results.iter_mut().find(|r| r.index == check.index) else {
            continue;
        };
        let mut certified: Option<PoseResult> = None;
        for (name, checked_metric) in &check.metrics {
            // Where the run lost paths of this metric and the check completed it, the
            // check's result stands (an independent route that lost nothing).
            if lost_paths_of(&run.failures, name) && completes(&check, run, name) {
                let completed = if check_options.certify {
                    let j = check.index;
                    let certified = certified.get_or_insert_with(|| {
                        let entries = entries.clone();
                        assemble_pose(stage, &wanted, j, samples[j], &k, entries, check_options)
                    });
                    certified
                        .metrics
                        .get(name)
                        .unwrap_or(checked_metric)
                        .clone()
                } else {
                    checked_metric.clone()
                };
                run.failures
                    .retain(|f| !lost_paths_of(std::slice::from_ref(f), name));
                run.metrics.insert(name.clone(), completed);
                completed_by_check += 1;
                continue;
            }
            let Some(run_metric) = run.metrics.get_mut(name) else {
                continue;
            };
            let difference = run_metric.distance - checked_metric.distance;
            let relative = difference.abs() / run_metric.distance.max(floor);
            worst = worst.max(relative);
            // Distances at rounding level (a configuration on the singular set) differ
            // by rounding only: `floor` is absolute.
            if difference > SELF_CHECK_TOLERANCE * run_metric.distance + floor {
                *run_metric = if check_options.certify {
                    let j = check.index;
                    let certified = certified.get_or_insert_with(|| {
                        let entries = entries.clone();
                        assemble_pose(stage, &wanted, j, samples[j], &k, entries, check_options)
                    });
                    let same = certified.metrics.get(name);
                    same.unwrap_or(checked_metric).clone()
                } else {
                    checked_metric.clone()
                };
                let failure = PathFailure {
                    pose_index: Some(run.index),
                    tau: Some(run.tau),
                    problem: format!("{name}:self-check"),
                    expected: 1,
                    accounted: 0,
                    reasons: BTreeMap::from([("SelfCheckFoundCloser".to_string(), 1)]),
                };
                run.failures.push(failure);
                disagreements += 1;
            }
        }
    }
    SelfCheck {
        seed: check_options.seed,
        poses,
        worst_relative_difference: worst,
        disagreements,
        completed: completed_by_check,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::rpr::{example_design, example_motion};

    #[test]
    fn a_missed_minimum_is_found_and_reported() {
        let (design, motion) = (example_design(), example_motion());
        let metrics = ["plate/plate".parse().unwrap()];
        let options = CurveOptions {
            self_check: false,
            ..CurveOptions::default()
        };
        let provider = &default_start_solutions;
        let mut result =
            compute_curve(&design, &motion, 6, &metrics, &options, provider, &|_| {}).unwrap();
        let truth = result.poses[5].metrics["plate/plate"].distance;
        // As if the run had missed the closest critical point at the last pose.
        result.poses[5]
            .metrics
            .get_mut("plate/plate")
            .unwrap()
            .distance *= 2.0;
        let samples = sample_motion(&motion, 6).unwrap();
        let context = (&design, &motion, &metrics[..]);
        let check = self_check(context, &samples, &mut result.poses, &options, provider).unwrap();
        assert_eq!(check.disagreements, 1, "{check:?}");
        let repaired = result.poses[5].metrics["plate/plate"].distance;
        assert!(
            (repaired - truth).abs() <= 1e-10 * truth,
            "{repaired} vs {truth}"
        );
        assert!(
            result.poses[5]
                .failures
                .iter()
                .any(|f| f.problem == "plate/plate:self-check")
        );
        assert!(check.poses.contains(&5));
    }
}
