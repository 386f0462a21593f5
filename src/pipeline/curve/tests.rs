use super::*;
use crate::mechanism::rpr::{example_design, example_motion};

/// `MotionPath::point_and_velocity` is the derivative of `MotionPath::point`
/// (central differences in complex t), on every segment of a detoured path.
#[test]
fn motion_path_velocity_matches_finite_differences() {
    let design = example_design();
    let motion = example_motion();
    let seed = seed_point(&design, &motion, 3);
    let k0 = design
        .configuration(motion.pose(0.3).expect("pose"))
        .to_array();
    let normalization = Normalization::of(&to_real(&k0));
    let target = MotionPoint::Tau(C64::new(1.7, 0.0));
    let mut rng = random::stream(3, 99);
    let waypoints = vec![seed.point, target.perturbed(0.5, &mut rng), target];
    let path = MotionPath::new(
        &design,
        &motion,
        waypoints,
        seed.perturbation,
        normalization,
        vec![C64::new(0.4, 0.1); 6],
    );
    let m = path.len();
    let (mut p, mut dp, mut plus, mut minus) = (
        vec![C64::new(0.0, 0.0); m],
        vec![C64::new(0.0, 0.0); m],
        vec![C64::new(0.0, 0.0); m],
        vec![C64::new(0.0, 0.0); m],
    );
    for t in [0.1, 0.37, 0.62, 0.9] {
        for direction in [C64::new(1.0, 0.0), C64::new(0.0, 1.0)] {
            let t = C64::new(t, 0.0);
            let h = direction * 1e-6;
            path.point_and_velocity(t, &mut p, &mut dp);
            path.point(t + h, &mut plus);
            path.point(t - h, &mut minus);
            for i in 0..m {
                let fd = (plus[i] - minus[i]) / (h * 2.0);
                assert!(
                    (fd - dp[i]).norm() <= 1e-6 * (1.0 + dp[i].norm()),
                    "t = {t}, i = {i}: {fd} vs {}",
                    dp[i]
                );
            }
        }
    }
}

/// The example's seed stage for `plate/plate` alone (no self-check): the motion, the
/// options, the stage and the index of its `singularity` sub-problem.
fn plate_plate_stage() -> (Motion, CurveOptions, SeedStage, usize) {
    let (design, motion) = (example_design(), example_motion());
    let (options, stage, index) = singularity_stage(&design, &motion, "plate/plate");
    (motion, options, stage, index)
}

/// The seed stage of `metric` alone (no self-check) and the index of its singularity
/// sub-problem.
fn singularity_stage(
    design: &Design,
    motion: &Motion,
    metric: &str,
) -> (CurveOptions, SeedStage, usize) {
    let metrics = Metric::parse_list(metric).expect("metric");
    let options = CurveOptions {
        self_check: false,
        ..CurveOptions::default()
    };
    let start = default_start_solutions;
    let stage = seed_stage(design, motion, &metrics, &options, &start).expect("stage");
    let name = format!("{metric}:singularity");
    let index = stage
        .problems
        .iter()
        .position(|p| p.id.name() == name)
        .expect("the singularity sub-problem");
    (options, stage, index)
}

/// Sub-problem `index` solved from the seed at a pose: no failure, all `generic` paths
/// accounted for, fewer than `most` paths tracked.
fn complete_from_the_seed(
    context: SolveContext<'_>,
    (pose, sample): (usize, SampledPose),
    index: usize,
    (generic, most): (usize, usize),
) {
    let at_pose = track_problem(context, (pose, sample), index, Route::Seed);
    assert!(
        at_pose.entry.failure.is_none(),
        "{:?}",
        at_pose.entry.failure
    );
    assert_eq!(at_pose.entry.accounted, generic);
    assert!(
        at_pose.entry.tracked < most,
        "{} paths",
        at_pose.entry.tracked
    );
}

