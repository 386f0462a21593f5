//! 3-RRR working modes continued along a motion: a mode flips only where the leg really
//! passes through its singularity (the leg determinant changes sign); a pose on a fold
//! is solved; reach is checked on the whole motion, not only on a grid.
use singdist::mechanism::rpr::{AnalyticMotion, Motion, MotionCoordinate};
use singdist::mechanism::rrr::*;
use singdist::pipeline::rrr::curve::*;

/// Leg 1 has `O_1 = (0, 0)`, links 0.9 + 0.9 = 1.8, and its platform joint at the
/// operation point `(x(τ), 0)`, so `|C_1 − O_1| = x(τ)`; legs 2 and 3 stay well inside
/// their rings for `x ∈ [1.5, 1.85]`.
fn design() -> RrrDesign {
    RrrDesign::new(
        [
            Point::new(0.0, 0.0),
            Point::new(2.4, 0.0),
            Point::new(1.7, 1.2),
        ],
        [0.9, 0.5, 0.6],
        [0.9, 0.6, 0.7],
        [
            Point::new(0.0, 0.0),
            Point::new(0.3, 0.0),
            Point::new(0.1, 0.3),
        ],
    )
    .expect("design")
}

fn motion(x: MotionCoordinate, tau_range: [f64; 2]) -> Motion {
    Motion::Analytic(AnalyticMotion {
        tau_range,
        x,
        y: MotionCoordinate::polynomial(vec![0.0]),
        phi: MotionCoordinate::polynomial(vec![0.0]),
    })
}

fn trajectory(x: Vec<f64>) -> RrrTrajectory {
    RrrTrajectory::new(
        design(),
        POSITIVE_MODES,
        motion(MotionCoordinate::polynomial(x), [-1.0, 1.0]),
    )
    .expect("trajectory")
}

fn leg1_determinant(trajectory: &RrrTrajectory, tau: f64) -> f64 {
    trajectory
        .configuration(tau)
        .expect("configuration")
        .leg_determinant(0)
}

#[test]
fn a_near_touch_of_full_reach_keeps_the_mode() {
    // |C − O| = 1.8 − 5e-10 − 0.25 τ²: never at full reach.
    let near = trajectory(vec![1.8 - 5e-10, 0.0, -0.25]);
    assert!(
        near.leg_crossings()[0].is_empty(),
        "{:?}",
        near.leg_crossings()
    );
    assert_eq!(near.modes_at(0.5), POSITIVE_MODES);
    assert!(leg1_determinant(&near, -0.5) > 0.0 && leg1_determinant(&near, 0.5) > 0.0);
}

#[test]
fn an_even_order_touch_keeps_the_mode() {
    // |C − O| = 1.8 − 0.25 τ⁴: det² ∝ τ⁴, det ∝ τ² does not change sign.
    let quartic = trajectory(vec![1.8, 0.0, 0.0, 0.0, -0.25]);
    assert!(
        quartic.leg_crossings()[0].is_empty(),
        "{:?}",
        quartic.leg_crossings()
    );
    assert_eq!(quartic.modes_at(0.5), POSITIVE_MODES);
}

#[test]
fn a_tangential_touch_flips_the_mode_and_its_pose_is_solved() {
    // |C − O| = 1.8 − 0.25 τ²: det ∝ τ changes sign at τ = 0.
    let touch = trajectory(vec![1.8, 0.0, -0.25]);
    let crossings = &touch.leg_crossings()[0];
    assert_eq!(crossings.len(), 1, "{crossings:?}");
    assert!(crossings[0].abs() < 1e-6, "{crossings:?}");
    assert_eq!(touch.modes_at(0.5)[0], ElbowMode::Negative);
    assert!(leg1_determinant(&touch, -0.5) > 0.0);
    assert!(leg1_determinant(&touch, 0.5) < 0.0);
    // The pose at full reach itself.
    let curve = compute_rrr_curve_at(
        &touch,
        &[0.0],
        &RrrCurveOptions::default(),
        &default_rrr_start_solutions,
    )
    .expect("curve at the fold");
    assert!(curve.failures.is_empty(), "{:?}", curve.failures);
    let leg1 = curve.poses[0].leg1.expect("leg 1 distance");
    assert!(leg1.abs() < 1e-8, "{leg1}");
}

#[test]
fn a_pose_with_a_platform_joint_on_its_base_joint_is_solved() {
    // The example's leg 1 (equal links) folds through its base joint at
    // τ₁ = atan2(0.8, −0.6).
    let trajectory = example_trajectory();
    let tau = 0.8f64.atan2(-0.6);
    assert!((trajectory.leg_crossings()[0][0] - tau).abs() < 1e-9);
    let before = trajectory.configuration(tau - 1e-6).expect("before");
    let at = trajectory.configuration(tau).expect("on the fold");
    let after = trajectory.configuration(tau + 1e-6).expect("after");
    // The elbow is continuous through the fold.
    assert!((at.elbow[0] - before.elbow[0]).norm() < 1e-5);
    assert!((at.elbow[0] - after.elbow[0]).norm() < 1e-5);
    let curve = compute_rrr_curve_at(
        &trajectory,
        &[tau],
        &RrrCurveOptions::default(),
        &default_rrr_start_solutions,
    )
    .expect("curve at the fold");
    assert!(curve.failures.is_empty(), "{:?}", curve.failures);
    assert!(curve.poses[0].leg1.expect("leg 1").abs() < 1e-8);
}

#[test]
fn a_motion_leaving_the_workspace_between_grid_points_is_refused() {
    // x = 1.77 − 0.04 cos(4096 τ) on [0, 2π]: 1.73 at every point of a 4096-interval
    // grid, but 1.81 > 1.8 (leg 1's full reach) halfway between.
    let x = MotionCoordinate {
        polynomial: vec![1.77],
        cosines: vec![[-0.04, 4096.0, 0.0].into()],
    };
    let error = RrrTrajectory::new(
        design(),
        POSITIVE_MODES,
        motion(x, [0.0, 2.0 * std::f64::consts::PI]),
    )
    .expect_err("leaves the workspace");
    let message = error.to_string();
    assert!(message.contains("leg 0"), "{message}");
    assert!(message.contains("leaves the workspace"), "{message}");
}

/// `rrr curve --modes … --hold-modes` uses those modes at every pose and says so in the
/// CSV; without `--hold-modes` the example's leg 1 flips at its fold.
#[test]
fn modes_given_on_the_command_line_are_reported_per_pose() {
    let dir = std::env::temp_dir().join(format!("singdist-rrr-modes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let column = |extra: &[&str]| -> Vec<String> {
        let out = dir.join("curve.csv");
        let mut args = vec![
            "rrr", "curve", "--quiet", "--poses", "4", "--modes", "+,-,+",
        ];
        args.extend_from_slice(extra);
        let out_text = out.display().to_string();
        args.extend_from_slice(&["--out", &out_text]);
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_singdist"))
            .args(&args)
            .output()
            .expect("run singdist");
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let mut reader = csv::Reader::from_path(&out).expect("CSV");
        let headers = reader.headers().expect("header").clone();
        let index = headers
            .iter()
            .position(|h| h == "working_modes")
            .expect("working_modes column");
        reader
            .records()
            .map(|r| r.expect("row")[index].to_string())
            .collect()
    };
    assert_eq!(column(&["--hold-modes"]), vec!["+,-,+"; 4]);
    // τ = 0, 2π/3, 4π/3, 2π: leg 1 folds at τ₁ ≈ 2.214.
    assert_eq!(column(&[]), vec!["+,-,+", "+,-,+", "-,-,+", "-,-,+"]);
}
