//! Variable partitions, multidegrees and the m-homogeneous Bézout number.
//!
//! For a partition of the n unknowns into groups `Z_1, …, Z_m` of sizes `k_j`
//! (Σ k_j = n) and `d_ij` the degree of equation i in the unknowns of group j, the
//! m-homogeneous Bézout number is the coefficient of `Π_j α_j^{k_j}` in
//! `Π_i (Σ_j d_ij α_j)`: the number of isolated solutions in
//! `P^{k_1} × … × P^{k_m}` of a generic system with these multidegrees, and an upper
//! bound of the isolated finite solutions of any system with them (Morgan & Sommese,
//! "A homotopy for solving general polynomial systems that respects m-homogeneous
//! structures", 1987). Equivalently it is the sum over the assignments σ of equations
//! to groups with `|σ⁻¹(j)| = k_j` of `Π_i d_{i σ(i)}`.
//!
//! [`BezoutTable`] computes it by dynamic programming over the equations (Wampler, "An
//! efficient start system for multi-homogeneous polynomial continuation", 1994): with
//! `N(r)` the weighted number of assignments of the last `|r|` equations in which
//! group j receives `r_j` of them,
//! `N(0) = 1`, `N(r) = Σ_{j: r_j > 0} d_{n−|r|, j} · N(r − e_j)`, and the Bézout number
//! is `N(k)`. States are indexed in mixed radix `(k_1 + 1, …, k_m + 1)`, so `r − e_j`
//! precedes `r` and one pass in index order fills the table in `O(m Π (k_j + 1))`
//! operations, exactly (overflow-checked `u128`). The same table decodes an index
//! `0 ≤ s < N(k)` into one assignment with one factor per equation, which is how the
//! start system's solutions are enumerated.

use crate::homotopy::polyhedral::supports::sorted_distinct;
use crate::system::System;
use crate::system::sparse::ExpansionError;

/// A partition of the unknowns `0..n` into non-empty groups, in canonical order (groups
/// ordered by their smallest unknown, unknowns ascending within a group).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct VariablePartition {
    group_of: Vec<usize>,
    groups: Vec<Vec<usize>>,
}

impl VariablePartition {
    /// The partition with `group_of[v]` the group label of unknown `v` (any labels;
    /// they are renumbered canonically).
    pub fn from_labels(group_of: &[usize]) -> Self {
        let mut relabel: Vec<(usize, usize)> = Vec::new();
        let mut canonical = Vec::with_capacity(group_of.len());
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for (v, &label) in group_of.iter().enumerate() {
            let g = match relabel.iter().find(|(l, _)| *l == label) {
                Some(&(_, g)) => g,
                None => {
                    relabel.push((label, groups.len()));
                    groups.push(Vec::new());
                    groups.len() - 1
                }
            };
            canonical.push(g);
            groups[g].push(v);
        }
        VariablePartition {
            group_of: canonical,
            groups,
        }
    }

    /// All n unknowns in one group (the 1-homogeneous, total-degree structure).
    pub fn single_group(n: usize) -> Self {
        Self::from_labels(&vec![0; n])
    }

    /// Every unknown in its own group.
    pub fn singletons(n: usize) -> Self {
        Self::from_labels(&(0..n).collect::<Vec<_>>())
    }

    /// Number of unknowns n.
    pub fn num_variables(&self) -> usize {
        self.group_of.len()
    }

    /// Number of groups m.
    pub fn num_groups(&self) -> usize {
        self.groups.len()
    }

    /// Group of each unknown.
    pub fn group_of(&self) -> &[usize] {
        &self.group_of
    }

    /// The unknowns of each group.
    pub fn groups(&self) -> &[Vec<usize>] {
        &self.groups
    }

    /// Group sizes `k_j`.
    pub fn sizes(&self) -> Vec<usize> {
        self.groups.iter().map(Vec::len).collect()
    }

    /// The groups written with the unknowns' names, `{x, y} {z}`.
    pub fn describe(&self, names: &[String]) -> String {
        let groups: Vec<String> = self
            .groups
            .iter()
            .map(|g| {
                let members: Vec<&str> = g.iter().map(|&v| names[v].as_str()).collect();
                format!("{{{}}}", members.join(", "))
            })
            .collect();
        groups.join(" ")
    }

    /// Number of states `Π (k_j + 1)` of the Bézout table (saturating).
    pub fn table_states(&self) -> usize {
        self.groups
            .iter()
            .fold(1usize, |acc, g| acc.saturating_mul(g.len() + 1))
    }
}

