//! docs/theory.md §6: the generic root counts do not depend on the random source point —
//! the ab-initio stage run with a second seed (the stored files used the default seed)
//! finds the same number of certified, nonsingular solutions for every sub-problem.

use singdist::pipeline::ab_initio::{AbInitioOptions, compute_start_solutions, expected_count};
use singdist::problem::{LagrangeProblem, ProblemError, ProblemId};

#[test]
fn root_counts_are_the_same_for_a_second_source_seed() {
    let options = AbInitioOptions {
        seed: 7,
        ..AbInitioOptions::default()
    };
    for id in ProblemId::all() {
        let problem = match LagrangeProblem::new(id) {
            Err(ProblemError::NotApplicable { .. }) => continue,
            other => other.unwrap(),
        };
        let file = compute_start_solutions(&problem, &options).unwrap();
        assert!(
            file.certificate.passed,
            "{id}: certificate {:?}",
            file.certificate
        );
        assert!(
            file.max_residual < 1e-10,
            "{id}: residual {:e}",
            file.max_residual
        );
        let stored = singdist::pipeline::ab_initio::embedded_start_solutions(id)
            .unwrap()
            .unwrap();
        assert_eq!(
            file.solutions.len(),
            stored.solutions.len(),
            "{id}: count differs between seeds"
        );
        if let Some(expected) = expected_count(id) {
            assert_eq!(file.solutions.len(), expected, "{id}");
        }
    }
}
