//! 3-RRR distance curves of the built-in example (docs/theory.md §10): 90 poses, four
//! sub-problems (parallel 50 paths, legs 2 paths each), on 2 threads, embedded start files:
//! the default (chains of 20 poses with Newton jumps, and the self-check), the chains
//! without Newton jumps (pose-to-pose paths only), every pose from the seed, and the
//! default without the self-check. Prints paths/s of one run of each before its criterion
//! measurement.

use criterion::{Criterion, criterion_group, criterion_main};
use singdist::mechanism::rrr::example_trajectory;
use singdist::pipeline::rrr::curve::{
    RrrCurveOptions, compute_rrr_curve, default_rrr_start_solutions,
};

mod bench_support;
use bench_support::{thread_pool, timed};

fn bench_rrr_curve(c: &mut Criterion) {
    let trajectory = example_trajectory();
    let pool = thread_pool(2);
    let mut group = c.benchmark_group("rrr_curve");
    group.sample_size(10);
    // The default (chains of 20 poses with jumps, self-check), the chains without jumps,
    // every pose from the seed, and the default without its self-check.
    let variants = [
        ("example_90_poses", RrrCurveOptions::default()),
        (
            "example_90_poses_no_jumps",
            RrrCurveOptions {
                jump: false,
                ..RrrCurveOptions::default()
            },
        ),
        (
            "example_90_poses_seed_route",
            RrrCurveOptions {
                chain_length: 1,
                ..RrrCurveOptions::default()
            },
        ),
        (
            "example_90_poses_no_self_check",
            RrrCurveOptions {
                self_check: false,
                ..RrrCurveOptions::default()
            },
        ),
    ];
    for (name, options) in variants {
        let run = || {
            pool.install(|| {
                compute_rrr_curve(&trajectory, 90, &options, &default_rrr_start_solutions)
                    .expect("curve")
            })
        };
        let (result, elapsed) = timed(run);
        println!(
            "{name}: {} paths in {elapsed:.3} s ({:.0} paths/s), {} failures",
            result.paths_tracked,
            result.paths_tracked as f64 / elapsed,
            result.failures.len()
        );
        group.bench_function(name, |b| b.iter(run));
    }
    group.finish();
}

criterion_group!(benches, bench_rrr_curve);
criterion_main!(benches);
