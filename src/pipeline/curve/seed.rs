//! Stage 1, the user homotopy: the generic start solutions tracked to the seed.

use super::*;
use crate::metric::Part;
use crate::pipeline::family::Family;
use crate::pipeline::sweep::{
    MonodromyLoops, ProjectiveTwin, SeedPolicy, SeedSolutions, completed_by_monodromy, first_run,
    seed_family, split_seeded, track_all_unless_steps_run_out,
};
use crate::problem::{equilateral, pedal};
use crate::system::CompiledSystem;

/// One sub-problem prepared at the seed.
pub struct SeededProblem {
    /// Which metric and sub-problem.
    pub id: ProblemId,
    /// The compiled Lagrange system, built for [`SeededProblem::design`].
    pub problem: LagrangeProblem,
    /// The design with its legs relabelled so that the rigid parts' reference anchors
    /// are well conditioned ([`Design::conditioned_labelling`]); every configuration
    /// of this sub-problem is in these labels.
    pub design: Design,
    /// Internal leg `i` is the user's leg `labels[i]`.
    pub labels: [usize; 3],
    /// This sub-problem's seed: the stage's common one ([`SeedStage::seed`]), or an
    /// independent one where the common one's finite count could not be confirmed
    /// (the seed stage of [`crate::pipeline::sweep`]).
    pub seed: SeedPoint,
    /// Its solutions at the seed (`p* = (K*, shape constants)` in the normalised
    /// frame) and its counts. The count is below the generic one only where an
    /// independent seed point confirmed it, or the projective twin ([`ChartTwin`])
    /// put every missing path on its hyperplane at infinity (the others are at
    /// infinity for this design's fixed rigid shapes, e.g. the leg-collapse points of
    /// Kapilavai and Nawratil, Thm 3 case 4 when base and platform have an equal
    /// corresponding angle), or where the shortfall is reported as a seed-stage
    /// [`PathFailure`].
    pub at_seed: SeedSolutions,
    /// The same sub-problem with multipliers in a random chart, where paths that end
    /// at infinity or are lost are checked once more ([`CurveOptions::twin_check`]).
    pub twin: Option<ChartTwin>,
    /// For a pose list, the first run of the seed route to its first pose, tracked in
    /// the seed stage ([`probe_seed_route`]).
    pub seed_route_probe: Option<SeedRouteProbe>,
    /// [`SeededProblem::problem`] with affine multipliers, built on first use where
    /// the tracked system uses [`Multipliers::Chart`] (certification works with the
    /// real system of affine multipliers).
    pub affine: std::sync::OnceLock<LagrangeProblem>,
}

impl SeededProblem {
    /// The Lagrange system with affine multipliers ([`Multipliers::Affine`]) in the
    /// tracked system's point coordinates: [`SeededProblem::problem`] itself, or its
    /// affine twin.
    pub fn affine_problem(&self) -> &LagrangeProblem {
        if self.problem.multipliers() == Multipliers::Affine {
            return &self.problem;
        }
        self.affine.get_or_init(|| {
            let representation = (self.problem.coordinates(), Multipliers::Affine);
            LagrangeProblem::new_on(self.id, representation, self.problem.stratum())
                .unwrap_or_else(|e| unreachable!("built once already with a chart: {e}"))
        })
    }

    /// A solution of [`SeededProblem::problem`] as one of
    /// [`SeededProblem::affine_problem`] (the same point, the multipliers affine).
    pub fn to_affine(&self, x: &[C64]) -> Vec<C64> {
        match self.problem.multipliers() {
            Multipliers::Affine => x.to_vec(),
            Multipliers::Chart => self
                .affine_problem()
                .from_cartesian(&self.problem.to_cartesian(x)),
        }
    }

    /// A configuration of this sub-problem's labelling in the user's labels.
    pub fn to_user_labels(&self, k: &[f64; 12]) -> [f64; 12] {
        let mut out = [0.0; 12];
        for (internal, &user) in self.labels.iter().enumerate() {
            for part in [0, 6] {
                out[part + 2 * user] = k[part + 2 * internal];
                out[part + 2 * user + 1] = k[part + 2 * internal + 1];
            }
        }
        out
    }
}

