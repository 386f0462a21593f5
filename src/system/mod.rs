//! Polynomial systems `F(x; p)`: expressions in named variables and parameters,
//! exact symbolic differentiation, compilation to a straight-line program, and the
//! Bertini / PHCpack text formats.
//!
//! The numerical layers ([`crate::homotopy`]) see a system only through the
//! [`Evaluator`] trait: evaluation into caller-provided buffers with a caller-provided
//! scratch workspace, so the hot loop of the tracker allocates nothing and one
//! compiled system is shared by all threads (`Send + Sync`, workspaces per thread).
//!
//! Files, in the order the data flows:
//! - [`expr`]: [`Expr`], the expression DAG with operator overloading, the
//!   [`crate::algebra::Ring`] instance, exact differentiation and naive evaluation;
//! - [`builder`]: [`System`] (validation, Lagrange systems `∇Λ = 0`, degrees, Bézout
//!   number, reference evaluation);
//! - [`compile`]: [`CompiledSystem`], straight-line programs for F, ∂F/∂x, ∂F/∂p and
//!   (∂F/∂p)·dp, the [`Evaluator`] used by the homotopy engine;
//! - [`sparse`]: expansion into monomials (exact degrees, PHCpack export);
//! - [`scaling`]: equation and variable scaling by powers of two (least squares on
//!   the coefficients' logarithms) for badly scaled systems;
//! - [`parse`], [`bertini`], [`phc`]: the text formats.
//!
//! ```
//! use singdist::C64;
//! use singdist::system::{Evaluator, Expr, System};
//!
//! let (x, y, p) = (Expr::variable("x"), Expr::variable("y"), Expr::parameter("p"));
//! let system = System::new(["x", "y"], ["p"], vec![&x * &x + &y * &y - &p, &x - &y]).unwrap();
//! let compiled = system.compile();
//! let mut work = compiled.new_workspace();
//! let (mut f, mut jac) = ([C64::new(0.0, 0.0); 2], [C64::new(0.0, 0.0); 4]);
//! let point = [C64::new(1.0, 0.0), C64::new(2.0, 0.0)];
//! compiled.evaluate_with_jacobian(&point, &[C64::new(5.0, 0.0)], &mut work, &mut f, &mut jac);
//! assert_eq!(f[0], C64::new(0.0, 0.0));
//! assert_eq!(jac[1], C64::new(4.0, 0.0)); // ∂f₀/∂y = 2y
//! ```

use crate::C64;

/// `Add`, `Sub` and `Neg` of a complex type `$complex { re, im }` over a real type with
/// `Add`, `Sub` and `Neg`, part by part: `(a + ib) ± (c + id) = (a ± c) + i(b ± d)` and
/// `−(a + ib) = −a − ib` (the rounding is the real type's, one operation per part).
/// Shared by [`double_double::ComplexDd`] and [`interval::ComplexInterval`].
macro_rules! complex_add_sub_neg {
    // With `scale_by_real_part`: also `z · Re(w) = Re(z)Re(w) + i Im(z)Re(w)`, the
    // real type's product per part (double-double values and midpoint–radius boxes).
    ($complex:ident, scale_by_real_part) => {
        complex_add_sub_neg!($complex);

        impl $complex {
            /// `self · Re(other)`: each part times the real part of `other`.
            #[inline(always)]
            pub fn scale_by_real_part(self, other: Self) -> Self {
                $complex {
                    re: self.re * other.re,
                    im: self.im * other.re,
                }
            }
        }
    };
    ($complex:ident) => {
        impl std::ops::Add for $complex {
            type Output = Self;
            #[inline(always)]
            fn add(self, other: Self) -> Self {
                $complex {
                    re: self.re + other.re,
                    im: self.im + other.im,
                }
            }
        }

        impl std::ops::Sub for $complex {
            type Output = Self;
            #[inline(always)]
            fn sub(self, other: Self) -> Self {
                $complex {
                    re: self.re - other.re,
                    im: self.im - other.im,
                }
            }
        }

        impl std::ops::Neg for $complex {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                $complex {
                    re: -self.re,
                    im: -self.im,
                }
            }
        }
    };
}

pub mod bertini;
pub mod builder;
pub mod compile;
pub mod double_double;
pub mod expr;
pub mod interval;
pub mod interval_dd;
pub mod parametric;
pub mod parse;
pub mod phc;
pub mod scaling;
pub mod sparse;

