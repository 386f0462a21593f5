//! Monodromy from one start pair, certified by the trace test.

mod homotopy_common;

use homotopy_common::*;
use singdist::C64;
use singdist::homotopy::{MonodromyOptions, monodromy_solve, trace_test};
use singdist::random::{complex_normal, seeded};

/// Random start pair of an all-coefficients-are-parameters family: random `x₀` and `p`,
/// then each equation's constant-term parameter is solved for so that `F(x₀; p) = 0`.
fn start_pair(system: &TermSystem, seed: u64) -> (Vec<C64>, Vec<C64>) {
    let mut rng = seeded(seed);
    let x0: Vec<C64> = (0..system.n).map(|_| complex_normal(&mut rng)).collect();
    let mut p: Vec<C64> = (0..system.m).map(|_| complex_normal(&mut rng)).collect();
    for eq in &system.equations {
        // Solve for the parameter of the first term (the constant term if there is one).
        let with_parameter = || eq.iter().filter(|t| t.parameter.is_some());
        let chosen = with_parameter()
            .find(|t| t.exponents.iter().all(|&e| e == 0))
            .or_else(|| with_parameter().next())
            .unwrap();
        let k = chosen.parameter.unwrap();
        p[k] = C64::new(0.0, 0.0);
        let one = TermSystem {
            n: system.n,
            m: system.m,
            equations: vec![eq.clone()],
        };
        let value = residual_signed(&one, &x0, &p);
        let monomial = x0
            .iter()
            .zip(&chosen.exponents)
            .fold(C64::new(1.0, 0.0), |a, (v, &e)| a * v.powu(e));
        p[k] = -value / (chosen.coefficient * monomial);
    }
    assert!(residual(system, &x0, &p) < 1e-12);
    (x0, p)
}

fn residual_signed(system: &TermSystem, x: &[C64], p: &[C64]) -> C64 {
    use singdist::system::Evaluator;
    let mut f = vec![C64::new(0.0, 0.0); 1];
    system.evaluate(x, p, &mut [], &mut f);
    f[0]
}

fn check_family(degrees: &[u32], expected: usize, seed: u64) {
    let (system, _) = parametric_dense(degrees, seed);
    let (x0, p0) = start_pair(&system, seed + 100);
    let result = monodromy_solve(&system, &x0, &p0, &MonodromyOptions::default(), seed).unwrap();
    assert_eq!(result.solutions.len(), expected, "{degrees:?}: {result:?}");
    let trace = result.trace_residual.unwrap();
    assert!(result.certified, "{degrees:?}: trace residual {trace:e}");
    for x in &result.solutions {
        assert!(residual(&system, x, &p0) < 1e-12);
    }
    // Independent check: total-degree solve of the same fiber finds the same set.
    let fixed = TermSystem {
        n: system.n,
        m: 0,
        equations: system
            .equations
            .iter()
            .map(|eq| {
                eq.iter()
                    .map(|t| Term {
                        coefficient: t.coefficient * p0[t.parameter.unwrap()],
                        parameter: None,
                        exponents: t.exponents.clone(),
                    })
                    .collect()
            })
            .collect(),
    };
    let td =
        singdist::homotopy::solve_total_degree(&fixed, degrees, &[], &Default::default()).unwrap();
    let td_solutions = td.nonsingular_solutions();
    assert_eq!(td_solutions.len(), expected);
    assert!(set_distance(&result.solutions, &td_solutions) < 1e-8);
    assert!(set_distance(&td_solutions, &result.solutions) < 1e-8);
}

#[test]
fn quadric_cubic_family_has_six_solutions_certified_by_trace() {
    check_family(&[2, 3], 6, 11);
}

#[test]
fn three_unknown_family_with_twelve_solutions_is_certified() {
    check_family(&[2, 2, 3], 12, 12);
}

/// Sparse family (the cyclic-5 monomial supports, every coefficient a parameter): its
/// generic count 70 is far below the Bézout number 120, so the fiber has solutions
/// at infinity and the witness set of the incidence curve is larger than the fiber.
#[test]
fn sparse_cyclic_5_family_has_seventy_solutions() {
    let (system, _) = coefficients_as_parameters(&cyclic(5));
    let (x0, p0) = start_pair(&system, 7);
    let result = monodromy_solve(&system, &x0, &p0, &MonodromyOptions::default(), 5).unwrap();
    assert_eq!(
        result.solutions.len(),
        70,
        "{:?}",
        (result.loops, result.trace_residual, result.witness_points)
    );
    assert!(result.certified, "{:?}", result.trace_residual);
}

