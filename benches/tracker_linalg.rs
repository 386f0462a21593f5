//! The tracker's hot linear solve `J Δ = b` (LU with partial pivoting, then one solve)
//! for n = 11..19: singdist's preallocated `LuWorkspace` against nalgebra (heap
//! `DMatrix` and stack `SMatrix` for n = 13) and faer (high-level `partial_piv_lu` and
//! the allocation-free `lu_in_place` with a preallocated stack), and singdist's
//! double-double LU (`DdLuWorkspace`, the tracker's extended-precision mode).
//!
//! `cargo bench --bench tracker_linalg -- --warm-up-time 1 --measurement-time 3`

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use singdist::C64;
use singdist::homotopy::{DdLuWorkspace, LuWorkspace};
use singdist::random::{complex_normal, seeded};
use std::hint::black_box;

fn random(n: usize, seed: u64) -> (Vec<C64>, Vec<C64>) {
    let mut rng = seeded(seed);
    let a = (0..n * n).map(|_| complex_normal(&mut rng)).collect();
    let b = (0..n).map(|_| complex_normal(&mut rng)).collect();
    (a, b)
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("lu_factor_solve");
    for n in [11usize, 13, 16, 19] {
        let (a, b) = random(n, n as u64);
        let mut lu = LuWorkspace::new(n);
        let mut x = b.clone();
        group.bench_with_input(BenchmarkId::new("singdist", n), &n, |bench, _| {
            bench.iter(|| {
                lu.factor(black_box(&a));
                x.copy_from_slice(&b);
                lu.solve_in_place(&mut x);
                black_box(&x);
            })
        });

        // The extended-precision mode's solve: double-double LU of a double-double
        // matrix (here with zero trailing parts), what one extended step pays per solve.
        let low = vec![C64::new(0.0, 0.0); n * n];
        let mut dd = DdLuWorkspace::new(n);
        group.bench_with_input(
            BenchmarkId::new("singdist_double_double", n),
            &n,
            |bench, _| {
                bench.iter(|| {
                    dd.factor(black_box(&a), &low);
                    x.copy_from_slice(&b);
                    dd.solve_in_place(&mut x);
                    black_box(&x);
                })
            },
        );

        let na = nalgebra::DMatrix::from_row_slice(n, n, &a);
        let nb = nalgebra::DVector::from_column_slice(&b);
        group.bench_with_input(BenchmarkId::new("nalgebra_dmatrix", n), &n, |bench, _| {
            bench.iter(|| {
                let lu = black_box(&na).clone().lu();
                black_box(lu.solve(&nb));
            })
        });
        if n == 13 {
            let sa = nalgebra::SMatrix::<C64, 13, 13>::from_row_slice(&a);
            let sb = nalgebra::SVector::<C64, 13>::from_column_slice(&b);
            group.bench_with_input(BenchmarkId::new("nalgebra_smatrix", n), &n, |bench, _| {
                bench.iter(|| {
                    let lu = black_box(sa).lu();
                    black_box(lu.solve(&sb));
                })
            });
        }

        let fa = faer::Mat::<faer::c64>::from_fn(n, n, |i, j| {
            let z = a[i * n + j];
            faer::c64::new(z.re, z.im)
        });
        let fb = faer::Mat::<faer::c64>::from_fn(n, 1, |i, _| faer::c64::new(b[i].re, b[i].im));
        group.bench_with_input(
            BenchmarkId::new("faer_partial_piv_lu", n),
            &n,
            |bench, _| {
                bench.iter(|| {
                    let lu = black_box(&fa).partial_piv_lu();
                    black_box(faer::linalg::solvers::Solve::solve(&lu, &fb));
                })
            },
        );

        use faer::dyn_stack::{MemBuffer, MemStack};
        use faer::linalg::lu::partial_pivoting::{factor, solve};
        let mut work = fa.clone();
        let mut rhs = fb.clone();
        let mut perm = vec![0usize; n];
        let mut perm_inv = vec![0usize; n];
        let mut buffer = MemBuffer::new(
            factor::lu_in_place_scratch::<usize, faer::c64>(
                n,
                n,
                faer::Par::Seq,
                Default::default(),
            )
            .or(solve::solve_in_place_scratch::<usize, faer::c64>(
                n,
                1,
                faer::Par::Seq,
            )),
        );
        group.bench_with_input(BenchmarkId::new("faer_in_place", n), &n, |bench, _| {
            bench.iter(|| {
                work.copy_from(black_box(&fa));
                rhs.copy_from(&fb);
                let stack = MemStack::new(&mut buffer);
                let (_, p) = factor::lu_in_place(
                    work.as_mut(),
                    &mut perm,
                    &mut perm_inv,
                    faer::Par::Seq,
                    stack,
                    Default::default(),
                );
                let stack = MemStack::new(&mut buffer);
                solve::solve_in_place(
                    work.as_ref(),
                    work.as_ref(),
                    p,
                    rhs.as_mut(),
                    faer::Par::Seq,
                    stack,
                );
                black_box(&rhs);
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