/// A seed count below the generic one is tested at the motion's first pose: the
/// example's `plate/plate` seed has all 50 critical points; with one dropped (a count
/// two seed points could have agreed on wrongly) the generic route to the first pose
/// refutes the 49, the expected count is 50 again, and a pose solved from the seed
/// is complete with 50 points (from the generic route), not with 49.
#[test]
fn a_seed_count_that_the_generic_route_refutes_is_raised() {
    let (motion, options, mut stage, index) = plate_plate_stage();
    let generic = stage.problems[index].at_seed.generic_count;
    assert_eq!(stage.problems[index].at_seed.start_count, generic);
    stage.problems[index].at_seed.solutions.pop();
    stage.problems[index].at_seed.start_count = generic - 1;
    let first = motion.pose(motion.tau_range()[0]).expect("pose");
    let normalization = stage.normalization;
    let (tracked, probes) = probe_seed_counts(
        &mut stage.problems,
        (first, normalization),
        &options,
        &BTreeMap::new(),
    );
    assert!(tracked >= generic, "{tracked}");
    assert_eq!(stage.problems[index].at_seed.start_count, generic);
    // The route's result is kept, and a stage given it (the self-check's) takes it
    // instead of tracking the route again, to the same count.
    assert_eq!(
        probes.get("plate/plate:singularity").map(|p| p.1),
        Some(generic)
    );
    stage.problems[index].at_seed.start_count = generic - 1;
    let (again, _) = probe_seed_counts(
        &mut stage.problems,
        (first, normalization),
        &options,
        &probes,
    );
    assert_eq!(
        (again, stage.problems[index].at_seed.start_count),
        (0, generic)
    );
    // The seed's shortfall, had the seed stage reported it, decides nothing now: that
    // failure goes; a pose's own failure and another sub-problem's seed failure stay.
    let failure = |problem: &str, pose_index: Option<usize>| PathFailure {
        pose_index,
        tau: None,
        problem: problem.to_string(),
        expected: generic,
        accounted: generic - 1,
        reasons: BTreeMap::new(),
    };
    let mut failures = vec![
        failure("plate/plate:singularity", None),
        failure("plate/plate:singularity", Some(3)),
        failure("rigid/rigid:singularity", None),
    ];
    settle_seed_failures(&stage.problems, &mut failures);
    let left: Vec<(&str, Option<usize>)> = failures
        .iter()
        .map(|f| (f.problem.as_str(), f.pose_index))
        .collect();
    assert_eq!(
        left,
        [
            ("plate/plate:singularity", Some(3)),
            ("rigid/rigid:singularity", None)
        ]
    );
    let samples = sample_motion(&motion, 5).expect("samples");
    let context = SolveContext {
        stage: &stage,
        motion: &motion,
        options: &options,
    };
    let at_pose = track_problem(context, (2, samples[2]), index, Route::Seed);
    assert_eq!(at_pose.complete.map(|set| set.len()), Some(generic));
    assert!(at_pose.entry.failure.is_none());
}

/// The self-check's generic route bends through a seed-drawn complex point
/// ([`CurveOptions::generic_route_bend`]): at a pose of the example, `plate/plate`'s
/// generic route with and without the bend reaches the same complete set of 50
/// critical points (each within 1e-8 of one of the other), along different paths (the
/// endpoints are not bit for bit the same, as they are for two straight runs).
#[test]
fn the_bent_generic_route_reaches_the_same_set_along_another_path() {
    let (motion, options, stage, index) = plate_plate_stage();
    let samples = sample_motion(&motion, 5).expect("samples");
    let context = SolveContext {
        stage: &stage,
        motion: &motion,
        options: &options,
    };
    let (seeded, _, _, parameters) = context.problem_at(index, &samples[3]);
    let straight = generic_route(seeded, &parameters, 7, &options);
    let again = generic_route(seeded, &parameters, 7, &options);
    let bent_options = CurveOptions {
        generic_route_bend: true,
        ..options.clone()
    };
    let bent = generic_route(seeded, &parameters, 7, &bent_options);
    let generic = seeded.at_seed.generic_count;
    for run in [&straight, &bent] {
        assert_eq!((run.accounted, run.endpoints.len()), (generic, 50));
    }
    assert_eq!(straight.endpoints, again.endpoints);
    assert_ne!(straight.endpoints, bent.endpoints);
    for x in &bent.endpoints {
        let scale = 1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        let near = |y: &Vec<C64>| x.iter().zip(y).all(|(a, b)| (a - b).norm() <= 1e-8 * scale);
        assert!(straight.endpoints.iter().any(near));
    }
}

