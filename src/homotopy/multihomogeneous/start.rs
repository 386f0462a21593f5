//! The linear-product start system of an m-homogeneous structure.
//!
//! For a partition `Z_1, …, Z_m` of the unknowns and degrees `d_ij` (equation i in
//! group j), `G_i(x) = Π_j Π_{l < d_ij} L_ijl(x_{Z_j})` with random affine linear
//! forms `L_ijl(y) = a_ijl · y + b_ijl` in the unknowns of group j, each coefficient
//! vector `(a_ijl, b_ijl)` complex normal scaled to unit length, so that `|G_i|` grows
//! like `‖(x, 1)‖^{deg G_i}` as the total-degree start system does (unscaled factors
//! make `G` dominate `F` until t is close to 1, where the endgame then meets the
//! homotopy's branch points). A solution makes
//! one factor of every equation vanish; choosing factor `(j_i, l_i)` for equation i,
//! the system splits into one linear system per group j made of the `k_j` equations
//! with `j_i = j`, so the admissible choices are exactly those giving each group as
//! many equations as it has unknowns, and for generic coefficients each gives one
//! nonsingular solution: `G` has exactly the m-homogeneous Bézout number of them, all
//! distinct. The straight-line homotopy `(1 − t)γG + tF` with this `G` reaches every
//! isolated solution of `F` (Morgan & Sommese, "A homotopy for solving general
//! polynomial systems that respects m-homogeneous structures", 1987; Wampler, "An
//! efficient start system for multi-homogeneous polynomial continuation", 1994).
//!
//! Solution `index` is decoded from the Bézout table ([`BezoutTable::decode`]), so
//! any subset of paths is generated independently and the result does not depend on
//! the thread count.

use super::bezout::{BezoutError, BezoutTable, VariablePartition};
use crate::C64;
use crate::homotopy::linalg::LuWorkspace;
use crate::system::PlainSystem;

/// Largest Bézout table a start system builds (states `Π (k_j + 1)`).
const MAX_TABLE_STATES: usize = 1 << 24;

/// One linear factor: its group and the offset of its `k_j + 1` coefficients
/// (`a` for the group's unknowns in group order, then `b`).
#[derive(Clone, Copy, Debug)]
struct Factor {
    group: usize,
    offset: usize,
}

/// `G_i(x) = Π_j Π_{l < d_ij} (a_ijl · x_{Z_j} + b_ijl)`.
#[derive(Clone, Debug)]
pub struct MultiHomogeneousStartSystem {
    partition: VariablePartition,
    degrees: Vec<u32>,
    table: BezoutTable,
    factors: Vec<Factor>,
    /// Factors of equation i: `factors[equation_start[i]..equation_start[i + 1]]`,
    /// ordered by group, then l.
    equation_start: Vec<usize>,
    coefficients: Vec<C64>,
    max_factors: usize,
}

impl MultiHomogeneousStartSystem {
    /// The start system of `partition` with degree matrix `degrees` (row-major,
    /// equations × groups), coefficients complex normal from stream 1 of `seed`
    /// ([`crate::random::stream`]), each factor's normalised to unit length.
    pub fn new(
        partition: VariablePartition,
        degrees: Vec<u32>,
        seed: u64,
    ) -> Result<Self, BezoutError> {
        let sizes = partition.sizes();
        let table = BezoutTable::new(&degrees, &sizes, MAX_TABLE_STATES)?;
        let n = partition.num_variables();
        let m = partition.num_groups();
        let mut rng = crate::random::stream(seed, 1);
        let mut factors = Vec::new();
        let mut equation_start = vec![0];
        let mut coefficients = Vec::new();
        let mut max_factors = 0;
        for i in 0..n {
            for j in 0..m {
                for _ in 0..degrees[i * m + j] {
                    factors.push(Factor {
                        group: j,
                        offset: coefficients.len(),
                    });
                    let first = coefficients.len();
                    for _ in 0..=sizes[j] {
                        coefficients.push(crate::random::complex_normal(&mut rng));
                    }
                    let norm = coefficients[first..]
                        .iter()
                        .map(|c| c.norm_sqr())
                        .sum::<f64>()
                        .sqrt();
                    coefficients[first..].iter_mut().for_each(|c| *c /= norm);
                }
            }
            max_factors = max_factors.max(factors.len() - equation_start[i]);
            equation_start.push(factors.len());
        }
        Ok(MultiHomogeneousStartSystem {
            partition,
            degrees,
            table,
            factors,
            equation_start,
            coefficients,
            max_factors,
        })
    }

