//! Equation and variable scaling of a polynomial system by powers of two, chosen by
//! least squares on the logarithms of the coefficients.
//!
//! A system whose coefficients span many orders of magnitude, or whose solutions have
//! coordinates of very different sizes (`pb601`: coordinates from 10⁻⁷ to 10,
//! coefficients from 10⁻¹³ to 8), is badly conditioned for a path tracker: its
//! absolute tolerances cannot tell a cluster of tiny distinct roots from one
//! multiple root, nor a path to a small root from one to infinity. Substituting
//! `x_j = 2^{d_j} y_j` and multiplying equation `i` by `2^{c_i}` changes term
//! `a_{iα} x^α` into `a_{iα} 2^{c_i + α·d} y^α`. The exponents minimise
//!
//! `Σ_{i,α} (log₂|a_{iα}| + c_i + α·d)²`
//!
//! over every term of every equation (Morgan's coefficient scaling: A. P. Morgan,
//! *Solving Polynomial Systems Using Continuation for Engineering and Scientific
//! Problems*, Prentice-Hall 1987, ch. 5; also PHCpack's scaling option), plus a tiny
//! multiple of `|c|² + |d|²` that picks the least-norm minimiser where the terms do not
//! determine one (homogeneous equations). Rounded to integers, the exponents scale
//! every coefficient and every coordinate exactly: the scaled system has the same
//! roots, each mapped by `x_j = 2^{d_j} y_j` without rounding.

use crate::C64;
use crate::system::sparse::SparsePolynomial;
use crate::system::{Expr, System};
use nalgebra::{DMatrix, DVector};

/// Weight of the least-norm term `|c|² + |d|²` relative to the terms' equations.
const LEAST_NORM_WEIGHT: f64 = 1e-8;

/// Binary orders of magnitude by which the equations' sizes must differ before they
/// are normalised alone ([`Scaling::unbalanced_equations`]): a factor `2^8 = 256`.
pub const BADLY_SCALED_RMS: f64 = 8.0;

/// Root-mean-square (in binary orders of magnitude) above which the least-squares
/// variable scaling is considered ([`Scaling::worthwhile`]): a factor `2^4 = 16` on
/// average. PHCpack's `cohn2` and `cohn3` (5.7 → 1.3 and 2.1 binary orders) and
/// `chemequ` (7.8 → 3.6) lie between it and [`BADLY_SCALED_RMS`]; solved unscaled,
/// `cohn3` failed 31 of its 269 polyhedral paths in 26 s on one thread, scaled none in
/// 3.1 s with 129 nonsingular roots (each converging quadratically under Newton's
/// method in 60-digit arithmetic; unscaled it found 121), `cohn2` took 0.57 → 0.19 s.
pub const WORTH_SCALING_RMS: f64 = 4.0;

/// Largest binary exponent a scaled term's factors may reach (`|c_i| + Σ α_j |d_j|`):
/// far inside the double range (`2^{±1022}`), so that no power of a scaled variable
/// overflows or underflows before the coefficient brings it back.
const MAX_EXPONENT: i64 = 900;

/// Exponents `c_i` (equation `i` times `2^{c_i}`) and `d_j` (`x_j = 2^{d_j} y_j`).
#[derive(Debug, Clone, PartialEq)]
pub struct Scaling {
    /// `c_i`, one per equation.
    pub equations: Vec<i32>,
    /// `d_j`, one per variable.
    pub variables: Vec<i32>,
    /// Root-mean-square of `log₂|a_{iα}| + c_i` over the terms with each equation
    /// only normalised (`d = 0`, `c_i` the mean of its terms): the spread the variable
    /// scaling works on.
    pub rms_before: f64,
    /// Root-mean-square of `log₂|a_{iα}| + c_i + α·d` with the chosen exponents.
    pub rms_after: f64,
}

/// `(equation, exponent vector, log₂|coefficient|)` of one term.
type LogTerm = (usize, Vec<u32>, f64);

