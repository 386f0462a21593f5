//! The 3-RRR singularity-distance sub-problems of docs/theory.md §10 (Kapilavai and
//! Nawratil, §6.3) with the all-deformable metric `D²` of
//! [`crate::mechanism::rrr::distance_sq`].
//!
//! For a given configuration `K` of the nine points (the 18 parameters `O1x … C3y`), the
//! closest configuration `K′` on a constraint set `C(K′) = 0` is a critical point of
//!
//! ```text
//!   Λ(K′, λ; K) = D²(K, K′) − λ·C(K′)
//! ```
//!
//! - `rrr:parallel`: `C` = the parallel-singularity polynomial (lines `B_iC_i` concurrent
//!   or parallel, [`parallel_polynomial`]);
//! - `rrr:leg1`, `rrr:leg2`, `rrr:leg3`: `C` = the leg-singularity polynomial
//!   (`O_i, B_i, C_i` collinear, [`leg_polynomial`]).
//!
//! Unknowns: all 18 coordinates of `K′` (`o1x … c3y`) and `λ` (19). For a leg problem the
//! constraint involves only `O_i, B_i, C_i`, but `D²` couples all nine points (the base and
//! platform plates), so the other six points are kept as unknowns: their equations are
//! linear, and eliminating them would only hide a Schur complement in the metric.

use crate::C64;
use crate::mechanism::rrr::{
    CONFIGURATION_LEN, COORDINATE_NAMES, distance_sq, leg_polynomial, parallel_polynomial,
};
use crate::system::{Evaluator, Expr, ParametricSystem, System};
use std::fmt;
use std::str::FromStr;

/// Errors of the 3-RRR problem layer.
#[derive(Debug, thiserror::Error)]
pub enum RrrProblemError {
    /// A name that is not one of `rrr:parallel`, `rrr:leg1`, `rrr:leg2`, `rrr:leg3`.
    #[error("unknown 3-RRR problem `{name}`; valid: rrr:parallel, rrr:leg1, rrr:leg2, rrr:leg3")]
    UnknownName {
        /// What was given.
        name: String,
    },
    /// The system builder rejected the Lagrangian (a bug, reported rather than hidden).
    #[error("building the system of `{problem}` failed: {message}")]
    Build {
        /// The problem name.
        problem: String,
        /// The builder's message.
        message: String,
    },
}

/// The four 3-RRR sub-problems of docs/theory.md §10.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum RrrSubProblem {
    /// Parallel singularity: lines `B_iC_i` concurrent or parallel.
    Parallel,
    /// Leg singularity of leg `i` (0-based): `O_i, B_i, C_i` collinear.
    Leg(usize),
}

impl RrrSubProblem {
    /// The four sub-problems in output order: parallel, leg 1, leg 2, leg 3.
    pub const ALL: [RrrSubProblem; 4] = [
        RrrSubProblem::Parallel,
        RrrSubProblem::Leg(0),
        RrrSubProblem::Leg(1),
        RrrSubProblem::Leg(2),
    ];

    /// Short name used as JSON key and CSV column: `parallel`, `leg1`, `leg2`, `leg3`.
    pub fn short_name(self) -> String {
        match self {
            RrrSubProblem::Parallel => "parallel".to_string(),
            RrrSubProblem::Leg(i) => format!("leg{}", i + 1),
        }
    }

    /// Stable problem name: `rrr:parallel`, `rrr:leg1`, ….
    pub fn name(self) -> String {
        format!("rrr:{}", self.short_name())
    }

    /// File stem of the start-solution file: `rrr-parallel`, `rrr-leg1`, ….
    pub fn file_stem(self) -> String {
        format!("rrr-{}", self.short_name())
    }

    /// The constraint polynomial `C(K′)` of this sub-problem, generic over the ring.
    pub fn constraint<T: crate::algebra::Ring>(self, k: &[T; CONFIGURATION_LEN]) -> T {
        match self {
            RrrSubProblem::Parallel => parallel_polynomial(k),
            RrrSubProblem::Leg(i) => leg_polynomial(k, i),
        }
    }
}

impl fmt::Display for RrrSubProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

impl FromStr for RrrSubProblem {
    type Err = RrrProblemError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        RrrSubProblem::ALL
            .into_iter()
            .find(|k| k.name() == s || k.short_name() == s)
            .ok_or_else(|| RrrProblemError::UnknownName {
                name: s.to_string(),
            })
    }
}

/// Metric name recorded in the start-solution files of the 3-RRR problems.
pub const RRR_METRIC_NAME: &str = "rrr-all-deformable";

/// Names of the parameters holding the given configuration K (the 18 coordinates).
pub const PARAMETER_NAMES: [&str; CONFIGURATION_LEN] = COORDINATE_NAMES;

/// A compiled 3-RRR Lagrange system `∇Λ = 0` (19 equations in `o1x … c3y, lambda`).
#[derive(Clone)]
pub struct RrrProblem {
    kind: RrrSubProblem,
    /// `∇Λ = 0`, symbolic and compiled.
    equations: ParametricSystem,
}

/// The system `∇Λ = 0` with its names ([`ParametricSystem`]'s accessors; the parameters
/// are the 18 coordinates of K).
impl std::ops::Deref for RrrProblem {
    type Target = ParametricSystem;
    fn deref(&self) -> &ParametricSystem {
        &self.equations
    }
}

impl fmt::Debug for RrrProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RrrProblem")
            .field("kind", &self.kind.name())
            .field("variables", &self.variable_names())
            .finish()
    }
}

/// Names of the unknowns: `o1x o1y … c3y lambda`.
pub fn variable_names() -> Vec<String> {
    COORDINATE_NAMES
        .iter()
        .map(|s| s.to_lowercase())
        .chain(std::iter::once("lambda".to_string()))
        .collect()
}

impl RrrProblem {
    /// Builds and compiles `∇Λ = 0` of `kind` (module documentation).
    pub fn new(kind: RrrSubProblem) -> Result<Self, RrrProblemError> {
        let variables = variable_names();
        let given: [Expr; CONFIGURATION_LEN] =
            std::array::from_fn(|j| Expr::parameter(PARAMETER_NAMES[j]));
        let unknown: [Expr; CONFIGURATION_LEN] =
            std::array::from_fn(|j| Expr::variable(&variables[j]));
        let lagrangian =
            distance_sq(&given, &unknown) - Expr::variable("lambda") * kind.constraint(&unknown);
        let system = System::lagrange(&lagrangian, variables, PARAMETER_NAMES).map_err(|e| {
            RrrProblemError::Build {
                problem: kind.name(),
                message: e.to_string(),
            }
        })?;
        Ok(RrrProblem {
            kind,
            equations: ParametricSystem::new(system),
        })
    }

    /// Which sub-problem this is.
    pub fn kind(&self) -> RrrSubProblem {
        self.kind
    }

    /// `K′` of a solution `x`: its first 18 entries.
    pub fn configuration(x: &[C64]) -> [C64; CONFIGURATION_LEN] {
        std::array::from_fn(|j| x.get(j).copied().unwrap_or_default())
    }

    /// The complex conjugate solution `x̄`: at real parameters (a real configuration
    /// `K`) the Lagrange system has real coefficients in these Cartesian unknowns, so
    /// with `x` also `x̄` is a solution, nonsingular with it.
    pub fn conjugate(x: &[C64]) -> Vec<C64> {
        x.iter().map(|v| v.conj()).collect()
    }

    /// Scratch length of the compiled system.
    pub fn workspace_len(&self) -> usize {
        self.evaluator().workspace_len()
    }
}
