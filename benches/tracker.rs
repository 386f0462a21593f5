//! Paths per second of the tracker (throughput in paths/s), 1 and 2 threads:
//! - katsura-7 by the total-degree homotopy (128 paths, all finite and nonsingular);
//! - a 13-unknown parameter homotopy `x_i² − a_i + Σ_j b_ij x_j = 0` (182 parameters),
//!   128 paths from the decoupled start `b = 0, x_i = ±√a_i` to random complex `(a, b)`.
//!
//! `cargo bench --bench tracker -- --warm-up-time 1 --measurement-time 3`

#[path = "../tests/homotopy_common/mod.rs"]
mod homotopy_common;

mod bench_support;
use bench_support::thread_pool;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use singdist::C64;
use singdist::homotopy::{
    HomotopyError, SolveOptions, SolveResult, solve_parameter_homotopy, solve_total_degree,
};
use singdist::random::{complex_normal, seeded};
use singdist::system::{Expr, System};

fn coupled_quadrics(n: usize) -> System {
    let x: Vec<Expr> = (0..n).map(|i| Expr::variable(format!("x{i}"))).collect();
    let mut parameters: Vec<String> = (0..n).map(|i| format!("a{i}")).collect();
    let mut equations = Vec::new();
    for i in 0..n {
        let mut f = x[i].pow(2) - Expr::parameter(format!("a{i}"));
        for (j, xj) in x.iter().enumerate() {
            let name = format!("b{i}_{j}");
            f += Expr::parameter(&name) * xj;
            parameters.push(name);
        }
        equations.push(f);
    }
    let variables: Vec<String> = (0..n).map(|i| format!("x{i}")).collect();
    System::new(&variables, &parameters, equations).expect("valid system")
}

fn bench(c: &mut Criterion) {
    let (katsura, degrees) = homotopy_common::katsura_compiled(7);
    let n = 13;
    let family = coupled_quadrics(n).compile();
    let mut rng = seeded(1);
    let a0: Vec<C64> = (0..n).map(|_| complex_normal(&mut rng)).collect();
    let mut p0 = a0.clone();
    p0.extend(std::iter::repeat_n(C64::new(0.0, 0.0), n * n));
    let p1: Vec<C64> = (0..n + n * n)
        .map(|k| complex_normal(&mut rng) * if k < n { 1.0 } else { 0.3 })
        .collect();
    let starts: Vec<Vec<C64>> = (0..128u32)
        .map(|pattern| {
            (0..n)
                .map(|i| {
                    let root = a0[i].sqrt();
                    if i < 7 && pattern >> i & 1 == 1 {
                        -root
                    } else {
                        root
                    }
                })
                .collect()
        })
        .collect();

    let mut group = c.benchmark_group("tracker");
    group.sample_size(10);
    group.throughput(Throughput::Elements(128));
    for threads in [1usize, 2] {
        let pool = thread_pool(threads);
        // Times `solve` on the pool; every result must pass `check`.
        type Solve<'a> = &'a (dyn Fn() -> Result<SolveResult, HomotopyError> + Sync);
        let mut bench = |name: &str, solve: Solve<'_>, check: fn(&SolveResult) -> bool| {
            group.bench_with_input(BenchmarkId::new(name, threads), &threads, |b, _| {
                b.iter(|| assert!(check(&pool.install(solve).expect("solve"))))
            });
        };
        let options = SolveOptions::default();
        bench(
            "katsura7_total_degree",
            &|| solve_total_degree(&katsura, &degrees, &[], &options),
            |r| r.summary.nonsingular == 128,
        );
        bench(
            "parameter_homotopy_13_unknowns",
            &|| solve_parameter_homotopy(&family, &starts, &p0, &p1, &options),
            |r| r.summary.failed == 0,
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
