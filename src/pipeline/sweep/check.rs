//! The pieces of a run's self-check every mechanism shares: which poses a window
//! re-solves from an independent seed stage, that stage's seed, the tolerance of a
//! disagreement, and the summary of what was compared ([`SelfCheck`]).

use serde::{Deserialize, Serialize};

/// What the self-check compared.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SelfCheck {
    /// Seed of the independent seed stage.
    pub seed: u64,
    /// Pose indices re-solved.
    pub poses: Vec<usize>,
    /// Largest `|D_run − D_check| / max(D_run, D_floor)` over the checked (pose,
    /// metric) pairs, `D_floor = 10⁻¹² ×` the design's length scale.
    pub worst_relative_difference: f64,
    /// (Pose, metric) pairs where the check found a closer singular configuration.
    pub disagreements: usize,
    /// (Pose, metric) pairs where the run lost paths and the check, losing none,
    /// completed them: the check's result replaced the run's and its failures.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub completed: usize,
}

fn is_zero(count: &usize) -> bool {
    *count == 0
}

/// Relative difference above which the check's smaller distance counts as a missed
/// minimum of the run (plus an absolute `10⁻¹²` × the design's length scale).
pub const SELF_CHECK_TOLERANCE: f64 = 1e-8;

/// The seed of the check's stage: the run's seed plus 24,095.
pub(crate) fn check_seed(seed: u64) -> u64 {
    seed.wrapping_add(0x5e1f)
}

/// The pose indices a self-check re-solves among a window's poses `indices` (in
/// order): the first, the last, and per name the pose of the smallest
/// `distance(i, name)` (`i` the position in `indices`; `None`: no distance there).
/// Sorted, without repetitions.
pub(crate) fn checked_poses(
    indices: &[usize],
    names: &[String],
    distance: impl Fn(usize, &str) -> Option<f64>,
) -> Vec<usize> {
    let mut poses: Vec<usize> = indices.first().into_iter().copied().collect();
    poses.extend(indices.last());
    for name in names {
        let smallest = (0..indices.len())
            .filter_map(|i| distance(i, name).map(|d| (indices[i], d)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        poses.extend(smallest.map(|(j, _)| j));
    }
    poses.sort_unstable();
    poses.dedup();
    poses
}

impl SelfCheck {
    /// The check of a run made of windows: the checks of `self` and `later` (a later
    /// window) together — poses of both, the larger worst difference, the sum of the
    /// disagreements.
    pub fn merge(&mut self, later: &SelfCheck) {
        self.poses.extend(&later.poses);
        self.worst_relative_difference = self
            .worst_relative_difference
            .max(later.worst_relative_difference);
        self.disagreements += later.disagreements;
        self.completed += later.completed;
    }
}