/// The monomial supports of a polynomial system in its unknowns: per equation the
/// exponent vectors of its terms (parameters are coefficients), without monomials
/// dominated exponent-wise by another one (they never decide a degree).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MonomialSupports {
    num_variables: usize,
    equations: Vec<Vec<Vec<u32>>>,
}

impl MonomialSupports {
    /// Supports from exponent vectors (each of length `num_variables`).
    ///
    /// # Panics
    /// If an exponent vector has the wrong length (a programming error).
    pub fn new(num_variables: usize, equations: Vec<Vec<Vec<u32>>>) -> Self {
        let equations = sorted_distinct(num_variables, equations)
            .into_iter()
            .map(|monomials| {
                let dominated =
                    |m: &Vec<u32>, by: &Vec<u32>| m != by && m.iter().zip(by).all(|(a, b)| a <= b);
                monomials
                    .iter()
                    .filter(|m| !monomials.iter().any(|other| dominated(m, other)))
                    .cloned()
                    .collect()
            })
            .collect();
        MonomialSupports {
            num_variables,
            equations,
        }
    }

    /// The supports of a system's equations, from their expansion
    /// ([`System::expand`]); fails when an equation is too large to expand.
    pub fn from_system(system: &System) -> Result<Self, ExpansionError> {
        let n = system.variables().len();
        let equations = system
            .expand()?
            .into_iter()
            .map(|p| p.terms.keys().map(|m| m[..n].to_vec()).collect())
            .collect();
        Ok(Self::new(n, equations))
    }

    /// Number of unknowns.
    pub fn num_variables(&self) -> usize {
        self.num_variables
    }

    /// Number of equations.
    pub fn num_equations(&self) -> usize {
        self.equations.len()
    }

    /// Total degree of each equation (0 for the zero polynomial).
    pub fn total_degrees(&self) -> Vec<u32> {
        self.equations
            .iter()
            .map(|ms| ms.iter().map(|m| m.iter().sum::<u32>()).max().unwrap_or(0))
            .collect()
    }

    /// The degree matrix `d_ij` (row-major, equations × groups) of a partition:
    /// `d_ij = max over the terms of equation i of their degree in group j`.
    pub fn degrees(&self, partition: &VariablePartition) -> Vec<u32> {
        let m = partition.num_groups();
        let group_of = partition.group_of();
        let mut degrees = vec![0u32; self.equations.len() * m];
        let mut sums = vec![0u32; m];
        for (row, monomials) in degrees.chunks_mut(m.max(1)).zip(&self.equations) {
            for monomial in monomials {
                sums.iter_mut().for_each(|s| *s = 0);
                for (v, &e) in monomial.iter().enumerate() {
                    sums[group_of[v]] += e;
                }
                for (d, &s) in row.iter_mut().zip(&sums) {
                    *d = (*d).max(s);
                }
            }
        }
        degrees
    }
}

/// Why a Bézout table could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BezoutError {
    /// A count exceeds `u128`.
    #[error("the multi-homogeneous Bézout number overflows 128 bits")]
    Overflow,
    /// The table would have more than the allowed number of states.
    #[error("the Bézout table needs {states} states, more than the limit {limit}")]
    TooManyStates {
        /// States `Π (k_j + 1)`.
        states: usize,
        /// The limit.
        limit: usize,
    },
    /// The degree matrix does not have one row per unknown and one column per group.
    #[error("the degree matrix has {found} entries, expected {expected}")]
    Shape {
        /// n · m.
        expected: usize,
        /// Given entries.
        found: usize,
    },
}

/// The table `N(r)` of the dynamic programme (module documentation) for one square
/// system's degree matrix and partition sizes.
#[derive(Clone, Debug)]
pub struct BezoutTable {
    sizes: Vec<usize>,
    strides: Vec<usize>,
    degrees: Vec<u32>,
    counts: Vec<u128>,
}

