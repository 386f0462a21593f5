//! 3-RRR model along a motion (SPEC Part C): complex IK, working-mode continuation,
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
    let roots = singdist::pipeline::rrr_curve::parallel_singular_parameters(&trajectory, &taus);
    println!("{roots:?}");
    assert_eq!(roots.len(), 2);
}
