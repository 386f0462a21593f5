//! Speed of the GCI of Ramana Babu et al. (docs/theory.md §11.5): one scheme on the 81×81
//! grid of the example geometry (the CLI table evaluates 16 of these), one local 1/κ
//! evaluation, and one GA objective evaluation (41×41 grid, the default inside
//! `--optimize`).

use criterion::{Criterion, criterion_group, criterion_main};
use singdist::analysis::actuation_design::DesignProblem;
use singdist::index::actuation::{
    ExampleGeometry, GciOptions, Scheme, WorkspaceGrid, gci, local_inverse_condition,
};
use singdist::mechanism::rrr::RrrPose;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let design = ExampleGeometry::default().design().unwrap();
    let scheme = Scheme::from_number(6).unwrap();
    let options = GciOptions::default();
    let grid = WorkspaceGrid::square(5.0, 81);
    c.bench_function("gci_81x81_one_scheme", |b| {
        b.iter(|| gci(black_box(&design), scheme, 0.2, &grid, &options).unwrap())
    });
    let pose = RrrPose::new(0.3, -0.2, 0.1);
    c.bench_function("local_inverse_condition", |b| {
        b.iter(|| local_inverse_condition(black_box(&design), &pose, scheme, &options))
    });
    let problem = DesignProblem::example(scheme, 0.0, 41);
    c.bench_function("ga_objective_41x41", |b| {
        b.iter(|| problem.objective(black_box(&[1.5, 3.0, 3.5])))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
