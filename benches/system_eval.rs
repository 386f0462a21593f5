//! F + ∂F/∂x of the 13-unknown plate/plate Lagrange system (docs/theory.md §5): compiled
//! straight-line program vs the naive expression walker. Goal: ≤ 2 µs compiled.

#[path = "../tests/system_support/mod.rs"]
mod system_support;

use criterion::{Criterion, criterion_group, criterion_main};
use singdist::C64;
use singdist::random::seeded;
use singdist::system::Evaluator;
use std::hint::black_box;
use system_support::{plate_plate_system, random_point};

fn plate_plate_evaluation(c: &mut Criterion) {
    let system = plate_plate_system();
    let compiled = system.compile();
    let mut rng = seeded(1);
    let x = random_point(&mut rng, 13);
    let p = random_point(&mut rng, 12);
    let dp = random_point(&mut rng, 12);
    let mut work = compiled.new_workspace();
    let mut f = vec![C64::new(0.0, 0.0); 13];
    let mut jac = vec![C64::new(0.0, 0.0); 169];
    eprintln!(
        "plate/plate Lagrange system: tapes (F, F+Jx, Jp, Jp·dp) and multiplications of F+Jx {:?}, workspace {} registers",
        compiled.tape_statistics(),
        compiled.workspace_len()
    );
    c.bench_function("plate_plate F+Jx compiled", |b| {
        b.iter(|| {
            compiled.evaluate_with_jacobian(
                black_box(&x),
                black_box(&p),
                &mut work,
                &mut f,
                &mut jac,
            );
            black_box(&jac);
        })
    });
    c.bench_function("plate_plate F compiled", |b| {
        b.iter(|| {
            compiled.evaluate(black_box(&x), black_box(&p), &mut work, &mut f);
            black_box(&f);
        })
    });
    c.bench_function("plate_plate dF/dp.dp compiled", |b| {
        b.iter(|| {
            compiled.evaluate_parameter_derivative(
                black_box(&x),
                black_box(&p),
                black_box(&dp),
                &mut work,
                &mut f,
            );
            black_box(&f);
        })
    });
    c.bench_function("plate_plate F+Jx naive", |b| {
        b.iter(|| {
            let f = system.evaluate_naive(black_box(&x), black_box(&p));
            let jac = system.jacobian_naive(black_box(&x), black_box(&p));
            black_box((f, jac));
        })
    });
}

criterion_group!(benches, plate_plate_evaluation);
criterion_main!(benches);
