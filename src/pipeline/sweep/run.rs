//! One driver for every mechanism's curve: a family of sub-problems swept over the
//! poses of a motion, window by window.
//!
//! A mechanism says what its sweep is made of ([`SweptFamily`]): its seed stage (the
//! generic start sets tracked to a seed point, the user homotopy of Kapilavai and
//! Nawratil, *Singularity distance computations for 3-RPR manipulators using extrinsic
//! metrics*, 2022, Eqs. 65–66), an independent seed stage for its self-check, how the
//! two reconcile their counts, how a range of poses is solved (chains of parameter
//! homotopies, Newton jumps, rescue: [`super::walk_chain`], [`super::rescue_lost_runs`])
//! and assembled, and how a window's poses are checked. [`Sweep`] runs the protocol
//! the same way for each of them:
//!
//! 1. the seed stage, once;
//! 2. the self-check's independent stage — over every sub-problem when the run checks
//!    itself, otherwise only over the sub-problems whose seed count is below the
//!    generic count of their start file (two seed points of one stage can agree on
//!    too few, and nothing else would notice) — and the reconciliation of the counts;
//! 3. the poses in consecutive windows, each final (solved, then checked) before the
//!    next one starts, so that a caller can write a window and drop it: memory is
//!    bounded by one window, and a run can start at any window (to resume) and gets
//!    the same results there.

use super::check::SelfCheck;
use std::ops::Range;

/// What a mechanism gives the [`Sweep`] (see the module documentation).
pub trait SweptFamily: Sync {
    /// The seed stage: every sub-problem's solutions at the seed point.
    type Stage: Sync;
    /// The self-check's independent seed stage (with whatever options it was run with).
    type Check: Sync;
    /// One pose's final result.
    type Pose: Send;
    /// What can stop a run.
    type Error;

    /// The number of poses of the run.
    fn pose_count(&self) -> usize;

    /// The run's seed stage.
    fn seed_stage(&self) -> Result<Self::Stage, Self::Error>;

    /// The self-check's independent seed stage: over every sub-problem (`all`), or
    /// only over the sub-problems of `stage` whose seed count is below their generic
    /// count (`None` when there are none).
    fn check_stage(
        &self,
        stage: &Self::Stage,
        all: bool,
    ) -> Result<Option<Self::Check>, Self::Error>;

    /// Reconciles the counts of the run's stage and the check's (the larger count of a
    /// sub-problem refutes the smaller).
    fn reconcile(&self, stage: &mut Self::Stage, check: &mut Self::Check);

    /// The poses of `poses.range` solved and assembled, in pose order, each handed to
    /// `poses.on_pose` as it completes (progress).
    fn solve_poses(
        &self,
        stage: &Self::Stage,
        poses: PoseRange<'_, Self::Pose>,
    ) -> Result<Vec<Self::Pose>, Self::Error>;

    /// A window's self-check: some of its poses (`poses`, consecutive, in order)
    /// solved again from the check's stage; what the check corrects is folded into
    /// them.
    fn check_poses(
        &self,
        stage: &Self::Stage,
        check: &Self::Check,
        poses: &mut [Self::Pose],
    ) -> Result<SelfCheck, Self::Error>;

    /// Paths tracked for one pose.
    fn paths_tracked(pose: &Self::Pose) -> usize;
}

/// Poses to solve: their index range and what to call as each completes.
pub struct PoseRange<'a, P> {
    /// The pose indices.
    pub range: Range<usize>,
    /// Called with each pose's result as it completes (progress).
    pub on_pose: &'a (dyn Fn(&P) + Sync),
}

/// One window's final results.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepWindow<P> {
    /// Index of the window (in [`Sweep::windows`]; 0 for a range solved on its own).
    pub index: usize,
    /// Its poses, in order.
    pub poses: Vec<P>,
    /// Paths tracked at its poses.
    pub paths_tracked: usize,
    /// Its self-check (first, last and each sub-problem's closest pose of the window).
    pub self_check: Option<SelfCheck>,
}

/// The pose index ranges `[first, last)` of the windows of `n` poses, `window_poses`
/// each (the last one shorter).
pub fn window_ranges(n: usize, window_poses: usize) -> Vec<Range<usize>> {
    let size = window_poses.max(1);
    (0..n.div_ceil(size))
        .map(|w| w * size..((w + 1) * size).min(n))
        .collect()
}

/// A family's curve being computed window by window (see the module documentation).
pub struct Sweep<F: SweptFamily> {
    family: F,
    stage: F::Stage,
    check: Option<F::Check>,
    windows: Vec<Range<usize>>,
}

