//! The compiled straight-line evaluator against the naive expression walker.

mod system_support;

use singdist::C64;
use singdist::random::seeded;
use singdist::system::{CompiledSystem, Evaluator, Expr, System};
use system_support::*;

fn check_compiled_equals_naive(system: &System, seed: u64, points: usize) {
    let compiled: CompiledSystem = system.compile();
    assert_eq!(compiled.num_variables(), system.variables().len());
    assert_eq!(compiled.num_parameters(), system.parameters().len());
    assert_eq!(compiled.num_equations(), system.num_equations());
    assert_eq!(compiled.variable_names(), system.variables());
    assert_eq!(compiled.parameter_names(), system.parameters());
    let (n, m, k) = (
        compiled.num_variables(),
        compiled.num_parameters(),
        compiled.num_equations(),
    );
    let mut work = compiled.new_workspace();
    assert_eq!(work.len(), compiled.workspace_len());
    // Poison the workspace: results must not depend on its previous content.
    work.iter_mut()
        .for_each(|w| *w = C64::new(f64::NAN, f64::NAN));
    let mut rng = seeded(seed);
    for _ in 0..points {
        let x = random_point(&mut rng, n);
        let p = random_point(&mut rng, m);
        let dp = random_point(&mut rng, m);
        let naive_f = system.evaluate_naive(&x, &p);
        let naive_jx = system.jacobian_naive(&x, &p);
        let naive_jp = system.parameter_jacobian_naive(&x, &p);
        let naive_directional: Vec<C64> = (0..k)
            .map(|i| (0..m).map(|j| naive_jp[i * m + j] * dp[j]).sum())
            .collect();

        let mut f = vec![C64::new(0.0, 0.0); k];
        compiled.evaluate(&x, &p, &mut work, &mut f);
        assert!(relative_error(&f, &naive_f) < 1e-12, "F");

        let mut f_extended = vec![C64::new(0.0, 0.0); k];
        compiled.evaluate_extended(&x, &p, &mut work, &mut f_extended);
        assert!(
            relative_error(&f_extended, &naive_f) < 1e-12,
            "F in double-double"
        );

        let mut f2 = vec![C64::new(0.0, 0.0); k];
        let mut jx = vec![C64::new(0.0, 0.0); k * n];
        compiled.evaluate_with_jacobian(&x, &p, &mut work, &mut f2, &mut jx);
        assert!(relative_error(&f2, &naive_f) < 1e-12, "F with Jacobian");
        assert!(relative_error(&jx, &naive_jx) < 1e-12, "∂F/∂x");

        let mut jp = vec![C64::new(0.0, 0.0); k * m];
        compiled.evaluate_parameter_jacobian(&x, &p, &mut work, &mut jp);
        if m > 0 {
            assert!(relative_error(&jp, &naive_jp) < 1e-12, "∂F/∂p");
        }

        let mut directional = vec![C64::new(0.0, 0.0); k];
        compiled.evaluate_parameter_derivative(&x, &p, &dp, &mut work, &mut directional);
        if m > 0 {
            assert!(
                relative_error(&directional, &naive_directional) < 1e-12,
                "∂F/∂p · dp"
            );
        } else {
            assert!(directional.iter().all(|v| *v == C64::new(0.0, 0.0)));
        }
    }
}

#[test]
fn compiled_random_systems_equal_naive_evaluation() {
    let mut rng = seeded(21);
    let (variables, parameters) = (symbol_names("x", 5), symbol_names("p", 3));
    for trial in 0..25 {
        let equations = random_equations(&mut rng, (&variables, &parameters), 4, 5);
        let system = System::new(&variables, &parameters, equations).unwrap();
        check_compiled_equals_naive(&system, 200 + trial, 3);
    }
}

#[test]
fn compiled_system_without_parameters() {
    let x = Expr::variable("x");
    let y = Expr::variable("y");
    let system = System::new(
        ["x", "y"],
        [""; 0],
        vec![x.pow(7) - &y + 2.0, &x * &y * (&x - 1.5)],
    )
    .unwrap();
    check_compiled_equals_naive(&system, 3, 5);
}

#[test]
fn compiled_plate_plate_lagrange_system_equals_naive_evaluation() {
    let system = plate_plate_system();
    check_compiled_equals_naive(&system, 31, 5);
}

