//! Choosing the variable partition: the one of smallest m-homogeneous Bézout number.
//!
//! For few unknowns every set partition is tried (restricted-growth strings,
//! Bell(n) partitions). Beyond, a deterministic steepest-descent local search runs
//! from the one-group and the all-singletons partitions; a move takes one unknown into
//! another group or a new group, or merges two groups, and the best strictly
//! improving move is taken until none improves or the evaluation budget is spent.
//! The budget counts evaluations, not seconds, so the choice depends only on the
//! system. (The idea of searching groupings for the least Bézout number is Wampler's,
//! "An efficient start system for multi-homogeneous polynomial continuation", 1994;
//! the search here is a plain local search.)

use super::bezout::{BezoutTable, MonomialSupports, VariablePartition};

/// Limits of [`best_partition`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PartitionSearchOptions {
    /// Every partition is tried for at most this many unknowns.
    pub exhaustive_up_to: usize,
    /// Largest number of partitions evaluated by the local search.
    pub max_evaluations: usize,
    /// Partitions whose Bézout table has more states are skipped.
    pub max_states: usize,
}

impl Default for PartitionSearchOptions {
    fn default() -> Self {
        PartitionSearchOptions {
            exhaustive_up_to: 8,
            max_evaluations: 20_000,
            max_states: 1 << 18,
        }
    }
}

/// How the partition was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SearchMethod {
    /// Every partition was evaluated.
    Exhaustive,
    /// Local search (not necessarily the optimum).
    LocalSearch,
}

/// Result of [`best_partition`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PartitionChoice {
    /// The partition of smallest Bézout number found (the one-group partition on ties
    /// with it; otherwise the first found).
    pub partition: VariablePartition,
    /// Its m-homogeneous Bézout number.
    pub bezout_number: u128,
    /// The total-degree Bézout number (one group), `None` on overflow.
    pub total_degree: Option<u128>,
    /// Partitions evaluated.
    pub evaluations: usize,
    /// How the search ran.
    pub method: SearchMethod,
}

struct Scorer<'a> {
    supports: &'a MonomialSupports,
    options: PartitionSearchOptions,
    evaluations: usize,
}

impl Scorer<'_> {
    fn bezout(&mut self, partition: &VariablePartition) -> Option<u128> {
        self.evaluations += 1;
        if partition.table_states() > self.options.max_states {
            return None;
        }
        let degrees = self.supports.degrees(partition);
        BezoutTable::new(&degrees, &partition.sizes(), self.options.max_states)
            .ok()
            .map(|t| t.bezout_number())
    }
}

/// The partition of smallest m-homogeneous Bézout number that the search finds for a
/// square system's supports; `None` when the system is not square or has no unknowns.
pub fn best_partition(
    supports: &MonomialSupports,
    options: &PartitionSearchOptions,
) -> Option<PartitionChoice> {
    let n = supports.num_variables();
    if n == 0 || supports.num_equations() != n {
        return None;
    }
    let mut evaluator = Scorer {
        supports,
        options: *options,
        evaluations: 0,
    };
    let single = VariablePartition::single_group(n);
    let total_degree = evaluator.bezout(&single);
    let mut best: Option<(VariablePartition, u128)> = total_degree.map(|b| (single.clone(), b));
    let mut consider = |p: VariablePartition, b: Option<u128>| {
        if let Some(b) = b
            && best.as_ref().is_none_or(|(_, current)| b < *current)
        {
            best = Some((p, b));
        }
    };
    let method = if n <= options.exhaustive_up_to {
        let mut labels = vec![0usize; n];
        // Restricted-growth strings: labels[0] = 0, labels[v] ≤ 1 + max(labels[..v]).
        loop {
            let p = VariablePartition::from_labels(&labels);
            if p.num_groups() > 1 {
                let b = evaluator.bezout(&p);
                consider(p, b);
            }
            if !next_restricted_growth(&mut labels) {
                break;
            }
        }
        SearchMethod::Exhaustive
    } else {
        for start in [single.clone(), VariablePartition::singletons(n)] {
            let b = evaluator.bezout(&start);
            let (p, b) = local_search(&mut evaluator, start, b);
            consider(p, b);
        }
        SearchMethod::LocalSearch
    };
    let (partition, bezout_number) = best?;
    Some(PartitionChoice {
        partition,
        bezout_number,
        total_degree,
        evaluations: evaluator.evaluations,
        method,
    })
}

