//! The ab-initio stage of the 3-RPR sub-problems (docs/theory.md §8.1): the
//! [`AbInitioProblem`] instance of [`super::ab_initio_stage`] for a [`LagrangeProblem`],
//! the generic counts of docs/theory.md §6 ([`expected_count`]) and the stored files of
//! `supplementary/start/PLATFORM-BASE-SUBPROBLEM.json`.
//!
//! Every sub-problem's generic count is known, so reaching it with distinct nonsingular
//! solutions is the certificate (the trace test is not run); further start pairs cover
//! the reducible solution varieties of the rigid/rigid problems.

use super::start_file::StartSolutions;
use crate::homotopy::{MonodromyOptions, PrecisionOptions, TrackerOptions};
use crate::metric::Part;
use crate::problem::{LagrangeProblem, ProblemId, Stratum, SubProblem};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

pub use super::ab_initio_stage::{
    AbInitioError, AbInitioOptions, AbInitioProblem, MAX_STORED_RESIDUAL, NONSINGULAR_THRESHOLD,
    Polish, VERIFIED_GENERIC_COUNT, Verification, smallest_relative_singular_value,
};

/// Default seed of the ab-initio stage (the stored files were made with it).
pub const DEFAULT_SEED: u64 = 20_260_101;

/// Generic number of finite critical points (docs/theory.md §6 table; the counts of
/// sub-problems whose counts are not in the text of Kapilavai and Nawratil available to us
/// (their Tables 8–9) were measured by this stage and are
/// asserted here). `None` where no count is known.
pub fn expected_count(id: ProblemId) -> Option<usize> {
    let rigid = [id.metric.platform, id.metric.base]
        .iter()
        .filter(|p| **p == Part::Rigid)
        .count();
    match id.subproblem {
        SubProblem::Singularity => Some([50, 80, 88][rigid]),
        SubProblem::CollinearPlatform | SubProblem::CollinearBase => {
            Some(if rigid == 1 { 8 } else { 2 })
        }
        // plate/plate: (w, t) and (−w, −t) give the same configuration: 2 configurations,
        // 4 solutions. With a rigid part: see ALL_COLLINEAR_RIGID.
        SubProblem::AllCollinear => Some([4, ALL_COLLINEAR_RIGID, 2 * ALL_COLLINEAR_RIGID][rigid]),
        SubProblem::CoincidentPlatform | SubProblem::CoincidentBase => MEASURED_COINCIDENT,
    }
}

/// Generic count of sub-problem `id` on `stratum` ([`Stratum`]): [`expected_count`] on
/// the generic stratum. With one rigid part on a line (`v = 0`) the singularity
/// sub-problem has [`SINGULARITY_ONE_RIGID_ON_A_LINE`] critical points instead of 80
/// (one rigid part) and [`SINGULARITY_RIGID_RIGID_ONE_ON_A_LINE`] instead of 88
/// (`rigid/rigid`). Measured, as the coincident-points counts: the seed stage of
/// `singdist curve` (from the generic start files, each count confirmed at two
/// independent seed points) finds them on designs with a base on a line and, by the
/// base–platform symmetry, with a platform on a line (`bars/rigid`, `plate/rigid`,
/// `rigid/bars`, `rigid/plate`: 72; `rigid/rigid`: 84), and monodromy at a random
/// complex point of the stratum saturates at the same counts: asked for 8 more (4 for
/// `rigid/rigid` with the base on a line), the ab-initio stage stopped at these after 40
/// loops in a row found nothing new, with its further start pairs too (the stored files of
/// `supplementary/start/*.collinear-*-anchors.json` stop at the counts). Other sub-problems: not
/// known (`None`; the ab-initio stage then certifies by the trace test). No count is
/// given for `rigid/rigid` with both parts on lines either, and no file is stored: a
/// design there settles on 42 points (from the generic files, two seed points), but
/// monodromy on that stratum stops at 40 at three source seeds (as on a platform
/// congruent with the base, 22 against a design's 24), so monodromy misses part of the
/// solution variety there and only the trace test could certify a file.
pub fn expected_count_on(id: ProblemId, stratum: Stratum) -> Option<usize> {
    if stratum.is_generic() {
        return expected_count(id);
    }
    let rigid = [id.metric.platform, id.metric.base]
        .iter()
        .filter(|p| **p == Part::Rigid)
        .count();
    let on_a_line = usize::from(stratum.collinear_base) + usize::from(stratum.collinear_platform);
    match (id.subproblem, rigid, on_a_line) {
        (SubProblem::Singularity, 1, 1) => Some(SINGULARITY_ONE_RIGID_ON_A_LINE),
        (SubProblem::Singularity, 2, 1) => Some(SINGULARITY_RIGID_RIGID_ONE_ON_A_LINE),
        _ => None,
    }
}

