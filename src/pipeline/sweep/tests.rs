use super::*;
use crate::C64;
use crate::homotopy::{PathResult, PathStatus};

fn path(index: usize, status: PathStatus, point: [f64; 2]) -> PathResult {
    let solution = point.iter().map(|&v| C64::new(v, 0.5)).collect();
    crate::homotopy::test_support::path_result(index, status, solution)
}

/// Two paths on one nonsingular endpoint are a crossing (one critical point
/// missed): both are flagged, one is unaccounted for and the point is listed once;
/// two paths on one singular endpoint reached with winding (Cauchy endgame,
/// winding number 2) are a double root (both accounted for); two paths on one
/// endpoint classified singular only by its condition number (winding number 1,
/// e.g. far out along an isotropic line) are a crossing too.
#[test]
fn path_crossings_are_unaccounted_and_shared_singular_endpoints_are_not() {
    use PathStatus::{AtInfinity, Failed, Nonsingular, Singular};
    let winding = |mut p: PathResult| {
        p.winding_number = 2;
        p
    };
    let paths = vec![
        path(0, Nonsingular, [1.0, 2.0]),
        path(1, Nonsingular, [1.0, 2.0 + 1e-12]),
        path(2, Nonsingular, [3.0, 4.0]),
        winding(path(3, Singular, [5.0, 6.0])),
        winding(path(4, Singular, [5.0, 6.0])),
        path(5, AtInfinity, [1e9, 0.0]),
        path(
            6,
            Failed(crate::homotopy::FailureReason::TooManySteps),
            [7.0, 7.0],
        ),
        path(7, Singular, [8.0, 9.0]),
        path(8, Singular, [8.0, 9.0]),
    ];
    assert_eq!(
        crossings(&paths),
        vec![true, true, false, false, false, false, false, true, true]
    );
    // 9 paths: one failed, one extra on each of the two crossings.
    assert_eq!(accounted(&paths), 6);
    assert_eq!(finite_solutions(&paths).len(), 5);
    // The three unaccounted paths, by reason (as `PathFailure::reasons`).
    let reasons = unaccounted_reasons(&paths);
    assert_eq!(
        reasons.into_iter().collect::<Vec<_>>(),
        vec![
            ("PathCrossing".to_string(), 2),
            ("TooManySteps".to_string(), 1)
        ]
    );
    assert!(unaccounted_reasons(&paths[..3]).len() == 1);
    assert!(unaccounted_reasons(&paths[2..6]).is_empty());
}

/// Two paths classified at infinity on the same point at the same `t` cross (one
/// jumped onto the other's divergent path); at different `t`, or on different
/// points, they do not.
#[test]
fn paths_diverging_together_are_a_crossing() {
    use PathStatus::{AtInfinity, Nonsingular};
    let at = |mut p: PathResult, t: f64| {
        p.last_t = C64::new(t, 0.0);
        p
    };
    let paths = vec![
        at(path(0, AtInfinity, [146.6, 3.0]), 0.9999755859375),
        at(path(1, AtInfinity, [146.6, 3.0]), 0.9999755859375),
        at(path(2, AtInfinity, [146.6, 3.0]), 0.99990234375),
        at(path(3, AtInfinity, [70.0, 3.0]), 0.9999755859375),
        path(4, Nonsingular, [1.0, 2.0]),
    ];
    assert_eq!(crossings(&paths), vec![true, true, false, false, false]);
    assert_eq!(accounted(&paths), 4);
}

/// The family `x² = p`.
fn square_root_family() -> crate::system::CompiledSystem {
    use crate::system::{Expr, System};
    let (x, p) = (Expr::variable("x"), Expr::parameter("p"));
    System::new(["x"], ["p"], vec![x.clone() * x - p])
        .unwrap()
        .compile()
}

/// `x² = p` from `p = 1` to `p = 4` with a step budget of two steps: both paths run
/// out of steps. A plan that hands over stops after the first run (both paths
/// tracked once, nothing found); one that does not re-runs them with the retry
/// tracker and finds both roots `±2`.
#[test]
fn a_plan_hands_over_after_a_first_run_whose_paths_run_out_of_steps() {
    use crate::homotopy::{PolylinePath, TrackerOptions};
    let system = square_root_family();
    let starts = vec![vec![C64::new(1.0, 0.0)], vec![C64::new(-1.0, 0.0)]];
    let route = |_| PolylinePath::new(vec![vec![C64::new(1.0, 0.0)], vec![C64::new(4.0, 0.0)]]);
    let mut starved = TrackerOptions::default();
    starved.step.max_steps = 2;
    let retry = TrackerOptions::default();
    for hand_over in [true, false] {
        let plan = TrackingPlan {
            hand_over_when_steps_run_out: hand_over,
            ..TrackingPlan::with_endgame(&starved, &retry)
        };
        let retried = track_with_retries(&system, &starts, route, 1, plan);
        assert_eq!(retried.handed_over, hand_over);
        if hand_over {
            assert_eq!((retried.tracked, retried.accounted), (2, 0));
            assert!(retried.endpoints.is_empty());
            assert_eq!(retried.reasons.get("TooManySteps"), Some(&2));
        } else {
            assert_eq!(retried.accounted, 2);
            let mut roots: Vec<f64> = retried.endpoints.iter().map(|e| e[0].re).collect();
            roots.sort_by(f64::total_cmp);
            assert!(
                (roots[0] + 2.0).abs() < 1e-12 && (roots[1] - 2.0).abs() < 1e-12,
                "{roots:?}"
            );
        }
    }
}

