//! The random-coefficient system `Q_i(x) = Σ_{a ∈ A_i} c_{ia} x^a` on given supports,
//! and the sparse term evaluation it shares with the cell homotopies.
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
//! Evaluation: the powers `x_j^k` up to the largest exponent of `x_j` are tabulated
//! once per call; each term is a product over its nonzero exponents, and its gradient
//! comes from prefix and suffix products of the same factors (no division, so zero
//! coordinates are fine). Everything lives in the caller's workspace.

use super::supports::Supports;
use crate::C64;
use crate::homotopy::start::no_parameter_derivatives;
use crate::system::Evaluator;

/// Flattened sparse terms of a system.
#[derive(Clone, Debug)]
pub struct Terms {
    n: usize,
    /// Terms of equation i: `equation_start[i]..equation_start[i + 1]`.
    equation_start: Vec<usize>,
    /// Factors of term t: `factors[term_start[t]..term_start[t + 1]]`.
    term_start: Vec<usize>,
    /// `(unknown, exponent)` with exponent ≥ 1.
    factors: Vec<(usize, usize)>,
    /// Largest exponent of each unknown.
    max_exponent: Vec<usize>,
    /// Longest factor list.
    max_factors: usize,
}

impl Terms {
    /// The terms of `supports`, equations in order, points in support order.
    pub fn new(supports: &Supports) -> Self {
        let n = supports.num_variables();
        let mut equation_start = vec![0];
        let mut term_start = vec![0];
        let mut factors = Vec::new();
        let mut max_exponent = vec![0usize; n];
        let mut max_factors = 0;
        for points in supports.equations() {
            for a in points {
                let before = factors.len();
                for (j, &e) in a.iter().enumerate() {
                    if e > 0 {
                        factors.push((j, e as usize));
                        max_exponent[j] = max_exponent[j].max(e as usize);
                    }
                }
                max_factors = max_factors.max(factors.len() - before);
                term_start.push(factors.len());
            }
            equation_start.push(term_start.len() - 1);
        }
        Terms {
            n,
            equation_start,
            term_start,
            factors,
            max_exponent,
            max_factors,
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
        self.term_start.len() - 1
    }

    /// The terms of equation i.
    pub fn equation(&self, i: usize) -> std::ops::Range<usize> {
        self.equation_start[i]..self.equation_start[i + 1]
    }

    fn stride(&self) -> usize {
        self.max_exponent.iter().copied().max().unwrap_or(0) + 1
    }

    /// Scratch entries of [`Terms::tabulate`] and [`Terms::gradient`].
    pub fn workspace_len(&self) -> usize {
        self.n * self.stride() + 2 * (self.max_factors + 1)
    }

    /// Tabulates `x_j^k` at the head of `work`; returns (table, rest of the scratch).
    pub fn tabulate<'w>(&self, x: &[C64], work: &'w mut [C64]) -> (&'w [C64], &'w mut [C64]) {
        let stride = self.stride();
        let (table, rest) = work.split_at_mut(self.n * stride);
        for (j, &xj) in x.iter().enumerate() {
            let row = &mut table[j * stride..j * stride + self.max_exponent[j] + 1];
            row[0] = C64::new(1.0, 0.0);
            for k in 1..row.len() {
                row[k] = row[k - 1] * xj;
            }
        }
        (table, rest)
    }

    /// `x^a` of term t from the power table.
    pub fn value(&self, t: usize, table: &[C64]) -> C64 {
        let stride = self.stride();
        self.factors[self.term_start[t]..self.term_start[t + 1]]
            .iter()
            .fold(C64::new(1.0, 0.0), |p, &(j, e)| p * table[j * stride + e])
    }

    /// `x^a` of term t, and `scale · ∂(x^a)/∂x_j` added to `row[j]` for its unknowns.
    pub fn value_and_gradient(
        &self,
        t: usize,
        table: &[C64],
        scratch: &mut [C64],
        scale: C64,
        row: &mut [C64],
    ) -> C64 {
        let stride = self.stride();
        let factors = &self.factors[self.term_start[t]..self.term_start[t + 1]];
        let k = factors.len();
        let (prefix, rest) = scratch.split_at_mut(self.max_factors + 1);
        let suffix = &mut rest[..self.max_factors + 1];
        prefix[0] = C64::new(1.0, 0.0);
        for (m, &(j, e)) in factors.iter().enumerate() {
            prefix[m + 1] = prefix[m] * table[j * stride + e];
        }
        suffix[k] = C64::new(1.0, 0.0);
        for (m, &(j, e)) in factors.iter().enumerate().rev() {
            suffix[m] = suffix[m + 1] * table[j * stride + e];
        }
        for (m, &(j, e)) in factors.iter().enumerate() {
            let derivative = table[j * stride + e - 1] * e as f64;
            row[j] += scale * derivative * prefix[m] * suffix[m + 1];
        }
        prefix[k]
    }
}

/// `Q_i(x) = Σ_{a ∈ A_i} c_{ia} x^a` with complex normal coefficients.
#[derive(Clone, Debug)]
pub struct RandomCoefficientSystem {
    terms: Terms,
    coefficients: Vec<C64>,
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
}

impl Evaluator for RandomCoefficientSystem {
    fn num_variables(&self) -> usize {
        self.terms.num_variables()
    }
    fn num_equations(&self) -> usize {
        self.terms.num_equations()
    }
    fn num_parameters(&self) -> usize {
        0
    }
    fn workspace_len(&self) -> usize {
        self.terms.workspace_len()
    }

    fn evaluate(&self, x: &[C64], _p: &[C64], work: &mut [C64], f: &mut [C64]) {
        let (table, _) = self.terms.tabulate(x, work);
        for (i, fi) in f.iter_mut().enumerate() {
            *fi = self
                .terms
                .equation(i)
                .map(|t| self.coefficients[t] * self.terms.value(t, table))
                .sum();
        }
    }

    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        _p: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    ) {
        let n = self.terms.num_variables();
        let (table, scratch) = self.terms.tabulate(x, work);
        jac.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        for (i, fi) in f.iter_mut().enumerate() {
            let row = &mut jac[i * n..(i + 1) * n];
            let mut sum = C64::new(0.0, 0.0);
            for t in self.terms.equation(i) {
                let c = self.coefficients[t];
                sum += c * self.terms.value_and_gradient(t, table, scratch, c, row);
            }
            *fi = sum;
        }
    }

    no_parameter_derivatives!();
}
