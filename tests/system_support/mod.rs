//! Shared builders for the `system_*` tests and the `system_eval` benchmark.
#![allow(dead_code)]

use singdist::C64;
use singdist::algebra::{Point, cross, det3, difference, dot};
use singdist::random::{SeededRng, complex_normal, uniform};
use singdist::system::{Expr, System};

/// The system in the unknowns `x`, `y` and the parameter `p` with the equations
/// `equations(x, y, p)`.
pub fn xy_system(equations: impl FnOnce(&Expr, &Expr, &Expr) -> Vec<Expr>) -> System {
    let (x, y) = (Expr::variable("x"), Expr::variable("y"));
    let p = Expr::parameter("p");
    System::new(["x", "y"], ["p"], equations(&x, &y, &p)).unwrap()
}

/// `|d|²` written with `dot` so it is a polynomial (no conjugation).
fn squared<T: singdist::algebra::Ring>(d: &Point<T>) -> T {
    dot(d, d)
}

/// `seg²` of docs/theory.md §2 from the displacements of the two end points.
pub fn seg2(d1: &Point<Expr>, d2: &Point<Expr>) -> Expr {
    (squared(d1) + squared(d2) + dot(d1, d2)) * (1.0 / 3.0)
}

/// `tri²` of docs/theory.md §2 from the displacements of the three corners.
pub fn tri2(d: &[Point<Expr>; 3]) -> Expr {
    (squared(&d[0])
        + squared(&d[1])
        + squared(&d[2])
        + dot(&d[0], &d[1])
        + dot(&d[0], &d[2])
        + dot(&d[1], &d[2]))
        * (1.0 / 6.0)
}

/// Singularity polynomial S of docs/theory.md §1.3 of the configuration (a_1..a_3,
/// b_1..b_3).
pub fn singularity_polynomial(a: &[Point<Expr>; 3], b: &[Point<Expr>; 3]) -> Expr {
    let row = |i: usize| {
        let leg = difference(&a[i], &b[i]);
        [leg[0].clone(), leg[1].clone(), cross(&a[i], &b[i])]
    };
    det3(&[row(0), row(1), row(2)])
}

fn point(prefix: &str, i: usize, make: fn(String) -> Expr) -> Point<Expr> {
    [make(format!("{prefix}{i}x")), make(format!("{prefix}{i}y"))]
}

/// Names of the 12 coordinates with the given prefixes (`a1x, a1y, …, b3y`).
pub fn coordinate_names(a: &str, b: &str) -> Vec<String> {
    let mut names = Vec::new();
    for prefix in [a, b] {
        for i in 1..=3 {
            names.push(format!("{prefix}{i}x"));
            names.push(format!("{prefix}{i}y"));
        }
    }
    names
}

/// The Lagrangian `Λ = D²(K, K′) − λ S(K′)` of the singularity-variety sub-problem of
/// the metric plate/plate (docs/theory.md §3, §5): unknowns K′ = a1x..b3y and `lambda`,
/// parameters K = A1x..B3y.
pub fn plate_plate_lagrangian() -> (Expr, Vec<String>, Vec<String>) {
    let a_new: [Point<Expr>; 3] = std::array::from_fn(|i| point("a", i + 1, Expr::variable));
    let b_new: [Point<Expr>; 3] = std::array::from_fn(|i| point("b", i + 1, Expr::variable));
    let a_old: [Point<Expr>; 3] = std::array::from_fn(|i| point("A", i + 1, Expr::parameter));
    let b_old: [Point<Expr>; 3] = std::array::from_fn(|i| point("B", i + 1, Expr::parameter));
    let da: [Point<Expr>; 3] = std::array::from_fn(|i| difference(&a_old[i], &a_new[i]));
    let db: [Point<Expr>; 3] = std::array::from_fn(|i| difference(&b_old[i], &b_new[i]));
    let legs: Expr = (0..3).map(|i| seg2(&da[i], &db[i])).sum();
    let distance2 = (legs + tri2(&db) + tri2(&da)) * (1.0 / 5.0);
    let lambda = Expr::variable("lambda");
    let lagrangian = distance2 - lambda * singularity_polynomial(&a_new, &b_new);
    let mut variables = coordinate_names("a", "b");
    variables.push("lambda".to_string());
    (lagrangian, variables, coordinate_names("A", "B"))
}

/// The 13×13 Lagrange system of [`plate_plate_lagrangian`].
pub fn plate_plate_system() -> System {
    let (lagrangian, variables, parameters) = plate_plate_lagrangian();
    System::lagrange(&lagrangian, &variables, &parameters).expect("valid Lagrange system")
}

/// A random polynomial expression of the given depth in `symbols`.
pub fn random_expression(rng: &mut SeededRng, symbols: &[String], depth: u32) -> Expr {
    let leaf = |rng: &mut SeededRng| {
        if uniform(rng, 0.0, 1.0) < 0.25 {
            Expr::constant(complex_normal(rng))
        } else {
            let i = (uniform(rng, 0.0, symbols.len() as f64) as usize).min(symbols.len() - 1);
            Expr::variable(&symbols[i])
        }
    };
    if depth == 0 {
        return leaf(rng);
    }
    let choice = uniform(rng, 0.0, 6.0) as u32;
    let a = random_expression(rng, symbols, depth - 1);
    match choice {
        0 => a + random_expression(rng, symbols, depth - 1),
        1 => a - random_expression(rng, symbols, depth - 1),
        2 | 3 => a * random_expression(rng, symbols, depth - 1),
        4 => -a + 0.5,
        _ => a.pow(2 + uniform(rng, 0.0, 3.0) as u32),
    }
}

/// A random point with `n` complex coordinates of modulus about 1.
pub fn random_point(rng: &mut SeededRng, n: usize) -> Vec<C64> {
    (0..n).map(|_| complex_normal(rng)).collect()
}

/// `max |a_i − b_i| / max(max |b_i|, tiny)`.
pub fn relative_error(a: &[C64], b: &[C64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().map(|v| v.norm()).fold(0.0, f64::max).max(1e-300);
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max)
        / scale
}

/// `PREFIX0, PREFIX1, …`: `count` symbol names.
pub fn symbol_names(prefix: &str, count: usize) -> Vec<String> {
    (0..count).map(|i| format!("{prefix}{i}")).collect()
}

/// `count` random expressions ([`random_expression`] of `depth`) in the variables and
/// parameters.
pub fn random_equations(
    rng: &mut SeededRng,
    (variables, parameters): (&[String], &[String]),
    count: usize,
    depth: u32,
) -> Vec<Expr> {
    let symbols: Vec<String> = variables.iter().chain(parameters).cloned().collect();
    (0..count)
        .map(|_| random_expression(rng, &symbols, depth))
        .collect()
}