/// A sub-problem ready for the user homotopy: id, compiled system (and its twin),
/// its relabelled design and labels, source parameters, start solutions (in the
/// system's coordinates).
type PreparedProblem = (
    ProblemId,
    (LagrangeProblem, Option<ChartTwin>),
    (Design, [usize; 3]),
    Vec<C64>,
    Vec<Vec<C64>>,
);

/// A sub-problem's Lagrange system with affine multipliers and the same system with
/// homogeneous multipliers `[λ₀ : λ : μ]` in a random chart ([`Multipliers::Chart`],
/// the Fritz John form `λ₀ ∇D² − λ ∇C − Σ μ ∇g = 0`) as its projective twin: a
/// critical point with huge multipliers has a small `λ₀` there and a bounded path.
pub struct ChartTwin {
    affine: LagrangeProblem,
    chart: LagrangeProblem,
}

impl ChartTwin {
    /// The twin of `affine` (a system with [`Multipliers::Affine`]) for `design`.
    pub fn of(affine: &LagrangeProblem, design: &Design) -> Result<Self, ProblemError> {
        let chart = LagrangeProblem::for_design_on(
            affine.id(),
            design,
            (affine.coordinates(), Multipliers::Chart),
            affine.stratum(),
        )?;
        Ok(ChartTwin {
            affine: affine.clone(),
            chart,
        })
    }
}

impl ProjectiveTwin for ChartTwin {
    fn system(&self) -> &CompiledSystem {
        self.chart.evaluator()
    }

    fn lift(&self, x: &[C64]) -> Vec<C64> {
        self.chart.from_cartesian(&self.affine.to_cartesian(x))
    }

    fn lower(&self, y: &[C64]) -> Vec<C64> {
        self.affine.from_cartesian(&self.chart.to_cartesian(y))
    }
}

/// The output of the user homotopy: every sub-problem at the common seed.
pub struct SeedStage {
    /// The prepared sub-problems, in the order of [`Metric::all`] and
    /// [`subproblems_of`].
    pub problems: Vec<SeededProblem>,
    /// Sub-problems reported as not applicable for this design (docs/theory.md §5.3).
    pub not_applicable: Vec<String>,
    /// Sub-problems solved in closed form at every pose instead of by homotopy
    /// ([`crate::problem::pedal`], [`crate::problem::equilateral`]: where the critical
    /// points are not isolated), in the order of [`problem_ids`].
    pub closed_form: Vec<ProblemId>,
    /// For each of [`SeedStage::closed_form`], the sub-problem's Lagrange system when
    /// its closed form gives every critical point ([`pedal::critical_points`]) and the
    /// run is certified ([`CurveOptions::certify`]): what certifies them.
    pub closed_form_systems: Vec<Option<ClosedFormSystem>>,
    /// The seed on the complexified motion.
    pub seed: SeedPoint,
    /// The normalised frame of every parameter vector of the run.
    pub normalization: Normalization,
    /// The seed configuration `K*` (original frame).
    pub seed_configuration: [C64; 12],
    /// Paths lost in the user homotopy.
    pub failures: Vec<PathFailure>,
    /// What the generic route to the motion's first pose found per sub-problem where
    /// the first-pose probe (`probe_seed_counts`) ran it (by name): `(accounted paths,
    /// distinct finite points)`. The route does not depend on the seed, so the self-check's stage
    /// takes these instead of tracking it again.
    pub probes: BTreeMap<String, (usize, usize)>,
    /// Paths tracked in this stage.
    pub paths_tracked: usize,
}

/// The Lagrange system of a sub-problem solved in closed form, to certify the closed
/// form's critical points (Krawczyk's test) against the family's generic count.
pub struct ClosedFormSystem {
    /// The compiled Lagrange system (Cartesian; no rigid part, so the user's labels).
    pub problem: LagrangeProblem,
    /// The design (user's labels).
    pub design: Design,
    /// The generic number of critical points (the start file's count).
    pub generic_count: usize,
}

