//! Options shared by the optimiser tests.

use singdist::optimize::GeneticOptions;

/// The default genetic-algorithm options with a small population and few generations.
pub fn small_genetic_options(population: usize, generations: usize, seed: u64) -> GeneticOptions {
    GeneticOptions {
        population,
        generations,
        seed,
        ..GeneticOptions::default()
    }
}
