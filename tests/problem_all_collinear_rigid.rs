//! All six points on one line with a rigid part whose anchors are collinear (Kapilavai and
//! Nawratil, Thm 3; docs/theory.md §5.3): the pipeline's all-collinear distance equals an
//! independent brute force over the line direction, the metric's distance is the minimum
//! over its sub-problems, and the sub-problem is reported as not applicable exactly when
//! a rigid part's anchors are not collinear.

use singdist::mechanism::rpr::{Design, Motion, Pose, PoseList, example_design};
use singdist::metric::{Metric, Part};
use singdist::pipeline::curve::{CurveOptions, compute_curve, default_start_solutions};
use singdist::problem::{LagrangeProblem, ProblemId, SubProblem};
use std::f64::consts::PI;

/// Signed offsets `(0, s2, s3)` of collinear anchors along their line, from anchor 1
/// in the direction of anchor 2 (computed here from the points, not by the library).
fn line_offsets(points: &[[f64; 2]; 3]) -> [f64; 3] {
    let e = [points[1][0] - points[0][0], points[1][1] - points[0][1]];
    let length = (e[0] * e[0] + e[1] * e[1]).sqrt();
    let d = [points[2][0] - points[0][0], points[2][1] - points[0][1]];
    [0.0, length, (d[0] * e[0] + d[1] * e[1]) / length]
}

/// Brute force of the all-collinear sub-problem: for a line direction `w(θ)` (and, for
/// a rigid platform on a rigid base, its orientation `σ = ±1`), `K′` is affine in the
/// unknowns `z` (the line's point `q = a₁′` and the free offsets), so `D²(K, K′(z))` is
/// a quadratic whose gradient and Hessian are recovered exactly from values
/// (polarisation) and minimised by one linear solve; the minimum over θ is found on a
/// fine grid and refined by golden-section search. Returns the minimal distance per
/// orientation `σ` (one entry unless both parts are rigid).
fn brute_force(metric: Metric, design: &Design, k: &[f64; 12]) -> Vec<f64> {
    let base_offsets = line_offsets(design.base());
    let platform_offsets = line_offsets(design.platform());
    let orientations: &[f64] = if metric.base == Part::Rigid && metric.platform == Part::Rigid {
        &[1.0, -1.0]
    } else {
        &[1.0]
    };
    let mut per_orientation = Vec::new();
    for &sigma in orientations {
        let mut best = f64::INFINITY;
        // K′ for direction θ and unknowns z = (qx, qy, free offsets…).
        let configuration = |theta: f64, z: &[f64]| -> [f64; 12] {
            let w = [theta.cos(), theta.sin()];
            let mut free = z[2..].iter();
            let mut offsets = [0.0; 6];
            if metric.base == Part::Rigid {
                offsets[1] = base_offsets[1];
                offsets[2] = base_offsets[2];
            } else {
                offsets[1] = *free.next().unwrap();
                offsets[2] = *free.next().unwrap();
            }
            if metric.platform == Part::Rigid {
                let shift = *free.next().unwrap();
                for j in 0..3 {
                    offsets[3 + j] = shift + sigma * platform_offsets[j];
                }
            } else {
                for offset in &mut offsets[3..] {
                    *offset = *free.next().unwrap();
                }
            }
            let mut out = [0.0; 12];
            for j in 0..6 {
                out[2 * j] = z[0] + offsets[j] * w[0];
                out[2 * j + 1] = z[1] + offsets[j] * w[1];
            }
            out
        };
        let unknowns = 2
            + if metric.base == Part::Rigid { 0 } else { 2 }
            + if metric.platform == Part::Rigid { 1 } else { 3 };
        let minimum_at = |theta: f64| -> f64 {
            let f = |z: &[f64]| metric.distance_sq(k, &configuration(theta, z));
            let zero = vec![0.0; unknowns];
            let unit = |i: usize, s: f64| {
                let mut z = zero.clone();
                z[i] = s;
                z
            };
            let f0 = f(&zero);
            let plus: Vec<f64> = (0..unknowns).map(|i| f(&unit(i, 1.0))).collect();
            let minus: Vec<f64> = (0..unknowns).map(|i| f(&unit(i, -1.0))).collect();
            let gradient = nalgebra::DVector::from_fn(unknowns, |i, _| 0.5 * (plus[i] - minus[i]));
            let mut hessian = nalgebra::DMatrix::zeros(unknowns, unknowns);
            for i in 0..unknowns {
                hessian[(i, i)] = plus[i] + minus[i] - 2.0 * f0;
            }
            for i in 0..unknowns {
                for j in 0..i {
                    let mut z = unit(i, 1.0);
                    z[j] = 1.0;
                    let value = f(&z)
                        - f0
                        - gradient[i]
                        - gradient[j]
                        - 0.5 * (hessian[(i, i)] + hessian[(j, j)]);
                    hessian[(i, j)] = value;
                    hessian[(j, i)] = value;
                }
            }
            let step = hessian
                .clone()
                .cholesky()
                .expect("the cost is strictly convex in q and the offsets")
                .solve(&(-gradient));
            f(step.as_slice())
        };
        const GRID: usize = 3600;
        let values: Vec<f64> = (0..GRID)
            .map(|i| minimum_at(2.0 * PI * i as f64 / GRID as f64))
            .collect();
        for i in 0..GRID {
            let (previous, next) = (values[(i + GRID - 1) % GRID], values[(i + 1) % GRID]);
            if values[i] > previous || values[i] > next {
                continue;
            }
            let step = 2.0 * PI / GRID as f64;
            let (mut lo, mut hi) = ((i as f64 - 1.0) * step, (i as f64 + 1.0) * step);
            let ratio = (5.0f64.sqrt() - 1.0) / 2.0;
            for _ in 0..200 {
                if hi - lo < 1e-14 {
                    break;
                }
                let a = hi - ratio * (hi - lo);
                let b = lo + ratio * (hi - lo);
                if minimum_at(a) < minimum_at(b) {
                    hi = b;
                } else {
                    lo = a;
                }
            }
            best = best.min(minimum_at(0.5 * (lo + hi)));
        }
        per_orientation.push(best.max(0.0).sqrt());
    }
    per_orientation
}

