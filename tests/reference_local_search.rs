//! The independent reference: jets, the local search and the design matrix.

use singdist::mechanism::rpr::{Pose, example_design, example_motion, singularity_polynomial};
use singdist::metric::{Metric, Part};
use singdist::reference::designs::{CLASS_NAMES, design_case, design_matrix};
use singdist::reference::jet::{Jet, Real};
use singdist::reference::local_search::{
    Constraint, FEASIBILITY_TOLERANCE, ReferenceOptions, configuration_size, feasibility,
    pedal_points, reference_distance, reference_distances, reference_subproblem,
};

fn options(starts: usize) -> ReferenceOptions {
    ReferenceOptions {
        starts,
        ..ReferenceOptions::default()
    }
}

#[test]
fn jet_product_and_trigonometry_match_hand_derivatives() {
    // f(x, y) = x² y + sin(x y) at (0.7, −1.3).
    let (x0, y0) = (0.7, -1.3);
    let x = Jet::variable(x0, 0);
    let y = Jet::variable(y0, 1);
    let f = x * x * y + (x * y).sin() - (x - y).cos();
    let (c, s) = ((x0 * y0).cos(), (x0 * y0).sin());
    let (cm, sm) = ((x0 - y0).cos(), (x0 - y0).sin());
    assert!((f.value - (x0 * x0 * y0 + s - cm)).abs() < 1e-15);
    assert!((f.gradient[0] - (2.0 * x0 * y0 + y0 * c + sm)).abs() < 1e-14);
    assert!((f.gradient[1] - (x0 * x0 + x0 * c - sm)).abs() < 1e-14);
    assert!((f.hessian_entry(0, 0) - (2.0 * y0 - y0 * y0 * s + cm)).abs() < 1e-14);
    assert!((f.hessian_entry(1, 0) - (2.0 * x0 + c - x0 * y0 * s - cm)).abs() < 1e-14);
    assert!((f.hessian_entry(1, 1) - (-x0 * x0 * s + cm)).abs() < 1e-14);
    assert_eq!(f.hessian_entry(0, 2), 0.0);
}

/// The homotopy pipeline's distances at pose (4, 3, 0.3) of the built-in example
/// (`singdist distance --pose 4,3,0.3 --metric all --json`, seed 1), an independent
/// method: the reference must agree to 1e-9.
#[test]
fn agrees_with_the_homotopy_on_the_example() {
    let expected = [
        ("plate/plate", 0.22165663116802672),
        ("plate/bars", 0.2078259481588014),
        ("plate/rigid", 0.24332276584986462),
        ("bars/plate", 0.2696532513746351),
        ("bars/bars", 0.26080984616992287),
        ("bars/rigid", 0.2882722774097439),
        ("rigid/plate", 0.239099649734978),
        ("rigid/bars", 0.21905905799178485),
        ("rigid/rigid", 0.26200834226658387),
    ];
    let design = example_design();
    let k = design.configuration(Pose::new(4.0, 3.0, 0.3)).to_array();
    let results = reference_distances(&design, &k, &Metric::all(), &ReferenceOptions::default());
    for (reference, (name, distance)) in results.iter().zip(expected) {
        assert_eq!(reference.metric.name(), name);
        let rel = (reference.distance - distance).abs() / distance;
        assert!(rel < 1e-9, "{name}: {} vs {distance}", reference.distance);
        assert_eq!(reference.constraint, Constraint::Singularity, "{name}");
        for sub in &reference.subproblems {
            let best = sub.best.as_ref().expect("feasible end");
            assert!(sub.converged > 0, "{name}:{}", sub.constraint);
            // The reported distance is D(K, K′) recomputed from the reported K′ …
            assert_eq!(best.distance, reference.metric.distance(&k, &best.closest));
            // … and K′ satisfies its constraint and rigidity.
            let f = feasibility(&k, reference.metric, sub.constraint, &best.closest);
            assert!(
                f.worst() <= FEASIBILITY_TOLERANCE,
                "{name}:{}: {f:?}",
                sub.constraint
            );
        }
    }
    // Metrics with a rigid part whose anchors are not collinear: no all-collinear.
    assert_eq!(results[2].not_applicable, vec![Constraint::AllCollinear]);
    assert!(results[0].subproblem(Constraint::AllCollinear).is_some());
}

