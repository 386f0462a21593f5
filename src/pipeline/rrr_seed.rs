//! Stage 1 of the 3-RRR curve, the user homotopy (Kapilavai and Nawratil, Eqs. 65–66):
//! the normalised frame of the run, the seed configuration `K*`, and the generic start
//! solutions tracked to it, with the bookkeeping that never lets a count exceed the
//! generic one.
//!
//! - **Frame** ([`RrrFrame`]): every parameter vector lives in the similarity frame
//!   `K ↦ (K − c)/s`, `c` the centroid of the nine points of the motion's first
//!   configuration and `s` their root-mean-square distance from it. The metric `D²` is a
//!   sum of squared point distances (it scales by `s²` and is translation invariant), the
//!   parallel polynomial (a 3×3 determinant of line coordinates) and the leg polynomials
//!   are translation invariant and homogeneous, so the critical points at `K` are the
//!   images under the inverse similarity of those at the normalised configuration, and
//!   distances scale by `s`. The run is then the same, up to rounding, for a design and
//!   for its copy scaled by any factor.
//! - **Seed** ([`seed_configuration`]): the trajectory's configuration at a random
//!   complex `τ*` (complex inverse kinematics), normalised, plus a random complex
//!   perturbation of all 18 coordinates of size 0.05 (for pose lists: the first pose's
//!   configuration plus a perturbation of size 0.3).
//! - **Counts**: the start file holds the generic number `G` of finite critical points;
//!   by coefficient-parameter theory no parameter of the family has more isolated ones
//!   (Morgan and Sommese, *Coefficient-parameter polynomial continuation*, Appl. Math.
//!   Comput. 29, 1989). The distinct finite endpoints at the seed are therefore kept
//!   only up to `G`; a count below `G` counts only when an independent seed point
//!   (another `τ*` and perturbation, reached along another route) finds exactly as many,
//!   otherwise the shortfall is a seed-stage failure.

use super::curve::{Retried, TrackingPlan, split_seed_results, track_with_retries};
use super::rrr_ab_initio::RrrAbInitioError;
use super::rrr_curve::{RrrCurveError, RrrCurveOptions, RrrPathFailure};
use super::start_file::StartSolutions;
use crate::C64;
use crate::homotopy::{PolylinePath, same_point};
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrTrajectory};
use crate::problem::rrr::{RrrProblem, RrrSubProblem};
use crate::random;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The similarity `K ↦ (K − c)/s` of the run's normalised frame (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RrrFrame {
    center: [f64; 2],
    scale: f64,
}

impl RrrFrame {
    /// The frame of configuration `k`: `c` the centroid of its nine points, `s` their
    /// root-mean-square distance from `c` (1 if that is not a positive number).
    pub fn of(k: &[f64; CONFIGURATION_LEN]) -> Self {
        let mut center = [0.0; 2];
        for (i, v) in k.iter().enumerate() {
            center[i % 2] += v / 9.0;
        }
        let spread = k
            .iter()
            .enumerate()
            .map(|(i, v)| (v - center[i % 2]).powi(2))
            .sum::<f64>()
            / 9.0;
        let scale = spread.sqrt();
        RrrFrame {
            center,
            scale: if scale.is_finite() && scale > 0.0 {
                scale
            } else {
                1.0
            },
        }
    }

    /// The scale `s` (lengths in the frame are lengths of `K` divided by `s`).
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// `(K − c)/s`, complex.
    pub fn apply_complex(&self, k: &[C64; CONFIGURATION_LEN]) -> [C64; CONFIGURATION_LEN] {
        std::array::from_fn(|i| (k[i] - self.center[i % 2]) / self.scale)
    }

    /// `(K − c)/s`.
    pub fn apply(&self, k: &[f64; CONFIGURATION_LEN]) -> [f64; CONFIGURATION_LEN] {
        std::array::from_fn(|i| (k[i] - self.center[i % 2]) / self.scale)
    }

    /// `s·K + c`.
    pub fn restore(&self, k: &[f64; CONFIGURATION_LEN]) -> [f64; CONFIGURATION_LEN] {
        std::array::from_fn(|i| k[i] * self.scale + self.center[i % 2])
    }
}

/// The frame of a trajectory: that of its configuration at the start of the motion.
pub fn trajectory_frame(trajectory: &RrrTrajectory) -> Result<RrrFrame, RrrCurveError> {
    Ok(RrrFrame::of(&first_configuration(trajectory)?))
}

/// The configuration at the start of the motion (an error of pose 0 if it is unreachable).
fn first_configuration(
    trajectory: &RrrTrajectory,
) -> Result<[f64; CONFIGURATION_LEN], RrrCurveError> {
    let lo = trajectory.motion().tau_range()[0];
    trajectory
        .configuration(lo)
        .map(|k| k.to_array())
        .map_err(|e| RrrCurveError::Pose {
            index: 0,
            tau: lo,
            message: e.to_string(),
        })
}

