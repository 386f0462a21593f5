//! Ab-initio stage for the 3-RRR sub-problems of docs/theory.md §10 (Kapilavai and
//! Nawratil, §6.3): all finite critical points of `∇Λ = 0` at a random complex source
//! configuration, certified by a trace test, stored in `supplementary/start/rrr-*.json`
//! (the JSON format of [`super::start_file`], `metric` = `rrr-all-deformable`).
//!
//! Method (as for the 3-RPR, [`super::ab_initio`]): a start pair from minimum-norm
//! Gauss–Newton ([`find_start_pair`]), monodromy loops until stagnation
//! ([`monodromy_solve`]), the trace test on the incidence curve as certificate (re-run on
//! fresh slices with conservative tracking if a path failed), Newton refinement. No
//! generic count is known in advance: the counts were measured with two seeds (see the
//! tests and `systems/rrr_example_README.md`), and `certificate.passed` is set only when
//! the trace test passed.
//!
//! The trace test slices and sums only the 18 coordinates of `K′` (and the line
//! parameter μ), not the multiplier λ ([`MonodromyOptions::trace_slice_unknowns`]):
//! along the incidence curve over a parameter line, critical points reach the singular
//! locus of `C = 0` (for the parallel problem: `B_i = C_i` at the intersection of the other
//! two lines) with `K′` finite and `λ → ∞`. A slice involving λ meets those branches near
//! infinity, so its witness set is much larger and ill-conditioned (the parallel problem's
//! test never finished that way); in the projection to `(K′, μ)` the branches end at finite
//! points, and the witness set of the parallel problem has 134 points (residual ≈ 5e-15).

use super::start_file::{Certificate, StartSolutions};
use super::start_pair::find_start_pair;
use crate::C64;
use crate::homotopy::{MonodromyOptions, TrackerOptions, monodromy_solve};
use crate::mechanism::rrr::CONFIGURATION_LEN;
use crate::problem::rrr::{RRR_METRIC_NAME, RrrProblem, RrrSubProblem};
use crate::system::Evaluator;

/// Default seed of the 3-RRR ab-initio stage (the stored files were made with it).
pub const RRR_DEFAULT_SEED: u64 = 20_260_201;

/// Errors of the 3-RRR ab-initio stage: those of the 3-RPR stage (start pair, monodromy,
/// start-solution file; never `Problem`, the 3-RRR systems are built infallibly here).
pub type RrrAbInitioError = super::ab_initio::AbInitioError;

/// Options of the 3-RRR ab-initio stage.
#[derive(Clone, Debug)]
pub struct RrrAbInitioOptions {
    /// Seed of the start pair, the loops and the trace slices.
    pub seed: u64,
    /// Monodromy options; with `trace_test = false` only the monodromy count is measured
    /// (certificate `none`).
    pub monodromy: MonodromyOptions,
}

impl Default for RrrAbInitioOptions {
    fn default() -> Self {
        RrrAbInitioOptions {
            seed: RRR_DEFAULT_SEED,
            monodromy: MonodromyOptions {
                max_stagnant_loops: 15,
                trace_test: true,
                trace_slice_unknowns: Some(CONFIGURATION_LEN),
                ..MonodromyOptions::default()
            },
        }
    }
}

/// Whether `x` is within 1e-6 (relative) of a point of `set`.
fn contains(set: &[Vec<C64>], x: &[C64]) -> bool {
    let scale = 1.0 + x.iter().map(|v| v.norm()).fold(0.0, f64::max);
    set.iter()
        .any(|y| y.iter().zip(x).all(|(a, b)| (a - b).norm() <= 1e-6 * scale))
}