#[test]
fn compiled_system_is_shareable_between_threads() {
    fn assert_send_sync<T: Send + Sync + Clone>() {}
    assert_send_sync::<CompiledSystem>();
    let system = plate_plate_system();
    let compiled = system.compile();
    let x = vec![C64::new(0.3, -0.2); 13];
    let p = vec![C64::new(-0.1, 0.4); 12];
    let reference = system.evaluate_naive(&x, &p);
    std::thread::scope(|scope| {
        for _ in 0..2 {
            let compiled = compiled.clone();
            let (x, p, reference) = (&x, &p, &reference);
            scope.spawn(move || {
                let mut work = compiled.new_workspace();
                let mut f = vec![C64::new(0.0, 0.0); 13];
                compiled.evaluate(x, p, &mut work, &mut f);
                assert!(relative_error(&f, reference) < 1e-12);
            });
        }
    });
}

/// `(x − 1)⁴` expanded, at `x = 1 + 2⁻²⁰`: the exact value `2⁻⁸⁰` is lost under the
/// rounding noise (~10⁻¹⁶) of the double-precision terms, but the double-double
/// evaluation (the tracker's extended-precision residual) keeps it.
#[test]
fn extended_evaluation_survives_catastrophic_cancellation() {
    let x = Expr::variable("x");
    let expanded = x.pow(4) - x.pow(3) * 4.0 + x.pow(2) * 6.0 - &x * 4.0 + 1.0;
    let system = System::new(["x"], [""; 0], vec![expanded]).unwrap();
    let compiled = system.compile();
    let mut work = compiled.new_workspace();
    let point = [C64::new(1.0 + 2f64.powi(-20), 0.0)];
    let exact = 2f64.powi(-80);
    let mut extended = [C64::new(0.0, 0.0)];
    compiled.evaluate_extended(&point, &[], &mut work, &mut extended);
    let mut double = [C64::new(0.0, 0.0)];
    compiled.evaluate(&point, &[], &mut work, &mut double);
    let extended_error = (extended[0] - exact).norm() / exact;
    let double_error = (double[0] - exact).norm() / exact;
    assert!(
        extended_error < 1e-12,
        "double-double error {extended_error:e}"
    );
    assert!(
        double_error >= 0.5,
        "double precision resolved 2^-80: {:e}",
        double[0]
    );
}

/// Without parameter derivatives a system evaluates F and ∂F/∂x as the full
/// compilation does, bit for bit, and its ∂F/∂p and (∂F/∂p)·dp are NaN.
#[test]
fn a_system_without_parameter_derivatives_evaluates_f_and_its_jacobian_alike() {
    let (x, y, p, q) = (
        Expr::variable("x"),
        Expr::variable("y"),
        Expr::parameter("p"),
        Expr::parameter("q"),
    );
    let system = System::new(
        ["x", "y"],
        ["p", "q"],
        vec![&p * &x * &y + &q * &x, &q * &y * &y - &p],
    )
    .unwrap();
    let (full, lean) = (
        CompiledSystem::new(&system),
        CompiledSystem::without_parameter_derivatives(&system),
    );
    let point = [C64::new(0.3, -1.2), C64::new(2.0, 0.5)];
    let parameters = [C64::new(-0.7, 0.1), C64::new(1.5, 2.0)];
    let evaluate = |s: &CompiledSystem| {
        let mut work = s.new_workspace();
        let (mut f, mut jac) = (vec![C64::new(0.0, 0.0); 2], vec![C64::new(0.0, 0.0); 4]);
        s.evaluate_with_jacobian(&point, &parameters, &mut work, &mut f, &mut jac);
        let mut dp = vec![C64::new(0.0, 0.0); 2];
        s.evaluate_parameter_derivative(&point, &parameters, &parameters, &mut work, &mut dp);
        (f, jac, dp)
    };
    let (f_full, jac_full, dp_full) = evaluate(&full);
    let (f_lean, jac_lean, dp_lean) = evaluate(&lean);
    assert_eq!(f_full, f_lean);
    assert_eq!(jac_full, jac_lean);
    assert!(dp_full.iter().all(|v| v.re.is_finite() && v.im.is_finite()));
    assert!(dp_lean.iter().all(|v| v.re.is_nan() && v.im.is_nan()));
}
