//! The sweep engine shared by every mechanism: one driver for a curve ([`Sweep`] over
//! a [`SweptFamily`]: seed stage, self-check stage, windows), one chain walk and
//! rescue, and, given a parametrised family over a motion ([`super::family::Family`]),
//! the seed stage that tracks the family's start set to a seed
//! point (the user homotopy of Kapilavai and Nawratil, *Singularity distance
//! computations for 3-RPR manipulators using extrinsic metrics*, Eqs. 65–66) with the
//! robust path-group tracking and its accounting (`track_with_retries`): re-runs,
//! arcs around divergences, detours, path crossings, and every path either finite, at
//! infinity, or reported as lost ([`PathFailure`]).

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

mod chains;
mod check;
mod jump;
mod retry;
mod run;
mod seed;
mod twin;
mod walk;
pub use chains::FAR_POSE_STEP;
pub(crate) use chains::{chain_anchor, chains_over};
pub use check::{SELF_CHECK_TOLERANCE, SelfCheck};
pub(crate) use check::{check_seed, checked_poses};
pub(crate) use jump::{JUMP_HISTORY, JumpRoutes, jump_set};
pub(crate) use retry::*;
pub use run::{PoseRange, Sweep, SweepWindow, SweptFamily, merge_windows, window_ranges};
pub(crate) use seed::{
    MonodromyLoops, completed_by_monodromy, first_run, seed_family, split_seeded,
};
pub use seed::{SeedPolicy, SeedSolutions, Seeded, distinct_solutions, seed_count_confirmed};
pub use twin::ProjectiveTwin;
pub(crate) use walk::{
    ChainHistory, ChainRoutes, Rescued, lost_runs, rescue_lost_runs, rescue_run, solve_in_chain,
    walk_chain,
};

/// A path (or group of paths) lost at some pose, reported instead of dropped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathFailure {
    /// Index of the pose (`None` for the seed stage, which affects every pose).
    pub pose_index: Option<usize>,
    /// τ of the pose.
    pub tau: Option<f64>,
    /// The problem's name, e.g. `PLATFORM/BASE:SUBPROBLEM` or `rrr:leg2`.
    pub problem: String,
    /// Start-solution count.
    pub expected: usize,
    /// Paths whose endpoint was classified (finite, or at infinity), best attempt; the
    /// difference to `expected` is the number of paths that failed.
    pub accounted: usize,
    /// Why paths were unaccounted for on the reference route after the careful
    /// re-runs, by reason: a [`crate::homotopy::FailureReason`] name (e.g.
    /// `TooManySteps`), or `PathCrossing` for a path that ended on another one's
    /// endpoint. The detours may have recovered some of them since.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub reasons: BTreeMap<String, usize>,
}

#[cfg(test)]
mod tests;
