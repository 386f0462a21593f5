//! The chain walk of the sweep engine, one rule for every mechanism: how one
//! sub-problem is solved at the next pose of a chain from the poses before it.
//!
//! A chain visits its poses in chain order (the anchor from the seed, then forwards
//! and backwards from it, [`super::chains_over`]). At each pose a sub-problem is
//! solved, in this order of routes:
//!
//! 1. *Newton jumps* from the complete solution sets of the preceding poses
//!    (extrapolated along the chain), where the family has them;
//! 2. a *pose-to-pose homotopy* from the latest complete set: parameter homotopy from
//!    a complete set of isolated solutions reaches every isolated solution at a
//!    generic target (Morgan and Sommese, *Coefficient-parameter polynomial
//!    continuation*, Appl. Math. Comput. 29, 1989);
//! 3. the *seed route* (with its re-runs and detours), the reference, where neither
//!    of the others reaches a complete set; of a pose-to-pose result and the seed
//!    route's, the one accounting for more paths is kept, and the paths of both count.
//!
//! A chain only passes on a complete set (as many distinct finite solutions as the
//! seed has, every path accounted for), so it can never pass on a loss; after the seed
//! route the history starts afresh (its solutions are in another order).
//!
//! Poses that still lost paths are rescued afterwards from their complete neighbours
//! in pose order ([`rescue_run`]).

use std::collections::BTreeMap;

/// What a mechanism provides for one sub-problem along one chain: its three routes to
/// a pose and how their outcomes are judged. Poses are the caller's indices.
pub(crate) trait ChainRoutes {
    /// A complete solution set at a pose (what the next pose starts from).
    type Set: Clone;
    /// The sub-problem's outcome at a pose.
    type Outcome;

    /// The seed route to pose `pose`.
    fn seed_route(&self, pose: usize) -> Self::Outcome;

    /// The pose-to-pose homotopy from `set`, complete at pose `previous`, to `pose`.
    fn neighbour_route(&self, pose: usize, previous: usize, set: &Self::Set) -> Self::Outcome;

    /// Newton jumps to `pose` from the complete sets of the preceding poses (`history`,
    /// latest first; the latest at pose `previous`): `Some` only for a complete
    /// outcome whose solutions are in the order of `history`. None by default.
    fn jump(
        &self,
        _pose: usize,
        _previous: usize,
        _history: &[Self::Set],
    ) -> Option<Self::Outcome> {
        None
    }

    /// The complete set of `outcome`, if it is complete (a copy: the next pose starts
    /// from it).
    fn complete_set(&self, outcome: &Self::Outcome) -> Option<Self::Set>;

    /// Whether `outcome` is complete, without copying its set.
    fn is_complete(&self, outcome: &Self::Outcome) -> bool;

    /// Paths `outcome` accounts for (finite or at infinity).
    fn accounted(&self, outcome: &Self::Outcome) -> usize;

    /// Paths tracked for `outcome` (re-runs and detours included).
    fn tracked<'o>(&self, outcome: &'o mut Self::Outcome) -> &'o mut usize;

    /// Whether `outcome` lost paths (some path neither finite nor at infinity).
    fn lost(&self, outcome: &Self::Outcome) -> bool;
}

/// The complete sets of a sub-problem's last poses along a chain (latest first) and
/// the latest pose: what the next pose starts from.
#[derive(Clone, Debug)]
pub(crate) struct ChainHistory<S> {
    /// The pose solved last.
    pub latest: usize,
    /// Complete sets of the last poses, latest first, in one solution order.
    pub sets: Vec<S>,
    /// How many sets are kept (the Newton jumps' extrapolation order).
    keep: usize,
}

impl<S> ChainHistory<S> {
    /// An empty history at the chain's anchor `anchor`, keeping `keep` sets.
    pub fn new(anchor: usize, keep: usize) -> Self {
        ChainHistory {
            latest: anchor,
            sets: Vec::new(),
            keep: keep.max(1),
        }
    }

