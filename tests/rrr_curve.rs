//! 3-RRR distance curves (docs/theory.md §10): zeros and sign changes at singular poses,
//! global minimality against random-start local minimisations, consistency of the reported
//! closest configurations, bad input.
use singdist::C64;
use singdist::io::load_motion;
use singdist::io::rrr::load_rrr_design;
use singdist::mechanism::rpr::{Motion, Pose, PoseList};
use singdist::mechanism::rrr::*;
use singdist::pipeline::rrr::curve::*;
use singdist::problem::rrr::RrrSubProblem;
use std::f64::consts::PI;

mod rrr_support;
use rrr_support::curve_at;

/// Lost paths are reported, never hidden (`accounted` counts finite endpoints and paths
/// classified at infinity only). Along the example motion the parallel problem has
/// critical points with a nearly collapsed distal bar (`|C_i − B_i| ≈ 1e-3`,
/// `λ ≈ 4e2 … 6e3`) next to the singular locus of the parallel-singularity hypersurface,
/// Jacobian condition 1e14 … 1e18: with double-precision residuals the tracker lost one
/// such path at 3 of the 90 example poses; with the tracker's adaptive precision
/// (double-double residuals) every path is accounted for. Any loss is a regression.
fn assert_no_lost_paths(curve: &RrrCurveResult) {
    assert!(curve.failures.is_empty(), "{:?}", curve.failures);
    for pose in &curve.poses {
        for result in pose.subproblems.values() {
            assert_eq!(result.accounted_paths, result.expected_endpoints);
            assert!(result.finite_endpoints <= result.accounted_paths);
        }
    }
}

fn value(pose: &RrrPoseResult, kind: RrrSubProblem) -> f64 {
    match kind {
        RrrSubProblem::Parallel => pose.parallel,
        RrrSubProblem::Leg(0) => pose.leg1,
        RrrSubProblem::Leg(1) => pose.leg2,
        RrrSubProblem::Leg(_) => pose.leg3,
    }
    .expect("a real critical point")
}

/// At the roots of the parallel determinant and of the leg-1 determinant along the example
/// motion (found by bisection / golden section), that curve is 0 to 1e-8 and changes sign.
#[test]
fn curves_vanish_and_change_sign_at_singular_poses() {
    let trajectory = example_trajectory();
    let grid: Vec<f64> = (0..=720)
        .map(|j| 2.0 * PI * (j as f64 + 0.5) / 721.0)
        .collect();
    let parallel_roots = parallel_singular_parameters(&trajectory, &grid);
    assert_eq!(parallel_roots.len(), 2, "{parallel_roots:?}");
    let leg_root = trajectory.leg_crossings()[0][0];
    for (kind, root, at_root) in [
        (RrrSubProblem::Parallel, parallel_roots[0], true),
        (RrrSubProblem::Parallel, parallel_roots[1], true),
        // At the leg-1 root C_1 = O_1 exactly (folded leg, elbow direction undefined):
        // only its neighbourhood is evaluated.
        (RrrSubProblem::Leg(0), leg_root, false),
    ] {
        let mut taus = vec![root - 0.05, root - 1e-9, root + 1e-9, root + 0.05];
        if at_root {
            taus.push(root);
        }
        let curve = curve_at(&trajectory, &taus);
        assert_no_lost_paths(&curve);
        let v: Vec<f64> = curve.poses.iter().map(|p| value(p, kind)).collect();
        println!("{} at {root}: {v:?}", kind.name());
        assert!(v[1].abs() < 1e-8 && v[2].abs() < 1e-8, "{v:?}");
        assert!(v[1] * v[2] < 0.0, "no sign change across the root: {v:?}");
        assert!(
            v[0] * v[3] < 0.0 && v[0].abs() > 1e-4 && v[3].abs() > 1e-4,
            "{v:?}"
        );
        assert_eq!(v[0].signum(), v[1].signum());
        if at_root {
            assert!(v[4].abs() < 1e-8, "{v:?}");
            // The overall distance is the smallest |value| of the four.
            assert!(curve.poses[4].distance.unwrap() <= v[4].abs());
        }
    }
}

