//! 3-RRR distance curves of the built-in example (docs/theory.md §10): 90 poses, four
//! sub-problems (parallel 50 paths, legs 2 paths each), on 2 threads, embedded start files.
//! Prints paths/s of one run before the criterion measurement.

use criterion::{Criterion, criterion_group, criterion_main};
use singdist::mechanism::rrr::example_trajectory;
use singdist::pipeline::rrr_curve::{
    RrrCurveOptions, compute_rrr_curve, default_rrr_start_solutions,
};

mod bench_support;
use bench_support::{thread_pool, timed};

fn bench_rrr_curve(c: &mut Criterion) {
    let trajectory = example_trajectory();
    let options = RrrCurveOptions::default();
    let pool = thread_pool(2);
    let run = || {
        pool.install(|| {
            compute_rrr_curve(&trajectory, 90, &options, &default_rrr_start_solutions)
                .expect("curve")
        })
    };
    let (result, elapsed) = timed(run);
    println!(
        "rrr curve: 90 poses, {} paths in {elapsed:.3} s ({:.0} paths/s), {} failures",
        result.paths_tracked,
        result.paths_tracked as f64 / elapsed,
        result.failures.len()
    );
    let mut group = c.benchmark_group("rrr_curve");
    group.sample_size(10);
    group.bench_function("example_90_poses", |b| b.iter(run));
    group.finish();
}

criterion_group!(benches, bench_rrr_curve);
criterion_main!(benches);
