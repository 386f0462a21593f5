//! Tests of the seeded genetic algorithm and the projected BFGS refinement.

mod optimize_support;
use optimize_support::small_genetic_options;
use singdist::optimize::{
    GeneticOptions, LocalOptions, OptimizeError, genetic_maximize, local_maximize, maximize,
};

/// Concave quadratic with maximum 0 at `centre`.
fn bowl(centre: &[f64]) -> impl Fn(&[f64]) -> f64 + Sync + '_ {
    move |x: &[f64]| {
        -x.iter()
            .zip(centre)
            .map(|(a, c)| (a - c).powi(2))
            .sum::<f64>()
    }
}

fn small_options(seed: u64) -> GeneticOptions {
    small_genetic_options(30, 40, seed)
}

#[test]
fn ga_finds_interior_maximum_of_a_quadratic() {
    let centre = [0.3, -0.7, 0.1];
    let bounds = [(-1.0, 1.0); 3];
    let result = genetic_maximize(bowl(&centre), &bounds, &small_options(1)).unwrap();
    assert!(
        result.best_value > -1e-3,
        "best value {}",
        result.best_value
    );
    for (x, c) in result.best.iter().zip(&centre) {
        assert!((x - c).abs() < 0.05, "{x} vs {c}");
    }
    // History is the best-so-far: non-decreasing, ends at best_value.
    assert_eq!(result.history.len(), 41);
    assert!(result.history.windows(2).all(|w| w[1] >= w[0]));
    assert_eq!(*result.history.last().unwrap(), result.best_value);
    assert_eq!(result.evaluations, 30 + 40 * 28);
}

#[test]
fn ga_is_reproducible_and_seed_dependent() {
    let centre = [0.2, 0.4];
    let bounds = [(-1.0, 1.0), (0.0, 2.0)];
    let a = genetic_maximize(bowl(&centre), &bounds, &small_options(7)).unwrap();
    let b = genetic_maximize(bowl(&centre), &bounds, &small_options(7)).unwrap();
    assert_eq!(a, b, "same seed must give the identical run");
    let c = genetic_maximize(bowl(&centre), &bounds, &small_options(8)).unwrap();
    assert_ne!(a.best, c.best, "a different seed should change the run");
    // Same result on a single-thread pool (thread-count independence).
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let d = pool.install(|| genetic_maximize(bowl(&centre), &bounds, &small_options(7)).unwrap());
    assert_eq!(a, d);
}

#[test]
fn ga_stays_in_bounds_and_finds_corner_maximum() {
    // Linear objective: maximum at the corner (hi, lo).
    let bounds = [(0.0, 1.0), (-2.0, -1.0)];
    let seen_outside = std::sync::atomic::AtomicBool::new(false);
    let objective = |x: &[f64]| {
        if x[0] < 0.0 || x[0] > 1.0 || x[1] < -2.0 || x[1] > -1.0 {
            seen_outside.store(true, std::sync::atomic::Ordering::Relaxed);
        }
        x[0] - x[1]
    };
    let result = genetic_maximize(objective, &bounds, &small_options(3)).unwrap();
    assert!(!seen_outside.load(std::sync::atomic::Ordering::Relaxed));
    assert!(result.best_value > 2.95, "{}", result.best_value);
}

#[test]
fn ga_ignores_nan_and_uses_initial_individuals() {
    let bounds = [(-1.0, 1.0)];
    let objective = |x: &[f64]| if x[0] < 0.0 { f64::NAN } else { -x[0] };
    let options = GeneticOptions {
        population: 10,
        generations: 5,
        initial: vec![vec![0.0]],
        ..GeneticOptions::default()
    };
    let result = genetic_maximize(objective, &bounds, &options).unwrap();
    assert_eq!(result.best_value, 0.0);
    assert_eq!(result.best, vec![0.0]);
}

#[test]
fn ga_rejects_bad_input_with_named_field() {
    let f = |x: &[f64]| x[0];
    assert_eq!(
        genetic_maximize(f, &[], &GeneticOptions::default()),
        Err(OptimizeError::EmptyBounds)
    );
    assert!(matches!(
        genetic_maximize(f, &[(1.0, 0.0)], &GeneticOptions::default()),
        Err(OptimizeError::InvalidBound { index: 0, .. })
    ));
    assert!(matches!(
        genetic_maximize(f, &[(0.0, f64::NAN)], &GeneticOptions::default()),
        Err(OptimizeError::InvalidBound { index: 0, .. })
    ));
    let options = GeneticOptions {
        elite: 60,
        ..GeneticOptions::default()
    };
    let err = genetic_maximize(f, &[(0.0, 1.0)], &options).unwrap_err();
    assert!(err.to_string().contains("elite"), "{err}");
    let options = GeneticOptions {
        crossover: 1.5,
        ..GeneticOptions::default()
    };
    let err = genetic_maximize(f, &[(0.0, 1.0)], &options).unwrap_err();
    assert!(err.to_string().contains("crossover"), "{err}");
}

#[test]
fn local_refinement_converges_on_rosenbrock_and_respects_bounds() {
    // Maximise −Rosenbrock: optimum (1, 1) inside the box.
    let rosen = |x: &[f64]| -((1.0 - x[0]).powi(2) + 100.0 * (x[1] - x[0] * x[0]).powi(2));
    let bounds = [(-2.0, 2.0), (-1.0, 3.0)];
    let options = LocalOptions {
        max_iterations: 500,
        ..LocalOptions::default()
    };
    let result = local_maximize(rosen, &bounds, &[-1.2, 1.0], &options).unwrap();
    assert!((result.best[0] - 1.0).abs() < 1e-3, "{:?}", result);
    assert!((result.best[1] - 1.0).abs() < 2e-3, "{:?}", result);

    // Bound-constrained optimum: max of −(x−2)² − (y+3)² on [0,1]×[−1,1] is at (1, −1).
    let centre = [2.0, -3.0];
    let result = local_maximize(
        bowl(&centre),
        &[(0.0, 1.0), (-1.0, 1.0)],
        &[0.2, 0.5],
        &LocalOptions::default(),
    )
    .unwrap();
    assert!(
        (result.best[0] - 1.0).abs() < 1e-12 && (result.best[1] + 1.0).abs() < 1e-12,
        "{:?}",
        result.best
    );
    assert!((result.best_value + 5.0).abs() < 1e-10);
    assert!(result.converged);
}

#[test]
fn hybrid_is_at_least_as_good_as_ga_and_improves_it() {
    let centre = [0.123_456, -0.654_321, 0.5];
    let bounds = [(-1.0, 1.0); 3];
    let ga = GeneticOptions {
        population: 12,
        generations: 5,
        seed: 11,
        ..GeneticOptions::default()
    };
    let result = maximize(bowl(&centre), &bounds, &ga, &LocalOptions::default()).unwrap();
    assert!(result.best_value >= result.genetic.best_value);
    assert!(
        result.genetic.best_value < -1e-6,
        "GA alone should be coarse here"
    );
    assert!(
        result.best_value > -1e-10,
        "refined value {}",
        result.best_value
    );
}