/// The seed of stage 1: a point of the complexified motion and a small complex
/// perturbation of all twelve (normalised) coordinates, so that the fixed real base
/// does not make the seed special. The perturbation fades linearly along every
/// seed → pose path.
#[derive(Clone, Debug, PartialEq)]
pub struct SeedPoint {
    /// Where on the complexified motion.
    pub point: MotionPoint,
    /// Added to the normalised seed configuration.
    pub perturbation: [C64; 12],
}

/// The seed (stage 1, see the module documentation): τ* with real part uniform on the
/// motion's range and imaginary part 0.1–0.3 × its width (at most 3), or for pose lists
/// the first pose plus a complex perturbation of size 0.3 (x, y scaled by the design's
/// length); perturbation of the normalised coordinates of size 0.05.
pub fn seed_point(design: &Design, motion: &Motion, seed: u64) -> SeedPoint {
    seed_point_in_stream(design, motion, seed, 0x5eed)
}

/// [`seed_point`] drawn from random stream `stream` of `seed` (independent seed
/// points of the same run).
fn seed_point_in_stream(design: &Design, motion: &Motion, seed: u64, stream: u64) -> SeedPoint {
    let mut rng = random::stream(seed, stream);
    let [lo, hi] = motion.tau_range();
    let width = (hi - lo).max(1e-3);
    let point = match motion {
        Motion::Analytic(_) => MotionPoint::Tau(C64::new(
            random::uniform(&mut rng, lo, hi),
            random::uniform(&mut rng, 0.1, 0.3) * width.min(3.0),
        )),
        Motion::Poses(_) => {
            let first = motion.pose(lo).unwrap_or_else(|| Pose::new(0.0, 0.0, 0.0));
            let scale = design.length_scale();
            MotionPoint::Pose([
                C64::new(first.x, 0.0) + random::complex_normal(&mut rng) * (0.3 * scale),
                C64::new(first.y, 0.0) + random::complex_normal(&mut rng) * (0.3 * scale),
                C64::new(first.phi, 0.0) + random::complex_normal(&mut rng) * 0.3,
            ])
        }
    };
    let perturbation = std::array::from_fn(|_| random::complex_normal(&mut rng) * 0.05);
    SeedPoint {
        point,
        perturbation,
    }
}

/// Independent seed points a sub-problem may use (the stage's common one first) to
/// confirm a finite count below the generic one.
pub const SEED_POINTS: usize = 5;

/// The parameters a 3-RPR motion moves: the twelve coordinates of the configuration
/// `K` (the rest are a rigid part's shape constants, fixed by the design).
const MOVING_PARAMETERS: usize = 12;

/// [`SeedPolicy::monodromy_stagnant_loops`] of the curve's seed stages: a seed point's
/// first run is completed by monodromy until two loops in a row add nothing.
pub const SEED_MONODROMY_STAGNANT_LOOPS: usize = 2;

/// The normalised configuration `N(K(seed)) + δ` of a seed point.
fn seed_configuration(
    design: &Design,
    motion: &Motion,
    seed: &SeedPoint,
    normalization: Normalization,
) -> [C64; 12] {
    let at_seed = MotionPath::new(
        design,
        motion,
        vec![seed.point, seed.point],
        seed.perturbation,
        normalization,
        Vec::new(),
    );
    let mut k = [C64::new(0.0, 0.0); 12];
    at_seed.point(C64::new(0.0, 0.0), &mut k);
    k
}

/// The prepared sub-problems of a design as a [`Family`]: seed point 0 is the
/// stage's common one, the others are drawn per sub-problem, each with its
/// normalised seed configuration `N(K(seed)) + δ` and the design's shape constants.
struct SeedFamily<'a> {
    motion: &'a Motion,
    normalization: Normalization,
    common: &'a SeedPoint,
    seed: u64,
    prepared: &'a [PreparedProblem],
}

