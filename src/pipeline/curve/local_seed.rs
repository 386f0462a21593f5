//! Stage 3c: a pose whose paths are still lost after the rescue from its neighbours
//! is solved once more, per metric that lost paths there, from a seed of its own.
//!
//! Every route of the run to a pose starts at the run's seed or at the start file's
//! generic point; on scattered pose lists the seed is near the first pose, so the
//! seed route to a far pose is long, and where its paths are hard all along (two
//! anchors of a rigid part 10⁻⁴ apart) neither it, its detours nor the generic route
//! may account for every path. A seed stage at the pose itself — the start file's
//! solutions tracked to a complex point next to the pose, confirmed there as every
//! seed is, then the short route to the pose — is a route independent of all of
//! them (it is what `singdist distance` runs). It expects at least the run's count
//! of each sub-problem (a count some seed reached), and its result replaces the
//! metric's at that pose only where it is complete: no path lost at its seed or at
//! the pose, and every sub-problem expecting at least as many critical points as the
//! run's did.

use super::*;
use crate::mechanism::rpr::PoseList;

/// At most this many (pose, metric) pairs of one window get a seed stage of their
/// own: each costs about one `distance` run (on two base anchors 10⁻⁴ apart, 2 s for
/// `bars/rigid`). Pairs beyond it stay reported as lost.
pub const LOCAL_SEED_LIMIT: usize = 16;

/// Whether any of `failures` is of a sub-problem of the metric `name` (a failure's
/// problem is named `metric:sub-problem`).
pub(super) fn lost_paths_of(failures: &[PathFailure], name: &str) -> bool {
    failures.iter().any(|f| {
        f.problem
            .split_once(':')
            .is_some_and(|(metric, _)| metric == name)
    })
}

/// The options of a seed stage at a pose: the run's, with its own seed (the run's plus
/// 68,769: a pose list's first pose is the run's seed point too, and the same seed
/// there would repeat the run's stage) and a bent generic route (as the self-check's).
fn local_options(options: &CurveOptions) -> CurveOptions {
    CurveOptions {
        seed: options.seed.wrapping_add(0x10ca1),
        generic_route_bend: true,
        ..options.clone()
    }
}

/// The metrics whose sub-problems lost paths at `result`'s pose, in the order of
/// `metrics`.
fn metrics_that_lost_paths<'m>(result: &PoseResult, metrics: &'m [Metric]) -> Vec<&'m Metric> {
    metrics
        .iter()
        .filter(|metric| lost_paths_of(&result.failures, &metric.name()))
        .collect()
}

/// Whether `local` (the metric `name` at a pose from a seed stage of its own, whose
/// seed stage lost nothing) completes what `run` (the run's result at that pose)
/// lost: no failure for the metric, and every sub-problem of `run` expecting at most
/// as many critical points as `local` accounted for.
pub(super) fn completes(local: &PoseResult, run: &PoseResult, name: &str) -> bool {
    if lost_paths_of(&local.failures, name) {
        return false;
    }
    let (Some(local_metric), Some(run_metric)) = (local.metrics.get(name), run.metrics.get(name))
    else {
        return false;
    };
    run_metric.subproblems.iter().all(|(sub, expected)| {
        local_metric.subproblems.get(sub).is_some_and(|found| {
            found.expected_paths >= expected.expected_paths
                && found.accounted_paths >= found.expected_paths
        })
    })
}

/// Stage 3c (see the module documentation) on one window's `results` (`samples`: every
/// pose of the run, by pose index). Returns the positions in `results` that changed.
pub(super) fn rescue_by_local_seed(
    (design, metrics): (&Design, &[Metric]),
    samples: &[SampledPose],
    results: &mut [PoseResult],
    options: &CurveOptions,
    provider: StartProvider<'_>,
) -> Vec<usize> {
    let tasks: Vec<(usize, &Metric)> = results
        .iter()
        .enumerate()
        .flat_map(|(position, result)| {
            metrics_that_lost_paths(result, metrics)
                .into_iter()
                .map(move |metric| (position, metric))
        })
        .take(LOCAL_SEED_LIMIT)
        .collect();
    if tasks.is_empty() {
        return Vec::new();
    }
    let view: &[PoseResult] = results;
    let solved: Vec<Option<(usize, String, PoseResult)>> = tasks
        .par_iter()
        .map(|&(position, metric)| {
            let j = view[position].index;
            let sample = samples[j];
            let motion = Motion::Poses(PoseList {
                poses: vec![sample.pose],
            });
            let one = std::slice::from_ref(metric);
            let options = &local_options(options);
            let mut stage = seed_stage(design, &motion, one, options, provider).ok()?;
            let name = metric.name();
            // The run's count was reached at some seed: no fewer are expected here
            // (as between the run's and the check's stages, `reconcile_seed_counts`).
            let run_metric = view[position].metrics.get(&name);
            for problem in &mut stage.problems {
                let sub = problem.id.subproblem.name();
                if let Some(run) = run_metric.and_then(|m| m.subproblems.get(sub)) {
                    problem.at_seed.start_count =
                        problem.at_seed.start_count.max(run.expected_paths);
                }
            }
            settle_seed_failures(&stage.problems, &mut stage.failures);
            if lost_paths_of(&stage.failures, &name) {
                return None;
            }
            let mut local = solve_pose(&stage, design, &motion, one, j, sample, options);
            local.paths_tracked += stage.paths_tracked;
            completes(&local, &view[position], &name).then_some((position, name, local))
        })
        .collect();
    let mut changed = Vec::new();
    for (position, name, local) in solved.into_iter().flatten() {
        let run = &mut results[position];
        run.failures
            .retain(|f| !lost_paths_of(std::slice::from_ref(f), &name));
        run.paths_tracked += local.paths_tracked;
        if let Some(metric) = local.metrics.get(&name) {
            run.metrics.insert(name, metric.clone());
        }
        changed.push(position);
    }
    changed.dedup();
    changed
}