/// `D²(K, K + d) = ½ dᵀ H d`: the constant Hessian, exact from second differences.
fn metric_hessian(k: &[f64; 18]) -> [[f64; 18]; 18] {
    let q = |d: &[f64; 18]| {
        let moved: [f64; 18] = std::array::from_fn(|j| k[j] + d[j]);
        distance_sq(k, &moved)
    };
    let unit = |j: usize| -> [f64; 18] { std::array::from_fn(|i| if i == j { 1.0 } else { 0.0 }) };
    std::array::from_fn(|j| {
        std::array::from_fn(|l| {
            let both: [f64; 18] = std::array::from_fn(|i| unit(j)[i] + unit(l)[i]);
            q(&both) - q(&unit(j)) - q(&unit(l))
        })
    })
}

/// Gradient of the constraint by complex-step differentiation (exact to rounding).
fn constraint_gradient(kind: RrrSubProblem, x: &[f64; 18]) -> [f64; 18] {
    let h = 1e-30;
    std::array::from_fn(|j| {
        let z: [C64; 18] = std::array::from_fn(|i| C64::new(x[i], if i == j { h } else { 0.0 }));
        kind.constraint(&z).im / h
    })
}

fn project(kind: RrrSubProblem, x: &mut [f64; 18]) -> bool {
    for _ in 0..100 {
        let c = kind.constraint(&*x);
        if c.abs() < 1e-15 {
            return true;
        }
        let n = constraint_gradient(kind, x);
        let nn: f64 = n.iter().map(|v| v * v).sum();
        if nn < 1e-300 {
            return false;
        }
        for j in 0..18 {
            x[j] -= c * n[j] / nn;
        }
    }
    kind.constraint(&*x).abs() < 1e-13
}

/// Projected gradient descent of `D²(K, ·)` on `C = 0` from `start` (independent of the
/// homotopy machinery); returns `D` at the end, `None` if the projection failed.
fn local_minimum(
    kind: RrrSubProblem,
    k: &[f64; 18],
    hessian: &[[f64; 18]; 18],
    start: [f64; 18],
) -> Option<f64> {
    let mut x = start;
    if !project(kind, &mut x) {
        return None;
    }
    let mut value = distance_sq(k, &x);
    let mut step = 1.0;
    for _ in 0..4000 {
        let d: [f64; 18] = std::array::from_fn(|j| x[j] - k[j]);
        let g: [f64; 18] = std::array::from_fn(|j| (0..18).map(|l| hessian[j][l] * d[l]).sum());
        let n = constraint_gradient(kind, &x);
        let nn: f64 = n.iter().map(|v| v * v).sum();
        let gn: f64 = g.iter().zip(&n).map(|(a, b)| a * b).sum();
        let tangent: [f64; 18] = std::array::from_fn(|j| g[j] - gn / nn * n[j]);
        let norm = tangent.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm < 1e-14 || step < 1e-16 {
            break;
        }
        let mut trial: [f64; 18] = std::array::from_fn(|j| x[j] - step * tangent[j]);
        if project(kind, &mut trial) && distance_sq(k, &trial) < value {
            x = trial;
            value = distance_sq(k, &x);
            step *= 1.5;
        } else {
            step *= 0.5;
        }
    }
    Some(value.max(0.0).sqrt())
}