impl Family for SeedFamily<'_> {
    type Seed = SeedPoint;

    fn problems(&self) -> usize {
        self.prepared.len()
    }

    fn name(&self, problem: usize) -> String {
        self.prepared[problem].0.name()
    }

    fn system(&self, problem: usize) -> &CompiledSystem {
        self.prepared[problem].1.0.evaluator()
    }

    fn twin(&self, problem: usize) -> Option<&dyn ProjectiveTwin> {
        let twin = self.prepared[problem].1.1.as_ref()?;
        Some(twin)
    }

    fn generic_start(&self, problem: usize) -> (&[C64], &[Vec<C64>]) {
        let (_, _, _, source, starts) = &self.prepared[problem];
        (source, starts)
    }

    fn seed(&self, problem: usize, point: usize) -> (SeedPoint, Vec<C64>) {
        let (_, (lagrange, _), (design, _), _, _) = &self.prepared[problem];
        let seed = if point == 0 {
            self.common.clone()
        } else {
            let stream = 0x5eed_0000_0000 + ((problem as u64) << 8) + point as u64;
            seed_point_in_stream(design, self.motion, self.seed, stream)
        };
        let k_star = seed_configuration(design, self.motion, &seed, self.normalization);
        let parameters = normalized_parameters(lagrange, design, &k_star, self.normalization);
        (seed, parameters)
    }

    fn moving_parameters(&self) -> usize {
        MOVING_PARAMETERS
    }
}

/// Stage 1, the user homotopy: builds every needed sub-problem, fetches its start
/// solutions from `provider` and tracks them to the seed (in parallel), confirming
/// every count below the generic one at an independent seed point
/// (the seed stage of [`crate::pipeline::sweep`]).
pub fn seed_stage(
    design: &Design,
    motion: &Motion,
    metrics: &[Metric],
    options: &CurveOptions,
    provider: StartProvider<'_>,
) -> Result<SeedStage, PipelineError> {
    seed_stage_with_probes(design, motion, metrics, options, provider, &BTreeMap::new())
}

