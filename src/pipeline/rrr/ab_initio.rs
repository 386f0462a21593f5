//! Ab-initio stage for the 3-RRR sub-problems of docs/theory.md §10 (Kapilavai and
//! Nawratil, §6.3): all finite critical points of `∇Λ = 0` at a random complex source
//! configuration, certified by a trace test, stored in `supplementary/start/rrr-*.json`
//! (the JSON format of [`crate::pipeline::start_file`], `metric` = `rrr-all-deformable`).
//!
//! The [`AbInitioProblem`] instance of [`crate::pipeline::ab_initio_stage`] for an [`RrrProblem`]
//! (the method of the 3-RPR, [`crate::pipeline::ab_initio`]). No generic count is known in advance: the counts were measured with two seeds (see the
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

use crate::homotopy::MonodromyOptions;
use crate::mechanism::rrr::CONFIGURATION_LEN;
use crate::pipeline::ab_initio_stage::{self, AbInitioOptions, AbInitioProblem, Polish};
use crate::pipeline::start_file::{Certificate, StartSolutions};
use crate::problem::rrr::{RRR_METRIC_NAME, RrrProblem, RrrSubProblem};

pub use crate::pipeline::ab_initio_stage::TRACE_ATTEMPTS;

/// Default seed of the 3-RRR ab-initio stage (the stored files were made with it).
pub const RRR_DEFAULT_SEED: u64 = 20_260_201;

/// Errors of the 3-RRR ab-initio stage: those of the stage (start pair, monodromy,
/// start-solution file; never `Problem`, the 3-RRR systems are built infallibly here).
pub type RrrAbInitioError = ab_initio_stage::AbInitioError;

/// Outcome of re-checking a 3-RRR start-solution file ([`verify_rrr_start_solutions`]).
pub type RrrVerification = ab_initio_stage::Verification;

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

impl RrrAbInitioOptions {
    /// The same settings as options of the stage.
    fn stage(&self) -> AbInitioOptions {
        AbInitioOptions {
            seed: self.seed,
            monodromy: self.monodromy.clone(),
        }
    }
}

impl AbInitioProblem for RrrProblem {
    /// One source point: without the trace test (`--no-trace-test`) a set is never
    /// certified, and its monodromy count at the given seed is the measurement.
    const SOURCE_ATTEMPTS: u64 = 1;
    const POLISH: Polish = Polish {
        steps: 3,
        keep_best: false,
    };
    /// The stored trace certificate stands; [`trace_certificate`] re-runs it (the
    /// parallel problem's witness set has 134 points).
    const VERIFY_RETRACES: bool = false;

    fn name(&self) -> String {
        self.kind().name()
    }
    fn metric_name(&self) -> String {
        RRR_METRIC_NAME.to_string()
    }
    fn subproblem_name(&self) -> String {
        self.kind().short_name()
    }
    fn file_stem(&self) -> String {
        self.kind().file_stem()
    }
    fn expected_count(&self) -> Option<usize> {
        None
    }
}

/// Computes and certifies the generic start solutions of `problem` (module documentation).
pub fn compute_rrr_start_solutions(
    problem: &RrrProblem,
    options: &RrrAbInitioOptions,
) -> Result<StartSolutions, RrrAbInitioError> {
    ab_initio_stage::compute_start_solutions(problem, &options.stage())
}

/// Re-runs the trace test (sliced on the coordinates `K′`, module documentation) on the
/// solutions stored in `file` ([`ab_initio_stage::retrace_certificate`]).
pub fn trace_certificate(
    problem: &RrrProblem,
    file: &StartSolutions,
    options: &RrrAbInitioOptions,
) -> Result<Certificate, RrrAbInitioError> {
    ab_initio_stage::retrace_certificate(problem, file, &options.stage())
}

/// Re-checks a stored file against its problem: names, residuals, distinctness,
/// nonsingularity and the stored certificate ([`ab_initio_stage::verify`]).
pub fn verify_rrr_start_solutions(
    problem: &RrrProblem,
    file: &StartSolutions,
) -> Result<RrrVerification, RrrAbInitioError> {
    ab_initio_stage::verify(problem, file)
}

/// The embedded start-solution file of `kind` (`supplementary/start/rrr-*.json`, embedded
/// by `build.rs`), if the build had one.
pub fn embedded_rrr_start_solutions(
    kind: RrrSubProblem,
) -> Option<Result<StartSolutions, RrrAbInitioError>> {
    ab_initio_stage::embedded_file(&kind.file_stem(), &kind.name())
}

/// The start solutions of `kind`: the embedded file, otherwise computed now with the
/// default options.
pub fn rrr_start_solutions(problem: &RrrProblem) -> Result<StartSolutions, RrrAbInitioError> {
    match embedded_rrr_start_solutions(problem.kind()) {
        Some(file) => file,
        None => compute_rrr_start_solutions(problem, &RrrAbInitioOptions::default()),
    }
}
