//! The Lagrangian sub-problems of every metric (Kapilavai and Nawratil, §3–§4;
//! docs/theory.md §5).
//!
//! For a given configuration `K` (the parameters) the closest configuration `K′` on a
//! constraint set is a critical point of a Lagrangian
//!
//! ```text
//!   Λ(K′, λ, μ; K) = D²(K, K′) − λ·C(K′) − Σ_rigid μ·g(K′)
//! ```
//!
//! where `C` is the singularity polynomial S (docs/theory.md §1.3), or a collinearity
//! polynomial `C_p`, `C_b`, and `g = |x₂′ − x₁′|² − r²` keeps a rigid part congruent
//! (docs/theory.md §4, point-based representation of SE(2): a rigid part's third point is
//! `x₃′ = x₁′ + u (x₂′ − x₁′) + v E(x₂′ − x₁′)`). Two further sub-problems parameterise
//! singular points of the constraint varieties directly: all six points on one line
//! (Kapilavai and Nawratil, Thm 3 case 1, Eqs. 56–57) and three coincident platform
//! (base) points under a rigid base (platform) (Kapilavai and Nawratil, §4.2, Eqs. 62–63).
//!
//! Every sub-problem is the square system `∇Λ = 0`, built once with
//! [`crate::system`] and compiled; its parameters are the twelve coordinates of `K`
//! (`A1x … B3y`) followed by the shape constants of the rigid parts.

mod build;
pub mod equilateral;
pub mod pedal;
pub mod rrr;
mod stratum;

pub use build::{
    CHART_VARIABLE, COLLINEAR_ANCHOR_TOLERANCE, CONFIGURATION_PARAMETER_NAMES, COORDINATE_NAMES,
    Coordinates, LagrangeProblem, Multipliers, ProblemError, anchors_collinear,
};
pub use stratum::{ON_A_LINE_TOLERANCE, Stratum};

use crate::metric::{Metric, Part};
use std::fmt;
use std::str::FromStr;

/// The kinds of sub-problem of docs/theory.md §5, with their stable names; serialised
/// as the variant name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub enum SubProblem {
    /// `S(K′) = 0`: leg lines concurrent or parallel (all nine metrics).
    Singularity,
    /// `C_p(K′) = 0`: platform anchors collinear (platform `bars`).
    CollinearPlatform,
    /// `C_b(K′) = 0`: base anchors collinear (base `bars`).
    CollinearBase,
    /// All six points on one line `q + t_k w`, `w·w = 1` (Kapilavai and Nawratil, Thm 3
    /// case 1; platform and base `plate` or `rigid`).
    AllCollinear,
    /// `b₁′ = b₂′ = b₃′` under a rigid base (metric `bars/rigid`, Kapilavai and Nawratil,
    /// Eq. 62).
    CoincidentPlatform,
    /// `a₁′ = a₂′ = a₃′` under a rigid platform (metric `rigid/bars`, Kapilavai and
    /// Nawratil, Eq. 63).
    CoincidentBase,
}

impl SubProblem {
    /// Every kind, in a fixed order.
    pub const ALL: [SubProblem; 6] = [
        SubProblem::Singularity,
        SubProblem::CollinearPlatform,
        SubProblem::CollinearBase,
        SubProblem::AllCollinear,
        SubProblem::CoincidentPlatform,
        SubProblem::CoincidentBase,
    ];

    /// Stable name used in problem names, files and JSON output.
    pub fn name(self) -> &'static str {
        match self {
            SubProblem::Singularity => "singularity",
            SubProblem::CollinearPlatform => "collinear-platform",
            SubProblem::CollinearBase => "collinear-base",
            SubProblem::AllCollinear => "all-collinear",
            SubProblem::CoincidentPlatform => "coincident-platform",
            SubProblem::CoincidentBase => "coincident-base",
        }
    }
}

impl fmt::Display for SubProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for SubProblem {
    type Err = ProblemError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        SubProblem::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| ProblemError::UnknownName {
                name: s.to_string(),
                valid: SubProblem::ALL
                    .iter()
                    .map(|k| k.name())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}

/// The sub-problems whose minimum is the singularity distance of `metric`
/// (docs/theory.md §5; Kapilavai and Nawratil, Eqs. 55 and 59 justify the ones left out):
/// the singularity variety always; the collinear platform (base) for a `bars`
/// platform (base); all-collinear when neither part is `bars`; coincident
/// platform (base) points when the platform (base) is `bars` and the other part rigid.
pub fn subproblems_of(metric: Metric) -> Vec<SubProblem> {
    let mut list = vec![SubProblem::Singularity];
    if metric.platform == Part::Bars {
        list.push(SubProblem::CollinearPlatform);
    }
    if metric.base == Part::Bars {
        list.push(SubProblem::CollinearBase);
    }
    if metric.platform != Part::Bars && metric.base != Part::Bars {
        list.push(SubProblem::AllCollinear);
    }
    if metric.platform == Part::Bars && metric.base == Part::Rigid {
        list.push(SubProblem::CoincidentPlatform);
    }
    if metric.base == Part::Bars && metric.platform == Part::Rigid {
        list.push(SubProblem::CoincidentBase);
    }
    list
}

/// A metric together with one of its sub-problems, e.g. `bars/rigid:collinear-platform`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ProblemId {
    /// The metric whose distance is minimised.
    pub metric: Metric,
    /// The constraint set.
    pub subproblem: SubProblem,
}

impl ProblemId {
    /// `PLATFORM/BASE:SUBPROBLEM` (the [`Display`](fmt::Display) form).
    pub fn name(&self) -> String {
        self.to_string()
    }

    /// File stem of the start-solution file: `PLATFORM-BASE-SUBPROBLEM`.
    pub fn file_stem(&self) -> String {
        format!(
            "{}-{}",
            self.metric.name().replace('/', "-"),
            self.subproblem.name()
        )
    }

    /// Every (metric, sub-problem) pair that some metric needs, metrics in the
    /// order of [`Metric::all`].
    pub fn all() -> Vec<ProblemId> {
        Metric::all()
            .into_iter()
            .flat_map(|metric| {
                subproblems_of(metric)
                    .into_iter()
                    .map(move |subproblem| ProblemId { metric, subproblem })
            })
            .collect()
    }
}

impl fmt::Display for ProblemId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.metric.name(), self.subproblem)
    }
}

impl FromStr for ProblemId {
    type Err = ProblemError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (metric, sub) = s.split_once(':').ok_or_else(|| ProblemError::UnknownName {
            name: s.to_string(),
            valid: "PLATFORM/BASE:SUBPROBLEM, e.g. bars/rigid:collinear-platform".to_string(),
        })?;
        let metric: Metric = metric.parse().map_err(|e| ProblemError::UnknownName {
            name: s.to_string(),
            valid: format!("{e}"),
        })?;
        let subproblem: SubProblem = sub.parse()?;
        if !subproblems_of(metric).contains(&subproblem) {
            return Err(ProblemError::NotNeeded {
                problem: s.to_string(),
                needed: subproblems_of(metric)
                    .iter()
                    .map(|k| k.name())
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
        Ok(ProblemId { metric, subproblem })
    }
}
