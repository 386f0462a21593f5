//! Actuation-scheme design optimisation of the 3-RRR (docs/theory.md §11.5; Ramana Babu et
//! al. §V.B): the seeded GA of [`crate::optimize`] maximises the GCI of
//! [`crate::index::actuation`] over the design vector `(a, b, c)` subject to `a + b + c ≤ λ`.
//! The objective is the grid mean ([`GciDomain::Grid`]) by default; see the module doc of
//! [`crate::index::actuation`] for why, and for the optima found on the example geometry.

use crate::index::actuation::{
    ActuationError, ExampleGeometry, GciDomain, GciOptions, GciResult, Scheme, WorkspaceGrid, gci,
};
use crate::mechanism::rrr::RrrDesign;
use crate::optimize::{GeneticOptions, OptimizeError, genetic_maximize};
use thiserror::Error;

/// Errors of the design optimisation: the actuation analysis (fields named as there) or the
/// genetic algorithm's options.
#[derive(Debug, Error)]
pub enum DesignError {
    /// Invalid problem, design, grid or GCI options.
    #[error(transparent)]
    Actuation(#[from] ActuationError),
    /// The genetic algorithm rejected its options.
    #[error("design optimisation: {0}")]
    Optimize(#[from] OptimizeError),
}

/// Ramana Babu et al., §V.B: maximise `GCI(a, b, c)` of one scheme at one orientation
/// subject to `a + b + c ≤ λ` and box bounds, base radius fixed.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignProblem {
    /// Base circumradius R (fixed).
    pub base_radius: f64,
    /// Size limit λ of `a + b + c ≤ λ`.
    pub size_limit: f64,
    /// Bounds of `(a, b, c)`.
    pub bounds: [(f64, f64); 3],
    /// Scheme.
    pub scheme: Scheme,
    /// Orientation φ (radians).
    pub phi: f64,
    /// Grid of the GCI.
    pub grid: WorkspaceGrid,
    /// GCI options (the domain defaults to [`GciDomain::Grid`] here, see the module doc).
    pub gci: GciOptions,
}

impl DesignProblem {
    /// The problem of Ramana Babu et al. for `scheme` at `phi` on the example geometry: λ
    /// = 9.3, `a ∈ [1, 3]`, `b, c ∈ [1, 4]`, grid `[−R, R]²` with `n × n` nodes, GCI over
    /// the grid.
    pub fn example(scheme: Scheme, phi: f64, n: usize) -> Self {
        let base_radius = ExampleGeometry::default().base_radius;
        Self {
            base_radius,
            size_limit: 9.3,
            bounds: [(1.0, 3.0), (1.0, 4.0), (1.0, 4.0)],
            scheme,
            phi,
            grid: WorkspaceGrid::square(base_radius, n),
            gci: GciOptions {
                domain: GciDomain::Grid,
                ..GciOptions::default()
            },
        }
    }

    /// Objective of the GA: the GCI when `a + b + c ≤ λ`, else the negative excess
    /// `−(a + b + c − λ)` (below every feasible value, pushing back into the feasible set).
    pub fn objective(&self, x: &[f64]) -> f64 {
        let excess = x.iter().sum::<f64>() - self.size_limit;
        if excess > 0.0 {
            return -excess;
        }
        let Ok(design) = RrrDesign::symmetric(self.base_radius, x[0], x[1], x[2]) else {
            return f64::NEG_INFINITY;
        };
        gci(&design, self.scheme, self.phi, &self.grid, &self.gci)
            .map(|r| r.gci)
            .unwrap_or(f64::NEG_INFINITY)
    }

    fn validate(&self, initial: &[f64; 3]) -> Result<(), ActuationError> {
        self.grid.validate()?;
        let bad = |field: &str, reason: String| ActuationError::InvalidField {
            field: field.to_string(),
            reason,
        };
        if !(self.base_radius.is_finite() && self.base_radius > 0.0) {
            return Err(bad(
                "base_radius",
                format!("{} must be > 0", self.base_radius),
            ));
        }
        if !(self.size_limit.is_finite() && self.size_limit > 0.0) {
            return Err(bad(
                "size_limit",
                format!("{} must be > 0", self.size_limit),
            ));
        }
        if !self.phi.is_finite() {
            return Err(bad("orientation", format!("{} must be finite", self.phi)));
        }
        for (k, &(lo, hi)) in self.bounds.iter().enumerate() {
            if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi) {
                return Err(bad(
                    &format!("bounds[{k}]"),
                    format!("[{lo}, {hi}] must satisfy 0 < lo <= hi"),
                ));
            }
            if !(lo..=hi).contains(&initial[k]) {
                return Err(bad(
                    &format!("initial[{k}]"),
                    format!("{} outside [{lo}, {hi}]", initial[k]),
                ));
            }
        }
        if initial.iter().sum::<f64>() > self.size_limit {
            return Err(bad(
                "initial",
                format!(
                    "a + b + c = {} exceeds λ = {}",
                    initial.iter().sum::<f64>(),
                    self.size_limit
                ),
            ));
        }
        Ok(())
    }
}

/// Result of [`optimize_design`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DesignOptimum {
    /// Optimal `(a, b, c)`.
    pub design_vector: [f64; 3],
    /// Objective (GCI per the problem's domain) at the optimum.
    pub objective: f64,
    /// Full GCI result at the optimum.
    pub gci: GciResult,
    /// Objective of the initial design.
    pub initial_objective: f64,
    /// Best objective per generation (non-decreasing).
    pub history: Vec<f64>,
    /// Objective evaluations.
    pub evaluations: usize,
}

/// Maximises the GCI over `(a, b, c)` with the crate's seeded GA ([`genetic_maximize`]); the
/// feasible `initial` design is placed in the first population, so the optimum is never worse
/// than it. Reproducible for a fixed `ga.seed`.
pub fn optimize_design(
    problem: &DesignProblem,
    initial: [f64; 3],
    ga: &GeneticOptions,
) -> Result<DesignOptimum, DesignError> {
    problem.validate(&initial)?;
    let initial_objective = problem.objective(&initial);
    let mut options = ga.clone();
    options.initial.insert(0, initial.to_vec());
    options.initial.truncate(options.population.max(1));
    let result = genetic_maximize(|x: &[f64]| problem.objective(x), &problem.bounds, &options)?;
    let design_vector = [result.best[0], result.best[1], result.best[2]];
    let design = RrrDesign::symmetric(
        problem.base_radius,
        design_vector[0],
        design_vector[1],
        design_vector[2],
    )
    .map_err(ActuationError::from)?;
    let gci_result = gci(
        &design,
        problem.scheme,
        problem.phi,
        &problem.grid,
        &problem.gci,
    )?;
    Ok(DesignOptimum {
        design_vector,
        objective: result.best_value,
        gci: gci_result,
        initial_objective,
        history: result.history,
        evaluations: result.evaluations,
    })
}
