//! The random-coefficient system `Q_i(x) = Σ_{a ∈ A_i} c_{ia} x^a` on given supports,
//! evaluated through the compiled term family it shares with the cell homotopies.
//!
//! For coefficients `c_{ia}` drawn from a continuous distribution, `Q` has exactly
//! `MV(A_1, …, A_n)` isolated roots in `(C*)^n`, all nonsingular (Bernstein, "The
//! number of roots of a system of equations", 1975; Huber and Sturmfels, "A polyhedral
//! method for solving sparse polynomial systems", Math. Comp. 1995); with the origin in
//! every support, none has a zero coordinate and they are all the roots in `C^n` (Li
//! and Wang, "The BKK root count in C^n", Math. Comp. 1996). `Q` is the start system
//! of the straight-line homotopy `(1 − t)γQ + tF` to the target (a coefficient-
//! parameter homotopy in the family of systems with supports in `A_i`, Morgan and
//! Sommese 1989, with the γ-trick).
//!
//! Evaluation: the term family `G(x; p) = Σ_t p_t x^{a_t}` (one parameter per term)
//! is compiled once, like every other system of the crate; `Q = G(·; c)` and each cell
//! homotopy is `G` at other coefficients, so all of them run on the compiled
//! straight-line program (with its double-double variants for ill-conditioned steps).
//! The tabulated term-by-term evaluation this replaced took 63 % of a `cpdm5` solve;
//! the compiled one cut the stage time 2.5–3×.

use super::supports::Supports;
use crate::C64;
use crate::system::expr::Expr;
use crate::system::{AtParameters, CompiledSystem, System};

/// The term layout of a system: how many unknowns, and which terms (in term order:
/// equations in order, points in support order) belong to each equation.
#[derive(Clone, Debug)]
pub struct Terms {
    n: usize,
    /// Terms of equation i: `equation_start[i]..equation_start[i + 1]`.
    equation_start: Vec<usize>,
}

impl Terms {
    /// The terms of `supports`.
    pub fn new(supports: &Supports) -> Self {
        let mut equation_start = vec![0];
        for points in supports.equations() {
            equation_start.push(equation_start.last().copied().unwrap_or(0) + points.len());
        }
        Terms {
            n: supports.num_variables(),
            equation_start,
        }
    }

    /// Number of unknowns.
    pub fn num_variables(&self) -> usize {
        self.n
    }

    /// Number of equations.
    pub fn num_equations(&self) -> usize {
        self.equation_start.len() - 1
    }

    /// Number of terms of all equations.
    pub fn num_terms(&self) -> usize {
        self.equation_start.last().copied().unwrap_or(0)
    }

    /// Term indices of equation i.
    pub fn equation(&self, i: usize) -> std::ops::Range<usize> {
        self.equation_start[i]..self.equation_start[i + 1]
    }
}

/// The term family `G_i(x; p) = Σ_{t ∈ terms of i} p_t x^{a_t}` of `supports`, one
/// parameter per term (in term order), compiled: `Q`, the cell homotopies and their
/// τ-derivatives are all evaluations of it (it is linear in `p`), on the compiled
/// straight-line program with its double-double variants.
fn term_family(supports: &Supports) -> CompiledSystem {
    let n = supports.num_variables();
    let variables: Vec<String> = (0..n).map(|j| format!("x{j}")).collect();
    let mut parameters = Vec::new();
    let mut equations = Vec::new();
    for points in supports.equations() {
        let mut terms = Vec::with_capacity(points.len());
        for a in points {
            let name = format!("c{}", parameters.len());
            let mut factors = vec![Expr::parameter(&name)];
            for (j, &e) in a.iter().enumerate() {
                if e > 0 {
                    factors.push(Expr::variable(&variables[j]).pow(e as u32));
                }
            }
            terms.push(Expr::balanced_product(factors));
            parameters.push(name);
        }
        equations.push(Expr::balanced_sum(terms));
    }
    let family = System::new(&variables, &parameters, equations)
        .expect("the term family declares every symbol it uses");
    // Its parameters only take values (coefficients, or their τ-derivatives).
    CompiledSystem::without_parameter_derivatives(&family)
}

/// `Q_i(x) = Σ_{a ∈ A_i} c_{ia} x^a` with complex normal coefficients.
#[derive(Clone, Debug)]
pub struct RandomCoefficientSystem {
    terms: Terms,
    coefficients: Vec<C64>,
    family: CompiledSystem,
}

impl RandomCoefficientSystem {
    /// The system on `supports` with coefficients complex normal from stream `stream`
    /// of `seed` ([`crate::random::stream`]), in term order.
    pub fn new(supports: &Supports, seed: u64, stream: u64) -> Self {
        let terms = Terms::new(supports);
        let mut rng = crate::random::stream(seed, stream);
        let coefficients = (0..terms.num_terms())
            .map(|_| crate::random::complex_normal(&mut rng))
            .collect();
        RandomCoefficientSystem {
            terms,
            coefficients,
            family: term_family(supports),
        }
    }

    /// The terms.
    pub fn terms(&self) -> &Terms {
        &self.terms
    }

    /// Coefficients in term order (equations in order, points in support order).
    pub fn coefficients(&self) -> &[C64] {
        &self.coefficients
    }

    /// The compiled term family `G(x; p) = Σ p_t x^{a_t}` (`Q = G(·; c)`).
    pub fn family(&self) -> &CompiledSystem {
        &self.family
    }

    /// `Q = G(·; c)`, the family at the coefficients, as a system.
    pub fn evaluator(&self) -> AtParameters<'_, CompiledSystem> {
        AtParameters::new(&self.family, &self.coefficients)
    }
}
