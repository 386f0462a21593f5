//! Generic start solutions: the files `supplementary/start/PLATFORM-BASE-SUBPROBLEM.json`
//! written by the ab-initio stage (docs/theory.md §8.1) and read by every later stage.
//!
//! A file records the problem, the variable names in order, the complex parameter
//! values of its source point, all finite critical points there, the largest residual,
//! the method and seed that produced it, and the certificate of completeness.

use crate::C64;
use crate::problem::Stratum;
use crate::system::Evaluator;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Certificate that a start-solution set is complete.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Certificate {
    /// `"trace-test"` (trace residual below tolerance), `"verified-count"` (the
    /// generic count of docs/theory.md §6, known exactly from Gröbner-basis computations,
    /// reached with distinct nonsingular solutions at a generic point: then no solution
    /// is missing), or `"none"` (not certified: the set may be incomplete).
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
    /// Generic count expected (docs/theory.md §6), if known.
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
    /// The stratum of the design space the source point lies on (absent: the generic
    /// one; [`Stratum`]).
    #[serde(default, skip_serializing_if = "Stratum::is_generic")]
    pub stratum: Stratum,
}

/// What every verification recomputes from a stored file (see
/// [`StartSolutions::measure`]).
#[derive(Clone, Debug, PartialEq)]
pub struct StoredMeasures {
    /// The stored parameters, in the system's order.
    pub parameters: Vec<C64>,
    /// Largest `‖F(x; p)‖_∞` over the stored solutions.
    pub max_residual: f64,
    /// Smallest `‖x − y‖_∞ / (1 + max(‖x‖_∞, ‖y‖_∞))` over pairs (∞ for fewer than two).
    pub min_separation: f64,
}

impl StartSolutions {
    /// Checks that the file belongs to problem `name` with unknowns `variables` and
    /// parameters `parameter_names` of `system`, then recomputes residuals and the
    /// separation of the stored solutions. Errors name the offending field.
    pub fn measure<E: Evaluator + ?Sized>(
        &self,
        name: &str,
        variables: &[String],
        parameter_names: &[String],
        system: &E,
    ) -> Result<StoredMeasures, String> {
        if self.problem != name {
            return Err(format!("field `problem` is `{}`", self.problem));
        }
        if self.variables != variables {
            return Err("field `variables` does not match the problem's unknowns".to_string());
        }
        let parameters = self.parameter_vector(parameter_names)?;
        let n = variables.len();
        if let Some(bad) = self.solutions.iter().position(|x| x.len() != n) {
            return Err(format!("field `solutions[{bad}]` has the wrong length"));
        }
        let max_norm = |v: &[C64]| v.iter().map(|z| z.norm()).fold(0.0, f64::max);
        let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
        let mut f = vec![C64::new(0.0, 0.0); system.num_equations()];
        let mut max_residual: f64 = 0.0;
        for x in &self.solutions {
            system.evaluate(x, &parameters, &mut work, &mut f);
            max_residual = max_residual.max(max_norm(&f));
        }
        let mut min_separation = f64::INFINITY;
        for (i, x) in self.solutions.iter().enumerate() {
            for y in &self.solutions[i + 1..] {
                let scale = 1.0 + max_norm(x).max(max_norm(y));
                let distance = x
                    .iter()
                    .zip(y)
                    .map(|(a, b)| (a - b).norm())
                    .fold(0.0, f64::max);
                min_separation = min_separation.min(distance / scale);
            }
        }
        Ok(StoredMeasures {
            parameters,
            max_residual,
            min_separation,
        })
    }

    /// The parameter vector in the order of `names` (the problem's parameters, all of
    /// them): an error names the first missing one, or says that the file has others
    /// too (a file of another stratum, [`Stratum`]).
    pub fn parameter_vector(&self, names: &[String]) -> Result<Vec<C64>, String> {
        let vector = names
            .iter()
            .map(|name| {
                self.parameters
                    .get(name)
                    .copied()
                    .ok_or_else(|| format!("field `parameters` lacks `{name}`"))
            })
            .collect::<Result<Vec<C64>, String>>()?;
        if self.parameters.len() != names.len() {
            return Err(format!(
                "field `parameters` has {} entries, the problem {} (a file of another \
                 stratum?)",
                self.parameters.len(),
                names.len()
            ));
        }
        Ok(vector)
    }

    /// The source point in the order of `parameter_names` (the problem's), after
    /// checking that the file fits a problem with these parameters and `variables`
    /// unknowns; the error says what does not fit.
    pub fn source_for(
        &self,
        parameter_names: &[String],
        variables: usize,
    ) -> Result<Vec<C64>, String> {
        let source = self.parameter_vector(parameter_names)?;
        if let Some(bad) = self.solutions.iter().find(|x| x.len() != variables) {
            return Err(format!(
                "a solution has {} entries, expected {variables}",
                bad.len()
            ));
        }
        Ok(source)
    }
}
