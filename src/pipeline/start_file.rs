//! Generic start solutions: the files `supplementary/start/PLATFORM-BASE-SUBPROBLEM.json`
//! written by the ab-initio stage (SPEC A.9 step 1) and read by every later stage.
//!
//! A file records the problem, the variable names in order, the complex parameter
//! values of its source point, all finite critical points there, the largest residual,
//! the method and seed that produced it, and the certificate of completeness.

use crate::C64;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Certificate that a start-solution set is complete.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Certificate {
    /// `"trace-test"` (trace residual below tolerance), `"verified-count"` (the SPEC
    /// A.7 generic count, known exactly from Gröbner-basis computations, reached with
    /// distinct nonsingular solutions at a generic point: then no solution is missing),
    /// or `"none"` (not certified: the set may be incomplete).
    pub kind: String,
    /// Trace-test residual: relative deviation of the solutions' trace from linearity
    /// along a pencil of slices (small when no solution is missing); `None` when the
    /// trace test was not run (the count certificate applies) or could not be formed.
    pub trace_residual: Option<f64>,
    /// Threshold below which the trace test passes.
    pub tolerance: f64,
    /// Whether the test passed.
    pub passed: bool,
    /// Number of monodromy loops run.
    pub loops: usize,
    /// Paths that failed during the loops (they never add solutions).
    #[serde(default)]
    pub failed_paths: usize,
    /// Number of solutions found.
    #[serde(default)]
    pub found_count: usize,
    /// Generic count expected (SPEC A.7), if known.
    #[serde(default)]
    pub expected_count: Option<usize>,
}

/// Contents of a start-solution file (field names fixed by the project: `problem`,
/// `metric`, `subproblem`, `variables`, `parameters`, `solutions`, `max_residual`,
/// `method`, `seed`, `certificate`). Complex numbers are `[re, im]` pairs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StartSolutions {
    /// `PLATFORM/BASE:SUBPROBLEM`.
    pub problem: String,
    /// `PLATFORM/BASE`.
    pub metric: String,
    /// Sub-problem name.
    pub subproblem: String,
    /// Unknowns, in the order of each solution vector.
    pub variables: Vec<String>,
    /// Source parameter point: name → `[re, im]`.
    pub parameters: BTreeMap<String, C64>,
    /// All finite critical points at the source parameters.
    pub solutions: Vec<Vec<C64>>,
    /// Largest `‖F(x; p₀)‖_∞` over the solutions.
    pub max_residual: f64,
    /// How they were computed, e.g. `"monodromy"`.
    pub method: String,
    /// Seed of that computation.
    pub seed: u64,
    /// Completeness certificate.
    pub certificate: Certificate,
}

impl StartSolutions {
    /// The parameter vector in the order of `names`; `None` names the first missing one.
    pub fn parameter_vector(&self, names: &[String]) -> Result<Vec<C64>, String> {
        names
            .iter()
            .map(|name| {
                self.parameters
                    .get(name)
                    .copied()
                    .ok_or_else(|| name.clone())
            })
            .collect()
    }
}