/// `G(x) = p` with dense random `G` of degrees (2, 3): the parameters are the constant
/// terms, so the incidence curve has degree 6 = the fiber count and the trace test
/// without witness monodromy tests the fiber itself: complete passes, five of six fail.
#[test]
fn trace_test_detects_a_missing_solution() {
    let mut system = random_dense(&[2, 3], 21);
    system.m = 2;
    for (i, eq) in system.equations.iter_mut().enumerate() {
        eq.push(Term {
            coefficient: C64::new(-1.0, 0.0),
            parameter: Some(i),
            exponents: vec![0, 0],
        });
    }
    let (x0, p0) = start_pair(&system, 121);
    let result = monodromy_solve(&system, &x0, &p0, &MonodromyOptions::default(), 11).unwrap();
    assert_eq!(result.solutions.len(), 6);
    assert_eq!(result.witness_points, 6);
    assert!(result.certified);
    let options = MonodromyOptions {
        max_stagnant_loops: 0,
        ..MonodromyOptions::default()
    };
    let complete = trace_test(&system, &p0, &result.solutions, &options, &mut seeded(3)).unwrap();
    let incomplete = trace_test(
        &system,
        &p0,
        &result.solutions[..5],
        &options,
        &mut seeded(3),
    )
    .unwrap();
    assert!(complete.residual < 1e-10, "{}", complete.residual);
    assert!(incomplete.residual > 1e-4, "{}", incomplete.residual);
}

#[test]
fn invalid_start_pair_is_rejected() {
    let (system, p) = parametric_dense(&[2, 3], 1);
    let x = vec![C64::new(1.0, 0.0); 2];
    assert!(monodromy_solve(&system, &x, &p, &MonodromyOptions::default(), 0).is_err());
    assert!(monodromy_solve(&system, &x[..1], &p, &MonodromyOptions::default(), 0).is_err());
}

/// Monodromy in a restricted family: `x³ = p₁`, `y² = p₂`. With both parameters
/// moving, loops around `p₁ = 0` and `p₂ = 0` carry one solution to all six
/// `(a ωᵏ, ±b)`; with `p₂` pinned (as a design's shape constants are) the restricted
/// family's fiber splits into two orbits and the loops reach the three `(a ωᵏ, b)`;
/// with nothing moving every loop is trivial and adds nothing.
#[test]
fn a_fiber_is_completed_by_loops_of_the_moving_parameters_alone() {
    use singdist::homotopy::{TrackerOptions, complete_fiber};
    let monomial = |coefficient: f64, parameter: Option<usize>, exponents: [u32; 2]| Term {
        coefficient: C64::new(coefficient, 0.0),
        parameter,
        exponents: exponents.to_vec(),
    };
    let system = TermSystem {
        n: 2,
        m: 2,
        equations: vec![
            vec![monomial(1.0, None, [3, 0]), monomial(-1.0, Some(0), [0, 0])],
            vec![monomial(1.0, None, [0, 2]), monomial(-1.0, Some(1), [0, 0])],
        ],
    };
    let (a, b) = (C64::new(0.7, 0.4), C64::new(-0.5, 0.9));
    let x0 = vec![a, b];
    let p0 = vec![a * a * a, b * b];
    let tracker = TrackerOptions::default();
    let omega = C64::new(-0.5, 3f64.sqrt() / 2.0);
    let orbit = |signs: &[f64]| -> Vec<Vec<C64>> {
        let mut points = Vec::new();
        for &sign in signs {
            for k in 0..3 {
                points.push(vec![a * omega.powu(k), b * sign]);
            }
        }
        points
    };
    let cases = [
        (2, orbit(&[1.0, -1.0])),
        (1, orbit(&[1.0])),
        (0, vec![x0.clone()]),
    ];
    for (moving, expected) in cases {
        let mut solutions = vec![x0.clone()];
        let completion = complete_fiber(
            &system,
            (&p0, moving),
            &mut solutions,
            (6, 8),
            &tracker,
            &mut seeded(4),
        );
        assert_eq!(solutions.len(), expected.len(), "{moving}: {completion:?}");
        assert_eq!(completion.added, expected.len() - 1);
        assert!(!completion.abandoned);
        assert!(set_distance(&solutions, &expected) < 1e-10, "{moving}");
        assert!(set_distance(&expected, &solutions) < 1e-10, "{moving}");
        for x in &solutions {
            assert!(residual(&system, x, &p0) < 1e-12);
        }
    }
}
