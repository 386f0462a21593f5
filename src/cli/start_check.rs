//! Re-checking stored start-solution files, for `ab-initio --verify` (every 3-RPR and
//! 3-RRR file) and `rrr ab-initio --verify`: where a stored file is read from, one line
//! per file with its measures and verdict, and the verdict of the whole check.

use super::outcome::Outcome;
use anyhow::{Context, Result, bail};
use singdist::pipeline::ab_initio_stage::{AbInitioProblem, Verification, verify};
use singdist::pipeline::start_file::StartSolutions;
use singdist::problem::LagrangeProblem;
use singdist::problem::rrr::RrrProblem;
use std::path::Path;

/// A problem with a stored start file, and how its `--verify` line reads.
pub trait StoredProblem: AbInitioProblem {
    /// The line of a checked file.
    fn line(check: &Verification) -> String;
}

impl StoredProblem for LagrangeProblem {
    fn line(check: &Verification) -> String {
        format!(
            "{:<40} {} solutions (expected {}), max residual {:.1e}, min separation {:.1e}, trace {}: {}",
            check.problem,
            check.count,
            check
                .expected
                .map_or("unknown".to_string(), |e| e.to_string()),
            check.max_residual,
            check.min_separation,
            trace_text(check.trace_residual),
            verdict(check.passed)
        )
    }
}

impl StoredProblem for RrrProblem {
    fn line(check: &Verification) -> String {
        format!(
            "{}: {} solutions, max residual {:.2e}, min separation {:.2e}, min σ ratio {:.2e}: {}",
            check.problem,
            check.count,
            check.max_residual,
            check.min_separation,
            check.min_relative_singular_value,
            verdict(check.passed)
        )
    }
}

/// Re-checks `file` ([`verify`]: names, residuals, distinctness, nonsingularity, the
/// count or trace test where the mechanism has one, stored certificate) and prints its
/// line; `true` if it passes.
pub fn verify_stored_file<P: StoredProblem>(problem: &P, file: &StartSolutions) -> Result<bool> {
    let check = verify(problem, file)?;
    println!("{}", P::line(&check));
    Ok(check.passed)
}

/// Re-checks the stored start file of every problem: `dir/STEM.json` where it exists,
/// otherwise the copy embedded in the binary; a problem with neither gets a `MISSING`
/// line. Returns how many are missing or fail.
pub fn check_stored<P: StoredProblem>(dir: &Path, problems: &[P]) -> Result<usize> {
    let mut failures = 0;
    for problem in problems {
        let path = dir.join(format!("{}.json", problem.file_stem()));
        let passed = match read_stored(&path, problem)? {
            Some(file) => verify_stored_file(problem, &file)?,
            None => {
                println!("{:<40} MISSING ({})", problem.name(), path.display());
                false
            }
        };
        failures += usize::from(!passed);
    }
    Ok(failures)
}

/// The start-solution file at `path` if it exists, otherwise `problem`'s embedded
/// copy; `None` when there is neither. Errors name the file.
fn read_stored(path: &Path, problem: &impl StoredProblem) -> Result<Option<StartSolutions>> {
    if path.exists() {
        let text = std::fs::read_to_string(path).with_context(|| path.display().to_string())?;
        let file = serde_json::from_str(&text).with_context(|| path.display().to_string())?;
        return Ok(Some(file));
    }
    Ok(problem.embedded().transpose()?)
}

/// Writes `file` as `dir/STEM.json` of `problem` (`pretty`: indented JSON, as the 3-RPR
/// files are stored; otherwise one line, as the 3-RRR files are); `flag` names the
/// folder's option in errors.
pub fn write_start_file<P: AbInitioProblem>(
    flag: &str,
    dir: &Path,
    problem: &P,
    file: &StartSolutions,
    pretty: bool,
) -> Result<()> {
    let path = dir.join(format!("{}.json", problem.file_stem()));
    let text = if pretty {
        serde_json::to_string_pretty(file)
    } else {
        serde_json::to_string(file)
    }
    .context("serialising start solutions")?;
    super::output::write_file(flag, &path, text)
}

/// A trace residual as printed (`not run` when the test was not run).
pub fn trace_text(residual: Option<f64>) -> String {
    residual.map_or("not run".to_string(), |t| format!("{t:.1e}"))
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