impl BezoutTable {
    /// Fills the table for the degree matrix `degrees` (row-major n × m, n = Σ sizes)
    /// and group sizes `sizes`, refusing more than `max_states` states.
    pub fn new(degrees: &[u32], sizes: &[usize], max_states: usize) -> Result<Self, BezoutError> {
        let m = sizes.len();
        let n: usize = sizes.iter().sum();
        if degrees.len() != n * m {
            return Err(BezoutError::Shape {
                expected: n * m,
                found: degrees.len(),
            });
        }
        let mut strides = Vec::with_capacity(m);
        let mut states = 1usize;
        for &k in sizes {
            strides.push(states);
            states = states.saturating_mul(k + 1);
        }
        if states > max_states {
            return Err(BezoutError::TooManyStates {
                states,
                limit: max_states,
            });
        }
        let mut counts = vec![0u128; states];
        counts[0] = 1;
        let mut r = vec![0usize; m];
        let mut assigned = 0usize;
        for index in 1..states {
            // Odometer step to the mixed-radix digits of `index`.
            for (j, digit) in r.iter_mut().enumerate() {
                if *digit < sizes[j] {
                    *digit += 1;
                    assigned += 1;
                    break;
                }
                assigned -= *digit;
                *digit = 0;
            }
            let equation = n - assigned;
            let row = &degrees[equation * m..(equation + 1) * m];
            let mut total = 0u128;
            for j in 0..m {
                if r[j] > 0 && row[j] > 0 {
                    let term = counts[index - strides[j]]
                        .checked_mul(row[j] as u128)
                        .ok_or(BezoutError::Overflow)?;
                    total = total.checked_add(term).ok_or(BezoutError::Overflow)?;
                }
            }
            counts[index] = total;
        }
        Ok(BezoutTable {
            sizes: sizes.to_vec(),
            strides,
            degrees: degrees.to_vec(),
            counts,
        })
    }

    /// The m-homogeneous Bézout number `N(k)`.
    pub fn bezout_number(&self) -> u128 {
        self.counts[self.counts.len() - 1]
    }

    /// Decodes `index < N(k)` into, per equation i, the group `j_i` whose factor
    /// vanishes and the factor `0 ≤ l_i < d_{i j_i}` (lexicographic order over
    /// equations, then groups, then factors). Returns `false` when `index` is out of
    /// range.
    pub fn decode(&self, index: u128, choice: &mut [(usize, u32)]) -> bool {
        let m = self.sizes.len();
        let n = choice.len();
        if index >= self.bezout_number() || n * m != self.degrees.len() {
            return false;
        }
        let mut rest = index;
        let mut state = self.counts.len() - 1;
        let mut remaining = self.sizes.clone();
        for (i, slot) in choice.iter_mut().enumerate() {
            let row = &self.degrees[i * m..(i + 1) * m];
            let mut found = false;
            for j in 0..m {
                if remaining[j] == 0 || row[j] == 0 {
                    continue;
                }
                let below = self.counts[state - self.strides[j]];
                let block = below * row[j] as u128;
                if rest < block {
                    *slot = (j, (rest / below) as u32);
                    rest %= below;
                    state -= self.strides[j];
                    remaining[j] -= 1;
                    found = true;
                    break;
                }
                rest -= block;
            }
            if !found {
                return false;
            }
        }
        true
    }
}

