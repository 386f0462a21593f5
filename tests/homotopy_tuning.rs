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

/// Dense random quadrics in 11 unknowns (compiled): all 2048 Bézout paths must end at
/// distinct nonsingular solutions.
#[test]
#[ignore]
fn random_quadrics_in_11_unknowns() {
    use singdist::C64;
    use singdist::random::{complex_normal, seeded};
    use singdist::system::{Expr, System};
    let n = 11;
    let mut rng = seeded(5);
    let x: Vec<Expr> = (0..n).map(|i| Expr::variable(format!("x{i}"))).collect();
    let equations: Vec<Expr> = (0..n)
        .map(|_| {
            let mut f = Expr::constant(complex_normal(&mut rng));
            for i in 0..n {
                f += Expr::constant(complex_normal(&mut rng)) * &x[i];
                for j in i..n {
                    f += Expr::constant(complex_normal(&mut rng)) * &x[i] * &x[j];
                }
            }
            f
        })
        .collect();
    let names: Vec<String> = (0..n).map(|i| format!("x{i}")).collect();
    let system = System::new(&names, Vec::<String>::new(), equations).unwrap();
    let compiled = system.compile();
    let start = std::time::Instant::now();
    let r = solve_total_degree(&compiled, &[2; 11], &[], &SolveOptions::default()).unwrap();
    let steps: usize = r.paths.iter().map(|p| p.steps).sum();
    let worst = r.paths.iter().map(|p| p.residual).fold(0.0f64, f64::max);
    eprintln!(
        "{:?} steps/path {:.1} worst residual {worst:e} time {:.2}s",
        r.summary,
        steps as f64 / r.paths.len() as f64,
        start.elapsed().as_secs_f64()
    );
    let _ = C64::new(0.0, 0.0);
    assert_eq!(r.summary.nonsingular, 2048);
}