    /// The partition.
    pub fn partition(&self) -> &VariablePartition {
        &self.partition
    }

    /// The degree matrix `d_ij` (row-major, equations × groups).
    pub fn degrees(&self) -> &[u32] {
        &self.degrees
    }

    /// Number of start solutions: the m-homogeneous Bézout number.
    pub fn path_count(&self) -> u128 {
        self.table.bezout_number()
    }

    fn factor_value(&self, factor: Factor, x: &[C64]) -> C64 {
        let group = &self.partition.groups()[factor.group];
        let c = &self.coefficients[factor.offset..factor.offset + group.len() + 1];
        group
            .iter()
            .zip(c)
            .fold(c[group.len()], |acc, (&v, &a)| acc + a * x[v])
    }

    /// Writes start solution number `index` into `x`; returns `false` (and writes NaN)
    /// when `index` is out of range or a linear system is singular, which for random
    /// coefficients has probability zero.
    pub fn start_solution(&self, index: u128, x: &mut [C64]) -> bool {
        let n = self.partition.num_variables();
        let mut choice = vec![(0usize, 0u32); n];
        let solved = self.table.decode(index, &mut choice) && self.solve_choice(&choice, x);
        if !solved {
            x.iter_mut().for_each(|v| *v = C64::new(f64::NAN, f64::NAN));
        }
        solved
    }

    /// Solves, group by group, the linear systems of the chosen vanishing factors.
    fn solve_choice(&self, choice: &[(usize, u32)], x: &mut [C64]) -> bool {
        let m = self.partition.num_groups();
        for (j, group) in self.partition.groups().iter().enumerate() {
            let k = group.len();
            let mut matrix = Vec::with_capacity(k * k);
            let mut rhs = Vec::with_capacity(k);
            for (i, &(g, l)) in choice.iter().enumerate() {
                if g != j {
                    continue;
                }
                let before: u32 = self.degrees[i * m..i * m + j].iter().sum();
                let factor = self.factors[self.equation_start[i] + (before + l) as usize];
                let c = &self.coefficients[factor.offset..factor.offset + k + 1];
                matrix.extend_from_slice(&c[..k]);
                rhs.push(-c[k]);
            }
            if rhs.len() != k {
                return false;
            }
            let mut lu = LuWorkspace::new(k);
            if !lu.factor(&matrix) {
                return false;
            }
            lu.solve_in_place(&mut rhs);
            for (&v, value) in group.iter().zip(rhs) {
                x[v] = value;
            }
        }
        true
    }
}

impl PlainSystem for MultiHomogeneousStartSystem {
    fn num_variables(&self) -> usize {
        self.partition.num_variables()
    }
    /// Factor values and their prefix products.
    fn workspace_len(&self) -> usize {
        2 * self.max_factors + 1
    }

    fn evaluate(&self, x: &[C64], _work: &mut [C64], f: &mut [C64]) {
        for (i, fi) in f.iter_mut().enumerate() {
            let range = self.equation_start[i]..self.equation_start[i + 1];
            *fi = self.factors[range]
                .iter()
                .fold(C64::new(1.0, 0.0), |acc, &factor| {
                    acc * self.factor_value(factor, x)
                });
        }
    }