impl<F: SweptFamily> Sweep<F> {
    /// Runs the seed stage and the self-check's (every sub-problem with `self_check`,
    /// otherwise only the short ones, to reconcile their counts), and cuts the poses
    /// into windows of `window_poses`.
    pub fn start(family: F, window_poses: usize, self_check: bool) -> Result<Self, F::Error> {
        let mut stage = family.seed_stage()?;
        let check = match family.check_stage(&stage, self_check)? {
            Some(mut check) => {
                family.reconcile(&mut stage, &mut check);
                self_check.then_some(check)
            }
            None => None,
        };
        let windows = window_ranges(family.pose_count(), window_poses);
        Ok(Sweep {
            family,
            stage,
            check,
            windows,
        })
    }

    /// The family swept.
    pub fn family(&self) -> &F {
        &self.family
    }

    /// The run's seed stage (after reconciliation).
    pub fn stage(&self) -> &F::Stage {
        &self.stage
    }

    /// The windows' pose ranges, in order.
    pub fn windows(&self) -> &[Range<usize>] {
        &self.windows
    }

    /// The pose range of window `index`.
    pub fn window_range(&self, index: usize) -> Range<usize> {
        self.windows[index].clone()
    }

    /// Solves window `index` completely: its poses, then its self-check.
    pub fn solve_window(
        &self,
        index: usize,
        on_pose: &(dyn Fn(&F::Pose) + Sync),
    ) -> Result<SweepWindow<F::Pose>, F::Error> {
        let window = self.solve_range(self.window_range(index), on_pose)?;
        Ok(SweepWindow { index, ..window })
    }

    /// Solves the poses `range` as one window (any range of the run: every pose is a
    /// function of its index and the stages alone, so a range's results are those of
    /// the whole curve there, up to which poses its self-check re-solves).
    pub fn solve_range(
        &self,
        range: Range<usize>,
        on_pose: &(dyn Fn(&F::Pose) + Sync),
    ) -> Result<SweepWindow<F::Pose>, F::Error> {
        let mut poses = (self.family).solve_poses(&self.stage, PoseRange { range, on_pose })?;
        let self_check = match &self.check {
            Some(check) => Some(self.family.check_poses(&self.stage, check, &mut poses)?),
            None => None,
        };
        Ok(SweepWindow {
            index: 0,
            paths_tracked: poses.iter().map(F::paths_tracked).sum(),
            poses,
            self_check,
        })
    }
}