/// Critical points of the singularity sub-problem with one rigid part, on a line
/// ([`expected_count_on`]; 80 off the line).
pub const SINGULARITY_ONE_RIGID_ON_A_LINE: usize = 72;

/// Critical points of the `rigid/rigid` singularity sub-problem with one rigid part on
/// a line ([`expected_count_on`]; 88 off it).
pub const SINGULARITY_RIGID_RIGID_ONE_ON_A_LINE: usize = 84;

/// Generic count of the all-collinear sub-problem with one rigid part whose anchors
/// are collinear (`plate/rigid`, `rigid/plate`; docs/theory.md §5.3, parameterisation of
/// `problem::build::all_collinear_offsets`), per orientation of the platform for
/// `rigid/rigid`. Derivation (as the total-least-squares note of docs/theory.md §5.3):
/// with `n = E w` the line's normal, every displacement `x_k′ − x_k` splits into a normal
/// part `h − x_k·n` (`h = q·n`) and a tangential part `q·w + c_k − x_k·w`; the cost `D²`
/// is an isotropic PSD quadratic form in the displacements, so it is the sum of the same
/// form on both parts. Minimising over `h` leaves `nᵀ C n` (C a weighted 2×2 scatter
/// matrix); minimising over `q·w` and the free offsets (plate part, rigid platform's
/// shift) leaves a quadratic in `w` with a *linear* term (the fixed offsets `s₂`, `s₃`
/// of the rigid part do not vanish): `F(w) = wᵀ N w − 2 bᵀ w + c` on `w·w = 1`. Its
/// critical points solve `(N − ν I) w = b`, `w·w = 1`, i.e. the quartic secular
/// equation `bᵀ (N − ν I)⁻² b = 1`: 4 critical points, each a distinct configuration
/// (the rigid part orients `w`, so there is no `(w, t) ↔ (−w, −t)` pairing). For
/// `rigid/rigid` the two orientations `σ = ±1` of the platform on the base's line each
/// give 4: 8 in all. Measured by monodromy with a passed trace test (2 source seeds,
/// 4 each; for rigid/rigid the solution set is reducible — `σ` is constant on each
/// component — and the seeds 20260101 and 7 certified the `σ = −1` and `σ = +1`
/// components with 4 each; the ab-initio stage's extra start pairs collect both).
const ALL_COLLINEAR_RIGID: usize = 4;

/// Generic count of the coincident-points sub-problems (docs/theory.md §6 note:
/// measured). For a fixed coincidence point q the cost over the rigid part's rotation
/// angle θ has the form `A cos θ + B sin θ + C`, with exactly two critical angles;
/// monodromy finds 2 for both `bars/rigid:coincident-platform` and
/// `rigid/bars:coincident-base`.
const MEASURED_COINCIDENT: Option<usize> = Some(2);

impl Default for AbInitioOptions {
    fn default() -> Self {
        // Monodromy stops as soon as the generic count is reached; a source point that
        // stalls is abandoned for the next one (see compute_start_solutions).
        AbInitioOptions {
            seed: DEFAULT_SEED,
            monodromy: MonodromyOptions {
                max_stagnant_loops: 40,
                // A loop path that needs more than 300 extended-precision steps is
                // dropped (the next loops find its endpoint): `ab-initio --all` took
                // 71 s with the tracker's default budget of 1000, 60 s with 300.
                tracker: TrackerOptions {
                    precision: PrecisionOptions {
                        max_extended_steps: 300,
                        ..PrecisionOptions::default()
                    },
                    ..TrackerOptions::default()
                },
                ..MonodromyOptions::default()
            },
        }
    }
}

impl AbInitioProblem for LagrangeProblem {
    const SOURCE_ATTEMPTS: u64 = 8;
    const POLISH: Polish = Polish {
        steps: 8,
        keep_best: true,
    };
    const VERIFY_RETRACES: bool = true;