/// [`seed_stage`] with the first-pose probes another stage of the same run already
/// ran ([`SeedStage::probes`]): the same route, so the same result.
pub(super) fn seed_stage_with_probes(
    design: &Design,
    motion: &Motion,
    metrics: &[Metric],
    options: &CurveOptions,
    provider: StartProvider<'_>,
    known_probes: &BTreeMap<String, (usize, usize)>,
) -> Result<SeedStage, PipelineError> {
    if metrics.is_empty() {
        return Err(PipelineError::NoMetrics);
    }
    motion
        .validate()
        .map_err(|e| PipelineError::Motion(e.to_string()))?;
    let seed = seed_point(design, motion, options.seed);
    let first_pose = motion
        .pose(motion.tau_range()[0])
        .unwrap_or_else(|| Pose::new(0.0, 0.0, 0.0));
    let normalization = Normalization::of(&to_real(&design.configuration(first_pose).to_array()));
    let k_star = seed_configuration(design, motion, &seed, normalization);
    let k_first = design.configuration(first_pose).to_array();
    let (closed_form, tracked_ids): (Vec<ProblemId>, Vec<ProblemId>) = problem_ids(metrics)
        .into_iter()
        .partition(|&id| pedal::has_closed_form(id) || equilateral::on_circle(id, &k_first));
    // Building and compiling the systems in parallel too (about 60 ms in sequence).
    let built: Vec<Result<Option<PreparedProblem>, PipelineError>> = tracked_ids
        .clone()
        .into_par_iter()
        .map(|id| {
            let labels = design.conditioned_labelling(
                id.metric.base == Part::Rigid,
                id.metric.platform == Part::Rigid,
            );
            let design = design.relabelled(labels);
            // On the smallest stratum containing the design that has a start file (a
            // rigid part on a line: the paths the generic family sends to infinity there
            // are gone), else on the generic one.
            let special = Stratum::of(id, &design)
                .containing()
                .into_iter()
                .find_map(|stratum| provider(id, stratum).ok().map(|file| (stratum, file)));
            let stratum = special.as_ref().map_or(Stratum::GENERIC, |(s, _)| *s);
            let representation = (options.coordinates, options.multipliers);
            let problem = match LagrangeProblem::for_design_on(id, &design, representation, stratum)
            {
                Ok(p) => p,
                Err(ProblemError::NotApplicable { .. }) => return Ok(None),
                Err(e) => return Err(e.into()),
            };
            let start = match special {
                Some((_, start)) => start,
                None => provider(id, Stratum::GENERIC).map_err(|message| {
                    PipelineError::StartSolutions {
                        problem: id.name(),
                        message,
                    }
                })?,
            };
            let source = start
                .source_for(problem.parameter_names(), problem.stored_solution_len())
                .map_err(|message| PipelineError::StartSolutions {
                    problem: id.name(),
                    message,
                })?;
            let starts: Vec<Vec<C64>> = start
                .solutions
                .iter()
                .map(|x| problem.from_cartesian(x))
                .collect();
            let twin = if options.twin_check && options.multipliers == Multipliers::Affine {
                Some(ChartTwin::of(&problem, &design)?)
            } else {
                None
            };
            Ok(Some((
                id,
                (problem, twin),
                (design, labels),
                source,
                starts,
            )))
        })
        .collect();
    let mut prepared = Vec::new();
    let mut not_applicable = Vec::new();
    for (id, result) in tracked_ids.into_iter().zip(built) {
        match result? {
            Some(problem) => prepared.push(problem),
            None => not_applicable.push(id.name()),
        }
    }
    let family = SeedFamily {
        motion,
        normalization,
        common: &seed,
        seed: options.seed,
        prepared: &prepared,
    };
    let trackers = (&options.seed_tracker, &options.retry_tracker);
    let policy = SeedPolicy {
        monodromy_stagnant_loops: SEED_MONODROMY_STAGNANT_LOOPS,
        ..SeedPolicy::new(
            SEED_POINTS,
            options.seed,
            trackers,
            options.seed_retry_attempts,
        )
    };
    let (seeded, failures, paths_tracked) = split_seeded(seed_family(&family, &policy));
    let mut problems: Vec<SeededProblem> = prepared
        .into_iter()
        .zip(seeded)
        .map(
            |((id, (problem, twin), (design, labels), source, starts), seeded)| {
                let (seed, at_seed) = SeedSolutions::new(seeded, (source, starts));
                SeededProblem {
                    affine: std::sync::OnceLock::new(),
                    seed_route_probe: None,
                    id,
                    problem,
                    twin,
                    design,
                    labels,
                    seed,
                    at_seed,
                }
            },
        )
        .collect();
    let (probed, probes) = probe_seed_counts(
        &mut problems,
        (first_pose, normalization),
        options,
        known_probes,
    );
    let route_probes: Vec<Option<SeedRouteProbe>> = problems
        .par_iter()
        .map(|seeded| probe_seed_route(seeded, motion, normalization, options))
        .collect();
    let mut route_probed = 0;
    for (seeded, probe) in problems.iter_mut().zip(route_probes) {
        if probe.is_some() {
            route_probed += seeded.at_seed.solutions.len();
        }
        seeded.seed_route_probe = probe;
    }
    let mut failures = failures;
    settle_seed_failures(&problems, &mut failures);
    let closed_form_systems = closed_form
        .iter()
        .map(|&id| {
            if !(options.certify && pedal::has_closed_form(id)) {
                return None;
            }
            let problem = LagrangeProblem::new(id).ok()?;
            let generic_count = provider(id, Stratum::GENERIC).ok()?.solutions.len();
            Some(ClosedFormSystem {
                problem,
                design: *design,
                generic_count,
            })
        })
        .collect();
    Ok(SeedStage {
        problems,
        not_applicable,
        closed_form,
        closed_form_systems,
        seed,
        normalization,
        seed_configuration: normalization.restore(&k_star),
        failures,
        probes,
        paths_tracked: paths_tracked + probed + route_probed,
    })
}

/// Rigid parts whose shortest edge is below this fraction of their longest get the
/// seed-route probe of [`probe_seed_route`].
const CLOSE_ANCHORS: f64 = 1e-2;

