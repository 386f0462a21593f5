//! Supports of a polynomial system and their random integer liftings.
//!
//! The support `A_i ⊂ Z^n` of equation i is the set of exponent vectors of its terms;
//! Bernstein's theorem bounds the isolated roots in the torus `(C*)^n` by the mixed
//! volume `MV(A_1, …, A_n)`, with equality for generic coefficients. Adding the origin
//! to every support that lacks it gives a bound for the isolated roots in all of
//! `C^n`, roots with zero coordinates included (Li and Wang, "The BKK root count in
//! C^n", Math. Comp. 1996): [`Supports::with_origin`]. A lifting `ω_i: A_i → Z` of
//! random integers induces a regular fine mixed subdivision of `A_1 + … + A_n` whose
//! mixed cells give the polyhedral homotopy (Huber and Sturmfels, "A polyhedral method
//! for solving sparse polynomial systems", Math. Comp. 1995).

use crate::system::System;
use crate::system::sparse::{ExpansionError, SparsePolynomial};

/// Every support of `equations` sorted and without repeated points.
///
/// # Panics
/// If an exponent vector's length is not `num_variables` (a programming error).
pub(crate) fn sorted_distinct<T: Ord>(
    num_variables: usize,
    equations: Vec<Vec<Vec<T>>>,
) -> Vec<Vec<Vec<T>>> {
    equations
        .into_iter()
        .map(|mut points| {
            for p in &points {
                assert_eq!(p.len(), num_variables, "one exponent per unknown");
            }
            points.sort();
            points.dedup();
            points
        })
        .collect()
}

/// Per equation the exponent vectors of its terms (sorted, distinct).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Supports {
    num_variables: usize,
    equations: Vec<Vec<Vec<i64>>>,
}

impl Supports {
    /// Supports from exponent vectors (each of length `num_variables`); duplicates are
    /// removed and every support is sorted.
    ///
    /// # Panics
    /// If an exponent vector has the wrong length (a programming error).
    pub fn new(num_variables: usize, equations: Vec<Vec<Vec<i64>>>) -> Self {
        Supports {
            num_variables,
            equations: sorted_distinct(num_variables, equations),
        }
    }

    /// The supports of a system's equations in its unknowns, from their expansion
    /// ([`System::expand`]); terms differing only in parameters are one monomial.
    pub fn from_system(system: &System) -> Result<Self, ExpansionError> {
        Ok(Self::from_expansion(
            system.variables().len(),
            &system.expand()?,
        ))
    }

    /// The supports in the first `n` symbols (the unknowns) of a system's expansion
    /// ([`System::expand`]), as [`Supports::from_system`].
    pub fn from_expansion(n: usize, expansion: &[SparsePolynomial]) -> Self {
        let equations = expansion
            .iter()
            .map(|p| {
                p.terms
                    .iter()
                    .filter(|(_, c)| c.norm() > 0.0)
                    .map(|(m, _)| m[..n].iter().map(|&e| e as i64).collect())
                    .collect()
            })
            .collect();
        Self::new(n, equations)
    }

    /// The same supports with the origin added to each one lacking it (Li–Wang).
    pub fn with_origin(&self) -> Self {
        let origin = vec![0i64; self.num_variables];
        let equations = self
            .equations
            .iter()
            .map(|points| {
                let mut points = points.clone();
                points.push(origin.clone());
                points
            })
            .collect();
        Self::new(self.num_variables, equations)
    }

    /// Number of unknowns n.
    pub fn num_variables(&self) -> usize {
        self.num_variables
    }

    /// Number of supports.
    pub fn num_equations(&self) -> usize {
        self.equations.len()
    }

    /// Support of equation i.
    pub fn support(&self, i: usize) -> &[Vec<i64>] {
        &self.equations[i]
    }

    /// All supports.
    pub fn equations(&self) -> &[Vec<Vec<i64>>] {
        &self.equations
    }

    /// Total degree of each equation (largest coordinate sum of its support).
    pub fn total_degrees(&self) -> Vec<u32> {
        self.equations
            .iter()
            .map(|points| {
                points
                    .iter()
                    .map(|p| p.iter().sum::<i64>().max(0) as u32)
                    .max()
                    .unwrap_or(0)
            })
            .collect()
    }
}

/// Random lifting values `ω_i(a)` in `0..range`, one per point of every support, from
/// stream `stream` of `seed` ([`crate::random::stream`]).
pub fn random_lifting(supports: &Supports, seed: u64, stream: u64, range: u64) -> Vec<Vec<i64>> {
    use rand::Rng;
    let mut rng = crate::random::stream(seed, stream);
    supports
        .equations()
        .iter()
        .map(|points| {
            points
                .iter()
                .map(|_| (rng.next_u64() % range) as i64)
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn origin_is_added_once_and_lifting_is_deterministic() {
        let s = Supports::new(
            2,
            vec![vec![vec![1, 0], vec![0, 1]], vec![vec![0, 0], vec![1, 1]]],
        );
        let o = s.with_origin();
        assert_eq!(o.support(0).len(), 3);
        assert_eq!(o.support(1).len(), 2);
        assert_eq!(o.total_degrees(), vec![1, 2]);
        assert_eq!(
            random_lifting(&o, 3, 2, 1 << 10),
            random_lifting(&o, 3, 2, 1 << 10)
        );
    }
}