/// The seed count of sub-problem `id` in a seed stage of its metric alone next to
/// `pose` (its first pose perturbed, as for a pose list of one), or `None` if that
/// stage could not be built or lost paths of the sub-problem.
pub(super) fn seed_count_at(
    design: &Design,
    pose: Pose,
    id: ProblemId,
    options: &CurveOptions,
    provider: StartProvider<'_>,
) -> Option<usize> {
    let motion = Motion::Poses(PoseList { poses: vec![pose] });
    let options = &local_options(options);
    let stage = seed_stage(design, &motion, &[id.metric], options, provider).ok()?;
    if stage.failures.iter().any(|f| f.problem == id.name()) {
        return None;
    }
    let seeded = stage.problems.iter().find(|p| p.id == id)?;
    Some(seeded.at_seed.start_count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::postprocess::SubproblemDistance;

    fn failure(problem: &str) -> PathFailure {
        PathFailure {
            pose_index: Some(0),
            tau: Some(0.0),
            problem: problem.into(),
            expected: 80,
            accounted: 79,
            reasons: BTreeMap::new(),
        }
    }

    fn pose_with(failures: Vec<PathFailure>) -> PoseResult {
        PoseResult {
            index: 0,
            tau: 0.0,
            pose: [0.0; 3],
            singularity: 0.0,
            metrics: BTreeMap::new(),
            failures,
            paths_tracked: 0,
        }
    }

    /// A pose whose `bars/rigid` sub-problems expect `counts` and account for
    /// `accounted`, with `failures`.
    fn pose_expecting(counts: &[(&str, usize, usize)], failures: Vec<PathFailure>) -> PoseResult {
        let subproblems = counts
            .iter()
            .map(|&(name, expected, accounted)| {
                let found = SubproblemDistance {
                    distance: Some(0.1),
                    closest: Some([0.0; 12]),
                    real_critical_points: 2,
                    accounted_paths: accounted,
                    expected_paths: expected,
                    certificate: None,
                };
                (name.to_string(), found)
            })
            .collect();
        let metric = MetricDistance {
            distance: 0.1,
            signed_distance: 0.1,
            subproblem: "singularity".into(),
            closest: [0.0; 12],
            cut_locus: false,
            minimisers: Vec::new(),
            subproblems,
            certificate: None,
        };
        PoseResult {
            metrics: BTreeMap::from([("bars/rigid".to_string(), metric)]),
            ..pose_with(failures)
        }
    }

    /// Only the metrics a failure names are re-solved: the name before the colon,
    /// exactly (`rigid/bars` is not `bars/rigid`).
    #[test]
    fn the_metrics_to_resolve_are_those_named_by_the_failures() {
        let metrics = Metric::parse_list("plate/rigid,bars/rigid,rigid/rigid,rigid/bars").unwrap();
        let result = pose_with(vec![
            failure("bars/rigid:singularity"),
            failure("bars/rigid:collinear-platform"),
            failure("rigid/rigid:singularity"),
        ]);
        let names: Vec<String> = metrics_that_lost_paths(&result, &metrics)
            .iter()
            .map(|m| m.name())
            .collect();
        assert_eq!(names, ["bars/rigid", "rigid/rigid"]);
        assert!(metrics_that_lost_paths(&pose_with(Vec::new()), &metrics).is_empty());
    }

    /// A result completes the run's only without failures of the metric, with every
    /// sub-problem accounted for and expecting at least the run's count: a seed stage
    /// that settled on fewer critical points (78 of 80) completes nothing.
    #[test]
    fn only_a_complete_result_expecting_as_many_completes_the_run() {
        let run = pose_expecting(
            &[("singularity", 80, 79), ("collinear-platform", 8, 8)],
            vec![failure("bars/rigid:singularity")],
        );
        let complete = pose_expecting(
            &[("singularity", 80, 80), ("collinear-platform", 8, 8)],
            Vec::new(),
        );
        assert!(completes(&complete, &run, "bars/rigid"));
        let fewer = pose_expecting(
            &[("singularity", 78, 78), ("collinear-platform", 8, 8)],
            Vec::new(),
        );
        assert!(!completes(&fewer, &run, "bars/rigid"));
        let lost = pose_expecting(
            &[("singularity", 80, 80), ("collinear-platform", 8, 8)],
            vec![failure("bars/rigid:collinear-platform")],
        );
        assert!(!completes(&lost, &run, "bars/rigid"));
        let short = pose_expecting(
            &[("singularity", 80, 79), ("collinear-platform", 8, 8)],
            Vec::new(),
        );
        assert!(!completes(&short, &run, "bars/rigid"));
        let missing = pose_expecting(&[("singularity", 80, 80)], Vec::new());
        assert!(!completes(&missing, &run, "bars/rigid"));
        // Another metric's failure does not matter.
        let other = pose_expecting(
            &[("singularity", 80, 80), ("collinear-platform", 8, 8)],
            vec![failure("rigid/bars:singularity")],
        );
        assert!(completes(&other, &run, "bars/rigid"));
    }
}
