//! Exact symbolic derivatives against central finite differences.

mod system_support;

use singdist::C64;
use singdist::random::seeded;
use singdist::system::{Expr, System};
use system_support::*;

/// Central differences of the naive evaluator with respect to the variables (`wrt_x`)
/// or the parameters, row-major like the Jacobians.
fn finite_difference_jacobian(system: &System, x: &[C64], p: &[C64], wrt_x: bool) -> Vec<C64> {
    let k = system.num_equations();
    let columns = if wrt_x { x.len() } else { p.len() };
    let mut jac = vec![C64::new(0.0, 0.0); k * columns];
    // Step along a complex direction so the complex-analytic derivative is probed.
    let h = C64::new(1e-5, 0.7e-5);
    for j in 0..columns {
        let (mut xp, mut pp) = (x.to_vec(), p.to_vec());
        let (mut xm, mut pm) = (x.to_vec(), p.to_vec());
        if wrt_x {
            xp[j] += h;
            xm[j] -= h;
        } else {
            pp[j] += h;
            pm[j] -= h;
        }
        let fp = system.evaluate_naive(&xp, &pp);
        let fm = system.evaluate_naive(&xm, &pm);
        for i in 0..k {
            jac[i * columns + j] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    jac
}

fn check_against_finite_differences(system: &System, seed: u64, points: usize) {
    let mut rng = seeded(seed);
    for _ in 0..points {
        let x = random_point(&mut rng, system.variables().len());
        let p = random_point(&mut rng, system.parameters().len());
        let exact = system.jacobian_naive(&x, &p);
        let numeric = finite_difference_jacobian(system, &x, &p, true);
        let error = relative_error(&numeric, &exact);
        assert!(error < 1e-7, "∂F/∂x relative error {error:e}");
        if !system.parameters().is_empty() {
            let exact = system.parameter_jacobian_naive(&x, &p);
            let numeric = finite_difference_jacobian(system, &x, &p, false);
            let error = relative_error(&numeric, &exact);
            assert!(error < 1e-7, "∂F/∂p relative error {error:e}");
        }
    }
}

#[test]
fn derivatives_of_random_polynomial_systems_match_finite_differences() {
    let mut rng = seeded(11);
    let (variables, parameters) = (symbol_names("x", 4), symbol_names("p", 2));
    let mut nontrivial = 0;
    for trial in 0..20 {
        let equations = random_equations(&mut rng, (&variables, &parameters), 4, 4);
        let used: Vec<String> = equations.iter().flat_map(|e| e.symbols()).collect();
        if used.iter().any(|s| variables.contains(s)) {
            nontrivial += 1;
        }
        let system = System::new(&variables, &parameters, equations).expect("valid system");
        check_against_finite_differences(&system, 100 + trial, 3);
    }
    assert!(
        nontrivial >= 15,
        "random systems should mostly involve the variables"
    );
}

#[test]
fn derivatives_of_plate_plate_lagrange_system_match_finite_differences() {
    let system = plate_plate_system();
    assert_eq!(system.variables().len(), 13);
    assert_eq!(system.parameters().len(), 12);
    assert_eq!(system.num_equations(), 13);
    check_against_finite_differences(&system, 7, 3);
}

#[test]
fn lagrange_equations_are_the_gradient_by_finite_differences() {
    // ∂Λ/∂v from finite differences of Λ itself, independent of `System::lagrange`.
    let (lagrangian, variables, parameters) = plate_plate_lagrangian();
    let system = plate_plate_system();
    let lagrangian_system = System::new(&variables, &parameters, vec![lagrangian]).unwrap();
    let mut rng = seeded(5);
    let x = random_point(&mut rng, 13);
    let p = random_point(&mut rng, 12);
    let gradient = finite_difference_jacobian(&lagrangian_system, &x, &p, true);
    let equations = system.evaluate_naive(&x, &p);
    let error = relative_error(&gradient, &equations);
    assert!(error < 1e-7, "gradient relative error {error:e}");
}

#[test]
fn differentiation_simplifies_zeros_and_ones() {
    let x = Expr::variable("x");
    let y = Expr::variable("y");
    assert!(y.differentiate("x").is_zero());
    assert!(x.differentiate("x").is_one());
    assert!((3.0 * &y).differentiate("x").is_zero());
    let d = (x.pow(3) * &y).differentiate("x");
    let value = d
        .evaluate(|s| match s {
            "x" => Some(C64::new(2.0, 0.0)),
            "y" => Some(C64::new(5.0, 0.0)),
            _ => None,
        })
        .unwrap();
    assert_eq!(value, C64::new(60.0, 0.0));
    assert_eq!(x.pow(0).as_constant(), Some(C64::new(1.0, 0.0)));
}
