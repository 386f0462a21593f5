//! 3-RRR sub-problems (docs/theory.md §10): the stored start files (residuals,
//! distinctness, certificates) and their root counts re-measured from a second seed.
use singdist::C64;
use singdist::mechanism::rrr::{distance_sq, leg_polynomial, parallel_polynomial};
use singdist::pipeline::rrr::ab_initio::*;
use singdist::pipeline::start_file::StartSolutions;
use singdist::problem::rrr::*;
use singdist::system::Evaluator;

#[test]
fn names_round_trip_and_unknown_names_are_errors() {
    for kind in RrrSubProblem::ALL {
        assert_eq!(kind.name().parse::<RrrSubProblem>().unwrap(), kind);
        assert_eq!(kind.short_name().parse::<RrrSubProblem>().unwrap(), kind);
    }
    assert!("rrr:leg4".parse::<RrrSubProblem>().is_err());
    assert_eq!(RrrSubProblem::Leg(1).file_stem(), "rrr-leg2");
}

/// The compiled system is ∇Λ of `D² − λ C`: compare with complex-step derivatives of the
/// generic formulas at a random complex point.
/// `n` standard complex normal numbers.
fn random_point(rng: &mut singdist::random::SeededRng, n: usize) -> Vec<C64> {
    (0..n)
        .map(|_| singdist::random::complex_normal(rng))
        .collect()
}

#[test]
fn system_is_the_gradient_of_the_lagrangian() {
    let mut rng = singdist::random::seeded(5);
    for kind in RrrSubProblem::ALL {
        let problem = RrrProblem::new(kind).unwrap();
        let system = problem.evaluator();
        assert_eq!(system.num_variables(), 19);
        assert_eq!(system.num_parameters(), 18);
        let x = random_point(&mut rng, 19);
        let p = random_point(&mut rng, 18);
        let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
        let mut f = vec![C64::new(0.0, 0.0); 19];
        system.evaluate(&x, &p, &mut work, &mut f);
        let lagrangian = |x: &[C64]| {
            let k: [C64; 18] = std::array::from_fn(|j| p[j]);
            let kp: [C64; 18] = std::array::from_fn(|j| x[j]);
            let c = match kind {
                RrrSubProblem::Parallel => parallel_polynomial(&kp),
                RrrSubProblem::Leg(i) => leg_polynomial(&kp, i),
            };
            distance_sq(&k, &kp) - x[18] * c
        };
        // Central differences in the complex direction are exact up to O(h²) for these
        // polynomials (degree ≤ 5); h = 1e-5 gives ~1e-10 relative.
        let h = 1e-5;
        for j in 0..19 {
            let mut plus = x.clone();
            let mut minus = x.clone();
            plus[j] += h;
            minus[j] -= h;
            let derivative = (lagrangian(&plus) - lagrangian(&minus)) / (2.0 * h);
            assert!(
                (derivative - f[j]).norm() < 1e-7 * (1.0 + f[j].norm()),
                "{}: equation {j}: {derivative} vs {}",
                kind.name(),
                f[j]
            );
        }
    }
}

/// At real parameters the system has real coefficients: `F(x̄; p) = conj F(x; p)`, so
/// the conjugate of a critical point ([`RrrProblem::conjugate`]) is one too — what the
/// curve's conjugate completion relies on.
#[test]
fn conjugation_maps_solutions_to_solutions_at_real_parameters() {
    let mut rng = singdist::random::seeded(11);
    for kind in RrrSubProblem::ALL {
        let x = random_point(&mut rng, 19);
        let p: Vec<C64> = random_point(&mut rng, 18)
            .iter()
            .map(|v| C64::new(v.re, 0.0))
            .collect();
        let conjugate = RrrProblem::conjugate(&x);
        assert_eq!(conjugate.len(), 19);
        let problem = RrrProblem::new(kind).unwrap();
        let values = |x: &[C64]| {
            let system = problem.evaluator();
            let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
            let mut f = vec![C64::new(0.0, 0.0); 19];
            system.evaluate(x, &p, &mut work, &mut f);
            f
        };
        let (f, g) = (values(&x), values(&conjugate));
        for j in 0..19 {
            assert!(
                (g[j] - f[j].conj()).norm() <= 1e-12 * (1.0 + f[j].norm()),
                "{}: equation {j}: {} vs conj {}",
                kind.name(),
                g[j],
                f[j]
            );
        }
    }
}

