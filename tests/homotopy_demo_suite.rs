//! A representative subset of PHCpack's demo systems (J. Verschelde, PHCpack, the
//! `examples` folder), committed as Bertini files under `tests/demo_systems/`: the
//! total-degree `solve` loses no path, finds every distinct nonsingular root once (the
//! counts were verified by refining PHCpack's and singdist's roots with Newton's method
//! against the original polynomials; `benches/phc_demo_suite.rs` reproduces them), and
//! gives the same counts for other seeds; the polyhedral `solve` tracks the mixed volume
//! of paths (Li and Wang, "The BKK root count in C^n", Math. Comp. 1996) to the same
//! roots. With `phc` installed, PHCpack's blackbox
//! solver is run on one of them and its nonsingular roots must be singdist's.

use singdist::C64;
use singdist::homotopy::{
    PathStatus, SolveOptions, Supports, distinct_nonsingular_roots, solve_polyhedral,
    solve_total_degree,
};
use singdist::system::{CompiledSystem, System, bertini, phc};

mod demo_support;
use demo_support::{SINGULAR_SYSTEMS, SYSTEMS, demo_file};

fn load(stem: &str) -> System {
    let path = demo_file(stem);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    bertini::read(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Distinct nonsingular roots among `points` after Newton refinement.
fn distinct_nonsingular(system: &CompiledSystem, points: &[Vec<C64>]) -> Vec<Vec<C64>> {
    distinct_nonsingular_roots(system, points)
}

fn solve(system: &System, seed: u64) -> singdist::homotopy::SolveResult {
    let degrees: Vec<u32> = system.degrees().iter().map(|&d| d as u32).collect();
    let options = SolveOptions {
        seed,
        ..SolveOptions::default()
    };
    solve_total_degree(&system.compile(), &degrees, &[], &options).unwrap()
}

#[test]
fn demo_systems_are_solved_completely_for_two_seeds() {
    for (stem, expected) in SYSTEMS {
        let system = load(stem);
        let compiled = system.compile();
        for seed in [0x5eed, 7] {
            let result = solve(&system, seed);
            let s = &result.summary;
            assert_eq!(s.failed, 0, "{stem}, seed {seed}: failed paths: {s:?}");
            assert_eq!(s.nonsingular, expected, "{stem}, seed {seed}: {s:?}");
            let finite = result.finite_endpoints();
            let distinct = distinct_nonsingular(&compiled, &finite);
            assert_eq!(
                distinct.len(),
                expected,
                "{stem}, seed {seed}: distinct roots"
            );
            let reported: Vec<Vec<C64>> = result
                .paths
                .iter()
                .filter(|p| p.status == PathStatus::Nonsingular)
                .map(|p| p.solution.clone())
                .collect();
            assert_eq!(
                distinct_nonsingular(&compiled, &reported).len(),
                expected,
                "{stem}, seed {seed}: a nonsingular root is reported twice"
            );
        }
    }
}

/// Paths to singular roots end there, classified singular with their multiplicity,
/// for two seeds: `redcyc5` (two double roots besides its 14 nonsingular ones) and
/// `tangents1` (six roots of multiplicity 4, where every finite path ends).
#[test]
fn every_path_to_a_singular_root_is_classified() {
    for (stem, roots, paths) in SINGULAR_SYSTEMS {
        let system = load(stem);
        for seed in [0x5eed, 7] {
            let s = solve(&system, seed).summary;
            assert_eq!(s.failed, 0, "{stem}, seed {seed}: {s:?}");
            assert_eq!(
                (s.singular, s.singular_paths),
                (roots, paths),
                "{stem}, seed {seed}: {s:?}"
            );
        }
    }
}

#[test]
fn phc_roots_of_cyclic5_are_singdist_roots() {
    if !phc::available() {
        eprintln!("phc (PHCpack) not installed; skipping the cross-check");
        return;
    }
    let system = load("cyclic5");
    let compiled = system.compile();
    let dir = std::env::temp_dir().join(format!("homotopy_demo_suite.{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("cyclic5.phc");
    std::fs::write(&input, phc::write(&system, &[]).unwrap()).unwrap();
    let status = std::process::Command::new("phc")
        .arg("-b")
        .arg("-t1")
        .arg(&input)
        .arg(dir.join("cyclic5.out"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    // `phc -b` appends its final solution list to the input file.
    let text = std::fs::read_to_string(&input).unwrap();
    let theirs: Vec<Vec<C64>> = phc::read_last_solutions(&text)
        .iter()
        .map(|s| {
            system
                .variables()
                .iter()
                .map(|n| s.value(n).unwrap())
                .collect()
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    let theirs = distinct_nonsingular(&compiled, &theirs);
    let ours = solve(&system, 0x5eed).nonsingular_solutions();
    let ours = distinct_nonsingular(&compiled, &ours);
    assert_eq!(theirs.len(), 70);
    for x in &theirs {
        let scale = 1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        assert!(
            ours.iter()
                .any(|y| x.iter().zip(y).all(|(a, b)| (a - b).norm() < 1e-8 * scale)),
            "a PHCpack root of cyclic5 is not among singdist's"
        );
    }
}

/// Two paths ending at one nonsingular root (path jumping) count it once: the second is
/// reported failed (`PathJumped`), never as a second solution.
#[test]
fn a_root_reached_twice_is_counted_once_and_reported() {
    let system = bertini::read("variable_group x;\nparameter p;\nfunction f;\nf = x^2 - p;\n")
        .unwrap()
        .compile();
    let root = C64::new(2f64.sqrt(), 0.0);
    let p = [C64::new(2.0, 0.0)];
    let result = singdist::homotopy::solve_parameter_homotopy(
        &system,
        &[vec![root], vec![root], vec![-root]],
        &p,
        &p,
        &SolveOptions::default(),
    )
    .unwrap();
    assert_eq!(result.summary.nonsingular, 2, "{:?}", result.summary);
    assert_eq!(result.summary.failed, 1);
    assert_eq!(
        result.paths[1].status,
        PathStatus::Failed(singdist::homotopy::FailureReason::PathJumped)
    );
}

/// (file stem, mixed volume with the origin, verified distinct nonsingular roots).
/// The root counts are those of `tests/homotopy_demo_suite.rs` (total-degree solves
/// refined against the polynomials and compared with PHCpack); a mixed volume equal to
/// the root count (cyclic-5: 70 of total degree 120, katsura-6: 64 = 2⁶) is attained,
/// so it cannot be larger, and none can be smaller than the roots it bounds.
const POLYHEDRAL_SYSTEMS: [(&str, u128, usize); 7] = [
    ("cyclic5", 70, 70),
    ("chemequ", 16, 16),
    ("game5two", 44, 44),
    ("katsura6", 64, 64),
    ("camera1s", 20, 20),
    ("lorentz", 12, 11),
    ("noon4", 73, 73),
];

#[test]
fn polyhedral_paths_are_the_mixed_volume_and_reach_every_root_for_two_seeds() {
    for (stem, mixed_volume, roots) in POLYHEDRAL_SYSTEMS {
        let system = load(stem);
        let compiled = system.compile();
        let supports = Supports::from_system(&system).unwrap();
        for seed in [0x5eed, 7] {
            let options = SolveOptions {
                seed,
                ..SolveOptions::default()
            };
            let solved = solve_polyhedral(&compiled, &supports, &[], &options).unwrap();
            let s = &solved.result.summary;
            assert_eq!(solved.mixed_volume, mixed_volume, "{stem}, seed {seed}");
            assert_eq!(s.paths as u128, mixed_volume, "{stem}, seed {seed}: {s:?}");
            assert_eq!(solved.start_failed, 0, "{stem}, seed {seed}: stage one");
            assert_eq!(s.failed, 0, "{stem}, seed {seed}: failed paths: {s:?}");
            let reported: Vec<Vec<C64>> = solved
                .result
                .paths
                .iter()
                .filter(|p| p.status == PathStatus::Nonsingular)
                .map(|p| p.solution.clone())
                .collect();
            assert_eq!(reported.len(), roots, "{stem}, seed {seed}: {s:?}");
            assert_eq!(
                distinct_nonsingular_roots(&compiled, &reported).len(),
                roots,
                "{stem}, seed {seed}: a nonsingular root is reported twice or lost"
            );
        }
    }
}

/// eco8 (mixed volume 64 = its 64 nonsingular roots, none at infinity) under the
/// polyhedral homotopy: in the second stage (random-coefficient system → eco8) a path
/// of seeds 0x5eed and 1 passes a pole near `t = 0.5` (norm past 10⁸ halfway), which
/// was once counted at infinity without any endgame — a silent lost root. No path may
/// be at infinity here, and every path is a distinct root or a reported failure.
#[test]
fn a_pole_passed_halfway_is_not_a_point_at_infinity() {
    let system = load("eco8");
    let compiled = system.compile();
    let supports = Supports::from_system(&system).unwrap();
    for (seed, complete) in [(0x5eed, true), (1, false)] {
        let options = SolveOptions {
            seed,
            ..SolveOptions::default()
        };
        let solved = solve_polyhedral(&compiled, &supports, &[], &options).unwrap();
        let s = &solved.result.summary;
        assert_eq!(solved.mixed_volume, 64);
        assert_eq!(s.at_infinity, 0, "seed {seed}: {s:?}");
        let roots = distinct_nonsingular_roots(&compiled, &solved.result.nonsingular_solutions());
        assert_eq!(
            roots.len(),
            s.nonsingular,
            "seed {seed}: a root counted twice"
        );
        assert_eq!(s.nonsingular + s.failed, 64, "seed {seed}: {s:?}");
        if complete {
            assert_eq!(s.nonsingular, 64, "seed {seed}: {s:?}");
        }
    }
}

/// PHCpack's `butemb3` (mixed volume 247, 198 nonsingular roots) under the polyhedral
/// homotopy with the default seed: two cell paths of the first lifting diverge (also
/// when re-tracked), so two roots of the random-coefficient system `Q` were lost and
/// with them two of the 198 roots. The cell paths of a fresh lifting of the same `Q`
/// reach them: no stage-one path is lost and every root is found once.
#[test]
fn roots_of_q_lost_on_one_lifting_are_found_on_another() {
    let system = load("butemb3");
    let compiled = system.compile();
    let supports = Supports::from_system(&system).unwrap();
    let solved = solve_polyhedral(&compiled, &supports, &[], &SolveOptions::default()).unwrap();
    let s = &solved.result.summary;
    assert_eq!(solved.mixed_volume, 247);
    assert_eq!(solved.start_failed, 0, "{s:?}");
    assert_eq!(s.failed, 0, "{s:?}");
    let roots = distinct_nonsingular_roots(&compiled, &solved.result.nonsingular_solutions());
    assert_eq!(roots.len(), 198, "{s:?}");
    assert_eq!(s.nonsingular, 198, "{s:?}");
}

/// The report of paths put at infinity after stalling near the roots
/// (`summary.stalled_near_roots`): with residuals in double precision only
/// (`extended_residual: false`) and the endgame's settled-condition direct finish and
/// averaging test off, as before they existed, the paths to `discret3s`'s largest roots
/// (norms 5·10⁴–1.2·10⁵) stall at `s ≈ 10⁻¹⁰` and are put at infinity: they are counted,
/// and roots are missing. With the default options every root is found and nothing is
/// counted; `reimer5`'s stalled paths stop at 19 times its largest root or more, and
/// are not counted either.
#[test]
fn paths_stalled_near_the_roots_are_counted() {
    let system = load("discret3s");
    let degrees: Vec<u32> = system.degrees().iter().map(|&d| d as u32).collect();
    let mut options = SolveOptions::default();
    options.tracker.precision.extended_residual = false;
    options.tracker.endgame.direct_finish_at_settled_condition = false;
    options.tracker.endgame.reject_averaging_loops = false;
    let compiled = system.compile();
    let stalled = solve_total_degree(&compiled, &degrees, &[], &options).unwrap();
    let s = &stalled.summary;
    assert!(s.stalled_near_roots >= 1, "{s:?}");
    assert!(s.nonsingular < 128, "{s:?}");
    let solved = solve_total_degree(&compiled, &degrees, &[], &SolveOptions::default()).unwrap();
    assert_eq!(solved.summary.stalled_near_roots, 0, "{:?}", solved.summary);
    assert_eq!(solved.summary.nonsingular, 128, "{:?}", solved.summary);
    let system = load("reimer5");
    let degrees: Vec<u32> = system.degrees().iter().map(|&d| d as u32).collect();
    let result =
        solve_total_degree(&system.compile(), &degrees, &[], &SolveOptions::default()).unwrap();
    assert_eq!(result.summary.stalled_near_roots, 0, "{:?}", result.summary);
    assert!(result.summary.at_infinity > 0);
}
