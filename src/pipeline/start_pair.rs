//! A start pair `(x₀, p₀)` with `F(x₀; p₀) = 0` for a parametric system, the seed of
//! the monodromy solver (ab-initio stage, docs/theory.md §8.1).
//!
//! The solution set `{(x, p) : F(x; p) = 0}` of a square parametric system is a variety
//! of dimension m (the number of parameters) in `C^{n+m}`. From a random complex point
//! we walk onto it with the minimum-norm Gauss–Newton step
//!
//! ```text
//!   (x, p) ← (x, p) − Jᴴ (J Jᴴ)⁻¹ F,     J = [∂F/∂x | ∂F/∂p]  (n × (n+m)),
//! ```
//!
//! which converges quadratically to a nearby point of the variety (the foot of an
//! approximately orthogonal projection), generically a smooth point with `∂F/∂x`
//! invertible. For our Lagrange systems F is linear in the configuration parameters,
//! so this succeeds from almost every random start; a few damped retries with fresh
//! random points cover the rest.

use crate::C64;
use crate::random::{self, SeededRng};
use crate::system::Evaluator;
use nalgebra::{DMatrix, DVector};

/// Why no start pair was found.
#[derive(Debug, thiserror::Error)]
pub enum StartPairError {
    /// Gauss–Newton did not reach the variety from any of the random starts.
    #[error(
        "no start pair found after {attempts} random starts (best residual {best_residual:.3e})"
    )]
    NotFound {
        /// Random starts tried.
        attempts: usize,
        /// Smallest residual reached.
        best_residual: f64,
    },
    /// The system is not square.
    #[error(
        "the system has {equations} equations in {variables} unknowns; a square system is required"
    )]
    NotSquare {
        /// Number of equations.
        equations: usize,
        /// Number of unknowns.
        variables: usize,
    },
}

/// A point on the solution variety with a nonsingular `∂F/∂x`.
#[derive(Clone, Debug)]
pub struct StartPair {
    /// Solution `x₀`.
    pub x: Vec<C64>,
    /// Parameters `p₀`.
    pub p: Vec<C64>,
    /// `‖F(x₀; p₀)‖_∞`.
    pub residual: f64,
}

/// Finds a start pair by minimum-norm Gauss–Newton from random complex points
/// (seeded). Accepts a point when `‖F‖_∞ < 1e-13 · (1 + ‖(x,p)‖_∞)` and the smallest
/// pivot of `∂F/∂x` is not negligible.
pub fn find_start_pair<E: Evaluator + ?Sized>(
    system: &E,
    seed: u64,
) -> Result<StartPair, StartPairError> {
    let n = system.num_variables();
    let m = system.num_parameters();
    if system.num_equations() != n {
        return Err(StartPairError::NotSquare {
            equations: system.num_equations(),
            variables: n,
        });
    }
    let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
    let mut f = vec![C64::new(0.0, 0.0); n];
    let mut jx = vec![C64::new(0.0, 0.0); n * n];
    let mut jp = vec![C64::new(0.0, 0.0); n * m];
    let mut best_residual = f64::INFINITY;
    const ATTEMPTS: usize = 50;
    for attempt in 0..ATTEMPTS {
        let mut rng: SeededRng = random::stream(seed, attempt as u64);
        let mut x: Vec<C64> = (0..n).map(|_| random::complex_normal(&mut rng)).collect();
        let mut p: Vec<C64> = (0..m).map(|_| random::complex_normal(&mut rng)).collect();
        for _iteration in 0..60 {
            system.evaluate_with_jacobian(&x, &p, &mut work, &mut f, &mut jx);
            system.evaluate_parameter_jacobian(&x, &p, &mut work, &mut jp);
            let residual = f.iter().map(|v| v.norm()).fold(0.0, f64::max);
            let scale = 1.0
                + x.iter()
                    .chain(p.iter())
                    .map(|v| v.norm())
                    .fold(0.0, f64::max);
            if !residual.is_finite() {
                break;
            }
            best_residual = best_residual.min(residual);
            if residual < 1e-13 * scale {
                if jacobian_is_regular(&jx, n) {
                    return Ok(StartPair { x, p, residual });
                }
                break;
            }
            let jacobian = DMatrix::from_fn(n, n + m, |i, j| {
                if j < n {
                    jx[i * n + j]
                } else {
                    jp[i * m + (j - n)]
                }
            });
            let gram = &jacobian * jacobian.adjoint();
            let Some(y) = gram.lu().solve(&DVector::from_column_slice(&f)) else {
                break;
            };
            let step = jacobian.adjoint() * y;
            for (i, xi) in x.iter_mut().enumerate() {
                *xi -= step[i];
            }
            for (j, pj) in p.iter_mut().enumerate() {
                *pj -= step[n + j];
            }
        }
    }
    Err(StartPairError::NotFound {
        attempts: ATTEMPTS,
        best_residual,
    })
}

/// `∂F/∂x` is regular when its smallest singular value is not negligible relative to
/// the largest (relative threshold 1e-10).
fn jacobian_is_regular(jx: &[C64], n: usize) -> bool {
    let matrix = DMatrix::from_row_slice(n, n, jx);
    let singular = matrix.singular_values();
    let max = singular.max();
    let min = singular.min();
    max > 0.0 && min > 1e-10 * max
}
