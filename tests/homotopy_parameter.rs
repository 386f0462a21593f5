//! Parameter homotopies, the compiled-system path, and thread-count determinism.

mod homotopy_common;

use homotopy_common::*;
use singdist::C64;
use singdist::homotopy::{PathStatus, SolveOptions, solve_parameter_homotopy, solve_total_degree};
use singdist::random::{complex_normal, seeded};

#[test]
fn katsura_6_there_and_back_along_a_parameter_segment_returns_the_same_set() {
    let (system, p0) = coefficients_as_parameters(&katsura(6));
    let td = solve_total_degree(
        &katsura(6),
        &katsura(6).degrees(),
        &[],
        &SolveOptions::default(),
    )
    .unwrap();
    let start = td.nonsingular_solutions();
    assert_eq!(start.len(), 64);
    let mut rng = seeded(42);
    let p1: Vec<C64> = p0
        .iter()
        .map(|c| c + complex_normal(&mut rng) * 0.3)
        .collect();
    let options = SolveOptions::default();
    let there = solve_parameter_homotopy(&system, &start, &p0, &p1, &options).unwrap();
    assert_eq!(there.summary.nonsingular, 64, "{:?}", there.summary);
    let middle = there.nonsingular_solutions();
    for x in &middle {
        assert!(residual(&system, x, &p1) < 1e-12);
    }
    // The perturbed system is a different one: its solutions moved.
    assert!(set_distance(&middle, &start) > 1e-3);
    let back = solve_parameter_homotopy(&system, &middle, &p1, &p0, &options).unwrap();
    assert_eq!(back.summary.nonsingular, 64, "{:?}", back.summary);
    let returned = back.nonsingular_solutions();
    for x in &returned {
        assert!(residual(&system, x, &p0) < 1e-12);
    }
    assert!(set_distance(&returned, &start) < 1e-10);
    assert!(set_distance(&start, &returned) < 1e-10);
    // Generic parameters: every returned point is a permutation of the start set (no
    // two paths coincide).
    assert!(back.paths.iter().all(|p| p.multiplicity == 1));
}

#[test]
fn compiled_katsura_6_gives_64_solutions() {
    let (system, degrees) = katsura_compiled(6);
    let result = solve_total_degree(&system, &degrees, &[], &SolveOptions::default()).unwrap();
    assert_eq!(result.summary.nonsingular, 64, "{:?}", result.summary);
    assert_eq!(result.summary.failed, 0);
    assert!(
        result
            .paths
            .iter()
            .all(|p| p.status != PathStatus::Nonsingular || p.residual < 1e-12)
    );
    // katsura-n has real solutions; the count is invariant under the seed.
    let other = solve_total_degree(
        &system,
        &degrees,
        &[],
        &SolveOptions {
            seed: 99,
            ..SolveOptions::default()
        },
    )
    .unwrap();
    assert_eq!(other.summary.real, result.summary.real);
}

#[test]
fn same_seed_gives_bit_identical_results_with_one_and_two_threads() {
    let (system, degrees) = katsura_compiled(5);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            solve_total_degree(
                &system,
                &degrees,
                &[],
                &SolveOptions {
                    seed: 7,
                    ..SolveOptions::default()
                },
            )
            .unwrap()
        })
    };
    let one = run(1);
    let two = run(2);
    assert_eq!(one.summary, two.summary);
    assert_eq!(one.paths, two.paths);
    let bits = |r: &singdist::homotopy::SolveResult| -> Vec<u64> {
        r.paths
            .iter()
            .flat_map(|p| {
                p.solution
                    .iter()
                    .flat_map(|z| [z.re.to_bits(), z.im.to_bits()])
            })
            .collect()
    };
    assert_eq!(bits(&one), bits(&two));
}