    /// Row i of the Jacobian is `Σ_f (Π_{g ≠ f} L_g) ∇L_f`, with the products of the
    /// other factors from prefix and suffix products (no division, so exact at the
    /// start solutions where a factor vanishes).
    fn evaluate_with_jacobian(&self, x: &[C64], work: &mut [C64], f: &mut [C64], jac: &mut [C64]) {
        let n = self.partition.num_variables();
        jac.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        let (values, prefix) = work.split_at_mut(self.max_factors);
        for i in 0..n {
            let factors = &self.factors[self.equation_start[i]..self.equation_start[i + 1]];
            prefix[0] = C64::new(1.0, 0.0);
            for (q, &factor) in factors.iter().enumerate() {
                values[q] = self.factor_value(factor, x);
                prefix[q + 1] = prefix[q] * values[q];
            }
            f[i] = prefix[factors.len()];
            let row = &mut jac[i * n..(i + 1) * n];
            let mut suffix = C64::new(1.0, 0.0);
            for (q, &factor) in factors.iter().enumerate().rev() {
                let scale = prefix[q] * suffix;
                let group = &self.partition.groups()[factor.group];
                let c = &self.coefficients[factor.offset..factor.offset + group.len()];
                for (&v, &a) in group.iter().zip(c) {
                    row[v] += scale * a;
                }
                suffix *= values[q];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn start_system() -> MultiHomogeneousStartSystem {
        // Unknowns (x0, x2 | x1 | x3), four equations.
        let partition = VariablePartition::from_labels(&[0, 1, 0, 2]);
        let degrees = vec![2, 1, 0, 1, 1, 1, 0, 2, 1, 1, 0, 1];
        MultiHomogeneousStartSystem::new(partition, degrees, 42).unwrap()
    }

    #[test]
    fn start_solutions_solve_g_are_nonsingular_and_distinct() {
        let g = start_system();
        let count = g.path_count();
        let expected =
            super::super::bezout::multihomogeneous_bezout_number(g.degrees(), &[2, 1, 1]);
        assert_eq!(Some(count), expected);
        assert!(count > 4, "{count}");
        let n = 4;
        let mut work = vec![C64::new(0.0, 0.0); g.workspace_len()];
        let mut f = vec![C64::new(0.0, 0.0); n];
        let mut jac = vec![C64::new(0.0, 0.0); n * n];
        let mut solutions: Vec<Vec<C64>> = Vec::new();
        for index in 0..count {
            let mut x = vec![C64::new(0.0, 0.0); n];
            assert!(g.start_solution(index, &mut x));
            g.evaluate_with_jacobian(&x, &mut work, &mut f, &mut jac);
            let scale = 1.0 + x.iter().map(|v| v.norm()).fold(0.0, f64::max);
            assert!(f.iter().all(|v| v.norm() < 1e-10 * scale.powi(3)), "{f:?}");
            let mut lu = LuWorkspace::new(n);
            assert!(lu.factor(&jac));
            assert!(lu.condition_estimate() < 1e8);
            for s in &solutions {
                let distance = s
                    .iter()
                    .zip(&x)
                    .map(|(a, b)| (a - b).norm())
                    .fold(0.0, f64::max);
                assert!(distance > 1e-6, "solutions {index} repeats");
            }
            solutions.push(x);
        }
        let mut x = vec![C64::new(0.0, 0.0); n];
        assert!(!g.start_solution(count, &mut x));
        assert!(x[0].re.is_nan());
    }

    #[test]
    fn jacobian_matches_finite_differences_and_evaluate() {
        let g = start_system();
        let n = 4;
        let mut rng = crate::random::seeded(5);
        let x: Vec<C64> = (0..n)
            .map(|_| crate::random::complex_normal(&mut rng))
            .collect();
        let mut work = vec![C64::new(0.0, 0.0); g.workspace_len()];
        let mut f = vec![C64::new(0.0, 0.0); n];
        let mut f_plain = vec![C64::new(0.0, 0.0); n];
        let mut jac = vec![C64::new(0.0, 0.0); n * n];
        g.evaluate_with_jacobian(&x, &mut work, &mut f, &mut jac);
        g.evaluate(&x, &mut work, &mut f_plain);
        for (a, b) in f.iter().zip(&f_plain) {
            assert!((a - b).norm() < 1e-12 * (1.0 + a.norm()));
        }
        let h = 1e-6;
        for k in 0..n {
            let mut xp = x.clone();
            let mut xm = x.clone();
            xp[k] += h;
            xm[k] -= h;
            let mut fp = vec![C64::new(0.0, 0.0); n];
            let mut fm = vec![C64::new(0.0, 0.0); n];
            g.evaluate(&xp, &mut work, &mut fp);
            g.evaluate(&xm, &mut work, &mut fm);
            for i in 0..n {
                let numeric = (fp[i] - fm[i]) / (2.0 * h);
                let exact = jac[i * n + k];
                assert!(
                    (numeric - exact).norm() < 1e-6 * (1.0 + exact.norm()),
                    "({i}, {k})"
                );
            }
        }
    }

    #[test]
    fn coefficients_follow_the_seed() {
        let partition = VariablePartition::from_labels(&[0, 1]);
        let a = MultiHomogeneousStartSystem::new(partition.clone(), vec![1, 1, 1, 1], 1).unwrap();
        let b = MultiHomogeneousStartSystem::new(partition.clone(), vec![1, 1, 1, 1], 1).unwrap();
        let c = MultiHomogeneousStartSystem::new(partition, vec![1, 1, 1, 1], 2).unwrap();
        assert_eq!(a.coefficients, b.coefficients);
        assert_ne!(a.coefficients, c.coefficients);
    }
}