/// Whether a rigid part of `id`'s metric has two anchors closer than
/// [`CLOSE_ANCHORS`] times its longest edge (coincident ones included).
pub(super) fn close_rigid_anchors(id: ProblemId, design: &Design) -> bool {
    (id.metric.base == Part::Rigid && design.edge_ratio(false) < CLOSE_ANCHORS)
        || (id.metric.platform == Part::Rigid && design.edge_ratio(true) < CLOSE_ANCHORS)
}

/// The first run of the seed route to a pose list's first pose ([`probe_seed_route`]).
pub struct SeedRouteProbe {
    /// The pose.
    pub target: MotionPoint,
    /// The paths of the run, or `None` where one of them ran out of steps.
    pub first_run: Option<Vec<PathResult>>,
}

impl SeedRouteProbe {
    /// Whether a path of the run ran out of steps.
    pub fn ran_out_of_steps(&self) -> bool {
        self.first_run.is_none()
    }
}

/// For a pose list, the first run of a pose's seed route (see `track_problem`) to its
/// first pose, which the pose then takes as its own. A pose list's poses are solved
/// from the seed wherever they are far apart, and where this run runs out of steps,
/// every pose takes the generic route first; where the generic route does not
/// complete a pose, the seed route still follows with its re-runs and detours. A
/// rigid part's shape constants stay those of the design along the whole seed route,
/// so where two of its anchors are close the critical points come in clusters (pairs
/// 10⁻¹⁰ apart relative to their norm, on two base anchors 10⁻⁴ apart) all along it,
/// not only at its end, and a route that runs out of steps at one pose runs out at
/// the others: on that design the `bars/rigid` and `plate/rigid` seed routes ran out
/// at 19 of the 20 poses of an 8-pose run and its self-check, each after about 30 ms,
/// before the generic route solved the pose. Only for designs with such close anchors
/// ([`close_rigid_anchors`]): elsewhere the seed route completes the poses, and the
/// probe would only move the first pose's run from the poses' parallel stage into the
/// seed stage. `None` also for
/// analytic motions (whose poses are solved from their neighbours, a few from the
/// seed), for a list of one pose (a seed stage at a pose, see [`super::local_seed`],
/// whose counts may be all it is for) and where the seed has fewer solutions than the
/// expected count (the generic route comes first anyway).
fn probe_seed_route(
    seeded: &SeededProblem,
    motion: &Motion,
    normalization: Normalization,
    options: &CurveOptions,
) -> Option<SeedRouteProbe> {
    let Motion::Poses(list) = motion else {
        return None;
    };
    if list.poses.len() < 2 || !close_rigid_anchors(seeded.id, &seeded.design) {
        return None;
    }
    let first = SampledPose {
        tau: 0.0,
        pose: *list.poses.first()?,
    };
    let starts = &seeded.at_seed.solutions;
    if starts.len() < seeded.at_seed.start_count {
        return None;
    }
    let design = &seeded.design;
    let k = normalization.apply(&to_real(&design.configuration(first.pose).to_array()));
    let parameters = normalized_parameters(&seeded.problem, design, &k, normalization);
    let target = MotionPoint::target(motion, &first);
    let route = MotionPath::new(
        design,
        motion,
        vec![seeded.seed.point, target],
        seeded.seed.perturbation,
        normalization,
        parameters[12..].to_vec(),
    );
    let homotopy = PathParameterHomotopy::new(seeded.problem.evaluator(), route);
    let first_run = track_all_unless_steps_run_out(&homotopy, starts, &options.tracker);
    Some(SeedRouteProbe { target, first_run })
}

