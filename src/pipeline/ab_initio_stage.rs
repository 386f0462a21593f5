//! The ab-initio stage of every mechanism (docs/theory.md §8.1): all finite critical
//! points of a sub-problem at a random complex source configuration, computed once,
//! certified, stored as a start-solution file ([`super::start_file`]), and re-checked
//! from the stored file.
//!
//! Method: a start pair `(x₀, p₀)` on the solution variety from minimum-norm
//! Gauss–Newton ([`super::start_pair`]); monodromy loops through random complex
//! parameter points until the fiber stops growing ([`monodromy_solve`]; Duff, Hill,
//! Jensen, Lee, Leykin, Sommars, "Solving polynomial systems via homotopy continuation
//! and monodromy", IMA J. Numer. Anal., 2019); where the generic count is known, further
//! start pairs carried to the source point seed the orbits of other components of a
//! reducible variety; the trace test on the incidence curve as the certificate of
//! completeness where it is not (Leykin, Rodriguez, Sottile, "Trace test", Arnold Math.
//! J., 2018), re-run on fresh slices with conservative tracking when a path failed;
//! Newton refinement; the solutions in lexicographic order.
//!
//! A mechanism enters the stage through [`AbInitioProblem`]: its system, names,
//! expected generic count and stage settings (the trace-test slice unknowns are part of
//! its default [`AbInitioOptions`]). The 3-RPR ([`super::ab_initio`]) and the 3-RRR
//! ([`super::rrr::ab_initio`]) are the two instances.

use super::start_file::{Certificate, StartSolutions, StoredMeasures};
use super::start_pair::{StartPair, StartPairError, find_start_pair};
use crate::C64;
use crate::homotopy::{
    HomotopyError, MonodromyOptions, SolveOptions, TrackerOptions, contains_point, monodromy_solve,
    solve_parameter_homotopy, trace_test,
};
use crate::problem::{ProblemError, Stratum};
use crate::system::{Evaluator, ParametricSystem};
use std::ops::Deref;

/// Errors of the ab-initio stage.
#[derive(Debug, thiserror::Error)]
pub enum AbInitioError {
    /// The problem could not be built.
    #[error(transparent)]
    Problem(#[from] ProblemError),
    /// No start pair.
    #[error("{problem}: {source}")]
    StartPair {
        /// Problem name.
        problem: String,
        /// Cause.
        source: StartPairError,
    },
    /// The monodromy solver failed.
    #[error("{problem}: {source}")]
    Homotopy {
        /// Problem name.
        problem: String,
        /// Cause.
        source: HomotopyError,
    },
    /// A start-solution file is unreadable or does not belong to its problem.
    #[error("start-solution file of {problem}: {message}")]
    File {
        /// Problem name.
        problem: String,
        /// What is wrong, naming the field.
        message: String,
    },
}

/// Options of the ab-initio stage.
#[derive(Clone, Debug)]
pub struct AbInitioOptions {
    /// Seed of the start pair, the monodromy loops and the trace slices.
    pub seed: u64,
    /// Monodromy options (with the trace-test settings: `trace_test = false` measures
    /// only the monodromy count where no generic count is known, certificate `none`).
    pub monodromy: MonodromyOptions,
}

/// A mechanism's sub-problem as the ab-initio stage sees it: its square parametric
/// system `F(x; p) = 0` with the names of unknowns and parameters (the [`Deref`]
/// target), its names in the start-solution file, its generic count and settings.
pub trait AbInitioProblem: Deref<Target = ParametricSystem> {
    /// Source points tried (seeds `seed, seed + 1, …`) until one gives a certified set.
    const SOURCE_ATTEMPTS: u64;
    /// The final Newton refinement ([`refine_solutions`]).
    const POLISH: Polish;
    /// Whether [`verify`] re-runs the trace test where no generic count is known
    /// (otherwise the stored certificate stands; [`retrace_certificate`] re-runs it).
    const VERIFY_RETRACES: bool;

    /// Its name (`bars/rigid:collinear-platform`, `rrr:leg1`): the file's `problem`.
    fn name(&self) -> String;
    /// The file's `metric` field.
    fn metric_name(&self) -> String;
    /// The file's `subproblem` field.
    fn subproblem_name(&self) -> String;
    /// The file's name in the start folder, without `.json`.
    fn file_stem(&self) -> String;
    /// The generic number of finite critical points, where it is known.
    fn expected_count(&self) -> Option<usize>;
    /// The stratum of the parameter space the problem is posed on (recorded in the
    /// file; the generic one by default).
    fn stratum(&self) -> Stratum {
        Stratum::GENERIC
    }
    /// The certificate kind of a set that reached [`AbInitioProblem::expected_count`]
    /// with distinct nonsingular solutions: it names where the count comes from.
    fn count_certificate(&self) -> String {
        VERIFIED_GENERIC_COUNT.to_string()
    }

