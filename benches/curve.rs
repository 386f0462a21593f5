//! Distance-to-singularity curve of the built-in example (docs/theory.md §8): seed stage
//! plus the pose stage (one chain: the pose nearest `Re τ*` by the seed → pose homotopy
//! along the complexified motion, every next one, forwards and backwards from it, by
//! Newton's method from extrapolated critical
//! points, with Newton sub-steps and pose-to-pose paths where that fails), 90 poses, on
//! 2 threads, with the embedded start files. `SINGDIST_BENCH_METRICS` selects the metrics (default
//! `all`).

use criterion::{Criterion, criterion_group, criterion_main};
use singdist::mechanism::rpr::{example_design, example_motion};
use singdist::metric::Metric;
use singdist::pipeline::curve::{CurveOptions, compute_curve_from_embedded_starts};

mod bench_support;
use bench_support::{thread_pool, timed};

fn bench_curve(c: &mut Criterion) {
    let list = std::env::var("SINGDIST_BENCH_METRICS").unwrap_or_else(|_| "all".into());
    let metrics = Metric::parse_list(&list).expect("SINGDIST_BENCH_METRICS: metric list");
    let design = example_design();
    let motion = example_motion();
    let pool = thread_pool(2);
    let options = CurveOptions::default();
    let run = || {
        pool.install(|| {
            compute_curve_from_embedded_starts(&design, &motion, 90, &metrics, &options)
                .expect("curve")
        })
    };
    // One reported run: wall time, per-pose latency, paths per second, failures.
    let (result, seconds) = timed(run);
    eprintln!(
        "curve: {} metrics x 90 poses, 2 threads: {seconds:.3} s, {:.2} ms/pose, {} critical points continued (paths and Newton), {:.0} per s, {} failure groups",
        metrics.len(),
        1e3 * seconds / 90.0,
        result.paths_tracked,
        result.paths_tracked as f64 / seconds,
        result.failures.len()
    );
    c.bench_function("curve_90_poses", |b| b.iter(run));
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench_curve
}
criterion_main!(benches);