/// Tests every seed count below the generic one at a real pose (the motion's first;
/// normalised frame `normalization`): the start file's generic
/// solutions tracked straight to it ([`generic_route`]). Two seed points agreeing on a
/// count do not prove it: on two base anchors 1e-4 apart, `bars/rigid` had 79 of 80
/// at two seed points while this route reached 80 distinct finite critical points at
/// every pose it was run at. Where the route accounts for every path and reaches more
/// distinct finite points than the seed count, up to the generic count, the seed count
/// is refuted: the sub-problem's expected count becomes that number, so that no pose
/// is complete with fewer (the seed route, short of it, hands the pose to the generic
/// route, and what neither completes is reported lost). Returns the paths tracked.
pub(super) fn probe_seed_counts(
    problems: &mut [SeededProblem],
    (pose, normalization): (Pose, Normalization),
    options: &CurveOptions,
    known: &BTreeMap<String, (usize, usize)>,
) -> (usize, BTreeMap<String, (usize, usize)>) {
    // Only a route that accounts for every path refutes: its detours, which only
    // matter where it loses paths, are left out. It runs straight in the self-check's
    // stage too: it can only raise a count, never lower one, and bending it there cost
    // 16 % of the built-in example's run (0.95 → 1.10 s) for no independence of the
    // results the check compares (its poses' generic routes stay bent).
    let without_detours = CurveOptions {
        seed_retry_attempts: 0,
        generic_route_bend: false,
        ..options.clone()
    };
    type Probe = (usize, usize, Option<(usize, usize)>);
    let probes: Vec<Probe> = problems
        .par_iter()
        .enumerate()
        .map(|(index, seeded)| {
            if seeded.at_seed.start_count >= seeded.at_seed.generic_count {
                return (seeded.at_seed.start_count, 0, None);
            }
            let (accounted, distinct, tracked) = match known.get(&seeded.id.name()) {
                Some(&(accounted, distinct)) => (accounted, distinct, 0),
                None => {
                    let design = &seeded.design;
                    let k = normalization.apply(&to_real(&design.configuration(pose).to_array()));
                    let parameters =
                        normalized_parameters(&seeded.problem, design, &k, normalization);
                    let stream = PROBE_STREAM | index as u64;
                    probe_at(seeded, &parameters, stream, (options, &without_detours))
                }
            };
            let refuted =
                accounted == seeded.at_seed.generic_count && distinct > seeded.at_seed.start_count;
            let count = if refuted {
                distinct
            } else {
                seeded.at_seed.start_count
            };
            (count, tracked, Some((accounted, distinct)))
        })
        .collect();
    let mut tracked = 0;
    let mut found = BTreeMap::new();
    for (seeded, (count, paths, probe)) in problems.iter_mut().zip(probes) {
        seeded.at_seed.start_count = count;
        tracked += paths;
        if let Some(probe) = probe {
            found.insert(seeded.id.name(), probe);
        }
    }
    (tracked, found)
}

/// Drops the seed-stage failures (`pose_index: None`) of sub-problems whose expected
/// count is the generic one after [`probe_seed_counts`]: a seed short of it (seed
/// points that disagreed, e.g. `[79, 72, 78, 78, 78]` of 80 on two base anchors 10⁻⁴
/// apart) then decides nothing at any pose. No parameter has more isolated critical
/// points than the generic count, every pose is measured against it, and a pose whose
/// seed route falls short goes the generic route first; what a pose cannot complete
/// is reported at that pose. A seed failure of a sub-problem whose count stays below
/// the generic one stays: poses are complete with that count.
pub(super) fn settle_seed_failures(problems: &[SeededProblem], failures: &mut Vec<PathFailure>) {
    failures.retain(|f| {
        f.pose_index.is_some()
            || !problems.iter().any(|p| {
                p.id.name() == f.problem && p.at_seed.start_count == p.at_seed.generic_count
            })
    });
}

