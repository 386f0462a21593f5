//! Polyhedral homotopy on PHCpack demo systems (J. Verschelde, PHCpack, the `examples`
//! folder; committed as Bertini files under `tests/demo_systems/`): the number of paths
//! is the mixed volume of the supports with the origin (Li and Wang, "The BKK root count
//! in C^n", Math. Comp. 1996), no path is lost, every distinct nonsingular root is found
//! once, and two seeds (two liftings and two random-coefficient systems) agree.

use singdist::C64;
use singdist::homotopy::{
    PathStatus, SolveOptions, Supports, distinct_nonsingular_roots, solve_polyhedral,
};
use singdist::system::{System, bertini};

/// (file stem, mixed volume with the origin, verified distinct nonsingular roots).
/// The root counts are those of `tests/homotopy_demo_suite.rs` (total-degree solves
/// refined against the polynomials and compared with PHCpack); a mixed volume equal to
/// the root count (cyclic-5: 70 of total degree 120, katsura-6: 64 = 2⁶) is attained,
/// so it cannot be larger, and none can be smaller than the roots it bounds.
const SYSTEMS: [(&str, u128, usize); 7] = [
    ("cyclic5", 70, 70),
    ("chemequ", 16, 16),
    ("game5two", 44, 44),
    ("katsura6", 64, 64),
    ("camera1s", 20, 20),
    ("lorentz", 12, 11),
    ("noon4", 73, 73),
];

fn load(stem: &str) -> System {
    let path = format!(
        "{}/tests/demo_systems/{stem}.input",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    bertini::read(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn polyhedral_paths_are_the_mixed_volume_and_reach_every_root_for_two_seeds() {
    for (stem, mixed_volume, roots) in SYSTEMS {
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