/// For random poses of the example, each reported distance is ≤ the best of many
/// random-start local minimisations (+1e-9); the reported closest configuration satisfies
/// its constraint to 1e-10 and reproduces the reported distance.
#[test]
fn distances_are_not_beaten_by_local_minimisation() {
    let trajectory = example_trajectory();
    let mut rng = singdist::random::seeded(77);
    let taus: Vec<f64> = (0..3)
        .map(|_| singdist::random::uniform(&mut rng, 0.0, 2.0 * PI))
        .collect();
    let curve = curve_at(&trajectory, &taus);
    assert!(curve.failures.is_empty(), "{:?}", curve.failures);
    for pose in &curve.poses {
        let k = trajectory.configuration(pose.tau).unwrap().to_array();
        let hessian = metric_hessian(&k);
        for kind in RrrSubProblem::ALL {
            let result = &pose.subproblems[&kind.short_name()];
            let reported = result.distance.expect("a real critical point");
            assert_eq!(value(pose, kind).abs(), reported);
            assert_eq!(
                value(pose, kind).signum(),
                if kind.constraint(&k) < 0.0 { -1.0 } else { 1.0 }
            );
            let closest = result.closest.unwrap();
            let constraint = kind.constraint(&closest);
            assert!(
                constraint.abs() < 1e-10,
                "{}: C(K′) = {constraint:e}",
                kind.name()
            );
            assert!((distance(&k, &closest) - reported).abs() < 1e-12);
            let mut best = f64::INFINITY;
            for start in 0..30 {
                let spread = [0.02, 0.1, 0.3][start % 3];
                let x0: [f64; 18] =
                    std::array::from_fn(|j| k[j] + spread * singdist::random::normal(&mut rng));
                if let Some(d) = local_minimum(kind, &k, &hessian, x0) {
                    best = best.min(d);
                }
            }
            println!(
                "tau {:.4} {}: reported {reported:.12} best local {best:.12}",
                pose.tau,
                kind.name()
            );
            assert!(
                reported <= best + 1e-9,
                "{}: reported {reported} > local {best}",
                kind.name()
            );
        }
        let overall = pose.distance.unwrap();
        let smallest = [pose.parallel, pose.leg1, pose.leg2, pose.leg3]
            .iter()
            .map(|v| v.unwrap().abs())
            .fold(f64::INFINITY, f64::min);
        assert_eq!(overall, smallest);
        assert!((0.0..=1.0).contains(&pose.parallel_determinant_abs_scaled));
    }
}

#[test]
fn example_files_match_the_built_in_example() {
    let root = env!("CARGO_MANIFEST_DIR");
    let (design, modes) =
        load_rrr_design(format!("{root}/systems/rrr_example_design.json")).unwrap();
    assert_eq!(modes, EXAMPLE_MODES);
    let built_in = example_design();
    for i in 0..3 {
        assert!((design.base()[i] - built_in.base()[i]).norm() < 1e-15);
        assert!((design.platform()[i] - built_in.platform()[i]).norm() < 1e-15);
        assert_eq!(design.proximal()[i], built_in.proximal()[i]);
        assert_eq!(design.distal()[i], built_in.distal()[i]);
    }
    let motion = load_motion(format!("{root}/systems/rrr_example_motion.json")).unwrap();
    for tau in [0.0, 1.0, 2.5, 6.0] {
        let (a, b) = (
            motion.pose(tau).unwrap(),
            example_motion().pose(tau).unwrap(),
        );
        assert!(
            (a.x - b.x).abs() < 1e-15 && (a.y - b.y).abs() < 1e-15 && (a.phi - b.phi).abs() < 1e-15
        );
    }
}