/// The [`log_terms`] of a system that can be scaled (no parameters left, not
/// homogenised, every equation expandable), with its numbers of equations and unknowns.
fn scalable_terms(system: &System) -> Option<(Vec<LogTerm>, usize, usize)> {
    scalable_terms_of(system, &system.expand().ok()?)
}

/// [`scalable_terms`] from the system's expansion.
fn scalable_terms_of(
    system: &System,
    expansion: &[SparsePolynomial],
) -> Option<(Vec<LogTerm>, usize, usize)> {
    if !system.parameters().is_empty() || system.homogenizing().is_some() {
        return None;
    }
    let terms = log_terms(system.variables().len(), expansion)?;
    Some((terms, system.num_equations(), system.variables().len()))
}

/// `(equation, exponent vector, log₂|coefficient|)` of every non-zero term of the
/// expansion of a system in `n` unknowns.
fn log_terms(n: usize, polynomials: &[SparsePolynomial]) -> Option<Vec<LogTerm>> {
    let mut terms = Vec::new();
    for (i, polynomial) in polynomials.iter().enumerate() {
        for (monomial, coefficient) in &polynomial.terms {
            // Parameters have been given values; a parameter left in a term makes the
            // coefficient unknown.
            if monomial[n..].iter().any(|&e| e != 0) {
                return None;
            }
            let size = coefficient.norm();
            if size > 0.0 && size.is_finite() {
                terms.push((i, monomial[..n].to_vec(), size.log2()));
            }
        }
    }
    Some(terms)
}

/// Root-mean-square of `log₂|a| + c_i + α·d` over `terms`.
fn rms(terms: &[(usize, Vec<u32>, f64)], c: &[f64], d: &[f64]) -> f64 {
    if terms.is_empty() {
        return 0.0;
    }
    let sum: f64 = terms
        .iter()
        .map(|(i, alpha, log)| {
            let r = log
                + c[*i]
                + alpha
                    .iter()
                    .zip(d)
                    .map(|(&e, dj)| e as f64 * dj)
                    .sum::<f64>();
            r * r
        })
        .sum();
    (sum / terms.len() as f64).sqrt()
}

/// `−mean of log₂|a_{iα}|` over the terms of each of the `m` equations (0 for an
/// equation without terms): the equation-wise normalisation.
fn normalising_exponents(terms: &[(usize, Vec<u32>, f64)], m: usize) -> Vec<f64> {
    let mut sums = vec![(0.0, 0usize); m];
    for (i, _, log) in terms {
        sums[*i].0 += log;
        sums[*i].1 += 1;
    }
    sums.iter()
        .map(|&(s, k)| if k > 0 { -s / k as f64 } else { 0.0 })
        .collect()
}

impl Scaling {
    /// The scaling `solve --scaling auto` solves in: the least-squares one where it is
    /// [`Scaling::worthwhile`], else the equation-only normalisation where the
    /// equations are [`Scaling::unbalanced_equations`], else none.
    pub fn automatic(system: &System) -> Option<Scaling> {
        Scaling::automatic_of_expansion(system, &system.expand().ok()?)
    }

    /// [`Scaling::automatic`] from the system's expansion ([`System::expand`]), when the
    /// caller has it already.
    pub fn automatic_of_expansion(
        system: &System,
        expansion: &[SparsePolynomial],
    ) -> Option<Scaling> {
        // One expansion of the system for both candidates.
        let (terms, m, n) = scalable_terms_of(system, expansion)?;
        Scaling::least_squares_of(&terms, m, n)
            .filter(Scaling::worthwhile)
            .or_else(|| {
                Some(Scaling::equations_only_of(&terms, m, n)).filter(Scaling::unbalanced_equations)
            })
    }

    /// Equation-only normalisation of `system` (no parameters left, every equation
    /// expandable): `c_i` the negated mean of equation `i`'s `log₂|a_{iα}|`, rounded,
    /// and `d = 0`, so the roots and their coordinates are unchanged. `rms_before` and
    /// `rms_after` are both the spread left within the equations.
    pub fn equations_only(system: &System) -> Option<Scaling> {
        let (terms, m, n) = scalable_terms(system)?;
        Some(Scaling::equations_only_of(&terms, m, n))
    }