pub use builder::{System, SystemError};
pub use compile::CompiledSystem;
pub use expr::Expr;
pub use parametric::ParametricSystem;
pub use parse::{ParseError, ParseErrorKind};
pub use sparse::SparsePolynomial;

/// A compiled parametric polynomial system `F: C^n × C^m → C^k`.
///
/// Buffer conventions (checked by implementations with `debug_assert!` only; sizes are
/// validated once, where a system is built):
/// - `x.len() == num_variables()`, `p.len() == num_parameters()`,
/// - `work.len() >= workspace_len()`,
/// - `f.len() == num_equations()`,
/// - Jacobians are row-major: entry `(i, j)` of `∂F/∂x` is `jac[i * num_variables() + j]`,
///   and of `∂F/∂p` is `jac_p[i * num_parameters() + j]`.
pub trait Evaluator: Send + Sync {
    /// Number of unknowns n.
    fn num_variables(&self) -> usize;
    /// Number of equations k; the default is n (a square system).
    fn num_equations(&self) -> usize {
        self.num_variables()
    }
    /// Number of parameters m; the default is 0 (a plain system).
    fn num_parameters(&self) -> usize {
        0
    }
    /// Length of the scratch buffer the evaluation calls need.
    fn workspace_len(&self) -> usize;
    /// The unknown whose zero means "at infinity" of an affine system this one is a
    /// chart of ([`System::with_homogenizing_variable`]); `None` by default.
    fn homogenizing_variable(&self) -> Option<usize> {
        None
    }

    /// `f ← F(x; p)`.
    fn evaluate(&self, x: &[C64], p: &[C64], work: &mut [C64], f: &mut [C64]);
    /// `f ← F(x; p)` evaluated in double-double arithmetic and rounded (see
    /// [`double_double`]): the residual for Newton steps at ill-conditioned points.
    /// The default evaluates in double precision.
    fn evaluate_extended(&self, x: &[C64], p: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.evaluate(x, p, work, f);
    }

    /// `f ← F(x; p)` and `jac ← ∂F/∂x (x; p)`.
    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        p: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    );

    /// [`Evaluator::evaluate_with_jacobian`] in double-double arithmetic: `f` and
    /// `jac` rounded, `jac_low` the Jacobian's trailing parts (`∂F/∂x = jac + jac_low`
    /// to about 32 digits), for velocities at ill-conditioned points where a Jacobian
    /// rounded to double would cost κ·ε of relative accuracy. The default evaluates in
    /// double precision (`jac_low = 0`).
    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        p: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
        jac_low: &mut [C64],
    ) {
        self.evaluate_with_jacobian(x, p, work, f, jac);
        jac_low.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
    }

    /// [`Evaluator::evaluate_parameter_derivative`] in double-double arithmetic,
    /// rounded. The default evaluates in double precision.
    fn evaluate_parameter_derivative_extended(
        &self,
        x: &[C64],
        p: &[C64],
        dp: &[C64],
        work: &mut [C64],
        out: &mut [C64],
    ) {
        self.evaluate_parameter_derivative(x, p, dp, work, out);
    }

    /// `out ← (∂F/∂p)(x; p) · dp`, the derivative of F along the parameter direction
    /// `dp` (what a parameter homotopy `p(t) = p₀ + t (p₁ − p₀)` needs as `∂H/∂t`).
    fn evaluate_parameter_derivative(
        &self,
        x: &[C64],
        p: &[C64],
        dp: &[C64],
        work: &mut [C64],
        out: &mut [C64],
    );

    /// `jac_p ← ∂F/∂p (x; p)` (row-major, k × m). The default builds it column by
    /// column from [`Evaluator::evaluate_parameter_derivative`] along the unit
    /// directions (allocating two vectors); [`CompiledSystem`] has a tape for it.
    fn evaluate_parameter_jacobian(
        &self,
        x: &[C64],
        p: &[C64],
        work: &mut [C64],
        jac_p: &mut [C64],
    ) {
        let (k, m) = (self.num_equations(), self.num_parameters());
        let mut direction = vec![C64::new(0.0, 0.0); m];
        let mut column = vec![C64::new(0.0, 0.0); k];
        for j in 0..m {
            direction[j] = C64::new(1.0, 0.0);
            self.evaluate_parameter_derivative(x, p, &direction, work, &mut column);
            direction[j] = C64::new(0.0, 0.0);
            for (i, value) in column.iter().enumerate() {
                jac_p[i * m + j] = *value;
            }
        }
    }
}