/// Computes and certifies the generic start solutions of `problem` (module documentation).
pub fn compute_rrr_start_solutions(
    problem: &RrrProblem,
    options: &RrrAbInitioOptions,
) -> Result<StartSolutions, RrrAbInitioError> {
    let kind = problem.kind();
    let system = problem.evaluator();
    let pair =
        find_start_pair(system, options.seed).map_err(|source| RrrAbInitioError::StartPair {
            problem: kind.name(),
            source,
        })?;
    let monodromy = options.monodromy.clone();
    let result =
        monodromy_solve(system, &pair.x, &pair.p, &monodromy, options.seed).map_err(|source| {
            RrrAbInitioError::Homotopy {
                problem: kind.name(),
                source,
            }
        })?;
    let mut solutions: Vec<Vec<C64>> = Vec::new();
    for x in result.solutions {
        if !contains(&solutions, &x) {
            solutions.push(x);
        }
    }
    let mut loops = result.loops + result.witness_loops;
    let mut failed_paths = result.failed_paths;
    let mut trace_residual = result.trace_residual;
    let mut certified = result.certified;
    // A failed path on the trace slices voids the test: retry on fresh random slices
    // with conservative tracking (points added there join the set).
    let mut careful = monodromy.clone();
    careful.tracker = TrackerOptions::conservative();
    let mut rng = crate::random::stream(options.seed, 1);
    let attempts = if monodromy.trace_test { 3 } else { 0 };
    for _attempt in 0..attempts {
        if certified {
            break;
        }
        if let Some(trace) =
            crate::homotopy::trace_test(system, &result.parameters, &solutions, &careful, &mut rng)
        {
            loops += trace.witness_loops;
            failed_paths += trace.failed_paths;
            for x in trace.added_solutions {
                if !contains(&solutions, &x) {
                    solutions.push(x);
                }
            }
            trace_residual = Some(trace.residual);
            certified = trace.residual < careful.trace_tolerance;
        }
    }
    let max_residual = refine(system, &result.parameters, &mut solutions);
    solutions.sort_by(|a, b| {
        a.iter()
            .zip(b)
            .map(|(x, y)| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let found = solutions.len();
    Ok(StartSolutions {
        problem: kind.name(),
        metric: RRR_METRIC_NAME.to_string(),
        subproblem: kind.short_name(),
        variables: problem.variable_names().to_vec(),
        parameters: problem
            .parameter_names()
            .iter()
            .cloned()
            .zip(result.parameters.iter().copied())
            .collect(),
        solutions,
        max_residual,
        method: "monodromy (minimum-norm Gauss-Newton start pair) + trace test".to_string(),
        seed: options.seed,
        certificate: Certificate {
            kind: if certified { "trace-test" } else { "none" }.to_string(),
            trace_residual,
            tolerance: monodromy.trace_tolerance,
            passed: certified,
            loops,
            failed_paths,
            found_count: found,
            expected_count: None,
        },
    })
}

/// Newton-refines every solution (a few steps) and returns the largest residual
/// `‖F(x; p)‖_∞` afterwards.
pub fn refine<E: Evaluator + ?Sized>(system: &E, p: &[C64], solutions: &mut [Vec<C64>]) -> f64 {
    let n = system.num_variables();
    let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
    let mut f = vec![C64::new(0.0, 0.0); n];
    let mut jac = vec![C64::new(0.0, 0.0); n * n];
    let mut worst: f64 = 0.0;
    for x in solutions.iter_mut() {
        for _ in 0..3 {
            system.evaluate_with_jacobian(x, p, &mut work, &mut f, &mut jac);
            let matrix = nalgebra::DMatrix::from_row_slice(n, n, &jac);
            let Some(step) = matrix.lu().solve(&nalgebra::DVector::from_column_slice(&f)) else {
                break;
            };
            for (xi, si) in x.iter_mut().zip(step.iter()) {
                *xi -= si;
            }
        }
        system.evaluate(x, p, &mut work, &mut f);
        worst = worst.max(f.iter().map(|v| v.norm()).fold(0.0, f64::max));
    }
    worst
}

/// Re-runs the trace test (sliced on the coordinates `K′`, module documentation) on the
/// solutions stored in `file` at its source parameters, with `options.monodromy`'s
/// witness-set settings and a stream of `options.seed`. The certificate passes when the
/// trace residual is below the tolerance and tracking the surplus witness points back
/// to the fiber adds no solution. A slice on which a trace path fails (or whose residual
/// is not small) is replaced by a fresh random slice tracked conservatively, up to
/// [`TRACE_ATTEMPTS`] slices in all; loops and failed paths are summed over them.
pub fn trace_certificate(
    problem: &RrrProblem,
    file: &StartSolutions,
    options: &RrrAbInitioOptions,
) -> Result<Certificate, RrrAbInitioError> {
    let kind = problem.kind();
    let system = problem.evaluator();
    let measured = file
        .measure(
            &kind.name(),
            problem.variable_names(),
            problem.parameter_names(),
            system,
        )
        .map_err(|message| RrrAbInitioError::File {
            problem: kind.name(),
            message,
        })?;
    let mut rng = crate::random::stream(options.seed, 2);
    let tolerance = options.monodromy.trace_tolerance;
    let mut certificate = Certificate {
        kind: "none: no witness point could be formed".to_string(),
        trace_residual: None,
        tolerance,
        passed: false,
        loops: 0,
        failed_paths: 0,
        found_count: file.solutions.len(),
        expected_count: None,
    };
    let mut monodromy = options.monodromy.clone();
    for _attempt in 0..TRACE_ATTEMPTS {
        if let Some(trace) = crate::homotopy::trace_test(
            system,
            &measured.parameters,
            &file.solutions,
            &monodromy,
            &mut rng,
        ) {
            certificate.kind = "trace-test".to_string();
            certificate.trace_residual = Some(trace.residual);
            certificate.passed = trace.residual < tolerance && trace.added_solutions.is_empty();
            certificate.loops += trace.witness_loops;
            certificate.failed_paths += trace.failed_paths;
            certificate.found_count = file.solutions.len() + trace.added_solutions.len();
            if certificate.passed || !trace.added_solutions.is_empty() {
                break;
            }
        }
        monodromy.tracker = TrackerOptions::conservative();
    }
    Ok(certificate)
}

/// Random slices [`trace_certificate`] tries.
pub const TRACE_ATTEMPTS: usize = 3;

/// Outcome of re-checking a 3-RRR start-solution file ([`verify_rrr_start_solutions`]).
#[derive(Clone, Debug, PartialEq)]
pub struct RrrVerification {
    /// Problem name.
    pub problem: String,
    /// Number of stored solutions.
    pub count: usize,
    /// Largest residual recomputed at the stored parameters.
    pub max_residual: f64,
    /// Smallest distance between two stored solutions (relative to their size).
    pub min_separation: f64,
    /// Smallest `σ_min/σ_max` of the Jacobian over the solutions.
    pub min_relative_singular_value: f64,
    /// Residual < 1e-10, separation > 1e-6, nonsingular, stored certificate passed.
    pub passed: bool,
}

/// Re-checks a stored file against its problem: names, residuals, distinctness,
/// nonsingularity and the stored certificate.
pub fn verify_rrr_start_solutions(
    problem: &RrrProblem,
    file: &StartSolutions,
) -> Result<RrrVerification, RrrAbInitioError> {
    let kind = problem.kind();
    let file_error = |message: String| RrrAbInitioError::File {
        problem: kind.name(),
        message,
    };
    let system = problem.evaluator();
    let super::start_file::StoredMeasures {
        parameters: p,
        max_residual,
        min_separation,
    } = file
        .measure(
            &kind.name(),
            problem.variable_names(),
            problem.parameter_names(),
            system,
        )
        .map_err(file_error)?;
    let min_relative_singular_value =
        super::ab_initio::smallest_relative_singular_value(system, &p, &file.solutions);
    let passed = max_residual < 1e-10
        && min_separation > 1e-6
        && min_relative_singular_value > super::ab_initio::NONSINGULAR_THRESHOLD
        && file.certificate.passed;
    Ok(RrrVerification {
        problem: kind.name(),
        count: file.solutions.len(),
        max_residual,
        min_separation,
        min_relative_singular_value,
        passed,
    })
}

/// The embedded start-solution file of `kind` (`supplementary/start/rrr-*.json`, embedded
/// by `build.rs`), if the build had one.
pub fn embedded_rrr_start_solutions(
    kind: RrrSubProblem,
) -> Option<Result<StartSolutions, RrrAbInitioError>> {
    let stem = kind.file_stem();
    super::embedded::EMBEDDED_START_FILES
        .iter()
        .find(|(s, _)| *s == stem)
        .map(|(_, text)| {
            serde_json::from_str(text).map_err(|e| RrrAbInitioError::File {
                problem: kind.name(),
                message: e.to_string(),
            })
        })
}

/// The start solutions of `kind`: the embedded file, otherwise computed now with the
/// default options.
pub fn rrr_start_solutions(problem: &RrrProblem) -> Result<StartSolutions, RrrAbInitioError> {
    match embedded_rrr_start_solutions(problem.kind()) {
        Some(file) => file,
        None => compute_rrr_start_solutions(problem, &RrrAbInitioOptions::default()),
    }
}
