//! 3-RRR model: validation errors, inverse kinematics round trip in both working modes,
//! unreachable poses, nine-point configuration (docs/theory.md §10, §11.5).

use singdist::mechanism::rrr::{
    ElbowMode, POSITIVE_MODES, Point, RrrDesign, RrrError, RrrPose, WorkingModes,
};
use singdist::random::{seeded, uniform};

mod rrr_support;
use rrr_support::modes_of;

fn random_design(rng: &mut singdist::random::SeededRng) -> RrrDesign {
    let mut p = || Point::new(uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0));
    let base = [p() * 5.0, p() * 5.0, p() * 5.0];
    let platform = [p(), p(), p()];
    let mut lengths = [0.0; 6];
    for l in lengths.iter_mut() {
        *l = uniform(rng, 1.5, 4.0);
    }
    RrrDesign::new(
        base,
        [lengths[0], lengths[1], lengths[2]],
        [lengths[3], lengths[4], lengths[5]],
        platform,
    )
    .expect("random design valid")
}

fn all_modes() -> Vec<WorkingModes> {
    let mut out = Vec::new();
    for m in 0..8 {
        let f = |bit: usize| {
            if m >> bit & 1 == 0 {
                ElbowMode::Positive
            } else {
                ElbowMode::Negative
            }
        };
        out.push([f(0), f(1), f(2)]);
    }
    out
}

#[test]
fn ik_round_trip_both_modes_and_unreachable_reported() {
    let mut rng = seeded(3);
    let mut reachable = 0;
    let mut unreachable = 0;
    for _ in 0..40 {
        let design = random_design(&mut rng);
        for _ in 0..25 {
            let pose = RrrPose::new(
                uniform(&mut rng, -6.0, 6.0),
                uniform(&mut rng, -6.0, 6.0),
                uniform(&mut rng, -3.0, 3.0),
            );
            for modes in all_modes() {
                match design.inverse_kinematics(&pose, &modes) {
                    Ok(config) => {
                        reachable += 1;
                        let c_expected = design.platform_joints(&pose);
                        for leg in 0..3 {
                            let b = config.proximal_vector(leg).norm();
                            let c = config.distal_vector(leg).norm();
                            assert!((b - design.proximal()[leg]).abs() < 1e-12, "proximal {leg}");
                            assert!((c - design.distal()[leg]).abs() < 1e-12, "distal {leg}");
                            assert!((config.platform[leg] - c_expected[leg]).norm() < 1e-12);
                            assert_eq!(config.base[leg], design.base()[leg]);
                            let det = config.leg_determinant(leg);
                            assert!(
                                det * modes[leg].sign() >= -1e-9,
                                "working mode sign: leg {leg} det {det} mode {:?}",
                                modes[leg]
                            );
                            assert!(config.theta(leg).is_finite() && config.psi(leg).is_finite());
                        }
                        // Platform joints keep the moving-frame shape.
                        let d01 = (config.platform[0] - config.platform[1]).norm();
                        let l01 = (design.platform()[0] - design.platform()[1]).norm();
                        assert!((d01 - l01).abs() < 1e-12);
                        let pts = config.points();
                        assert_eq!(pts[0], config.base[0]);
                        assert_eq!(pts[4], config.elbow[1]);
                        assert_eq!(pts[8], config.platform[2]);
                    }
                    Err(RrrError::Unreachable {
                        leg,
                        distance,
                        min_reach,
                        max_reach,
                    }) => {
                        unreachable += 1;
                        assert!(leg < 3);
                        assert!(distance > max_reach || distance < min_reach);
                        assert!(design.try_inverse_kinematics(&pose, &modes).is_none());
                    }
                    Err(other) => panic!("unexpected error {other}"),
                }
            }
        }
    }
    assert!(reachable > 500, "too few reachable poses: {reachable}");
    assert!(
        unreachable > 500,
        "too few unreachable poses: {unreachable}"
    );
}

#[test]
fn the_two_working_modes_are_mirror_images_about_line_oc() {
    let design = RrrDesign::symmetric(5.0, 1.3, 3.0, 3.5).unwrap();
    let pose = RrrPose::new(0.4, -0.3, 0.2);
    let plus = design.inverse_kinematics(&pose, &POSITIVE_MODES).unwrap();
    let minus = design
        .inverse_kinematics(&pose, &[ElbowMode::Negative; 3])
        .unwrap();
    for leg in 0..3 {
        let o = plus.base[leg];
        let u = (plus.platform[leg] - o).normalize();
        let reflect = |p: Point| {
            let v = p - o;
            o + 2.0 * u * u.dot(&v) - v
        };
        assert!((reflect(plus.elbow[leg]) - minus.elbow[leg]).norm() < 1e-12);
        assert!(plus.leg_determinant(leg) > 0.0 && minus.leg_determinant(leg) < 0.0);
    }
}