/// Makes the run's stage and the self-check's stage expect the same count per
/// sub-problem: the larger of the two, and where they disagree, the larger with the
/// count of a third seed stage at the motion's first pose (`probe_at_pose(id)`, the
/// seed count of a stage for that sub-problem's metric alone, next to the pose; `None`
/// where it lost paths itself). Each stage confirms a count below the generic one only
/// by two of its own seed points agreeing (or its projective twin), and on two anchors
/// of a rigid part 10⁻⁴ apart both can fall short: `bars/rigid` had 78 of 80
/// confirmed at two seed points of one seed while the other seed's stage reached 80;
/// on two platform anchors 10⁻⁴ apart the stages had 85 and 86 `rigid/rigid` points
/// where a stage at the first pose reached all 88 (at a real pose an odd count of a
/// sub-problem's critical points, which come in conjugate pairs besides the real ones,
/// cannot be complete). No parameter has more isolated critical points than a count
/// some seed reached (each is a set of distinct finite solutions at one parameter,
/// and the family's finite count is generically constant), so the largest count
/// refutes the smaller; a stage short of it sends its poses the generic route first
/// and reports what that cannot complete. Seed-stage failures that the raised count
/// settles are dropped ([`settle_seed_failures`]).
pub(super) fn reconcile_seed_counts(
    run: &mut SeedStage,
    check: &mut SeedStage,
    probe_at_pose: impl Fn(ProblemId) -> Option<usize> + Sync,
) {
    let counts: Vec<Option<usize>> = run
        .problems
        .par_iter()
        .map(|problem| {
            let other = check.problems.iter().find(|p| p.id == problem.id)?;
            let mut count = problem.at_seed.start_count.max(other.at_seed.start_count);
            if problem.at_seed.start_count != other.at_seed.start_count
                && count < problem.at_seed.generic_count
            {
                count = count.max(probe_at_pose(problem.id).unwrap_or(0));
            }
            Some(count.min(problem.at_seed.generic_count))
        })
        .collect();
    for (problem, count) in run.problems.iter_mut().zip(counts) {
        let Some(count) = count else {
            continue;
        };
        problem.at_seed.start_count = count;
        if let Some(other) = check.problems.iter_mut().find(|p| p.id == problem.id) {
            other.at_seed.start_count = count;
        }
    }
    for stage in [run, check] {
        settle_seed_failures(&stage.problems, &mut stage.failures);
    }
}

/// The probe of [`probe_seed_counts`] at `parameters` (a real pose): paths accounted
/// for, distinct finite solutions, paths tracked. Where the seed count was settled by
/// monodromy and no path of the first run to the pose fails, that run completed by
/// monodromy at the pose ([`completed_by_monodromy`]); a set the loops completed counts
/// as settled, as a route that accounts for every path does. Elsewhere, or where the
/// loops give up, the generic route with its re-runs and projective twin
/// (`without_detours`).
fn probe_at(
    seeded: &SeededProblem,
    parameters: &[C64],
    stream: u64,
    (options, without_detours): (&CurveOptions, &CurveOptions),
) -> (usize, usize, usize) {
    let mut tracked = 0;
    if seeded.at_seed.completed_by_monodromy {
        let (source, starts) = &seeded.at_seed.generic_start;
        let system = seeded.problem.evaluator();
        let paths = first_run(system, (source, starts), parameters, &options.tracker);
        tracked += paths.len();
        let failed = paths
            .iter()
            .any(|p| matches!(p.status, crate::homotopy::PathStatus::Failed(_)));
        let probe = (!failed).then(|| {
            completed_by_monodromy(
                system,
                &paths,
                (parameters, MOVING_PARAMETERS),
                MonodromyLoops {
                    stagnant: SEED_MONODROMY_STAGNANT_LOOPS,
                    at_least: 0,
                    unless_reached: None,
                },
                &options.tracker,
                &mut random::stream(options.seed, stream ^ PROBE_MONODROMY),
            )
        });
        if let Some(probe) = probe {
            tracked += probe.tracked;
            if !probe.abandoned {
                return (seeded.at_seed.generic_count, probe.solutions.len(), tracked);
            }
        }
    }
    let probe = generic_route(seeded, parameters, stream, without_detours);
    (
        probe.accounted,
        probe.endpoints.len(),
        tracked + probe.tracked,
    )
}

/// Random stream tag of [`probe_at`]'s monodromy loops.
const PROBE_MONODROMY: u64 = 0x6d6f_6e6f;

/// Random stream of [`probe_seed_counts`] (ored with the sub-problem's index): apart
/// from every pose's streams, which hold the pose index + 1 in the upper half.
const PROBE_STREAM: u64 = 0xffff_0000_0000_0000;
