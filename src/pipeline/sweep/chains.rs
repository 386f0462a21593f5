//! The chain scheduler of the sweep engine, one for every mechanism: which poses are
//! solved one after the other (each from its predecessor's complete solution set),
//! where a chain starts from the seed, and in which order a chain is walked.
//!
//! Parameter homotopy from a complete solution set at one parameter point reaches
//! every isolated solution at a nearby generic one (Morgan and Sommese,
//! *Coefficient-parameter polynomial continuation*, Appl. Math. Comput. 29, 1989); the
//! shorter the step, the cheaper the paths. A chain therefore follows poses in an
//! order where neighbours are close, and a new chain (from the seed) starts where the
//! next pose is far.

/// Largest step between consecutive poses that a chain continues across: the
/// largest coordinate change of the normalised configuration (units of the RMS size
/// of the configuration). Across a larger step the Newton jumps and pose-to-pose
/// paths of a chain cost more than the seed route (30 scattered poses of the 3-RPR
/// example design: chained through every step 2.2 × the CPU time of the seed route
/// per pose), so a new chain starts there. The 3-RPR example's steps are 0.05.
pub const FAR_POSE_STEP: f64 = 0.25;

/// The poses `range` in nearest-neighbour order: from the first, always on to the
/// nearest pose not yet visited by `distance` (the first of equally near ones).
pub(crate) fn nearest_neighbour_order(
    range: std::ops::Range<usize>,
    distance: &dyn Fn(usize, usize) -> f64,
) -> Vec<usize> {
    let mut left: Vec<usize> = range.collect();
    let mut order = Vec::with_capacity(left.len());
    if left.is_empty() {
        return order;
    }
    order.push(left.remove(0));
    while !left.is_empty() {
        let last = *order.last().expect("a pose");
        let (k, _) = left
            .iter()
            .enumerate()
            .map(|(k, &j)| (k, distance(last, j)))
            .fold(
                (0, f64::INFINITY),
                |best, c| if c.1 < best.1 { c } else { best },
            );
        order.push(left.remove(k));
    }
    order
}

/// The chains over the poses `range`, each as its pose indices in chain order: the
/// poses in motion order (`ordered_motion`: an analytic motion, in the order of τ) or
/// else in nearest-neighbour order ([`nearest_neighbour_order`]: an explicit pose
/// list), cut into chains of at most `chain_length` poses and wherever consecutive
/// poses are more than [`FAR_POSE_STEP`] apart by `step`. Depends on the poses only.
pub(crate) fn chains_over(
    range: std::ops::Range<usize>,
    step: &dyn Fn(usize, usize) -> f64,
    ordered_motion: bool,
    chain_length: usize,
) -> Vec<Vec<usize>> {
    let order: Vec<usize> = if ordered_motion {
        range.collect()
    } else {
        nearest_neighbour_order(range, step)
    };
    let mut chains: Vec<Vec<usize>> = Vec::new();
    for (i, &j) in order.iter().enumerate() {
        let split = match chains.last() {
            None => true,
            Some(chain) => {
                chain.len() >= chain_length.max(1) || step(order[i - 1], j) > FAR_POSE_STEP
            }
        };
        if split {
            chains.push(Vec::new());
        }
        chains.last_mut().expect("a chain").push(j);
    }
    chains
}

/// The anchor of a chain of poses with motion parameters `taus` (in chain order): the
/// pose nearest `Re τ*` of the seed (the shortest seed route), or the first one when
/// the seed is not a point of the motion (pose lists).
pub(crate) fn chain_anchor(taus: impl Iterator<Item = f64>, seed_tau: Option<f64>) -> usize {
    let Some(target) = seed_tau else {
        return 0;
    };
    taus.enumerate()
        .min_by(|a, b| (a.1 - target).abs().total_cmp(&(b.1 - target).abs()))
        .map_or(0, |(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pose_lists_are_chained_in_nearest_neighbour_order() {
        // Poses on a line at 0, 5, 1, 4, 2, 3: visited 0, 1, 2, 3, 4, 5 by position.
        let at: [f64; 6] = [0.0, 5.0, 1.0, 4.0, 2.0, 3.0];
        let distance = |a: usize, b: usize| (at[a] - at[b]).abs();
        assert_eq!(
            nearest_neighbour_order(0..6, &distance),
            vec![0, 2, 4, 5, 3, 1]
        );
        let ties = |_: usize, _: usize| 1.0;
        assert_eq!(nearest_neighbour_order(10..13, &ties), vec![10, 11, 12]);
        assert!(nearest_neighbour_order(3..3, &ties).is_empty());
    }

    #[test]
    fn chains_split_at_far_steps_and_at_their_length() {
        // Positions 0, 0.1, 0.2, 5, 5.1 (far step between 0.2 and 5).
        let at: [f64; 5] = [0.0, 0.1, 0.2, 5.0, 5.1];
        let step = |a: usize, b: usize| (at[a] - at[b]).abs();
        assert_eq!(
            chains_over(0..5, &step, true, 10),
            vec![vec![0, 1, 2], vec![3, 4]]
        );
        assert_eq!(
            chains_over(0..5, &step, true, 2),
            vec![vec![0, 1], vec![2], vec![3, 4]]
        );
        // Out of order: the nearest-neighbour order joins the near poses first.
        let at: [f64; 4] = [0.0, 5.0, 0.1, 5.1];
        let step = |a: usize, b: usize| (at[a] - at[b]).abs();
        assert_eq!(
            chains_over(0..4, &step, false, 10),
            vec![vec![0, 2], vec![1, 3]]
        );
        assert_eq!(
            chains_over(0..4, &step, true, 10),
            vec![vec![0], vec![1], vec![2], vec![3]]
        );
        assert!(chains_over(2..2, &step, true, 10).is_empty());
    }

    #[test]
    fn the_anchor_is_the_pose_nearest_the_seed() {
        let taus = [0.0, 0.1, 0.2, 0.3];
        assert_eq!(chain_anchor(taus.iter().copied(), Some(0.21)), 2);
        assert_eq!(chain_anchor(taus.iter().copied(), Some(-4.0)), 0);
        assert_eq!(chain_anchor(taus.iter().copied(), None), 0);
    }
}
