//! 3-RRR distances against an independent many-start local solution of the constrained
//! problem ([`singdist::reference::rrr`]): at poses of several design classes each of
//! the four distances is ≤ the best of 200 local solutions (+1e-9 relative).
use singdist::mechanism::rpr::{Motion, MotionCoordinate};
use singdist::mechanism::rrr::*;
use singdist::pipeline::rrr_curve::*;
use singdist::problem::rrr::RrrSubProblem;
use singdist::reference::rrr::reference_distance;

/// The built-in example (equal links), an asymmetric design with unequal links and
/// mixed modes, a symmetric design with unequal links and an oscillating orientation,
/// with two poses each.
fn cases() -> Vec<(RrrTrajectory, [f64; 2])> {
    let asymmetric = RrrDesign::new(
        [
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.2),
            Point::new(0.8, 1.9),
        ],
        [1.0, 0.9, 1.1],
        [0.9, 1.2, 1.0],
        [
            Point::new(-0.2, -0.15),
            Point::new(0.3, -0.1),
            Point::new(0.05, 0.3),
        ],
    )
    .expect("design");
    let symmetric = RrrDesign::symmetric(1.0, 0.3, 0.6, 0.7).expect("design");
    let mut oscillating = circular_translation(Point::new(0.05, 0.0), 0.1, 0.0, [0.0, 6.0]);
    if let Motion::Analytic(m) = &mut oscillating {
        m.phi = MotionCoordinate {
            polynomial: vec![0.1],
            cosines: vec![[0.3, 1.0, 0.0].into()],
        };
    }
    vec![
        (example_trajectory(), [1.49, 4.26]),
        (
            RrrTrajectory::new(
                asymmetric,
                [
                    ElbowMode::Positive,
                    ElbowMode::Negative,
                    ElbowMode::Positive,
                ],
                circular_translation(Point::new(1.0, 0.7), 0.1, 0.2, [0.0, 6.0]),
            )
            .expect("trajectory"),
            [0.7, 3.9],
        ),
        (
            RrrTrajectory::new(symmetric, POSITIVE_MODES, oscillating).expect("trajectory"),
            [1.2, 5.0],
        ),
    ]
}

#[test]
fn distances_are_not_beaten_by_many_start_local_solutions() {
    for (case, (trajectory, taus)) in cases().iter().enumerate() {
        let curve = compute_rrr_curve_at(
            trajectory,
            taus,
            &RrrCurveOptions::default(),
            &default_rrr_start_solutions,
        )
        .expect("curve");
        assert!(curve.failures.is_empty(), "{:?}", curve.failures);
        for pose in &curve.poses {
            let k = trajectory.configuration(pose.tau).expect("pose").to_array();
            for kind in RrrSubProblem::ALL {
                let reported = pose.subproblems[&kind.short_name()]
                    .distance
                    .expect("a real critical point");
                let best = reference_distance(kind, &k, 200, 7 + case as u64)
                    .expect("a converged local solution");
                println!(
                    "case {case} tau {} {}: reported {reported:.15} best local {best:.15}",
                    pose.tau,
                    kind.name()
                );
                assert!(
                    reported <= best * (1.0 + 1e-9),
                    "case {case} tau {} {}: reported {reported} > local {best}",
                    pose.tau,
                    kind.name()
                );
            }
        }
    }
}