/// The m-homogeneous Bézout number of a degree matrix (row-major n × m) and group sizes
/// (`None` on overflow of `u128` or a table above 2²⁴ states).
pub fn multihomogeneous_bezout_number(degrees: &[u32], sizes: &[usize]) -> Option<u128> {
    BezoutTable::new(degrees, sizes, 1 << 24)
        .ok()
        .map(|t| t.bezout_number())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Σ over assignments σ with |σ⁻¹(j)| = k_j of Π d_{iσ(i)}, by brute force.
    fn brute_force(degrees: &[u32], sizes: &[usize]) -> u128 {
        let m = sizes.len();
        let n: usize = sizes.iter().sum();
        let mut total = 0u128;
        let mut sigma = vec![0usize; n];
        'all: loop {
            let mut used = vec![0usize; m];
            sigma.iter().for_each(|&j| used[j] += 1);
            if used == sizes {
                total += (0..n)
                    .map(|i| degrees[i * m + sigma[i]] as u128)
                    .product::<u128>();
            }
            for s in sigma.iter_mut() {
                *s += 1;
                if *s < m {
                    continue 'all;
                }
                *s = 0;
            }
            break;
        }
        total
    }

    /// `(A − λI)v = 0, c·v = 1` in unknowns `v_1..v_n, λ`.
    fn eigenvalue_supports(n: usize) -> MonomialSupports {
        let mut equations = Vec::new();
        for i in 0..n {
            let mut terms = Vec::new();
            for j in 0..n {
                let mut e = vec![0; n + 1];
                e[j] = 1;
                terms.push(e);
            }
            let mut e = vec![0; n + 1];
            e[i] = 1;
            e[n] = 1;
            terms.push(e);
            equations.push(terms);
        }
        let mut normalisation: Vec<Vec<u32>> = (0..n)
            .map(|j| {
                let mut e = vec![0; n + 1];
                e[j] = 1;
                e
            })
            .collect();
        normalisation.push(vec![0; n + 1]);
        equations.push(normalisation);
        MonomialSupports::new(n + 1, equations)
    }

    #[test]
    fn eigenvalue_problem_has_n_two_homogeneous_paths_against_two_to_the_n() {
        for n in [2usize, 3, 5, 8] {
            let supports = eigenvalue_supports(n);
            let mut labels = vec![0; n + 1];
            labels[n] = 1;
            let partition = VariablePartition::from_labels(&labels);
            let degrees = supports.degrees(&partition);
            let mut expected = [1u32, 1].repeat(n);
            expected.extend([1, 0]);
            assert_eq!(degrees, expected);
            assert_eq!(
                multihomogeneous_bezout_number(&degrees, &partition.sizes()),
                Some(n as u128)
            );
            let single = VariablePartition::single_group(n + 1);
            assert_eq!(
                multihomogeneous_bezout_number(&supports.degrees(&single), &single.sizes()),
                Some(1u128 << n)
            );
            assert_eq!(supports.total_degrees().iter().product::<u32>(), 1 << n);
        }
    }

    #[test]
    fn hand_computed_counts() {
        // Two bilinear equations in (x; y): coefficient of αβ in (α + β)² = 2.
        assert_eq!(
            multihomogeneous_bezout_number(&[1, 1, 1, 1], &[1, 1]),
            Some(2)
        );
        // (2α + β)(α + β)α = 2α³ + 3α²β + αβ²: coefficient of α²β is 3.
        assert_eq!(
            multihomogeneous_bezout_number(&[2, 1, 1, 1, 1, 0], &[2, 1]),
            Some(3)
        );
        // One group: the total degree 2·3·4.
        assert_eq!(multihomogeneous_bezout_number(&[2, 3, 4], &[3]), Some(24));
        // A group no equation involves: no solutions.
        assert_eq!(
            multihomogeneous_bezout_number(&[1, 0, 1, 0], &[1, 1]),
            Some(0)
        );
    }

    #[test]
    fn dynamic_programme_matches_brute_force_and_detects_overflow() {
        let mut rng = crate::random::seeded(11);
        for sizes in [vec![1usize, 2, 1], vec![3, 1], vec![2, 2, 1], vec![1; 5]] {
            let n: usize = sizes.iter().sum();
            let degrees: Vec<u32> = (0..n * sizes.len())
                .map(|_| crate::random::uniform(&mut rng, 0.0, 4.0) as u32)
                .collect();
            assert_eq!(
                multihomogeneous_bezout_number(&degrees, &sizes),
                Some(brute_force(&degrees, &sizes)),
                "{sizes:?} {degrees:?}"
            );
        }
        let huge = vec![u32::MAX; 8];
        assert_eq!(
            BezoutTable::new(&huge, &[8], 1 << 10).err(),
            Some(BezoutError::Overflow)
        );
        assert!(matches!(
            BezoutTable::new(&[1; 400], &[1; 20], 1 << 10),
            Err(BezoutError::TooManyStates { .. })
        ));
    }

    #[test]
    fn decoding_enumerates_every_admissible_choice_once() {
        let degrees = [2u32, 1, 1, 1, 3, 2, 1, 0];
        let sizes = [2usize, 2];
        let table = BezoutTable::new(&degrees, &sizes, 1 << 10).unwrap();
        let count = table.bezout_number();
        assert_eq!(count, brute_force(&degrees, &sizes));
        let mut seen = std::collections::HashSet::new();
        let mut choice = vec![(0usize, 0u32); 4];
        for index in 0..count {
            assert!(table.decode(index, &mut choice));
            let mut used = [0usize; 2];
            for (i, &(j, l)) in choice.iter().enumerate() {
                assert!(l < degrees[i * 2 + j]);
                used[j] += 1;
            }
            assert_eq!(used, sizes);
            assert!(seen.insert(choice.clone()));
        }
        assert!(!table.decode(count, &mut choice));
    }

    #[test]
    fn supports_drop_dominated_monomials_and_partitions_are_canonical() {
        let s = MonomialSupports::new(
            2,
            vec![vec![vec![1, 1], vec![1, 0], vec![0, 0], vec![0, 2]]],
        );
        assert_eq!(s.equations[0], vec![vec![0, 2], vec![1, 1]]);
        let p = VariablePartition::from_labels(&[7, 3, 7]);
        assert_eq!(p.group_of(), &[0, 1, 0]);
        assert_eq!(p.groups(), &[vec![0, 2], vec![1]]);
        assert_eq!(p.table_states(), 6);
        let names: Vec<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
        assert_eq!(p.describe(&names), "{a, c} {b}");
    }
}
