//! Redundancy resolution of the 3-PRRR along a task (docs/theory.md §11.3; Farias Filho
//! et al. (2021) §4).
//!
//! The end effector follows one of four trajectories sampled at `s_k = k/(N−1)`; the
//! redundant prismatic inputs δ are chosen to maximise an objective
//! `F = aggregate_k index(IK(pose(s_k), δ(s_k)))`:
//!
//! * **prepositioning** (Farias Filho et al. (2021) Eq. 27): three variables, δ fixed during the task;
//! * **continuous positioning** (Eq. 28): six variables `(δ_o, δ_f)`,
//!   `δ_i(s) = δ_o,i + (δ_f,i − δ_o,i)(10s³ − 15s⁴ + 6s⁵)` (quintic with zero end velocity and
//!   acceleration);
//!
//! with bounds `δ_min ≤ δ ≤ δ_max` on every variable. The index is LCI `1/κ(Ā⁻¹B̄)` or NSIR
//! (docs/theory.md §11.2); the aggregate is the mean (default, **Choice**) or the minimum
//! along the samples; an unreachable sample contributes 0. The optimiser is
//! [`maximize`]: GA, then the local projected quasi-Newton refinement from the
//! GA's best.

use crate::choice::UnknownChoice;
use crate::index::prrr::{LciVariant, lci, nsir};
use crate::mechanism::prrr::{Pose, PrrrDesign, PrrrError, Robot, WorkingMode};
use crate::optimize::{
    GaResult, GeneticOptions, LocalOptions, LocalResult, OptimizeError, maximize,
};
use std::f64::consts::TAU;
use std::time::Instant;
use thiserror::Error;

