//! Newton's method on a square system `F(x; p) = 0` at fixed parameters, the
//! implementation behind endpoint refinement ([`super::refine::newton_refine`]). (The
//! polishing before a Krawczyk test, [`crate::certify::krawczyk`], takes double-
//! precision steps of its own: the certified box is as wide as the enclosure of the
//! residual in any case.)
//!
//! Each iteration solves `J(x) Δ = F(x)` by LU with partial pivoting and sets
//! `x ← x − Δ`. The residual `F(x)` is evaluated in double-double arithmetic
//! ([`Evaluator::evaluate_extended`]), so the attainable accuracy is `κ·ε·‖x‖`, set by
//! the linear solve, not by the rounding error of `F` (the mixed-precision iterative
//! refinement of Wilkinson, "Rounding Errors in Algebraic Processes", 1963; see also
//! Higham, "Accuracy and Stability of Numerical Algorithms", 2002, §12.1). The
//! iteration stops when the relative correction `‖Δ‖∞/(1 + ‖x‖∞)` is below the
//! tolerance (converged), when the Jacobian is singular or a value is not finite, when
//! (optionally) a correction more than doubles after the second iteration (Newton is
//! not converging), or after the iteration budget.

use super::linalg::LuWorkspace;
use crate::C64;
use crate::system::Evaluator;

/// Stopping rule of [`newton`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    /// Converged once a correction is at most this, relative to `1 + ‖x‖∞`.
    pub tolerance: f64,
    /// Newton iterations at most.
    pub max_iterations: usize,
    /// Stop (without applying it) at a correction more than twice the previous one,
    /// from the third iteration on.
    pub stop_when_growing: bool,
}

/// Why [`newton`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NewtonStop {
    /// A correction fell below the tolerance (it was applied).
    Converged,
    /// The Jacobian at the current iterate is singular to working precision.
    Singular,
    /// The residual or the correction is not finite.
    NonFinite,
    /// A correction more than doubled ([`NewtonOptions::stop_when_growing`]).
    Growing,
    /// The iteration budget ran out.
    MaxIterations,
}

/// What [`newton`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOutcome {
    /// Why it stopped.
    pub stop: NewtonStop,
    /// Corrections applied.
    pub iterations: usize,
    /// The last applied correction, relative to `1 + ‖x‖∞` before it (∞ if none).
    pub last_correction: f64,
}

impl NewtonOutcome {
    /// A correction fell below the tolerance.
    pub fn converged(&self) -> bool {
        self.stop == NewtonStop::Converged
    }
}

/// Caller-owned buffers of [`newton`]: the evaluation workspace, `F`, the row-major
/// Jacobian and its LU factorisation. After a run the LU holds the factorisation of
/// the Jacobian at the iterate before the last applied correction.
pub struct NewtonBuffers<'a> {
    /// The system's evaluation workspace.
    pub work: &'a mut [C64],
    /// Residual (then correction), one entry per equation.
    pub f: &'a mut [C64],
    /// Jacobian, equations × unknowns.
    pub jac: &'a mut [C64],
    /// LU workspace of the Jacobian.
    pub lu: &'a mut LuWorkspace,
}

/// `‖x‖∞ = max |x_i|` (from the squared moduli: no square root per coordinate).
pub(crate) fn max_norm(x: &[C64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.norm_sqr())).sqrt()
}

