//! 3-RRR model along a motion (docs/theory.md §10): complex IK, working-mode continuation,
//! the example's singular crossings.
use singdist::C64;
use singdist::mechanism::rrr::*;

#[test]
fn complex_configuration_matches_real_inverse_kinematics() {
    let design = example_design();
    for modes in [
        POSITIVE_MODES,
        [
            ElbowMode::Negative,
            ElbowMode::Positive,
            ElbowMode::Negative,
        ],
    ] {
        let pose = RrrPose::new(0.1, 0.3, 0.2);
        let real = design.inverse_kinematics(&pose, &modes).unwrap().to_array();
        let complex = design.configuration_complex(
            C64::new(pose.x, 0.0),
            C64::new(pose.y, 0.0),
            C64::new(pose.phi, 0.0),
            &modes,
        );
        for (a, b) in real.iter().zip(&complex) {
            assert!((a - b.re).abs() < 1e-14 && b.im.abs() < 1e-14, "{a} vs {b}");
        }
    }
}

#[test]
fn example_crosses_a_leg_and_a_parallel_singularity() {
    let trajectory = example_trajectory();
    let crossings = trajectory.leg_crossings();
    println!("{crossings:?}");
    assert_eq!(crossings[0].len(), 1);
    assert!((crossings[0][0] - 0.8f64.atan2(-0.6)).abs() < 1e-7);
    assert!(crossings[1].is_empty() && crossings[2].is_empty());
    let taus: Vec<f64> = (0..=720)
        .map(|j| 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / 721.0)
        .collect();
    let roots = singdist::pipeline::rrr::curve::parallel_singular_parameters(&trajectory, &taus);
    println!("{roots:?}");
    assert_eq!(roots.len(), 2);
}

/// With a fixed working mode the leg determinant keeps its sign; along the example the
/// continued working mode flips leg 1 at its crossing, so its determinant changes sign.
#[test]
fn leg_determinant_changes_sign_at_the_crossing() {
    let trajectory = example_trajectory();
    let root = trajectory.leg_crossings()[0][0];
    let before = trajectory.configuration(root - 1e-6).unwrap();
    let after = trajectory.configuration(root + 1e-6).unwrap();
    assert_eq!(trajectory.modes_at(root - 1e-6)[0], ElbowMode::Positive);
    assert_eq!(trajectory.modes_at(root + 1e-6)[0], ElbowMode::Negative);
    assert!(before.leg_determinant(0) > 0.0 && after.leg_determinant(0) < 0.0);
    // The elbow moves continuously through the crossing (no jump between the modes).
    assert!((before.elbow[0] - after.elbow[0]).norm() < 1e-5);
    // The polynomial on the 18-vector agrees with the configuration's determinants.
    let k = before.to_array();
    assert!((leg_polynomial(&k, 0) - before.leg_determinant(0)).abs() < 1e-15);
    assert!((parallel_polynomial(&k) - before.parallel_determinant()).abs() < 1e-14);
    // D(K, K) = 0 and D is invariant under a rigid motion applied to both configurations.
    let other = after.to_array();
    assert_eq!(distance(&k, &k), 0.0);
    let (s, c) = (0.7f64.sin(), 0.7f64.cos());
    let moved = |v: &[f64; 18]| -> [f64; 18] {
        std::array::from_fn(|j| {
            let (x, y) = (v[j - j % 2], v[j - j % 2 + 1]);
            if j % 2 == 0 {
                c * x - s * y + 0.3
            } else {
                s * x + c * y - 1.1
            }
        })
    };
    assert!((distance(&k, &other) - distance(&moved(&k), &moved(&other))).abs() < 1e-14);
}