/// Endgame: a path whose multiplier diverges like 1/s (s = 1 − t) while still small
/// at the endgame's first checkpoints (0.2 at s = 0.025) is classified at infinity, and
/// the other path still ends at its finite root. Family `p λ² − ε λ + ε c = 0` from
/// p = 1 to p = 0: one root tends to c, the other is ≈ ε/p. (The regression that
/// motivated the direct-finish veto, a jump onto another path's endpoint, is the
/// built-in example's `rigid/rigid` seed stage: see the `pipeline_curve` tests.)
#[test]
fn a_slowly_diverging_multiplier_is_classified_at_infinity() {
    use singdist::homotopy::{PathParameterHomotopy, PolylinePath, Tracker, TrackerOptions};
    use singdist::system::{Expr, System};
    let epsilon = 0.005;
    let c = C64::new(-0.5, 0.1);
    let lambda = Expr::variable("lambda");
    let p = Expr::parameter("p");
    let f = p * lambda.clone() * lambda.clone() - Expr::constant(C64::new(epsilon, 0.0)) * lambda
        + Expr::constant(c * epsilon);
    let system = System::new(["lambda"], ["p"], vec![f]).unwrap().compile();
    // Roots of λ² − ελ + εc (p = 1).
    let discriminant = (C64::new(epsilon * epsilon, 0.0) - 4.0 * epsilon * c).sqrt();
    let starts = [
        vec![(C64::new(epsilon, 0.0) + discriminant) / 2.0],
        vec![(C64::new(epsilon, 0.0) - discriminant) / 2.0],
    ];
    let homotopy = PathParameterHomotopy::new(
        &system,
        PolylinePath::new(vec![vec![C64::new(1.0, 0.0)], vec![C64::new(0.0, 0.0)]]),
    );
    for options in [
        TrackerOptions::default(),
        TrackerOptions::fast(),
        TrackerOptions::conservative(),
    ] {
        let mut tracker = Tracker::new(&homotopy, options);
        let results: Vec<_> = starts
            .iter()
            .enumerate()
            .map(|(i, x)| tracker.track(x, i))
            .collect();
        let finite: Vec<_> = results.iter().filter(|r| r.status.is_finite()).collect();
        assert_eq!(finite.len(), 1, "{results:?}");
        assert!((finite[0].solution[0] - c).norm() < 1e-8, "{results:?}");
        assert_eq!(
            results
                .iter()
                .filter(|r| r.status == PathStatus::AtInfinity)
                .count(),
            1,
            "{results:?}"
        );
    }
}

/// The same family homogenised, `p λ₁² − ε λ₁ λ₀ + ε c λ₀² = 0` in the chart
/// `c₀ λ₀ + c₁ λ₁ = 1` (the Fritz John form the curve pipeline tracks, see
/// `singdist::problem::Multipliers::Chart`): the root escaping to infinity now
/// converges, to `λ₀ = 0`, and is classified at infinity because `λ₀` is declared the
/// homogenising unknown; the other ends at `λ₁/λ₀ = c`. Undeclared, the same point is
/// an ordinary finite endpoint.
#[test]
fn a_root_on_the_hyperplane_at_infinity_of_a_chart_is_at_infinity() {
    use singdist::homotopy::{PathParameterHomotopy, PolylinePath, Tracker, TrackerOptions};
    use singdist::system::{Expr, System};
    let epsilon = 0.005;
    let c = C64::new(-0.5, 0.1);
    let (c0, c1) = (C64::new(0.8, 0.6), C64::new(-0.28, 0.96));
    let (l0, l1) = (Expr::variable("lambda0"), Expr::variable("lambda1"));
    let p = Expr::parameter("p");
    let f = p * l1.clone() * l1.clone()
        - Expr::constant(C64::new(epsilon, 0.0)) * l1.clone() * l0.clone()
        + Expr::constant(c * epsilon) * l0.clone() * l0.clone();
    let chart =
        Expr::constant(c0) * l0 + Expr::constant(c1) * l1 - Expr::constant(C64::new(1.0, 0.0));
    let system = System::new(["lambda0", "lambda1"], ["p"], vec![f, chart]).unwrap();
    let discriminant = (C64::new(epsilon * epsilon, 0.0) - 4.0 * epsilon * c).sqrt();
    // Affine roots λ of λ² − ελ + εc at p = 1, in the chart: λ₀ = 1/(c₀ + c₁λ).
    let starts: Vec<Vec<C64>> = [1.0, -1.0]
        .iter()
        .map(|&sign| {
            let lambda = (C64::new(epsilon, 0.0) + sign * discriminant) / 2.0;
            let lambda0 = (c0 + c1 * lambda).inv();
            vec![lambda0, lambda * lambda0]
        })
        .collect();
    for declared in [true, false] {
        let compiled = if declared {
            system
                .clone()
                .with_homogenizing_variable("lambda0")
                .unwrap()
                .compile()
        } else {
            system.compile()
        };
        let homotopy = PathParameterHomotopy::new(
            &compiled,
            PolylinePath::new(vec![vec![C64::new(1.0, 0.0)], vec![C64::new(0.0, 0.0)]]),
        );
        let mut tracker = Tracker::new(&homotopy, TrackerOptions::default());
        let results: Vec<_> = (0..starts.len())
            .map(|i| tracker.track(&starts[i], i))
            .collect();
        let (finite, at_infinity): (Vec<_>, Vec<_>) = results
            .iter()
            .filter(|r| r.status.is_finite() || r.status == PathStatus::AtInfinity)
            .partition(|r| r.status.is_finite());
        let at_infinity = at_infinity.len();
        if declared {
            assert_eq!((finite.len(), at_infinity), (1, 1), "{results:?}");
            let x = &finite[0].solution;
            assert!((x[1] / x[0] - c).norm() < 1e-8, "{results:?}");
        } else {
            assert_eq!((finite.len(), at_infinity), (2, 0), "{results:?}");
            assert!(
                finite.iter().any(|r| r.solution[0].norm() < 1e-12),
                "{results:?}"
            );
        }
    }
}