/// Next restricted-growth string in lexicographic order; `false` after the last.
fn next_restricted_growth(labels: &mut [usize]) -> bool {
    for v in (1..labels.len()).rev() {
        let max_before = labels[..v].iter().copied().max().unwrap_or(0);
        if labels[v] <= max_before {
            labels[v] += 1;
            labels[v + 1..].iter_mut().for_each(|l| *l = 0);
            return true;
        }
    }
    false
}

/// Steepest descent from `start` (Bézout number `value`, `None` if not computable).
fn local_search(
    evaluator: &mut Scorer<'_>,
    start: VariablePartition,
    value: Option<u128>,
) -> (VariablePartition, Option<u128>) {
    let mut current = start;
    let mut current_value = value;
    loop {
        let mut best_move: Option<(VariablePartition, u128)> = None;
        for candidate in neighbours(&current) {
            if evaluator.evaluations >= evaluator.options.max_evaluations {
                break;
            }
            if let Some(b) = evaluator.bezout(&candidate) {
                let improves = current_value.is_none_or(|c| b < c)
                    && best_move.as_ref().is_none_or(|(_, m)| b < *m);
                if improves {
                    best_move = Some((candidate, b));
                }
            }
        }
        match best_move {
            Some((p, b)) => {
                current = p;
                current_value = Some(b);
            }
            None => return (current, current_value),
        }
    }
}

/// Partitions one move away: an unknown into another or a new group, or two groups
/// merged.
fn neighbours(partition: &VariablePartition) -> Vec<VariablePartition> {
    let labels = partition.group_of();
    let m = partition.num_groups();
    let mut out = Vec::new();
    for v in 0..labels.len() {
        for target in 0..=m {
            if target == labels[v] || (target == m && partition.groups()[labels[v]].len() == 1) {
                continue;
            }
            let mut moved = labels.to_vec();
            moved[v] = target;
            out.push(VariablePartition::from_labels(&moved));
        }
    }
    for a in 0..m {
        for b in a + 1..m {
            let merged: Vec<usize> = labels.iter().map(|&g| if g == b { a } else { g }).collect();
            out.push(VariablePartition::from_labels(&merged));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(A − λI)v = 0, c·v = 1` (dense A) in unknowns `v_1..v_n, λ`.
    fn eigenvalue_supports(n: usize) -> MonomialSupports {
        let unit = |j: usize| {
            let mut e = vec![0u32; n + 1];
            e[j] = 1;
            e
        };
        let mut equations: Vec<Vec<Vec<u32>>> = (0..n)
            .map(|i| {
                let mut terms: Vec<Vec<u32>> = (0..n).map(unit).collect();
                let mut e = unit(i);
                e[n] = 1;
                terms.push(e);
                terms
            })
            .collect();
        let mut normalisation: Vec<Vec<u32>> = (0..n).map(unit).collect();
        normalisation.push(vec![0; n + 1]);
        equations.push(normalisation);
        MonomialSupports::new(n + 1, equations)
    }

    #[test]
    fn exhaustive_and_local_search_find_the_eigenvalue_grouping() {
        for n in [3usize, 6, 11] {
            let choice =
                best_partition(&eigenvalue_supports(n), &PartitionSearchOptions::default())
                    .unwrap();
            assert_eq!(choice.bezout_number, n as u128, "n = {n}");
            assert_eq!(choice.total_degree, Some(1 << n));
            let mut groups = vec![(0..n).collect::<Vec<_>>(), vec![n]];
            groups.sort();
            assert_eq!(choice.partition.groups(), groups.as_slice());
            let expected = if n < 8 {
                SearchMethod::Exhaustive
            } else {
                SearchMethod::LocalSearch
            };
            assert_eq!(choice.method, expected);
        }
    }

    #[test]
    fn dense_system_keeps_one_group_and_exhaustive_count_is_bell() {
        // x² + y² + z², xyz, x + y + z + 1: no grouping beats 2·3·1 = 6.
        let supports = MonomialSupports::new(
            3,
            vec![
                vec![vec![2, 0, 0], vec![0, 2, 0], vec![0, 0, 2]],
                vec![vec![1, 1, 1]],
                vec![vec![1, 0, 0], vec![0, 1, 0], vec![0, 0, 1], vec![0, 0, 0]],
            ],
        );
        let choice = best_partition(&supports, &PartitionSearchOptions::default()).unwrap();
        assert_eq!(choice.partition, VariablePartition::single_group(3));
        assert_eq!(choice.bezout_number, 6);
        // Bell(3) = 5 partitions, the one-group one evaluated first.
        assert_eq!(choice.evaluations, 5);
        let mut labels = vec![0usize; 5];
        let mut count = 1;
        while next_restricted_growth(&mut labels) {
            count += 1;
        }
        assert_eq!(count, 52);
    }
}
