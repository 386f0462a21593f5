//! Post-processing of the critical points at one pose (Kapilavai and Nawratil, §5.4;
//! docs/theory.md §8.4).
//!
//! From the finite endpoints of every sub-problem's Lagrange system `∇Λ = 0` at the
//! real configuration `K` of a pose:
//!
//! 1. keep the real ones: `max_k |Im x_k| ≤ real_tolerance · (1 + ‖x‖∞)` over the
//!    unknowns before the multipliers (K′ and the like; the multipliers of a real K′
//!    are real, and they are the least accurate entries of ill-conditioned points);
//! 2. map each to its closest-configuration candidate `K′ = Re K′(x; p)` and recompute
//!    `D(K, K′)` in f64 with [`Metric::distance`] (docs/theory.md §3), independently of the
//!    homotopy's arithmetic;
//! 3. the sub-problem distance is the smallest such `D`; the metric's singularity
//!    distance is the minimum over its sub-problems (Kapilavai and Nawratil, Fig. 14;
//!    docs/theory.md §5);
//! 4. the signed distance carries the sign of `S(K)` (docs/theory.md §1.3, §7);
//! 5. a pose is on a cut locus when a second minimiser with a different `K′` attains
//!    the minimum within `cut_locus_tolerance` (Kapilavai and Nawratil, §6): both are
//!    reported.

use crate::certify::distance::{MetricCertificate, SubproblemCertificate};
use crate::metric::Metric;
use crate::problem::SubProblem;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A real critical point of one sub-problem, reduced to what the curve needs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    /// `D(K, K′)` recomputed in f64.
    pub distance: f64,
    /// The configuration `K′` (twelve coordinates in the order of docs/theory.md §1.1).
    pub closest: [f64; 12],
}

/// Closest configuration of one sub-problem at one pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubproblemDistance {
    /// Smallest `D(K, K′)` over the real critical points (`None` if there are none).
    pub distance: Option<f64>,
    /// The minimising `K′`.
    pub closest: Option<[f64; 12]>,
    /// Number of real critical points found.
    pub real_critical_points: usize,
    /// Number of paths whose endpoint was classified: finite, or at infinity (a
    /// critical point that does not exist at this pose). Best attempt.
    pub accounted_paths: usize,
    /// Number of paths tracked from the seed (its finite solutions).
    pub expected_paths: usize,
    /// What interval arithmetic proved about its critical points (when certifying).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub certificate: Option<SubproblemCertificate>,
}

/// An alternative minimiser reported at a cut locus.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Minimiser {
    /// Sub-problem that attains it.
    pub subproblem: String,
    /// `D(K, K′)`.
    pub distance: f64,
    /// `K′`.
    pub closest: [f64; 12],
}

/// Singularity distance of one metric at one pose (docs/theory.md §5, §8).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MetricDistance {
    /// `min` over the sub-problems of the smallest real critical value of `D`.
    pub distance: f64,
    /// `sign(S(K)) · distance`.
    pub signed_distance: f64,
    /// Name of the sub-problem that attains the minimum.
    pub subproblem: String,
    /// The closest configuration `K′`.
    pub closest: [f64; 12],
    /// Two distinct minimisers (different `K′`) tie within the tolerance.
    pub cut_locus: bool,
    /// At a cut locus, every minimiser within tolerance (the reported one first).
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub minimisers: Vec<Minimiser>,
    /// Per sub-problem: its own distance and closest configuration.
    pub subproblems: BTreeMap<String, SubproblemDistance>,
    /// Whether the distance is a proved global minimum (when certifying).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub certificate: Option<MetricCertificate>,
}

/// One sub-problem's real candidates with its finite and expected endpoint counts.
pub type SubproblemCandidates = (SubProblem, Vec<Candidate>, usize, usize);

/// Whether the complex point `x` is real: `max |Im x_k| ≤ tolerance · (1 + ‖x‖∞)`.
pub fn is_real(x: &[crate::C64], tolerance: f64) -> bool {
    let scale = 1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.norm()));
    x.iter().all(|v| v.im.abs() <= tolerance * scale)
}

/// Whether two configurations differ by more than `tolerance · scale` in some coordinate.
pub fn distinct_configurations(a: &[f64; 12], b: &[f64; 12], tolerance: f64) -> bool {
    let scale = 1.0 + a.iter().chain(b.iter()).fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b.iter())
        .any(|(x, y)| (x - y).abs() > tolerance * scale)
}

