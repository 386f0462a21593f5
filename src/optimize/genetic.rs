//! Real-coded genetic algorithm over a box (Farias Filho et al. (2021) §4, Ramana Babu et al. §V).
//!
//! One generation: the `elite` best individuals survive unchanged; every other slot gets a
//! child of two parents chosen by tournament (size `tournament`). With probability
//! `crossover` the child is a BLX-α blend (`x_j` uniform in `[m_j − α d_j, M_j + α d_j]`,
//! `m_j, M_j` the parents' smaller and larger gene, `d_j = M_j − m_j`), otherwise a copy of
//! the first parent; then each gene mutates with probability `mutation` by a Gaussian step of
//! standard deviation `mutation_scale · (hi_j − lo_j)`; finally the child is clamped into the box.
//!
//! Reproducibility: generation `g` draws only from `random::stream(seed, g)`, serially; the
//! objective is evaluated in parallel (rayon) into a vector in population order, so the
//! run does not depend on the number of threads.

use super::{OptimizeError, sanitize, validate_bounds};
use crate::random::{self, SeededRng};
use rayon::prelude::*;

/// Options of [`genetic_maximize`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GeneticOptions {
    /// Individuals per generation (≥ 2).
    pub population: usize,
    /// Number of generations after the initial one.
    pub generations: usize,
    /// Probability of crossover for each child, in [0, 1].
    pub crossover: f64,
    /// Probability of mutating each gene, in [0, 1].
    pub mutation: f64,
    /// Standard deviation of a mutation step as a fraction of the variable's range (> 0).
    pub mutation_scale: f64,
    /// BLX-α extension factor (≥ 0).
    pub blend_alpha: f64,
    /// Number of best individuals copied unchanged into the next generation (< population).
    pub elite: usize,
    /// Tournament size for parent selection (≥ 1).
    pub tournament: usize,
    /// Seed of every random draw.
    pub seed: u64,
    /// Individuals placed in the initial population before the random ones (clamped into the box).
    pub initial: Vec<Vec<f64>>,
}

impl Default for GeneticOptions {
    /// The setting of Ramana Babu et al. (population 60, 100 generations) with common GA
    /// rates.
    fn default() -> Self {
        Self {
            population: 60,
            generations: 100,
            crossover: 0.8,
            mutation: 0.1,
            mutation_scale: 0.1,
            blend_alpha: 0.5,
            elite: 2,
            tournament: 2,
            seed: 0,
            initial: Vec::new(),
        }
    }
}

impl GeneticOptions {
    fn validate(&self, dimension: usize) -> Result<(), OptimizeError> {
        let bad = |field: &'static str, reason: String| {
            Err(OptimizeError::InvalidOption { field, reason })
        };
        if !(2..=1_000_000).contains(&self.population) {
            return bad(
                "population",
                format!("{} not in 2..=1000000", self.population),
            );
        }
        if self.generations > 1_000_000 {
            return bad("generations", format!("{} > 1000000", self.generations));
        }
        if !(0.0..=1.0).contains(&self.crossover) {
            return bad("crossover", format!("{} not in [0, 1]", self.crossover));
        }
        if !(0.0..=1.0).contains(&self.mutation) {
            return bad("mutation", format!("{} not in [0, 1]", self.mutation));
        }
        if !(self.mutation_scale.is_finite() && self.mutation_scale > 0.0) {
            return bad(
                "mutation_scale",
                format!("{} must be finite and > 0", self.mutation_scale),
            );
        }
        if !(self.blend_alpha.is_finite() && self.blend_alpha >= 0.0) {
            return bad(
                "blend_alpha",
                format!("{} must be finite and >= 0", self.blend_alpha),
            );
        }
        if self.elite >= self.population {
            return bad(
                "elite",
                format!("{} >= population {}", self.elite, self.population),
            );
        }
        if self.tournament == 0 {
            return bad("tournament", "must be >= 1".into());
        }
        if self.initial.len() > self.population {
            return bad(
                "initial",
                format!(
                    "{} individuals > population {}",
                    self.initial.len(),
                    self.population
                ),
            );
        }
        for (k, individual) in self.initial.iter().enumerate() {
            if individual.len() != dimension || individual.iter().any(|v| !v.is_finite()) {
                return Err(OptimizeError::InvalidStart {
                    field: "initial",
                    reason: format!("individual {k} must have {dimension} finite values"),
                });
            }
        }
        Ok(())
    }
}

/// Result of [`genetic_maximize`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GaResult {
    /// Best individual ever evaluated.
    pub best: Vec<f64>,
    /// Objective at `best` (`−∞` if every evaluation was NaN or −∞).
    pub best_value: f64,
    /// Best value after each generation (entry 0: the initial population); non-decreasing.
    pub history: Vec<f64>,
    /// Number of objective evaluations.
    pub evaluations: usize,
}