/// Two base anchors 10⁻⁴ apart (the design matrix's `close-base-12`), `bars/rigid`,
/// pose 4 of the class's scattered list: one of the 80 critical points has multipliers
/// of about 10¹² there. The seed route runs out of steps (clusters of critical points
/// along the whole route) and the generic route reaches 79 distinct finite points; the
/// projective twin ends the 80th path at `λ₀ = 0` with the configuration finite, a
/// point within about `|λ₀|` of a singular point of the constraint set, whose distance
/// the singular-point sub-problems bound. The pose is complete from the generic route
/// with that path accounted for, without the seed route's re-runs and detours (before:
/// 261 paths at the pose, 95 of them re-runs of the seed route that reached the 80th
/// point after 1.3 s), and its distance is not above the independent reference's.
#[test]
fn a_critical_point_at_a_fritz_john_point_of_the_twin_completes_the_generic_route() {
    use crate::reference::designs::design_case;
    use crate::reference::local_search::{ReferenceOptions, reference_distances};
    let case = design_case("close-base-12", 1).expect("a class of the matrix");
    let design = case.design().expect("design");
    let motion = case.scattered_motion();
    let metrics = Metric::parse_list("bars/rigid").expect("metric");
    let (options, stage, index) = singularity_stage(&design, &motion, "bars/rigid");
    let samples = sample_motion(&motion, 0).expect("samples");
    let context = SolveContext {
        stage: &stage,
        motion: &motion,
        options: &options,
    };
    let (seeded, _, _, parameters) = context.problem_at(index, &samples[4]);
    let generic = seeded.at_seed.generic_count;
    assert_eq!((generic, seeded.at_seed.start_count), (80, 80));
    let stream = (5u64 << 32) | index as u64;
    let from_generic = generic_route(seeded, &parameters, stream, &options);
    assert_eq!(
        (from_generic.accounted, from_generic.endpoints.len()),
        (generic, generic - 1)
    );
    assert!(from_generic.at_infinity_in_twin >= 1);
    complete_from_the_seed(context, (4, samples[4]), index, (generic, 200));
    let pose = samples[4].pose;
    let result = solve_pose(&stage, &design, &motion, &metrics, 4, samples[4], &options);
    let k = design.configuration(pose).to_array();
    for reference in reference_distances(&design, &k, &metrics, &ReferenceOptions::default()) {
        let got = result.metrics[&reference.metric.name()].distance;
        assert!(
            got <= reference.distance * (1.0 + 1e-9) + 1e-12,
            "pipeline {got} above the reference {}",
            reference.distance
        );
    }
}

/// On two base anchors 10⁻⁴ apart the `bars/rigid` seed route runs out of steps at
/// a pose list's first pose, and the stage records it: at another pose the generic
/// route comes first, and the pose is complete without the seed route's paths
/// (before: the 80 seed-route paths, abandoned when one ran out of steps, then the
/// generic route's). Where the probe completes, it is the first pose's first run.
#[test]
fn a_seed_route_that_runs_out_of_steps_at_the_first_pose_is_skipped_at_the_others() {
    use crate::reference::designs::design_case;
    let probed = |class: &str| {
        let case = design_case(class, 1).expect("a class of the matrix");
        let (design, motion) = (case.design().expect("design"), case.scattered_motion());
        let (options, stage, index) = singularity_stage(&design, &motion, "bars/rigid");
        (motion, options, stage, index)
    };
    let (motion, options, stage, index) = probed("close-base-12");
    let seeded = &stage.problems[index];
    let probe = seeded
        .seed_route_probe
        .as_ref()
        .expect("a pose list is probed");
    assert!(probe.ran_out_of_steps());
    let generic = seeded.at_seed.generic_count;
    let samples = sample_motion(&motion, 0).expect("samples");
    let context = SolveContext {
        stage: &stage,
        motion: &motion,
        options: &options,
    };
    complete_from_the_seed(context, (3, samples[3]), index, (generic, 2 * generic));
    // A generic design is not probed. Where the probe completes (base anchors 2 and 3
    // 10⁻⁴ apart), its pose takes the probe's paths as its first run: the same
    // endpoints as a pose whose seed route is tracked afresh, and the paths are not
    // tracked (nor counted) twice.
    let (_, _, stage, index) = probed("random-scale-1");
    assert!(stage.problems[index].seed_route_probe.is_none());
    let (motion, options, mut stage, index) = probed("close-base-23");
    let probe = stage.problems[index]
        .seed_route_probe
        .as_ref()
        .expect("probed");
    assert!(!probe.ran_out_of_steps());
    let samples = sample_motion(&motion, 0).expect("samples");
    let solve = |stage: &SeedStage| {
        let context = SolveContext {
            stage,
            motion: &motion,
            options: &options,
        };
        track_problem(context, (0, samples[0]), index, Route::Seed).entry
    };
    let reused = solve(&stage);
    stage.problems[index].seed_route_probe = None;
    let afresh = solve(&stage);
    assert_eq!(reused.accounted, afresh.accounted);
    assert_eq!(reused.tracked + afresh.accounted, afresh.tracked);
    assert_eq!(
        format!("{:?}", reused.candidates),
        format!("{:?}", afresh.candidates)
    );
}