    /// [`Scaling::equations_only`] of the terms of a system of `m` equations in `n`
    /// unknowns ([`scalable_terms`]).
    fn equations_only_of(terms: &[LogTerm], m: usize, n: usize) -> Scaling {
        let equations: Vec<i32> = normalising_exponents(terms, m)
            .iter()
            .map(|c| c.round().clamp(-900.0, 900.0) as i32)
            .collect();
        let c: Vec<f64> = equations.iter().map(|&e| e as f64).collect();
        let spread = rms(terms, &c, &vec![0.0; n]);
        Scaling {
            equations,
            variables: vec![0; n],
            rms_before: spread,
            rms_after: spread,
        }
    }

    /// Whether the equations' sizes differ by more than `2^BADLY_SCALED_RMS`: their
    /// normalising exponents span more than [`BADLY_SCALED_RMS`] binary orders. The
    /// straight-line homotopy `γ(1 − t)G + tF` from a start system `G` of unit
    /// coefficients then lets the large equations of `F` dominate from `t ≈ 0`
    /// (PHCpack's `rbpl24`: equations from 6·10⁴ to 10¹⁴; every path failed at
    /// `t = 0` and its 40 roots were missed).
    pub fn unbalanced_equations(&self) -> bool {
        let (lo, hi) = self
            .equations
            .iter()
            .fold((i32::MAX, i32::MIN), |(lo, hi), &c| (lo.min(c), hi.max(c)));
        !self.equations.is_empty() && f64::from(hi - lo) > BADLY_SCALED_RMS
    }

    /// The least-squares scaling of `system` (no parameters left, every equation
    /// expandable, every scaled factor within 2^±900, `MAX_EXPONENT`); `None` otherwise.
    pub fn least_squares(system: &System) -> Option<Scaling> {
        let (terms, m, n) = scalable_terms(system)?;
        Scaling::least_squares_of(&terms, m, n)
    }

    /// [`Scaling::least_squares`] of the terms of a system of `m` equations in `n`
    /// unknowns ([`scalable_terms`]).
    fn least_squares_of(terms: &[LogTerm], m: usize, n: usize) -> Option<Scaling> {
        // Equation-only normalisation: c_i = −mean of equation i's log sizes.
        let normalised = normalising_exponents(terms, m);
        let rms_before = rms(terms, &normalised, &vec![0.0; n]);
        // Normal equations of the least-squares problem in z = (c, d).
        let size = m + n;
        let mut normal = DMatrix::<f64>::identity(size, size) * LEAST_NORM_WEIGHT;
        let mut rhs = DVector::<f64>::zeros(size);
        let mut row = vec![0.0; size];
        for (i, alpha, log) in terms {
            row.iter_mut().for_each(|r| *r = 0.0);
            row[*i] = 1.0;
            for (j, &e) in alpha.iter().enumerate() {
                row[m + j] = e as f64;
            }
            for (a, &ra) in row.iter().enumerate() {
                if ra == 0.0 {
                    continue;
                }
                rhs[a] -= ra * log;
                for (b, &rb) in row.iter().enumerate() {
                    normal[(a, b)] += ra * rb;
                }
            }
        }
        let z = normal.cholesky()?.solve(&rhs);
        let round = |v: f64| v.round().clamp(-2000.0, 2000.0) as i32;
        let equations: Vec<i32> = (0..m).map(|i| round(z[i])).collect();
        let variables: Vec<i32> = (0..n).map(|j| round(z[m + j])).collect();
        let as_f64 = |v: &[i32]| v.iter().map(|&e| e as f64).collect::<Vec<_>>();
        // The scaled system evaluates 2^{d_j}·y_j, its powers and 2^{c_i} apart: every
        // such factor must stay far inside the double range.
        let representable = terms.iter().all(|(i, alpha, _)| {
            let shift: i64 = alpha
                .iter()
                .zip(&variables)
                .map(|(&e, &d)| e as i64 * (d as i64).abs())
                .sum();
            (equations[*i] as i64).abs() + shift <= MAX_EXPONENT
        });
        if !representable {
            return None;
        }
        let rms_after = rms(terms, &as_f64(&equations), &as_f64(&variables));
        Some(Scaling {
            equations,
            variables,
            rms_before,
            rms_after,
        })
    }