/// Maximise `objective` over the box `bounds` with a seeded real-coded genetic algorithm
/// (see the module doc). Deterministic for a given `options.seed`.
pub fn genetic_maximize<F>(
    objective: F,
    bounds: &[(f64, f64)],
    options: &GeneticOptions,
) -> Result<GaResult, OptimizeError>
where
    F: Fn(&[f64]) -> f64 + Sync,
{
    validate_bounds(bounds)?;
    let n = bounds.len();
    options.validate(n)?;
    let size = options.population;

    // Flat storage: individual k occupies genes[k*n .. (k+1)*n].
    let mut genes = vec![0.0; size * n];
    let mut rng = random::stream(options.seed, 0);
    for (k, individual) in genes.chunks_exact_mut(n).enumerate() {
        if let Some(given) = options.initial.get(k) {
            individual.copy_from_slice(given);
            super::project_onto_box(individual, bounds);
        } else {
            for (gene, &(lo, hi)) in individual.iter_mut().zip(bounds) {
                *gene = random::uniform(&mut rng, lo, hi);
            }
        }
    }
    let mut fitness = vec![f64::NEG_INFINITY; size];
    evaluate(&objective, &genes, n, &mut fitness);
    let mut evaluations = size;

    let mut best_index = argmax(&fitness);
    let mut best = genes[best_index * n..(best_index + 1) * n].to_vec();
    let mut best_value = fitness[best_index];
    let mut history = Vec::with_capacity(options.generations + 1);
    history.push(best_value);

    let mut next = vec![0.0; size * n];
    let mut next_fitness = vec![f64::NEG_INFINITY; size];
    let mut order: Vec<usize> = (0..size).collect();
    for generation in 1..=options.generations {
        let mut rng = random::stream(options.seed, generation as u64);
        // Rank: best first, ties broken by index (stable sort) for determinism.
        order.sort_by(|&a, &b| fitness[b].total_cmp(&fitness[a]));
        for (slot, &source) in order.iter().take(options.elite).enumerate() {
            next[slot * n..(slot + 1) * n].copy_from_slice(&genes[source * n..(source + 1) * n]);
            next_fitness[slot] = fitness[source];
        }
        for slot in options.elite..size {
            let first = tournament(&mut rng, &fitness, options.tournament);
            let second = tournament(&mut rng, &fitness, options.tournament);
            let child = &mut next[slot * n..(slot + 1) * n];
            let do_cross = random::uniform(&mut rng, 0.0, 1.0) < options.crossover;
            for j in 0..n {
                let p = genes[first * n + j];
                let q = genes[second * n + j];
                let (lo, hi) = bounds[j];
                let mut value = if do_cross {
                    let (m, big) = if p <= q { (p, q) } else { (q, p) };
                    let d = big - m;
                    random::uniform(
                        &mut rng,
                        m - options.blend_alpha * d,
                        big + options.blend_alpha * d,
                    )
                } else {
                    p
                };
                if random::uniform(&mut rng, 0.0, 1.0) < options.mutation {
                    value += random::normal(&mut rng) * options.mutation_scale * (hi - lo);
                }
                child[j] = value.clamp(lo, hi);
            }
        }
        evaluate(
            &objective,
            &next[options.elite * n..],
            n,
            &mut next_fitness[options.elite..],
        );
        evaluations += size - options.elite;
        std::mem::swap(&mut genes, &mut next);
        std::mem::swap(&mut fitness, &mut next_fitness);

        best_index = argmax(&fitness);
        if fitness[best_index] > best_value {
            best_value = fitness[best_index];
            best.copy_from_slice(&genes[best_index * n..(best_index + 1) * n]);
        }
        history.push(best_value);
    }
    Ok(GaResult {
        best,
        best_value,
        history,
        evaluations,
    })
}

/// Evaluate every individual of a flat gene block in parallel into `out` (same order).
fn evaluate<F>(objective: &F, genes: &[f64], n: usize, out: &mut [f64])
where
    F: Fn(&[f64]) -> f64 + Sync,
{
    out.par_iter_mut()
        .zip(genes.par_chunks_exact(n))
        .for_each(|(value, individual)| *value = sanitize(objective(individual)));
}

/// Index of the largest value (first one on ties).
fn argmax(values: &[f64]) -> usize {
    let mut best = 0;
    for (k, &v) in values.iter().enumerate() {
        if v > values[best] {
            best = k;
        }
    }
    best
}

/// Tournament selection: the fittest of `size` uniformly drawn individuals.
fn tournament(rng: &mut SeededRng, fitness: &[f64], size: usize) -> usize {
    let len = fitness.len();
    let mut winner = draw_index(rng, len);
    for _ in 1..size {
        let challenger = draw_index(rng, len);
        if fitness[challenger] > fitness[winner] {
            winner = challenger;
        }
    }
    winner
}

/// Uniform index in `0..len` (`len ≥ 1`).
fn draw_index(rng: &mut SeededRng, len: usize) -> usize {
    ((random::uniform(rng, 0.0, len as f64)) as usize).min(len - 1)
}
