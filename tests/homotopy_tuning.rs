//! Manual tuning aid (ignored): steps and time per preset on katsura-7 and cyclic-5.
mod homotopy_common;
use homotopy_common::*;
use singdist::homotopy::{SolveOptions, TrackerOptions, solve_total_degree};

#[test]
#[ignore]
fn presets_on_katsura_7() {
    let (system, degrees) = katsura_compiled(7);
    for (name, tracker) in [
        ("fast", TrackerOptions::fast()),
        ("default", TrackerOptions::default()),
        ("conservative", TrackerOptions::conservative()),
    ] {
        let options = SolveOptions {
            tracker,
            retry_failed: false,
            ..SolveOptions::default()
        };
        let start = std::time::Instant::now();
        let r = solve_total_degree(&system, &degrees, &[], &options).unwrap();
        let steps: usize = r.paths.iter().map(|p| p.steps).sum();
        let rejected: usize = r.paths.iter().map(|p| p.rejected_steps).sum();
        eprintln!(
            "{name}: {:?} steps/path {:.1} rejected/path {:.2} time {:.3}s",
            r.summary,
            steps as f64 / r.paths.len() as f64,
            rejected as f64 / r.paths.len() as f64,
            start.elapsed().as_secs_f64()
        );
        let c = cyclic(5);
        let r = solve_total_degree(&c, &c.degrees(), &[], &options).unwrap();
        let steps: usize = r.paths.iter().map(|p| p.steps).sum();
        eprintln!(
            "  cyclic5 {:?} steps/path {:.1}",
            r.summary,
            steps as f64 / r.paths.len() as f64
        );
    }
}