    /// Whether the variable scaling is worth its change of coordinates: the
    /// coefficients spread over more than [`WORTH_SCALING_RMS`] binary orders and the
    /// scaling at least halves their spread.
    pub fn worthwhile(&self) -> bool {
        self.variables.iter().any(|&d| d != 0)
            && self.rms_before > WORTH_SCALING_RMS
            && self.rms_after <= 0.5 * self.rms_before
    }

    /// The scaled system `2^{c_i} f_i(2^{d_1} y_1, …, 2^{d_n} y_n)` in the same
    /// variable names (whose values are now the `y_j`).
    pub fn apply(&self, system: &System) -> System {
        let variables = system.variables();
        let factors: Vec<Expr> = self
            .variables
            .iter()
            .zip(variables)
            .map(|(&d, name)| Expr::constant(C64::new(2f64.powi(d), 0.0)) * Expr::variable(name))
            .collect();
        let substitute = |name: &str| {
            variables
                .iter()
                .position(|v| v == name)
                .map(|j| factors[j].clone())
        };
        let equations = system
            .equations()
            .iter()
            .zip(&self.equations)
            .map(|(f, &c)| Expr::constant(C64::new(2f64.powi(c), 0.0)) * f.substitute(&substitute))
            .collect();
        System::new(variables, system.parameters(), equations)
            .expect("the same symbols as a valid system")
    }

    /// A point `x` of the original coordinates in the scaled ones: `y_j = 2^{−d_j} x_j`
    /// (exact; the inverse of [`Scaling::unscale`]).
    pub fn scale(&self, x: &[C64]) -> Vec<C64> {
        x.iter()
            .zip(&self.variables)
            .map(|(z, &d)| z * 2f64.powi(-d))
            .collect()
    }