fn design(base: [[f64; 2]; 3], platform: [[f64; 2]; 3]) -> Design {
    Design::new(base, platform).expect("a valid design")
}

/// A collinear part: anchors `p1`, `p1 + e`, `p1 + u e`.
fn collinear(p1: [f64; 2], e: [f64; 2], u: f64) -> [[f64; 2]; 3] {
    [
        p1,
        [p1[0] + e[0], p1[1] + e[1]],
        [p1[0] + u * e[0], p1[1] + u * e[1]],
    ]
}

#[test]
fn all_collinear_with_collinear_rigid_parts_matches_brute_force() {
    let triangle = [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]];
    let base_line = collinear([1.0, 0.5], [8.0, 2.0], -0.4);
    let platform_line = collinear([0.0, 0.0], [2.5, 0.5], 1.6);
    let cases = [
        ("plate/rigid", design(base_line, triangle)),
        (
            "rigid/plate",
            design(*example_design().base(), platform_line),
        ),
        ("rigid/rigid", design(base_line, platform_line)),
    ];
    // The third pose turns the platform's anchor line against the base's (φ ≈ π), so
    // for rigid/rigid the reversed orientation σ = −1 is the closer one there.
    let poses = vec![
        Pose::new(4.0, 3.0, 0.3),
        Pose::new(3.0, 5.0, -1.1),
        Pose::new(4.0, 3.0, 3.0),
    ];
    let mut reversed_orientation_wins = false;
    let options = CurveOptions::default();
    for (name, design) in &cases {
        let metric: Metric = name.parse().unwrap();
        let motion = Motion::Poses(PoseList {
            poses: poses.clone(),
        });
        let curve = compute_curve(
            design,
            &motion,
            poses.len(),
            &[metric],
            &options,
            &default_start_solutions,
            &|_| {},
        )
        .unwrap();
        assert!(curve.not_applicable.is_empty(), "{name}: {curve:?}");
        // Lost paths are allowed here: for a real K the cost along the line direction is
        // a degree-2 trigonometric polynomial whose second harmonic may be small, and
        // then a complex-conjugate pair of critical points is very large (|w| ~ 50 at
        // the second pose of plate/rigid); the real ones, which give the distance, are
        // checked against the brute force below.
        for (pose, result) in poses.iter().zip(&curve.poses) {
            let k = design.configuration(*pose).to_array();
            let reported = &result.metrics[name.to_string().as_str()];
            let sub = &reported.subproblems["all-collinear"];
            let distance = sub.distance.expect("a real critical point exists");
            let orientations = brute_force(metric, design, &k);
            let expected = orientations.iter().copied().fold(f64::INFINITY, f64::min);
            reversed_orientation_wins |=
                orientations.len() == 2 && orientations[1] < orientations[0];
            assert!(
                (distance - expected).abs() < 1e-8,
                "{name} at {pose:?}: pipeline {distance} vs brute force {expected}"
            );
            // The closest configuration is collinear and moves the rigid parts rigidly.
            let closest = sub.closest.unwrap();
            assert!((metric.distance(&k, &closest) - distance).abs() < 1e-12);
            let cross = |j: usize, l: usize| {
                let (x0, y0) = (closest[0], closest[1]);
                (closest[2 * j] - x0) * (closest[2 * l + 1] - y0)
                    - (closest[2 * j + 1] - y0) * (closest[2 * l] - x0)
            };
            for j in 1..6 {
                assert!(cross(1, j).abs() < 1e-8 * (1.0 + distance), "{name}");
            }
            for (part, points, first) in [
                (metric.base, *design.base(), 0),
                (metric.platform, *design.platform(), 6),
            ] {
                if part != Part::Rigid {
                    continue;
                }
                for (j, l) in [(0, 1), (0, 2), (1, 2)] {
                    let moved = ((closest[first + 2 * j] - closest[first + 2 * l]).powi(2)
                        + (closest[first + 2 * j + 1] - closest[first + 2 * l + 1]).powi(2))
                    .sqrt();
                    let original = ((points[j][0] - points[l][0]).powi(2)
                        + (points[j][1] - points[l][1]).powi(2))
                    .sqrt();
                    assert!(
                        (moved - original).abs() < 1e-9,
                        "{name}: rigid part deformed"
                    );
                }
            }
            // The metric's distance is the minimum over its sub-problems.
            for (sub_name, other) in &reported.subproblems {
                if let Some(d) = other.distance {
                    assert!(reported.distance <= d, "{name}: {sub_name}");
                }
            }
            assert!(
                reported
                    .subproblems
                    .values()
                    .any(|s| s.distance == Some(reported.distance))
            );
        }
    }
    assert!(
        reversed_orientation_wins,
        "rigid/rigid: no pose where the orientation sigma = -1 is the closer one"
    );
}

