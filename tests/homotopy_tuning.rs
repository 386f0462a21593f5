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

/// Monodromy + trace test timings on all-coefficient families.
#[test]
#[ignore]
fn monodromy_timings() {
    use singdist::homotopy::{MonodromyOptions, monodromy_solve};
    for degrees in [vec![2u32, 2, 2, 2], vec![2, 2, 2, 2, 2], vec![3, 3, 3]] {
        let (system, _) = parametric_dense(&degrees, 3);
        // start pair: random x0, p; solve for the constant-term parameters
        let mut p: Vec<singdist::C64> = {
            let mut rng = singdist::random::seeded(9);
            (0..system.m)
                .map(|_| singdist::random::complex_normal(&mut rng))
                .collect()
        };
        let x0: Vec<singdist::C64> = {
            let mut rng = singdist::random::seeded(10);
            (0..system.n)
                .map(|_| singdist::random::complex_normal(&mut rng))
                .collect()
        };
        for eq in &system.equations {
            let k = eq
                .iter()
                .find(|t| t.exponents.iter().all(|&e| e == 0))
                .unwrap()
                .parameter
                .unwrap();
            p[k] = singdist::C64::new(0.0, 0.0);
            let one = TermSystem {
                n: system.n,
                m: system.m,
                equations: vec![eq.clone()],
            };
            let mut f = vec![singdist::C64::new(0.0, 0.0)];
            singdist::system::Evaluator::evaluate(&one, &x0, &p, &mut [], &mut f);
            p[k] = -f[0];
        }
        let start = std::time::Instant::now();
        let r = monodromy_solve(&system, &x0, &p, &MonodromyOptions::default(), 1).unwrap();
        eprintln!(
            "{degrees:?}: {} solutions, loops {}, witness {} ({} loops), trace {:?}, added {}, {:.2}s",
            r.solutions.len(),
            r.loops,
            r.witness_points,
            r.witness_loops,
            r.trace_residual,
            r.added_by_trace_test,
            start.elapsed().as_secs_f64()
        );
    }
}

#[test]
#[ignore]
fn quadric_cubic_debug() {
    use singdist::homotopy::{MonodromyOptions, trace_test};
    let (system, _) = parametric_dense(&[2, 3], 11);
    let mut rng = singdist::random::seeded(111);
    let x0: Vec<singdist::C64> = (0..2)
        .map(|_| singdist::random::complex_normal(&mut rng))
        .collect();
    let mut p: Vec<singdist::C64> = (0..system.m)
        .map(|_| singdist::random::complex_normal(&mut rng))
        .collect();
    for eq in &system.equations {
        let k = eq
            .iter()
            .find(|t| t.exponents.iter().all(|&e| e == 0))
            .unwrap()
            .parameter
            .unwrap();
        p[k] = singdist::C64::new(0.0, 0.0);
        let one = TermSystem {
            n: system.n,
            m: system.m,
            equations: vec![eq.clone()],
        };
        let mut f = vec![singdist::C64::new(0.0, 0.0)];
        singdist::system::Evaluator::evaluate(&one, &x0, &p, &mut [], &mut f);
        p[k] = -f[0];
    }
    let r = singdist::homotopy::monodromy_solve(&system, &x0, &p, &MonodromyOptions::default(), 11)
        .unwrap();
    for seed in 0..4 {
        let o = MonodromyOptions {
            max_stagnant_loops: 30,
            ..MonodromyOptions::default()
        };
        let c = trace_test(
            &system,
            &p,
            &r.solutions,
            &o,
            &mut singdist::random::seeded(seed),
        )
        .unwrap();
        eprintln!(
            "seed {seed}: witness {} residual {:e}",
            c.witness_points, c.residual
        );
    }
}

#[test]
#[ignore]
fn cyclic_6_failures() {
    use singdist::homotopy::PathStatus;
    let text = std::fs::read_to_string("/tmp/engine/cyclic6.input").unwrap();
    let system = singdist::system::bertini::read(&text).unwrap();
    let degrees: Vec<u32> = system.degrees().iter().map(|&d| d as u32).collect();
    let compiled = system.compile();
    let winding: usize = std::env::var("WINDING")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(16);
    let ratio: f64 = std::env::var("RATIO")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.25);
    let tracker = singdist::homotopy::TrackerOptions {
        max_winding_number: winding,
        endgame_ratio: ratio,
        ..Default::default()
    };
    let options = SolveOptions {
        tracker,
        retry_failed: false,
        ..SolveOptions::default()
    };
    let r = solve_total_degree(&compiled, &degrees, &[], &options).unwrap();
    eprintln!("{:?}", r.summary);
    let mut inf_steps = 0;
    for p in &r.paths {
        if let PathStatus::Failed(_) = p.status {
            let nrm = p.solution.iter().fold(0.0f64, |m, v| m.max(v.norm()));
            eprintln!(
                "{} {:?} norm {nrm:.2e} steps {} rej {} w {} ext {}",
                p.path_index,
                p.status,
                p.steps,
                p.rejected_steps,
                p.winding_number,
                p.used_extended_precision
            );
        }
        if p.status == PathStatus::AtInfinity {
            inf_steps += p.steps;
        }
    }
    eprintln!(
        "mean steps at infinity {}",
        inf_steps as f64 / r.summary.at_infinity as f64
    );
}

#[test]
#[ignore]
fn cyclic_6_path_197() {
    use singdist::homotopy::*;
    let text = std::fs::read_to_string("/tmp/engine/cyclic6.input").unwrap();
    let system = singdist::system::bertini::read(&text).unwrap();
    let degrees: Vec<u32> = system.degrees().iter().map(|&d| d as u32).collect();
    let compiled = system.compile();
    let start = TotalDegreeStartSystem::new(degrees);
    let gamma = singdist::random::unit_complex(&mut singdist::random::seeded(0x5eed));
    let h = StraightLineHomotopy::new(&start, &compiled, vec![], gamma);
    let mut tr = Tracker::new(&h, TrackerOptions::default());
    let mut x = vec![singdist::C64::new(0.0, 0.0); 6];
    start.start_solution(197, &mut x);
    for t1 in [0.5, 0.9, 0.99, 0.999, 0.99999, 0.9999999] {
        let r = tr.track_between(&x, 0.0, t1, 0);
        let nrm = r.solution.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        eprintln!(
            "t={t1} {:?} steps {} norm {nrm:.3e} cond {:.2e}",
            r.status, r.steps, r.condition
        );
    }
}