    /// A start pair on the solution variety, seeded.
    fn start_pair(&self, seed: u64) -> Result<StartPair, StartPairError> {
        find_start_pair(self.evaluator(), seed)
    }

    /// The start-solution file of this problem embedded in the binary
    /// (`supplementary/start/`, see `build.rs`), if the build had one.
    fn embedded(&self) -> Option<Result<StartSolutions, AbInitioError>> {
        embedded_file(&self.file_stem(), &self.name())
    }
}

/// The embedded start-solution file `stem` (problem `name` in errors), if any.
pub fn embedded_file(stem: &str, name: &str) -> Option<Result<StartSolutions, AbInitioError>> {
    super::embedded::EMBEDDED_START_FILES
        .iter()
        .find(|(s, _)| *s == stem)
        .map(|(_, text)| {
            serde_json::from_str(text).map_err(|e| AbInitioError::File {
                problem: name.to_string(),
                message: e.to_string(),
            })
        })
}

/// The certificate kind of a set that reached the generic count of docs/theory.md §6.
pub const VERIFIED_GENERIC_COUNT: &str = "verified-count (generic count of docs/theory.md §6 reached with distinct nonsingular solutions)";

/// Further start pairs tried when monodromy from the first stays below the generic count.
const EXTRA_START_PAIRS: usize = 4;

/// Trace tests tried on fresh slices (conservative tracking after the first).
pub const TRACE_ATTEMPTS: usize = 3;

/// Largest residual `‖F(x; p)‖_∞` a stored start solution may have (checked by [`verify`]).
pub const MAX_STORED_RESIDUAL: f64 = 1e-10;

/// Solutions whose `σ_min/σ_max(∂F/∂x)` is below this are treated as singular.
pub const NONSINGULAR_THRESHOLD: f64 = 1e-10;

/// Two stored solutions closer than this (relative, [`StoredMeasures::min_separation`])
/// are not distinct; also the same-point tolerance of the stage.
pub const MIN_SEPARATION: f64 = 1e-6;

/// Computes the generic start solutions of `problem` (module documentation).
///
/// Some random source points are badly scaled (solutions of norm ~10³, many failed loop
/// paths, monodromy stalling below the generic count); up to
/// [`AbInitioProblem::SOURCE_ATTEMPTS`] seeds are tried, and the first certified set is
/// returned (its `seed` field records the seed that produced it). If none is certified,
/// the largest set is returned with `certificate.passed = false`.
pub fn compute_start_solutions<P: AbInitioProblem>(
    problem: &P,
    options: &AbInitioOptions,
) -> Result<StartSolutions, AbInitioError> {
    let mut best: Option<StartSolutions> = None;
    for attempt in 0..P::SOURCE_ATTEMPTS.max(1) {
        let seed = options.seed.wrapping_add(attempt);
        let file = compute_at_source(problem, options, seed)?;
        if file.certificate.passed {
            return Ok(file);
        }
        if best
            .as_ref()
            .is_none_or(|b| file.solutions.len() > b.solutions.len())
        {
            best = Some(file);
        }
    }
    Ok(best.expect("at least one source attempt"))
}

/// One source point (of seed `seed`): start pair, monodromy, orbits of further start
/// pairs, trace test, refinement, certificate.
fn compute_at_source<P: AbInitioProblem>(
    problem: &P,
    options: &AbInitioOptions,
    seed: u64,
) -> Result<StartSolutions, AbInitioError> {
    let name = problem.name();
    let system = problem.evaluator();
    let expected = problem.expected_count();
    let pair = problem
        .start_pair(seed)
        .map_err(|source| AbInitioError::StartPair {
            problem: name.clone(),
            source,
        })?;
    let mut monodromy = options.monodromy.clone();
    if monodromy.target_solution_count.is_none() {
        monodromy.target_solution_count = expected;
    }
    // Where the generic count is known exactly (docs/theory.md §6), reaching it with
    // distinct nonsingular solutions is the certificate; the trace test (whose witness
    // set on the incidence curve is far larger than the fiber) is run only where it is not.
    if expected.is_some() {
        monodromy.trace_test = false;
    }
    let result = monodromy_solve(system, &pair.x, &pair.p, &monodromy, seed).map_err(|source| {
        AbInitioError::Homotopy {
            problem: name.clone(),
            source,
        }
    })?;
    let source = result.parameters.clone();
    let mut solutions: Vec<Vec<C64>> = Vec::new();
    add_new(&mut solutions, result.solutions);
    let mut loops = result.loops + result.witness_loops;
    let mut failed_paths = result.failed_paths;
    // The solution variety may be reducible: monodromy only permutes the fiber of the
    // component through its start pair. Further random start pairs, carried to the
    // source parameters by a parameter homotopy, seed the orbits of other components.
    let mut extra_pair = 1;
    while expected.is_some_and(|e| solutions.len() < e) && extra_pair <= EXTRA_START_PAIRS {
        let seed = seed.wrapping_add(1_000 * extra_pair as u64);
        extra_pair += 1;
        let Some(x) = carried_start(problem, &source, seed) else {
            continue;
        };
        if contains_point(&solutions, &x, MIN_SEPARATION) {
            continue;
        }
        let mut orbit_options = monodromy.clone();
        orbit_options.target_solution_count = expected.map(|e| e - solutions.len());
        let Ok(orbit) = monodromy_solve(system, &x, &source, &orbit_options, seed) else {
            continue;
        };
        loops += orbit.loops;
        failed_paths += orbit.failed_paths;
        add_new(&mut solutions, orbit.solutions);
    }
    let mut trace_residual = result.trace_residual;
    let mut certified = result.certified;
    // A failed path on the trace slices voids the test: retry on fresh random slices
    // with conservative tracking (points added there join the set).
    let mut careful = monodromy.clone();
    careful.tracker = TrackerOptions::conservative();
    let mut rng = crate::random::stream(seed, 1);
    let attempts = if monodromy.trace_test {
        TRACE_ATTEMPTS
    } else {
        0
    };
    for _attempt in 0..attempts {
        if certified {
            break;
        }
        if let Some(trace) = trace_test(system, &source, &solutions, &careful, &mut rng) {
            loops += trace.witness_loops;
            failed_paths += trace.failed_paths;
            add_new(&mut solutions, trace.added_solutions);
            trace_residual = Some(trace.residual);
            certified = trace.residual < careful.trace_tolerance;
        }
    }
    let max_residual = refine_solutions(system, &source, &mut solutions, P::POLISH);
    let found = solutions.len();
    let kind = if certified {
        "trace-test".to_string()
    } else if expected == Some(found)
        && smallest_relative_singular_value(system, &source, &solutions) > NONSINGULAR_THRESHOLD
    {
        // The generic fiber has exactly `expected` points (docs/theory.md §6, exact
        // Gröbner-basis counts), so that many distinct nonsingular solutions at a generic
        // point are all.
        certified = true;
        problem.count_certificate()
    } else {
        "none".to_string()
    };
    solutions.sort_by(|a, b| lexicographic(a, b));
    Ok(StartSolutions {
        problem: name,
        metric: problem.metric_name(),
        subproblem: problem.subproblem_name(),
        variables: problem.variable_names().to_vec(),
        parameters: problem
            .parameter_names()
            .iter()
            .cloned()
            .zip(source.iter().copied())
            .collect(),
        solutions,
        max_residual,
        method: "monodromy (minimum-norm Gauss-Newton start pair) + trace test".to_string(),
        seed,
        stratum: problem.stratum(),
        certificate: Certificate {
            kind,
            trace_residual,
            tolerance: monodromy.trace_tolerance,
            // A set whose residuals cannot be refined below the storage bound comes from a
            // badly scaled source point: not accepted, the next source point is tried.
            passed: certified && max_residual < MAX_STORED_RESIDUAL,
            loops,
            failed_paths,
            found_count: found,
            expected_count: expected,
        },
    })
}

/// A solution at the parameters `source`: a fresh start pair of seed `seed` carried
/// there by a parameter homotopy, if it arrives nonsingular.
fn carried_start<P: AbInitioProblem>(problem: &P, source: &[C64], seed: u64) -> Option<Vec<C64>> {
    let other = problem.start_pair(seed).ok()?;
    let carry = SolveOptions {
        seed,
        // The classic endgame the stored start files were made with.
        tracker: TrackerOptions::default(),
        ..SolveOptions::default()
    };
    let carried =
        solve_parameter_homotopy(problem.evaluator(), &[other.x], &other.p, source, &carry).ok()?;
    carried.nonsingular_solutions().into_iter().next()
}

/// Appends the points of `new` that are not yet in `set` (nor earlier in `new`).
fn add_new(set: &mut Vec<Vec<C64>>, new: Vec<Vec<C64>>) {
    for x in new {
        if !contains_point(set, &x, MIN_SEPARATION) {
            set.push(x);
        }
    }
}

/// Lexicographic order on `(Re x₁, Im x₁, Re x₂, …)` (total order of the floats).
fn lexicographic(a: &[C64], b: &[C64]) -> std::cmp::Ordering {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)))
        .find(|o| o.is_ne())
        .unwrap_or(std::cmp::Ordering::Equal)
}