#[test]
fn a_singular_configuration_has_distance_zero() {
    let design = example_design();
    let motion = example_motion();
    // Bisect the sign change of S near τ ≈ −0.086.
    let s_of = |tau: f64| {
        design
            .configuration(motion.pose(tau).expect("analytic"))
            .singularity()
    };
    let (mut lo, mut hi) = (-0.5, 0.3);
    assert!(s_of(lo) * s_of(hi) < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (s_of(mid) < 0.0) == (s_of(lo) < 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let k = design
        .configuration(motion.pose(lo).expect("analytic"))
        .to_array();
    let size = configuration_size(&k);
    for reference in reference_distances(&design, &k, &Metric::all(), &options(8)) {
        assert!(
            reference.distance <= 1e-12 * size,
            "{}: {}",
            reference.metric,
            reference.distance
        );
    }
}

#[test]
fn pedal_points_are_the_closest_collinear_platform_for_bars_plate_and_bars_bars() {
    let design = example_design();
    let mut distances = Vec::new();
    for metric in [
        Metric::new(Part::Bars, Part::Plate),
        Metric::new(Part::Bars, Part::Bars),
    ] {
        for pose in [Pose::new(4.0, 3.0, 0.3), Pose::new(5.5, 2.0, -1.1)] {
            let k = design.configuration(pose).to_array();
            let sub = reference_subproblem(&k, metric, Constraint::CollinearPlatform, &options(24))
                .expect("applies");
            let best = sub.best.expect("feasible");
            let b = [[k[6], k[7]], [k[8], k[9]], [k[10], k[11]]];
            let pedal = pedal_points(&b);
            for (i, point) in pedal.iter().enumerate() {
                for (axis, value) in point.iter().enumerate() {
                    let error = (best.closest[6 + 2 * i + axis] - value).abs();
                    assert!(error < 1e-8, "{metric} {pose:?}: b{i}: {error}");
                }
            }
            distances.push(best.distance);
        }
        // The distance does not depend on the pose.
        let n = distances.len();
        assert!((distances[n - 1] - distances[n - 2]).abs() < 1e-10 * distances[n - 1]);
    }
}

#[test]
fn feasibility_detects_a_perturbed_configuration() {
    let design = example_design();
    let k = design.configuration(Pose::new(4.0, 3.0, 0.3)).to_array();
    let metric = Metric::new(Part::Rigid, Part::Rigid);
    let reference = reference_distance(&design, &k, metric, &options(8));
    let mut moved = reference.closest;
    assert!(feasibility(&k, metric, Constraint::Singularity, &moved).worst() <= 1e-12);
    // Off the singularity variety.
    moved[6] += 1e-3;
    let f = feasibility(&k, metric, Constraint::Singularity, &moved);
    assert!(f.constraint > 1e-6 && f.rigidity > 1e-6, "{f:?}");
    // A reflected platform is not a proper motion.
    let mut mirrored = k;
    for i in 0..3 {
        mirrored[6 + 2 * i + 1] = -k[6 + 2 * i + 1];
    }
    assert!(feasibility(&k, metric, Constraint::Singularity, &mirrored).rigidity > 1e-3);
}

#[test]
fn design_matrix_is_deterministic_and_every_motion_crosses_the_singularity() {
    let cases = design_matrix(1);
    assert_eq!(cases.len(), CLASS_NAMES.len());
    assert_eq!(cases, design_matrix(1));
    assert_ne!(cases, design_matrix(2));
    for case in &cases {
        assert!(!case.crossings.is_empty(), "{}: no crossing", case.name);
        // Every class is a valid design (two coincident anchors included).
        let design = case.design().expect("a valid design");
        let motion = case.analytic_motion();
        for &tau in &case.crossings {
            let s = |t: f64| {
                singularity_polynomial(&design.configuration(motion.pose(t).unwrap()).to_array())
            };
            assert!(
                s(tau - 1e-6) * s(tau + 1e-6) < 0.0,
                "{} at {tau}",
                case.name
            );
        }
        assert_eq!(case.scattered.len(), 8);
    }
    assert_eq!(design_case("no-such-class", 1), None);
}

#[test]
fn rigid_part_with_collinear_anchors_has_the_all_collinear_subproblem() {
    let rigid_plate = Metric::new(Part::Plate, Part::Rigid);
    for (name, applies) in [("collinear-base", true), ("nearly-collinear-base", false)] {
        let case = design_case(name, 1).expect("class");
        let design = case.design().expect("valid");
        let k = design.configuration(case.scattered[0]).to_array();
        let reference = reference_distance(&design, &k, rigid_plate, &options(16));
        assert_eq!(
            reference.subproblem(Constraint::AllCollinear).is_some(),
            applies,
            "{name}"
        );
        for sub in &reference.subproblems {
            let best = sub.best.as_ref().expect("feasible");
            let f = feasibility(&k, rigid_plate, sub.constraint, &best.closest);
            assert!(
                f.worst() <= FEASIBILITY_TOLERANCE,
                "{name}:{}",
                sub.constraint
            );
        }
    }
}

#[test]
fn jets_through_real_trait_match_values() {
    let t = Jet::variable(0.4, 3);
    assert_eq!(t.sin().value(), 0.4f64.sin());
    assert!((t.cos().gradient[3] + 0.4f64.sin()).abs() < 1e-16);
}