fn temp_file(name: &str, text: &str) -> std::path::PathBuf {
    let path =
        std::env::temp_dir().join(format!("singdist-rrr-test-{}-{name}", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn bad_input_is_an_error_naming_the_field() {
    let good = r#"{"base": [[0,1],[-0.8,-0.5],[0.8,-0.5]], "proximal": [0.8,0.8,0.8],
        "distal": [0.8,0.8,0.8], "platform": [[0,0.4],[-0.3,-0.2],[0.3,-0.2]]"#;
    let cases = [
        (
            "malformed",
            "{\"base\": [[0,1],".to_string(),
            "malformed JSON",
        ),
        (
            "missing",
            good.replace("\"distal\": [0.8,0.8,0.8],", "") + "}",
            "distal",
        ),
        (
            "modes",
            good.to_string() + ", \"working_modes\": [1, 2, 1]}",
            "working_modes[1]",
        ),
        (
            "negative",
            good.replace(
                "\"proximal\": [0.8,0.8,0.8]",
                "\"proximal\": [0.8,-0.8,0.8]",
            ) + "}",
            "proximal[1]",
        ),
        (
            "shape",
            good.replace("[-0.3,-0.2]", "[-0.3]") + "}",
            "platform[1]",
        ),
        ("unknown", good.to_string() + ", \"elbows\": 3}", "elbows"),
    ];
    for (name, text, needle) in cases {
        let path = temp_file(name, &text);
        let error = load_rrr_design(&path).expect_err(name).to_string();
        assert!(error.contains(needle), "{name}: {error}");
        let _ = std::fs::remove_file(path);
    }
    let path = temp_file("good", &(good.to_string() + "}"));
    assert!(load_rrr_design(&path).is_ok());
    let _ = std::fs::remove_file(path);
    // A motion leaving the workspace: the circle of radius 2 takes leg joints beyond reach.
    let far = circular_translation(Point::new(0.0, 0.0), 2.0, 0.0, [0.0, 2.0 * PI]);
    let error = RrrTrajectory::new(example_design(), EXAMPLE_MODES, far).unwrap_err();
    assert!(
        matches!(error, TrajectoryError::OutsideWorkspace { .. }),
        "{error}"
    );
    assert!(error.to_string().contains("leg"), "{error}");
    // An unreachable pose in an explicit pose list.
    let list = Motion::Poses(PoseList {
        poses: vec![Pose::new(0.0, 0.0, 0.0), Pose::new(5.0, 0.0, 0.0)],
    });
    assert!(RrrTrajectory::new(example_design(), EXAMPLE_MODES, list).is_err());
    let nan = Motion::Poses(PoseList {
        poses: vec![Pose::new(f64::NAN, 0.0, 0.0)],
    });
    assert!(RrrTrajectory::new(example_design(), EXAMPLE_MODES, nan).is_err());
    // No poses, and τ outside the workspace at evaluation time.
    let trajectory = example_trajectory();
    let options = RrrCurveOptions::default();
    assert!(compute_rrr_curve(&trajectory, 0, &options, &default_rrr_start_solutions).is_err());
    assert!(
        compute_rrr_curve_at(&trajectory, &[], &options, &default_rrr_start_solutions).is_err()
    );
}

/// Pose by pose, `a` and `b` have the same counts of real and finite critical points
/// per sub-problem and the same distances to 1e-9 relative.
fn assert_same_critical_points(a: &RrrCurveResult, b: &RrrCurveResult) {
    for (p, q) in a.poses.iter().zip(&b.poses) {
        for (name, x) in &p.subproblems {
            let y = &q.subproblems[name];
            assert_eq!(x.real_critical_points, y.real_critical_points, "{name}");
            assert_eq!(x.finite_endpoints, y.finite_endpoints, "{name}");
            let (dx, dy) = (x.distance.expect("real"), y.distance.expect("real"));
            assert!(
                (dx - dy).abs() <= 1e-9 * dx.abs().max(1e-12),
                "pose {} {name}: {dx} vs {dy}",
                p.index
            );
        }
    }
}

/// Chained poses (each from its neighbour's critical points, by pose-to-pose paths or
/// by Newton jumps: critical points extrapolated from the preceding poses and
/// corrected at the pose) and poses solved from the seed (along the complexified
/// motion) find the same critical points, on the three design classes of `rrr_support::trajectories`: equal counts,
/// distances equal to 1e-9 relative, and the chained runs lose no path; the jumps
/// track fewer paths (they do replace paths).
#[test]
fn chained_poses_equal_poses_from_the_seed() {
    for trajectory in rrr_support::trajectories() {
        let [lo, hi] = trajectory.motion().tau_range();
        let taus: Vec<f64> = (0..24)
            .map(|j| lo + (hi - lo) * (j as f64 + 0.5) / 24.0)
            .collect();
        let solve = |chain_length, jump| {
            let options = RrrCurveOptions {
                chain_length,
                jump,
                // Every pose from the seed along the motion; chained poses take the
                // straight seed route.
                motion_route: chain_length == 1,
                ..RrrCurveOptions::default()
            };
            compute_rrr_curve_at(&trajectory, &taus, &options, &default_rrr_start_solutions)
                .expect("curve")
        };
        let from_seed = solve(1, false);
        let (paths, jumps) = (solve(8, false), solve(8, true));
        for chained in [&paths, &jumps] {
            assert_no_lost_paths(chained);
            assert_same_critical_points(&from_seed, chained);
        }
        assert!(
            jumps.paths_tracked < paths.paths_tracked,
            "{} paths with jumps, {} without",
            jumps.paths_tracked,
            paths.paths_tracked
        );
    }
}

/// A scattered pose list (points of the example's circle in random order) is chained
/// in nearest-neighbour order: the same counts and distances (1e-9 relative) as every
/// pose from the seed, no lost path, and the poses reported in their own order.
#[test]
fn scattered_pose_lists_chain_in_nearest_neighbour_order() {
    let mut rng = singdist::random::seeded(17);
    let poses: Vec<Pose> = (0..16)
        .map(|_| {
            let t = singdist::random::uniform(&mut rng, 0.0, 2.0 * PI);
            Pose::new(
                0.15 + 0.25 * t.cos(),
                0.4 + 0.25 * (t - PI / 2.0).cos(),
                0.0,
            )
        })
        .collect();
    let list = Motion::Poses(PoseList { poses });
    let trajectory = RrrTrajectory::new(example_design(), EXAMPLE_MODES, list).unwrap();
    let solve = |chain_length| {
        let options = RrrCurveOptions {
            chain_length,
            ..RrrCurveOptions::default()
        };
        compute_rrr_curve(&trajectory, 0, &options, &default_rrr_start_solutions).expect("curve")
    };
    let (from_seed, chained) = (solve(1), solve(1000));
    assert_no_lost_paths(&chained);
    let indices: Vec<usize> = chained.poses.iter().map(|p| p.index).collect();
    assert_eq!(indices, (0..16).collect::<Vec<_>>());
    assert_same_critical_points(&from_seed, &chained);
}

/// Results do not depend on the number of worker threads (every path is a pure function
/// of its inputs and seeded streams).
#[test]
fn results_are_identical_for_one_and_two_threads() {
    let trajectory = example_trajectory();
    let taus = [0.3, 1.9, 4.4];
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| curve_at(&trajectory, &taus))
    };
    assert_eq!(run(1), run(2));
}

/// An invalid design file's error states its cause once, also when the error chain is
/// printed (message, then each source).
#[test]
fn design_file_errors_state_their_cause_once() {
    let path = temp_file(
        "rrr_negative_proximal.json",
        r#"{"base": [[0, 1], [-0.866, -0.5], [0.866, -0.5]], "proximal": [0.8, -0.8, 0.8],
            "distal": [0.8, 0.8, 0.8], "platform": [[0, 0.4], [-0.35, -0.2], [0.35, -0.2]]}"#,
    );
    let error = load_rrr_design(&path).expect_err("negative proximal length");
    let mut chain = error.to_string();
    let mut source = std::error::Error::source(&error);
    while let Some(cause) = source {
        chain.push_str(&format!(": {cause}"));
        source = cause.source();
    }
    assert_eq!(
        chain.matches("proximal[1] must be positive").count(),
        1,
        "{chain}"
    );
    assert!(chain.contains("rrr_negative_proximal.json"), "{chain}");
}