/// Buffers of one evaluation of `F(x; p)` and `∂F/∂x` (workspace, values, Jacobian).
struct Scratch {
    work: Vec<C64>,
    f: Vec<C64>,
    jac: Vec<C64>,
}

impl Scratch {
    fn new<E: Evaluator + ?Sized>(system: &E) -> Self {
        let n = system.num_variables();
        Scratch {
            work: vec![C64::new(0.0, 0.0); system.workspace_len()],
            f: vec![C64::new(0.0, 0.0); n],
            jac: vec![C64::new(0.0, 0.0); n * n],
        }
    }

    /// Evaluates `F(x; p)` into `self.f` and returns `∂F/∂x` as a matrix.
    fn jacobian<E: Evaluator + ?Sized>(
        &mut self,
        system: &E,
        x: &[C64],
        p: &[C64],
    ) -> nalgebra::DMatrix<C64> {
        system.evaluate_with_jacobian(x, p, &mut self.work, &mut self.f, &mut self.jac);
        let n = self.f.len();
        nalgebra::DMatrix::from_row_slice(n, n, &self.jac)
    }
}

/// The final Newton refinement of a stage ([`refine_solutions`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Polish {
    /// Newton steps `x ← x − (∂F/∂x)⁻¹ F` at most (fewer where `∂F/∂x` is singular).
    pub steps: usize,
    /// Keep the iterate of smallest residual (at rounding level the updates only add
    /// noise) instead of the last one.
    pub keep_best: bool,
}

