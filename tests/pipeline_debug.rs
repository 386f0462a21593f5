//! Warms the start-solution cache of every sub-problem (run with `--ignored`).
mod pipeline_support;
use singdist::problem::{LagrangeProblem, ProblemId};

#[test]
#[ignore]
fn warm_start_cache() {
    for id in ProblemId::all() {
        if LagrangeProblem::new(id).is_err() {
            continue;
        }
        let t = std::time::Instant::now();
        let r = pipeline_support::cached_start_solutions(id);
        println!(
            "{} {:?} {:.1}s",
            id.name(),
            r.map(|s| s.solutions.len()),
            t.elapsed().as_secs_f64()
        );
    }
}