/// `λ² − p` (roots `±√p`), one unknown, one parameter.
fn square_root_family() -> singdist::system::CompiledSystem {
    use singdist::system::{Expr, System};
    let lambda = Expr::variable("lambda");
    let p = Expr::parameter("p");
    System::new(["lambda"], ["p"], vec![lambda.clone() * lambda - p])
        .unwrap()
        .compile()
}

/// The one-entry real vector `[v]`.
fn real(v: f64) -> Vec<C64> {
    vec![C64::new(v, 0.0)]
}

/// The parameter homotopy of a one-parameter `system` along `p: from → to`.
fn segment(
    system: &singdist::system::CompiledSystem,
    from: f64,
    to: f64,
) -> singdist::homotopy::PathParameterHomotopy<
    '_,
    singdist::system::CompiledSystem,
    singdist::homotopy::PolylinePath,
> {
    use singdist::homotopy::{PathParameterHomotopy, PolylinePath};
    PathParameterHomotopy::new(system, PolylinePath::new(vec![real(from), real(to)]))
}

/// Newton's method from a prediction ([`Tracker::correct_at`]) converges to the root
/// near the prediction to full accuracy in a few updates, fails from a point where the
/// Jacobian is singular, and does not report a double root (linear convergence) as a
/// nonsingular solution.
#[test]
fn newton_from_a_prediction_converges_only_to_nonsingular_roots() {
    use singdist::homotopy::{
        FailureReason, Tracker, TrackerOptions, tracker::CORRECT_AT_ITERATIONS,
    };
    use singdist::system::{Expr, System};
    let c = real;
    let system = square_root_family();
    let homotopy = segment(&system, 1.0, 4.0);
    let mut tracker = Tracker::new(&homotopy, TrackerOptions::fast());
    let near = tracker.correct_at(&c(1.8), 1.0, 0);
    assert_eq!(near.status, PathStatus::Nonsingular, "{near:?}");
    assert!((near.solution[0] - 2.0).norm() < 1e-14, "{near:?}");
    assert!(near.steps <= 5, "{near:?}");
    assert!(near.residual < 1e-13, "{near:?}");
    let other = tracker.correct_at(&c(-2.3), 1.0, 1);
    assert!((other.solution[0] + 2.0).norm() < 1e-14, "{other:?}");
    let singular = tracker.correct_at(&c(0.0), 1.0, 2);
    assert_eq!(
        singular.status,
        PathStatus::Failed(FailureReason::CorrectorDidNotConverge),
        "{singular:?}"
    );
    // (λ − p)²: a double root at λ = p, Newton's updates halve.
    let lambda = Expr::variable("lambda");
    let p = Expr::parameter("p");
    let double = System::new(
        ["lambda"],
        ["p"],
        vec![(lambda.clone() - p.clone()) * (lambda - p)],
    )
    .unwrap()
    .compile();
    let homotopy = segment(&double, 1.0, 2.0);
    let mut tracker = Tracker::new(&homotopy, TrackerOptions::fast());
    let result = tracker.correct_at(&c(2.1), 1.0, 0);
    assert_eq!(
        result.status,
        PathStatus::Failed(FailureReason::CorrectorDidNotConverge),
        "{result:?}"
    );
    assert_eq!(result.steps, CORRECT_AT_ITERATIONS, "{result:?}");
}