    /// Records pose `pose`'s complete set (`None`: incomplete, the history is
    /// cleared); `same_order`: its solutions are in the order of the history's sets
    /// (else the history starts afresh with it).
    fn record(&mut self, pose: usize, set: Option<S>, same_order: bool) {
        if !same_order {
            self.sets.clear();
        }
        match set {
            Some(set) => {
                self.sets.insert(0, set);
                self.sets.truncate(self.keep);
            }
            None => self.sets.clear(),
        }
        self.latest = pose;
    }
}

/// The sub-problem at pose `pose` after the poses of `history` (module
/// documentation), and the history updated with it.
pub(crate) fn solve_in_chain<R: ChainRoutes>(
    routes: &R,
    pose: usize,
    history: &mut ChainHistory<R::Set>,
) -> R::Outcome {
    let previous = history.latest;
    let jumped = if history.sets.is_empty() {
        None
    } else {
        routes.jump(pose, previous, &history.sets)
    };
    let (outcome, same_order) = match jumped {
        Some(jumped) => (jumped, true),
        None => {
            let neighbour = history
                .sets
                .first()
                .map(|set| routes.neighbour_route(pose, previous, set));
            match neighbour {
                Some(result) if routes.is_complete(&result) => (result, true),
                neighbour => {
                    let mut result = routes.seed_route(pose);
                    if let Some(mut neighbour) = neighbour {
                        let tracked =
                            *routes.tracked(&mut result) + *routes.tracked(&mut neighbour);
                        if routes.accounted(&neighbour) > routes.accounted(&result) {
                            result = neighbour;
                        }
                        *routes.tracked(&mut result) = tracked;
                    }
                    (result, false)
                }
            }
        }
    };
    history.record(pose, routes.complete_set(&outcome), same_order);
    outcome
}

/// One sub-problem along a whole chain, `order[0]` its anchor (from the seed) and
/// `anchor_then` the poses after it (forwards) and before it (backwards, nearest
/// first), each direction continuing from the anchor: the outcomes in the order
/// anchor, forwards, backwards.
pub(crate) fn walk_chain<R: ChainRoutes>(
    routes: &R,
    anchor: usize,
    [forwards, backwards]: [&[usize]; 2],
    keep: usize,
) -> Vec<(usize, R::Outcome)> {
    let mut history = ChainHistory::new(anchor, keep);
    let mut out = vec![(anchor, solve_in_chain(routes, anchor, &mut history))];
    let at_anchor = history.clone();
    for &pose in forwards {
        out.push((pose, solve_in_chain(routes, pose, &mut history)));
    }
    history = at_anchor;
    for &pose in backwards {
        out.push((pose, solve_in_chain(routes, pose, &mut history)));
    }
    out
}

/// The runs `(first, last)` of consecutive poses `0..n` (in pose order) at which
/// `lost(pose)` holds.
pub(crate) fn lost_runs(n: usize, lost: impl Fn(usize) -> bool) -> Vec<(usize, usize)> {
    let mut runs = Vec::new();
    let mut j = 0;
    while j < n {
        if lost(j) {
            let first = j;
            while j + 1 < n && lost(j + 1) {
                j += 1;
            }
            runs.push((first, j));
        }
        j += 1;
    }
    runs
}

/// What the rescue of one run of poses reached: the outcomes that account for more
/// paths than before, and the paths tracked, by pose.
pub(crate) struct Rescued<O> {
    pub improved: BTreeMap<usize, O>,
    pub tracked: BTreeMap<usize, usize>,
}