/// Errors of redundancy resolution.
#[derive(Debug, Error)]
pub enum RedundancyError {
    /// Invalid design.
    #[error(transparent)]
    Design(#[from] PrrrError),
    /// Optimiser rejected its input.
    #[error(transparent)]
    Optimize(#[from] OptimizeError),
    /// Unknown trajectory, scheme, index or aggregate.
    #[error(transparent)]
    UnknownChoice(#[from] UnknownChoice),
    /// Bad option.
    #[error("`{field}`: {reason}")]
    InvalidOption {
        /// Option name.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
}

named_choices! {
    option "trajectory", error RedundancyError, serde "lowercase";
    /// The four tasks of Farias Filho et al. (2021) §4 (docs/theory.md §11.3), parametrised
    /// by `s ∈ [0, 1]`; `ALL` in the order of the paper.
    pub enum Trajectory {
        /// Straight line from (−0.02, −0.09, α = 0.2) to (0.02, 0.09, α = 0); α interpolated
        /// linearly.
        Line = "line",
        /// Circle of radius 0.05 about the origin from (0, 0.05), `(0.05 sin 2πs, 0.05 cos 2πs)`
        /// (clockwise, as the spiral), α = 0.5.
        Circle = "circle",
        /// Archimedean spiral `x = (0.01 + k u) sin 2πu`, `y = (0.01 + k u) cos 2πu`,
        /// `u = 6s ∈ [0, 6]`, `k = 0.04/6`, α = 0.5.
        Spiral = "spiral",
        /// Square of side 0.12 centred at the origin from (−0.06, −0.06), counter-clockwise at
        /// constant speed, α = 0.3.
        Square = "square",
    }
}

impl Trajectory {
    /// Pose at `s ∈ [0, 1]`.
    pub fn pose_at(self, s: f64) -> Pose {
        match self {
            Trajectory::Line => Pose::new(-0.02 + 0.04 * s, -0.09 + 0.18 * s, 0.2 * (1.0 - s)),
            Trajectory::Circle => {
                let (sn, cs) = (TAU * s).sin_cos();
                Pose::new(0.05 * sn, 0.05 * cs, 0.5)
            }
            Trajectory::Spiral => {
                let u = 6.0 * s;
                let radius = 0.01 + 0.04 / 6.0 * u;
                let (sn, cs) = (TAU * u).sin_cos();
                Pose::new(radius * sn, radius * cs, 0.5)
            }
            Trajectory::Square => {
                let t = (4.0 * s).clamp(0.0, 4.0);
                let side = (t.floor() as usize).min(3);
                let f = 0.12 * (t - side as f64);
                let (x, y) = match side {
                    0 => (-0.06 + f, -0.06),
                    1 => (0.06, -0.06 + f),
                    2 => (0.06 - f, 0.06),
                    _ => (-0.06, 0.06 - f),
                };
                Pose::new(x, y, 0.3)
            }
        }
    }

    /// Default number of samples: 361 for the six-turn spiral, 121 otherwise.
    pub fn default_samples(self) -> usize {
        match self {
            Trajectory::Spiral => 361,
            _ => 121,
        }
    }
}

named_choices! {
    option "scheme", error RedundancyError, serde "lowercase";
    /// Redundancy-resolution scheme (Farias Filho et al. (2021) Eqs. 27–28).
    pub enum Scheme {
        /// δ fixed along the task: 3 variables.
        Prepositioning = "prepositioning",
        /// Quintic δ(s) from δ_o to δ_f: 6 variables.
        Continuous = "continuous",
    }
}

impl Scheme {
    /// Number of optimisation variables (3 or 6).
    pub fn dimension(self) -> usize {
        match self {
            Scheme::Prepositioning => 3,
            Scheme::Continuous => 6,
        }
    }
}

named_choices! {
    option "index", error RedundancyError, serde "lowercase";
    /// Index optimised along the task.
    pub enum TaskIndex {
        /// LCI `1/κ(Ā⁻¹B̄)` (Farias Filho et al. (2021)).
        Lci = "lci",
        /// NSIR.
        Nsir = "nsir",
    }
}

named_choices! {
    option "aggregate", error RedundancyError, serde "lowercase";
    /// How per-sample index values become the objective F.
    pub enum Aggregate {
        /// Arithmetic mean (default).
        Mean = "mean",
        /// Minimum.
        Min = "min",
    }
}

/// Largest number of samples along a task.
pub const MAX_SAMPLES: usize = 1_000_000;

/// Quintic blend `10s³ − 15s⁴ + 6s⁵` (zero velocity and acceleration at s = 0, 1).
pub fn quintic(s: f64) -> f64 {
    s * s * s * (10.0 + s * (-15.0 + 6.0 * s))
}

/// Mean, minimum and maximum of an index along the samples (unreachable samples count 0).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stats {
    /// Mean.
    pub mean: f64,
    /// Minimum.
    pub min: f64,
    /// Maximum.
    pub max: f64,
}

/// One sample of an optimised task (see [`RedundancyProblem::profile`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ProfileSample {
    /// Task parameter s ∈ [0, 1].
    pub s: f64,
    /// End-effector pose.
    pub pose: Pose,
    /// Prismatic inputs δ(s).
    pub delta: [f64; 3],
    /// LCI `1/κ(Ā⁻¹B̄)`, `None` if unreachable.
    pub lci: Option<f64>,
    /// NSIR, `None` if unreachable.
    pub nsir: Option<f64>,
}

/// One redundancy-resolution problem: design, task, scheme, index and aggregate.
#[derive(Debug, Clone)]
pub struct RedundancyProblem {
    /// The 3-PRRR.
    pub design: PrrrDesign,
    /// The task.
    pub trajectory: Trajectory,
    /// Scheme (3 or 6 variables).
    pub scheme: Scheme,
    /// Index to maximise.
    pub index: TaskIndex,
    /// Mean or min along the task.
    pub aggregate: Aggregate,
    /// Working modes, the same along the task.
    pub modes: [WorkingMode; 3],
    poses: Vec<Pose>,
    blends: Vec<f64>,
}

impl RedundancyProblem {
    /// Build a problem with `samples` (≥ 2) poses along the trajectory.
    pub fn new(
        design: PrrrDesign,
        trajectory: Trajectory,
        scheme: Scheme,
        index: TaskIndex,
        aggregate: Aggregate,
        modes: [WorkingMode; 3],
        samples: usize,
    ) -> Result<Self, RedundancyError> {
        design.validate()?;
        if !(2..=MAX_SAMPLES).contains(&samples) {
            return Err(RedundancyError::InvalidOption {
                field: "samples",
                reason: format!("{samples} not in 2..={MAX_SAMPLES}"),
            });
        }
        let s: Vec<f64> = (0..samples)
            .map(|k| k as f64 / (samples - 1) as f64)
            .collect();
        Ok(Self {
            design,
            trajectory,
            scheme,
            index,
            aggregate,
            modes,
            poses: s.iter().map(|&s| trajectory.pose_at(s)).collect(),
            blends: s.iter().map(|&s| quintic(s)).collect(),
        })
    }

    /// The sampled poses.
    pub fn poses(&self) -> &[Pose] {
        &self.poses
    }

    /// Box of the optimisation variables: `[δ_min, δ_max]` for each.
    pub fn bounds(&self) -> Vec<(f64, f64)> {
        vec![self.design.delta_range; self.scheme.dimension()]
    }

    /// δ at sample `k` for the variable vector (3 for prepositioning, 6 for continuous).
    pub fn delta_at(&self, variables: &[f64], k: usize) -> [f64; 3] {
        match self.scheme {
            Scheme::Prepositioning => [variables[0], variables[1], variables[2]],
            Scheme::Continuous => {
                let b = self.blends[k];
                [0, 1, 2].map(|i| variables[i] + (variables[i + 3] - variables[i]) * b)
            }
        }
    }

    /// Index value at sample `k` (0 if unreachable).
    pub fn index_at(&self, index: TaskIndex, variables: &[f64], k: usize) -> f64 {
        let delta = self.delta_at(variables, k);
        match self
            .design
            .inverse_kinematics(&self.poses[k], &delta, &self.modes)
        {
            Ok(c) => match index {
                TaskIndex::Lci => lci(&self.design, &c, Robot::ThreePrrr, LciVariant::InverseAB),
                TaskIndex::Nsir => nsir(&self.design, &c, Robot::ThreePrrr).nsir,
            },
            Err(_) => 0.0,
        }
    }

    /// Objective F: aggregate of the problem's index along the samples (docs/theory.md
    /// §11.3). Allocation-free. Variables of the wrong length give −∞.
    pub fn objective(&self, variables: &[f64]) -> f64 {
        if variables.len() != self.scheme.dimension() {
            return f64::NEG_INFINITY;
        }
        let n = self.poses.len();
        match self.aggregate {
            Aggregate::Mean => {
                (0..n)
                    .map(|k| self.index_at(self.index, variables, k))
                    .sum::<f64>()
                    / n as f64
            }
            Aggregate::Min => (0..n)
                .map(|k| self.index_at(self.index, variables, k))
                .fold(f64::INFINITY, f64::min),
        }
    }

    /// Mean/min/max of `index` along the task for these variables.
    pub fn stats(&self, index: TaskIndex, variables: &[f64]) -> Stats {
        let n = self.poses.len();
        let (mut sum, mut min, mut max) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..n {
            let v = self.index_at(index, variables, k);
            sum += v;
            min = min.min(v);
            max = max.max(v);
        }
        Stats {
            mean: sum / n as f64,
            min,
            max,
        }
    }

    /// The joint trajectory along the task: pose, δ and both indices at every sample
    /// (indices `None` when unreachable).
    pub fn profile(&self, variables: &[f64]) -> Vec<ProfileSample> {
        (0..self.poses.len())
            .map(|k| {
                let delta = self.delta_at(variables, k);
                let configuration = self
                    .design
                    .inverse_kinematics(&self.poses[k], &delta, &self.modes)
                    .ok();
                ProfileSample {
                    s: if self.poses.len() > 1 {
                        k as f64 / (self.poses.len() - 1) as f64
                    } else {
                        0.0
                    },
                    pose: self.poses[k],
                    delta,
                    lci: configuration
                        .map(|c| lci(&self.design, &c, Robot::ThreePrrr, LciVariant::InverseAB)),
                    nsir: configuration.map(|c| nsir(&self.design, &c, Robot::ThreePrrr).nsir),
                }
            })
            .collect()
    }

    /// Number of unreachable samples for these variables.
    pub fn unreachable_samples(&self, variables: &[f64]) -> usize {
        (0..self.poses.len())
            .filter(|&k| {
                self.design
                    .inverse_kinematics(&self.poses[k], &self.delta_at(variables, k), &self.modes)
                    .is_err()
            })
            .count()
    }

    /// Mean wall time in nanoseconds of one evaluation (inverse kinematics + index) of
    /// `index`, over `repetitions` passes along the task.
    pub fn time_per_evaluation_ns(
        &self,
        index: TaskIndex,
        variables: &[f64],
        repetitions: usize,
    ) -> f64 {
        let n = self.poses.len();
        let start = Instant::now();
        let mut sink = 0.0;
        for _ in 0..repetitions.max(1) {
            for k in 0..n {
                sink +=
                    std::hint::black_box(self.index_at(index, std::hint::black_box(variables), k));
            }
        }
        std::hint::black_box(sink);
        start.elapsed().as_nanos() as f64 / (repetitions.max(1) * n) as f64
    }
}

/// Outcome of [`resolve`].
#[derive(Debug, Clone, serde::Serialize)]
pub struct Resolution {
    /// Task name.
    pub trajectory: Trajectory,
    /// Scheme.
    pub scheme: Scheme,
    /// Optimised index.
    pub index: TaskIndex,
    /// Aggregate.
    pub aggregate: Aggregate,
    /// Optimal variables: δ (3) or (δ_o, δ_f) (6), metres.
    pub variables: Vec<f64>,
    /// Objective at the optimum.
    pub objective: f64,
    /// Objective with δ = 0 (the 3RRR-like reference).
    pub objective_at_zero: f64,
    /// LCI along the optimised task.
    pub lci: Stats,
    /// NSIR along the optimised task.
    pub nsir: Stats,
    /// Unreachable samples on the optimised task.
    pub unreachable_samples: usize,
    /// Samples along the task.
    pub samples: usize,
    /// Genetic stage.
    pub genetic: GaResult,
    /// Local stage.
    pub local: LocalResult,
    /// Wall time of the whole optimisation (s).
    pub optimisation_seconds: f64,
    /// Mean time of one IK + LCI evaluation along the task (ns).
    pub ns_per_lci: f64,
    /// Mean time of one IK + NSIR evaluation along the task (ns).
    pub ns_per_nsir: f64,
}

/// Solve a redundancy-resolution problem with the hybrid GA + local optimiser.
pub fn resolve(
    problem: &RedundancyProblem,
    genetic: &GeneticOptions,
    local: &LocalOptions,
    timing_repetitions: usize,
) -> Result<Resolution, RedundancyError> {
    let bounds = problem.bounds();
    let start = Instant::now();
    let result = maximize(|x: &[f64]| problem.objective(x), &bounds, genetic, local)?;
    let optimisation_seconds = start.elapsed().as_secs_f64();
    let zero = vec![0.0; problem.scheme.dimension()];
    let variables = result.best.clone();
    Ok(Resolution {
        trajectory: problem.trajectory,
        scheme: problem.scheme,
        index: problem.index,
        aggregate: problem.aggregate,
        objective: result.best_value,
        objective_at_zero: problem.objective(&zero),
        lci: problem.stats(TaskIndex::Lci, &variables),
        nsir: problem.stats(TaskIndex::Nsir, &variables),
        unreachable_samples: problem.unreachable_samples(&variables),
        samples: problem.poses.len(),
        ns_per_lci: problem.time_per_evaluation_ns(TaskIndex::Lci, &variables, timing_repetitions),
        ns_per_nsir: problem.time_per_evaluation_ns(
            TaskIndex::Nsir,
            &variables,
            timing_repetitions,
        ),
        variables,
        genetic: result.genetic,
        local: result.local,
        optimisation_seconds,
    })
}