/// Windows in order merged into one curve: every pose, the windows' self-checks merged
/// ([`SelfCheck::merge`]) and the paths they tracked.
pub fn merge_windows<P>(windows: Vec<SweepWindow<P>>) -> (Vec<P>, Option<SelfCheck>, usize) {
    let mut self_check: Option<SelfCheck> = None;
    let mut paths_tracked = 0;
    let mut poses = Vec::new();
    for window in windows {
        paths_tracked += window.paths_tracked;
        match (&mut self_check, window.self_check) {
            (Some(total), Some(check)) => total.merge(&check),
            (None, check) => self_check = check,
            (Some(_), None) => {}
        }
        poses.extend(window.poses);
    }
    (poses, self_check, paths_tracked)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// A scripted family: sub-problem counts at the seed (`generic` each), poses whose
    /// result is `(index, count of sub-problem 0 + index)`, a self-check that marks
    /// the poses it sees, and a log of the calls.
    struct Scripted {
        poses: usize,
        seed_counts: Vec<usize>,
        check_counts: Vec<usize>,
        generic: usize,
        log: Mutex<Vec<String>>,
    }

    impl Scripted {
        fn new(poses: usize, seed_counts: &[usize], check_counts: &[usize]) -> Self {
            Scripted {
                poses,
                seed_counts: seed_counts.to_vec(),
                check_counts: check_counts.to_vec(),
                generic: 4,
                log: Mutex::new(Vec::new()),
            }
        }

        fn note(&self, entry: String) {
            self.log.lock().unwrap().push(entry);
        }
    }

    impl SweptFamily for Scripted {
        type Stage = Vec<usize>;
        type Check = Vec<usize>;
        type Pose = (usize, usize);
        type Error = String;

        fn pose_count(&self) -> usize {
            self.poses
        }

        fn seed_stage(&self) -> Result<Vec<usize>, String> {
            self.note("seed".into());
            Ok(self.seed_counts.clone())
        }

        fn check_stage(&self, stage: &Vec<usize>, all: bool) -> Result<Option<Vec<usize>>, String> {
            let short = stage.iter().any(|&c| c < self.generic);
            self.note(format!("check all={all} short={short}"));
            Ok((all || short).then(|| self.check_counts.clone()))
        }

        fn reconcile(&self, stage: &mut Vec<usize>, check: &mut Vec<usize>) {
            self.note("reconcile".into());
            for (a, b) in stage.iter_mut().zip(check.iter_mut()) {
                let larger = (*a).max(*b);
                (*a, *b) = (larger, larger);
            }
        }

        fn solve_poses(
            &self,
            stage: &Vec<usize>,
            PoseRange { range, on_pose }: PoseRange<'_, (usize, usize)>,
        ) -> Result<Vec<(usize, usize)>, String> {
            if range.end > self.poses {
                return Err(format!("no pose {}", range.end - 1));
            }
            let poses: Vec<(usize, usize)> = range.map(|i| (i, stage[0] + i)).collect();
            poses.iter().for_each(on_pose);
            Ok(poses)
        }

        fn check_poses(
            &self,
            _stage: &Vec<usize>,
            check: &Vec<usize>,
            poses: &mut [(usize, usize)],
        ) -> Result<SelfCheck, String> {
            let checked: Vec<usize> = poses.iter().map(|p| p.0).collect();
            Ok(SelfCheck {
                seed: check[0] as u64,
                worst_relative_difference: checked.len() as f64,
                poses: checked,
                disagreements: 1,
                completed: 0,
            })
        }

        fn paths_tracked(pose: &(usize, usize)) -> usize {
            pose.1
        }
    }

    #[test]
    fn with_the_self_check_the_check_stage_covers_everything_and_is_kept() {
        let sweep = Sweep::start(Scripted::new(5, &[4, 4], &[4, 4]), 2, true).unwrap();
        let log = sweep.family().log.lock().unwrap().clone();
        assert_eq!(log, ["seed", "check all=true short=false", "reconcile"]);
        let window = sweep.solve_window(1, &|_| {}).unwrap();
        assert_eq!(window.index, 1);
        assert_eq!(window.poses, [(2, 6), (3, 7)]);
        assert_eq!(window.paths_tracked, 13);
        assert_eq!(window.self_check.unwrap().poses, [2, 3]);
    }

    #[test]
    fn without_the_self_check_only_a_short_stage_is_checked_and_reconciled() {
        // Nothing short: no check stage at all.
        let sweep = Sweep::start(Scripted::new(3, &[4, 4], &[4, 4]), 2, false).unwrap();
        let log = sweep.family().log.lock().unwrap().clone();
        assert_eq!(log, ["seed", "check all=false short=false"]);
        assert!(sweep.solve_window(0, &|_| {}).unwrap().self_check.is_none());
        // A short count is raised by the check's, and the check is not kept.
        let sweep = Sweep::start(Scripted::new(3, &[3, 4], &[4, 2]), 2, false).unwrap();
        let log = sweep.family().log.lock().unwrap().clone();
        assert_eq!(log, ["seed", "check all=false short=true", "reconcile"]);
        assert_eq!(sweep.stage(), &[4, 4]);
        let window = sweep.solve_window(0, &|_| {}).unwrap();
        assert_eq!(window.poses, [(0, 4), (1, 5)]);
        assert!(window.self_check.is_none());
    }

    #[test]
    fn windows_cover_the_poses_in_order_and_merge_into_the_whole_curve() {
        let sweep = Sweep::start(Scripted::new(5, &[4], &[7]), 2, true).unwrap();
        assert_eq!(sweep.windows(), [0..2, 2..4, 4..5]);
        let seen = Mutex::new(Vec::new());
        let on_pose = |p: &(usize, usize)| seen.lock().unwrap().push(p.0);
        let windows: Vec<_> = (0..3)
            .map(|w| sweep.solve_window(w, &on_pose).unwrap())
            .collect();
        assert_eq!(*seen.lock().unwrap(), [0, 1, 2, 3, 4]);
        let whole = sweep.solve_range(0..5, &|_| {}).unwrap();
        let (poses, check, paths) = merge_windows(windows);
        assert_eq!(poses, whole.poses);
        assert_eq!(paths, whole.paths_tracked);
        let check = check.unwrap();
        assert_eq!(check.poses, [0, 1, 2, 3, 4]);
        assert_eq!(check.seed, 7);
        assert_eq!(check.worst_relative_difference, 2.0);
        assert_eq!(check.disagreements, 3);
    }

    #[test]
    fn a_family_error_stops_the_window() {
        let sweep = Sweep::start(Scripted::new(2, &[4], &[4]), 2, true).unwrap();
        assert_eq!(
            sweep.solve_range(1..3, &|_| {}).unwrap_err(),
            "no pose 2".to_string()
        );
    }

    #[test]
    fn window_ranges_cut_the_poses_and_shorten_the_last() {
        assert_eq!(window_ranges(5, 2), [0..2, 2..4, 4..5]);
        assert_eq!(window_ranges(4, 0), [0..1, 1..2, 2..3, 3..4]);
        assert!(window_ranges(0, 3).is_empty());
    }
}
