//! 3-RRR distances against an independent many-start local solution of the constrained
//! problem ([`singdist::reference::rrr`]): at poses of several design classes each of
//! the four distances is ≤ the best of 200 local solutions (+1e-9 relative).
use singdist::mechanism::rrr::*;
use singdist::pipeline::rrr::curve::*;
use singdist::problem::rrr::RrrSubProblem;
use singdist::reference::rrr::reference_distance;

mod rrr_support;
use rrr_support::trajectories;

/// The shared design classes, with two poses each.
fn cases() -> Vec<(RrrTrajectory, [f64; 2])> {
    trajectories()
        .into_iter()
        .zip([[1.49, 4.26], [0.7, 3.9], [1.2, 5.0]])
        .collect()
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