/// The rescue of the run `first..=last` of consecutive poses (in pose order) at which
/// a sub-problem lost paths, from its complete neighbours: pose by pose forward from
/// the pose before the run, then backward from the pose after it for what is still
/// incomplete. Near a pose the solutions move little, so short pose-to-pose paths
/// follow solutions that the long seed routes lose (e.g. huge ill-conditioned ones).
/// The poses are `offset..offset + n`; `outcome(j)` is pose `offset + j`'s outcome so
/// far, and the result is by `j` too. A result is kept where it accounts for more
/// paths than the best so far.
pub(crate) fn rescue_run<'v, R: ChainRoutes>(
    routes: &R,
    outcome: &dyn Fn(usize) -> &'v R::Outcome,
    (offset, n): (usize, usize),
    (first, last): (usize, usize),
) -> Rescued<R::Outcome>
where
    R::Outcome: 'v,
{
    let mut rescued = Rescued {
        improved: BTreeMap::new(),
        tracked: BTreeMap::new(),
    };
    // Solves pose `to` from the complete set at pose `from`; returns the complete set
    // at `to`, if reached.
    let mut step = |from: usize, to: usize, set: &R::Set| {
        let mut result = routes.neighbour_route(offset + to, offset + from, set);
        *rescued.tracked.entry(to).or_default() += *routes.tracked(&mut result);
        let best = rescued
            .improved
            .get(&to)
            .map_or(routes.accounted(outcome(to)), |r| routes.accounted(r));
        let complete = routes.complete_set(&result);
        if routes.accounted(&result) > best {
            rescued.improved.insert(to, result);
        }
        complete
    };
    let mut reached = first;
    if first > 0
        && let Some(mut set) = routes.complete_set(outcome(first - 1))
    {
        while reached <= last {
            match step(reached - 1, reached, &set) {
                Some(next) => {
                    set = next;
                    reached += 1;
                }
                None => break,
            }
        }
    }
    if reached <= last
        && last + 1 < n
        && let Some(mut set) = routes.complete_set(outcome(last + 1))
    {
        let mut j = last;
        while j >= reached {
            match step(j + 1, j, &set) {
                Some(next) if j > reached => {
                    set = next;
                    j -= 1;
                }
                _ => break,
            }
        }
    }
    rescued
}

