//! `System`: validation, degrees, Bézout number, parameter substitution, Lagrange.

mod system_support;

use singdist::C64;
use singdist::algebra::{Ring, det3};
use singdist::system::{Expr, System, SystemError};
use system_support::*;

#[test]
fn invalid_systems_are_rejected_with_the_offending_name() {
    let x = Expr::variable("x");
    let q = Expr::variable("q");
    assert_eq!(
        System::new(["x"], ["p"], vec![&x + &q]).unwrap_err(),
        SystemError::UnknownSymbol {
            symbol: "q".into(),
            equation: 0
        }
    );
    assert_eq!(
        System::new(["x", "x"], [""; 0], vec![x.clone()]).unwrap_err(),
        SystemError::DuplicateSymbol("x".into())
    );
    assert_eq!(
        System::new(["x"], ["x"], vec![x.clone()]).unwrap_err(),
        SystemError::DuplicateSymbol("x".into())
    );
    assert_eq!(
        System::new(["x"], [""; 0], vec![]).unwrap_err(),
        SystemError::EmptySystem
    );
    assert_eq!(
        System::new([""; 0], ["p"], vec![Expr::parameter("p")]).unwrap_err(),
        SystemError::NoVariables
    );
}

#[test]
fn degrees_see_cancellations_and_treat_parameters_as_coefficients() {
    let system = xy_system(|x, y, p| {
        vec![
            // (x + y)² − x² − 2xy = y²: degree 2 though the tree has x² terms.
            (x + y).pow(2) - x.pow(2) - 2.0 * x * y,
            // p³·x: degree 1 in the variables.
            p.pow(3) * x - 1.0,
            // (x·y)³ − (x·y)³ + x: degree 1 after cancellation.
            (x * y).pow(3) - (y * x).pow(3) + x,
        ]
    });
    assert_eq!(system.degrees(), vec![2, 1, 1]);
    assert_eq!(system.bezout_number(), 2);
}

#[test]
fn plate_plate_lagrange_system_shape() {
    let system = plate_plate_system();
    // ∂Λ/∂(coordinate) = linear − λ·(cubic) has degree 4, ∂Λ/∂λ = −S has degree 4.
    assert_eq!(system.degrees(), vec![4; 13]);
    assert_eq!(system.bezout_number(), 4u128.pow(13));
    // At K′ = K (no displacement) and λ = 0 the gradient of D² vanishes, so the first 12
    // equations vanish and the last is −S(K).
    let mut rng = singdist::random::seeded(3);
    let k = random_point(&mut rng, 12);
    let mut x = k.clone();
    x.push(C64::new(0.0, 0.0));
    let f = system.evaluate_naive(&x, &k);
    assert!(f[..12].iter().all(|v| v.norm() < 1e-14));
    // S(K) by the generic det3 over C64.
    let (a, b) = (&k[..6], &k[6..]);
    let row = |i: usize| {
        let (ax, ay, bx, by) = (a[2 * i], a[2 * i + 1], b[2 * i], b[2 * i + 1]);
        [bx - ax, by - ay, ax * by - ay * bx]
    };
    let s = det3(&[row(0), row(1), row(2)]);
    assert!((f[12] + s).norm() < 1e-12 * s.norm().max(1.0));
    let _ = C64::from_f64(0.0);
}

#[test]
fn parameter_values_are_substituted() {
    let x = Expr::variable("x");
    let p = Expr::parameter("p");
    let system = System::new(["x"], ["p"], vec![&x * &p - 1.0]).unwrap();
    let fixed = system
        .with_parameter_values(&[("p".into(), C64::new(2.0, 1.0))])
        .unwrap();
    assert!(fixed.parameters().is_empty());
    let value = fixed.evaluate_naive(&[C64::new(1.0, 0.0)], &[]);
    assert_eq!(value[0], C64::new(1.0, 1.0));
    assert_eq!(
        system.with_parameter_values(&[]).unwrap_err(),
        SystemError::MissingParameterValue("p".into())
    );
    assert_eq!(
        system
            .with_parameter_values(&[
                ("p".into(), C64::new(1.0, 0.0)),
                ("z".into(), C64::new(1.0, 0.0))
            ])
            .unwrap_err(),
        SystemError::NotAParameter("z".into())
    );
}
