//! `rrr curve` solved window by window ([`RrrCurveRun`]): windows give exactly the whole
//! curve's poses (the scaled parallel determinant still divided by its maximum over the
//! whole motion), and the streamed CSV is complete with no partial file left.

use singdist::mechanism::rrr::example_trajectory;
use singdist::pipeline::rrr::curve::*;
use std::process::Command;

#[test]
fn windows_equal_the_whole_curve() {
    let trajectory = example_trajectory();
    let taus = [0.2, 0.9, 1.7, 2.6, 3.4, 4.8, 5.9];
    let options = RrrCurveOptions::default();
    let whole = compute_rrr_curve_at(&trajectory, &taus, &options, &default_rrr_start_solutions)
        .expect("curve");
    let run =
        RrrCurveRun::new(&trajectory, &taus, &options, &default_rrr_start_solutions).expect("run");
    let first = run.solve_range(0..4, &|_| {}).expect("window 0");
    assert_eq!(first.poses.len(), 4);
    let second = run.solve_range(4..7, &|_| {}).expect("window 1");
    let mut poses = first.poses.clone();
    poses.extend(second.poses.clone());
    assert_eq!(poses, whole.poses);
    // The maximum of |parallel determinant| is over all seven poses, not per window.
    let top = poses
        .iter()
        .map(|p| p.parallel_determinant_abs_scaled)
        .fold(0.0f64, f64::max);
    assert_eq!(top, 1.0);
    // The windows' self-checks re-solve other poses than the whole curve's.
    let windowed = run.collect(vec![first, second]);
    assert_eq!(windowed.poses, whole.poses);
    assert_eq!(
        windowed.self_check.as_ref().map(|c| c.disagreements),
        Some(0)
    );
}

/// With chains of 3 poses the windows 0..2, 2..5, 5..7 cut blocks in two: each window
/// still gives exactly the whole curve's poses (a block is solved from its anchor).
#[test]
fn windows_cutting_chains_equal_the_whole_curve() {
    let trajectory = example_trajectory();
    let taus = [0.2, 0.5, 0.9, 1.3, 1.7, 2.1, 2.6];
    let options = RrrCurveOptions {
        chain_length: 3,
        ..RrrCurveOptions::default()
    };
    let whole = compute_rrr_curve_at(&trajectory, &taus, &options, &default_rrr_start_solutions)
        .expect("curve");
    let run =
        RrrCurveRun::new(&trajectory, &taus, &options, &default_rrr_start_solutions).expect("run");
    let mut poses = Vec::new();
    for range in [0..2, 2..5, 5..7] {
        let window = run
            .solve_range(range.clone(), &|_| {})
            .expect("window")
            .poses;
        assert_eq!(
            window.iter().map(|p| p.index).collect::<Vec<_>>(),
            range.collect::<Vec<_>>()
        );
        poses.extend(window);
    }
    assert_eq!(poses, whole.poses);
}

#[test]
fn streamed_csv_is_complete() {
    let dir = std::env::temp_dir().join(format!("singdist-rrr-stream-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let out = dir.join("r.csv");
    let status = Command::new(env!("CARGO_BIN_EXE_singdist"))
        .args(["rrr", "curve", "--quiet", "--poses", "5", "--out"])
        .arg(&out)
        .status()
        .expect("run");
    assert!(status.success());
    let text = std::fs::read_to_string(&out).expect("csv");
    assert!(text.starts_with("tau,x,y,phi,parallel,leg1,leg2,leg3,distance,"));
    assert_eq!(text.lines().count(), 6, "{text}");
    assert!(!dir.join("r.csv.partial").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