#[test]
fn stored_start_files_are_certified_with_small_residuals() {
    for kind in RrrSubProblem::ALL {
        let problem = RrrProblem::new(kind).unwrap();
        let file = embedded_rrr_start_solutions(kind)
            .unwrap_or_else(|| panic!("{}: no embedded start file", kind.name()))
            .unwrap();
        assert_eq!(file.metric, RRR_METRIC_NAME);
        let report = verify_rrr_start_solutions(&problem, &file).unwrap();
        println!("{report:?} trace {:?}", file.certificate.trace_residual);
        assert!(report.max_residual < 1e-10, "{report:?}");
        assert!(report.min_separation > 1e-6, "{report:?}");
        assert!(report.min_relative_singular_value > 1e-10, "{report:?}");
        assert_eq!(report.count, file.certificate.found_count);
        match kind {
            // Legs: certified by the trace test (2 critical points).
            RrrSubProblem::Leg(_) => {
                assert!(report.passed, "{report:?}");
                assert_eq!(file.certificate.kind, "trace-test");
                assert!(file.certificate.trace_residual.unwrap() < 1e-8);
                assert_eq!(report.count, 2);
            }
            // Parallel: certified by the trace test sliced on K′ (50 critical points).
            RrrSubProblem::Parallel => {
                assert!(report.passed, "{report:?}");
                assert_eq!(file.certificate.kind, "trace-test");
                assert!(file.certificate.trace_residual.unwrap() < 1e-8);
                assert_eq!(report.count, 50);
            }
        }
    }
}

/// Root counts are stable across source seeds: a fresh ab-initio run with another seed
/// (new random source point, start pair and loops) finds the stored count.
#[test]
fn leg_counts_are_stable_across_seeds() {
    for kind in [
        RrrSubProblem::Leg(0),
        RrrSubProblem::Leg(1),
        RrrSubProblem::Leg(2),
    ] {
        let problem = RrrProblem::new(kind).unwrap();
        let stored = embedded_rrr_start_solutions(kind).unwrap().unwrap();
        let options = RrrAbInitioOptions {
            seed: 4242,
            ..RrrAbInitioOptions::default()
        };
        let fresh = compute_rrr_start_solutions(&problem, &options).unwrap();
        assert!(fresh.certificate.passed, "{:?}", fresh.certificate);
        assert!(fresh.max_residual < 1e-10);
        assert_eq!(
            fresh.solutions.len(),
            stored.solutions.len(),
            "{}",
            kind.name()
        );
    }
}

/// The problem `kind` and its start solutions stored in the binary.
fn problem_and_stored_set(kind: RrrSubProblem) -> (RrrProblem, StartSolutions) {
    let problem = RrrProblem::new(kind).unwrap();
    let stored = embedded_rrr_start_solutions(kind).unwrap().unwrap();
    (problem, stored)
}

/// The default ab-initio options with `seed`, monodromy stopping after
/// `max_stagnant_loops` loops without a new solution.
fn ab_initio_options(seed: u64, max_stagnant_loops: usize) -> RrrAbInitioOptions {
    let mut options = RrrAbInitioOptions {
        seed,
        ..RrrAbInitioOptions::default()
    };
    options.monodromy.max_stagnant_loops = max_stagnant_loops;
    options
}

/// The parallel problem's count from a second seed: monodromy from a fresh start pair at a
/// fresh source point (no target count given, stops on stagnation) reaches the stored count,
/// certified by the trace test sliced on K′ (≈ 6 s).
#[test]
fn parallel_count_is_stable_across_seeds() {
    let kind = RrrSubProblem::Parallel;
    let (problem, stored) = problem_and_stored_set(kind);
    let options = ab_initio_options(4243, 10);
    assert_eq!(options.monodromy.trace_slice_unknowns, Some(18));
    let fresh = compute_rrr_start_solutions(&problem, &options).unwrap();
    assert!(fresh.max_residual < 1e-10);
    assert!(fresh.certificate.passed, "{:?}", fresh.certificate);
    assert_eq!(fresh.solutions.len(), stored.solutions.len());
}

/// The stored solution sets pass a fresh trace test (other random slices than the stored
/// certificate's): the projection of the incidence curve to `(K′, μ)` has 134 points on a
/// slice for the parallel problem, and the trace of the witness set is linear only if none
/// is missing; tracking the surplus witness points back to the fiber adds no solution.
#[test]
fn stored_solution_sets_pass_a_fresh_trace_test() {
    for kind in RrrSubProblem::ALL {
        let (problem, file) = problem_and_stored_set(kind);
        let options = ab_initio_options(1, 3);
        let started = std::time::Instant::now();
        let certificate = trace_certificate(&problem, &file, &options).unwrap();
        println!(
            "{}: {certificate:?} in {:.1} s",
            kind.name(),
            started.elapsed().as_secs_f64()
        );
        assert!(certificate.passed, "{}: {certificate:?}", kind.name());
        assert_eq!(certificate.found_count, file.solutions.len());
        // A set with one solution removed fails; the witness set (repopulated by
        // monodromy) leads back to the missing solution.
        if kind == RrrSubProblem::Leg(0) {
            let mut incomplete = file.clone();
            incomplete.solutions.pop();
            let failed = trace_certificate(&problem, &incomplete, &options).unwrap();
            assert!(!failed.passed, "{failed:?}");
            assert_eq!(failed.found_count, 2, "{failed:?}");
        }
    }
}