    /// A solution `y` of the scaled system as one of the original: `x_j = 2^{d_j} y_j`
    /// (exact).
    pub fn unscale(&self, y: &[C64]) -> Vec<C64> {
        y.iter()
            .zip(&self.variables)
            .map(|(z, &d)| z * 2f64.powi(d))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(re: f64) -> Expr {
        Expr::constant(C64::new(re, 0.0))
    }

    /// The system `equations` in the unknowns `x`, `y`.
    fn in_x_and_y(equations: Vec<Expr>) -> System {
        System::new(["x", "y"], Vec::<String>::new(), equations).unwrap()
    }

    /// x = 10⁻⁶·u, y = 10⁴·v with u, v of order one: the roots (10⁻⁶, 10⁴) and
    /// (−10⁻⁶, 10⁴) of `10¹² x² − 1 = 0`, `10⁻⁴ y − 1 + 10⁶ x … `.
    fn badly_scaled() -> System {
        let (x, y) = (Expr::variable("x"), Expr::variable("y"));
        System::new(
            ["x", "y"],
            Vec::<String>::new(),
            vec![
                c(1e12) * &x * &x - c(1.0),
                c(1e-8) * &y * &y + c(1e2) * &x * &y - c(1.0),
            ],
        )
        .unwrap()
    }

    #[test]
    fn scaling_balances_the_coefficients_and_maps_roots_exactly() {
        let system = badly_scaled();
        let scaling = Scaling::least_squares(&system).unwrap();
        assert!(scaling.worthwhile(), "{scaling:?}");
        assert!(scaling.rms_after < 2.0, "{scaling:?}");
        // x ≈ 2^{d_x} with d_x ≈ log₂ 10⁻⁶ ≈ −20.
        assert!((scaling.variables[0] + 20).abs() <= 1, "{scaling:?}");
        let scaled = scaling.apply(&system);
        // A root of the original, mapped to the scaled coordinates, is a root there.
        let x = 1e-6;
        // 10⁻⁸ y² + 10⁻⁴ y − 1 = 0 → the positive root.
        let y = (-1e-4 + (1e-8f64 + 4e-8).sqrt()) / 2e-8;
        let original = [C64::new(x, 0.0), C64::new(y, 0.0)];
        let residual = system.evaluate_naive(&original, &[]);
        assert!(residual.iter().all(|r| r.norm() < 1e-9), "{residual:?}");
        let inverse = scaling.scale(&original);
        let scaled_residual = scaled.evaluate_naive(&inverse, &[]);
        assert!(
            scaled_residual.iter().all(|r| r.norm() < 1e-9),
            "{scaled_residual:?}"
        );
        assert_eq!(scaling.unscale(&inverse), original.to_vec());
    }

    /// `10¹²(x² + y² − 2) = 0, 3x − y = 0`: equations of sizes 10¹² and 1, each balanced
    /// within.
    fn unbalanced() -> System {
        let (x, y) = (Expr::variable("x"), Expr::variable("y"));
        in_x_and_y(vec![
            c(1e12) * (&x * &x + &y * &y - c(2.0)),
            c(3.0) * &x - &y,
        ])
    }

    /// The automatic scaling and the degrees from an expansion the caller made once are
    /// those the system's own expansions give.
    #[test]
    fn one_expansion_gives_the_automatic_scaling_and_the_degrees() {
        for system in [badly_scaled(), unbalanced()] {
            let expansion = system.expand().unwrap();
            let automatic = Scaling::automatic(&system);
            assert!(automatic.is_some());
            assert_eq!(
                Scaling::automatic_of_expansion(&system, &expansion),
                automatic
            );
            assert_eq!(system.degrees_of_expansion(&expansion), system.degrees());
        }
    }

    #[test]
    fn a_well_scaled_system_is_left_alone() {
        let (x, y) = (Expr::variable("x"), Expr::variable("y"));
        let system = in_x_and_y(vec![&x * &x + &y * &y - c(2.0), c(3.0) * &x - &y + c(0.5)]);
        let scaling = Scaling::least_squares(&system).unwrap();
        assert!(!scaling.worthwhile(), "{scaling:?}");
    }

    /// Equations of sizes 10¹² and 1, each balanced within: only the equations are
    /// normalised (the roots keep their coordinates); a balanced system is not.
    #[test]
    fn unbalanced_equations_are_normalised_alone() {
        let system = unbalanced();
        let least_squares = Scaling::least_squares(&system).unwrap();
        assert!(!least_squares.worthwhile(), "{least_squares:?}");
        let scaling = Scaling::equations_only(&system).unwrap();
        assert!(scaling.unbalanced_equations(), "{scaling:?}");
        assert_eq!(scaling.variables, vec![0, 0]);
        // 10¹² ≈ 2^39.9 (the mean of log₂ 10¹² and log₂ 2·10¹²).
        assert_eq!(scaling.equations[0], -40, "{scaling:?}");
        let root = [
            C64::new(0.2f64.sqrt(), 0.0),
            C64::new(3.0 * 0.2f64.sqrt(), 0.0),
        ];
        let scaled = scaling.apply(&system).evaluate_naive(&root, &[]);
        assert!(scaled.iter().all(|r| r.norm() < 1e-12), "{scaled:?}");
        let (x, y) = (Expr::variable("x"), Expr::variable("y"));
        let balanced = in_x_and_y(vec![&x * &x + &y * &y - c(2.0), c(3.0) * &x - &y]);
        assert!(
            !Scaling::equations_only(&balanced)
                .unwrap()
                .unbalanced_equations()
        );
    }

    /// Exponents that would overflow a power of a scaled variable are refused: `x`
    /// of order 10⁻³⁰⁰ squared.
    #[test]
    fn an_unrepresentable_scaling_is_refused() {
        let text =
            "INPUT\nvariable_group x, y;\nfunction f, g;\nf = x^2 - 1e-300*y;\ng = y - 1;\nEND;\n";
        let system = crate::system::bertini::read(text).unwrap();
        assert_eq!(Scaling::least_squares(&system), None);
    }
}
