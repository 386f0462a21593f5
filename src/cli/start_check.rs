//! Re-checking stored start-solution files, for `ab-initio --verify` (every 3-RPR and
//! 3-RRR file) and `rrr ab-initio --verify`: where a stored file is read from, one line
//! per file with its measures and verdict, and the verdict of the whole check.

use super::outcome::Outcome;
use anyhow::{Context, Result, bail};
use singdist::pipeline::ab_initio;
use singdist::pipeline::rrr_ab_initio::verify_rrr_start_solutions;
use singdist::pipeline::start_file::StartSolutions;
use singdist::problem::LagrangeProblem;
use singdist::problem::rrr::RrrProblem;
use std::path::Path;

/// The start-solution file at `path` if it exists, otherwise the copy `embedded` in the
/// binary; `None` when there is neither. Errors name the file.
pub fn read_stored<E>(
    path: &Path,
    embedded: impl FnOnce() -> Option<Result<StartSolutions, E>>,
) -> Result<Option<StartSolutions>>
where
    E: std::error::Error + Send + Sync + 'static,
{
    if path.exists() {
        let text = std::fs::read_to_string(path).with_context(|| path.display().to_string())?;
        let file = serde_json::from_str(&text).with_context(|| path.display().to_string())?;
        return Ok(Some(file));
    }
    Ok(embedded().transpose()?)
}

/// Prints the line of a problem whose file is neither at `path` nor embedded.
pub fn print_missing(problem: &str, path: &Path) {
    println!("{problem:<40} MISSING ({})", path.display());
}

/// Re-checks a 3-RPR start file ([`ab_initio::verify`]: residuals, count, distinctness,
/// trace test where no count is known) and prints its line; `true` if it passes.
pub fn verify_rpr(problem: &LagrangeProblem, file: &StartSolutions) -> Result<bool> {
    let check = ab_initio::verify(problem, file)?;
    println!(
        "{:<40} {} solutions (expected {}), max residual {:.1e}, min separation {:.1e}, trace {}: {}",
        check.problem,
        check.count,
        check
            .expected
            .map_or("unknown".to_string(), |e| e.to_string()),
        check.max_residual,
        check.min_separation,
        check
            .trace_residual
            .map_or("not run".to_string(), |t| format!("{t:.1e}")),
        verdict(check.passed)
    );
    Ok(check.passed)
}

/// Re-checks a 3-RRR start file ([`verify_rrr_start_solutions`]: residuals,
/// distinctness, nonsingularity, stored certificate) and prints its line; `true` if it
/// passes.
pub fn verify_rrr(problem: &RrrProblem, file: &StartSolutions) -> Result<bool> {
    let report = verify_rrr_start_solutions(problem, file)?;
    println!(
        "{}: {} solutions, max residual {:.2e}, min separation {:.2e}, min σ ratio {:.2e}: {}",
        report.problem,
        report.count,
        report.max_residual,
        report.min_separation,
        report.min_relative_singular_value,
        verdict(report.passed)
    );
    Ok(report.passed)
}

fn verdict(passed: bool) -> &'static str {
    if passed { "ok" } else { "FAILED" }
}

/// The end of a check of several files: complete, or an error counting the files that
/// failed (each already named on its line).
pub fn all_passed(failures: usize) -> Result<Outcome> {
    if failures > 0 {
        bail!("{failures} problem(s) failed their checks");
    }
    Ok(Outcome::Complete)
}