/// One sub-problem prepared at the seed.
pub struct RrrSeededProblem {
    /// The compiled system.
    pub problem: RrrProblem,
    /// Seed parameters `K*` (normalised frame).
    pub seed_parameters: Vec<C64>,
    /// Distinct finite solutions at the seed, at most [`RrrSeededProblem::generic_count`].
    pub seed_solutions: Vec<Vec<C64>>,
    /// The generic number of finite critical points (the start file's count): no
    /// parameter of the family has more isolated ones.
    pub generic_count: usize,
    /// Number of paths tracked from the seed to every pose: the seed's distinct finite
    /// solutions. Below [`RrrSeededProblem::generic_count`] only when an independent seed
    /// point confirmed the count, or with a seed-stage failure reporting the shortfall.
    pub start_count: usize,
}

/// Every sub-problem at the common seed.
pub struct RrrSeedStage {
    /// Parallel, leg 1, leg 2, leg 3.
    pub problems: Vec<RrrSeededProblem>,
    /// Complex motion parameter of the common seed (`None` for pose lists).
    pub tau_star: Option<C64>,
    /// The run's normalised frame.
    pub frame: RrrFrame,
    /// Paths lost in the seed stage.
    pub failures: Vec<RrrPathFailure>,
    /// Paths tracked in the seed stage.
    pub paths_tracked: usize,
}

/// Independent seed points a sub-problem may use (the common one first) to confirm a
/// finite count below the generic one.
pub const SEED_POINTS: usize = 4;

/// Random complex detour point near `target`: `target + ε·ξ`, ξ standard complex normal
/// per coordinate, `ε = 0.1·(1 + ‖target‖∞)`.
fn detour_point(target: &[C64], rng: &mut random::SeededRng) -> Vec<C64> {
    let scale = 0.1 * (1.0 + target.iter().fold(0.0f64, |m, v| m.max(v.norm())));
    target
        .iter()
        .map(|v| v + random::complex_normal(rng) * scale)
        .collect()
}

/// The route of attempt `attempt` from `from` to `to`: the straight segment for attempt
/// 0, else the polyline through a random complex detour point near `to` (seeded by
/// `(seed, stream, attempt)`).
pub(crate) fn route(
    from: &[C64],
    to: &[C64],
    seed: u64,
    stream: u64,
    attempt: usize,
) -> PolylinePath {
    let mut points = vec![from.to_vec()];
    if attempt > 0 {
        let mut rng = random::stream(seed, stream.wrapping_mul(16).wrapping_add(attempt as u64));
        points.push(detour_point(to, &mut rng));
    }
    points.push(to.to_vec());
    PolylinePath::new(points)
}

/// Seed configuration `K*` in `frame` drawn from random stream `stream` of `seed`
/// (module documentation); `None` as τ* for pose lists.
pub fn seed_configuration(
    trajectory: &RrrTrajectory,
    frame: &RrrFrame,
    seed: u64,
    stream: u64,
) -> Result<(Option<C64>, [C64; CONFIGURATION_LEN]), RrrCurveError> {
    let mut rng = random::stream(seed, stream);
    let [lo, hi] = trajectory.motion().tau_range();
    let width = (hi - lo).max(1e-3);
    let tau_star = C64::new(
        random::uniform(&mut rng, lo, hi),
        random::uniform(&mut rng, 0.1, 0.3) * width.min(3.0),
    );
    let (tau, mut k, amplitude) = match trajectory.configuration_complex(tau_star) {
        Some(k) if k.iter().all(|v| v.re.is_finite() && v.im.is_finite()) => {
            (Some(tau_star), frame.apply_complex(&k), 0.05)
        }
        _ => {
            let first = first_configuration(trajectory)?;
            let k = frame.apply(&first).map(|v| C64::new(v, 0.0));
            (None, k, 0.3)
        }
    };
    for v in k.iter_mut() {
        *v += random::complex_normal(&mut rng) * amplitude;
    }
    Ok((tau, k))
}

/// Relative distance under which two endpoints are the same point.
const SAME_ENDPOINT: f64 = 1e-8;

/// The distinct points of `endpoints`, at most `limit` of them (a parameter homotopy
/// starts from simple points, and no parameter has more than the generic count).
pub fn distinct_solutions(endpoints: Vec<Vec<C64>>, limit: usize) -> Vec<Vec<C64>> {
    let mut out: Vec<Vec<C64>> = Vec::new();
    for x in endpoints {
        if out.len() < limit && !out.iter().any(|y| same_point(y, &x, SAME_ENDPOINT)) {
            out.push(x);
        }
    }
    out
}

/// One solve of a sub-problem at one seed point.
struct SeedRun {
    parameters: Vec<C64>,
    solutions: Vec<Vec<C64>>,
    reasons: BTreeMap<String, usize>,
}

/// Whether the seed runs' counts (in order) settle the count: the generic count
/// reached, or the largest count found by at least two seed points.
pub fn seed_count_confirmed(counts: &[usize], generic: usize) -> bool {
    let most = counts.iter().copied().max().unwrap_or(0);
    most == generic || counts.iter().filter(|&&c| c == most).count() >= 2
}