/// Newton-refines every solution in place as `polish` says and returns the largest
/// residual `‖F(x; p)‖_∞` afterwards.
pub fn refine_solutions<E: Evaluator + ?Sized>(
    system: &E,
    p: &[C64],
    solutions: &mut [Vec<C64>],
    polish: Polish,
) -> f64 {
    let mut scratch = Scratch::new(system);
    let mut worst: f64 = 0.0;
    let max_norm = |v: &[C64]| v.iter().map(|z| z.norm()).fold(0.0, f64::max);
    for x in solutions.iter_mut() {
        let mut best = polish.keep_best.then(|| (x.clone(), f64::INFINITY));
        for _ in 0..polish.steps {
            let matrix = scratch.jacobian(system, x, p);
            if let Some((point, smallest)) = best.as_mut() {
                let residual = max_norm(&scratch.f);
                if residual < *smallest {
                    *smallest = residual;
                    point.copy_from_slice(x);
                }
            }
            let f = nalgebra::DVector::from_column_slice(&scratch.f);
            let Some(step) = matrix.lu().solve(&f) else {
                break;
            };
            for (xi, si) in x.iter_mut().zip(step.iter()) {
                *xi -= si;
            }
        }
        system.evaluate(x, p, &mut scratch.work, &mut scratch.f);
        let mut residual = max_norm(&scratch.f);
        if let Some((point, smallest)) = &best {
            if residual > *smallest {
                x.copy_from_slice(point);
            }
            residual = residual.min(*smallest);
        }
        worst = worst.max(residual);
    }
    worst
}

/// Smallest `σ_min/σ_max` of `∂F/∂x` over the solutions (1 for an empty set).
pub fn smallest_relative_singular_value<E: Evaluator + ?Sized>(
    system: &E,
    p: &[C64],
    solutions: &[Vec<C64>],
) -> f64 {
    let mut scratch = Scratch::new(system);
    let mut smallest: f64 = 1.0;
    for x in solutions {
        let singular = scratch.jacobian(system, x, p).singular_values();
        let ratio = if singular.max() > 0.0 {
            singular.min() / singular.max()
        } else {
            0.0
        };
        smallest = smallest.min(ratio);
    }
    smallest
}

