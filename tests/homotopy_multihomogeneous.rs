//! Multi-homogeneous start systems end to end: an eigenvalue problem (n paths instead
//! of 2ⁿ) and PHCpack's `camera1s` (20 instead of 64) solved completely, with the same
//! roots as the total-degree homotopy and the same paths on one and two threads; the
//! automatic choice keeps the total degree when no grouping beats it.

use singdist::C64;
use singdist::homotopy::multihomogeneous::{
    MonomialSupports, PartitionSearchOptions, total_degree_paths,
};
use singdist::homotopy::{
    PathStatus, SolveOptions, SolveResult, StartChoice, StartRequest, choose_start_system,
    distinct_nonsingular_roots, solve_multihomogeneous, solve_total_degree,
};
use singdist::system::{System, bertini};

fn load(stem: &str) -> System {
    let path = format!(
        "{}/tests/demo_systems/{stem}.input",
        env!("CARGO_MANIFEST_DIR")
    );
    bertini::read(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

fn degrees(system: &System) -> Vec<u32> {
    system.degrees().iter().map(|&d| d as u32).collect()
}

fn choose(system: &System, request: StartRequest) -> StartChoice {
    let supports = MonomialSupports::from_system(system).unwrap();
    choose_start_system(
        &degrees(system),
        Some(&supports),
        request,
        &PartitionSearchOptions::default(),
    )
    .unwrap()
}

fn solve_by(system: &System, choice: &StartChoice, options: &SolveOptions) -> SolveResult {
    let compiled = system.compile();
    match choice {
        StartChoice::MultiHomogeneous { search, degrees } => {
            solve_multihomogeneous(&compiled, &search.partition, degrees, &[], options).unwrap()
        }
        StartChoice::TotalDegree { .. } => {
            solve_total_degree(&compiled, &degrees(system), &[], options).unwrap()
        }
    }
}

/// Refined nonsingular roots, one per distinct root.
fn distinct_roots(system: &System, result: &SolveResult) -> Vec<Vec<C64>> {
    distinct_nonsingular_roots(&system.compile(), &result.nonsingular_solutions())
}

fn same_root_sets(a: &[Vec<C64>], b: &[Vec<C64>]) -> bool {
    let close = |x: &Vec<C64>, y: &Vec<C64>| {
        let scale = 1.0 + x.iter().map(|v| v.norm()).fold(0.0, f64::max);
        x.iter().zip(y).all(|(u, v)| (u - v).norm() < 1e-8 * scale)
    };
    a.len() == b.len() && a.iter().all(|x| b.iter().any(|y| close(x, y)))
}

/// `(A − λI)v = 0, c·v = 1` with A upper triangular, eigenvalues 1, …, n.
fn eigenvalue_problem(n: usize) -> System {
    let mut rng = singdist::random::seeded(3);
    let mut text = String::from("INPUT\nvariable_group ");
    let v: Vec<String> = (1..=n).map(|i| format!("v{i}")).collect();
    text.push_str(&v.join(", "));
    text.push_str(", lam;\nfunction ");
    let f: Vec<String> = (0..=n).map(|i| format!("f{i}")).collect();
    text.push_str(&f.join(", "));
    text.push_str(";\n");
    for i in 0..n {
        let mut terms = vec![format!("({} - lam)*v{}", i + 1, i + 1)];
        for name in v.iter().skip(i + 1) {
            let a = singdist::random::uniform(&mut rng, -1.0, 1.0);
            terms.push(format!("({a:.6})*{name}"));
        }
        text.push_str(&format!("f{i} = {};\n", terms.join(" + ")));
    }
    let normalisation: Vec<String> = v
        .iter()
        .map(|name| {
            format!(
                "({:.6})*{name}",
                singdist::random::uniform(&mut rng, 0.5, 1.5)
            )
        })
        .collect();
    text.push_str(&format!(
        "f{n} = {} - 1;\nEND;\n",
        normalisation.join(" + ")
    ));
    bertini::read(&text).unwrap()
}

#[test]
fn eigenvalue_problem_takes_n_paths_and_finds_every_eigenpair() {
    let n = 6;
    let system = eigenvalue_problem(n);
    let choice = choose(&system, StartRequest::Auto);
    assert_eq!(choice.paths(), n as u128);
    assert!(matches!(choice, StartChoice::MultiHomogeneous { .. }));
    assert_eq!(total_degree_paths(&degrees(&system)), 1 << n);
    let options = SolveOptions::default();
    let result = solve_by(&system, &choice, &options);
    let s = &result.summary;
    assert_eq!((s.paths, s.nonsingular, s.failed), (n, n, 0), "{s:?}");
    let mut eigenvalues: Vec<f64> = result
        .nonsingular_solutions()
        .iter()
        .map(|x| {
            assert!(x[n].im.abs() < 1e-9);
            x[n].re
        })
        .collect();
    eigenvalues.sort_by(f64::total_cmp);
    for (k, lam) in eigenvalues.iter().enumerate() {
        assert!((lam - (k + 1) as f64).abs() < 1e-9, "{eigenvalues:?}");
    }
    let total = solve_by(
        &system,
        &choose(&system, StartRequest::TotalDegree),
        &options,
    );
    assert_eq!(total.summary.paths, 1 << n);
    assert!(same_root_sets(
        &distinct_roots(&system, &result),
        &distinct_roots(&system, &total)
    ));
}

#[test]
fn camera1s_by_twenty_paths_matches_total_degree_and_thread_counts() {
    let system = load("camera1s");
    let choice = choose(&system, StartRequest::Auto);
    let StartChoice::MultiHomogeneous { search, .. } = &choice else {
        panic!("expected a multi-homogeneous start system: {choice:?}");
    };
    assert_eq!(search.bezout_number, 20);
    assert_eq!(search.total_degree, Some(64));
    let names = system.variables();
    assert_eq!(
        search.partition.describe(names),
        "{d1, d2, d3} {q1, q2, q3}"
    );
    for seed in [0x5eed, 7] {
        let options = SolveOptions {
            seed,
            ..SolveOptions::default()
        };
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| solve_by(&system, &choice, &options))
        };
        let one = on(1);
        let two = on(2);
        assert_eq!(
            one, two,
            "seed {seed}: results differ between thread counts"
        );
        let s = &one.summary;
        assert_eq!((s.paths, s.nonsingular, s.failed), (20, 20, 0), "{s:?}");
        assert!(
            one.paths
                .iter()
                .all(|p| p.status == PathStatus::Nonsingular)
        );
        let total = solve_by(
            &system,
            &choose(&system, StartRequest::TotalDegree),
            &options,
        );
        let roots = distinct_roots(&system, &one);
        assert_eq!(roots.len(), 20);
        assert!(same_root_sets(&roots, &distinct_roots(&system, &total)));
    }
}

#[test]
fn auto_keeps_total_degree_when_no_grouping_beats_it() {
    let system = load("noon4");
    let StartChoice::TotalDegree { paths, search } = choose(&system, StartRequest::Auto) else {
        panic!("noon4: no grouping beats 3⁴");
    };
    assert_eq!(paths, 81);
    assert_eq!(search.unwrap().bezout_number, 81);
    let forced = choose(&system, StartRequest::MultiHomogeneous);
    assert!(matches!(forced, StartChoice::MultiHomogeneous { .. }));
    assert_eq!(forced.paths(), 81);
    assert!(
        choose_start_system(
            &degrees(&system),
            None,
            StartRequest::MultiHomogeneous,
            &PartitionSearchOptions::default()
        )
        .is_err()
    );
}
