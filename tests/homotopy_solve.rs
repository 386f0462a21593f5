//! Total-degree solving: exact root counts, singular and infinite endpoints.

mod homotopy_common;

use homotopy_common::*;
use singdist::C64;
use singdist::homotopy::{PathStatus, SolveOptions, solve_total_degree};

fn distinct_count(solutions: &[Vec<C64>]) -> usize {
    let mut distinct: Vec<&Vec<C64>> = Vec::new();
    for s in solutions {
        if !distinct
            .iter()
            .any(|d| d.iter().zip(s).all(|(a, b)| (a - b).norm() < 1e-6))
        {
            distinct.push(s);
        }
    }
    distinct.len()
}

#[test]
fn katsura_5_and_6_have_all_2_to_the_n_solutions() {
    for (n, expected) in [(5, 32), (6, 64)] {
        let system = katsura(n);
        let result =
            solve_total_degree(&system, &system.degrees(), &[], &SolveOptions::default()).unwrap();
        let s = &result.summary;
        assert_eq!(s.failed, 0, "katsura-{n}: {s:?}");
        assert_eq!(s.nonsingular, expected, "katsura-{n}: {s:?}");
        let solutions = result.nonsingular_solutions();
        assert_eq!(distinct_count(&solutions), expected);
        for x in &solutions {
            assert!(residual(&system, x, &[]) < 1e-12);
        }
        assert_eq!(s.at_infinity + s.nonsingular, 1 << n);
    }
}

#[test]
fn cyclic_5_has_70_nonsingular_solutions_and_50_paths_at_infinity() {
    let system = cyclic(5);
    let result =
        solve_total_degree(&system, &system.degrees(), &[], &SolveOptions::default()).unwrap();
    let s = &result.summary;
    assert_eq!(s.paths, 120);
    assert_eq!(s.failed, 0, "{s:?}");
    assert_eq!(s.nonsingular, 70, "{s:?}");
    assert_eq!(s.at_infinity, 50, "{s:?}");
    assert_eq!(distinct_count(&result.nonsingular_solutions()), 70);
}

#[test]
fn random_dense_systems_reach_the_bezout_number() {
    for (degrees, seed) in [
        (vec![2u32, 3, 2], 1u64),
        (vec![3, 3, 2, 1], 2),
        (vec![2, 2, 2, 2, 2], 3),
    ] {
        let system = random_dense(&degrees, seed);
        let bezout: usize = degrees.iter().product::<u32>() as usize;
        let result = solve_total_degree(&system, &degrees, &[], &SolveOptions::default()).unwrap();
        assert_eq!(result.summary.failed, 0, "{degrees:?}");
        assert_eq!(
            result.summary.nonsingular, bezout,
            "{degrees:?}: {:?}",
            result.summary
        );
        assert_eq!(distinct_count(&result.nonsingular_solutions()), bezout);
    }
}

/// `f₁ = (x − 2)²·(x + 1) = x³ − 3x² + 4`, `f₂ = y² − x − 2`: roots x = 2 (double) with
/// y = ±2, x = −1 (simple) with y = ±1. Bézout 6: four paths to the two double roots
/// (each pair a cycle of winding number 2), two to the simple ones. (A double root at a
/// root of unity would be reached by two smooth paths, since x³ − 1 vanishes there.)
#[test]
fn double_roots_are_singular_with_multiplicity_two() {
    let t = |c: f64, e: Vec<u32>| Term {
        coefficient: C64::new(c, 0.0),
        parameter: None,
        exponents: e,
    };
    let f1 = vec![t(1.0, vec![3, 0]), t(-3.0, vec![2, 0]), t(4.0, vec![0, 0])];
    let f2 = vec![t(1.0, vec![0, 2]), t(-1.0, vec![1, 0]), t(-2.0, vec![0, 0])];
    let system = TermSystem {
        n: 2,
        m: 0,
        equations: vec![f1, f2],
    };
    let result = solve_total_degree(&system, &[3, 2], &[], &SolveOptions::default()).unwrap();
    let s = &result.summary;
    assert_eq!(s.failed, 0, "{s:?}");
    assert_eq!(s.nonsingular, 2, "{s:?}");
    assert_eq!(s.singular, 2, "{s:?}");
    assert_eq!(s.singular_paths, 4, "{s:?}");
    for p in result
        .paths
        .iter()
        .filter(|p| p.status == PathStatus::Singular)
    {
        assert_eq!(p.multiplicity, 2);
        assert_eq!(p.winding_number, 2);
        assert!((p.solution[0] - 2.0).norm() < 1e-6, "{:?}", p.solution);
        assert!(
            (p.solution[1].norm() - 2.0).abs() < 1e-6,
            "{:?}",
            p.solution
        );
        assert!(p.residual < 1e-10);
    }
    for p in result
        .paths
        .iter()
        .filter(|p| p.status == PathStatus::Nonsingular)
    {
        assert!((p.solution[0] + 1.0).norm() < 1e-12);
        assert!((p.solution[1].norm() - 1.0).abs() < 1e-12);
        assert!(p.residual < 1e-13);
    }
    assert_eq!(s.real, 4);
}

/// `x·y = 1, x = 2`: Bézout 2, one finite solution, one path to infinity.
#[test]
fn solutions_at_infinity_are_reported() {
    let t = |c: f64, e: Vec<u32>| Term {
        coefficient: C64::new(c, 0.0),
        parameter: None,
        exponents: e,
    };
    let system = TermSystem {
        n: 2,
        m: 0,
        equations: vec![
            vec![t(1.0, vec![1, 1]), t(-1.0, vec![0, 0])],
            vec![t(1.0, vec![1, 0]), t(-2.0, vec![0, 0])],
        ],
    };
    let result = solve_total_degree(&system, &[2, 1], &[], &SolveOptions::default()).unwrap();
    let s = &result.summary;
    assert_eq!((s.nonsingular, s.at_infinity, s.failed), (1, 1, 0), "{s:?}");
    let x = &result.nonsingular_solutions()[0];
    assert!((x[0] - 2.0).norm() < 1e-14 && (x[1] - 0.5).norm() < 1e-14);
    assert_eq!(s.real, 1);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let system = katsura(3);
    assert!(solve_total_degree(&system, &[1, 2], &[], &SolveOptions::default()).is_err());
    assert!(solve_total_degree(&system, &[1, 2, 2, 0], &[], &SolveOptions::default()).is_err());
    assert!(
        solve_total_degree(
            &system,
            &[1, 2, 2, 2],
            &[C64::new(1.0, 0.0)],
            &SolveOptions::default()
        )
        .is_err()
    );
}

/// Paths that fail in the first pass (here: a step budget of 5) are re-tracked with the
/// conservative preset, never dropped.
#[test]
fn failed_paths_are_retracked_with_conservative_options() {
    use singdist::homotopy::TrackerOptions;
    let system = katsura(4);
    let mut tracker = TrackerOptions::default();
    tracker.step.max_steps = 5;
    let options = SolveOptions {
        tracker,
        ..SolveOptions::default()
    };
    let result = solve_total_degree(&system, &system.degrees(), &[], &options).unwrap();
    assert_eq!(result.summary.retracked, 16);
    assert_eq!(result.summary.nonsingular, 16, "{:?}", result.summary);
    let without = SolveOptions {
        retry_failed: false,
        ..options
    };
    let result = solve_total_degree(&system, &system.degrees(), &[], &without).unwrap();
    assert_eq!(result.summary.failed, 16);
    assert!(
        result.paths.iter().all(
            |p| p.status == PathStatus::Failed(singdist::homotopy::FailureReason::TooManySteps)
        )
    );
}