/// Reduces a list of candidates to the sub-problem's closest configuration.
pub fn subproblem_distance(
    candidates: &[Candidate],
    accounted_paths: usize,
    expected_paths: usize,
) -> SubproblemDistance {
    let best = candidates
        .iter()
        .min_by(|a, b| a.distance.total_cmp(&b.distance));
    SubproblemDistance {
        distance: best.map(|c| c.distance),
        closest: best.map(|c| c.closest),
        real_critical_points: candidates.len(),
        accounted_paths,
        expected_paths,
        certificate: None,
    }
}

/// Combines the sub-problems of one metric (docs/theory.md §5: minimum over sub-problems),
/// attaches the sign of `S(K)` and detects a cut locus: another candidate with a
/// different `K′` (coordinates differ by more than `1e-6` relative) whose distance
/// exceeds the minimum by at most `cut_locus_tolerance`. Returns `None` when no
/// sub-problem has a real critical point.
pub fn metric_distance(
    metric: Metric,
    per_subproblem: &[SubproblemCandidates],
    singularity_value: f64,
    cut_locus_tolerance: f64,
) -> Option<MetricDistance> {
    let _ = metric;
    let mut all: Vec<(SubProblem, &Candidate)> = per_subproblem
        .iter()
        .flat_map(|(kind, list, _, _)| list.iter().map(move |c| (*kind, c)))
        .collect();
    all.sort_by(|a, b| a.1.distance.total_cmp(&b.1.distance));
    let (best_kind, best) = *all.first()?;
    let mut minimisers = vec![Minimiser {
        subproblem: best_kind.name().to_string(),
        distance: best.distance,
        closest: best.closest,
    }];
    for (kind, candidate) in all.iter().skip(1) {
        if candidate.distance - best.distance > cut_locus_tolerance {
            break;
        }
        if minimisers
            .iter()
            .all(|m| distinct_configurations(&m.closest, &candidate.closest, 1e-6))
        {
            minimisers.push(Minimiser {
                subproblem: kind.name().to_string(),
                distance: candidate.distance,
                closest: candidate.closest,
            });
        }
    }
    let cut_locus = minimisers.len() > 1;
    if !cut_locus {
        minimisers.clear();
    }
    let sign = if singularity_value < 0.0 { -1.0 } else { 1.0 };
    Some(MetricDistance {
        distance: best.distance,
        signed_distance: sign * best.distance,
        subproblem: best_kind.name().to_string(),
        closest: best.closest,
        cut_locus,
        minimisers,
        subproblems: per_subproblem
            .iter()
            .map(|(kind, list, finite, expected)| {
                (
                    kind.name().to_string(),
                    subproblem_distance(list, *finite, *expected),
                )
            })
            .collect(),
        certificate: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::C64;

    fn candidate(distance: f64, shift: f64) -> Candidate {
        let mut closest = [0.0; 12];
        closest[0] = shift;
        Candidate { distance, closest }
    }

    #[test]
    fn real_test_is_relative_to_magnitude() {
        let x = [C64::new(1e6, 1e-5), C64::new(1.0, 0.0)];
        assert!(is_real(&x, 1e-10));
        let y = [C64::new(1.0, 1e-5), C64::new(1.0, 0.0)];
        assert!(!is_real(&y, 1e-8));
    }

    #[test]
    fn minimum_over_subproblems_sign_and_cut_locus() {
        let metric = Metric::all()[0];
        let data = vec![
            (
                SubProblem::Singularity,
                vec![candidate(2.0, 0.0), candidate(1.0, 1.0)],
                4,
                4,
            ),
            (SubProblem::AllCollinear, vec![candidate(1.5, 2.0)], 2, 2),
        ];
        let result = metric_distance(metric, &data, -3.0, 1e-9).expect("candidates exist");
        assert_eq!(result.distance, 1.0);
        assert_eq!(result.signed_distance, -1.0);
        assert_eq!(result.subproblem, "singularity");
        assert!(!result.cut_locus);
        assert_eq!(result.subproblems["all-collinear"].distance, Some(1.5));
        // A tie with a different K′ is a cut locus; a tie with the same K′ is not.
        let tie = vec![(
            SubProblem::Singularity,
            vec![
                candidate(1.0, 0.0),
                candidate(1.0, 0.0),
                candidate(1.0, 5.0),
            ],
            3,
            3,
        )];
        let result = metric_distance(metric, &tie, 1.0, 1e-9).expect("candidates exist");
        assert!(result.cut_locus);
        assert_eq!(result.minimisers.len(), 2);
        let same = vec![(
            SubProblem::Singularity,
            vec![candidate(1.0, 0.0), candidate(1.0, 0.0)],
            2,
            2,
        )];
        assert!(
            !metric_distance(metric, &same, 1.0, 1e-9)
                .expect("candidates exist")
                .cut_locus
        );
        assert!(metric_distance(metric, &[], 1.0, 1e-9).is_none());
    }
}