/// The rescue pass ([`rescue_run`]) over poses `0..outcomes.len()` solved in one
/// thread (`outcomes` in pose order): every run of poses that lost paths is solved
/// again from its complete neighbours; a result accounting for more paths replaces the
/// pose's, and every path tracked counts. (Runs are separated by poses that lost
/// nothing, so each run starts from the same neighbours in any order.)
pub(crate) fn rescue_lost_runs<R: ChainRoutes>(routes: &R, outcomes: &mut [R::Outcome]) {
    let n = outcomes.len();
    for run in lost_runs(n, |j| routes.lost(&outcomes[j])) {
        let view: &[R::Outcome] = outcomes;
        let Rescued { improved, tracked } = rescue_run(routes, &|j| &view[j], (0, n), run);
        for (j, count) in tracked {
            *routes.tracked(&mut outcomes[j]) += count;
        }
        for (j, mut result) in improved {
            *routes.tracked(&mut result) = *routes.tracked(&mut outcomes[j]);
            outcomes[j] = result;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    /// Outcome `(accounted, tracked, route, pose)`; complete when 4 paths are
    /// accounted, its set then the pose itself.
    type Outcome = (usize, usize, &'static str, usize);

    /// Routes whose pose-to-pose homotopy reaches a complete set only at the poses of
    /// `neighbour_complete`, jumps only at the poses of `jumps`, and that log every
    /// route taken as `(route, pose, previous)`.
    struct Scripted {
        neighbour_complete: Vec<usize>,
        jumps: Vec<usize>,
        /// Paths the seed route accounts for, by pose.
        seed_accounted: Vec<usize>,
        log: RefCell<Vec<(&'static str, usize, usize)>>,
    }

    impl ChainRoutes for Scripted {
        type Set = usize;
        type Outcome = Outcome;

        fn seed_route(&self, pose: usize) -> Outcome {
            self.log.borrow_mut().push(("seed", pose, pose));
            (self.seed_accounted[pose], 10, "seed", pose)
        }

        fn neighbour_route(&self, pose: usize, previous: usize, set: &usize) -> Outcome {
            assert_eq!(*set, previous, "the latest set is the previous pose's");
            self.log.borrow_mut().push(("neighbour", pose, previous));
            if self.neighbour_complete.contains(&pose) {
                (4, 3, "neighbour", pose)
            } else {
                (3, 3, "neighbour", pose)
            }
        }

        fn jump(&self, pose: usize, previous: usize, history: &[usize]) -> Option<Outcome> {
            (self.jumps.contains(&pose) && history.len() >= 2).then(|| {
                self.log.borrow_mut().push(("jump", pose, previous));
                (4, 0, "jump", pose)
            })
        }

        fn complete_set(&self, outcome: &Outcome) -> Option<usize> {
            self.is_complete(outcome).then_some(outcome.3)
        }

        fn is_complete(&self, outcome: &Outcome) -> bool {
            outcome.0 == 4
        }

        fn accounted(&self, outcome: &Outcome) -> usize {
            outcome.0
        }

        fn tracked<'o>(&self, outcome: &'o mut Outcome) -> &'o mut usize {
            &mut outcome.1
        }

        fn lost(&self, outcome: &Outcome) -> bool {
            outcome.0 < 4
        }
    }

    fn scripted(
        neighbour_complete: &[usize],
        jumps: &[usize],
        seed_accounted: &[usize],
    ) -> Scripted {
        Scripted {
            neighbour_complete: neighbour_complete.to_vec(),
            jumps: jumps.to_vec(),
            seed_accounted: seed_accounted.to_vec(),
            log: RefCell::new(Vec::new()),
        }
    }

    /// The anchor from the seed, both directions from the anchor's set, each pose
    /// from its predecessor in chain order.
    #[test]
    fn both_directions_continue_from_the_anchor() {
        let routes = scripted(&[0, 1, 3, 4], &[], &[4; 5]);
        let out = walk_chain(&routes, 2, [&[3, 4], &[1, 0]], 1);
        let order: Vec<usize> = out.iter().map(|(p, _)| *p).collect();
        assert_eq!(order, [2, 3, 4, 1, 0]);
        let expected = [("seed", 2, 2), ("neighbour", 3, 2), ("neighbour", 4, 3)];
        assert_eq!(routes.log.borrow()[..3], expected);
        assert_eq!(
            routes.log.borrow()[3..],
            [("neighbour", 1, 2), ("neighbour", 0, 1)]
        );
    }

    /// An incomplete pose-to-pose result sends the pose to the seed route; the better
    /// accounted of the two is kept, the paths of both count, and an incomplete pose
    /// passes nothing on (the next pose takes the seed route directly).
    #[test]
    fn an_incomplete_neighbour_falls_back_to_the_seed_and_passes_nothing_on() {
        // An incomplete anchor: every pose takes the seed route.
        let routes = scripted(&[], &[], &[2, 2, 2]);
        let out = walk_chain(&routes, 0, [&[1, 2], &[]], 1);
        assert_eq!(out[1].1, (2, 10, "seed", 1));
        assert_eq!(
            *routes.log.borrow(),
            [("seed", 0, 0), ("seed", 1, 1), ("seed", 2, 2)]
        );
        // A complete anchor; pose 1's neighbour route (3 paths) is incomplete and its
        // seed route accounts for fewer (2): the neighbour's result stays, with the
        // paths of both, and pose 2 starts from the seed again.
        let routes = scripted(&[2], &[], &[4, 2, 4]);
        let out = walk_chain(&routes, 0, [&[1, 2], &[]], 1);
        assert_eq!(out[1].1, (3, 13, "neighbour", 1));
        assert_eq!(out[2].1, (4, 10, "seed", 2));
        let expected = [("seed", 0, 0), ("neighbour", 1, 0), ("seed", 1, 1)];
        assert_eq!(routes.log.borrow()[..3], expected);
        assert_eq!(routes.log.borrow()[3..], [("seed", 2, 2)]);
        // A seed route accounting for more wins, the paths of both still count.
        let routes = scripted(&[], &[], &[4, 4]);
        let out = walk_chain(&routes, 0, [&[1], &[]], 1);
        assert_eq!(out[1].1, (4, 13, "seed", 1));
    }

    /// Newton jumps come first once the history holds enough sets, and a seed route
    /// starts the history afresh.
    #[test]
    fn jumps_come_first_and_the_seed_route_restarts_the_history() {
        let routes = scripted(&[1, 2], &[3, 5], &[4; 6]);
        let out = walk_chain(&routes, 0, [&[1, 2, 3, 4, 5], &[]], 3);
        let taken: Vec<&str> = out.iter().map(|(_, o)| o.2).collect();
        // Pose 3 jumps (history 2, 1, 0). Pose 4's neighbour route is incomplete, so it
        // takes the seed route, after which pose 5 has one set only: no jump.
        assert_eq!(
            taken,
            ["seed", "neighbour", "neighbour", "jump", "seed", "seed"]
        );
        let mut history = ChainHistory::new(0, 3);
        history.record(1, Some(1), true);
        history.record(2, Some(2), true);
        history.record(3, Some(3), false);
        assert_eq!(history.sets, [3]);
        history.record(4, None, true);
        assert!(history.sets.is_empty());
        assert_eq!(history.latest, 4);
    }

    /// Lost poses are rescued from complete neighbours: forward from the pose before
    /// a run, backward from the pose after it where the forward pass stopped; poses
    /// that lost nothing and runs without a complete neighbour stay as they were.
    #[test]
    fn lost_runs_are_rescued_from_complete_neighbours() {
        assert_eq!(
            lost_runs(7, |j| [1, 2, 3, 5].contains(&j)),
            [(1, 3), (5, 5)]
        );
        // Pose-to-pose paths complete at poses 1 and 3 only: pose 1 forward from 0;
        // pose 2 forward fails (3 paths, kept: more than the seed's 2), then backward
        // from 4 reaches 3 and pose 2 again; pose 5 from 4 (forward) is complete.
        let routes = scripted(&[1, 3, 5], &[], &[]);
        let complete = |pose| (4, 10, "seed", pose);
        let lost = |pose| (2, 10, "seed", pose);
        let mut outcomes = [0, 1, 2, 3, 4, 5, 6].map(lost);
        for j in [0, 4, 6] {
            outcomes[j] = complete(j);
        }
        rescue_lost_runs(&routes, &mut outcomes);
        let expected = [
            ("neighbour", 1, 0),
            ("neighbour", 2, 1),
            ("neighbour", 3, 4),
        ];
        assert_eq!(routes.log.borrow()[..3], expected);
        assert_eq!(
            routes.log.borrow()[3..],
            [("neighbour", 2, 3), ("neighbour", 5, 4)]
        );
        assert_eq!(outcomes[1], (4, 13, "neighbour", 1));
        // Pose 2: tried twice (3 + 3 paths), 3 accounted for, still lost.
        assert_eq!(outcomes[2], (3, 16, "neighbour", 2));
        assert_eq!(outcomes[3], (4, 13, "neighbour", 3));
        assert_eq!(outcomes[5], (4, 13, "neighbour", 5));
        assert_eq!(
            [outcomes[0], outcomes[4], outcomes[6]],
            [0, 4, 6].map(complete)
        );
        // Without a complete neighbour nothing is tried.
        let routes = scripted(&[1], &[], &[]);
        let mut outcomes = [0, 1].map(lost);
        rescue_lost_runs(&routes, &mut outcomes);
        assert!(routes.log.borrow().is_empty());
        assert_eq!(outcomes, [0, 1].map(lost));
    }
}
