//! Re-checking stored start-solution files, for `ab-initio --verify` (every 3-RPR and
//! 3-RRR file) and `rrr ab-initio --verify`: where a stored file is read from, one line
//! per file with its measures and verdict, and the verdict of the whole check.

use super::outcome::Outcome;
use anyhow::{Context, Result, bail};
use singdist::pipeline::ab_initio::{self, embedded_start_solutions};
use singdist::pipeline::rrr_ab_initio::{embedded_rrr_start_solutions, verify_rrr_start_solutions};
use singdist::pipeline::start_file::StartSolutions;
use singdist::problem::LagrangeProblem;
use singdist::problem::rrr::RrrProblem;
use std::path::Path;

/// A problem with a stored start file.
pub trait StoredProblem {
    /// Its name in the output (`bars/rigid:collinear-platform`, `rrr:leg1`).
    fn name(&self) -> String;
    /// The file's name in the start folder without `.json`.
    fn file_stem(&self) -> String;
    /// The copy embedded in the binary, if the build had one.
    fn embedded(&self) -> Option<Result<StartSolutions>>;
    /// Re-checks `file` and prints its line; `true` if it passes.
    fn verify(&self, file: &StartSolutions) -> Result<bool>;
}

impl StoredProblem for LagrangeProblem {
    fn name(&self) -> String {
        self.id().name()
    }
    fn file_stem(&self) -> String {
        self.id().file_stem()
    }
    fn embedded(&self) -> Option<Result<StartSolutions>> {
        embedded_start_solutions(self.id()).map(|file| file.map_err(Into::into))
    }
    fn verify(&self, file: &StartSolutions) -> Result<bool> {
        verify_rpr(self, file)
    }
}

impl StoredProblem for RrrProblem {
    fn name(&self) -> String {
        self.kind().name()
    }
    fn file_stem(&self) -> String {
        self.kind().file_stem()
    }
    fn embedded(&self) -> Option<Result<StartSolutions>> {
        embedded_rrr_start_solutions(self.kind()).map(|file| file.map_err(Into::into))
    }
    fn verify(&self, file: &StartSolutions) -> Result<bool> {
        verify_rrr(self, file)
    }
}

/// Re-checks the stored start file of every problem: `dir/STEM.json` where it exists,
/// otherwise the copy embedded in the binary; a problem with neither gets a `MISSING`
/// line. Returns how many are missing or fail.
pub fn check_stored<P: StoredProblem>(dir: &Path, problems: &[P]) -> Result<usize> {
    let mut failures = 0;
    for problem in problems {
        let path = dir.join(format!("{}.json", problem.file_stem()));
        let passed = match read_stored(&path, problem)? {
            Some(file) => problem.verify(&file)?,
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
    problem.embedded().transpose()
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
