//! Time per evaluation of the 3-PRRR indices (the comparison of computation cost of
//! Farias Filho et al. (2021)): LCI `1/κ(Ā⁻¹B̄)`, LCI `1/κ(Ā)` and NSIR, each from a
//! configuration and including the inverse kinematics.

use criterion::{Criterion, criterion_group, criterion_main};
use singdist::index::prrr::{LciVariant, lci, lci_reference, nsir};
use singdist::mechanism::prrr::{Pose, PrrrDesign, Robot, WorkingMode};
use std::hint::black_box;

fn indices(c: &mut Criterion) {
    let design = PrrrDesign::farias2021();
    let pose = Pose::new(0.02, -0.03, 0.2);
    let delta = [0.05, -0.04, 0.03];
    let modes = [WorkingMode::Plus; 3];
    let configuration = design
        .inverse_kinematics(&pose, &delta, &modes)
        .expect("reachable");
    c.bench_function("inverse_kinematics", |b| {
        b.iter(|| design.inverse_kinematics(black_box(&pose), black_box(&delta), &modes))
    });
    c.bench_function("lci_inv_a_b", |b| {
        b.iter(|| {
            lci(
                &design,
                black_box(&configuration),
                Robot::ThreePrrr,
                LciVariant::InverseAB,
            )
        })
    });
    c.bench_function("lci_a", |b| {
        b.iter(|| {
            lci(
                &design,
                black_box(&configuration),
                Robot::ThreePrrr,
                LciVariant::DirectA,
            )
        })
    });
    c.bench_function("lci_inv_a_b_reference_svd", |b| {
        b.iter(|| {
            lci_reference(
                &design,
                black_box(&configuration),
                Robot::ThreePrrr,
                LciVariant::InverseAB,
            )
        })
    });
    c.bench_function("nsir", |b| {
        b.iter(|| nsir(&design, black_box(&configuration), Robot::ThreePrrr))
    });
    c.bench_function("ik+lci_inv_a_b", |b| {
        b.iter(|| {
            let k = design
                .inverse_kinematics(black_box(&pose), &delta, &modes)
                .expect("reachable");
            lci(&design, &k, Robot::ThreePrrr, LciVariant::InverseAB)
        })
    });
    c.bench_function("ik+nsir", |b| {
        b.iter(|| {
            let k = design
                .inverse_kinematics(black_box(&pose), &delta, &modes)
                .expect("reachable");
            nsir(&design, &k, Robot::ThreePrrr).nsir
        })
    });
}

criterion_group!(benches, indices);
criterion_main!(benches);
