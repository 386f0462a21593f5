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

use super::ab_initio::RrrAbInitioError;
use super::curve::{RrrCurveError, RrrCurveOptions, RrrPathFailure};
use crate::C64;
use crate::homotopy::PolylinePath;
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrTrajectory};
use crate::pipeline::family::{Family, frame_scale};
use crate::pipeline::start_file::StartSolutions;
use crate::pipeline::sweep::{SeedPolicy, SeedSolutions, detour_point, seed_family, split_seeded};
pub use crate::pipeline::sweep::{distinct_solutions, seed_count_confirmed};
use crate::problem::rrr::{RrrProblem, RrrSubProblem};
use crate::random;
use crate::system::CompiledSystem;

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
        RrrFrame {
            center,
            scale: frame_scale(spread),
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
    /// Its solutions at the seed (`K*` in the normalised frame) and its counts.
    pub at_seed: SeedSolutions,
    /// The complex motion parameter `τ*` of its seed point (`None` for pose lists).
    pub tau_star: Option<C64>,
}

/// Makes the run's seed stage and the self-check's expect the same count per
/// sub-problem: the larger of their two counts (at most the generic one). Each stage
/// confirms a count below the generic one by two of its own seed points agreeing, and
/// two seed points can agree on too few; no parameter has more isolated critical
/// points than a count some seed point reached, so the larger count refutes the
/// smaller. A stage with fewer seed solutions than the reconciled count then solves
/// its poses by the generic route (the start file's solutions tracked to the pose,
/// `track_from_seed`), and reports the shortfall where that does not reach the count,
/// instead of expecting too few.
pub fn reconcile_seed_counts(run: &mut RrrSeedStage, check: &mut RrrSeedStage) {
    for (a, b) in run.problems.iter_mut().zip(check.problems.iter_mut()) {
        debug_assert_eq!(a.problem.kind(), b.problem.kind());
        let count = a
            .at_seed
            .start_count
            .max(b.at_seed.start_count)
            .min(a.at_seed.generic_count);
        a.at_seed.start_count = count;
        b.at_seed.start_count = count;
    }
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
        points.push(detour_point(to, to.len(), &mut rng));
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

/// A sub-problem ready for the user homotopy: its system, generic point and start set.
type PreparedProblem = (RrrProblem, Vec<C64>, Vec<Vec<C64>>);

/// The four prepared sub-problems (system, generic point, start set) as a
/// [`Family`] whose seed points are common to all of them.
struct SeedFamily<'a> {
    prepared: &'a [PreparedProblem],
    seeds: &'a [(Option<C64>, Vec<C64>)],
}

impl Family for SeedFamily<'_> {
    type Seed = Option<C64>;

    fn problems(&self) -> usize {
        self.prepared.len()
    }

    fn name(&self, problem: usize) -> String {
        self.prepared[problem].0.kind().name()
    }

    fn system(&self, problem: usize) -> &CompiledSystem {
        self.prepared[problem].0.evaluator()
    }

    fn generic_start(&self, problem: usize) -> (&[C64], &[Vec<C64>]) {
        let (_, source, starts) = &self.prepared[problem];
        (source, starts)
    }

    fn seed(&self, _problem: usize, point: usize) -> (Option<C64>, Vec<C64>) {
        let (tau, k) = &self.seeds[point];
        (*tau, k.clone())
    }

    fn moving_parameters(&self) -> usize {
        CONFIGURATION_LEN
    }

    fn detour_stream(&self, stream: u64, attempt: usize) -> u64 {
        stream.wrapping_mul(16).wrapping_add(attempt as u64)
    }
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
        if start.variables != problem.variable_names() {
            return Err(RrrCurveError::StartSolutions {
                problem: kind.name(),
                message: "field `variables` does not match the problem's unknowns".to_string(),
            });
        }
        let source = start
            .source_for(problem.parameter_names(), problem.variable_names().len())
            .map_err(|message| RrrCurveError::StartSolutions {
                problem: kind.name(),
                message,
            })?;
        prepared.push((problem, source, start.solutions));
    }
    let family = SeedFamily {
        prepared: &prepared,
        seeds: &seeds,
    };
    // Whole detours at every seed point.
    let policy = SeedPolicy {
        confirm_lost_paths_first: false,
        ..SeedPolicy::new(
            SEED_POINTS,
            options.seed,
            (&options.tracker, &options.retry_tracker),
            options.seed_retry_attempts,
        )
    };
    let seeded = seed_family(&family, &policy);
    let (seeded, failures, paths_tracked) = split_seeded(seeded);
    let problems = prepared
        .into_iter()
        .zip(seeded)
        .map(|((problem, source, starts), seeded)| {
            let (tau_star, at_seed) = SeedSolutions::new(seeded, (source, starts));
            RrrSeededProblem {
                problem,
                at_seed,
                tau_star,
            }
        })
        .collect();
    Ok(RrrSeedStage {
        problems,
        tau_star: seeds[0].0,
        frame,
        failures,
        paths_tracked,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stage(counts: &[usize]) -> RrrSeedStage {
        let problems = RrrSubProblem::ALL
            .iter()
            .zip(counts)
            .map(|(&kind, &count)| RrrSeededProblem {
                problem: RrrProblem::new(kind).unwrap(),
                at_seed: SeedSolutions {
                    parameters: Vec::new(),
                    solutions: vec![Vec::new(); count],
                    generic_count: if kind == RrrSubProblem::Parallel {
                        50
                    } else {
                        2
                    },
                    start_count: count,
                    generic_start: (Vec::new(), Vec::new()),
                    completed_by_monodromy: false,
                },
                tau_star: None,
            })
            .collect();
        RrrSeedStage {
            problems,
            tau_star: None,
            frame: RrrFrame::of(&[0.0; CONFIGURATION_LEN]),
            failures: Vec::new(),
            paths_tracked: 0,
        }
    }

    /// Both stages expect the larger count, never more than the generic one; a stage
    /// that found fewer keeps its solutions (and will report the shortfall).
    #[test]
    fn the_larger_seed_count_refutes_the_smaller() {
        let (mut run, mut check) = (stage(&[48, 2, 1, 2]), stage(&[50, 2, 2, 1]));
        reconcile_seed_counts(&mut run, &mut check);
        for s in [&run, &check] {
            let counts: Vec<usize> = s.problems.iter().map(|p| p.at_seed.start_count).collect();
            assert_eq!(counts, vec![50, 2, 2, 2]);
        }
        assert_eq!(run.problems[0].at_seed.solutions.len(), 48);
    }
}
