//! Lost homotopy paths as the user sees them: the stderr warning and the per-pose count
//! written into CSV tables.

use singdist::pipeline::curve::PathFailure;

/// Paths lost at one pose: the pose's own failures plus those of the seed stage
/// (`pose_index` = `None` in `all`), which affect every pose, each counted as
/// `expected − accounted`.
pub fn lost_paths(pose_failures: &[PathFailure], all: &[PathFailure]) -> usize {
    all.iter()
        .filter(|f| f.pose_index.is_none())
        .chain(pose_failures)
        .map(|f| f.expected.saturating_sub(f.accounted))
        .sum()
}

/// Prints a warning listing lost paths; returns whether there were any.
pub fn warn_failures(failures: &[PathFailure]) -> bool {
    if failures.is_empty() {
        return false;
    }
    let list: Vec<String> = failures
        .iter()
        .map(|f| {
            let why = if f.reasons.is_empty() {
                String::new()
            } else {
                let reasons: Vec<String> =
                    f.reasons.iter().map(|(r, n)| format!("{r} {n}")).collect();
                format!(" (reference route: {})", reasons.join(", "))
            };
            let lost = f.expected.saturating_sub(f.accounted);
            match (f.pose_index, f.tau) {
                (Some(j), Some(tau)) => format!(
                    "pose {j} (tau = {tau:.6}) {}: {lost} of {} paths failed{why}",
                    f.problem, f.expected
                ),
                _ => format!(
                    "seed {}: {lost} of {} paths failed{why}",
                    f.problem, f.expected
                ),
            }
        })
        .collect();
    const SHOWN: usize = 8;
    let more = list.len().saturating_sub(SHOWN);
    eprintln!(
        "singdist: warning: {} (pose, sub-problem) group(s) lost paths after re-runs (results may miss critical points; all listed under `failures` in the output): {}{}",
        failures.len(),
        list[..list.len().min(SHOWN)].join("; "),
        if more > 0 {
            format!("; … and {more} more")
        } else {
            String::new()
        }
    );
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn failure(pose_index: Option<usize>, expected: usize, accounted: usize) -> PathFailure {
        PathFailure {
            pose_index,
            tau: pose_index.map(|j| j as f64),
            problem: "rigid/rigid:singularity".into(),
            expected,
            accounted,
            reasons: Default::default(),
        }
    }

    #[test]
    fn seed_losses_count_at_every_pose() {
        let seed = failure(None, 88, 87);
        let at_two = failure(Some(2), 80, 77);
        let all = vec![seed, at_two.clone()];
        assert_eq!(lost_paths(&[], &all), 1);
        assert_eq!(lost_paths(&[at_two], &all), 4);
    }
}