#[test]
fn all_collinear_is_not_applicable_when_rigid_anchors_are_not_collinear() {
    let base_line = collinear([1.0, 0.5], [8.0, 2.0], -0.4);
    let options = CurveOptions::default();
    let motion = Motion::Poses(PoseList {
        poses: vec![Pose::new(4.0, 3.0, 0.3)],
    });
    // Collinear base, triangular platform: plate/rigid has it, rigid/plate and
    // rigid/rigid do not (their platform is rigid and not collinear).
    let design = design(base_line, *example_design().platform());
    let metrics: Vec<Metric> = ["plate/rigid", "rigid/plate", "rigid/rigid"]
        .iter()
        .map(|m| m.parse().unwrap())
        .collect();
    let tilted = collinear([1.0, 0.5], [8.0, 2.0], -0.4);
    let mut off_line = tilted;
    off_line[2][1] += 1e-6;
    for (base, applicable) in [(tilted, true), (off_line, false)] {
        let design = self::design(base, *example_design().platform());
        let id = ProblemId {
            metric: metrics[0],
            subproblem: SubProblem::AllCollinear,
        };
        assert_eq!(
            LagrangeProblem::check_applicable(id, &design).is_ok(),
            applicable
        );
    }
    for (metric, applicable) in metrics.iter().zip([true, false, false]) {
        let id = ProblemId {
            metric: *metric,
            subproblem: SubProblem::AllCollinear,
        };
        let check = LagrangeProblem::check_applicable(id, &design);
        assert_eq!(check.is_ok(), applicable, "{metric}");
    }
    // The example design has no collinear part: the pipeline lists it as not
    // applicable and the metric is still computed from its other sub-problems.
    let curve = compute_curve(
        &example_design(),
        &motion,
        1,
        &metrics[..1],
        &options,
        &default_start_solutions,
        &|_| {},
    )
    .unwrap();
    assert_eq!(curve.not_applicable, ["plate/rigid:all-collinear"]);
    assert!(curve.poses[0].metrics.contains_key("plate/rigid"));
}
