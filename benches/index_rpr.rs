//! Cost of the 3-RPR kinematic indices (docs/theory.md §9) per pose.

use criterion::{Criterion, criterion_group, criterion_main};
use singdist::index::rpr::{
    IndexOptions, compute_indices, orientation_singularity_distance, position_singularity_distance,
    singularity_free_cylinder_radius,
};
use singdist::mechanism::rpr::{Pose, example_design};
use std::hint::black_box;

fn indices(c: &mut Criterion) {
    let design = example_design();
    let pose = Pose::new(4.0, 3.0, 0.3);
    let options = IndexOptions::default();
    c.bench_function("rpr compute_indices (all)", |b| {
        b.iter(|| compute_indices(black_box(&design), black_box(pose), &options))
    });
    c.bench_function("rpr orientation distance", |b| {
        b.iter(|| orientation_singularity_distance(black_box(&design), black_box(pose)))
    });
    c.bench_function("rpr position distance", |b| {
        b.iter(|| position_singularity_distance(black_box(&design), black_box(pose)))
    });
    c.bench_function("rpr cylinder radius", |b| {
        b.iter(|| singularity_free_cylinder_radius(black_box(&design), 4.0, 3.0, [0.2, 0.4]))
    });
}

criterion_group!(benches, indices);
criterion_main!(benches);