/// Stage 1: builds the four sub-problems, takes their start solutions from `provider`
/// and tracks them to the seed (in parallel), confirming a count below the generic one at
/// an independent seed point (module documentation).
pub fn rrr_seed_stage(
    trajectory: &RrrTrajectory,
    options: &RrrCurveOptions,
    provider: &(dyn Fn(&RrrProblem) -> Result<StartSolutions, RrrAbInitioError> + Sync),
) -> Result<RrrSeedStage, RrrCurveError> {
    let frame = trajectory_frame(trajectory)?;
    let seeds: Vec<(Option<C64>, Vec<C64>)> = (0..SEED_POINTS as u64)
        .map(|point| {
            let stream = if point == 0 {
                0x5eed
            } else {
                0x5eed_0000 + point
            };
            seed_configuration(trajectory, &frame, options.seed, stream)
                .map(|(tau, k)| (tau, k.to_vec()))
        })
        .collect::<Result<_, _>>()?;
    let mut prepared = Vec::new();
    for kind in RrrSubProblem::ALL {
        let problem = RrrProblem::new(kind)?;
        let start = provider(&problem)?;
        let source = start
            .parameter_vector(problem.parameter_names())
            .map_err(|name| RrrCurveError::StartSolutions {
                problem: kind.name(),
                message: format!("parameter `{name}` missing"),
            })?;
        let n = problem.variable_names().len();
        if start.variables != problem.variable_names() {
            return Err(RrrCurveError::StartSolutions {
                problem: kind.name(),
                message: "field `variables` does not match the problem's unknowns".to_string(),
            });
        }
        if let Some(bad) = start.solutions.iter().find(|x| x.len() != n) {
            return Err(RrrCurveError::StartSolutions {
                problem: kind.name(),
                message: format!("a solution has {} entries, expected {n}", bad.len()),
            });
        }
        prepared.push((problem, source, start.solutions));
    }
    let tracked: Vec<(RrrSeededProblem, Option<RrrPathFailure>, usize)> = prepared
        .into_par_iter()
        .enumerate()
        .map(|(index, (problem, source, starts))| {
            seed_problem(index, problem, &source, &starts, &seeds, options)
        })
        .collect();
    let (problems, failures, paths_tracked) = split_seed_results(tracked);
    Ok(RrrSeedStage {
        problems,
        tau_star: seeds[0].0,
        frame,
        failures,
        paths_tracked,
    })
}

/// One sub-problem at the seed points (the common one first, the others only while the
/// count is not settled, [`seed_count_confirmed`]).
fn seed_problem(
    index: usize,
    problem: RrrProblem,
    source: &[C64],
    starts: &[Vec<C64>],
    seeds: &[(Option<C64>, Vec<C64>)],
    options: &RrrCurveOptions,
) -> (RrrSeededProblem, Option<RrrPathFailure>, usize) {
    let generic = starts.len();
    let mut runs: Vec<SeedRun> = Vec::new();
    let mut tracked = 0;
    for (point, (_, parameters)) in seeds.iter().enumerate() {
        let stream = ((index as u64) << 32) + ((point as u64) << 24);
        let Retried {
            endpoints,
            tracked: count,
            reasons,
            ..
        } = track_with_retries(
            problem.evaluator(),
            starts,
            |attempt| route(source, parameters, options.seed, stream, attempt),
            options.seed_retry_attempts,
            TrackingPlan::with_endgame(&options.tracker, &options.retry_tracker),
        );
        tracked += count;
        runs.push(SeedRun {
            parameters: parameters.clone(),
            solutions: distinct_solutions(endpoints, generic),
            reasons,
        });
        let counts: Vec<usize> = runs.iter().map(|r| r.solutions.len()).collect();
        if seed_count_confirmed(&counts, generic) {
            break;
        }
    }
    let counts: Vec<usize> = runs.iter().map(|r| r.solutions.len()).collect();
    let most = counts.iter().copied().max().unwrap_or(0);
    let confirmed = seed_count_confirmed(&counts, generic);
    let chosen = runs
        .into_iter()
        .find(|r| r.solutions.len() == most)
        .unwrap_or_else(|| unreachable!("at least one seed point is solved"));
    let failure = (!confirmed).then(|| {
        let mut reasons = chosen.reasons.clone();
        reasons.insert(
            format!("SeedCountsDisagree{counts:?}").replace(' ', ""),
            generic - most,
        );
        RrrPathFailure {
            pose_index: None,
            tau: None,
            problem: problem.kind().name(),
            expected: generic,
            accounted: most,
            reasons,
        }
    });
    (
        RrrSeededProblem {
            problem,
            seed_parameters: chosen.parameters,
            start_count: chosen.solutions.len(),
            seed_solutions: chosen.solutions,
            generic_count: generic,
        },
        failure,
        tracked,
    )
}
