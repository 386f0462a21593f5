//! Seeded genetic algorithm and local constrained refinement: generic box-constrained
//! solvers (docs/theory.md §11.3, §11.5). The mechanism studies that use them (redundancy
//! resolution, design optimisation) live in the `analysis` layer above.
//!
//! Both optimisers *maximise* a real objective over a box `lo_j ≤ x_j ≤ hi_j`:
//!
//! * [`genetic`]: a real-coded genetic algorithm (tournament selection, blend crossover
//!   BLX-α, Gaussian mutation, elitism). Every random draw comes from a ChaCha8 stream
//!   derived from the seed and the generation number, and the objective is evaluated in
//!   parallel with results collected in population order, so a run repeats bit for bit
//!   whatever the thread count.
//! * [`local`]: a projected quasi-Newton (BFGS) ascent with central finite-difference
//!   gradients and box bounds, a compact SQP-like method for bound constraints (the
//!   quadratic model is maximised over the free variables, the step projected on the box).
//! * [`maximize`]: the hybrid of Farias Filho et al. (2021) §4: the GA's best individual seeds the local solver.
//!
//! Objective values that are NaN are treated as `−∞` (never selected, never accepted).

pub mod genetic;
pub mod local;

pub use genetic::{GaResult, GeneticOptions, genetic_maximize};
pub use local::{LocalOptions, LocalResult, local_maximize};

use thiserror::Error;

/// Errors of the optimisers: bad bounds or options, named by field.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum OptimizeError {
    /// The box has no dimension.
    #[error("bounds: at least one variable is required")]
    EmptyBounds,
    /// A bound is not finite or has `lo > hi`.
    #[error("bounds[{index}]: invalid interval [{lo}, {hi}] (finite, lo <= hi required)")]
    InvalidBound {
        /// Variable index.
        index: usize,
        /// Lower bound given.
        lo: f64,
        /// Upper bound given.
        hi: f64,
    },
    /// An option is out of its valid range.
    #[error("option `{field}`: {reason}")]
    InvalidOption {
        /// Name of the option field.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// A start point has the wrong dimension or is not finite.
    #[error("start point `{field}`: {reason}")]
    InvalidStart {
        /// Which start point.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
}

/// Check that `bounds` is a non-empty list of finite intervals with `lo ≤ hi`.
pub fn validate_bounds(bounds: &[(f64, f64)]) -> Result<(), OptimizeError> {
    if bounds.is_empty() {
        return Err(OptimizeError::EmptyBounds);
    }
    for (index, &(lo, hi)) in bounds.iter().enumerate() {
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(OptimizeError::InvalidBound { index, lo, hi });
        }
    }
    Ok(())
}

/// Clamp `x` into the box, componentwise.
pub fn project_onto_box(x: &mut [f64], bounds: &[(f64, f64)]) {
    for (value, &(lo, hi)) in x.iter_mut().zip(bounds) {
        *value = value.clamp(lo, hi);
    }
}

/// NaN objective values count as `−∞`.
pub(crate) fn sanitize(value: f64) -> f64 {
    if value.is_nan() {
        f64::NEG_INFINITY
    } else {
        value
    }
}

/// Result of the hybrid GA + local refinement.
#[derive(Debug, Clone, PartialEq)]
pub struct HybridResult {
    /// Best point found (after refinement).
    pub best: Vec<f64>,
    /// Objective at `best`.
    pub best_value: f64,
    /// The genetic stage alone.
    pub genetic: GaResult,
    /// The local stage, started from the GA's best.
    pub local: LocalResult,
}

/// The optimiser of Farias Filho et al. (2021), §4: a genetic algorithm whose best
/// individual starts a local constrained (projected quasi-Newton) refinement. The result
/// is never worse than the GA's best.
pub fn maximize<F>(
    objective: F,
    bounds: &[(f64, f64)],
    genetic_options: &GeneticOptions,
    local_options: &LocalOptions,
) -> Result<HybridResult, OptimizeError>
where
    F: Fn(&[f64]) -> f64 + Sync,
{
    let genetic = genetic_maximize(&objective, bounds, genetic_options)?;
    let local = local_maximize(&objective, bounds, &genetic.best, local_options)?;
    let (best, best_value) = if local.best_value >= genetic.best_value {
        (local.best.clone(), local.best_value)
    } else {
        (genetic.best.clone(), genetic.best_value)
    };
    Ok(HybridResult {
        best,
        best_value,
        genetic,
        local,
    })
}
