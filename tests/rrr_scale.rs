//! 3-RRR distances are equivariant under scaling: a design and its motion scaled by `f`
//! (every length and position times `f`, orientations unchanged) give every distance
//! times `f`, with no lost paths and never more accounted paths than expected.
use singdist::mechanism::rpr::{AnalyticMotion, Motion, MotionCoordinate};
use singdist::mechanism::rrr::*;
use singdist::pipeline::rrr::curve::*;
use singdist::problem::rrr::RrrSubProblem;

mod rrr_support;
use rrr_support::{curve_at, trajectories};

fn scaled_coordinate(c: &MotionCoordinate, factor: f64) -> MotionCoordinate {
    let mut out = c.clone();
    out.polynomial.iter_mut().for_each(|v| *v *= factor);
    out.cosines.iter_mut().for_each(|t| t.amplitude *= factor);
    out
}

fn scaled(trajectory: &RrrTrajectory, factor: f64) -> RrrTrajectory {
    let d = trajectory.design();
    let design = RrrDesign::new(
        d.base().map(|p| p * factor),
        d.proximal().map(|v| v * factor),
        d.distal().map(|v| v * factor),
        d.platform().map(|p| p * factor),
    )
    .expect("scaled design");
    let Motion::Analytic(m) = trajectory.motion() else {
        panic!("analytic motions only")
    };
    let motion = Motion::Analytic(AnalyticMotion {
        tau_range: m.tau_range,
        x: scaled_coordinate(&m.x, factor),
        y: scaled_coordinate(&m.y, factor),
        phi: m.phi.clone(),
    });
    RrrTrajectory::new(design, trajectory.initial_modes(), motion).expect("scaled trajectory")
}

fn distances(curve: &RrrCurveResult) -> Vec<f64> {
    curve
        .poses
        .iter()
        .flat_map(|p| {
            RrrSubProblem::ALL.map(|kind| {
                p.subproblems[&kind.short_name()]
                    .distance
                    .expect("a real critical point")
            })
        })
        .collect()
}

fn assert_complete(curve: &RrrCurveResult, label: &str) {
    assert!(curve.failures.is_empty(), "{label}: {:?}", curve.failures);
    for pose in &curve.poses {
        for result in pose.subproblems.values() {
            assert_eq!(result.accounted_paths, result.expected_endpoints, "{label}");
        }
    }
}

#[test]
fn distances_scale_with_the_design() {
    // τ ≈ 1.49 and 4.26 are the poses where the unnormalised pipeline went wrong at
    // size 0.01.
    let taus = [1.49, 4.26];
    for (t, trajectory) in trajectories().iter().enumerate() {
        let reference = curve_at(trajectory, &taus);
        assert_complete(&reference, &format!("design {t}"));
        let expected = distances(&reference);
        for factor in [0.01, 100.0] {
            let curve = curve_at(&scaled(trajectory, factor), &taus);
            let label = format!("design {t} scaled by {factor}");
            assert_complete(&curve, &label);
            for (got, want) in distances(&curve).iter().zip(&expected) {
                let relative = (got - factor * want).abs() / (factor * want).max(1e-300);
                assert!(
                    relative <= 1e-9,
                    "{label}: {got} vs {} (relative {relative:e})",
                    factor * want
                );
            }
        }
    }
}

/// The seed stage keeps at most the generic count of distinct solutions, and a count
/// below it counts only when two seed points agree.
#[test]
fn seed_counts_never_exceed_the_generic_count() {
    use singdist::C64;
    use singdist::pipeline::rrr::seed::{distinct_solutions, seed_count_confirmed};
    let point = |v: f64| vec![C64::new(v, 0.5), C64::new(-v, 0.0)];
    // Three distinct points, one repeated to rounding, one beyond the limit.
    let endpoints = vec![
        point(1.0),
        point(1.0 + 1e-13),
        point(2.0),
        point(3.0),
        point(4.0),
    ];
    assert_eq!(distinct_solutions(endpoints.clone(), 10).len(), 4);
    assert_eq!(distinct_solutions(endpoints, 3).len(), 3);
    assert!(seed_count_confirmed(&[50], 50));
    assert!(!seed_count_confirmed(&[48], 50));
    assert!(!seed_count_confirmed(&[48, 49], 50));
    assert!(seed_count_confirmed(&[48, 49, 49], 50));
}