/// [`Tracker::track_via`] along a route through the complex `t`-plane reaches the
/// endpoint of the straight route when no branch point lies between them (`λ² − p`
/// branches only at `p = 0`, i.e. `t = −1/3`), on either side.
#[test]
fn tracking_around_an_arc_reaches_the_straight_route_endpoint() {
    use singdist::homotopy::{Tracker, TrackerOptions};
    let c = real;
    let system = square_root_family();
    let homotopy = segment(&system, 1.0, 4.0);
    let mut tracker = Tracker::new(&homotopy, TrackerOptions::fast());
    for start in [1.0, -1.0] {
        let straight = tracker.track(&c(start), 0);
        for side in [0.2, -0.2] {
            let via = [C64::new(0.3, 0.0), C64::new(0.5, side), C64::new(0.7, 0.0)];
            let around = tracker.track_via(&c(start), &via, 0);
            assert_eq!(around.status, PathStatus::Nonsingular, "{around:?}");
            assert!(
                (around.solution[0] - straight.solution[0]).norm() < 1e-12
                    && (around.solution[0] - 2.0 * start).norm() < 1e-12,
                "{around:?} vs {straight:?}"
            );
        }
    }
}

/// Rejected steps alone do not switch the tracker to extended precision: along
/// `λ² − p`, `p: 1 → 10⁴`, the Jacobian `2λ` is perfectly conditioned (1×1) but the
/// root grows a hundredfold, so long first steps are rejected.
#[test]
fn rejections_at_a_well_conditioned_point_keep_double_precision() {
    use singdist::homotopy::{Tracker, TrackerOptions};
    let c = real;
    let system = square_root_family();
    let homotopy = segment(&system, 1.0, 1e4);
    let mut options = TrackerOptions::fast();
    options.step.initial_step = 0.5;
    options.step.max_step = 0.5;
    assert!(options.precision.extended_after_rejections > 0);
    let mut tracker = Tracker::new(&homotopy, options);
    let result = tracker.track_between(&c(1.0), 0.0, 1.0, 0);
    assert_eq!(result.status, PathStatus::Nonsingular, "{result:?}");
    assert!((result.solution[0] - 100.0).norm() < 1e-10, "{result:?}");
    assert!(
        result.rejected_steps >= 3,
        "no rejections, nothing tested: {result:?}"
    );
    assert!(!result.used_extended_precision, "{result:?}");
}

/// A root far out (|λ| ≈ 3.7·10⁷) of a polynomial in expanded form,
/// `λ² − 2pλ + p² − δ²` with roots `p ± δ`: the terms are of order 10¹⁵, so the
/// double-precision residual carries rounding noise of order 0.1 and Newton's updates
/// stagnate near 10⁻¹⁰…10⁻⁸ relative, above [`Tracker::correct_at`]'s 10⁻⁹ floor (with
/// double precision only, this call fails 4·10⁻³ from the root). The correction goes
/// on in double-double and reaches the root to 10⁻⁶ absolute (3·10⁻¹⁴ relative).
#[test]
fn newton_from_a_prediction_goes_on_in_double_double_below_the_rounding_floor() {
    use singdist::homotopy::{PathParameterHomotopy, PolylinePath, Tracker, TrackerOptions};
    use singdist::system::{Expr, System};
    let (p, delta) = (3.0e7 + 0.3, 1.0);
    let lambda = Expr::variable("lambda");
    let q = Expr::parameter("p");
    let constant = |v: f64| Expr::constant(C64::new(v, 0.0));
    let expanded = lambda.clone() * lambda.clone() - constant(2.0) * q.clone() * lambda
        + q.clone() * q
        - constant(delta * delta);
    let system = System::new(["lambda"], ["p"], vec![expanded])
        .unwrap()
        .compile();
    let p = C64::new(p, 0.7 * p);
    let homotopy = PathParameterHomotopy::new(&system, PolylinePath::new(vec![vec![p], vec![p]]));
    let mut tracker = Tracker::new(&homotopy, TrackerOptions::fast());
    let result = tracker.correct_at(&[p + delta + 0.3], 1.0, 0);
    assert_eq!(result.status, PathStatus::Nonsingular, "{result:?}");
    assert!(result.used_extended_precision, "{result:?}");
    assert!(
        (result.solution[0] - (p + delta)).norm() < 1e-6,
        "{result:?}"
    );
}