/// Outcome of re-checking one start-solution file ([`verify`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Verification {
    /// Problem name.
    pub problem: String,
    /// Number of stored solutions.
    pub count: usize,
    /// The generic count expected, if known.
    pub expected: Option<usize>,
    /// Largest residual recomputed at the stored parameters.
    pub max_residual: f64,
    /// Smallest distance between two stored solutions (relative to their size).
    pub min_separation: f64,
    /// Smallest `σ_min/σ_max` of the Jacobian over the solutions.
    pub min_relative_singular_value: f64,
    /// Trace test re-run from the stored data (only where no generic count is known and
    /// the mechanism re-runs it, [`AbInitioProblem::VERIFY_RETRACES`]).
    pub trace_residual: Option<f64>,
    /// All checks pass: completeness (the generic count, or the re-run trace test),
    /// nonsingular, residual below [`MAX_STORED_RESIDUAL`], separation above
    /// [`MIN_SEPARATION`], stored certificate passed.
    pub passed: bool,
}

/// The stored measures of `file` checked against `problem` (names, lengths, residuals,
/// separation); errors name the field.
fn measure<P: AbInitioProblem>(
    problem: &P,
    file: &StartSolutions,
) -> Result<StoredMeasures, AbInitioError> {
    if file.stratum != problem.stratum() {
        return Err(AbInitioError::File {
            problem: problem.name(),
            message: format!(
                "field `stratum` is {}, the problem's {}",
                file.stratum.name().unwrap_or("generic"),
                problem.stratum().name().unwrap_or("generic")
            ),
        });
    }
    file.measure(
        &problem.name(),
        problem.variable_names(),
        problem.parameter_names(),
        problem.evaluator(),
    )
    .map_err(|message| AbInitioError::File {
        problem: problem.name(),
        message,
    })
}

/// Re-checks a start-solution file: its variables and parameters match the problem,
/// residuals, distinctness, nonsingularity, the count where it is known, and where it
/// is not the trace test re-run (seeded by the file's seed) if the mechanism asks for it.
pub fn verify<P: AbInitioProblem>(
    problem: &P,
    file: &StartSolutions,
) -> Result<Verification, AbInitioError> {
    let system = problem.evaluator();
    let StoredMeasures {
        parameters: p,
        max_residual,
        min_separation,
    } = measure(problem, file)?;
    let expected = problem.expected_count();
    let min_relative_singular_value = smallest_relative_singular_value(system, &p, &file.solutions);
    let (complete, trace_residual) = match expected {
        Some(count) => (count == file.solutions.len(), None),
        None if P::VERIFY_RETRACES => {
            let mut rng = crate::random::seeded(file.seed ^ 0x5eed);
            let options = MonodromyOptions {
                max_stagnant_loops: 2,
                ..MonodromyOptions::default()
            };
            let trace = trace_test(system, &p, &file.solutions, &options, &mut rng);
            let passed = trace.as_ref().is_some_and(|t| {
                t.residual < options.trace_tolerance && t.added_solutions.is_empty()
            });
            (passed, trace.map(|t| t.residual))
        }
        None => (true, None),
    };
    let passed = complete
        && min_relative_singular_value > NONSINGULAR_THRESHOLD
        && max_residual < MAX_STORED_RESIDUAL
        && min_separation > MIN_SEPARATION
        && file.certificate.passed;
    Ok(Verification {
        problem: problem.name(),
        count: file.solutions.len(),
        expected,
        max_residual,
        min_separation,
        min_relative_singular_value,
        trace_residual,
        passed,
    })
}

/// Re-runs the trace test on the solutions stored in `file` at its source parameters,
/// with `options.monodromy`'s witness-set settings and a stream of `options.seed`. The
/// certificate passes when the trace residual is below the tolerance and tracking the
/// surplus witness points back to the fiber adds no solution. A slice on which a trace
/// path fails (or whose residual is not small) is replaced by a fresh random slice
/// tracked conservatively, up to [`TRACE_ATTEMPTS`] slices in all; loops and failed
/// paths are summed over them.
pub fn retrace_certificate<P: AbInitioProblem>(
    problem: &P,
    file: &StartSolutions,
    options: &AbInitioOptions,
) -> Result<Certificate, AbInitioError> {
    let measured = measure(problem, file)?;
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
        expected_count: problem.expected_count(),
    };
    let mut monodromy = options.monodromy.clone();
    for _attempt in 0..TRACE_ATTEMPTS {
        if let Some(trace) = trace_test(
            problem.evaluator(),
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