/// A system without parameters `G: Cⁿ → Cᵏ` (start systems, a homotopy's target
/// `H(·, 1)`, the polyhedral random-coefficient system), written without the parameter
/// arguments of [`Evaluator`]. Every `PlainSystem` is an [`Evaluator`] with no
/// parameters: `∂G/∂p · dp` is zero and `∂G/∂p` is empty.
pub trait PlainSystem: Send + Sync {
    /// Number of unknowns n.
    fn num_variables(&self) -> usize;
    /// Number of equations k; the default is n (a square system).
    fn num_equations(&self) -> usize {
        self.num_variables()
    }
    /// Length of the scratch buffer the evaluation calls need.
    fn workspace_len(&self) -> usize;
    /// `f ← G(x)`.
    fn evaluate(&self, x: &[C64], work: &mut [C64], f: &mut [C64]);
    /// `f ← G(x)` in double-double arithmetic where supported
    /// ([`Evaluator::evaluate_extended`]). The default evaluates in double precision.
    fn evaluate_extended(&self, x: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.evaluate(x, work, f);
    }
    /// `f ← G(x)` and `jac ← ∂G/∂x (x)`.
    fn evaluate_with_jacobian(&self, x: &[C64], work: &mut [C64], f: &mut [C64], jac: &mut [C64]);
    /// `f ← G(x)`, `jac + jac_low ← ∂G/∂x (x)` in double-double arithmetic where
    /// supported ([`Evaluator::evaluate_with_jacobian_extended`]). The default evaluates
    /// in double precision (`jac_low = 0`).
    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
        jac_low: &mut [C64],
    ) {
        self.evaluate_with_jacobian(x, work, f, jac);
        jac_low.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
    }
}

impl<S: PlainSystem + ?Sized> Evaluator for S {
    fn num_variables(&self) -> usize {
        PlainSystem::num_variables(self)
    }
    fn num_equations(&self) -> usize {
        PlainSystem::num_equations(self)
    }
    fn workspace_len(&self) -> usize {
        PlainSystem::workspace_len(self)
    }
    fn evaluate(&self, x: &[C64], _: &[C64], work: &mut [C64], f: &mut [C64]) {
        PlainSystem::evaluate(self, x, work, f);
    }
    fn evaluate_extended(&self, x: &[C64], _: &[C64], work: &mut [C64], f: &mut [C64]) {
        PlainSystem::evaluate_extended(self, x, work, f);
    }
    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        _: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    ) {
        PlainSystem::evaluate_with_jacobian(self, x, work, f, jac);
    }
    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        _: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
        jac_low: &mut [C64],
    ) {
        PlainSystem::evaluate_with_jacobian_extended(self, x, work, f, jac, jac_low);
    }
    fn evaluate_parameter_derivative(
        &self,
        _: &[C64],
        _: &[C64],
        _: &[C64],
        _: &mut [C64],
        out: &mut [C64],
    ) {
        out.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
    }
}

/// `F(·; p)`: a parametric system at fixed parameters `p`, as a system without
/// parameters (the polyhedral random-coefficient system is its term family at the
/// random coefficients).
pub struct AtParameters<'a, F: Evaluator + ?Sized> {
    system: &'a F,
    parameters: &'a [C64],
}

impl<'a, F: Evaluator + ?Sized> AtParameters<'a, F> {
    /// `system` at `parameters` (of length `system.num_parameters()`).
    pub fn new(system: &'a F, parameters: &'a [C64]) -> Self {
        assert_eq!(parameters.len(), system.num_parameters());
        AtParameters { system, parameters }
    }
}

impl<F: Evaluator + ?Sized> PlainSystem for AtParameters<'_, F> {
    fn num_variables(&self) -> usize {
        self.system.num_variables()
    }
    fn num_equations(&self) -> usize {
        self.system.num_equations()
    }
    fn workspace_len(&self) -> usize {
        self.system.workspace_len()
    }
    fn evaluate(&self, x: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.system.evaluate(x, self.parameters, work, f);
    }
    fn evaluate_extended(&self, x: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.system.evaluate_extended(x, self.parameters, work, f);
    }
    fn evaluate_with_jacobian(&self, x: &[C64], work: &mut [C64], f: &mut [C64], jac: &mut [C64]) {
        self.system
            .evaluate_with_jacobian(x, self.parameters, work, f, jac);
    }
    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
        jac_low: &mut [C64],
    ) {
        self.system
            .evaluate_with_jacobian_extended(x, self.parameters, work, f, jac, jac_low);
    }
}