#[test]
fn stretched_leg_is_reachable_and_beyond_is_not() {
    // Leg 0 of the symmetric design points along the y axis at phi = 0:
    // |C_0 - O_0| = R - a - y, stretched when y = R - a - b - c.
    let (r, a, b, c) = (5.0, 1.0, 2.0, 2.5);
    let design = RrrDesign::symmetric(r, a, b, c).unwrap();
    let y = r - a - b - c;
    let config = design
        .inverse_kinematics(&RrrPose::new(0.0, y, 0.0), &POSITIVE_MODES)
        .expect("stretched leg reachable");
    assert!(config.leg_determinant(0).abs() < 1e-9);
    let err = design
        .inverse_kinematics(&RrrPose::new(0.0, y - 1e-6, 0.0), &POSITIVE_MODES)
        .unwrap_err();
    assert!(matches!(err, RrrError::Unreachable { leg: 0, .. }), "{err}");
}

#[test]
fn invalid_designs_and_poses_name_the_field() {
    let p = |x: f64, y: f64| Point::new(x, y);
    let base = [p(0.0, 0.0), p(4.0, 0.0), p(2.0, 3.0)];
    let platform = [p(-0.5, 0.0), p(0.5, 0.0), p(0.0, 0.7)];
    let err = RrrDesign::new(
        [p(0.0, 0.0), p(f64::NAN, 0.0), p(2.0, 3.0)],
        [1.0; 3],
        [1.0; 3],
        platform,
    )
    .unwrap_err();
    assert_eq!(err.to_string(), "base[1].x: not a finite number (NaN)");
    let err = RrrDesign::new(base, [1.0; 3], [1.0, 1.0, -2.0], platform).unwrap_err();
    assert!(err.to_string().contains("distal[2]"), "{err}");
    let err = RrrDesign::new(base, [0.0, 1.0, 1.0], [1.0; 3], platform).unwrap_err();
    assert!(err.to_string().contains("proximal[0]"), "{err}");
    let err = RrrDesign::new(
        base,
        [1.0; 3],
        [1.0; 3],
        [p(0.1, 0.1), p(0.5, 0.0), p(0.1, 0.1)],
    )
    .unwrap_err();
    assert!(
        matches!(err, RrrError::CoincidentJoints { ref first, ref second, .. } if first == "platform[0]" && second == "platform[2]"),
        "{err}"
    );
    let err = RrrDesign::symmetric(5.0, f64::INFINITY, 1.0, 1.0).unwrap_err();
    assert!(err.to_string().contains("platform_radius"), "{err}");
    let design = RrrDesign::new(base, [2.0; 3], [2.0; 3], platform).unwrap();
    let err = design
        .inverse_kinematics(&RrrPose::new(1.0, f64::NAN, 0.0), &POSITIVE_MODES)
        .unwrap_err();
    assert!(err.to_string().contains("pose.y"), "{err}");
}

#[test]
fn parallel_determinant_vanishes_when_distal_lines_are_concurrent() {
    // Build a configuration whose distal lines B_iC_i meet at Q, and one where they do not.
    let q = Point::new(0.3, 0.2);
    let platform_fixed = [
        Point::new(-1.0, -0.6),
        Point::new(1.2, -0.5),
        Point::new(0.1, 1.1),
    ];
    let dirs = platform_fixed.map(|c| (c - q).normalize());
    let elbows = [0, 1, 2].map(|i| platform_fixed[i] + 2.0 * dirs[i]);
    let bases = [0, 1, 2].map(|i| {
        let perp = Point::new(-dirs[i].y, dirs[i].x);
        elbows[i] + 1.7 * (0.6 * dirs[i] + 0.8 * perp)
    });
    let design = RrrDesign::new(
        bases,
        [1.7; 3],
        [2.0; 3],
        platform_fixed, // pose (0, 0, 0): moving frame = fixed frame
    )
    .unwrap();
    let modes = modes_of(&bases, &elbows, &platform_fixed);
    let config = design
        .inverse_kinematics(&RrrPose::new(0.0, 0.0, 0.0), &modes)
        .unwrap();
    for (i, elbow) in elbows.iter().enumerate() {
        assert!(
            (config.elbow[i] - elbow).norm() < 1e-12,
            "IK reproduces elbow {i}"
        );
    }
    assert!(config.parallel_determinant().abs() < 1e-12);
    let moved = design
        .inverse_kinematics(&RrrPose::new(0.05, -0.04, 0.03), &modes)
        .unwrap();
    assert!(moved.parallel_determinant().abs() > 1e-4);
}
