//! 3-RRR sub-problems (SPEC Part C): start files, root counts, residuals.
use singdist::pipeline::rrr_ab_initio::*;
use singdist::problem::rrr::*;

#[test]
#[ignore]
fn explore_counts() {
    for kind in RrrSubProblem::ALL {
        let problem = RrrProblem::new(kind).unwrap();
        for seed in [1u64, 2] {
            let t = std::time::Instant::now();
            let opts = RrrAbInitioOptions { seed, ..Default::default() };
            let file = compute_rrr_start_solutions(&problem, &opts).unwrap();
            println!("{} seed {} count {} cert {:?} resid {:e} time {:?}", kind.name(), seed, file.solutions.len(), file.certificate, file.max_residual, t.elapsed());
        }
    }
}