/// Newton's method on `F(·; parameters) = 0` from `point`, in place (module
/// documentation).
pub fn newton<F: Evaluator + ?Sized>(
    system: &F,
    point: &mut [C64],
    parameters: &[C64],
    options: &NewtonOptions,
    buffers: NewtonBuffers<'_>,
) -> NewtonOutcome {
    let NewtonBuffers { work, f, jac, lu } = buffers;
    let mut outcome = NewtonOutcome {
        stop: NewtonStop::MaxIterations,
        iterations: 0,
        last_correction: f64::INFINITY,
    };
    let mut previous = f64::INFINITY;
    for iteration in 0..options.max_iterations {
        system.evaluate_with_jacobian(point, parameters, work, f, jac);
        system.evaluate_extended(point, parameters, work, f);
        if !lu.factor(jac) {
            outcome.stop = NewtonStop::Singular;
            break;
        }
        if f.iter().any(|v| !v.re.is_finite() || !v.im.is_finite()) {
            outcome.stop = NewtonStop::NonFinite;
            break;
        }
        lu.solve_in_place(f);
        let scale = 1.0 + max_norm(point);
        let correction = max_norm(f) / scale;
        if !correction.is_finite() {
            outcome.stop = NewtonStop::NonFinite;
            break;
        }
        if options.stop_when_growing && correction > 2.0 * previous && iteration > 1 {
            outcome.stop = NewtonStop::Growing;
            break;
        }
        for (xi, di) in point.iter_mut().zip(f.iter()) {
            *xi -= di;
        }
        outcome.iterations = iteration + 1;
        outcome.last_correction = correction;
        if correction <= options.tolerance {
            outcome.stop = NewtonStop::Converged;
            break;
        }
        previous = correction;
    }
    outcome
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::system::{CompiledSystem, Expr, System};

    /// `x² − p = 0`, one unknown and one parameter.
    fn square_root() -> CompiledSystem {
        let x = Expr::variable("x");
        let p = Expr::parameter("p");
        System::new(["x"], ["p"], vec![x.clone() * x - p])
            .unwrap()
            .compile()
    }

    fn run(point: &mut [C64], p: f64, options: &NewtonOptions) -> NewtonOutcome {
        let system = square_root();
        let zero = C64::new(0.0, 0.0);
        let mut work = vec![zero; system.workspace_len()];
        let (mut f, mut jac) = (vec![zero; 1], vec![zero; 1]);
        let mut lu = LuWorkspace::new(1);
        let buffers = NewtonBuffers {
            work: &mut work,
            f: &mut f,
            jac: &mut jac,
            lu: &mut lu,
        };
        newton(&system, point, &[C64::new(p, 0.0)], options, buffers)
    }

    const OPTIONS: NewtonOptions = NewtonOptions {
        tolerance: 1e-14,
        max_iterations: 20,
        stop_when_growing: true,
    };

    #[test]
    fn converges_quadratically_to_the_root() {
        let mut x = [C64::new(1.5, 0.0)];
        let outcome = run(&mut x, 2.0, &OPTIONS);
        assert_eq!(outcome.stop, NewtonStop::Converged);
        assert!(outcome.converged());
        assert!((x[0] - 2.0f64.sqrt()).norm() < 1e-15, "{x:?}");
        // From 1.5 the errors are 9·10⁻², 2.5·10⁻³, 2·10⁻⁶, 1.5·10⁻¹², then rounding.
        assert!((4..=6).contains(&outcome.iterations), "{outcome:?}");
    }

    #[test]
    fn a_singular_jacobian_stops_before_any_update() {
        let mut x = [C64::new(0.0, 0.0)];
        let outcome = run(&mut x, 2.0, &OPTIONS);
        assert_eq!(outcome.stop, NewtonStop::Singular);
        assert_eq!(outcome.iterations, 0);
        assert_eq!(x[0], C64::new(0.0, 0.0));
    }

    #[test]
    fn the_budget_bounds_the_iterations() {
        let mut x = [C64::new(100.0, 0.0)];
        let options = NewtonOptions {
            max_iterations: 2,
            ..OPTIONS
        };
        let outcome = run(&mut x, 2.0, &options);
        assert_eq!(outcome.stop, NewtonStop::MaxIterations);
        assert_eq!(outcome.iterations, 2);
        // Far from the roots each update about halves x: 100 → 50.01 → 25.02.
        assert!((x[0].re - 25.02).abs() < 0.01, "{x:?}");
    }

    /// At a real start for a negative parameter (roots ±i√2) real Newton iterates
    /// never converge; their corrections jump around chaotically, and the growth
    /// test stops them, while without it the budget does.
    #[test]
    fn growing_corrections_stop_the_iteration_only_when_asked() {
        let mut x = [C64::new(0.3, 0.0)];
        let outcome = run(&mut x, -2.0, &OPTIONS);
        assert_eq!(outcome.stop, NewtonStop::Growing, "{outcome:?}");
        let mut y = [C64::new(0.3, 0.0)];
        let options = NewtonOptions {
            stop_when_growing: false,
            ..OPTIONS
        };
        let outcome = run(&mut y, -2.0, &options);
        assert_eq!(outcome.stop, NewtonStop::MaxIterations, "{outcome:?}");
        assert_eq!(outcome.iterations, 20);
    }
}