    /// `PLATFORM/BASE:SUBPROBLEM`, on a special stratum followed by `@STRATUM`.
    fn name(&self) -> String {
        match self.stratum().name() {
            None => self.id().name(),
            Some(stratum) => format!("{}@{stratum}", self.id().name()),
        }
    }
    fn metric_name(&self) -> String {
        self.id().metric.name()
    }
    fn subproblem_name(&self) -> String {
        self.id().subproblem.name().to_string()
    }
    fn file_stem(&self) -> String {
        self.stratum().file_stem(self.id())
    }
    /// The generic count of docs/theory.md §6 on the generic stratum, the measured one
    /// of [`expected_count_on`] on a special one.
    fn expected_count(&self) -> Option<usize> {
        expected_count_on(self.id(), self.stratum())
    }
    fn count_certificate(&self) -> String {
        if self.stratum().is_generic() {
            VERIFIED_GENERIC_COUNT.to_string()
        } else {
            "verified-count (the stratum's measured count of \
             singdist::pipeline::ab_initio::expected_count_on reached with distinct \
             nonsingular solutions)"
                .to_string()
        }
    }
    fn stratum(&self) -> Stratum {
        LagrangeProblem::stratum(self)
    }
}

/// Computes the generic start solutions of `problem`: up to eight source points (seeds
/// `seed, seed+1, …`), the first certified set ([`super::ab_initio_stage::compute_start_solutions`]).
pub fn compute_start_solutions(
    problem: &LagrangeProblem,
    options: &AbInitioOptions,
) -> Result<StartSolutions, AbInitioError> {
    super::ab_initio_stage::compute_start_solutions(problem, options)
}

/// Re-checks a start-solution file: its variables and parameters match the problem,
/// residuals, distinctness, nonsingularity and the count of docs/theory.md §6
/// ([`super::ab_initio_stage::verify`]).
pub fn verify(
    problem: &LagrangeProblem,
    file: &StartSolutions,
) -> Result<Verification, AbInitioError> {
    super::ab_initio_stage::verify(problem, file)
}

/// The embedded start-solution file of `id`, if the build had one.
pub fn embedded_start_solutions(id: ProblemId) -> Option<Result<StartSolutions, AbInitioError>> {
    embedded_start_solutions_on(id, Stratum::GENERIC)
}

/// The embedded start-solution file of `id` on `stratum`, if the build had one.
pub fn embedded_start_solutions_on(
    id: ProblemId,
    stratum: Stratum,
) -> Option<Result<StartSolutions, AbInitioError>> {
    super::ab_initio_stage::embedded_file(&stratum.file_stem(id), &id.name())
}

type Cache = Mutex<HashMap<String, Arc<StartSolutions>>>;

fn cache() -> &'static Cache {
    static CACHE: OnceLock<Cache> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// The generic start solutions of `id`: the embedded file when present, otherwise
/// computed now with the default options (and kept for the rest of the process).
pub fn start_solutions(id: ProblemId) -> Result<Arc<StartSolutions>, AbInitioError> {
    let found = start_solutions_on(id, Stratum::GENERIC)?;
    Ok(found.unwrap_or_else(|| unreachable!("the generic stratum computes a missing file")))
}

/// The start solutions of `id` on `stratum` (kept for the rest of the process): the
/// embedded file when present; otherwise, on the generic stratum, computed now with the
/// default options, and on a special stratum `None` (its problems fall back to the
/// generic stratum: computing a stratum's set takes a minute and more).
pub fn start_solutions_on(
    id: ProblemId,
    stratum: Stratum,
) -> Result<Option<Arc<StartSolutions>>, AbInitioError> {
    let key = stratum.file_stem(id);
    if let Some(found) = cache().lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return Ok(Some(found.clone()));
    }
    let solutions = match embedded_start_solutions_on(id, stratum) {
        Some(file) => file?,
        None if stratum.is_generic() => {
            compute_start_solutions(&LagrangeProblem::new(id)?, &AbInitioOptions::default())?
        }
        None => return Ok(None),
    };
    let solutions = Arc::new(solutions);
    cache()
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, solutions.clone());
    Ok(Some(solutions))
}