/// The abandoned first run ([`TrackingPlan::abandon_when_steps_run_out`]): on `x² = p`
/// from `p = 1` to `p = 4` with 40 starts (three chunks), a budget of two steps hands
/// over with no endpoint and every start counted as tracked, on one thread and on
/// four; with the full budget the run is the one [`track_all`] gives, path for path,
/// and the plan goes on as without the flag.
#[test]
fn an_abandoned_first_run_hands_over_whatever_the_thread_count_and_changes_nothing_else() {
    use crate::homotopy::{PathParameterHomotopy, PolylinePath, TrackerOptions};
    let system = square_root_family();
    let starts: Vec<Vec<C64>> = (0..40)
        .map(|k| vec![C64::new(if k % 2 == 0 { 1.0 } else { -1.0 }, 0.0)])
        .collect();
    let route = |_| PolylinePath::new(vec![vec![C64::new(1.0, 0.0)], vec![C64::new(4.0, 0.0)]]);
    let mut starved = TrackerOptions::default();
    starved.step.max_steps = 2;
    let full = TrackerOptions::default();
    let plan = |first| TrackingPlan {
        endgame: false,
        hand_over_when_steps_run_out: true,
        abandon_when_steps_run_out: true,
        ..TrackingPlan::with_endgame(first, &full)
    };
    for threads in [1, 4] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let retried =
            pool.install(|| track_with_retries(&system, &starts, route, 1, plan(&starved)));
        assert!(retried.handed_over);
        assert_eq!((retried.tracked, retried.accounted), (40, 0));
        assert!(retried.endpoints.is_empty());
    }
    let homotopy = PathParameterHomotopy::new(&system, route(0));
    let abandoned =
        track_all_unless_steps_run_out(&homotopy, &starts, &full).expect("no path runs out");
    let whole = track_all(&homotopy, &starts, &full, false);
    assert_eq!(abandoned.len(), 40);
    for (a, w) in abandoned.iter().zip(&whole) {
        assert_eq!(
            (a.path_index, a.status, a.steps),
            (w.path_index, w.status, w.steps)
        );
        assert_eq!(a.solution, w.solution);
    }
    let retried = track_with_retries(&system, &starts, route, 1, plan(&full));
    assert!(!retried.handed_over);
    let mut roots: Vec<f64> = retried.endpoints.iter().map(|e| e[0].re).collect();
    roots.sort_by(f64::total_cmp);
    assert_eq!(roots.len(), 2, "{roots:?}");
    assert!((roots[0] + 2.0).abs() < 1e-12 && (roots[1] - 2.0).abs() < 1e-12);
}

/// `x² = p` from `p = 1` to `p = 4` with the start `1` given twice: the two paths
/// from it always cross on `2`, so one path stays unaccounted for on every route.
/// Of six whole detours only the first two are tracked: they add no endpoint and
/// account for no more paths ([`STAGNANT_DETOURS`]). Tracked: 3 (first run) + 2
/// (re-run of the crossing pair) + 2 (the crossing pair on detour 1) + 3 + 3 (two whole
/// detours), not 3 + 2 + 2 + 6·3.
#[test]
fn detours_stop_after_two_that_add_nothing() {
    use crate::homotopy::{PolylinePath, TrackerOptions};
    let system = square_root_family();
    let one = vec![C64::new(1.0, 0.0)];
    let starts = vec![one.clone(), vec![C64::new(-1.0, 0.0)], one];
    let route = |attempt: usize| {
        let detour = C64::new(2.5, 0.3 * attempt as f64);
        PolylinePath::new(vec![
            vec![C64::new(1.0, 0.0)],
            vec![detour],
            vec![C64::new(4.0, 0.0)],
        ])
    };
    let options = TrackerOptions::default();
    let plan = TrackingPlan::with_endgame(&options, &options);
    let retried = track_with_retries(&system, &starts, route, 6, plan);
    assert_eq!(retried.endpoints.len(), 2);
    assert_eq!(retried.accounted, 2);
    assert_eq!(retried.tracked, 3 + 2 + 2 + STAGNANT_DETOURS * 3);
}

/// The conjugates a set lacks are added (a real point is its own conjugate), up to
/// the limit, and the count of those added is returned.
#[test]
fn endpoints_are_completed_with_their_missing_conjugates() {
    let conjugate = |x: &[C64]| x.iter().map(|v| v.conj()).collect::<Vec<C64>>();
    let point = |re: f64, im: f64| vec![C64::new(re, im), C64::new(2.0 * re, -im)];
    let mut endpoints = vec![point(1.0, 2.0), point(3.0, 0.0), point(-1.0, 0.5)];
    assert_eq!(with_conjugates(&conjugate, &mut endpoints, 10), 2);
    assert_eq!(endpoints.len(), 5);
    for x in &endpoints {
        assert!(endpoints.iter().any(|y| same_endpoint(y, &conjugate(x))));
    }
    // Complete sets gain nothing; the limit caps what is added.
    assert_eq!(with_conjugates(&conjugate, &mut endpoints, 10), 0);
    let mut capped = vec![point(1.0, 2.0), point(-1.0, 0.5)];
    assert_eq!(with_conjugates(&conjugate, &mut capped, 3), 1);
    assert_eq!(capped.len(), 3);
}
