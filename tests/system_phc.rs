//! PHCpack export: expanded polynomials with numeric coefficients.

mod system_support;

use singdist::C64;
use singdist::random::seeded;
use singdist::system::{Expr, System, SystemError, phc};
use system_support::*;

#[test]
fn small_system_is_written_expanded() {
    // (x + y)^2 − p·x and x·y − 3
    let system = xy_system(|x, y, p| vec![(x + y).pow(2) - p * x, x * y - 3.0]);
    let text = phc::write(&system, &[("p".to_string(), C64::new(2.0, 0.0))]).unwrap();
    assert_eq!(
        text,
        "2\n1.0*x^2 + 2.0*x*y + 1.0*y^2 - 2.0*x;\n1.0*x*y - 3.0;\n"
    );
    let back = phc::read(&text).unwrap();
    assert_eq!(back.variables(), ["x", "y"]);
    assert_eq!(back.degrees(), vec![2, 2]);
}

#[test]
fn exported_polynomials_evaluate_like_the_system() {
    // Random systems with complex coefficients and parameter values: parse the PHC text
    // back and compare values at random points.
    let mut rng = seeded(77);
    let variables: Vec<String> = vec!["x".into(), "y".into(), "z".into()];
    let parameters: Vec<String> = vec!["a".into(), "b".into()];
    let symbols: Vec<String> = variables.iter().chain(&parameters).cloned().collect();
    for trial in 0..20 {
        let equations: Vec<Expr> = (0..3)
            .map(|_| random_expression(&mut rng, &symbols, 3) + Expr::variable("x"))
            .collect();
        let system = System::new(&variables, &parameters, equations).unwrap();
        let values = random_point(&mut rng, 2);
        let assignment: Vec<(String, C64)> = parameters
            .iter()
            .cloned()
            .zip(values.iter().copied())
            .collect();
        let text = phc::write(&system, &assignment).unwrap();
        let back = phc::read(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        // Variables read back in order of first appearance: reorder the point.
        let mut point_rng = seeded(500 + trial);
        for _ in 0..3 {
            let x = random_point(&mut point_rng, 3);
            let expected = system.evaluate_naive(&x, &values);
            let reordered: Vec<C64> = back
                .variables()
                .iter()
                .map(|name| x[variables.iter().position(|v| v == name).unwrap()])
                .collect();
            let got = back.evaluate_naive(&reordered, &[]);
            assert!(relative_error(&got, &expected) < 1e-12, "{text}");
        }
    }
}

#[test]
fn non_square_header_and_errors() {
    let x = Expr::variable("x");
    let y = Expr::variable("y");
    let system = System::new(["x", "y"], ["p"], vec![&x * &y - Expr::parameter("p")]).unwrap();
    let missing = phc::write(&system, &[]).unwrap_err();
    assert!(matches!(
        missing,
        phc::PhcWriteError::Parameters(SystemError::MissingParameterValue(_))
    ));
    let text = phc::write(&system, &[("p".into(), C64::new(0.0, -1.5))]).unwrap();
    assert_eq!(text, "1 2\n1.0*x*y + 1.5*i;\n");
    let named_e = System::new(["e"], [""; 0], vec![Expr::variable("e") - 1.0]).unwrap();
    assert!(matches!(
        phc::write(&named_e, &[]),
        Err(phc::PhcWriteError::InvalidName(_))
    ));
}

/// PHCpack's own files go on after the polynomials (a title, root counts, the solution
/// list `phc -b` appends): the reader stops after the declared number of polynomials.
#[test]
fn text_after_the_polynomials_is_ignored() {
    let text =
        "2\n x^2 + y - 1;\n x*y - 2;\n\nTITLE : a small system\n\nTHE SOLUTIONS :\n1 2\n=====\n";
    let system = phc::read(text).unwrap();
    assert_eq!(system.variables(), ["x", "y"]);
    assert_eq!(system.degrees(), vec![2, 2]);
    // Fewer polynomials than declared is still an error.
    assert!(phc::read("3\n x^2 + y - 1;\n x*y - 2;\n").is_err());
}
